"""Material laws: viscoelastic solids (Prony series, SLS, complex modulus and compliance,
creep spectrum) and their time-temperature shift laws (WLF, Arrhenius) (:mod:`.viscoelastic`)."""
from .viscoelastic import Arrhenius, CreepSpectrum, Material, WLF

__all__ = ["Arrhenius", "CreepSpectrum", "Material", "WLF"]
