"""The finite journal bearing's steady solve: Newton with its fallbacks (half-Sommerfeld
restart, the sub-cell rupture stage, continuation in the bodies' compliance and the speed,
JFO from the Reynolds solution), nested starts from a coarser grid, implicit derivatives,
and :func:`finite_journal_bearing`."""
from __future__ import annotations

import dataclasses
import math
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from ...._core import checks, solve as _solve, xla
from .... import reference
from ....bodies.operator import grid
from ....films import film2d, reynolds
from ..options import FiniteJournalOptions
from ..setup import roughness_hint
from .film import (Config, Params, as_unknowns, asperity_unknowns, equations, fields, is_rigid, linear_model, own_nodes,
                   own_columns,
                   solved_by_linear_model, unknowns)
from .outputs import FiniteJournalResult, outputs
from .setup import setup, start_from


# Newton gives up when its residual has not halved in this many steps: caught on the
# rupture line's kinks it would otherwise creep for all of max_iter (a lined bearing on 64 x 16:
# 60 steps at a residual of 0.29) before the half-Sommerfeld restart or the continuation
STALL_WINDOW = 12


def _newton(x0, pr: Params, cfg: Config, relaxed=False, subcell=1.0):
    """The core's Newton; each step by the block solve for rigid bodies; with deformable ones,
    whose compliance couples every cell of an axial slice, by GMRES (``cfg.krylov``,
    :func:`linear_model`; with rough surfaces over the asperity unknowns too) or a dense LU of
    the Jacobian from jacfwd (n (m - 1) + 2 unknowns, and n (m + 1) asperity ones: up to a few
    thousand)."""
    def eqs(x, state):
        r, film_margin = equations(x, pr, cfg, relaxed, subcell)
        return r, state, film_margin > 0

    N = unknowns(cfg)
    cap = jnp.concatenate([jnp.full(N, jnp.inf), jnp.full(2, 0.3), jnp.full(x0.shape[0] - N - 2, jnp.inf)])
    cap = cap.astype(x0.dtype)
    linear_solve = (lambda x, state, r: linear_model(x, pr, cfg, relaxed, subcell)[0](-r)) \
        if solved_by_linear_model(pr, cfg) else None
    x, _, stats = _solve.newton(eqs, x0, None, tol=cfg.tol, max_iter=cfg.max_iter, max_step=cap,
                                linear_solve=linear_solve, stall_window=STALL_WINDOW)
    return x, stats


def _rigid_capacity(eps, pr: Params, parts=False):
    """The rigid bearing's load capacity (N) at eccentricity ratio eps, estimated as the short
    (Ocvirk) and the long half-Sommerfeld capacities in series, 1/W = 1/W_short + 1/W_long (with
    ``parts``: the two)."""
    v, c, R, L, eta = jnp.abs(pr.v), pr.c, pr.R, pr.L, jnp.mean(pr.eta)     # a viscosity field: its mean
    Ws = eta * 2 * v * L**3 / c**2 * eps * jnp.sqrt(16 * eps**2 + jnp.pi**2 * (1 - eps**2)) / (4 * (1 - eps**2) ** 2)
    Wl = 12 * eta * v * R**2 * L / c**2 * reference.half_sommerfeld_load(eps)
    return (Ws, Wl) if parts else Ws * Wl / (Ws + Wl)


def _guess(pr: Params, cfg: Config):
    """Rigid estimate of the unknowns: the eccentricity whose load, the short (Ocvirk) and the
    long half-Sommerfeld capacities combined in series (1/W = 1/W_short + 1/W_long), equals
    the load, at their correspondingly weighted attitude angle; the long bearing's pressure
    along theta times a parabola across the width, scaled to carry the load. With deformable
    bodies the journal moves with their rigid displacement under the load (the slices' first
    mode, :func:`deformations`), so that the film keeps the rigid estimate's shape. With rough
    surfaces the asperities' capacity adds to the film's (:func:`_asperity_capacity`): at low
    speed they carry the load at an eccentricity past 1, along the line of centres."""
    c, R, L, eta = pr.c, pr.R, pr.L, jnp.mean(pr.eta)
    if pr.rough is None:
        eps = _solve.bisect(lambda e: _rigid_capacity(e, pr) - pr.W, jnp.asarray(1e-6, c.dtype),
                            jnp.asarray(0.999, c.dtype), 50)
        share = jnp.zeros((), c.dtype)
    else:
        total = lambda e: _rigid_capacity(jnp.minimum(e, 0.999), pr) + _asperity_capacity(e, pr, cfg)  # noqa: E731
        eps = _solve.bisect(lambda e: total(e) - pr.W, jnp.asarray(1e-6, c.dtype), jnp.asarray(1.5, c.dtype), 60)
        share = jnp.clip(_asperity_capacity(eps, pr, cfg) / pr.W, 0.0, 1.0)
    centre = jnp.where(share > 0.5, eps, jnp.minimum(eps, 0.95))     # where the journal is put
    eps = jnp.minimum(eps, 0.95)                                       # the film's shape
    Ws, Wl = _rigid_capacity(eps, pr, parts=True)
    short = jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 4 * eps)
    long = jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 2 * eps)
    # the asperities' force lies along the line of centres: their share turns the attitude to 0
    phi = (1 - share) * jnp.sign(pr.v) * (Wl * short + Ws * long) / (Ws + Wl)
    # the load direction in the grid, and the film's minimum at phi ahead of it (behind for v < 0)
    a = jnp.arctan2(pr.load[1], pr.load[0]) + phi
    # the journal: c eps e^{i a} plus the bodies' rigid displacement under the load's first
    # mode (amplitude |symbol_1| W / (pi R L), along the film's minimum)
    s1 = pr.compliance * sum(op.plane_symbol[1] for op in (pr.op_B, pr.op_J) if op is not None)
    moved = c * centre + s1 * pr.W / (jnp.pi * R * L)
    position = jnp.abs(moved) / c * jnp.exp(1j * (a - jnp.angle(moved)))
    n = cfg.n
    theta, _ = grid(n)
    z = 0.5 * L * pr.s[1:-1]
    t = theta - a
    p = (-12 * eta * pr.v * R * eps * jnp.sin(t) * (2 - eps * jnp.cos(t))
         / (c**2 * (2 + eps**2) * (1 - eps * jnp.cos(t)) ** 2))
    p = jnp.maximum(p, 0.0)[:, None] * (1 - (2 * z / L) ** 2)[None, :]
    F, _ = film2d.resultants(film2d.with_ends(p), theta, 0.5 * L * pr.s, R)
    p = p * (1 - share) * pr.W / jnp.maximum(jnp.hypot(F[0], F[1]), jnp.finfo(c.dtype).tiny) / pr.p_ref
    # a small positive offset: with p = 0 exactly, the FB Newton step grows the pressurized
    # zone by one cell per iteration
    p = jnp.where(pr.groove[:, 1:-1] > 0, pr.ps / pr.p_ref, p + 0.1)
    x = jnp.concatenate([own_columns(p, cfg).ravel(), jnp.stack([position.real, position.imag])])
    if asperity_unknowns(pr, cfg):      # the asperities at the rigid film of that position
        rigid = film2d.film(theta, 0.5 * L * pr.s, c, c * x[-2:], pr.tilt)
        x = jnp.concatenate([x, own_nodes(pr.rough.asperity_pressure(rigid), cfg).ravel() / pr.p_ref])
    return x


def _asperity_capacity(eps, pr: Params, cfg: Config):
    """The load (N) the asperities of an aligned rigid journal carry at eccentricity ratio eps
    (any, > 1 where the nominal film closes): R dtheta L sum p_a(c (1 - eps cos theta)) cos theta."""
    theta, _ = grid(cfg.n)
    p_a = pr.rough.asperity_pressure(pr.c * (1 - eps * jnp.cos(theta)))
    return pr.R * pr.L * (2 * jnp.pi / cfg.n) * jnp.sum(p_a * jnp.cos(theta))


CONTINUATION_STAGES = 40   # at most this many Newton solves in the continuation of soft bodies


def _staged(pr: Params, t):
    """The problem at continuation parameter t in [0, 2] (as the long bearing's): t in [0, 1] the
    bodies' compliance ramped in (factor t) at M times the entrainment speed, M such that the
    rigid bearing would run at eps ~ 0.6 (a thick film, a mild coupling); t in [1, 2] the full
    compliance, the speed M^(2 - t) down to the target's (geometric; the surfaces' speeds with
    it, which set a rough film's shear flow)."""
    M = jnp.maximum(1.0, pr.W / _rigid_capacity(0.6, pr))
    m = M ** jnp.clip(2.0 - t, 0.0, 1.0)
    return dataclasses.replace(pr, v=pr.v * m, omega_B=pr.omega_B * m, omega_J=pr.omega_J * m,
                               compliance=jnp.clip(t, 0.0, 1.0).astype(pr.v.dtype))


def _steady(pr: Params, cfg: Config):
    """The steady unknowns and the Newton record: :func:`_film_steady` from ``pr.x0``; with
    deformable bodies or rough surfaces, if that fails (a soft body far from the rigid estimate,
    a load the rigid film could carry only at a far higher speed, a mixed film far from the
    estimate's), adaptive continuation in the compliance and the speed (:func:`_staged`,
    :func:`vjax._core.solve.continuation`), the first stage from the rigid estimate: one Newton
    in one loop (compiled once), the stage parameter traced."""
    if is_rigid(pr) and pr.rough is None:
        return _film_steady(pr, cfg)
    # the intermediate stages are only starts: their rupture on a face will do
    solve = lambda x, t: _film_steady(dataclasses.replace(_staged(pr, t), x0=x), cfg, t >= 2.0)     # noqa: E731
    guess = jax.lax.stop_gradient(_guess(_staged(pr, 0.0), cfg))
    x, st, _ = _solve.continuation(solve, guess, jax.lax.stop_gradient(pr.x0), CONTINUATION_STAGES)
    return x, st


def _jfo_start(x, pr: Params, cfg: Config):
    """JFO unknowns from a Reynolds solution x: its pressure where positive; in the cavity of
    each axial line the film fraction that carries, as a Couette flow, the flow leaving that
    line's pressurized film at its pressure peak, f = Q / (v h), as the universal variable f - 1."""
    N = unknowns(cfg)
    f = fields(x, pr, dataclasses.replace(cfg, cavitation="reynolds"))
    p, qx = f["p"][:, 1:-1], f["qx"][:, 1:-1]
    peak = jnp.argmax(p, axis=0)
    flow = jnp.take_along_axis(qx, peak[None, :], axis=0)
    fraction = jnp.clip(flow / (pr.v * f["h"][:, 1:-1]), 0.0, 1.0)
    cavity = p <= 1e-9 * jnp.max(p)
    return x.at[:N].set(own_columns(jnp.where(cavity, fraction - 1.0, p / pr.p_ref), cfg).ravel())


def _jfo_steady(pr: Params, cfg: Config):
    """Mass-conserving cavitation: the Reynolds solution (the same pressure where the film
    re-forms only at the groove) with its cavity filled by :func:`_jfo_start`, then Newton on
    the exact switch; if that fails (the semismooth Newton can stall on the switch's kinks
    far from the root), the smoothed switch from that start through mu =
    reynolds.JFO_SMOOTHING down to 0 (a turn ending NONFINITE keeps its start). One Newton in
    one loop, mu traced: compiled once (the Reynolds stage apart)."""
    N = unknowns(cfg)
    start = dataclasses.replace(pr, x0=pr.x0.at[:N].max(0.0))
    xr, st_r = _film_steady(start, dataclasses.replace(cfg, cavitation="reynolds"), subcell=False)
    x0 = _jfo_start(xr, pr, cfg)
    x, st = _solve.homotopy(lambda x, mu: _newton(x, dataclasses.replace(pr, smoothing=mu), cfg), x0,
                            (0.0,) + reynolds.JFO_SMOOTHING + (0.0,))
    result = jnp.where(st_r.converged, st.result, st_r.result)
    return x, _solve.Stats(st_r.iterations + st.iterations, st.residual, result)


def _film_steady(pr: Params, cfg: Config, subcell=True):
    """Newton from ``pr.x0``; under Reynolds conditions, if that fails (the semismooth Newton can
    stall on the complementarity's kinks far from the root), again from the half-Sommerfeld
    solution (a linear film for a given position: a few steps), its pressure clipped at 0 and
    raised by 0.1 p_ref; these with the rupture on a cell face, then a last Newton from there
    with the rupture within its cell (a few steps; from a cold start the sub-cell rupture's
    square root makes Newton creep); ``subcell`` (a traced bool) False stops before that last
    Newton: a start for another solve (a continuation's intermediate stage, JFO's Reynolds
    start) needs no more. The stages run through one Newton (compiled once), the relaxation and
    the sub-cell rupture traced switches."""
    x0 = jax.lax.stop_gradient(pr.x0)
    if cfg.cavitation == "jfo":
        return _jfo_steady(pr, cfg)
    if cfg.cavitation != "reynolds":
        return _newton(x0, pr, cfg)
    N = unknowns(cfg)
    held = own_columns(pr.groove[:, 1:-1], cfg).ravel() > 0
    # stages: 0 from x0, 1 half-Sommerfeld from x0 (if 0 failed), 2 from its solution, 3 the
    # rupture within its cell (after 0 or 2 converged), 4 done
    after = jnp.array([[1, 3], [4, 2], [4, 3], [4, 4]])     # [stage, converged] -> next stage
    after = jnp.where(subcell, after, jnp.where(after == 3, 4, after))

    def body(c):
        k, x, its, _ = c
        relaxed = k == 1
        x1, st = _newton(jnp.where(relaxed, x0, x), pr, cfg, relaxed, (k == 3).astype(x0.dtype))
        # after the half-Sommerfeld stage: its pressure, clipped and raised, starts Reynolds
        start = x1.at[:N].set(jnp.where(held, x1[:N], jnp.maximum(x1[:N], 0.0) + 0.1))
        return after[k, st.converged.astype(int)], jnp.where(relaxed, start, x1), its + st.iterations, st

    init = _solve.Stats(jnp.asarray(0), jnp.asarray(jnp.inf, x0.dtype), jnp.asarray(_solve.MAX_ITERATIONS))
    # a warm start (a solution nearby) goes straight to stage 3
    warm = jnp.max(jnp.abs(equations(x0, pr, cfg)[0])) < reynolds.WARM_RESIDUAL
    k, x, its, st = jax.lax.while_loop(lambda c: c[0] < 4, body,
                                       (jnp.where(warm & subcell, 3, 0), x0, jnp.asarray(0), init))
    # a failed stage ends the solve with its own code
    return x, _solve.Stats(its, st.residual, st.result)


def solve(pr: Params, cfg: Config, start: str = "given") -> tuple[jax.Array, _solve.Stats]:
    """The converged unknowns x (implicitly differentiable) and the Newton record; ``start``:
    "given" (Newton from ``pr.x0``), "guess" (from the rigid estimate, :func:`_guess`),
    "given_or_guess" (``pr.x0`` unless it is not finite: a coarse grid's failed solve) or
    "polish" (one Newton from ``pr.x0``, under Reynolds conditions with the sub-cell rupture on, no
    fallback: a start near the root, a coarser grid's solution or a thermal round's last film)."""
    if start in ("guess", "given_or_guess"):
        guess = jax.lax.stop_gradient(_guess(pr, cfg))
        x0 = guess if start == "guess" else jnp.where(jnp.all(jnp.isfinite(pr.x0)), pr.x0, guess)
        pr = dataclasses.replace(pr, x0=x0)
    steady = ((lambda prm: _newton(jax.lax.stop_gradient(prm.x0), prm, cfg, subcell=1.0)) if start == "polish"
              else (lambda prm: _steady(prm, cfg)))
    block = (lambda x, aux, prm: linear_model(x, prm, cfg)) if solved_by_linear_model(pr, cfg) else None
    return _solve.implicit_root(steady, lambda x, aux, prm: equations(x, prm, cfg)[0], block)(pr)


def _solved(pr: Params, cfg: Config):
    """The steady solve from ``pr.x0``, or from the rigid estimate where x0 is not finite (a cold
    start is x0 = NaN): one program for a sweep's cold first point and its warm ones."""
    x, stats = solve(pr, cfg, "given_or_guess")
    return outputs(x, pr, cfg, stats)


def _polished(pr: Params, cfg: Config):
    """The steady solve from a start near the root under Reynolds conditions (a coarser grid's
    solution, :func:`refined`): the last stage of :func:`_film_steady` alone, Newton with the
    rupture within its cell; a program about a third smaller than :func:`_solved`'s, whose
    other stages such a start does not need (:func:`finite_journal_bearing` falls back to them
    if it fails)."""
    x, stats = solve(pr, cfg, "polish")
    return outputs(x, pr, cfg, stats)


_run = xla.jit(_solved, static_argnums=(1,))
_run_polish = xla.jit(_polished, static_argnums=(1,))
# a nested solve's coarse start (:func:`nests`): a small grid, solved once, so its program is
# compiled for speed of compiling (:data:`vjax._core.xla.START`), apart from the same grid's own
_run_start = xla.jit(_solved, static_argnums=(1,), options=xla.START)


NESTED_MIN_CELLS = 2048    # cold solves on n m >= this many cells start from a coarser grid's solution


def coarse_options(options: FiniteJournalOptions) -> FiniteJournalOptions:
    """The grid a cold solve on a nesting grid (:func:`nests`) starts from: halved until it no
    longer nests (256 x 64 -> 64 x 16), so that one coarse program is compiled, not one per
    level (each is a whole Newton; its size hardly depends on the grid)."""
    while nests(options):
        options = dataclasses.replace(options, n=options.n // 2, m=options.m // 2)
    return options


def nests(options: FiniteJournalOptions) -> bool:
    """Whether a cold solve on this grid starts on a coarser one (:func:`coarse_options`; its
    nodes every 2nd, 4th, ... node of this one in theta and z, uniform or cosine spacing): on fine grids the rigid
    estimate is far from the root in Newton's terms (a 96 x 32 grid at eps = 0.8, L/D = 1:
    74 steps without converging directly, 9 on 48 x 16)."""
    return (options.nested and options.n * options.m >= NESTED_MIN_CELLS and options.n % 4 == 0
            and options.m % 4 == 0)


@partial(jax.jit, static_argnums=(2,))
def refined(coarse: FiniteJournalResult, pr: Params, cfg: Config):
    """Unknowns on this grid from a solution on a 2^j x coarser one (the coarse nodes every
    2^j-th node here): at each doubling the new nodes get the mean of their two neighbours, in
    theta, then in z; NaN where the coarse solve failed (then the rigid estimate starts,
    :func:`solve`)."""
    u = coarse.pressure / pr.p_ref + (coarse.film_fraction - 1.0)      # "jfo": the universal unknown
    x0 = as_unknowns(finer(u, cfg.n), coarse.position, pr, cfg, finer(coarse.asperity_pressure, cfg.n))
    return jax.lax.stop_gradient(jnp.where(coarse.converged, x0, jnp.nan)).astype(pr.x0.dtype)


def finer(u, n: int):
    """Node values (n_c, m_c + 1) of a 2^j x coarser grid on this grid's n lines: :func:`doubled`
    until they have n."""
    while u.shape[0] < n:
        u = doubled(u)
    return u


def doubled(u):
    """Values on the nodes of the 2x finer grid (n, m + 1) -> (2 n, 2 m + 1): the new nodes the
    mean of their two neighbours, in theta, then in z."""
    u = jnp.stack([u, 0.5 * (u + jnp.roll(u, -1, axis=0))], axis=1).reshape(-1, u.shape[1])
    mid = 0.5 * (u[:, :-1] + u[:, 1:])
    return jnp.concatenate([jnp.stack([u[:, :-1], mid], axis=2).reshape(u.shape[0], -1), u[:, -1:]], axis=1)


def finite_journal_bearing(R, radial_clearance, viscosity, load, length, *, housing=None, shaft=None,
                           omega_shaft=0.0, omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic",
                           cavitation="reynolds", supply_angle=math.pi, supply_pressure=0.0, supply_width=1.0,
                           tilt=None, temperature=None, shift=None, groove="fixed", roughness=None,
                           initial: FiniteJournalResult | None = None,
                           options: FiniteJournalOptions = FiniteJournalOptions(),
                           throw: bool = True) -> FiniteJournalResult:
    """Steady state of a finite journal bearing of axial ``length`` L (m) under ``load`` (N,
    total). Called by :func:`vjax.journal_bearing` with ``length=``; the arguments are its own
    (module docstring), plus ``supply_width`` (fraction of L the axial groove spans, centred;
    default 1) and ``tilt`` (gamma_x, gamma_y) (rad, absolute axes; the journal centre at axial
    position z is displaced by z gamma). ``housing`` and ``shaft`` (None: rigid) deform as
    plane-strain slices (:func:`deformations`). ``groove``: "fixed" (the axial groove at
    ``supply_angle``; a feed hole is one with ``supply_width`` = its diameter over L) or
    "circumferential" (round the mid-width, at ``supply_pressure``; ``supply_angle`` unused).
    ``roughness``: a :class:`~vjax.Roughness` for mixed lubrication (rigid or deformable bodies),
    None for smooth surfaces. Returns :class:`FiniteJournalResult`."""
    arguments = dict(housing=housing, shaft=shaft, omega_shaft=omega_shaft, omega_housing=omega_housing,
                     load_angle=load_angle, memory=memory, cavitation=cavitation, supply_angle=supply_angle,
                     supply_pressure=supply_pressure, supply_width=supply_width, tilt=tilt, temperature=temperature,
                     shift=shift, groove=groove, roughness=roughness)
    pr, cfg = _prepared(R, radial_clearance, viscosity, load, length, arguments, options)
    n, m = options.n, options.m
    if initial is not None:
        if not isinstance(initial, FiniteJournalResult) or initial.pressure.shape != (n, m + 1):
            raise ValueError(f"initial must be a FiniteJournalResult of the same grid (n = {n}, m = {m})")
        pr = dataclasses.replace(pr, x0=start_from(initial, pr, cfg))
    elif nests(options):
        coarse = _run_start(*_prepared(R, radial_clearance, viscosity, load, length, arguments,
                                       coarse_options(options)))
        pr = dataclasses.replace(pr, x0=refined(coarse, pr, cfg))
        # from the coarse solution Newton alone will do, in a smaller program (less to compile);
        # not inside a transformation (the fallback's choice needs concrete values), under JFO,
        # or where the coarse solve failed (then the rigid estimate starts, :func:`_run`)
        if cfg.cavitation == "reynolds" and checks.is_concrete(pr) and bool(coarse.converged):
            sol = _run_polish(pr, cfg)
            if bool(sol.converged):
                return sol
    sol = _run(pr, cfg)
    # the hint only for a failure it can explain (concrete values)
    failed = throw and checks.is_concrete(sol.result) and int(sol.result) != _solve.SUCCESS
    _solve.report("journal_bearing (finite length)", sol, throw, hint=_thin_film_hint(sol, pr) if failed else "")
    return sol


def _prepared(R, radial_clearance, viscosity, load, length, arguments, options):
    """The finite bearing's parameters and configuration (:func:`setup`), from the rigid estimate
    (x0 = NaN, :func:`_run`)."""
    pr, cfg = setup(R, radial_clearance, viscosity, load, length, options=options, **arguments)
    # an aligned bearing's pressure is symmetric about mid-width (the grooves, the bodies and the
    # axial nodes are): the steady solve keeps the unknowns from mid-width to one end
    cfg = dataclasses.replace(cfg, half=arguments["tilt"] is None)
    x0 = jnp.full(unknowns(cfg) + 2 + asperity_unknowns(pr, cfg), jnp.nan, pr.x0.dtype)
    return dataclasses.replace(pr, x0=x0), cfg


def _thin_film_hint(sol: FiniteJournalResult, pr: Params) -> str:
    """A closing sentence for a smooth bearing's failure where its film nearly closes: rough
    surfaces would let the asperities carry the load (mixed lubrication)."""
    if pr.rough is not None or not checks.is_concrete((pr.W, pr.v, pr.eta, pr.c)):
        return ""
    # the film the rigid estimate needs to carry the load: 1 - eps where its capacity is W
    gaps = np.logspace(-6, 0, 121)
    capacity = np.asarray(_rigid_capacity(jnp.asarray(1 - gaps[:-1], pr.c.dtype), pr))
    short = capacity < float(pr.W)
    thin = gaps[np.argmax(short)]
    if not short.any() or thin >= 0.05:
        return ""
    return roughness_hint(thin)
