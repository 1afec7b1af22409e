"""The infinitely long journal bearing's steady solve: Newton from the rigid estimate or a
nested coarse-grid start, continuation in the bodies' compliance and the speed, JFO from the
Reynolds solution, implicit derivatives, and :func:`long_journal_bearing`."""
from __future__ import annotations

import dataclasses
import math
from functools import partial

import jax
import jax.numpy as jnp

from ...._core import checks, solve as _solve, xla
from .... import reference
from ....bodies.operator import RingOperator
from ....films import reynolds
from ..options import JournalOptions
from ..setup import roughness_hint
from . import film
from .outputs import JournalResult, outputs


NESTED_MIN_N = 128   # "auto" cold starts on n >= this many elements begin on a 4x coarser grid,
NESTED_MIN_N_RIGID = 512   # rigid ones from this many (direct: 19 steps at n = 256, 27 at 512, > 40 at 1024)


def _staged(pr: film.Params, t):
    """Problem at continuation parameter t in [0, 2].

    t in [0, 1]: compliance ramped in (factor t) at M times the entrainment speed, with M
    such that the rigid bearing runs at eps ~ 0.6 (thick film, mild coupling);
    t in [1, 2]: full compliance, speed M^(2 - t) (geometric) down to the target (the
    surfaces' speeds with it, which set a rough film's shear flow).
    """
    M = jnp.maximum(1.0, film.load_number(pr) / reference.half_sommerfeld_load(0.6))
    m = M ** jnp.clip(2.0 - t, 0.0, 1.0)
    s = jnp.clip(t, 0.0, 1.0)
    scale = lambda op: None if op is None else RingOperator(op.symbol * s, op.n)
    return dataclasses.replace(pr, v=pr.v * m, q_ref=pr.q_ref * m, omega_B=pr.omega_B * m, omega_J=pr.omega_J * m,
                               op_B=scale(pr.op_B), op_J=scale(pr.op_J)), m


def _continuation(pr, cfg, x0=None, subcell=True):
    """Adaptive continuation in t (see :func:`_staged`, :func:`vjax._core.solve.continuation`): at most
    ``stages`` Newton solves; with ``x0`` (``strategy="auto"``) a direct solve from it first;
    ``subcell`` as :func:`_solve_steady`."""
    guess = film.guess(_staged(pr, 0.0)[0], cfg.options.n, cfg)
    # the intermediate stages are only starts: their rupture on a face will do
    solve = lambda x, t: film.newton(x, _staged(pr, t)[0], cfg, subcell=subcell & (t >= 2.0))     # noqa: E731
    return _solve.continuation(solve, guess, x0, cfg.options.stages)


def _jfo_start(x, pr: film.Params, cfg: film.Config):
    """JFO unknowns from a Reynolds solution x: its pressure where positive; in the cavity the
    film fraction that carries the flow leaving the pressurized film (the flux at the
    pressure peak) as a Couette flow, f = Q / (v h) (rough surfaces: Q over their Couette flux),
    as the universal variable f - 1."""
    n = cfg.options.n
    f = film.fields(x, pr, dataclasses.replace(cfg, cavitation="reynolds"))
    flow = f["q"][jnp.argmax(f["p"])]
    fraction = jnp.clip(flow / reynolds.couette_flux(f["h"], pr.v, pr.rough, film.sliding(pr)), 0.0, 1.0)
    cavity = f["p"] <= 1e-9 * jnp.max(f["p"])
    return x.at[:n].set(jnp.where(cavity, fraction - 1.0, x[:n]))


def _solver(pr: film.Params, cfg: film.Config):
    """Steady solution; "jfo" starts from the Reynolds solution (the same pressure where the
    film re-forms only at the groove), whose cavity it fills with the mass-conserving film."""
    if cfg.cavitation != "jfo":
        return _solve_steady(pr, cfg)
    n = cfg.options.n
    start = dataclasses.replace(pr, x0=pr.x0.at[:n].max(0.0))
    xr, (st_r, stages) = _solve_steady(start, dataclasses.replace(cfg, cavitation="reynolds"), subcell=False)
    x0 = _jfo_start(xr, pr, cfg)
    # Newton on the exact switch from the Reynolds start. Where the film re-forms before the
    # groove, that start can be far from the JFO solution and the semismooth Newton stall on
    # the switch's kinks: then follow the smoothed switch p = (u + sqrt(u^2 + mu^2))/2 from
    # x0 through mu = reynolds.JFO_SMOOTHING down to mu = 0.
    x, st = _solve.homotopy(lambda x, mu: film.newton(x, pr, cfg, mu), x0,
                            (0.0,) + reynolds.JFO_SMOOTHING + (0.0,))
    result = jnp.where(st_r.converged, st.result, st_r.result)
    return x, (_solve.Stats(st_r.iterations + st.iterations, st.residual, result), stages)


def _solve_steady(pr: film.Params, cfg: film.Config, subcell=True):
    """Steady solution: Newton, or continuation (compliant bodies, rough surfaces: a mixed film
    far from the estimate's); ``subcell`` False leaves a Reynolds rupture on a cell face (a start
    for JFO, :func:`vjax.scenes.journal.long.film.newton`)."""
    compliant = pr.op_B is not None or pr.op_J is not None
    x0 = jax.lax.stop_gradient(pr.x0)
    strategy = cfg.options.strategy if compliant or pr.rough is not None else "newton"
    if strategy == "newton":
        x, stats = film.newton(x0, pr, cfg, subcell=subcell)
        stages = jnp.asarray(0)
    else:
        x, stats, stages = _continuation(pr, cfg, x0 if strategy == "auto" else None, subcell)
    # the residual of the target problem at the returned point (after a failed
    # continuation x belongs to an intermediate stage)
    r = jnp.max(jnp.abs(film.equations(x, pr, cfg, subcell=jnp.where(subcell, 1.0, 0.0))[0]))
    residual = jnp.where(jnp.isfinite(r), r, jnp.inf)
    result = jnp.where(stats.converged & ~(residual <= cfg.tol), _solve.MAX_ITERATIONS, stats.result)
    return x, (_solve.Stats(stats.iterations, residual, result), stages)


@xla.jit(static_argnums=(1,))
def _run(pr: film.Params, cfg: film.Config):
    residual = lambda x, aux, prm: film.equations(x, prm, cfg)[0]
    linear_solver = None
    if cfg.options.krylov:
        def linear_solver(x, aux, prm):
            solve, solve_t, matvec, matvec_t = film.linear_model(x, prm, cfg)
            return film.gmres(matvec, solve), film.gmres(matvec_t, solve_t)
    x, (stats, stages) = _solve.implicit_root(lambda prm: _solver(prm, cfg), residual, linear_solver)(pr)
    return outputs(x, pr, cfg, stats, stages)


def long_journal_bearing(R, radial_clearance, viscosity, load, *, housing=None, shaft=None, omega_shaft=0.0,
                         omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic", cavitation: str = "reynolds",
                         supply_angle=math.pi, supply_pressure=0.0, groove: str | None = None, temperature=None,
                         shift=None, initial: JournalResult | None = None,
                         options: JournalOptions = JournalOptions(), throw: bool = True,
                         nested: bool = True, roughness=None) -> JournalResult:
    """Steady state of an infinitely long (visco)elastic journal bearing: :func:`vjax.journal_bearing`
    without ``length`` (its arguments; :mod:`vjax.scenes.journal.long` for the equations).
    ``roughness``: a :class:`~vjax.Roughness` for mixed lubrication, None for smooth surfaces.
    ``nested``: whether a cold start on a fine grid may begin on the 4x coarser one (one level:
    the coarse solve itself starts cold, so that one more program is compiled, not one per level)."""
    groove = "line_of_centres" if groove is None else groove
    checks.instance("options", options, JournalOptions, "a vjax.JournalOptions")
    pr, cfg, housing, shaft = film.setup(
        R, radial_clearance, viscosity, load, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
        omega_housing=omega_housing, load_angle=load_angle, memory=memory, cavitation=cavitation,
        supply_angle=supply_angle, supply_pressure=supply_pressure, temperature=temperature, shift=shift,
        options=options, groove=groove, roughness=roughness)
    n, p_ref, dtype = options.n, pr.p_ref, pr.x0.dtype
    implicit = film.asperity_unknowns(pr, cfg) > 0
    if initial is not None:
        if not isinstance(initial, JournalResult) or any(a.shape != (n,) for a in (initial.pressure,
                                                                                   initial.film_fraction)):
            raise ValueError(f"initial must be a JournalResult of the same bearing (n = {n})")
        x0 = film.start(initial.pressure, initial.film_fraction, initial.eccentricity, initial.attitude_angle, p_ref,
                        initial.asperity_pressure if implicit else None)
    elif nested and options.strategy == "auto" and n % 4 == 0 and n >= (
            NESTED_MIN_N if housing is not None or shaft is not None else NESTED_MIN_N_RIGID):
        # Nested start: solve on a 4x coarser grid, interpolate. Most Newton steps from a
        # cold start are spent far from the solution, where a coarse grid is as good and
        # (n/4)^3 cheaper. If the coarse start misleads, "auto" still falls back.
        coarse = long_journal_bearing(
            R, radial_clearance, viscosity, load, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
            omega_housing=omega_housing, load_angle=load_angle, memory=memory, cavitation=cavitation,
            supply_angle=supply_angle, supply_pressure=supply_pressure, groove=groove,
            options=dataclasses.replace(options, n=n // 4), throw=False, nested=False, roughness=roughness)
        x0 = film.start(_refine_periodic(coarse.pressure, n), 1.0, coarse.eccentricity, coarse.attitude_angle, p_ref,
                        _refine_periodic(coarse.asperity_pressure, n) if implicit else None)
    else:
        x0 = film.guess(pr, n, cfg)
    sol = _run(dataclasses.replace(pr, x0=jax.lax.stop_gradient(x0).astype(dtype)), cfg)
    # the hint only for a failure it can explain (concrete values; its eager operations
    # would otherwise compile on every first call)
    failed = throw and checks.is_concrete(sol.result) and int(sol.result) != _solve.SUCCESS and roughness is None
    _solve.report("journal_bearing" + (_failure_hint(pr, n) if failed else ""), sol, throw,
                  hint=_roughness_hint(pr) if failed else "")
    return sol


@partial(jax.jit, static_argnums=1)
def _refine_periodic(values, n):
    """Periodic Catmull-Rom (C1 cubic) interpolation of values on a ring grid onto n points,
    clipped at 0. Not linear: a piecewise-linear pressure puts all its curvature on the
    coarse nodes, so every fourth cell of the fine grid starts with an O(1) mass imbalance and
    Newton spends tens of steps (growing with n) undoing it near the rupture."""
    m = values.shape[0]
    t = jnp.arange(n) * (m / n)
    i = jnp.floor(t).astype(int)
    u = t - i
    a, b, c, d = (values[(i + k) % m] for k in (-1, 0, 1, 2))
    p = b + 0.5 * u * ((c - a) + u * ((2 * a - 5 * b + 4 * c - d) + u * (3 * (b - c) + d - a)))
    return jnp.maximum(p, 0.0)


def _roughness_hint(pr: film.Params) -> str:
    """A closing sentence for a rigid smooth bearing's failure where its film would be far
    thinner than the clearance: rough surfaces would let the asperities carry the load."""
    if pr.op_B is not None or pr.op_J is not None or not checks.is_concrete((pr.c, pr.W, pr.eta, pr.v)):
        return ""
    # the rigid half-Sommerfeld film that carries this load: G ~ 1 / (3 (1 - eps)) for eps -> 1
    thin = 1.0 / (3.0 * float(film.load_number(pr)))
    if thin >= 0.01:
        return ""
    return roughness_hint(thin)


def _failure_hint(pr: film.Params, n: int) -> str:
    """A note for the failure message when the bodies make the problem one this solver is not
    built for: their deformation under the load dwarfs the clearance (mode 2, the first that
    changes the film's shape, of the mean pressure W/(2R)), or the load far exceeds the rigid
    film's capacity, so that the bodies carry it through an elastohydrodynamic film far
    thinner than the clearance, whose inlet and exit the grid does not resolve."""
    ops = [op for op in (pr.op_B, pr.op_J) if op is not None]
    if not ops or not checks.is_concrete((pr.c, pr.p_ref, pr.W, pr.eta, pr.v, *[op.symbol for op in ops])):
        return ""
    ratio = float(sum(abs(complex(op.symbol[2])) for op in ops) * pr.p_ref / pr.c)
    if ratio >= 30:      # continuation has been seen to converge up to ~20
        return (f" (the bodies' compliance deforms the film's shape by ~{ratio:.0f} clearances under this load: a "
                f"soft conformal contact, beyond this Newton solver's reach and, past strains of a few percent, "
                f"beyond linear viscoelasticity; stiffer bodies, a larger clearance or a smaller load)")
    # rigid half-Sommerfeld film at this load: G ~ 1 / (3 (1 - eps)) for eps -> 1
    G = float(film.load_number(pr))
    thin = 1.0 / (3.0 * G)
    cause = (f" (the load is {G:.2g} times the rigid film's capacity scale: a rigid bearing would run at a film of "
             f"~{thin:.1e} c, so the bodies carry the load through an elastohydrodynamic film far thinner than "
             f"their deformation")
    # thesis HS bore slowed down: converged at 7e-5 c (n = 256) and 7e-6 c (n = 2048), failed at
    # 7e-6 c (n = 256) and 7e-7 c (n = 256 ... 32768)
    if thin < 3e-6:
        return cause + ("; films this thin are beyond this solver on any grid (seen to fail up to n = 32768): "
                        "a higher speed, a larger viscosity or a smaller load)")
    if n * thin < 0.01:
        return cause + (f", whose inlet and exit {n} elements do not resolve: about {0.02 / thin:.0e} elements, or "
                        f"a higher speed, a larger viscosity or a smaller load)")
    return ""
