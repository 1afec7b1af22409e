"""Level 2: the film's temperature field in a finite journal bearing (thermohydrodynamics).

The film's mean temperature T(theta, z) over the land (:mod:`vjax.films.energy`: convected by
the film's flow, heated by its shear, cooled through the bush and the journal, the groove
mixing the oil carried over with supply oil) and the Reynolds equation with the viscosity
of the lubricant at each node's temperature, solved together (docs/theory.md §19.2).

Solve: rounds of T -> eta(T) -> the film's steady state (Newton from the last one, the
sub-cell rupture on) -> the energy equation (a direct solve) -> T, mixed by Anderson's method
over the last rounds: 15-30 rounds to 1e-9 K where the viscosity halves every 10-20 K. On a
grid that nests (:func:`vjax.scenes.journal.finite.steady.nests`: 2048 cells and more) the
rounds start from the coarser grid's thermal solution (to 1e-6 K: a start) refined (128 x 32:
20 rounds from the cold film, 16 from the 64 x 16 solution, whose rounds are cheap).
Each deformable body sits at the land's mean film temperature (area-weighted): a body's
steady Green's function is that of a homogeneous body, so one temperature per body is what
the Fourier-space operator can hold (a liner's conductance is also far larger along it than
across the film's variation). The bodies' hysteresis heat, small beside the film's shear, is
spread evenly over the land.

Derivatives are implicit (:func:`vjax._core.solve.implicit_root`) in the film's unknowns and
the temperatures together: one GMRES solve of the coupled Jacobian, preconditioned by the
film's own Jacobian solve and the energy operator's (:mod:`.thermal_steady`: the coupled
equations, the rounds, the linear solves; the striated cavity's liquid fraction:
:func:`vjax.films.shear.striated_fraction`). Failures, thermal runaway among them (the film
passing ``FilmHeat.T_limit``: :data:`vjax._core.solve.RUNAWAY`), go through the core's one
failure path (:func:`vjax._core.solve.report`).
"""
from __future__ import annotations

import dataclasses
import math

import jax
import jax.numpy as jnp
import numpy as np

from ...._core import checks, scene as _scene, solve as _solve, xla
from ....films import energy
from ....materials.lubricant import as_lubricant
from ..options import FiniteJournalOptions
from . import setup as _finite_setup, steady as _steady
from .outputs import outputs
from .thermal_steady import (Static, moves, area_mean, coupled_residual, energy_equation, film_params, first_temperatures,
                             linear_solver, rounds)

COARSE_TOL = 1e-6    # K: a nesting grid's coarse rounds are a start, off by the grids' difference (~0.1 K)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class FilmHeat:
    """How heat enters and leaves a finite bearing's film (level 2).

    ``T_supply`` (C): the supply oil's temperature at the groove. ``carry_over``: the share of
    the oil arriving at the groove that stays in the film and mixes with supply oil (ROSS's
    default 0.8; 0: the groove refills with supply oil only). ``bush`` (W/(m^2 K)): the bush's
    heat-transfer coefficient to ``T_housing`` (C; None: ``T_supply``), e.g. a liner's
    conductivity over its thickness (:meth:`liner`); 0: adiabatic. ``journal``, ``T_journal``:
    the same for the journal's surface (0: adiabatic). ``T_limit`` (C): a film hotter than this
    anywhere is thermal runaway."""

    T_supply: jax.Array = 40.0
    carry_over: jax.Array = 0.8
    bush: jax.Array = 0.0
    T_housing: jax.Array | None = None
    journal: jax.Array = 0.0
    T_journal: jax.Array | None = None
    T_limit: jax.Array = 250.0

    def __post_init__(self):
        for name in ("T_supply", "T_limit", "T_housing", "T_journal"):
            if getattr(self, name) is not None:
                checks.finite(name, getattr(self, name))
        for name in ("bush", "journal"):
            v = checks.values(name, getattr(self, name))
            if v is not None and not (np.all(np.isfinite(v)) and np.all(np.asarray(v) >= 0)):
                raise ValueError(f"{name} must be a finite heat-transfer coefficient >= 0 (W/(m^2 K); 0: "
                                 f"adiabatic), got {v!r}")
        v = checks.values("carry_over", self.carry_over)
        if v is not None and not np.all((np.asarray(v) >= 0) & (np.asarray(v) < 1)):
            raise ValueError(f"carry_over must be in [0, 1) (the share of the arriving oil that stays in the film; 1 "
                             f"would recirculate all of it and the film could not cool), got {v!r}")

    @classmethod
    def liner(cls, conductivity, thickness, T_housing=None, **kw):
        """Heat conducted through a liner (``conductivity`` W/(m K), ``thickness`` m) to a housing
        at ``T_housing`` (C): bush = conductivity / thickness."""
        checks.positive("conductivity", conductivity)
        checks.positive("thickness", thickness)
        return cls(bush=conductivity / thickness, T_housing=T_housing, **kw)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class FilmTemperatureResult(_scene.SceneResult):
    """A finite bearing with its film's temperature field (level 2; W, K, C).

    ``temperature`` (n, m + 1) the film's mean temperature on the nodes (C), ``max_temperature``,
    ``mean_temperature`` (over the land's area), ``groove_temperature`` (m + 1,) the mixed inlet
    temperature on the groove's line, ``outlet_temperature`` the mean of the oil leaving
    through the ends, ``body_temperature`` the bodies' (the mean). ``viscosity`` (n, m + 1)
    (Pa s). Power: ``power_film`` the film's dissipation (Couette part striated in a Reynolds
    cavity), ``power_bodies`` the bodies' hysteresis, ``power`` their sum. Heat: ``heat_ends``
    carried out through both ends, ``heat_groove`` through the groove's discharge (the oil not
    carried over), ``heat_bush``, ``heat_journal`` conducted; power = the sum of the four to
    round-off. ``side_leakage`` Q (m^3/s). ``scene``: the film's :class:`~vjax.FiniteJournalResult`.
    ``film_overheated``: the maximum above the lubricant's T_max. Convergence: ``iterations``
    (rounds), ``residual`` (K), ``result`` (:data:`vjax._core.solve.RUNAWAY`: thermal runaway)."""

    temperature: jax.Array
    max_temperature: jax.Array
    mean_temperature: jax.Array
    groove_temperature: jax.Array
    outlet_temperature: jax.Array
    body_temperature: jax.Array
    viscosity: jax.Array
    power: jax.Array
    power_film: jax.Array
    power_bodies: jax.Array
    heat_ends: jax.Array
    heat_groove: jax.Array
    heat_bush: jax.Array
    heat_journal: jax.Array
    side_leakage: jax.Array
    film_overheated: jax.Array
    scene: object
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array

    def _describe(self, sep):
        keys = ("max_temperature", "mean_temperature", "outlet_temperature", "power", "heat_ends", "heat_groove",
                "iterations", "residual")
        parts = [f"{k}={np.asarray(getattr(self, k)).item():.6g}" for k in keys
                 if checks.is_concrete(getattr(self, k)) and np.shape(getattr(self, k)) == ()]
        if checks.is_concrete(self.result) and np.shape(self.result) == ():
            code = int(self.result)
            words = "thermal runaway: the film passed T_limit" if code == _solve.RUNAWAY else _solve.MESSAGES[code]
            parts.append(f"status: {words}")
        return sep.join(parts)


def thermal_film_bearing(R, radial_clearance, lubricant, load, heat: FilmHeat, *, length, housing=None, shaft=None,
                         shift=None, omega_shaft=0.0, omega_housing=0.0, load_angle=-math.pi / 2,
                         supply_angle=math.pi, supply_width=1.0, cavitation="reynolds",
                         options: FiniteJournalOptions = FiniteJournalOptions(), tol=None, max_iter=80,
                         relax=0.5, initial: FilmTemperatureResult | None = None,
                         throw=True) -> FilmTemperatureResult:
    """A finite journal bearing with its film's temperature field (module docs; docs/theory.md
    §19.2): the arguments of :func:`vjax.journal_bearing` with ``length=`` for an aligned
    bearing with an axial groove at ``supply_angle`` (held at ambient pressure), the
    :class:`~vjax.Lubricant` ``lubricant`` (its viscosity law, rho and c_p) in place of a
    viscosity, and ``heat`` (:class:`FilmHeat`). ``cavitation``: "reynolds" (the cavity's
    striated film carries the flux at rupture and shears its liquid only) or "jfo".

    ``tol`` (K): of the last round's largest change (None: 1e-9 K in float64). ``max_iter``:
    rounds. ``relax``: each round's update factor. ``initial``: a result of the same grid to
    start from (a sweep's last point: its film and temperatures). Thermal runaway (the film passing
    ``heat.T_limit``) and failures raise :class:`~vjax.ConvergenceError` (``throw=False``: the
    result code). Returns :class:`FilmTemperatureResult`."""
    lubricant = as_lubricant(lubricant, "lubricant")
    lubricant.require("rho", "c_p")
    checks.instance("heat", heat, FilmHeat, "a vjax.FilmHeat")
    checks.instance("options", options, FiniteJournalOptions, "a vjax.FiniteJournalOptions")
    checks.one_of("cavitation", cavitation, ("reynolds", "jfo"))
    v = checks.values("omega_shaft", 0.5 * (omega_housing * R + omega_shaft * (R - radial_clearance)))
    if v is None or v == 0:
        raise ValueError("omega_shaft, omega_housing: the film's temperature needs concrete speeds with a nonzero "
                         "entrainment speed (omega_housing R + omega_shaft R_J != 0): a film at rest has no flow")
    if supply_angle is None:
        raise ValueError("supply_angle: the film's temperature needs an axial groove (its inlet of supply oil); "
                         "give its angle from the load (rad)")
    if not 0 < relax <= 1:
        raise ValueError(f"relax must be in (0, 1], got {relax!r}")
    eps = float(jnp.finfo(jnp.result_type(float)).eps)
    tol_K = float(tol) if tol is not None else (1e-9 if eps < 1e-10 else 1e-3)
    st = Static(options, float(supply_angle), float(supply_width), cavitation, float(load_angle), bool(v > 0),
                housing is not None or shaft is not None, tol_K, int(max_iter), float(relax))
    params = dict(R=R, c=radial_clearance, load=load, L=length, wJ=omega_shaft, wB=omega_housing, oil=lubricant,
                  heat=heat, housing=housing, shaft=shaft, shift=shift)
    shape = (options.n, options.m + 1)
    pr0, cfg0 = film_params(jnp.zeros(shape), params, st)
    if initial is not None:
        if not isinstance(initial, FilmTemperatureResult) or initial.temperature.shape != shape:
            raise ValueError(f"initial must be a FilmTemperatureResult of the same grid (n = {options.n}, "
                             f"m = {options.m})")
        x0 = jax.lax.stop_gradient(_finite_setup.start_from(initial.scene, pr0, cfg0))
        T0 = jax.lax.stop_gradient(initial.temperature - heat.T_supply)
        return _finish(x0, T0, params, st, shape, lubricant, heat, throw)
    if _steady.nests(options) and checks.is_concrete(params):
        # from the coarser grid's thermal solution, refined (module docs)
        coarse = thermal_film_bearing(R, radial_clearance, lubricant, load, heat, length=length, housing=housing,
                                      shaft=shaft, shift=shift, omega_shaft=omega_shaft, omega_housing=omega_housing,
                                      load_angle=load_angle, supply_angle=supply_angle, supply_width=supply_width,
                                      cavitation=cavitation, options=_steady.coarse_options(options),
                                      tol=max(st.tol, COARSE_TOL), max_iter=max_iter, relax=relax, throw=False)
        if bool(coarse.converged):
            T0 = _steady.finer(coarse.temperature - heat.T_supply, shape[0])
            return _finish(_steady.refined(coarse.scene, pr0, cfg0), jax.lax.stop_gradient(T0), params, st, shape,
                           lubricant, heat, throw)
    # else from the isothermal film at the supply temperature and a mean-rise estimate (first_temperatures)
    at = dict(temperature=heat.T_supply, shift=shift) if st.deformable and moves(housing, shaft, shift) else {}
    cold = _steady.finite_journal_bearing(
        R, radial_clearance, lubricant.viscosity(heat.T_supply), load, length, housing=housing, shaft=shaft,
        omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle, cavitation=cavitation,
        supply_angle=supply_angle, supply_width=supply_width, options=options, throw=False, **at)
    x0 = jax.lax.stop_gradient(_finite_setup.start_from(cold, pr0, cfg0))
    T0 = jax.lax.stop_gradient(first_temperatures(x0, params, st, shape))
    return _finish(x0, T0, params, st, shape, lubricant, heat, throw)


def _finish(x0, T0, params, st: Static, shape, lubricant, heat, throw):
    """The rounds from (x0, T0), implicitly differentiated, and the result."""
    u, stats = _solve.implicit_root(lambda p: rounds(p, st, shape, x0, T0),
                                    lambda uu, aux, p: coupled_residual(uu, p, st, shape),
                                    linear_solver(st, shape))(params)
    out = _outputs(u, params, st, shape, stats, lubricant)
    _solve.report("thermal_film_bearing", out, throw, hint=_hint,
                  values=dict(T_max=out.max_temperature, T_limit=heat.T_limit))
    return out


@xla.jit(static_argnums=(2, 3))
def _outputs(u, params, st: Static, shape, stats, lubricant):
    heat = params["heat"]
    n_T = shape[0] * shape[1]
    x, T_rise = u[:-n_T], u[-n_T:].reshape(shape)
    pr, cfg = film_params(T_rise, params, st)
    _, _, parts = energy_equation(x, T_rise, params, st, pr, cfg)
    scene = outputs(x, pr, cfg, stats)
    T = heat.T_supply + T_rise
    rho_cp = parts["rho_cp"]
    ends = jnp.maximum(energy.end_flows(parts["Fx"], parts["Fz"]), 0.0)
    T_ends = jnp.stack([T_rise[:, 0], T_rise[:, -1]], axis=1)
    heat_ends = rho_cp * jnp.sum(ends * T_ends)
    heat_bush = jnp.sum(parts["hB"] * (T - parts["T_B"]))
    heat_journal = jnp.sum(parts["hJ"] * (T - parts["T_J"]))
    power = jnp.sum(parts["source"])
    # the groove's discharge: what its volumes take in (flows, their own heat) and do not pass on
    g = pr.groove > 0
    plain, _ = energy.operator(parts["Fx"], parts["Fz"], jnp.zeros_like(pr.groove), heat.carry_over,
                               (parts["hB"] + parts["hJ"]) / rho_cp, st.v_positive)
    imbalance = rho_cp * energy.matvec(plain, T_rise) - parts["source"] \
        - parts["hB"] * (parts["T_B"] - heat.T_supply) - parts["hJ"] * (parts["T_J"] - heat.T_supply)
    heat_groove = -jnp.sum(jnp.where(g, imbalance, 0.0))
    groove_line = jnp.argmax(jnp.sum(pr.groove, axis=1))
    return FilmTemperatureResult(
        temperature=T, max_temperature=jnp.max(T), mean_temperature=heat.T_supply + area_mean(T_rise, params, st),
        groove_temperature=T[groove_line],
        outlet_temperature=heat.T_supply + jnp.sum(ends * T_ends) / jnp.maximum(jnp.sum(ends), jnp.finfo(T.dtype).tiny),
        body_temperature=heat.T_supply + area_mean(T_rise, params, st), viscosity=pr.eta, power=power,
        power_film=jnp.sum(parts["Phi"]), power_bodies=parts["P_bodies"], heat_ends=heat_ends,
        heat_groove=heat_groove, heat_bush=heat_bush, heat_journal=heat_journal,
        side_leakage=scene.side_leakage,
        film_overheated=jnp.asarray(False) if lubricant.T_max is None else jnp.max(T) > lubricant.T_max,
        scene=scene, iterations=stats.iterations, residual=stats.residual, result=stats.result)


def _hint(result, T_max, T_limit):
    """The failed solve's cause and what the user can change."""
    if result == _solve.RUNAWAY:
        return (f" This is thermal runaway: the film's temperature passed T_limit = {T_limit:.6g} C (reached "
                f"{T_max:.6g} C): the heat generated outgrows the heat carried off. More cooling (supply flow, a "
                f"cooler supply, a conducting bush), or a higher FilmHeat.T_limit.")
    if result == _solve.INNER_FAILED:
        return (f" The film's Newton failed at the rounds' last temperatures (max temperature {T_max:.6g} C): a "
                f"smaller relax, or a start nearer the answer (initial=).")
    return (f" Its iterations are rounds (a film and an energy solve each), its residual the last round's largest "
            f"change (K), at a max temperature of {T_max:.6g} C: a larger max_iter or tol, or a smaller relax.")
