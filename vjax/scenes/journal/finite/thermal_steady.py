"""The finite bearing's thermal film, its solve (internal; :mod:`.thermal`, docs/theory.md §19.2).

The coupled equations (:func:`coupled_residual`: the film's cell equations and force balance
at the viscosity of each node's temperature, and the energy equation of
:mod:`vjax.films.energy` over the land); their solve by rounds, T -> eta(T) -> the film's
steady state -> the energy equation -> T, mixed by Anderson's method (:func:`rounds`, from
:func:`first_temperatures`); and the matrix-free solves of their Jacobian for the implicit
derivatives (:func:`linear_solver`).
"""
from __future__ import annotations

import dataclasses
import math

import jax
import jax.numpy as jnp

from ...._core import checks, krylov, scene as _scene, solve as _solve, xla
from ....films import energy, film2d
from ....films.shear import striated_fraction
from ..options import FiniteJournalOptions
from . import setup as _finite_setup, steady as _steady
from .film import equations, fields, linear_model, solved_by_linear_model

GMRES_TOL = 1e-13
FULL = 1e-3          # a node with p below FULL p_max is partly cavitated (:func:`energy_equation`)
ANDERSON = 5         # rounds in Anderson's mixing
MAX_FAILS = 6        # failed films in a row before the solve gives up


@dataclasses.dataclass(frozen=True)
class Static:
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


def moves(housing, shaft, shift) -> bool:
    """Whether the bodies follow the film's temperature: their materials carry shift laws (or
    the 0.2 ``shift=`` gives them one)."""
    return shift is not None or _scene.responds(housing) or _scene.responds(shaft)


def film_params(T_rise, params, st: Static):
    """The finite bearing's parameters with the viscosity at each node's temperature and the
    bodies at the mean, and its configuration."""
    heat, oil = params["heat"], params["oil"]
    T = heat.T_supply + T_rise
    body = {}
    if st.deformable and moves(params["housing"], params["shaft"], params["shift"]):
        body = dict(temperature=heat.T_supply + area_mean(T_rise, params, st), shift=params["shift"])
    pr, cfg = _finite_setup.setup(params["R"], params["c"], oil.viscosity(heat.T_supply), params["load"], params["L"],
                                  housing=params["housing"], shaft=params["shaft"], omega_shaft=params["wJ"],
                                  omega_housing=params["wB"], load_angle=st.load_angle, cavitation=st.cavitation,
                                  supply_angle=st.supply_angle, supply_width=st.supply_width, options=st.options,
                                  **body)
    cfg = dataclasses.replace(cfg, half=True)
    return dataclasses.replace(pr, eta=oil.viscosity(T)), cfg


def area_mean(T_rise, params, st: Static):
    """The land's area-weighted mean of ``T_rise`` (n, m + 1) (K)."""
    wz = film2d.node_widths(0.5 * params["L"] * film2d.unit_nodes(st.options.m, st.options.spacing))
    return jnp.sum(T_rise @ wz) / (T_rise.shape[0] * jnp.sum(wz))


def energy_equation(x, T_rise, params, st: Static, pr, cfg):
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


def coupled_residual(u, params, st: Static, shape):
    """The coupled equations at u = (the film's unknowns, the temperature rise): the film's cell
    equations and force balance, and the energy equation over its diagonal (K)."""
    n_T = shape[0] * shape[1]
    x, T_rise = u[:-n_T], u[-n_T:].reshape(shape)
    pr, cfg = film_params(T_rise, params, st)
    blocks, rhs, _ = energy_equation(x, T_rise, params, st, pr, cfg)
    scale = jnp.einsum("ijj->ij", blocks[1])
    r_T = (energy.matvec(blocks, T_rise) - rhs) / scale
    return jnp.concatenate([equations(x, pr, cfg)[0], r_T.ravel()])


def _round(carry, params, st: Static, shape):
    """One round: the film at the viscosity of T, then G(T), the temperature the energy equation
    gives at that film; the next T by Anderson's mixing of the last ANDERSON rounds (Walker and
    Ni 2011; the plain relaxed step T + relax (G - T) while the history is empty). G's slope is
    about -1 in the film's mean temperature (a hotter film thins and shears less), which plain
    substitution would follow in a slow oscillation. Where the film's Newton fails at a T (a
    mixing step too bold), the round goes back halfway to the last T whose film converged and
    restarts the history."""
    x_good, T_rise, _, k, fails, (dT, dF, T_prev, F_prev) = carry
    pr, cfg = film_params(T_rise, params, st)
    x, stats = _steady.solve(dataclasses.replace(pr, x0=x_good), cfg, "polish")
    blocks, rhs, _ = energy_equation(x, T_rise, params, st, pr, cfg)
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
def first_temperatures(x0, params, st: Static, shape):
    """The rounds' start: the energy equation's field G0 at the cold film (x0, the supply
    temperature's viscosity), scaled to the mean rise r that a film whose dissipation followed
    its viscosity, flows held, would have: r = mean(G0) eta(T_s + r) / eta(T_s) (bisection).
    Near the answer, so that the first rounds' films move little (each cell the cavity moves
    costs the film's Newton a step)."""
    zero = jnp.zeros(shape, x0.dtype)
    pr, cfg = film_params(zero, params, st)
    blocks, rhs, _ = energy_equation(x0, zero, params, st, pr, cfg)
    G0 = energy.cyclic_block_solve(blocks, rhs)
    mean0 = jnp.maximum(area_mean(G0, params, st), 0.0)
    oil, T_s = params["oil"], params["heat"].T_supply
    r = _solve.bisect(lambda r: r - mean0 * oil.viscosity(T_s + r) / oil.viscosity(T_s), jnp.zeros_like(mean0),
                      mean0, 60, sign_lo=-1.0)
    return jnp.where(mean0 > 0, G0 * r / jnp.where(mean0 > 0, mean0, 1.0), zero)


def rounds(params, st: Static, shape, x0, T0):
    """Rounds (:func:`_round`) from x0 (the film at the supply temperature) and T' = T0
    (:func:`first_temperatures`), under a trace in a while_loop, else in Python over one
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
                       jnp.where(hot(T_rise), _solve.RUNAWAY,
                                 jnp.where(change <= st.tol, _solve.SUCCESS, _solve.MAX_ITERATIONS)))
    return jnp.concatenate([x, T_rise.ravel()]), _solve.Stats(k, change, result)


def linear_solver(st: Static, shape):
    """Matrix-free solves of the coupled Jacobian: GMRES, preconditioned block by block with the
    film's Jacobian solve (its block solver, or a dense LU) and the energy operator's."""
    n_T = shape[0] * shape[1]

    def make(u, aux, params):
        x, T_rise = u[:-n_T], u[-n_T:].reshape(shape)
        pr, cfg = film_params(T_rise, params, st)
        blocks, _, _ = energy_equation(x, T_rise, params, st, pr, cfg)
        diag = jnp.einsum("ijj->ij", blocks[1])
        if solved_by_linear_model(pr, cfg):
            film_solve, film_solve_t = linear_model(x, pr, cfg)
        else:
            lu = jax.scipy.linalg.lu_factor(jax.jacfwd(lambda y: equations(y, pr, cfg)[0])(x))
            film_solve = lambda b: jax.scipy.linalg.lu_solve(lu, b)            # noqa: E731
            film_solve_t = lambda b: jax.scipy.linalg.lu_solve(lu, b, trans=1)   # noqa: E731
        coupled = lambda v: coupled_residual(v, params, st, shape)                # noqa: E731

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
