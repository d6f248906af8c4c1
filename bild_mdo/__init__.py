"""bild-mdo: BEM-based ideal-loading design (BILD) of optimal rotors for OpenMDAO.

Implements Ruh & Hwang, "Fast and robust computation of optimal rotor designs
using blade element momentum theory", AIAA Journal 61(9), 2023.
"""
__version__ = "0.1.0"
