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
film's own Jacobian solve and the energy operator's.
"""
from __future__ import annotations

import dataclasses
import math

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks, krylov, scene as _scene, solve as _solve, xla
from ..films import energy, film2d
from ..materials.lubricant import as_lubricant
from .journal.finite import setup as _finite_setup
from .journal.finite.film import equations, fields, linear_model, solved_by_linear_model
from .journal.finite.outputs import outputs
from .journal.finite import steady as _steady
from .journal.options import FiniteJournalOptions
from .thermal import MESSAGES, RUNAWAY, striated_fraction

GMRES_TOL = 1e-13
FULL = 1e-3          # a node with p below FULL p_max is partly cavitated (:func:`_energy`)
ANDERSON = 5         # rounds in Anderson's mixing
MAX_FAILS = 6        # failed films in a row before the solve gives up
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
    (rounds), ``residual`` (K), ``result`` (:data:`vjax.scenes.thermal.RUNAWAY`: runaway)."""

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
            parts.append(f"status: {MESSAGES[int(self.result)]}")
        return sep.join(parts)


@dataclasses.dataclass(frozen=True)
class _Static:
    """What the solve holds fixed: the finite bearing's static arguments and its configuration."""

    options: FiniteJournalOptions
    supply_angle: float
    supply_width: float
    cavitation: str
    load_angle: float
    v_positive: bool
    deformable: bool
    tol: float
    max_iter: int
    relax: float


def _film_params(T_rise, params, st: _Static):
    """The finite bearing's parameters with the viscosity at each node's temperature and the
    bodies at the mean, and its configuration."""
    heat, oil = params["heat"], params["oil"]
    T = heat.T_supply + T_rise
    body = {}
    if st.deformable and params["shift"] is not None:
        body = dict(temperature=heat.T_supply + _area_mean(T_rise, params, st), shift=params["shift"])
    pr, cfg = _finite_setup.setup(params["R"], params["c"], oil.viscosity(heat.T_supply), params["load"], params["L"],
                                  housing=params["housing"], shaft=params["shaft"], omega_shaft=params["wJ"],
                                  omega_housing=params["wB"], load_angle=st.load_angle, cavitation=st.cavitation,
                                  supply_angle=st.supply_angle, supply_width=st.supply_width, options=st.options,
                                  **body)
    cfg = dataclasses.replace(cfg, half=True)
    return dataclasses.replace(pr, eta=oil.viscosity(T)), cfg


def _area_mean(T_rise, params, st: _Static):
    wz = film2d.node_widths(0.5 * params["L"] * film2d.unit_nodes(st.options.m, st.options.spacing))
    return jnp.sum(T_rise @ wz) / (T_rise.shape[0] * jnp.sum(wz))


def _energy(x, T_rise, params, st: _Static, pr, cfg):
    """The energy equation at the film's unknowns x: (operator blocks, right side, parts). Under
    Reynolds cavitation a node is full in the proportion min(1, p / (FULL p_max)) (a groove's
    fully): a continuous switch, so that the temperatures are a smooth function of the film
    (a node at the rupture flipping between full and striated would make the rounds cycle and
    the results jump)."""
    heat, oil = params["heat"], params["oil"]
    f = fields(x, pr, cfg)
    p, h, z = f["p_load"], f["h"], f["z"]
    n = p.shape[0]
    dU = pr.omega_B * pr.R - pr.omega_J * pr.RJ
    if st.cavitation == "jfo":
        frac = film2d.upwind(f["fraction"], pr.v)
        flux = film2d.fluxes(p, h, pr.R, z, pr.eta, pr.v)
    else:
        full = jnp.maximum(jnp.clip(p / (FULL * jnp.max(p)), 0.0, 1.0), pr.groove)
        frac, flux = striated_fraction(p, h, z, pr.R, pr.eta, pr.v, full)
    Fx, Fz = energy.face_flows(flux, frac, pr.R, z)
    Phi = energy.dissipation(flux, frac, dU, pr.R, z)
    area = pr.R * (2 * math.pi / n) * film2d.node_widths(z)[None, :] * jnp.ones_like(p)
    rho_cp = oil.density(heat.T_supply) * oil.c_p      # J/(m^3 K): the supply oil's (an incompressible film)
    P_bodies = -pr.omega_B * _hysteresis(f, pr, "uB") - pr.omega_J * _hysteresis(f, pr, "uJ")
    source = Phi + P_bodies * area / jnp.sum(area)
    T_B = heat.T_supply if heat.T_housing is None else heat.T_housing
    T_J = heat.T_supply if heat.T_journal is None else heat.T_journal
    hB, hJ = heat.bush * area, heat.journal * area
    wall = (hB + hJ) / rho_cp
    rhs = (source + hB * (T_B - heat.T_supply) + hJ * (T_J - heat.T_supply)) / rho_cp
    blocks, _ = energy.operator(Fx, Fz, pr.groove, heat.carry_over, wall, st.v_positive)
    rhs = jnp.where(pr.groove > 0, 0.0, rhs)
    parts = dict(Fx=Fx, Fz=Fz, Phi=Phi, P_bodies=P_bodies, hB=hB, hJ=hJ, T_B=T_B, T_J=T_J, rho_cp=rho_cp,
                 source=source, area=area)
    return blocks, rhs, parts


def _hysteresis(f, pr, key):
    """A body's viscoelastic torque (N m): the pressure's moment on its deformed profile
    (:func:`vjax.scenes.journal.finite.outputs.outputs`)."""
    central = 0.5 * (jnp.roll(f[key], -1, axis=0) - jnp.roll(f[key], 1, axis=0))
    return -pr.R * jnp.sum(f["p_load"] * central, axis=0) @ film2d.node_widths(f["z"])


def _residual(u, params, st: _Static, shape):
    """The coupled equations at u = (the film's unknowns, the temperature rise): the film's cell
    equations and force balance, and the energy equation over its diagonal (K)."""
    n_T = shape[0] * shape[1]
    x, T_rise = u[:-n_T], u[-n_T:].reshape(shape)
    pr, cfg = _film_params(T_rise, params, st)
    blocks, rhs, _ = _energy(x, T_rise, params, st, pr, cfg)
    scale = jnp.einsum("ijj->ij", blocks[1])
    r_T = (energy.matvec(blocks, T_rise) - rhs) / scale
    return jnp.concatenate([equations(x, pr, cfg)[0], r_T.ravel()])


def _round(carry, params, st: _Static, shape):
    """One round: the film at the viscosity of T, then G(T), the temperature the energy equation
    gives at that film; the next T by Anderson's mixing of the last ANDERSON rounds (Walker and
    Ni 2011; the plain relaxed step T + relax (G - T) while the history is empty). G's slope is
    about -1 in the film's mean temperature (a hotter film thins and shears less), which plain
    substitution would follow in a slow oscillation. Where the film's Newton fails at a T (a
    mixing step too bold), the round goes back halfway to the last T whose film converged and
    restarts the history."""
    x_good, T_rise, _, k, fails, (dT, dF, T_prev, F_prev) = carry
    pr, cfg = _film_params(T_rise, params, st)
    x, stats = _steady.solve(dataclasses.replace(pr, x0=x_good), cfg, "polish")
    blocks, rhs, _ = _energy(x, T_rise, params, st, pr, cfg)
    T, F = T_rise.ravel(), energy.cyclic_block_solve(blocks, rhs).ravel() - T_rise.ravel()
    ok = (stats.result == _solve.SUCCESS) & jnp.all(jnp.isfinite(F))
    change = jnp.where(ok, jnp.max(jnp.abs(F)), jnp.inf)
    # the history: differences of the iterates and of their residuals, a ring of ANDERSON slots
    slot = (k - 1) % ANDERSON
    restart = (k == 0) | (fails > 0) | ~ok
    dT = jnp.where(restart, 0.0, dT.at[slot].set(T - T_prev))
    dF = jnp.where(restart, 0.0, dF.at[slot].set(F - F_prev))
    used = jnp.any(dF != 0.0, axis=1)
    gram = dF @ dF.T
    gram = jnp.where(used[:, None] & used[None, :], gram, 0.0) + jnp.diag(jnp.where(used, 1e-14 * jnp.trace(gram), 1.0))
    gamma = jnp.where(used, jnp.linalg.solve(gram, jnp.where(used, dF @ F, 0.0)), 0.0)
    step = st.relax * F - (dT + st.relax * dF).T @ gamma
    step = jnp.where(jnp.all(jnp.isfinite(step)), step, st.relax * F)
    # a failed film: back halfway to the last good T (T_prev, whose film x_good is)
    T_next = jnp.where(ok, T + step, 0.5 * (T + T_prev)).reshape(shape)
    T_prev, F_prev = jnp.where(ok, T, T_prev), jnp.where(ok, F, F_prev)
    return jnp.where(ok, x, x_good), T_next, change, k + 1, jnp.where(ok, 0, fails + 1), (dT, dF, T_prev, F_prev)


_round_compiled = xla.jit(_round, static_argnums=(2, 3))


@xla.jit(static_argnums=(2, 3))
def _first_temperatures(x0, params, st: _Static, shape):
    """The rounds' start: the energy equation's field G0 at the cold film (x0, the supply
    temperature's viscosity), scaled to the mean rise r that a film whose dissipation followed
    its viscosity, flows held, would have: r = mean(G0) eta(T_s + r) / eta(T_s) (bisection).
    Near the answer, so that the first rounds' films move little (each cell the cavity moves
    costs the film's Newton a step)."""
    zero = jnp.zeros(shape, x0.dtype)
    pr, cfg = _film_params(zero, params, st)
    blocks, rhs, _ = _energy(x0, zero, params, st, pr, cfg)
    G0 = energy.cyclic_block_solve(blocks, rhs)
    mean0 = jnp.maximum(_area_mean(G0, params, st), 0.0)
    oil, T_s = params["oil"], params["heat"].T_supply
    r = _solve.bisect(lambda r: r - mean0 * oil.viscosity(T_s + r) / oil.viscosity(T_s), jnp.zeros_like(mean0),
                      mean0, 60, sign_lo=-1.0)
    return jnp.where(mean0 > 0, G0 * r / jnp.where(mean0 > 0, mean0, 1.0), zero)


def _solver(params, st: _Static, shape, x0, T0):
    """Rounds (:func:`_round`) from x0 (the film at the supply temperature) and T' = T0
    (:func:`_first_temperatures`), under a trace in a while_loop, else in Python over one
    compiled round."""
    f = jnp.result_type(float)
    heat = params["heat"]
    N = shape[0] * shape[1]
    history = (jnp.zeros((ANDERSON, N), f), jnp.zeros((ANDERSON, N), f), jnp.zeros(N, f), jnp.zeros(N, f))
    carry = (x0, T0, jnp.asarray(jnp.inf, f), jnp.asarray(0), jnp.asarray(0), history)
    hot = lambda T_rise: jnp.max(heat.T_supply + T_rise) > heat.T_limit       # noqa: E731

    def cond(c):
        _, T_rise, change, k, fails = c[:5]
        return (change > st.tol) & (k < st.max_iter) & (fails < MAX_FAILS) & ~hot(T_rise)

    if checks.is_concrete(params):
        while bool(cond(carry)):
            carry = _round_compiled(carry, params, st, shape)
    else:
        carry = jax.lax.while_loop(cond, lambda c: _round(c, params, st, shape), carry)
    x, T_next, change, k, fails, (_, _, T_rise, _) = carry
    # the temperatures x's film was solved at (the last round's, before its update): the pair is
    # the root to the film's tolerance and the last change, whatever the update did
    T_rise = jnp.where((k > 0) & ~hot(T_next), T_rise.reshape(shape), T_next)      # runaway: where it got to
    result = jnp.where(fails > 0, _solve.INNER_FAILED,
                       jnp.where(hot(T_rise), RUNAWAY,
                                 jnp.where(change <= st.tol, _solve.SUCCESS, _solve.MAX_ITERATIONS)))
    return jnp.concatenate([x, T_rise.ravel()]), _solve.Stats(k, change, result)


def _linear_solver(st: _Static, shape):
    """Matrix-free solves of the coupled Jacobian: GMRES, preconditioned block by block with the
    film's Jacobian solve (its block solver, or a dense LU) and the energy operator's."""
    n_T = shape[0] * shape[1]

    def make(u, aux, params):
        x, T_rise = u[:-n_T], u[-n_T:].reshape(shape)
        pr, cfg = _film_params(T_rise, params, st)
        blocks, _, _ = _energy(x, T_rise, params, st, pr, cfg)
        diag = jnp.einsum("ijj->ij", blocks[1])
        if solved_by_linear_model(pr, cfg):
            film_solve, film_solve_t = linear_model(x, pr, cfg)
        else:
            lu = jax.scipy.linalg.lu_factor(jax.jacfwd(lambda y: equations(y, pr, cfg)[0])(x))
            film_solve = lambda b: jax.scipy.linalg.lu_solve(lu, b)            # noqa: E731
            film_solve_t = lambda b: jax.scipy.linalg.lu_solve(lu, b, trans=1)   # noqa: E731
        coupled = lambda v: _residual(v, params, st, shape)                      # noqa: E731

        def precond(fs, transposed):
            def apply(b):
                bx, bT = b[:-n_T], b[-n_T:].reshape(shape)
                if transposed:
                    tT = energy.cyclic_block_solve(blocks, bT, transposed=True) * diag
                else:
                    tT = energy.cyclic_block_solve(blocks, bT * diag)
                return jnp.concatenate([fs(bx), tT.ravel()])
            return apply

        def forward(b):
            _, mv = jax.linearize(coupled, u)
            return krylov.gmres(mv, b, precond(film_solve, False), GMRES_TOL, 400)[0]

        def transpose(b):
            _, vjp = jax.vjp(coupled, u)
            return krylov.gmres(lambda v: vjp(v)[0], b, precond(film_solve_t, True), GMRES_TOL, 400)[0]
        return forward, transpose
    return make


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
    st = _Static(options, float(supply_angle), float(supply_width), cavitation, float(load_angle), bool(v > 0),
                 housing is not None or shaft is not None, float(tol) if tol is not None else (1e-9 if eps < 1e-10
                                                                                              else 1e-3),
                 int(max_iter), float(relax))
    params = dict(R=R, c=radial_clearance, load=load, L=length, wJ=omega_shaft, wB=omega_housing, oil=lubricant,
                  heat=heat, housing=housing, shaft=shaft, shift=shift)
    shape = (options.n, options.m + 1)
    pr0, cfg0 = _film_params(jnp.zeros(shape), params, st)
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
    # else from the isothermal film at the supply temperature and a mean-rise estimate (_first_temperatures)
    at = dict(temperature=heat.T_supply, shift=shift) if st.deformable and shift is not None else {}
    cold = _steady.finite_journal_bearing(
        R, radial_clearance, lubricant.viscosity(heat.T_supply), load, length, housing=housing, shaft=shaft,
        omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle, cavitation=cavitation,
        supply_angle=supply_angle, supply_width=supply_width, options=options, throw=False, **at)
    x0 = jax.lax.stop_gradient(_finite_setup.start_from(cold, pr0, cfg0))
    T0 = jax.lax.stop_gradient(_first_temperatures(x0, params, st, shape))
    return _finish(x0, T0, params, st, shape, lubricant, heat, throw)


def _finish(x0, T0, params, st: _Static, shape, lubricant, heat, throw):
    """The rounds from (x0, T0), implicitly differentiated, and the result."""
    u, stats = _solve.implicit_root(lambda p: _solver(p, st, shape, x0, T0),
                                    lambda uu, aux, p: _residual(uu, p, st, shape),
                                    _linear_solver(st, shape))(params)
    out = _outputs(u, params, st, shape, stats, lubricant)
    _report(out, heat.T_limit, throw)
    return out


@xla.jit(static_argnums=(2, 3))
def _outputs(u, params, st: _Static, shape, stats, lubricant):
    heat = params["heat"]
    n_T = shape[0] * shape[1]
    x, T_rise = u[:-n_T], u[-n_T:].reshape(shape)
    pr, cfg = _film_params(T_rise, params, st)
    _, _, parts = _energy(x, T_rise, params, st, pr, cfg)
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
        temperature=T, max_temperature=jnp.max(T), mean_temperature=heat.T_supply + _area_mean(T_rise, params, st),
        groove_temperature=T[groove_line],
        outlet_temperature=heat.T_supply + jnp.sum(ends * T_ends) / jnp.maximum(jnp.sum(ends), jnp.finfo(T.dtype).tiny),
        body_temperature=heat.T_supply + _area_mean(T_rise, params, st), viscosity=pr.eta, power=power,
        power_film=jnp.sum(parts["Phi"]), power_bodies=parts["P_bodies"], heat_ends=heat_ends,
        heat_groove=heat_groove, heat_bush=heat_bush, heat_journal=heat_journal,
        side_leakage=scene.side_leakage,
        film_overheated=jnp.asarray(False) if lubricant.T_max is None else jnp.max(T) > lubricant.T_max,
        scene=scene, iterations=stats.iterations, residual=stats.residual, result=stats.result)


def _message(out_max, result, iterations, residual, T_limit):
    result = int(np.ravel(np.asarray(result))[0])
    if result == _solve.SUCCESS:
        return None
    if result == RUNAWAY:
        return (f"thermal_film_bearing: thermal runaway: the film's temperature passed T_limit = "
                f"{float(np.ravel(T_limit)[0]):.6g} C (reached {float(np.ravel(out_max)[0]):.6g} C after "
                f"{int(np.ravel(iterations)[0])} rounds): the heat generated outgrows the heat carried off; more "
                f"cooling (supply flow, a cooler supply, a conducting bush) or a higher FilmHeat.T_limit")
    return (f"thermal_film_bearing: {MESSAGES[result]} after {int(np.ravel(iterations)[0])} rounds, the last "
            f"change {float(np.ravel(residual)[0]):.3e} K (max temperature {float(np.ravel(out_max)[0]):.6g} C)")


def _report(out: FilmTemperatureResult, T_limit, throw):
    if not throw:
        return
    args = (out.max_temperature, out.result, out.iterations, out.residual, T_limit)

    def raise_(*a):
        message = _message(*a)
        if message is not None:
            raise _solve.ConvergenceError(message, out if checks.is_concrete(out.result) else None)

    if checks.is_concrete(args):
        raise_(*args)
    else:
        jax.lax.cond(out.result != _solve.SUCCESS, lambda a: jax.debug.callback(raise_, *a), lambda a: None, args)
