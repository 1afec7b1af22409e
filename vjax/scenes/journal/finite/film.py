"""The finite journal bearing's equations: parameters, the unknowns' layout over the land,
the film and the bodies' deformation on the (theta, z) grid, the cell balances with the force
balance, and the Newton system's linear model (block solve, multigrid, GMRES).
:mod:`vjax.scenes.journal.finite` states the equations and conventions."""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp

from ...._core import krylov as _krylov
from ....bodies.land import LandOperator
from ....bodies.operator import RingOperator, grid
from ....films import blocks, film2d, multigrid, reynolds

from ....films.roughness import Roughness

KRYLOV_TOL = 1e-9         # relative residual of each GMRES solve (Newton steps and derivatives)
KRYLOV_MAX_ITER = 300     # GMRES steps per solve (restarted every 20)
EXACT_WIDTH = 32          # Newton's preconditioner: the exact block solve up to this many unknown cells across the
                          # width (O(n m^3)), a multigrid V-cycle above (O(n m), :mod:`vjax.films.multigrid`)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Params:
    """Differentiable parameters of the finite bearing (SI; grid axes: x along ``frame``)."""

    R: jax.Array
    RJ: jax.Array
    c: jax.Array
    L: jax.Array
    eta: jax.Array               # viscosity (Pa s): a number, or a node field (n, m + 1) (a film's temperature field)
    v: jax.Array                 # entrainment speed (m/s)
    W: jax.Array                 # load magnitude (N)
    load: jax.Array              # (2,) load on the journal, grid axes (N)
    frame: jax.Array             # absolute angle of the grid's x axis (the load's at setup; not differentiated)
    tilt: jax.Array              # (2,) grid axes (rad)
    ps: jax.Array                # groove pressure (Pa)
    omega_B: jax.Array
    omega_J: jax.Array
    p_ref: jax.Array             # W / (2 R L)
    groove: jax.Array            # (n, m + 1) 0/1 mask of the groove's nodes (the end ones at ambient pressure)
    circumferential: jax.Array   # 1: the groove runs round the mid-width (its inlet flow is axial), else 0
    s: jax.Array                 # (m + 1,) axial nodes over L/2, -1 ... 1 (the spacing; not differentiated)
    op_B: RingOperator | LandOperator | None   # each axial slice's ring operator (plane strain), or a
    op_J: RingOperator | LandOperator | None   # 3D layer's land operator; None: rigid
    compliance: jax.Array        # the bodies' compliance scaled by this (1; less in the solver's continuation)
    smoothing: jax.Array         # mu of the "jfo" switch (0: exact; more in the solver's homotopy)
    rough: Roughness | None      # the surfaces' roughness (mixed lubrication); None: smooth
    x0: jax.Array                # Newton's start (travels with the parameters, not differentiated)


@dataclasses.dataclass(frozen=True)
class Config:
    """Static configuration: cavitation model, grid size, Newton's tolerance and step cap, and
    whether deformable bodies' linear solves are GMRES (the axial spacing is a parameter,
    ``Params.s``: uniform and cosine grids share one compile)."""

    cavitation: str
    n: int
    m: int
    tol: float
    max_iter: int
    krylov: bool = False
    half: bool = False    # the steady solve of an aligned bearing: unknowns from mid-width to one end


def unknowns(cfg: Config):
    return cfg.n * columns(cfg)


def asperity_unknowns(pr: Params, cfg: Config) -> int:
    """How many asperity-pressure unknowns follow the position: one per node, n (m + 1) (a
    half-width solve's: from mid-width to one end, :func:`node_columns`), when rough surfaces
    meet a deformable body (the asperity pressure loads the body, whose deformation sets the
    gap the asperities see: an implicit pair, solved with the film); none otherwise (rigid
    bodies: the asperity pressure follows the film explicitly)."""
    return cfg.n * node_columns(cfg) if pr.rough is not None and not is_rigid(pr) else 0


def node_columns(cfg: Config):
    """Axial columns of the node unknowns (the asperity pressure): all m + 1 nodes; in a
    half-width solve the m / 2 + 1 from mid-width to the end."""
    return cfg.m // 2 + 1 if cfg.half else cfg.m + 1


def all_nodes(a, cfg: Config):
    """Node values (n, m + 1) from the node unknowns' columns (n, :func:`node_columns`):
    a half-width solve's mirrored about mid-width."""
    return jnp.concatenate([a[:, :0:-1], a], axis=1) if cfg.half else a


def own_nodes(a, cfg: Config):
    """The node unknowns' columns of a node array (n, m + 1)."""
    return a[:, cfg.m // 2:] if cfg.half else a


def columns(cfg: Config):
    """Axial columns of the cell unknowns: the m - 1 interior nodes; in a half-width solve
    (``cfg.half``) the m / 2 from mid-width to the last interior one."""
    return cfg.m // 2 if cfg.half else cfg.m - 1


def interior(u, cfg: Config):
    """The flat cell unknowns (n columns) as values (n, m - 1) at every interior node: a
    half-width solve's mirrored about mid-width (an aligned bearing's pressure is symmetric)."""
    u = u.reshape(cfg.n, columns(cfg))
    return jnp.concatenate([u[:, :0:-1], u], axis=1) if cfg.half else u


def own_columns(a, cfg: Config):
    """The unknowns' columns (n, columns) of an array over the interior nodes (n, m - 1)."""
    return a[:, cfg.m // 2 - 1:] if cfg.half else a


def rotation(frame):
    """The 2 x 2 rotation from grid axes to absolute ones (the grid's x axis at ``frame``)."""
    c, s = jnp.cos(frame), jnp.sin(frame)
    return jnp.array([[c, -s], [s, c]])


def as_unknowns(scaled, position, pr: Params, cfg: Config, asperity=None):
    """Unknowns [scaled pressure (the universal unknown for "jfo") at the interior nodes (those
    of the unknowns, :func:`columns`), journal centre / c in grid axes, and the asperity
    pressure / p_ref if it is an unknown (:func:`asperity_unknowns`)] from ``scaled`` (n, m + 1),
    an absolute ``position`` (m) and the ``asperity`` pressure (n, m + 1) (Pa)."""
    x = jnp.concatenate([own_columns(scaled[:, 1:-1], cfg).ravel(), rotation(pr.frame).T @ position / pr.c])
    if asperity_unknowns(pr, cfg):
        x = jnp.concatenate([x, own_nodes(asperity, cfg).ravel() / pr.p_ref])
    return x


def fields(x, pr: Params, cfg: Config, motion=None, relaxed=False, deformation=None):
    """Grid, pressure (all nodes, Pa), film and fluxes for the unknowns x = [p/p_ref (n (m - 1)),
    e/c (2)]; ``motion`` (dX, dY, dX/dt, dY/dt) of the journal (m, m/s, grid axes) adds to the
    position and gives the film's rate dh/dt (the dynamic coefficients). ``relaxed`` (traced
    bool): Reynolds conditions relaxed to half-Sommerfeld ones (the solver's fallback).
    ``deformation``: (U, dU/dt) (m, m/s; (n, m + 1) each) the bodies' displacement u_B + u_J and
    its rate, given instead of computed from the pressure (the dynamic coefficients). With rough
    surfaces (``pr.rough``) the fluxes are Patir and Cheng's average flow and ``p_asp`` (n, m + 1)
    (Pa) the asperities' Greenwood-Tripp pressure (zero for smooth ones)."""
    n, m = cfg.n, cfg.m
    N = unknowns(cfg)
    theta, _ = grid(n)
    z = 0.5 * pr.L * pr.s
    pz = interior(x[:N], cfg)
    jfo = cfg.cavitation == "jfo"
    p, fraction, p_load = loading(pz, pr, cfg, relaxed)
    e = pr.c * x[N:N + 2]
    implicit = asperity_unknowns(pr, cfg) > 0       # the asperity pressure an unknown (x's tail)
    p_asp = all_nodes(x[N + 2:].reshape(n, node_columns(cfg)), cfg) * pr.p_ref if implicit else None
    hdot = jnp.zeros((n, m + 1), x.dtype)
    if motion is not None:
        e = e + motion[:2]
        hdot = hdot - motion[2] * jnp.cos(theta)[:, None] - motion[3] * jnp.sin(theta)[:, None]
    if deformation is None:
        uB, uJ = deformations(p_load if p_asp is None else p_load + p_asp, pr, z)
    else:
        uB, uJ = deformation[0], jnp.zeros_like(deformation[0])
        hdot = hdot + deformation[1]
    h = film2d.film(theta, z, pr.c, e, pr.tilt) + uB + uJ
    f = film2d.fluxes(p, h, pr.R, z, pr.eta, pr.v, fraction if jfo else None, pr.rough, sliding(pr))
    gap_pressure = jnp.zeros_like(h) if pr.rough is None else pr.rough.asperity_pressure(h)
    return dict(f, theta=theta, z=z, pz=pz, p=p, h=h, hdot=hdot, e=e, p_load=p_load, uB=uB, uJ=uJ,
                fraction=fraction, p_asp=gap_pressure if p_asp is None else p_asp,
                # the asperity unknowns' equations: the pressure the gap gives, over p_ref
                asperity_residual=None if p_asp is None else own_nodes((p_asp - gap_pressure) / pr.p_ref, cfg).ravel())


def sliding(pr: Params):
    """U_journal - U_bore (m/s): the surfaces' relative speed along x."""
    return pr.omega_J * pr.RJ - pr.omega_B * pr.R


def loading(pz, pr: Params, cfg: Config, relaxed=False):
    """Pressure (n, m + 1) (Pa, all nodes), liquid fraction and loading pressure (the one the
    bodies and the journal carry: clipped at 0 by half-Sommerfeld, or by ``relaxed`` Reynolds
    conditions) from the cell unknowns ``pz`` (n, m - 1)."""
    jfo = cfg.cavitation == "jfo"
    # "jfo": pz is Elrod's universal unknown, the pressure where positive, the liquid film
    # fraction - 1 where negative (:func:`vjax.films.reynolds.pressure_and_fraction`)
    p_scaled, fraction = reynolds.pressure_and_fraction(pz, cfg.cavitation, pr.smoothing if jfo else 0.0)
    p = film2d.with_ends(p_scaled * pr.p_ref)
    fraction = 1.0 + film2d.with_ends(fraction - 1.0)     # the ends: ambient, a full film
    p_load = reynolds.load_pressure(p, cfg.cavitation)
    if cfg.cavitation == "reynolds" and relaxed is not False:
        p_load = jnp.where(relaxed, jnp.maximum(p, 0.0), p_load)
    return p, fraction, p_load


def deformations(p_load, pr: Params, z):
    """Radial displacements (n, m + 1) (m, each opening the film) of the bore and the journal
    under the loading pressure ``p_load`` (Pa): every axial slice deforms as the plane ring
    (plane strain) under its own pressure, by the ring operator's symbol along theta. The
    slices' mean first mode is the film force per unit length, which equals the load over L
    at equilibrium: it is taken from the load (as the long bearing does; for a soft body it
    moves the slices by up to hundreds of clearances, which Newton then need not find), the
    slices' deviations from it from their own pressure. Zero for rigid bodies."""
    zero = jnp.zeros_like(p_load)
    if pr.op_B is None and pr.op_J is None:
        return zero, zero
    n = p_load.shape[0]
    wz = film2d.node_widths(z)
    P = jnp.fft.rfft(p_load, axis=0)                       # (n // 2 + 1, m + 1)
    # F_x + i F_y = -R dtheta sum_j w_j conj(P[1, j]) = -(load_x + i load_y) at equilibrium
    mean = (P[1] @ wz) / pr.L
    P = P.at[1].add((pr.load[0] - 1j * pr.load[1]) / (pr.R * 2 * jnp.pi / n * pr.L) - mean)

    # slices: each section as the plane ring; a 3D layer: DCT-I in z as well
    deform = lambda op: zero if op is None else op.apply_theta_modes(pr.compliance * P)    # noqa: E731
    return deform(pr.op_B), deform(pr.op_J)


def cell_residual(x, pr: Params, cfg: Config, motion=None, relaxed=False, deformation=None, rate=None,
                  subcell=1.0):
    """Scaled cell equations (n (m - 1),; followed by the asperity unknowns' equations, n node_columns,
    when there are some, :func:`asperity_unknowns`), the force of the film and the asperities on the
    journal (N, grid axes) and the film's margin (m, positive where the model holds,
    :func:`margin`); the
    arguments those of :func:`fields`, and ``rate`` (n (m - 1),) (1/s): the rate of the
    unknowns, with which a "jfo" cavity's liquid fraction changes (the dynamic coefficients);
    ``subcell``: 1 locates a Reynolds rupture within its cell, 0 on a face (the solver's first
    stages)."""
    f = fields(x, pr, cfg, motion, relaxed, deformation)
    out = film2d.net_outflow(f, pr.R, f["z"])
    dth = 2 * jnp.pi / cfg.n
    # the film's own growth d(h f)/dt per unit area, f the liquid fraction (1 but in a "jfo" cavity);
    # on rough surfaces the average flow stores the expected gap h_T (as its Couette flux carries
    # it; h with rough.couette == "nominal"): its rate (dh_T/dh) dh/dt
    hdot = f["hdot"]
    if pr.rough is not None and pr.rough.couette == "expected":
        hdot = jax.jvp(pr.rough.expected_gap, (f["h"],), (hdot,))[1]
    growth = hdot[:, 1:-1] * f["fraction"][:, 1:-1]
    if rate is not None and cfg.cavitation == "jfo":
        growth = growth + f["h"][:, 1:-1] * jnp.where(f["pz"] < 0, interior(rate, cfg), 0.0)
    out = out + pr.R * dth * film2d.node_widths(f["z"])[None, 1:-1] * growth
    scale = film2d.conductance(f, pr.R, f["z"]) * pr.p_ref
    couette = f["cx"][:, 1:-1]
    couette_out = (couette - jnp.roll(couette, 1, axis=0)) * film2d.node_widths(f["z"])[None, 1:-1]
    r = film2d.cell_equations(f["pz"], out, scale, cfg.cavitation, pr.groove[:, 1:-1], pr.ps / pr.p_ref,
                               couette_out, pr.v, subcell)
    if cfg.cavitation == "reynolds" and relaxed is not False:
        sommerfeld = film2d.cell_equations(f["pz"], out, scale, "sommerfeld", pr.groove[:, 1:-1], pr.ps / pr.p_ref)
        r = jnp.where(relaxed, sommerfeld, r)
    F, _ = film2d.resultants(f["p_load"] + f["p_asp"], f["theta"], f["z"], pr.R)
    r = own_columns(r, cfg).ravel()
    if f["asperity_residual"] is not None:
        r = jnp.concatenate([r, f["asperity_residual"]])
    return r, F, margin(f["h"], pr)


def margin(h, pr: Params):
    """The film's margin (m), positive where the model holds: min h for smooth surfaces; the
    clearance for rough ones, whose model holds for any nominal film (a closed one is an
    asperity layer compressed beyond its mean planes, carrying the load)."""
    return jnp.min(h) if pr.rough is None else pr.c


def equations(x, pr: Params, cfg: Config, relaxed=False, subcell=1.0):
    """Cell equations and the force balance (film and asperity force + load = 0, over |W|); and
    the film's margin (:func:`margin`)."""
    r, F, hmin = cell_residual(x, pr, cfg, relaxed=relaxed, subcell=subcell)
    return jnp.concatenate([r, (F + pr.load) / pr.W]), hmin


def own_compliance(pr: Params, cfg: Config):
    """The bodies' displacement (m/Pa) at a node under a unit pressure on that node alone, mode 1
    left out (it comes from the load, :func:`deformations`): the diagonal of their compliance
    (at mid-width; a slice's is the same at every node), for :func:`linear_model`."""
    n, m = cfg.n, cfg.m
    P = jnp.ones((n // 2 + 1, m + 1), jnp.result_type(pr.c, 1j)).at[1].set(0.0)
    P = P * (jnp.arange(m + 1) == m // 2)                  # a unit pressure at (theta_0, z = 0)
    u = sum(op.apply_theta_modes(P) for op in (pr.op_B, pr.op_J) if op is not None)
    return pr.compliance * u[0, m // 2]


def linear_model(x, pr: Params, cfg: Config, relaxed=False, subcell=1.0):
    """``(solve, solve_transpose)`` of the Newton system at x. The cell equations' Jacobian in
    the pressures, the film's deformation held, is block tridiagonal (a ring of n blocks of
    m - 1 cells across the width, cyclic), bordered by the two position columns and force rows
    (:func:`vjax.films.blocks.bordered_solver`, O(n m^3)): for rigid bodies that is the Jacobian, and
    the solve is exact and direct up to EXACT_WIDTH unknown cells across; above that, GMRES
    preconditioned by an aggregation multigrid V-cycle of the same stencil, the two border
    unknowns left to GMRES (:func:`vjax.films.multigrid.bordered`, O(n m) per application).
    Deformable bodies add G K D (G the cells' derivative in the film, K the bodies' compliance,
    which couples every node of a slice, D the loading pressure's slope): with ``cfg.krylov``
    the system is solved by GMRES, its products matrix-free (one FFT per product, O(N log N)),
    preconditioned as above with K kept on each node's own entry of the film's Jacobian
    (:func:`own_compliance`: a thin layer's compliance is mostly that local, Winkler-like part).
    Rough surfaces on a deformable body add the asperity pressures, one unknown per node
    (:func:`asperity_unknowns`): GMRES over all unknowns, preconditioned by
    :func:`_asperity_preconditioner`."""
    n = cfg.n
    N = unknowns(cfg)
    full = lambda y: equations(y, pr, cfg, relaxed, subcell)[0]     # noqa: E731
    _, matvec = jax.linearize(full, x)
    unit = jnp.eye(2, N + 2, N, dtype=x.dtype)          # the rows of e/c in the identity
    gmres = lambda A, M, b: _krylov.gmres(A, b, M, KRYLOV_TOL, KRYLOV_MAX_ITER)[0]     # noqa: E731

    def solve_transposed(precondition):      # J^T's products traced only where its solve is called
        def solve(b):
            _, vjp = jax.vjp(full, x)
            return gmres(lambda v: vjp(v)[0], precondition(), b)
        return solve

    if asperity_unknowns(pr, cfg):
        precondition = _asperity_preconditioner(x, pr, cfg, relaxed, subcell)
        return (lambda b: gmres(matvec, precondition(), b)), solve_transposed(lambda: precondition(True))
    if is_rigid(pr):
        # the cells' stencil and the two columns d/d(e/c) from one batch of products with the
        # linearized equations: one copy of their linearization in the compiled program
        colour, seeds = blocks.stencil_seeds(n, columns(cfg), x.dtype)
        products = jax.vmap(matvec)(jnp.concatenate([jnp.pad(seeds, ((0, 0), (0, 2))), unit]))
        C = blocks.stencil_from_products(products[:-2, :N], colour)
        cols = products[-2:].T                          # (N + 2, 2): d/d(e/c)
    else:
        rest = lambda pz: jnp.concatenate([pz, x[N:]])     # noqa: E731
        U0, load0, own = _held(x, pr, cfg, relaxed)

        def cells(pz):
            U = U0 + own * (loading(interior(pz, cfg), pr, cfg, relaxed)[2] - load0)
            return cell_residual(rest(pz), pr, cfg, relaxed=relaxed, deformation=(U, jnp.zeros_like(U)),
                                 subcell=subcell)[0]
        C = blocks.stencil(cells, x[:N], n, columns(cfg))
        cols = jax.vmap(matvec)(unit).T
    # the force rows' pressure part: their own reverse-mode Jacobian, not the transpose of the
    # whole equations (which Newton's program then need not hold)
    rows = jax.jacrev(lambda y: force_balance(y, pr, cfg, relaxed))(x)
    border = (cols[:N], rows[:, :N], cols[N:])
    solve = stencil_solver(C, border)
    # J^T's factors are made where its solve is called (the derivatives), not in Newton's loop
    transposed = lambda: stencil_solver(C, border, transposed=True)     # noqa: E731
    if is_rigid(pr) and columns(cfg) <= EXACT_WIDTH:
        return solve, lambda b: transposed()(b)
    return (lambda b: gmres(matvec, solve, b)), solve_transposed(transposed)


def _held(x, pr: Params, cfg: Config, relaxed=False):
    """The bodies' displacement U0 (n, m + 1) (m) and loading pressure (Pa) at x, and each
    node's own compliance (m/Pa, :func:`own_compliance`): the local model of the bodies in
    :func:`linear_model`'s preconditioners, U = U0 + own (p - p0)."""
    f0 = fields(x, pr, cfg, relaxed=relaxed)
    return f0["uB"] + f0["uJ"], f0["p_load"], own_compliance(pr, cfg).real


def _asperity_preconditioner(x, pr: Params, cfg: Config, relaxed=False, subcell=1.0):
    """The preconditioner of the Newton system with asperity unknowns a (rough surfaces on a
    deformable body): ``transposed -> (b -> M b)`` (``transposed``: M^T). M is the exact inverse
    of the local model's Jacobian, the bodies' compliance kept on each node's own entry
    (:func:`own_compliance`: U = U0 + own (p_load + p_a - p0)). In that model a node's asperity
    equation, a - p_a(h)/p_ref, involves only its own a, its own film pressure and the position
    y_e: the asperity unknowns are eliminated node by node, a = D^-1 (b_a - A_ay y) with D the
    (diagonal) 1 - p_a'(h) own > 1, and the film's 9-point stencil with its border (y =
    pressures and position) then holds the Schur complement S = A_yy - A_ya D^-1 A_ay, solved as
    the smooth film's (:func:`stencil_solver`); a is back-substituted."""
    N, Na = unknowns(cfg), asperity_unknowns(pr, cfg)
    U0, load0, own = _held(x, pr, cfg, relaxed)
    a0 = x[N + 2:]

    def local(y, a):         # the local model's equations [cells, asperities, forces]
        p_a = all_nodes((a - a0).reshape(cfg.n, node_columns(cfg)), cfg) * pr.p_ref
        U = U0 + own * (loading(interior(y[:N], cfg), pr, cfg, relaxed)[2] - load0 + p_a)
        r, F, _ = cell_residual(jnp.concatenate([y, a]), pr, cfg, relaxed=relaxed,
                                deformation=(U, jnp.zeros_like(U)), subcell=subcell)
        return jnp.concatenate([r, (F + pr.load) / pr.W])
    film_rows = lambda r: jnp.concatenate([r[:N], r[N + Na:]])     # noqa: E731
    y0 = x[:N + 2]
    # D: each asperity row depends on its own node's a alone, so one product gives the diagonal
    D = jax.jvp(lambda a: local(y0, a)[N:N + Na], (a0,), (jnp.ones_like(a0),))[1]
    _, A_ay = jax.linearize(lambda y: local(y, a0)[N:N + Na], y0)
    _, A_ya = jax.linearize(lambda a: film_rows(local(y0, a)), a0)

    def schur(y):            # the film rows with a eliminated: their Jacobian is S
        return film_rows(local(y, a0 - A_ay(y - y0) / D))
    colour, seeds = blocks.stencil_seeds(cfg.n, columns(cfg), x.dtype)
    products = jax.vmap(jax.linearize(schur, y0)[1])(
        jnp.concatenate([jnp.pad(seeds, ((0, 0), (0, 2))), jnp.eye(2, N + 2, N, dtype=x.dtype)]))
    C = blocks.stencil_from_products(products[:-2, :N], colour)
    cols = products[-2:].T
    _, vjp = jax.vjp(schur, y0)
    rows = jax.vmap(lambda v: vjp(v)[0])(jnp.eye(2, N + 2, N, dtype=x.dtype))
    border = (cols[:N], rows[:, :N], cols[N:])

    def forward():
        S = stencil_solver(C, border)

        def apply(b):        # b: [cells, asperities, forces] -> [pressures, position, asperities]
            w = b[N:N + Na] / D
            y = S(film_rows(b) - A_ya(w))
            return jnp.concatenate([y, w - A_ay(y) / D])
        return apply

    def transposed():
        S_T = stencil_solver(C, border, transposed=True)
        A_ay_T = jax.linear_transpose(A_ay, y0)
        A_ya_T = jax.linear_transpose(A_ya, a0)

        def apply(c):        # c: [pressures, position, asperities] -> [cells, asperities, forces]
            w = c[N + 2:] / D
            u = S_T(c[:N + 2] - A_ay_T(w)[0])
            return jnp.concatenate([u[:N], w - A_ya_T(u)[0] / D, u[N:]])
        return apply
    return lambda transposed_=False: transposed() if transposed_ else forward()


def force_balance(x, pr: Params, cfg: Config, relaxed=False):
    """The force rows of :func:`equations`, (film force + load) / |W|, from the pressures alone
    (the loading pressure's resultant): their Jacobian in the pressures for :func:`linear_model`
    (the asperities' force, which depends on the position only, adds nothing there)."""
    p_load = loading(interior(x[:unknowns(cfg)], cfg), pr, cfg, relaxed)[2]
    F, _ = film2d.resultants(p_load, grid(cfg.n)[0], 0.5 * pr.L * pr.s, pr.R)
    return (F + pr.load) / pr.W


def stencil_solver(C, border=None, transposed=False):
    """``b -> A^-1 b`` (``transposed``: ``A^-T b``) for the film's 9-point stencil C (3, 3, n,
    k), bordered by ``border`` = (columns (n k, g), rows (g, n k), corner (g, g)) if given: up
    to EXACT_WIDTH cells across the exact block solve (:func:`vjax.films.blocks.bordered_solver`),
    above that the multigrid V-cycle, the border left to GMRES (:func:`vjax.films.multigrid.bordered`:
    then a preconditioner, not a solve). Factored when called."""
    if C.shape[3] > EXACT_WIDTH:
        return multigrid.bordered(C, 0 if border is None else border[2].shape[0], transposed)
    ring = blocks.stencil_blocks(C)
    return blocks.ring_solver(ring, transposed) if border is None else blocks.bordered_solver(
        ring, *border, transposed)


def is_rigid(pr: Params):
    return pr.op_B is None and pr.op_J is None


def solved_by_linear_model(pr: Params, cfg: Config):
    """Whether Newton's steps and the derivatives use :func:`linear_model` (block solve or
    GMRES), not a dense LU of the AD Jacobian (deformable bodies, smooth or rough, on small
    grids unless ``cfg.krylov``)."""
    return is_rigid(pr) or cfg.krylov or columns(cfg) > EXACT_WIDTH
