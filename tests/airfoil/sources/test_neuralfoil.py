"""NeuralFoil polars: agreement with the shipped XFOIL data and the message when it is not installed."""
import builtins
import re

import numpy as np
import pytest

from bild_mdo.airfoil.sources.neuralfoil import MODEL_SIZES, run_neuralfoil
from bild_mdo.airfoil.sources.readers import load_builtin_polars


def test_input_checks_come_before_the_optional_import():
    with pytest.raises(ValueError, match="model_size must be one of"):
        run_neuralfoil("4412", [1e6], [0.0], model_size="huge")
    with pytest.raises(ValueError, match="reynolds_list must hold finite Reynolds numbers > 0"):
        run_neuralfoil("4412", [-1.0], [0.0])
    with pytest.raises(ValueError, match="within \\[-90, 90\\]"):
        run_neuralfoil("4412", [1e6], [95.0])
    assert MODEL_SIZES[0] == "xxsmall" and "large" in MODEL_SIZES


def test_neuralfoil_agrees_with_shipped_xfoil_data():
    # NeuralFoil is a neural-network emulator of XFOIL, so it is an independent
    # check of the shipped data in attached flow (optional dependency).
    pytest.importorskip("neuralfoil")
    alpha = np.arange(0.0, 8.5, 1.0)
    (nf,) = run_neuralfoil("NACA 4412", [1e6], alpha, model_size="large")
    assert nf.reynolds == 1e6 and nf.source.startswith("NeuralFoil")
    ref = next(p for p in load_builtin_polars("naca4412") if p.reynolds == 1e6)
    idx = np.searchsorted(ref.alpha_deg, alpha)
    np.testing.assert_allclose(nf.cl, ref.cl[idx], atol=0.03)
    np.testing.assert_allclose(nf.cd, ref.cd[idx], rtol=0.12)
    assert abs(nf.lift_to_drag.max() / ref.lift_to_drag.max() - 1.0) < 0.05


def test_neuralfoil_missing_says_how_to_install(monkeypatch):
    real_import = builtins.__import__

    def no_neuralfoil(name, *args, **kwargs):
        if name in ("neuralfoil", "aerosandbox"):
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_neuralfoil)
    with pytest.raises(ImportError, match=re.escape("pip install bild-mdo[neuralfoil]")):
        run_neuralfoil("4412", [1e6], [0.0, 2.0])
