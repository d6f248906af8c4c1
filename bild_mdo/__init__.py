"""bild-mdo: BEM-based ideal-loading design (BILD) of optimal rotors for OpenMDAO.

Implements Ruh & Hwang, "Fast and robust computation of optimal rotor designs
using blade element momentum theory", AIAA Journal 61(9), 2023.

The public API is re-exported here::

    from bild_mdo import BILDGroup, BEMAnalysisGroup, analyze_rotor, design_rotor, naca4412, optimize_rotor
    from bild_mdo import RotorNoiseGroup, rotor_noise    # rotor noise at observers (bild_mdo.acoustics)

Importing bild_mdo needs no optional package (cyipopt, matplotlib, dask):
:class:`IpoptDriver` imports cyipopt only when a driver is made.
"""
__version__ = "0.1.0"

from bild_mdo.acoustics.rotor_noise_group import RotorNoiseGroup
from bild_mdo.airfoil import (AnalyticPolar, CompressiblePolar, MachTabulatedPolar, Polar, SpanwisePolar,
                              TabulatedPolar, get_polar, naca4412, resolve_polar, spanwise_polar)
from bild_mdo.atmosphere import AtmosphereComp, isa
from bild_mdo.bem import BEMAnalysisGroup, BEMResult, BEMStateWarning, TipMachWarning, analyze_rotor
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.turbine_group import TurbineBILDGroup
from bild_mdo.energy import AnnualEnergyComp, PowerCurveGroup
from bild_mdo.io import RotorGeometry, read_geometry, write_geometry
from bild_mdo.mil import MILGroup, design_mil
from bild_mdo.multipoint import MultipointRotorGroup
from bild_mdo.optimization import optimize_rotor
from bild_mdo.optimization.ipopt_driver import IpoptDriver
from bild_mdo.results import DesignResult, OffDesignResult, design_rotor, off_design_sweep
from bild_mdo.results.noise import NoiseResult, combine_noise, rotor_noise
from bild_mdo.results.power_curve import PowerCurve, power_curve
from bild_mdo.results.turbine_design import TurbineDesign, design_turbine

__all__ = [
    "AnalyticPolar", "AnnualEnergyComp", "AtmosphereComp", "BEMAnalysisGroup", "BEMResult", "BEMStateWarning", "BILDGroup",
    "CompressiblePolar", "DesignResult", "IpoptDriver", "MILGroup", "MachTabulatedPolar",
    "MultipointRotorGroup", "NoiseResult", "OffDesignResult", "Polar", "PowerCurve", "PowerCurveGroup", "RotorGeometry",
    "RotorNoiseGroup",
    "SpanwisePolar", "TabulatedPolar", "TipMachWarning", "TurbineBILDGroup", "TurbineDesign", "__version__",
    "analyze_rotor", "combine_noise", "design_mil", "design_rotor", "design_turbine", "get_polar", "isa", "naca4412", "off_design_sweep", "optimize_rotor",
    "power_curve", "read_geometry", "resolve_polar", "rotor_noise", "spanwise_polar", "write_geometry",
]
