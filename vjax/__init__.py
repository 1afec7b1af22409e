"""vjax: differentiable viscoelastic contact mechanics in circular geometries, in JAX.

Precision: vjax never changes JAX's global configuration on import. Its results are meant
to be float64, so enable it **before any JAX computation**::

    import jax
    jax.config.update("jax_enable_x64", True)   # or: export JAX_ENABLE_X64=1
    import vjax

Without it everything runs in float32 (no NaN, lower accuracy); vjax warns once on import.
The command-line tools, experiments and tests enable float64 themselves.
"""
import importlib.metadata as _metadata
import sys as _sys
import warnings as _warnings

import jax as _jax

from ._core import checks
from ._core.cache import enable_compilation_cache
from ._core.solve import ConvergenceError
from .materials import Arrhenius, CreepSpectrum, Lubricant, Material, WLF, as_lubricant
from . import bodies
from .bodies import Body, disc, green, half_plane, hole, land, layer3d, liner, sleeve
from .bodies.operator import RingOperator, effective_compliance, element_symbol, grid, ring_operator
from .contact import ContactOptions, ContactSolution, solve_contact
from .films import reynolds
from .films.roughness import Roughness
from .scenes.pin import PinOptions, PinResult, pin_in_hole, pin_patch_speed, pin_shaft_speed
from .scenes.roller import RollerOptions, RollerResult, roller_bearing, roller_patch_speeds
from .scenes.thermal import HeatTransfer, ThermalResult, thermal_journal_bearing, thermal_pin, thermal_roller
from .scenes.journal.finite.thermal import FilmHeat, FilmTemperatureResult, thermal_film_bearing
from .scenes.journal import (FiniteJournalOptions, FiniteJournalResult, JournalCoefficients, JournalOptions,
                             JournalResult, StribeckCurve, journal_bearing, journal_coefficients,
                             stability_threshold, stribeck_curve, tilt_coefficients)
from . import reference
from .sweep import initialize_processes, sweep

try:
    __version__ = _metadata.version("vjax")
    """vjax's version: pyproject.toml's ``version`` as installed (``pip install -e .`` after changing it)."""
except _metadata.PackageNotFoundError:          # imported from a source tree that was never installed
    __version__ = "0+unknown"

__all__ = ["Arrhenius", "CreepSpectrum", "Lubricant", "Material", "WLF", "as_lubricant", "RingOperator", "effective_compliance",
           "element_symbol", "grid", "ring_operator", "bodies", "green", "layer3d", "Body", "disc", "half_plane",
           "hole", "liner", "sleeve", "ConvergenceError", "ContactOptions", "ContactSolution", "solve_contact",
           "PinOptions", "PinResult", "pin_in_hole", "pin_patch_speed", "pin_shaft_speed",
           "JournalOptions", "JournalResult", "journal_bearing", "FiniteJournalOptions", "FiniteJournalResult",
           "JournalCoefficients", "journal_coefficients", "stability_threshold", "tilt_coefficients",
           "RollerOptions", "RollerResult", "roller_bearing", "roller_patch_speeds", "reference", "sweep",
           "initialize_processes", "checks", "reynolds", "enable_compilation_cache", "Roughness", "StribeckCurve", "stribeck_curve"]
__all__ += ["HeatTransfer", "ThermalResult", "thermal_journal_bearing", "thermal_pin", "thermal_roller"]
__all__ += ["FilmHeat", "FilmTemperatureResult", "thermal_film_bearing"]
__all__ += ["__version__"]

# The flat module paths of vjax 0.1 (before the layer folders), kept working as aliases of
# their new homes: ``from vjax.layer3d import layer_modes`` and ``vjax.journal_finite`` still
# import. New code should use the names above or the new paths (CHANGELOG.md, 0.2.0).
from .bodies import operator as _operator
from .materials import viscoelastic as _viscoelastic
from .scenes import journal as _journal, pin as _pin, roller as _roller
from .scenes.journal import dynamics as _dynamics, finite as _finite

for _old, _module in {"material": _viscoelastic, "operator": _operator, "green": green, "layer3d": layer3d,
                      "layer3d_land": land, "reynolds": reynolds, "checks": checks, "pin": _pin,
                      "roller": _roller, "journal": _journal, "journal_finite": _finite,
                      "journal_dynamics": _dynamics}.items():
    _sys.modules[f"{__name__}.{_old}"] = _module
    globals()[_old] = _module

if not _jax.config.read("jax_enable_x64"):
    _warnings.warn(
        "vjax: JAX runs in float32; results are meant to be float64. Call "
        "jax.config.update('jax_enable_x64', True) (or set JAX_ENABLE_X64=1) before any JAX "
        "computation.", stacklevel=2)
