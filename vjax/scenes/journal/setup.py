"""What the long and the finite journal bearing share in their set-up: the checks of the
arguments both take, the bodies (checked, fitted to their radii, at their temperature), and
the closing sentence of a smooth film's failure where roughness would carry the load."""
from __future__ import annotations

import numpy as np

from ..._core import checks, scene as _scene
from ...bodies.body import Body, as_body, check_fits, disc, hole
from ...bodies.operator import memory_revolutions
from ...films import reynolds
from ...materials.lubricant import Lubricant, as_lubricant
from ...materials.viscoelastic import Material

HOUSINGS = ("hole", "liner", "half_plane")
SHAFTS = ("disc", "sleeve", "half_plane")


def check_arguments(R, radial_clearance, viscosity, load, *, omega_shaft, omega_housing, load_angle, memory,
                    cavitation, supply_pressure, **positive):
    """Refuse, naming the argument, what neither film can take: non-positive sizes and viscosity
    (and the further ``positive`` ones, e.g. the length), non-finite speeds, a clearance not
    below R, zero entrainment speed (no hydrodynamic load capacity), a negative supply pressure,
    an unknown cavitation model or memory, a malformed load."""
    checks.one_of("cavitation", cavitation, reynolds.CAVITATION)
    memory_revolutions(memory)
    _scene.scalars(checks.positive, R=R, radial_clearance=radial_clearance, viscosity=viscosity, **positive)
    _scene.scalars(checks.finite, omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle)
    _scene.scalars(checks.nonnegative, supply_pressure=supply_pressure)
    Rv, cv = checks.values("R", R), checks.values("radial_clearance", radial_clearance)
    if Rv is not None and cv is not None and not np.all(cv < Rv):
        raise ValueError(f"radial_clearance must be < R, got radial_clearance={radial_clearance!r}, R={R!r}")
    wB, wJ = (checks.values(k, v) for k, v in (("omega_housing", omega_housing), ("omega_shaft", omega_shaft)))
    if wB is not None and wJ is not None and Rv is not None and cv is not None and wB * Rv + wJ * (Rv - cv) == 0:
        raise ValueError("omega_housing R + omega_shaft (R - radial_clearance) = 0: zero entrainment speed, "
                         "no hydrodynamic load capacity (omega_shaft, omega_housing)")
    checks.load(load)


def bodies_at(R, radial_clearance, housing, shaft, temperature, shift):
    """The checked housing and shaft bodies (None: rigid; a bare Material: a hole, resp. a disc)
    at ``temperature`` under ``shift``."""
    housing = as_body("housing", housing, hole, HOUSINGS)
    shaft = as_body("shaft", shaft, disc, SHAFTS)
    check_fits("housing", housing, R)
    check_fits("shaft", shaft, R - radial_clearance)
    return _scene.at_temperature(temperature, shift, housing, shaft)


def oil_and_bodies(viscosity, temperature, oil_temperature, housing, shaft, shift):
    """The film's viscosity (Pa s) and the temperature the bodies are given (C, or None).

    ``viscosity``: a number (Pa s: the oil at its own temperature), or a :class:`~vjax.Lubricant`
    (or a function of the temperature in C returning Pa s) evaluated at ``oil_temperature``, or
    at ``temperature`` when that is None. ``temperature`` moves the bodies whose materials carry
    a shift law and no temperature of their own; when it set only the oil, none is passed on.
    """
    oil_T = temperature if oil_temperature is None else oil_temperature
    if isinstance(viscosity, Lubricant) or callable(viscosity):
        if oil_T is None:
            raise ValueError("viscosity: a Lubricant (or a function of the temperature) is evaluated at the oil's "
                             "temperature: give temperature= or oil_temperature= (C)")
        checks.finite("oil_temperature" if oil_temperature is not None else "temperature", oil_T)
        viscosity = as_lubricant(viscosity).viscosity(oil_T)
        bodies = [b.material if isinstance(b, Body) else b for b in (housing, shaft)]
        moved = any(isinstance(m, Material) and m.shift is not None and m.temperature is None for m in bodies)
        if oil_temperature is None and shift is None and not moved:
            temperature = None          # the temperature was the oil's alone
    elif oil_temperature is not None:
        raise ValueError("oil_temperature: the viscosity is a number (Pa s), the oil's at its own temperature; "
                         "give a vjax.Lubricant to evaluate it at oil_temperature")
    return viscosity, temperature


def roughness_hint(thin: float) -> str:
    """The closing sentence of a smooth bearing's failure whose film would have to be ``thin``
    (a fraction of the clearance) to carry the load: rough surfaces let the asperities carry
    their share (mixed lubrication)."""
    return (f" A film of ~{thin:.2g} c would carry this load: with smooth surfaces it must carry all of it; give "
            f"the surfaces' roughness (roughness=vjax.Roughness(...)) and the asperities carry their share (mixed "
            f"lubrication).")
