"""The real part of a value that may carry a complex-step perturbation (one definition for the package)."""
import numpy as np


def real_part(x):
    """``x`` itself when real, its real part when complex (a complex-step evaluation)."""
    return np.real(x) if np.iscomplexobj(x) else x
