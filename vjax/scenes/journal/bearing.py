"""The journal bearing scene's entry point: one function for its two films, the infinitely long
one (:mod:`vjax.scenes.journal.long`) and the finite one over the land
(:mod:`vjax.scenes.journal.finite`, ``length=L``)."""
from __future__ import annotations

import math

from .finite import FiniteJournalResult, finite_journal_bearing
from .finite.setup import check_supported
from .long import JournalResult, long_journal_bearing
from .options import FiniteJournalOptions, JournalOptions
from .setup import oil_and_bodies


def is_finite(length, tilt, supply_width) -> bool:
    """Whether these arguments describe a finite bearing (a length, a tilt or an axial groove's width)."""
    return length is not None or tilt is not None or supply_width != 1.0


def journal_bearing(R, radial_clearance, viscosity, load, *, housing=None, shaft=None, omega_shaft=0.0,
                    omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic", cavitation: str = "reynolds",
                    supply_angle=math.pi, supply_pressure=0.0, groove: str | None = None, temperature=None,
                    oil_temperature=None, initial: JournalResult | FiniteJournalResult | None = None,
                    options: JournalOptions | FiniteJournalOptions | None = None, throw: bool = True, length=None,
                    tilt=None, supply_width=1.0, roughness=None, shift=None) -> JournalResult | FiniteJournalResult:
    """Steady state of an infinitely long (visco)elastic journal bearing under a given load.

    The equations, conventions and solver: :mod:`vjax.scenes.journal.long` (infinitely long)
    and :mod:`vjax.scenes.journal.finite` (``length=``). Configurations of
    thesis Section 3.2: HS (``housing=`` soft, ``shaft=None``), SH, SS; both ``None`` is
    the rigid bearing.

    Args:
      R: bore radius R_B (m).
      radial_clearance: c = R_B - R_J (m), 0 < c < R.
      viscosity: lubricant viscosity eta (Pa s), isoviscous; or a :class:`~vjax.Lubricant` (or a
        function of the temperature in C returning Pa s), evaluated at ``oil_temperature``
        (default: ``temperature``).
      load: external force on the journal (N/m): a vector (Fx, Fy), or a magnitude with
        ``load_angle`` (rad, default -pi/2: downward).
      housing: body of the bearing: a :class:`~vjax.Material` (a hole with ``ref_length``
        1 m), a hole, liner or half_plane, or None (rigid, the default).
      shaft: body of the journal: a :class:`~vjax.Material` (a disc with ``ref_length`` 1 m),
        a disc, sleeve or half_plane, or None (rigid, the default).
      omega_shaft: angular velocity of the journal, omega_J (rad/s, CCW > 0).
      omega_housing: angular velocity of the bearing, omega_B (rad/s, CCW > 0). The
        entrainment speed v = (omega_B R_B + omega_J R_J)/2 must not be zero.
      memory: "periodic", "thesis" or a number of revolutions (see :mod:`vjax.bodies.operator`).
      cavitation: "reynolds" (default), "jfo" (mass-conserving), "half_sommerfeld" or
        "sommerfeld".
      supply_angle: groove position (rad, default pi), from the line of centres or, with
        ``groove="fixed"``, from the load direction (pi: opposite the load).
      supply_pressure: groove gauge pressure (Pa, default 0).
      groove: "line_of_centres" (the groove turns with it, the classical theory; the default
        of the infinitely long bearing) or "fixed" (in the bearing, as in a real bearing; the
        default of a finite one, which also takes "circumferential": a groove round the
        mid-width at ``supply_pressure``); see the module docstring.
      temperature: the bodies' temperature (C): each body whose material has a shift law
        (:meth:`~vjax.Material.with_shift`) and no temperature of its own answers at it (a
        material put at its own, :meth:`~vjax.Material.at_temperature`, keeps that); and the
        oil's, unless ``oil_temperature`` is given.
      oil_temperature: the :class:`~vjax.Lubricant`'s temperature (C), when it differs from
        the bodies'.
      initial: a previous :class:`JournalResult` (same n) to start Newton from (sweeps).
      options: :class:`~vjax.JournalOptions` (grid, tolerance, iteration caps, strategy; static),
        or with ``length`` a :class:`~vjax.FiniteJournalOptions`; None: the film's defaults.
      throw: raise :class:`~vjax.ConvergenceError` on failure (inside jit too); with False
        inspect ``converged`` and ``result``.
      length: axial length L (m) of a finite bearing (None: infinitely long, per unit length).
        With it the film covers the land (:mod:`vjax.scenes.journal.finite`): ``load`` is the total
        (N), the groove is fixed in the bearing at ``supply_angle`` from the load (None: no
        groove) over the central fraction ``supply_width`` of L (a feed hole: its diameter over
        L) or runs round the mid-width (``groove="circumferential"``), the journal may be tilted by
        ``tilt`` (gamma_x, gamma_y) (rad), ``options`` is a :class:`~vjax.FiniteJournalOptions`,
        the bodies deform as plane-strain slices (each axial section as the ring under its own
        pressure); returns a :class:`~vjax.FiniteJournalResult` (SI totals).
      shift: deprecated since 0.3 (a DeprecationWarning): the shift law of every material that
        has none; give each material its own instead.
      roughness: a :class:`~vjax.Roughness` (the surfaces' rms roughness, asperities, composite
        modulus and boundary friction): mixed lubrication, Patir and Cheng's average flow with
        Greenwood and Tripp's asperity contact, from full film down to a journal that barely
        turns, in the finite and the infinitely long bearing (per unit length), rigid bodies or
        deformable ones loaded by film and asperities together; the result's ``asperity_share``,
        ``asperity_pressure``, ``friction_viscous``, ``friction_boundary``,
        ``friction_coefficient`` and ``film_parameter`` (docs/theory.md §18). None: smooth
        surfaces.

    >>> import jax; jax.config.update("jax_enable_x64", True)
    >>> sol = journal_bearing(0.05, 5e-5, 0.01, 2e4, omega_shaft=100.0, options=JournalOptions(n=64))
    >>> bool(sol.converged), 0 < float(sol.eccentricity) < 1
    (True, True)
    """
    viscosity, temperature = oil_and_bodies(viscosity, temperature, oil_temperature, housing, shaft, shift)
    common = dict(housing=housing, shaft=shaft, omega_shaft=omega_shaft, omega_housing=omega_housing,
                  load_angle=load_angle, memory=memory, cavitation=cavitation, supply_angle=supply_angle,
                  supply_pressure=supply_pressure, temperature=temperature, shift=shift, initial=initial, throw=throw)
    if is_finite(length, tilt, supply_width):
        check_supported(length, groove, cavitation)
        return finite_journal_bearing(R, radial_clearance, viscosity, load, length, supply_width=supply_width,
                                      tilt=tilt, groove=groove or "fixed", roughness=roughness,
                                      options=FiniteJournalOptions() if options is None else options, **common)
    return long_journal_bearing(R, radial_clearance, viscosity, load, groove=groove, roughness=roughness,
                                options=JournalOptions() if options is None else options, **common)
