"""Material laws: viscoelastic solids (Prony series, SLS, complex modulus and compliance,
creep spectrum) and their time-temperature shift laws (WLF, Arrhenius) (:mod:`.viscoelastic`);
lubricants: viscosity by temperature, density, heat capacity, conductivity (:mod:`.lubricant`)."""
from .lubricant import Lubricant, as_lubricant
from .viscoelastic import GAS_CONSTANT, KELVIN, Arrhenius, CreepSpectrum, Material, WLF

__all__ = ["GAS_CONSTANT", "KELVIN", "Arrhenius", "CreepSpectrum", "Lubricant", "Material", "WLF", "as_lubricant"]
