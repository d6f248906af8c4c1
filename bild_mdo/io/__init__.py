"""Blade geometry files: CSV, JSON and the QPROP propeller file, all holding one :class:`RotorGeometry`.

::

    from bild_mdo.io import read_geometry, write_geometry

    write_geometry("blade.csv", design_rotor())     # format from the suffix: .csv, .json, else QPROP
    geometry = read_geometry("blade.csv")
    write_stl("blade.stl", design_rotor())          # a closed 3D blade for CAD or 3D printing (bild_mdo.io.blade_3d)
"""
from bild_mdo.io.blade_3d import blade_surface, section_coordinates, write_step, write_stl
from bild_mdo.io.csv import read_csv, write_csv
from bild_mdo.io.files import FORMATS, read_geometry, write_geometry
from bild_mdo.io.geometry import DESIGN_POINT_UNITS, RotorGeometry, as_geometry, unit_key
from bild_mdo.io.json import read_json, write_json
from bild_mdo.io.qprop import polar_from_qprop, qprop_airfoil_coefficients, read_qprop, write_qprop

__all__ = [
    "DESIGN_POINT_UNITS", "FORMATS", "RotorGeometry", "as_geometry", "blade_surface", "polar_from_qprop",
    "qprop_airfoil_coefficients", "read_csv", "read_geometry", "read_json", "read_qprop", "section_coordinates",
    "unit_key", "write_csv", "write_geometry", "write_json", "write_qprop", "write_step", "write_stl",
]
