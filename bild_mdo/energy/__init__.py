"""Energy production of a turbine rotor over a wind distribution (:class:`AnnualEnergyComp`)."""
from bild_mdo.energy.annual_energy import HOURS_PER_YEAR, AnnualEnergyComp

__all__ = ["HOURS_PER_YEAR", "AnnualEnergyComp"]
