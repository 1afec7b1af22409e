"""vjax: differentiable viscoelastic contact mechanics in circular geometries, in JAX.

Precision: vjax never changes JAX's global configuration on import. Its results are meant
to be float64, so enable it **before any JAX computation**::

    import jax
    jax.config.update("jax_enable_x64", True)   # or: export JAX_ENABLE_X64=1
    import vjax

Without it everything runs in float32 (no NaN, lower accuracy); vjax warns once on import.
The command-line tools, experiments and tests enable float64 themselves.
"""
import warnings as _warnings

import jax as _jax

from .material import Arrhenius, CreepSpectrum, Material, WLF
from .operator import RingOperator, effective_compliance, element_symbol, grid, ring_operator
from . import bodies, green
from .bodies import Body, disc, half_plane, hole, liner, sleeve
from ._solve import ConvergenceError
from .contact import ContactOptions, ContactSolution, solve_contact
from .pin import PinOptions, PinResult, pin_in_hole, pin_patch_speed, pin_shaft_speed
from .journal import JournalOptions, JournalResult, journal_bearing
from .journal_finite import FiniteJournalOptions, FiniteJournalResult
from .journal_dynamics import JournalCoefficients, journal_coefficients, stability_threshold
from .roller import RollerOptions, RollerResult, roller_bearing, roller_patch_speeds
from . import reference
from .sweep import initialize_processes, sweep

__all__ = ["Arrhenius", "CreepSpectrum", "Material", "WLF", "RingOperator", "effective_compliance",
           "element_symbol", "grid", "ring_operator", "bodies", "green", "Body", "disc", "half_plane", "hole", "liner", "sleeve",
           "ConvergenceError", "ContactOptions", "ContactSolution", "solve_contact",
           "PinOptions", "PinResult", "pin_in_hole", "pin_patch_speed", "pin_shaft_speed",
           "JournalOptions", "JournalResult", "journal_bearing", "FiniteJournalOptions", "FiniteJournalResult", "JournalCoefficients", "journal_coefficients",
           "stability_threshold",
           "RollerOptions", "RollerResult", "roller_bearing", "roller_patch_speeds", "reference", "sweep",
           "initialize_processes"]

if not _jax.config.read("jax_enable_x64"):
    _warnings.warn(
        "vjax: JAX runs in float32; results are meant to be float64. Call "
        "jax.config.update('jax_enable_x64', True) (or set JAX_ENABLE_X64=1) before any JAX "
        "computation.", stacklevel=2)
