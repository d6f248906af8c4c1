"""bild-mdo: BEM-based ideal-loading design (BILD) of optimal rotors for OpenMDAO.

Implements Ruh & Hwang, "Fast and robust computation of optimal rotor designs
using blade element momentum theory", AIAA Journal 61(9), 2023.

The public API is re-exported here::

    from bild_mdo import BILDGroup, BEMAnalysisGroup, analyze_rotor, naca4412
"""
__version__ = "0.1.0"

from bild_mdo.airfoil import AnalyticPolar, Polar, TabulatedPolar, get_polar, naca4412
from bild_mdo.atmosphere import AtmosphereComp, isa
from bild_mdo.bem import BEMAnalysisGroup, BEMResult, analyze_rotor
from bild_mdo.bild import BILDGroup
from bild_mdo.design import DesignResult, design_rotor
from bild_mdo.off_design import OffDesignResult, off_design_sweep

__all__ = [
    "AnalyticPolar", "AtmosphereComp", "BEMAnalysisGroup", "BEMResult", "BILDGroup", "DesignResult",
    "OffDesignResult", "Polar", "design_rotor", "off_design_sweep",
    "TabulatedPolar", "analyze_rotor", "get_polar", "isa", "naca4412", "__version__",
]
