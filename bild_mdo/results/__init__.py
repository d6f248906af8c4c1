"""Result objects of the Python API: BILD designs and off-design sweeps, with their text tables and files."""
from bild_mdo.results.design import DesignResult, design_rotor
from bild_mdo.results.off_design import OffDesignResult, off_design_sweep

__all__ = ["DesignResult", "OffDesignResult", "design_rotor", "off_design_sweep"]
