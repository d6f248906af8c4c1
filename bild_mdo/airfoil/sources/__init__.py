"""Where airfoil polars come from: files, XFOIL and NeuralFoil, all returning :class:`PolarData`.

Every source gives a list of :class:`PolarData` (one airfoil at one Reynolds
number), which :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar` fits.

Modules
-------
polar_data
    :class:`PolarData`, :class:`PolarFileError` and the row checks every file reader shares.
readers
    XFOIL ``PACC`` polar files and plain tables (read and write; folders and lists); the built-in NACA 4412 data.
coordinates
    The ``airfoil`` argument of the generators: a NACA 4- or 5-digit designation or a Selig coordinates file.
xfoil
    Run XFOIL (``python -m bild_mdo.airfoil.sources.xfoil`` writes the tables in ``airfoil/data``).
neuralfoil
    Run NeuralFoil, the optional neural-network emulator of XFOIL.

The two generators are imported from their modules
(``from bild_mdo.airfoil.sources.xfoil import run_xfoil``), not re-exported
here, so ``python -m bild_mdo.airfoil.sources.xfoil`` runs the module once.
"""
from bild_mdo.airfoil.sources.coordinates import parse_airfoil, read_coordinates
from bild_mdo.airfoil.sources.polar_data import MIN_POINTS, PolarData, PolarFileError
from bild_mdo.airfoil.sources.readers import (available_builtin_polars, load_builtin_polars, read_polar_file,
                                              read_polar_files, read_polar_table, read_xfoil_polar,
                                              write_polar_table)

__all__ = [
    "MIN_POINTS", "PolarData", "PolarFileError", "available_builtin_polars", "load_builtin_polars",
    "parse_airfoil", "read_coordinates", "read_polar_file", "read_polar_files", "read_polar_table",
    "read_xfoil_polar", "write_polar_table",
]
