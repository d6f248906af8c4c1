"""Energy production of a turbine rotor over a wind distribution.

:class:`AnnualEnergyComp` takes one design ``C_P`` for region 2 and assumes rated power above rated;
:class:`PowerCurveGroup` analyses the blade by the BEM at every wind speed, with the collective pitch
trimmed to rated power above rated.
"""
from bild_mdo.energy.annual_energy import HOURS_PER_YEAR, AnnualEnergyComp
from bild_mdo.energy.power_curve_group import PowerCurveGroup

__all__ = ["HOURS_PER_YEAR", "AnnualEnergyComp", "PowerCurveGroup"]
