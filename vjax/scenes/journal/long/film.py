"""The infinitely long journal bearing's equations: parameters, the film and the bodies'
deformation on the ring grid, the cell balances with the load balance, the rigid start, and
Newton on them (dense or matrix-free). :mod:`vjax.scenes.journal.long` solves them for the steady state
(its module docstring states the equations and conventions), :mod:`vjax.scenes.journal.dynamics`
linearizes them for the dynamic coefficients."""
from __future__ import annotations

import dataclasses
import math
from functools import partial

import jax
import jax.numpy as jnp

from ...._core import checks, krylov as _krylov, scene as _scene, solve as _solve
from .... import reference
from ....bodies.operator import RingOperator, grid
from ....films import banded, reynolds
from ....films.roughness import Roughness
from ..options import JournalOptions
from ..setup import bodies_at, check_arguments


GROOVES = ("line_of_centres", "fixed")
KRYLOV_TOL = 1e-9    # relative residual of each Newton step's GMRES solve


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Params:
    """Differentiable parameters (SI); the operators are None for rigid bodies."""

    R: jax.Array
    RJ: jax.Array
    c: jax.Array
    eta: jax.Array
    v: jax.Array                 # entrainment speed (m/s)
    W: jax.Array                 # load magnitude (N/m)
    load_angle: jax.Array
    ps: jax.Array                # groove pressure (Pa)
    groove: jax.Array            # grid index of the groove's cell (int; traced: a groove moved compiles nothing)
    omega_B: jax.Array
    omega_J: jax.Array
    p_ref: jax.Array
    q_ref: jax.Array
    op_B: RingOperator | None
    op_J: RingOperator | None
    rough: Roughness | None      # the surfaces' roughness (mixed lubrication); None: smooth
    x0: jax.Array                # starting point: travels with the parameters, not differentiated


@dataclasses.dataclass(frozen=True)
class Config:
    cavitation: str
    options: JournalOptions
    tol: float
    fixed_groove: bool = False     # grid on the load line (groove fixed in the bearing)


def offset(x, cfg: Config):
    """Angle of the line of centres on the grid: 0 on the line-of-centres grid, the
    attitude angle on the load-line grid of a fixed groove."""
    return x[cfg.options.n + 1] if cfg.fixed_groove else jnp.zeros((), x.dtype)


def asperity_unknowns(pr: Params, cfg: Config) -> int:
    """How many asperity-pressure unknowns follow (eps, attitude): one per cell, n, when rough
    surfaces meet a deformable body (the asperity pressure loads the body, whose deformation
    sets the gap the asperities see: an implicit pair, solved with the film, as in the finite
    film); none otherwise (rigid bodies: the asperity pressure follows the film explicitly)."""
    return cfg.options.n if pr.rough is not None and (pr.op_B is not None or pr.op_J is not None) else 0


def sliding(pr: Params):
    """U_journal - U_bore (m/s): the surfaces' relative speed (Vr's sign: the journal's roughness
    counts positive)."""
    return pr.omega_J * pr.RJ - pr.omega_B * pr.R


def film_capacity(eps, pr: Params):
    """The rigid half-Sommerfeld film's load capacity (N/m) at eccentricity ratio eps < 1."""
    return 12 * pr.eta * jnp.abs(pr.v) * pr.R**2 / pr.c**2 * reference.half_sommerfeld_load(eps)


def asperity_capacity(eps, pr: Params, n: int):
    """The load (N/m) the asperities of a rigid journal carry at eccentricity ratio eps (any,
    > 1 where the nominal film closes): R dtheta sum p_a(c (1 - eps cos theta)) cos theta."""
    theta, _ = grid(n)
    p_a = pr.rough.asperity_pressure(pr.c * (1 - eps * jnp.cos(theta)))
    return pr.R * (2 * jnp.pi / n) * jnp.sum(p_a * jnp.cos(theta))


def load_number(pr: Params):
    """G = |W| c^2 / (12 eta |v| R^2): the load over the rigid film's capacity scale (the rigid
    half-Sommerfeld bearing runs at the eccentricity with this load number)."""
    return pr.W * pr.c**2 / (12 * pr.eta * jnp.abs(pr.v) * pr.R**2)


def gmres(matvec, precond):
    """b -> the GMRES solution of one Newton (or derivative) system, preconditioned."""
    return lambda b: _krylov.gmres(matvec, b, precond, KRYLOV_TOL, 200)[0]


@partial(jax.jit, static_argnums=(1, 2))
def guess(pr: Params, n, cfg: Config):
    """Rigid half-Sommerfeld estimate of the unknowns [p/p_ref, eps, attitude], the journal
    moved with the bodies' rigid displacement under the load. With rough surfaces the
    asperities' capacity adds to the film's (:func:`asperity_capacity`): at low speed they
    carry the load at an eccentricity past 1, along the line of centres; and the asperity
    unknowns (:func:`asperity_unknowns`) start at the rigid film of that position."""
    v = pr.v
    if pr.rough is None:
        eps = jnp.minimum(reference.half_sommerfeld_eccentricity(load_number(pr)), 0.95)
        share, centre = jnp.zeros((), pr.c.dtype), eps
    else:
        total = lambda e: film_capacity(jnp.minimum(e, 0.999), pr) + asperity_capacity(e, pr, n)  # noqa: E731
        eps = _solve.bisect(lambda e: total(e) - pr.W, jnp.asarray(1e-6, pr.c.dtype), jnp.asarray(1.5, pr.c.dtype),
                            60)
        share = jnp.clip(asperity_capacity(eps, pr, n) / pr.W, 0.0, 1.0)
        centre = jnp.where(share > 0.5, eps, jnp.minimum(eps, 0.95))     # where the journal is put
        eps = jnp.minimum(eps, 0.95)                                       # the film's shape
    # the asperities' force lies along the line of centres: their share turns the attitude to 0
    phi = (1 - share) * jnp.sign(v) * jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 2 * eps)
    # The load's mode-1 pressure moves the bodies rigidly by D (complex, m): place the journal
    # so that the film keeps the rigid estimate's shape and its angle to the load,
    # c eps e^{i beta} = c eps_r + D e^{i phi_r} = z (beta: angle of the film's minimum from
    # the line of centres), and let the pressure follow the film.
    s1 = sum(op.symbol[1] for op in (pr.op_B, pr.op_J) if op is not None)
    z = pr.c * centre + s1 * pr.W / (pr.R * jnp.pi) * jnp.exp(1j * phi)
    film_line = phi if cfg.fixed_groove else jnp.angle(z)      # grid angle of the film's minimum
    theta = grid(n)[0] - film_line
    p = (-12 * pr.eta * v * pr.R * eps * jnp.sin(theta) * (2 - eps * jnp.cos(theta))
         / (pr.c**2 * (2 + eps**2) * (1 - eps * jnp.cos(theta)) ** 2))
    if pr.rough is not None:     # the film's share of the load, not the capacity at the clipped eps
        p = p * jnp.minimum(1.0, (1 - share) * pr.W / film_capacity(eps, pr))
    position = jnp.stack([jnp.abs(z) / pr.c, phi - jnp.angle(z)])
    # A small positive offset everywhere: with p = 0 exactly in the future cavity, the FB
    # Newton step can only grow the pressurized zone by one cell per iteration.
    p = jnp.maximum(p, 0.0) / pr.p_ref + 0.1
    x = jnp.concatenate([p, position])
    if asperity_unknowns(pr, cfg):
        rigid = pr.c * (1 - position[0] * jnp.cos(grid(n)[0] - offset(x, cfg)))
        x = jnp.concatenate([x, pr.rough.asperity_pressure(rigid) / pr.p_ref])
    return x


def fields(x, pr: Params, cfg: Config, smoothing=0.0, deformation=None):
    """Pressure, film, displacements and face fluxes for unknowns x (``smoothing``: of the
    "jfo" switch, see :func:`vjax.scenes.journal.long.steady._solver`; ``deformation``: u_B + u_J given instead of computed,
    for the Newton preconditioner). With rough surfaces (``pr.rough``) the fluxes are Patir and
    Cheng's average flow and ``p_asp`` (Pa) the asperities' Greenwood-Tripp pressure, which
    loads the bodies with the film's (zero for smooth surfaces); ``couette`` the faces' Couette
    flux of a full film (m^2/s)."""
    n = cfg.options.n
    theta, alpha = grid(n)
    pz, fraction = reynolds.pressure_and_fraction(x[:n], cfg.cavitation, smoothing)
    p = pz * pr.p_ref
    p_load = reynolds.load_pressure(p, cfg.cavitation)
    implicit = asperity_unknowns(pr, cfg) > 0       # the asperity pressure an unknown (x's tail)
    p_unknown = x[n + 2:] * pr.p_ref if implicit else None
    # Mode 1 of the loading pressure is the film force, which equals the load at equilibrium:
    # take it from the load (it moves the bodies rigidly, by up to hundreds of clearances for a
    # soft bore) so that Newton does not have to find it - the same root, a far milder system.
    zero = jnp.zeros_like(p)
    if deformation is not None:
        uB, uJ = deformation, zero
    else:
        P = jnp.fft.rfft(p_load if p_unknown is None else p_load + p_unknown)
        P = P.at[1].set(pr.W * jnp.exp(-1j * (offset(x, cfg) - x[n + 1])) / (pr.R * 2 * alpha))
        deform = lambda op: jnp.fft.irfft(op.symbol * P, n)
        uB = zero if pr.op_B is None else deform(pr.op_B)
        uJ = zero if pr.op_J is None else deform(pr.op_J)
    h = pr.c * (1 - x[n] * jnp.cos(theta - offset(x, cfg))) + uB + uJ
    hf, dpds, q = reynolds.face_fluxes(p, h, pr.R, pr.eta, pr.v, fraction if cfg.cavitation == "jfo" else None,
                                       pr.rough, sliding(pr))
    gap_pressure = jnp.zeros_like(h) if pr.rough is None else pr.rough.asperity_pressure(h)
    return dict(theta=theta, dth=2 * alpha, p=p, p_load=p_load, uB=uB, uJ=uJ, h=h, hf=hf, dpds=dpds, q=q,
                fraction=fraction, couette=reynolds.couette_flux(hf, pr.v, pr.rough, sliding(pr)),
                p_asp=gap_pressure if p_unknown is None else p_unknown,
                # the asperity unknowns' equations: the pressure the gap gives, over p_ref
                asperity_residual=None if p_unknown is None else (p_unknown - gap_pressure) / pr.p_ref)


def equations(x, pr: Params, cfg: Config, smoothing=0.0, deformation=None, subcell=1.0):
    """Cell balances (with cavitation), the groove datum and the load balance (film and
    asperities); followed by the asperity unknowns' equations when there are some
    (:func:`asperity_unknowns`); and the film's margin (:func:`margin`). ``subcell``: 1 locates a
    Reynolds rupture within its cell, 0 on a face (:func:`newton`'s first stage)."""
    n = cfg.options.n
    f = fields(x, pr, cfg, smoothing, deformation)
    r = reynolds.cell_equations(x[:n], f["q"], balance_scale(f, pr), cfg.cavitation, couette=f["couette"],
                                v=pr.v, subcell=subcell)
    r = r.at[pr.groove].set(x[pr.groove] - pr.ps / pr.p_ref)
    carried = f["p_load"] + f["p_asp"]
    Fx = -pr.R * f["dth"] * jnp.sum(carried * jnp.cos(f["theta"]))
    Fy = -pr.R * f["dth"] * jnp.sum(carried * jnp.sin(f["theta"]))
    # the film balances the load, which points along the grid angle offset - attitude
    a = offset(x, cfg) - x[n + 1]
    bal = jnp.stack([Fx / pr.W + jnp.cos(a), Fy / pr.W + jnp.sin(a)])
    r = jnp.concatenate([r, bal])
    if f["asperity_residual"] is not None:
        r = jnp.concatenate([r, f["asperity_residual"]])
    return r, margin(f["h"], pr)


def balance_scale(f, pr: Params):
    """The flow (m^2/s) the cell balances are scaled by: q_ref for smooth surfaces; for rough ones
    each cell's own, p_ref times the conductance of its two faces over a cell (per radian), as
    the finite film's. Where the asperities touch, the local conductance phi_x h_c^3 is ~(sigma /
    c)^3 of the clearance's: scaled by q_ref, those cells' balances would be ~1e-6 of their
    pressures in the Fischer-Burmeister pair, and Newton crawls there."""
    if pr.rough is None:
        return pr.q_ref
    k = reynolds.conductance_gap(f["hf"], pr.rough) / (12 * pr.eta)
    dth = f["dth"]
    return pr.p_ref * (k + jnp.roll(k, 1)) / (pr.R * dth * dth)


def margin(h, pr: Params):
    """The film's margin (m), positive where the model holds: min h for smooth surfaces; the
    clearance for rough ones, whose model holds for any nominal film (a closed one is an
    asperity layer compressed beyond its mean planes, carrying the load)."""
    return jnp.min(h) if pr.rough is None else pr.c


def effective_eps(h, c, offset=0.0):
    """First Fourier mode of the film over c along the line of centres (at grid angle ``offset``)."""
    theta, _ = grid(h.shape[0])
    a1 = 2.0 / h.shape[0] * jnp.sum(h * jnp.cos(theta - offset))
    b1 = 2.0 / h.shape[0] * jnp.sum(h * jnp.sin(theta - offset))
    return -jnp.sign(a1) * jnp.sqrt(a1**2 + b1**2) / c


def newton(x0, pr, cfg, smoothing=0.0, subcell=True):
    """The core's Newton on the equations (films must stay positive): x, Stats (with the
    physical branch folded into the result). Under Reynolds conditions in two stages: the
    rupture on a face, then within its cell from there (a few steps; from a cold start the
    sub-cell rupture's square root makes Newton creep). ``subcell`` (a traced bool) False stops
    after the first stage: a start for another solve (a continuation's intermediate stage,
    JFO's Reynolds start) needs no more."""
    n = cfg.options.n
    # a trust cap on the two geometric unknowns (eps, attitude)
    cap = jnp.concatenate([jnp.full(n, jnp.inf), jnp.full(2, 0.3), jnp.full(x0.shape[0] - n - 2, jnp.inf)])
    cap = cap.astype(x0.dtype)

    def stage(x, subcell):
        def fn(x, state):
            r, hmin = equations(x, pr, cfg, smoothing, subcell=subcell)
            return r, state, hmin > 0

        linear_solve = None
        if cfg.options.krylov:
            def linear_solve(x, state, r):
                solve, _, matvec, _ = linear_model(x, pr, cfg, smoothing, subcell)
                return gmres(matvec, solve)(-r)
        x, _, stats = _solve.newton(fn, x, None, tol=cfg.tol, max_iter=cfg.options.max_iter, max_step=cap,
                                    linear_solve=linear_solve)
        return x, stats

    if cfg.cavitation == "reynolds":
        # a warm start (a solution nearby) goes straight to the second stage
        warm = jnp.max(jnp.abs(equations(x0, pr, cfg, smoothing)[0])) < reynolds.WARM_RESIDUAL
        second = jnp.where(subcell, 1.0, 0.0)     # without the sub-cell stage: the first again, a no-op
        x, stats = _solve.in_turn(stage, x0, jnp.stack([jnp.where(warm, second, 0.0), second]).astype(x0.dtype))
    else:
        x, stats = stage(x0, 1.0)
    physical = effective_eps(fields(x, pr, cfg)["h"], pr.c, offset(x, cfg)) > 0
    result = jnp.where((stats.result == _solve.SUCCESS) & ~physical, _solve.NONPHYSICAL, stats.result)
    return x, _solve.Stats(stats.iterations, stats.residual, result)


def linear_model(x, pr: Params, cfg: Config, smoothing=0.0, subcell=1.0):
    """The Newton system at x, matrix-free: ``(solve, solve_transpose, matvec, matvec_transpose)``,
    the solves those of a preconditioner M ~ J, O(n k) per application.

    J = A + G K D in the cell rows, plus the rows and columns of (eps, attitude): A and G the
    derivatives of the cell equations with respect to the pressure (the film held) and to the
    deformation (cyclic tridiagonal: a cell sees its neighbours' faces), K the bodies'
    compliance (circulant), D the derivative of the loading pressure (diagonal). M keeps K on
    its lowest ``krylov_modes`` Fourier modes, which carry most of a body's compliance
    (|K_k| ~ 1/k), so M = tridiagonal + rank k and is solved by Woodbury (:mod:`vjax.films.banded`).
    For rigid bodies M = J exactly: GMRES converges in one step."""
    n = cfg.options.n
    N, dtype = n + 2, x.dtype
    f = fields(x, pr, cfg, smoothing)
    deformation = f["uB"] + f["uJ"]
    cells = lambda u, U: equations(jnp.concatenate([u, x[n:]]), pr, cfg, smoothing, U, subcell)[0][:n]
    lower, diag, upper = banded.cyclic_diagonals(lambda u: cells(u, deformation), x[:n])
    full = lambda y: equations(y, pr, cfg, smoothing, subcell=subcell)[0]
    _, matvec = jax.linearize(full, x)
    _, vjp = jax.vjp(full, x)
    unit = jnp.eye(N, dtype=dtype)
    J_cols = jax.vmap(matvec)(unit[n:]).T                    # (N, 2): d/d(eps, attitude)
    J_rows = jax.vmap(lambda c: vjp(c)[0])(unit[n:])[:, :n]    # (2, n): force rows d/dp
    pad = lambda a: jnp.concatenate([a, jnp.zeros((2,) + a.shape[1:], dtype)])
    # the ring's corners, and the border of the two geometric unknowns (diagonal 1 in T)
    U = [pad(jnp.stack([lower[0] * unit[0, :n], upper[-1] * unit[n - 1, :n]], axis=1)),
         J_cols - unit[:, n:], unit[:, n:]]
    V = [pad(jnp.stack([unit[n - 1, :n], unit[0, :n]], axis=1)), unit[:, n:],
         jnp.concatenate([J_rows.T, jnp.zeros((2, 2), dtype)])]
    ops = [op for op in (pr.op_B, pr.op_J) if op is not None]
    if ops:
        G = banded.cyclic_diagonals(lambda U_: cells(x[:n], U_), deformation)
        load = lambda u: reynolds.load_pressure(reynolds.pressure_and_fraction(u, cfg.cavitation, smoothing)[0]
                                                * pr.p_ref, cfg.cavitation)
        D = jax.jvp(load, (x[:n],), (jnp.ones(n, dtype),))[1]
        m = min(cfg.options.krylov_modes, n // 2 - 1)
        theta, _ = grid(n)
        k = jnp.arange(2, m + 1)                                  # mode 1 comes from the load
        basis = jnp.concatenate([jnp.ones((n, 1), dtype), jnp.cos(theta[:, None] * k), jnp.sin(theta[:, None] * k)],
                                axis=1)
        weight = jnp.concatenate([jnp.full(1, 1.0 / n), jnp.full(2 * (m - 1), 2.0 / n)]).astype(dtype)
        symbol = sum(op.symbol for op in ops).at[1].set(0.0)
        K_basis = jnp.fft.irfft(symbol[:, None] * jnp.fft.rfft(basis, axis=0), n, axis=0)
        U.append(pad(banded.cyclic_matvec(G, K_basis * weight)))
        V.append(pad(D[:, None] * basis))
    zeros2 = jnp.zeros(2, dtype)
    tri = (jnp.concatenate([lower, zeros2]), jnp.concatenate([diag, jnp.ones(2, dtype)]),
           jnp.concatenate([upper.at[-1].set(0.0), zeros2]))
    solve, solve_transpose = banded.woodbury(tri, jnp.concatenate(U, axis=1), jnp.concatenate(V, axis=1))
    return solve, solve_transpose, matvec, lambda v: vjp(v)[0]


def setup(R, radial_clearance, viscosity, load, *, housing, shaft, omega_shaft, omega_housing, load_angle, memory,
          cavitation, supply_angle, supply_pressure, temperature, shift, options: JournalOptions,
          groove="line_of_centres", roughness: Roughness | None = None):
    """Checked arguments of :func:`vjax.journal_bearing` (``options`` a checked
    :class:`~vjax.JournalOptions`) -> (parameters with a zero start, config, housing body,
    shaft body) - the bodies at ``temperature``, None when rigid; ``roughness`` a
    :class:`~vjax.Roughness` (mixed lubrication) or None (smooth surfaces)."""
    check_arguments(R, radial_clearance, viscosity, load, omega_shaft=omega_shaft, omega_housing=omega_housing,
                    load_angle=load_angle, memory=memory, cavitation=cavitation, supply_pressure=supply_pressure)
    checks.one_of("groove", groove, GROOVES)
    if supply_angle is None:
        raise ValueError("supply_angle: the infinitely long bearing's film has a groove (its ambient datum): give "
                         "its angle (rad); a film without a groove is the finite bearing's (give length=)")
    _scene.scalars(checks.finite, supply_angle=supply_angle)
    sa = checks.values("supply_angle", supply_angle)
    if sa is None:
        raise ValueError("supply_angle must be a concrete number (it selects a grid element)")
    housing, shaft = bodies_at(R, radial_clearance, housing, shaft, temperature, shift)
    rigid = housing is None and shaft is None
    if roughness is not None:
        checks.instance("roughness", roughness, Roughness, "a vjax.Roughness (or None: smooth surfaces)")
        if cavitation == "jfo":
            raise ValueError("cavitation='jfo': the infinitely long bearing's mixed film (roughness=) is solved with "
                             "'reynolds', 'half_sommerfeld' or 'sommerfeld' conditions; its mass-conserving cavity "
                             "does not converge where the asperities carry the load")
        if not rigid and options.linear_solver == "krylov":
            raise ValueError("linear_solver='krylov': rough surfaces on a deformable body are solved with a dense "
                             "LU (the asperity pressure an unknown per cell); use 'auto' or 'dense'")
    n = options.n
    dtype = jnp.result_type(float)
    floor = 4 * float(jnp.finfo(jnp.float64).eps) * (n / (2 * math.pi)) ** 2
    tol = options.tol if options.tol is not None else (max(1e-10, floor) if dtype == jnp.float64 else 1e-4)
    # The compiled solver's static key: options that do not change the program take their
    # defaults (a dense solve ignores krylov_modes, rigid bodies the continuation's strategy
    # and stages, the tolerance is cfg.tol), so calls differing only in those share it.
    # rough surfaces on a deformable body: dense ("auto" too), the asperity unknowns couple every cell
    krylov, default = options.krylov and (rigid or roughness is None), type(options)()
    key = dataclasses.replace(options, tol=None, linear_solver="krylov" if krylov else "dense",
                              krylov_modes=options.krylov_modes if krylov else default.krylov_modes,
                              strategy=default.strategy if rigid else options.strategy,
                              stages=default.stages if rigid else options.stages)
    cfg = Config(cavitation, key, float(tol), groove == "fixed")

    groove_cell = int(round(float(sa) % (2 * math.pi) / (2 * math.pi / n))) % n
    pr = params(*_scene.canonical(R, radial_clearance, viscosity, load, load_angle, omega_housing, omega_shaft,
                                  supply_pressure), groove_cell, housing, shaft, roughness, n=n, memory=memory)
    return pr, cfg, housing, shaft


@partial(jax.jit, static_argnames=("n", "memory"))
def params(R, radial_clearance, viscosity, load, load_angle, omega_housing, omega_shaft, supply_pressure, groove,
           housing, shaft, roughness=None, *, n, memory):
    """Checked arguments -> :class:`Params` with a zero start, in one compiled program (built
    eagerly, its few dozen scalar and grid operations would each compile on a first call,
    together about as long as the solver itself)."""
    dtype = jnp.result_type(float)
    f = lambda v: jnp.asarray(v, dtype)
    load = f(load)
    Wx, Wy = (load * jnp.cos(load_angle), load * jnp.sin(load_angle)) if load.ndim == 0 else (load[0], load[1])
    W = jnp.hypot(Wx, Wy)
    eta, c = f(viscosity), f(radial_clearance)
    v = 0.5 * (omega_housing * R + omega_shaft * (R - radial_clearance))
    p_ref = W / (2 * R)
    return Params(R=f(R), RJ=f(R - radial_clearance), c=c, eta=eta, v=f(v), W=W, load_angle=jnp.arctan2(Wy, Wx),
                  ps=f(supply_pressure), groove=jnp.asarray(groove), omega_B=f(omega_housing), omega_J=f(omega_shaft),
                  p_ref=p_ref, q_ref=c**3 * p_ref / (12 * eta * R) + jnp.abs(v) * c,
                  op_B=None if housing is None else housing.operator(R, n, -omega_housing, memory),
                  op_J=None if shaft is None else shaft.operator(R - radial_clearance, n, omega=-omega_shaft,
                                                                 memory=memory),
                  rough=roughness, x0=jnp.zeros(n + 2, dtype))


@jax.jit
def start(pressure, film_fraction, eccentricity, attitude_angle, p_ref, asperity=None):
    """Unknowns from a solution: p / p_ref plus, in a "jfo" cavity, film fraction - 1 (the
    universal variable), then eps and the attitude angle, then (the unknowns of rough surfaces
    on a deformable body, :func:`asperity_unknowns`) the ``asperity`` pressure / p_ref."""
    x = jnp.concatenate([pressure / p_ref + (film_fraction - 1.0), jnp.stack([eccentricity, attitude_angle])])
    return x if asperity is None else jnp.concatenate([x, asperity / p_ref])
