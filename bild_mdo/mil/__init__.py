"""Minimum-induced-loss propeller design (Adkins & Liebeck 1994) beside BILD: MILGroup and design_mil."""
from bild_mdo.mil.design import MILDesign, design_mil
from bild_mdo.mil.mil_group import MILGroup

__all__ = ["MILDesign", "MILGroup", "design_mil"]
