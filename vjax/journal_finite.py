"""Finite-length journal bearing: the film over the bearing's width, the bodies in plane-strain slices.

Called by :func:`vjax.journal_bearing` with ``length=L``; docs/theory.md §16.

Geometry and frames
-------------------
Bore of radius R (centre O), journal of radius R - c, land z in [-L/2, L/2] with ambient
pressure at both ends. The grid theta_i = 2 pi i / n is fixed in the bearing: theta = 0
points along the load (its direction when the bearing is set up, so that derivatives with
respect to the load vector do not turn the bearing). An axial supply groove at
``supply_angle`` (rad from the load, counter-clockwise; default pi, opposite the load) holds
``supply_pressure`` over the central fraction ``supply_width`` of the land (1: the whole
width; a feed hole: its diameter over L); ``supply_angle=None``: no groove, the ends alone
set the datum. ``groove="circumferential"``: instead a groove round the mid-width z = 0 at
``supply_pressure`` (zero width: it splits the land into two of L/2). The journal centre
at axial position z sits at e + z gamma from the bore's axis: e the eccentricity vector
(unknown), gamma = ``tilt`` (rad, absolute x, y components: the journal's axis turned about
y by gamma_x and about -x by gamma_y, small angles), so that

    h(theta, z) = c - (e_x + z gamma_x) cos theta - (e_y + z gamma_y) sin theta

(grid axes), plus the bodies' deformations u_B + u_J (each positive where it opens the film).
Film equations: :mod:`vjax._film2d`. Cavitation "reynolds" (default), "jfo" (mass-conserving:
Elrod's universal unknown, as in 1D), "half_sommerfeld", "sommerfeld".

Bodies: ``housing`` (hole, liner, half-plane) and ``shaft`` (disc, sleeve, half-plane), as in
the long bearing, None for rigid. Each axial section deforms as the plane ring does under
its own pressure (plane strain: no axial coupling between the slices), with the ring's
steady-state viscoelastic operator, the pattern fixed in space moving at -omega relative to
each body; the exact limit of a long bearing, and of any bearing whose bodies are thin
against the pressure's axial length scale (a liner much thinner than L; a bonded layer's
axial coupling is of the order of its thickness over L). :func:`deformations`. A liner or
sleeve made with ``axial="3d"`` is instead the bonded layer in 3D elasticity over the land,
its ends sliding on rigid shoulders at z = +-L/2 (:mod:`vjax.layer3d_land`: the pressure
piecewise linear in z, FFT in theta and DCT-I in z; uniform axial spacing; in the dynamic
coefficients by its whirl response,
:func:`vjax.layer3d_land.whirl_symbol`).

Load control: the pressure force of the film on the journal balances ``load`` (N, the
external force on the journal, total for the bearing); the unknowns are the scaled pressures
and the eccentricity vector e/c (grid axes). With a tilt the film also exerts a moment on the
journal (``moment``, about the centre plane z = 0), which the shaft must carry; the tilt is
given, not solved for.

Outputs (SI totals for the bearing)
-----------------------------------
``force`` on the housing (N, absolute; the load at equilibrium), ``moment`` of the film on the
journal about the bore's centre point (N m, absolute x, y), ``position`` e (m, absolute),
``eccentricity`` |e|/c, ``attitude_angle`` (from the load line to e, counter-clockwise),
``line_of_centres_angle`` (absolute). ``min_film`` (m) and where: ``min_film_theta`` (grid
angle, from the load) and ``min_film_z`` (m); ``max_pressure`` (Pa). Torques by the fluid
(N m, counter-clockwise positive), shear tau_B = -h/2 dp/dx - eta (U_B - U_J)/h on the bore and
tau_J = -h/2 dp/dx + eta (U_B - U_J)/h on the journal (U = omega R): ``torque`` on the housing
about O, ``torque_shaft`` on the journal about its own centre, and their pressure-flow
(Poiseuille) parts ``torque_poiseuille``, ``torque_poiseuille_shaft`` and the viscoelastic
parts ``torque_viscoelastic``, ``torque_viscoelastic_shaft``: the moment of the pressure on
each slice's deformed profile about the body's centre, -R int int p du/dtheta dtheta dz (the
rest is Couette; the Reynolds cavity is taken as full of lubricant, as in Raimondi and Boyd);
-omega times a viscoelastic torque is the body's hysteretic dissipation. Flows (m^3/s):
``side_leakage`` out of both ends, ``supply_flow`` the groove's net outflow, ``inlet_flow``
the flow the groove sends downstream into the land (Raimondi and Boyd's Q). ``power_loss``
(W): the viscous dissipation in the film; with the bodies' hysteresis it balances the power
put in, -omega_B torque - omega_J torque_shaft + p_s supply_flow = power_loss - omega_B
torque_viscoelastic - omega_J torque_viscoelastic_shaft, up to the pressure energy
sum p_i w_i of the flow let out within the rupture's cells (the rupture located within its
cell, :func:`vjax.reynolds.rupture_outflow`; ~1e-8 of the power), which the left side gains.

Solver: the core's damped Newton (:func:`vjax._solve.newton`, steps giving h <= 0 rejected).
An aligned bearing (``tilt`` None) has a pressure symmetric about mid-width: its unknowns are
the cells from mid-width to one end, mirrored (:func:`_interior`), half the width's; a tilt,
even a zero one given, solves the whole width. Each Newton step (:func:`linear_model`): the
cell equations' Jacobian in the pressures, the deformation held, is a 9-point stencil, block
tridiagonal (a ring of n blocks across the width, cyclic), bordered by the eccentricity's two
columns and the two force rows. Rigid bodies: that is the Jacobian, solved exactly by a
block Thomas factorization and Woodbury (:mod:`vjax._blocks`, O(n k^3) for k cells across)
up to EXACT_WIDTH cells across, above that by GMRES preconditioned by an aggregation
multigrid V-cycle (:mod:`vjax._multigrid`, O(n k) per application). Deformable bodies
couple every cell of a slice through their compliance: a dense LU of the Jacobian from
jacfwd (``linear_solver="dense"``, up to a few thousand unknowns, O(N^3)), or GMRES with
matrix-free products (one FFT each, O(N log N)) preconditioned as the rigid film with each
node's own compliance added (``"krylov"``; "auto": from KRYLOV_MIN_CELLS cells). Under
Reynolds conditions a Newton that stalls restarts from the half-Sommerfeld solution; "jfo"
starts from the Reynolds solution (:func:`_jfo_steady`); soft bodies fall back on
continuation in their compliance and the speed (:func:`_steady`); cold solves on grids of
NESTED_MIN_CELLS cells or more start from the 2x coarser grid's solution. Derivatives are
implicit (:func:`vjax._solve.implicit_root`, the same linear solve and its transpose).
Dynamic coefficients: :func:`impedance`, the cell equations linearized in the pressures and
the journal's position (and tilt) and their rates, with the bodies by their whirl operators
and a "jfo" cavity's fraction by its own dynamics; matrix-free, one GMRES solve per whirl
frequency and load column, preconditioned as Newton's steps (rigid bodies on grids up to
EXACT_WIDTH cells across: the exact block solve alone). ``throw=True`` raises
:class:`~vjax.ConvergenceError` on failure, inside ``jit`` too.
"""
from __future__ import annotations

import dataclasses
import math
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from . import _blocks, _film2d, _journal_film, _krylov, _multigrid, _scene, _solve, checks, reference, reynolds
from .bodies import as_body, check_fits, disc, hole
from .layer3d_land import LandOperator, dct1, idct1
from .operator import RingOperator, grid, memory_revolutions

GROOVES = ("fixed", "circumferential")
KRYLOV_MIN_CELLS = 512    # linear_solver="auto": a dense LU with deformable bodies up to this many cells
KRYLOV_TOL = 1e-9         # relative residual of each GMRES solve (Newton steps and derivatives)
KRYLOV_MAX_ITER = 300     # GMRES steps per solve (restarted every 20)
KRYLOV_ACCEPT = 1e-6      # the dynamic coefficients' GMRES solves fail above this relative residual (float32: 1e-3)
EXACT_WIDTH = 32          # Newton's preconditioner: the exact block solve up to this many unknown cells across the
                          # width (O(n m^3)), a multigrid V-cycle above (O(n m), :mod:`vjax._multigrid`)


@dataclasses.dataclass(frozen=True)
class FiniteJournalOptions:
    """Static options of the finite bearing (``journal_bearing(..., length=L)``): ``n`` cells in
    theta (even, >= 8), ``m`` axial intervals (even, >= 2: m + 1 nodes, the end ones at ambient
    pressure), axial ``spacing`` "uniform" or "cosine" (nodes clustered at the ends, for long
    bearings whose pressure drops to ambient within about R of the ends), Newton tolerance
    ``tol`` (max-norm of the scaled equations; None: 1e-10 in float64, 1e-4 in float32),
    ``max_iter`` Newton steps and, with deformable bodies, the ``linear_solver`` of each Newton
    step, of the implicit derivatives and of the dynamic coefficients' whirl solves: "dense" (LU of the AD Jacobian, O(N^3) for N = n (m -
    1) cells), "krylov" (matrix-free GMRES, O(N log N) per product, preconditioned by the film's
    block-tridiagonal Jacobian with each node's own compliance: :func:`linear_model`) or "auto"
    (Krylov above KRYLOV_MIN_CELLS cells). Rigid bodies: the exact block solve, or GMRES with a
    multigrid V-cycle on grids wider than EXACT_WIDTH cells (:func:`linear_model`). The default
    64 x 16 is for a quick look; K and C under Reynolds conditions change by at most 0.33% from
    128 x 32 to the next grid and 0.06% from 256 x 64 (README, grid study)."""

    n: int = 64
    m: int = 16
    spacing: str = "uniform"
    tol: float | None = None
    max_iter: int = 60
    linear_solver: str = "auto"

    def __post_init__(self):
        checks.option_count("n", self.n, 8)
        checks.option_count("m", self.m, 2)
        if self.n % 2 or self.m % 2:
            raise ValueError(f"n and m must be even, got n={self.n}, m={self.m}")
        checks.one_of("spacing", self.spacing, _film2d.SPACINGS)
        if self.tol is not None:
            checks.option_number("tol", self.tol)
        checks.option_count("max_iter", self.max_iter)
        checks.one_of("linear_solver", self.linear_solver, ("auto", "dense", "krylov"))

    @property
    def krylov(self) -> bool:
        """Whether deformable bodies' Newton steps and derivatives are solved by GMRES."""
        return self.linear_solver == "krylov" or (self.linear_solver == "auto"
                                                  and self.n * (self.m - 1) > KRYLOV_MIN_CELLS)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class FiniteJournalResult(_scene.SceneResult):
    """Solution of ``journal_bearing(..., length=L)`` (SI totals for the bearing; see
    :mod:`vjax.journal_finite`). Arrays on the grid: ``theta`` (n,) from the load direction
    (rad), ``z`` (m + 1,) axial nodes (m), ``pressure`` and ``film`` (n, m + 1) (Pa, m),
    ``film_fraction`` (n, m + 1): the liquid fraction of the film (below 1 in a "jfo" cavity),
    ``displacement`` of the bore and ``displacement_shaft`` of the journal (n, m + 1) (m,
    each positive where it opens the film; zero for a rigid body). Convergence:
    ``iterations``, ``residual``, ``result``; ``converged`` is ``result == 0``."""

    theta: jax.Array
    z: jax.Array
    pressure: jax.Array
    film: jax.Array
    film_fraction: jax.Array
    displacement: jax.Array
    displacement_shaft: jax.Array
    force: jax.Array
    moment: jax.Array
    position: jax.Array
    eccentricity: jax.Array
    attitude_angle: jax.Array
    line_of_centres_angle: jax.Array
    min_film: jax.Array
    min_film_theta: jax.Array
    min_film_z: jax.Array
    max_pressure: jax.Array
    torque: jax.Array
    torque_shaft: jax.Array
    torque_poiseuille: jax.Array
    torque_poiseuille_shaft: jax.Array
    torque_viscoelastic: jax.Array
    torque_viscoelastic_shaft: jax.Array
    side_leakage: jax.Array
    supply_flow: jax.Array
    inlet_flow: jax.Array
    power_loss: jax.Array
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Params:
    """Differentiable parameters of the finite bearing (SI; grid axes: x along ``frame``)."""

    R: jax.Array
    RJ: jax.Array
    c: jax.Array
    L: jax.Array
    eta: jax.Array
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


def _unknowns(cfg: Config):
    return cfg.n * _columns(cfg)


def _columns(cfg: Config):
    """Axial columns of the cell unknowns: the m - 1 interior nodes; in a half-width solve
    (``cfg.half``) the m / 2 from mid-width to the last interior one."""
    return cfg.m // 2 if cfg.half else cfg.m - 1


def _interior(u, cfg: Config):
    """The flat cell unknowns (n _columns) as values (n, m - 1) at every interior node: a
    half-width solve's mirrored about mid-width (an aligned bearing's pressure is symmetric)."""
    u = u.reshape(cfg.n, _columns(cfg))
    return jnp.concatenate([u[:, :0:-1], u], axis=1) if cfg.half else u


def _own_columns(a, cfg: Config):
    """The unknowns' columns (n, _columns) of an array over the interior nodes (n, m - 1)."""
    return a[:, cfg.m // 2 - 1:] if cfg.half else a


def _rotation(frame):
    """The 2 x 2 rotation from grid axes to absolute ones (the grid's x axis at ``frame``)."""
    c, s = jnp.cos(frame), jnp.sin(frame)
    return jnp.array([[c, -s], [s, c]])


def _as_unknowns(scaled, position, pr: Params, cfg: Config):
    """Unknowns [scaled pressure (the universal unknown for "jfo") at the interior nodes (those
    of the unknowns, :func:`_columns`), journal centre / c in grid axes] from ``scaled`` (n, m + 1)
    and an absolute ``position`` (m)."""
    return jnp.concatenate([_own_columns(scaled[:, 1:-1], cfg).ravel(), _rotation(pr.frame).T @ position / pr.c])


def fields(x, pr: Params, cfg: Config, motion=None, relaxed=False, deformation=None):
    """Grid, pressure (all nodes, Pa), film and fluxes for the unknowns x = [p/p_ref (n (m - 1)),
    e/c (2)]; ``motion`` (dX, dY, dX/dt, dY/dt) of the journal (m, m/s, grid axes) adds to the
    position and gives the film's rate dh/dt (the dynamic coefficients). ``relaxed`` (traced
    bool): Reynolds conditions relaxed to half-Sommerfeld ones (the solver's fallback).
    ``deformation``: (U, dU/dt) (m, m/s; (n, m + 1) each) the bodies' displacement u_B + u_J and
    its rate, given instead of computed from the pressure (the dynamic coefficients)."""
    n, m = cfg.n, cfg.m
    N = _unknowns(cfg)
    theta, _ = grid(n)
    z = 0.5 * pr.L * pr.s
    pz = _interior(x[:N], cfg)
    jfo = cfg.cavitation == "jfo"
    p, fraction, p_load = _loading(pz, pr, cfg, relaxed)
    e = pr.c * x[N:N + 2]
    hdot = jnp.zeros((n, m + 1), x.dtype)
    if motion is not None:
        e = e + motion[:2]
        hdot = hdot - motion[2] * jnp.cos(theta)[:, None] - motion[3] * jnp.sin(theta)[:, None]
    if deformation is None:
        uB, uJ = deformations(p_load, pr, z)
    else:
        uB, uJ = deformation[0], jnp.zeros_like(deformation[0])
        hdot = hdot + deformation[1]
    h = _film2d.film(theta, z, pr.c, e, pr.tilt) + uB + uJ
    f = _film2d.fluxes(p, h, pr.R, z, pr.eta, pr.v, fraction if jfo else None)
    return dict(f, theta=theta, z=z, pz=pz, p=p, h=h, hdot=hdot, e=e, p_load=p_load, uB=uB, uJ=uJ,
                fraction=fraction)


def _loading(pz, pr: Params, cfg: Config, relaxed=False):
    """Pressure (n, m + 1) (Pa, all nodes), liquid fraction and loading pressure (the one the
    bodies and the journal carry: clipped at 0 by half-Sommerfeld, or by ``relaxed`` Reynolds
    conditions) from the cell unknowns ``pz`` (n, m - 1)."""
    jfo = cfg.cavitation == "jfo"
    # "jfo": pz is Elrod's universal unknown, the pressure where positive, the liquid film
    # fraction - 1 where negative (:func:`vjax.reynolds.pressure_and_fraction`)
    p_scaled, fraction = reynolds.pressure_and_fraction(pz, cfg.cavitation, pr.smoothing if jfo else 0.0)
    p = _film2d.with_ends(p_scaled * pr.p_ref)
    fraction = 1.0 + _film2d.with_ends(fraction - 1.0)     # the ends: ambient, a full film
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
    wz = _film2d.node_widths(z)
    P = jnp.fft.rfft(p_load, axis=0)                       # (n // 2 + 1, m + 1)
    # F_x + i F_y = -R dtheta sum_j w_j conj(P[1, j]) = -(load_x + i load_y) at equilibrium
    mean = (P[1] @ wz) / pr.L
    P = P.at[1].add((pr.load[0] - 1j * pr.load[1]) / (pr.R * 2 * jnp.pi / n * pr.L) - mean)

    # slices: each section as the plane ring; a 3D layer: DCT-I in z as well
    deform = lambda op: zero if op is None else op.apply_theta_modes(pr.compliance * P)    # noqa: E731
    return deform(pr.op_B), deform(pr.op_J)


def cell_residual(x, pr: Params, cfg: Config, motion=None, relaxed=False, deformation=None, rate=None,
                  subcell=1.0):
    """Scaled cell equations (n (m - 1),) and the film's force on the journal (N, grid axes);
    the arguments those of :func:`fields`, and ``rate`` (n (m - 1),) (1/s): the rate of the
    unknowns, with which a "jfo" cavity's liquid fraction changes (the dynamic coefficients);
    ``subcell``: 1 locates a Reynolds rupture within its cell, 0 on a face (the solver's first
    stages)."""
    f = fields(x, pr, cfg, motion, relaxed, deformation)
    out = _film2d.net_outflow(f, pr.R, f["z"])
    dth = 2 * jnp.pi / cfg.n
    # the film's own growth d(h f)/dt per unit area, f the liquid fraction (1 but in a "jfo" cavity)
    growth = f["hdot"][:, 1:-1] * f["fraction"][:, 1:-1]
    if rate is not None and cfg.cavitation == "jfo":
        growth = growth + f["h"][:, 1:-1] * jnp.where(f["pz"] < 0, _interior(rate, cfg), 0.0)
    out = out + pr.R * dth * _film2d.node_widths(f["z"])[None, 1:-1] * growth
    scale = _film2d.conductance(f, pr.R, f["z"], pr.eta) * pr.p_ref
    couette = pr.v * f["hx"][:, 1:-1]
    couette_out = (couette - jnp.roll(couette, 1, axis=0)) * _film2d.node_widths(f["z"])[None, 1:-1]
    r = _film2d.cell_equations(f["pz"], out, scale, cfg.cavitation, pr.groove[:, 1:-1], pr.ps / pr.p_ref,
                               couette_out, pr.v, subcell)
    if cfg.cavitation == "reynolds" and relaxed is not False:
        sommerfeld = _film2d.cell_equations(f["pz"], out, scale, "sommerfeld", pr.groove[:, 1:-1], pr.ps / pr.p_ref)
        r = jnp.where(relaxed, sommerfeld, r)
    F, _ = _film2d.resultants(f["p_load"], f["theta"], f["z"], pr.R)
    return _own_columns(r, cfg).ravel(), F, jnp.min(f["h"])


def equations(x, pr: Params, cfg: Config, relaxed=False, subcell=1.0):
    """Cell equations and the force balance (film force + load = 0, over |W|); and min film."""
    r, F, hmin = cell_residual(x, pr, cfg, relaxed=relaxed, subcell=subcell)
    return jnp.concatenate([r, (F + pr.load) / pr.W]), hmin


def _rigid_capacity(eps, pr: Params, parts=False):
    """The rigid bearing's load capacity (N) at eccentricity ratio eps, estimated as the short
    (Ocvirk) and the long half-Sommerfeld capacities in series, 1/W = 1/W_short + 1/W_long (with
    ``parts``: the two)."""
    v, c, R, L, eta = jnp.abs(pr.v), pr.c, pr.R, pr.L, pr.eta
    Ws = eta * 2 * v * L**3 / c**2 * eps * jnp.sqrt(16 * eps**2 + jnp.pi**2 * (1 - eps**2)) / (4 * (1 - eps**2) ** 2)
    Wl = 12 * eta * v * R**2 * L / c**2 * reference.half_sommerfeld_load(eps)
    return (Ws, Wl) if parts else Ws * Wl / (Ws + Wl)


def _guess(pr: Params, cfg: Config):
    """Rigid estimate of the unknowns: the eccentricity whose load, the short (Ocvirk) and the
    long half-Sommerfeld capacities combined in series (1/W = 1/W_short + 1/W_long), equals
    the load, at their correspondingly weighted attitude angle; the long bearing's pressure
    along theta times a parabola across the width, scaled to carry the load. With deformable
    bodies the journal moves with their rigid displacement under the load (the slices' first
    mode, :func:`deformations`), so that the film keeps the rigid estimate's shape."""
    c, R, L, eta = pr.c, pr.R, pr.L, pr.eta
    eps = _solve.bisect(lambda e: _rigid_capacity(e, pr) - pr.W, jnp.asarray(1e-6, c.dtype),
                        jnp.asarray(0.999, c.dtype), 50)
    eps = jnp.minimum(eps, 0.95)
    Ws, Wl = _rigid_capacity(eps, pr, parts=True)
    short = jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 4 * eps)
    long = jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 2 * eps)
    phi = jnp.sign(pr.v) * (Wl * short + Ws * long) / (Ws + Wl)
    # the load direction in the grid, and the film's minimum at phi ahead of it (behind for v < 0)
    a = jnp.arctan2(pr.load[1], pr.load[0]) + phi
    # the journal: c eps e^{i a} plus the bodies' rigid displacement under the load's first
    # mode (amplitude |symbol_1| W / (pi R L), along the film's minimum)
    s1 = pr.compliance * sum(op.plane_symbol[1] for op in (pr.op_B, pr.op_J) if op is not None)
    moved = c * eps + s1 * pr.W / (jnp.pi * R * L)
    position = jnp.abs(moved) / c * jnp.exp(1j * (a - jnp.angle(moved)))
    n = cfg.n
    theta, _ = grid(n)
    z = 0.5 * L * pr.s[1:-1]
    t = theta - a
    p = (-12 * eta * pr.v * R * eps * jnp.sin(t) * (2 - eps * jnp.cos(t))
         / (c**2 * (2 + eps**2) * (1 - eps * jnp.cos(t)) ** 2))
    p = jnp.maximum(p, 0.0)[:, None] * (1 - (2 * z / L) ** 2)[None, :]
    F, _ = _film2d.resultants(_film2d.with_ends(p), theta, 0.5 * L * pr.s, R)
    p = p * pr.W / jnp.maximum(jnp.hypot(F[0], F[1]), jnp.finfo(c.dtype).tiny) / pr.p_ref
    # a small positive offset: with p = 0 exactly, the FB Newton step grows the pressurized
    # zone by one cell per iteration
    p = jnp.where(pr.groove[:, 1:-1] > 0, pr.ps / pr.p_ref, p + 0.1)
    return jnp.concatenate([_own_columns(p, cfg).ravel(), jnp.stack([position.real, position.imag])])


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
    (:func:`vjax._blocks.bordered_solver`, O(n m^3)): for rigid bodies that is the Jacobian, and
    the solve is exact and direct up to EXACT_WIDTH unknown cells across; above that, GMRES
    preconditioned by an aggregation multigrid V-cycle of the same stencil, the two border
    unknowns left to GMRES (:func:`vjax._multigrid.bordered`, O(n m) per application).
    Deformable bodies add G K D (G the cells' derivative in the film, K the bodies' compliance,
    which couples every node of a slice, D the loading pressure's slope): with ``cfg.krylov``
    the system is solved by GMRES, its products matrix-free (one FFT per product, O(N log N)),
    preconditioned as above with K kept on each node's own entry of the film's Jacobian
    (:func:`own_compliance`: a thin layer's compliance is mostly that local, Winkler-like part)."""
    n = cfg.n
    N = _unknowns(cfg)
    rest = lambda pz: jnp.concatenate([pz, x[N:]])     # noqa: E731
    if _rigid(pr):
        cells = lambda pz: cell_residual(rest(pz), pr, cfg, relaxed=relaxed, subcell=subcell)[0]     # noqa: E731
    else:
        f0 = fields(x, pr, cfg, relaxed=relaxed)
        U0, load0, own = f0["uB"] + f0["uJ"], f0["p_load"], own_compliance(pr, cfg)

        def cells(pz):
            U = U0 + own.real * (_loading(_interior(pz, cfg), pr, cfg, relaxed)[2] - load0)
            return cell_residual(rest(pz), pr, cfg, relaxed=relaxed, deformation=(U, jnp.zeros_like(U)),
                                 subcell=subcell)[0]
    C = _blocks.stencil(cells, x[:N], n, _columns(cfg))
    full = lambda y: equations(y, pr, cfg, relaxed, subcell)[0]     # noqa: E731
    _, matvec = jax.linearize(full, x)
    _, vjp = jax.vjp(full, x)
    unit = jnp.eye(2, N + 2, N, dtype=x.dtype)          # the rows of e/c in the identity
    cols = jax.vmap(matvec)(unit).T                     # (N + 2, 2): d/d(e/c)
    rows = jax.vmap(lambda c: vjp(c)[0])(unit)          # (2, N + 2): the force rows
    border = (cols[:N], rows[:, :N], cols[N:])
    solve = _stencil_solver(C, border)
    # J^T's factors are made where its solve is called (the derivatives), not in Newton's loop
    transposed = lambda: _stencil_solver(C, border, transposed=True)     # noqa: E731
    if _rigid(pr) and _columns(cfg) <= EXACT_WIDTH:
        return solve, lambda b: transposed()(b)
    gmres = lambda A, M, b: _krylov.gmres(A, b, M, KRYLOV_TOL, KRYLOV_MAX_ITER)[0]     # noqa: E731
    return (lambda b: gmres(matvec, solve, b)), (lambda b: gmres(lambda v: vjp(v)[0], transposed(), b))


def _stencil_solver(C, border=None, transposed=False):
    """``b -> A^-1 b`` (``transposed``: ``A^-T b``) for the film's 9-point stencil C (3, 3, n,
    k), bordered by ``border`` = (columns (n k, g), rows (g, n k), corner (g, g)) if given: up
    to EXACT_WIDTH cells across the exact block solve (:func:`vjax._blocks.bordered_solver`),
    above that the multigrid V-cycle, the border left to GMRES (:func:`vjax._multigrid.bordered`:
    then a preconditioner, not a solve). Factored when called."""
    if C.shape[3] > EXACT_WIDTH:
        return _multigrid.bordered(C, 0 if border is None else border[2].shape[0], transposed)
    blocks = _blocks.stencil_blocks(C)
    return _blocks.ring_solver(blocks, transposed) if border is None else _blocks.bordered_solver(
        blocks, *border, transposed)


def _rigid(pr: Params):
    return pr.op_B is None and pr.op_J is None


def _solved_by_linear_model(pr: Params, cfg: Config):
    """Whether Newton's steps and the derivatives use :func:`linear_model` (block solve or
    GMRES), not a dense LU of the AD Jacobian (deformable bodies on small grids)."""
    return _rigid(pr) or cfg.krylov or _columns(cfg) > EXACT_WIDTH


# Newton gives up when its residual has not halved in this many steps: caught on the
# rupture line's kinks it would otherwise creep for all of max_iter (a lined bearing on 64 x 16:
# 60 steps at a residual of 0.29) before the half-Sommerfeld restart or the continuation
STALL_WINDOW = 12


def _newton(x0, pr: Params, cfg: Config, relaxed=False, subcell=1.0):
    """The core's Newton; each step by the block solve for rigid bodies; with deformable ones,
    whose compliance couples every cell of an axial slice, by GMRES (``cfg.krylov``,
    :func:`linear_model`) or a dense LU of the Jacobian from jacfwd (n (m - 1) + 2 unknowns:
    up to a few thousand)."""
    def eqs(x, state):
        r, hmin = equations(x, pr, cfg, relaxed, subcell)
        return r, state, hmin > 0

    N = _unknowns(cfg)
    cap = jnp.concatenate([jnp.full(N, jnp.inf), jnp.full(2, 0.3)]).astype(x0.dtype)
    linear_solve = (lambda x, state, r: linear_model(x, pr, cfg, relaxed, subcell)[0](-r)) \
        if _solved_by_linear_model(pr, cfg) else None
    x, _, stats = _solve.newton(eqs, x0, None, tol=cfg.tol, max_iter=cfg.max_iter, max_step=cap,
                                linear_solve=linear_solve, stall_window=STALL_WINDOW)
    return x, stats


CONTINUATION_STAGES = 40   # at most this many Newton solves in the continuation of soft bodies


def _staged(pr: Params, t):
    """The problem at continuation parameter t in [0, 2] (as the long bearing's): t in [0, 1] the
    bodies' compliance ramped in (factor t) at M times the entrainment speed, M such that the
    rigid bearing would run at eps ~ 0.6 (a thick film, a mild coupling); t in [1, 2] the full
    compliance, the speed M^(2 - t) down to the target's (geometric)."""
    M = jnp.maximum(1.0, pr.W / _rigid_capacity(0.6, pr))
    m = M ** jnp.clip(2.0 - t, 0.0, 1.0)
    return dataclasses.replace(pr, v=pr.v * m, compliance=jnp.clip(t, 0.0, 1.0).astype(pr.v.dtype))


def _steady(pr: Params, cfg: Config):
    """The steady unknowns and the Newton record: :func:`_film_steady` from ``pr.x0``; with
    deformable bodies, if that fails (a soft body far from the rigid estimate, or a load the
    rigid film could carry only at a far higher speed), adaptive continuation in the compliance
    and the speed (:func:`_staged`, :func:`vjax._solve.continuation`), the first stage from the
    rigid estimate: one Newton in one loop (compiled once), the stage parameter traced."""
    if _rigid(pr):
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
    N = _unknowns(cfg)
    f = fields(x, pr, dataclasses.replace(cfg, cavitation="reynolds"))
    p, qx = f["p"][:, 1:-1], f["qx"][:, 1:-1]
    peak = jnp.argmax(p, axis=0)
    flow = jnp.take_along_axis(qx, peak[None, :], axis=0)
    fraction = jnp.clip(flow / (pr.v * f["h"][:, 1:-1]), 0.0, 1.0)
    cavity = p <= 1e-9 * jnp.max(p)
    return x.at[:N].set(_own_columns(jnp.where(cavity, fraction - 1.0, p / pr.p_ref), cfg).ravel())


def _jfo_steady(pr: Params, cfg: Config):
    """Mass-conserving cavitation: the Reynolds solution (the same pressure where the film
    re-forms only at the groove) with its cavity filled by :func:`_jfo_start`, then Newton on
    the exact switch; if that fails (the semismooth Newton can stall on the switch's kinks
    far from the root), the smoothed switch from that start through mu =
    reynolds.JFO_SMOOTHING down to 0 (a turn ending NONFINITE keeps its start). One Newton in
    one loop, mu traced: compiled once (the Reynolds stage apart)."""
    N = _unknowns(cfg)
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
    N = _unknowns(cfg)
    held = _own_columns(pr.groove[:, 1:-1], cfg).ravel() > 0
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


def _outputs(x, pr: Params, cfg: Config, stats):
    f = fields(x, pr, cfg)
    n = cfg.n
    R, RJ, eta, z, theta = pr.R, pr.RJ, pr.eta, f["z"], f["theta"]
    dth = 2 * jnp.pi / n
    wz = _film2d.node_widths(z)
    hx, dpdx = f["hx"], f["dpdx"]
    dU = pr.omega_B * R - pr.omega_J * RJ
    # a striated ("jfo") cavity shears only its liquid: the upwind fraction of each face
    liquid = _film2d.upwind(f["fraction"], pr.v)
    poiseuille = (-0.5 * hx * dpdx) @ wz
    couette = (liquid * eta * dU / hx) @ wz
    arc = R * dth
    TB_p, TJ_p = R * arc * jnp.sum(poiseuille), RJ * arc * jnp.sum(poiseuille)
    # the pressure on each slice's deformed profile: its moment about the body's centre
    # (the viscoelastic torque of the long bearing, per slice; central differences in theta)
    central = lambda u: 0.5 * (jnp.roll(u, -1, axis=0) - jnp.roll(u, 1, axis=0))
    TvB, TvJ = (-R * jnp.sum(f["p_load"] * central(u), axis=0) @ wz for u in (f["uB"], f["uJ"]))
    TB = TB_p - R * arc * jnp.sum(couette) + TvB
    TJ = TJ_p + RJ * arc * jnp.sum(couette) + TvJ
    power = arc * jnp.sum((hx**3 * dpdx**2 / (12 * eta) + liquid * eta * dU**2 / hx) @ wz) \
        + arc * jnp.sum(f["hz"] ** 3 * f["dpdz"] ** 2 / (12 * eta) * jnp.diff(z)[None, :])
    leakage = _film2d.end_outflow(f["p"], f["h"], z, R, eta)
    # the groove's net outflow: its interior cells, the ones held at the supply pressure; its
    # downstream flow into the land: every node of its column (the end nodes' half cells carry
    # Couette flow too)
    supply = jnp.sum(pr.groove[:, 1:-1] * _film2d.net_outflow(f, R, z))
    qx = f["qx"]
    downstream = jnp.where(pr.v >= 0, qx, -jnp.roll(qx, 1, axis=0))
    # a circumferential groove feeds the land axially: all its outflow goes in
    inlet = jnp.where(pr.circumferential > 0, supply, jnp.sum(pr.groove * downstream * wz[None, :]))
    F, M = _film2d.resultants(f["p_load"], theta, z, R)
    rot = lambda a: _rotation(pr.frame) @ a
    e = f["e"]
    h = f["h"]
    k = jnp.argmin(h)
    i, j = k // h.shape[1], k % h.shape[1]
    load_dir = jnp.arctan2(pr.load[1], pr.load[0])
    phi = jnp.angle(jnp.exp(1j * (jnp.arctan2(e[1], e[0]) - load_dir)))
    return FiniteJournalResult(
        theta=theta, z=z, pressure=f["p_load"], film=h, film_fraction=f["fraction"], displacement=f["uB"],
        displacement_shaft=f["uJ"], force=-rot(F),
        moment=rot(M), position=rot(e), eccentricity=jnp.hypot(e[0], e[1]) / pr.c, attitude_angle=phi,
        line_of_centres_angle=jnp.angle(jnp.exp(1j * (pr.frame + jnp.arctan2(e[1], e[0])))),
        min_film=h[i, j], min_film_theta=theta[i], min_film_z=z[j], max_pressure=jnp.max(f["p_load"]),
        torque=TB, torque_shaft=TJ, torque_poiseuille=TB_p, torque_poiseuille_shaft=TJ_p,
        torque_viscoelastic=TvB, torque_viscoelastic_shaft=TvJ,
        side_leakage=leakage, supply_flow=supply, inlet_flow=inlet, power_loss=power,
        iterations=stats.iterations, residual=stats.residual, result=stats.result)


def solve(pr: Params, cfg: Config, start: str = "given") -> tuple[jax.Array, _solve.Stats]:
    """The converged unknowns x (implicitly differentiable) and the Newton record; ``start``:
    "given" (Newton from ``pr.x0``), "guess" (from the rigid estimate, :func:`_guess`) or
    "given_or_guess" (``pr.x0`` unless it is not finite: a coarse grid's failed solve)."""
    if start != "given":
        guess = jax.lax.stop_gradient(_guess(pr, cfg))
        x0 = guess if start == "guess" else jnp.where(jnp.all(jnp.isfinite(pr.x0)), pr.x0, guess)
        pr = dataclasses.replace(pr, x0=x0)
    block = (lambda x, aux, prm: linear_model(x, prm, cfg)) if _solved_by_linear_model(pr, cfg) else None
    return _solve.implicit_root(lambda prm: _steady(prm, cfg), lambda x, aux, prm: equations(x, prm, cfg)[0],
                                block)(pr)


@partial(jax.jit, static_argnums=(1, 2))
def _run(pr: Params, cfg: Config, start: str):
    x, stats = solve(pr, cfg, start)
    return _outputs(x, pr, cfg, stats)


NESTED_MIN_CELLS = 2048    # cold solves on n m >= this many cells start from the 2x coarser grid's solution


def _nests(options: FiniteJournalOptions) -> bool:
    """Whether a cold solve on this grid starts on the 2x coarser one (its nodes every other
    node of this one in theta and z, uniform or cosine spacing): on fine grids the rigid
    estimate is far from the root in Newton's terms (a 96 x 32 grid at eps = 0.8, L/D = 1:
    74 steps without converging directly, 9 on 48 x 16)."""
    return options.n * options.m >= NESTED_MIN_CELLS and options.n % 4 == 0 and options.m % 4 == 0


@partial(jax.jit, static_argnums=(2,))
def _refined(coarse: FiniteJournalResult, pr: Params, cfg: Config):
    """Unknowns on this grid from a solution on the 2x coarser one (the coarse nodes are the
    even ones here): the new nodes get the mean of their two neighbours, in theta, then in z;
    NaN where the coarse solve failed (then the rigid estimate starts, :func:`solve`)."""
    u = coarse.pressure / pr.p_ref + (coarse.film_fraction - 1.0)      # "jfo": the universal unknown
    u = jnp.stack([u, 0.5 * (u + jnp.roll(u, -1, axis=0))], axis=1).reshape(-1, u.shape[1])
    mid = 0.5 * (u[:, :-1] + u[:, 1:])
    u = jnp.concatenate([jnp.stack([u[:, :-1], mid], axis=2).reshape(u.shape[0], -1), u[:, -1:]], axis=1)
    x0 = _as_unknowns(u, coarse.position, pr, cfg)
    return jax.lax.stop_gradient(jnp.where(coarse.converged, x0, jnp.nan)).astype(pr.x0.dtype)


def setup(R, radial_clearance, viscosity, load, length, *, housing=None, shaft=None, omega_shaft=0.0,
          omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic", cavitation="reynolds",
          supply_angle=math.pi, supply_pressure=0.0, supply_width=1.0, tilt=None, temperature=None, shift=None,
          groove="fixed", options: FiniteJournalOptions = FiniteJournalOptions()):
    """Checked arguments -> (:class:`Params` with a zero start, :class:`Config`); ``groove``
    "fixed" (an axial groove at ``supply_angle``) or "circumferential"."""
    checks.one_of("groove", groove, GROOVES)
    checks.instance("options", options, FiniteJournalOptions, "a vjax.FiniteJournalOptions (with length=)")
    memory_revolutions(memory)
    _scene.scalars(checks.positive, R=R, radial_clearance=radial_clearance, viscosity=viscosity, length=length)
    _scene.scalars(checks.finite, omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle)
    _scene.scalars(checks.nonnegative, supply_pressure=supply_pressure)
    checks.one_of("cavitation", cavitation, reynolds.CAVITATION)
    Rv, cv = checks.values("R", R), checks.values("radial_clearance", radial_clearance)
    if Rv is not None and cv is not None and not np.all(cv < Rv):
        raise ValueError(f"radial_clearance must be < R, got radial_clearance={radial_clearance!r}, R={R!r}")
    wB, wJ = (checks.values(k, v) for k, v in (("omega_housing", omega_housing), ("omega_shaft", omega_shaft)))
    if wB is not None and wJ is not None and Rv is not None and cv is not None and wB * Rv + wJ * (Rv - cv) == 0:
        raise ValueError("omega_housing R + omega_shaft (R - radial_clearance) = 0: zero entrainment speed, "
                         "no hydrodynamic load capacity (omega_shaft, omega_housing)")
    sw = checks.values("supply_width", supply_width)
    if sw is None or not (0 < sw <= 1):
        raise ValueError(f"supply_width must be a concrete number in (0, 1] (a fraction of the length), "
                         f"got {supply_width!r}")
    checks.load(load)
    housing, shaft = bodies_at(R, radial_clearance, housing, shaft, temperature, shift)
    if any(b is not None and b.axial == "3d" for b in (housing, shaft)) and options.spacing != "uniform":
        raise ValueError("a 3D layer (axial='3d') needs uniform axial nodes (its cosine modes): "
                         "FiniteJournalOptions(spacing='uniform')")
    if tilt is not None:
        checks.finite("tilt", tilt)
        if np.shape(tilt) != (2,):
            raise ValueError(f"tilt must be two angles (gamma_x, gamma_y) (rad), got shape {np.shape(tilt)}")
    n, m = options.n, options.m
    s = _film2d.unit_nodes(m, options.spacing)     # z / (L/2)
    mask = np.zeros((n, m + 1))
    circumferential = groove == "circumferential"
    if circumferential:
        if supply_width != 1.0:
            raise ValueError("supply_width is the axial extent of an axial groove; a circumferential groove "
                             "(groove='circumferential') runs round the mid-width: leave supply_width at 1")
        mask[:, m // 2] = 1.0            # the mid-width nodes (m is even: z = 0 is a node)
    elif supply_angle is not None:
        _scene.scalars(checks.finite, supply_angle=supply_angle)
        sa = checks.values("supply_angle", supply_angle)
        if sa is None:
            raise ValueError("supply_angle must be a concrete number (it selects a grid column)")
        g = int(round(float(sa) % (2 * math.pi) / (2 * math.pi / n))) % n
        mask[g] = np.abs(s) <= float(sw) * (1 + 1e-12)
    floor = 1e-10 if jnp.result_type(float) == jnp.float64 else 1e-4
    rigid = housing is None and shaft is None
    cfg = Config(cavitation, n, m, float(options.tol if options.tol is not None else floor), options.max_iter,
                 krylov=options.krylov and not rigid)
    pr = _params(R, radial_clearance, viscosity, length, load, load_angle, tilt, omega_housing, omega_shaft,
                 supply_pressure, mask, float(circumferential), s, housing, shaft, unknowns=_unknowns(cfg),
                 memory=memory)
    return pr, cfg


def bodies_at(R, radial_clearance, housing, shaft, temperature, shift):
    """The checked housing and shaft bodies (None: rigid) at ``temperature`` under ``shift``."""
    housing = as_body("housing", housing, hole, _journal_film.HOUSINGS)
    shaft = as_body("shaft", shaft, disc, _journal_film.SHAFTS)
    check_fits("housing", housing, R)
    check_fits("shaft", shaft, R - radial_clearance)
    return _scene.at_temperature(temperature, shift, housing, shaft)


@partial(jax.jit, static_argnames=("unknowns", "memory"))
def _params(R, radial_clearance, viscosity, length, load, load_angle, tilt, omega_housing, omega_shaft,
            supply_pressure, groove, circumferential, s, housing, shaft, *, unknowns, memory):
    """Checked arguments -> :class:`Params` with a zero start, in one compiled program (eager,
    each of its operations would compile on a first call)."""
    dtype = jnp.result_type(float)
    f = lambda v: jnp.asarray(v, dtype)
    load = f(load)
    Wvec = jnp.stack([load * jnp.cos(load_angle), load * jnp.sin(load_angle)]) if load.ndim == 0 else load
    frame = jax.lax.stop_gradient(jnp.arctan2(Wvec[1], Wvec[0]))
    turn = lambda a: _rotation(frame).T @ a
    tilt = jnp.zeros(2, dtype) if tilt is None else f(tilt)
    W = jnp.hypot(Wvec[0], Wvec[1])
    v = 0.5 * (omega_housing * R + omega_shaft * (R - radial_clearance))
    return Params(R=f(R), RJ=f(R - radial_clearance), c=f(radial_clearance), L=f(length), eta=f(viscosity), v=f(v),
                  W=W, load=turn(Wvec), frame=frame, tilt=turn(tilt), ps=f(supply_pressure), omega_B=f(omega_housing),
                  omega_J=f(omega_shaft), p_ref=W / (2 * f(R) * f(length)), groove=f(groove),
                  circumferential=f(circumferential), s=f(s),
                  # the pressure pattern is fixed in space: it moves at -omega relative to each body
                  op_B=_operator(housing, R, groove.shape, length, -omega_housing, memory),
                  op_J=_operator(shaft, R - radial_clearance, groove.shape, length, -omega_shaft, memory),
                  compliance=f(1.0), smoothing=f(0.0), x0=jnp.zeros(unknowns + 2, dtype))


def _operator(body, R, shape, length, omega, memory):
    """A body's operator on the (n, m + 1) grid: None (rigid), the plane ring's for the slices, a
    3D layer's land operator."""
    if body is None:
        return None
    if body.axial == "3d":
        return body.land_operator(R, shape[0], shape[1] - 1, length, omega, memory)
    return body.operator(R, shape[0], omega, memory)


@partial(jax.jit, static_argnums=(3,))
def _start(pressure, position, pr: Params, cfg: Config):
    """Unknowns from a solution (:func:`_as_unknowns`), as a start that is not differentiated."""
    return jax.lax.stop_gradient(_as_unknowns(pressure / pr.p_ref, position, pr, cfg)).astype(pr.x0.dtype)


def finite_journal_bearing(R, radial_clearance, viscosity, load, length, *, housing=None, shaft=None,
                           omega_shaft=0.0, omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic",
                           cavitation="reynolds", supply_angle=math.pi, supply_pressure=0.0, supply_width=1.0,
                           tilt=None, temperature=None, shift=None, groove="fixed",
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
    Returns :class:`FiniteJournalResult`."""
    pr, cfg = setup(R, radial_clearance, viscosity, load, length, housing=housing, shaft=shaft,
                    omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle, memory=memory,
                    cavitation=cavitation, supply_angle=supply_angle, supply_pressure=supply_pressure,
                    supply_width=supply_width, tilt=tilt, temperature=temperature, shift=shift, groove=groove,
                    options=options)
    n, m = options.n, options.m
    # an aligned bearing's pressure is symmetric about mid-width (the grooves, the bodies and the
    # axial nodes are): the steady solve keeps the unknowns from mid-width to one end
    cfg = dataclasses.replace(cfg, half=tilt is None)
    pr = dataclasses.replace(pr, x0=jnp.zeros(_unknowns(cfg) + 2, pr.x0.dtype))
    start = "guess"
    if initial is not None:
        if not isinstance(initial, FiniteJournalResult) or initial.pressure.shape != (n, m + 1):
            raise ValueError(f"initial must be a FiniteJournalResult of the same grid (n = {n}, m = {m})")
        pr, start = dataclasses.replace(pr, x0=_start(initial.pressure, initial.position, pr, cfg)), "given"
    elif _nests(options):
        coarse = finite_journal_bearing(
            R, radial_clearance, viscosity, load, length, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
            omega_housing=omega_housing, load_angle=load_angle, memory=memory, cavitation=cavitation,
            supply_angle=supply_angle, supply_pressure=supply_pressure, supply_width=supply_width, tilt=tilt,
            temperature=temperature, shift=shift, groove=groove, throw=False,
            options=dataclasses.replace(options, n=n // 2, m=m // 2))
        pr, start = dataclasses.replace(pr, x0=_refined(coarse, pr, cfg)), "given_or_guess"
    sol = _run(pr, cfg, start)
    _solve.report("journal_bearing (finite length)", sol, throw)
    return sol


def check_supported(length, groove, cavitation):
    """Refuse, naming the argument, what the finite bearing does not have: a groove turning with
    the line of centres; and tilt without a length."""
    if length is None:
        raise ValueError("tilt and supply_width need a finite bearing: give its length (m)")
    if groove not in (None,) + GROOVES:
        raise ValueError(f"groove must be 'fixed' (an axial groove fixed in the bearing) or 'circumferential' "
                         f"with length=, got {groove!r}")
    checks.one_of("cavitation", cavitation, reynolds.CAVITATION)


def from_journal_arguments(R, radial_clearance, viscosity, load, *, length, housing, shaft, omega_shaft,
                           omega_housing, load_angle, memory, cavitation, supply_angle, supply_pressure,
                           supply_width, groove, tilt, temperature, shift, initial, options, throw):
    """:func:`vjax.journal_bearing`'s arguments -> :func:`finite_journal_bearing`."""
    check_supported(length, groove, cavitation)
    return finite_journal_bearing(R, radial_clearance, viscosity, load, length, housing=housing, shaft=shaft,
                                  omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle,
                                  memory=memory, cavitation=cavitation, supply_angle=supply_angle,
                                  supply_pressure=supply_pressure, supply_width=supply_width, tilt=tilt,
                                  temperature=temperature, shift=shift, groove=groove or "fixed", initial=initial,
                                  options=options, throw=throw)


def _pressure_solver(cells, pz, cfg: Config):
    """Solve with the rigid film's Jacobian d cells / d pz at pz (the pressures alone, the
    position held: block tridiagonal, :mod:`vjax._blocks`)."""
    return _blocks.ring_solver(_blocks.neighbourhood_blocks(cells, pz, cfg.n, cfg.m - 1))


def _whirl_response(pr: Params, cfg: Config, bodies, W):
    """The bodies' displacement (n, m + 1) (m, complex: u_B + u_J, each opening the film) under a
    small loading pressure dp (n, m + 1) (Pa) e^(i W t) on the pattern fixed in space; ``bodies``
    as in :func:`impedance`. Each theta mode k (full FFT) responds at its own frequency -k omega +
    W: an axial slice as its plane ring (:meth:`vjax.Body.whirl_symbol`), a 3D layer with its
    sections coupled through the DCT-I in z (:func:`vjax.layer3d_land.whirl_symbol`): O(N log N)."""
    n, m = cfg.n, cfg.m
    slices = [b for b in bodies if b[0] is not None and b[0].axial != "3d"]
    layers = [b for b in bodies if b[0] is not None and b[0].axial == "3d"]
    S = sum(body.whirl_symbol(R_b, n, omega_b, W) for body, R_b, omega_b in slices)
    S3 = sum(body.land_whirl_symbol(R_b, n, m, pr.L, omega_b, W) for body, R_b, omega_b in layers)

    def response(dp):
        P = jnp.fft.fft(dp, axis=0)
        U = (S[:, None] * P if slices else 0.0) + (idct1(S3 * dct1(P, axis=1), axis=1) if layers else 0.0)
        return pr.compliance * jnp.fft.ifft(U, axis=0)
    return response


@partial(jax.jit, static_argnums=(2, 5))
def impedance(x0, pr: Params, cfg: Config, bodies, whirl, tilt: bool = False):
    """Z(Omega) = K + i Omega C (complex, absolute axes) of the finite bearing about the steady
    unknowns x0 (whole width) at the whirl frequencies ``whirl`` (k,) (rad/s), and the
    :class:`~vjax._solve.Stats` of its linear solves. Z is (k, 2, 2) (N/m) in the journal's
    position; with ``tilt`` (k, 4, 4) in its position and tilt q = (X, Y, gamma_x, gamma_y) for
    the film's force and moment (F_x, F_y, M_x, M_y): blocks in N/m, N/rad, N m/m, N m/rad; the
    forces conjugate to q are (F_x, F_y, M_y, -M_x) (gamma_x turns the journal about y, gamma_y
    about -x). ``bodies``: ((body or None, radius, speed of the pattern relative to it), ...) for
    the housing and the shaft.

    The grid is fixed in space (the groove fixed in the bearing): a journal motion changes the
    film by -(dX + z dgamma_x) cos theta - (dY + z dgamma_y) sin theta and adds its rate to
    dh/dt. The bodies respond to the perturbed loading pressure by their whirl operator
    (:func:`_whirl_response`: each theta mode at its own frequency), which adds to the film and,
    times i Omega, to its rate; in a "jfo" cavity the liquid fraction has its own dynamics, h
    df/dt (so K and C depend on Omega even for rigid bodies: the cavity carries its liquid to
    where the film re-forms with a delay). With dU = M(Omega) S dp:

        (A_p + i Omega A_f + (A_U + i Omega A_Udot) M(Omega) S) dp = -(B_q + i Omega B_qdot) dq,
        dQ = G dp,   Z = -dQ/dq

    (S the loading pressure's slope: the half-Sommerfeld clip; A_f diagonal, R dtheta dz h in
    a "jfo" cavity's cells, 0 elsewhere). The products are matrix-free (one FFT each). With
    deformable bodies and ``cfg.krylov`` (``FiniteJournalOptions.linear_solver``, as Newton's
    steps) the solves are GMRES, one per whirl frequency and load column, preconditioned by the
    film's stencil with each node's own whirl compliance on its diagonal (as
    :func:`linear_model`: the exact block solve up to EXACT_WIDTH cells across, the multigrid
    V-cycle above); a relative residual above KRYLOV_ACCEPT is reported as a failure
    (``stats``). Otherwise a dense complex LU of the matrix from N products (small grids).
    Rigid bodies: the block solve alone, exact, up to EXACT_WIDTH cells across; GMRES with the
    V-cycle above."""
    n, m = cfg.n, cfg.m
    N = _unknowns(cfg)
    pz0 = x0[:N]
    theta, _ = grid(n)
    z = 0.5 * pr.L * pr.s
    f0 = fields(x0, pr, cfg)
    U0, zero, no_rate = f0["uB"] + f0["uJ"], jnp.zeros((n, m + 1), x0.dtype), jnp.zeros(N, x0.dtype)
    k = 4 if tilt else 2
    q0 = jnp.zeros(2 * k, x0.dtype)         # (dX, dY[, dgamma_x, dgamma_y]) and their rates
    rigid = all(body is None for body, _, _ in bodies)
    direct = rigid and m - 1 <= EXACT_WIDTH

    def cells(pz, U, Udot, rate, q):
        p = pr
        if tilt:                            # the tilt moves the journal centre at z by z dgamma
            p = dataclasses.replace(pr, tilt=pr.tilt + q[2:4])
            Udot = Udot - z[None, :] * (q[6] * jnp.cos(theta)[:, None] + q[7] * jnp.sin(theta)[:, None])
        motion = jnp.stack([q[0], q[1], q[k], q[k + 1]])
        return cell_residual(jnp.concatenate([pz, x0[N:]]), p, cfg, motion, deformation=(U, Udot), rate=rate)[0]

    def loads(pz):                          # the film's force (and moment) on the journal
        p_load = _loading(_interior(pz, cfg), pr, cfg)[2]
        return jnp.concatenate(_film2d.resultants(p_load, theta, z, pr.R))[:k]

    _, film = jax.linearize(lambda pz, U, Udot, rate: cells(pz, U, Udot, rate, q0), pz0, U0, zero, no_rate)
    B = jax.jacfwd(lambda q: cells(pz0, U0, zero, no_rate, q))(q0)                    # (N, 2 k)
    G = jax.jacrev(loads)(pz0)                                                         # (k, N)
    slope = reynolds.load_slope(pz0, cfg.cavitation).reshape(n, m - 1) * pr.p_ref
    loading = lambda v: _film2d.with_ends(slope * v.reshape(n, m - 1))                 # noqa: E731
    dense = not (rigid or cfg.krylov)       # the matrix from N products and its LU (small grids)
    if not dense:   # the film's stencils: in the pressures, in the cavity's rate, and through each
        # node's own loading in U and dU/dt (the preconditioner's)
        stencil = lambda fn: _blocks.stencil(fn, no_rate, n, m - 1)                    # noqa: E731
        C_p, C_f = stencil(lambda v: film(v, zero, zero, 0 * v)), stencil(lambda v: film(0 * v, zero, zero, v))
        if not rigid:
            C_U = stencil(lambda v: film(0 * v, loading(v), zero, 0 * v))
            C_Ud = stencil(lambda v: film(0 * v, zero, loading(v), 0 * v))
    unit = jnp.zeros((n, m + 1), x0.dtype).at[0, m // 2].set(1.0)

    def one(W):
        response = None if rigid else _whirl_response(pr, cfg, bodies, W)

        def matvec(v):                  # the complex system's product: the real linear map on Re and Im
            dU = jnp.zeros((n, m + 1), v.dtype) if rigid else response(loading(v))
            ri = lambda a: jnp.stack([a.real, a.imag])     # noqa: E731
            parts = jax.vmap(film)(ri(v), ri(dU), ri(1j * W * dU), ri(1j * W * v))
            return parts[0] + 1j * parts[1]

        b = (B[:, :k] + 1j * W * B[:, k:]).T                                               # (k, N)
        if dense:
            return G @ jnp.linalg.solve(jax.vmap(matvec)(jnp.eye(N, dtype=b.dtype)).T, b.T), jnp.zeros(())
        C = C_p + 1j * W * C_f
        if direct:                      # the stencil is the whole matrix: its exact block solve
            dp = jax.vmap(_stencil_solver(C))(b)
            residual = jnp.linalg.norm(b - jax.vmap(matvec)(dp)) / jnp.linalg.norm(b)
            return G @ dp.T, residual
        if not rigid:
            C = C + response(unit)[0, m // 2] * (C_U + 1j * W * C_Ud)
        # the preconditioner does not change the solution: no derivatives through its factors
        precondition = _stencil_solver(jax.lax.stop_gradient(C))
        dp, residual = jax.vmap(lambda r: _krylov.gmres(matvec, r, precondition, KRYLOV_TOL, KRYLOV_MAX_ITER))(b)
        return G @ dp.T, jnp.max(residual)

    Z, residual = jax.vmap(one)(whirl)
    accept = KRYLOV_ACCEPT if x0.dtype == jnp.float64 else 1e-3
    stats = _solve.Stats(jnp.ones(whirl.shape, jnp.int32), residual,
                         jnp.where(residual <= accept, _solve.SUCCESS, _solve.INNER_FAILED))
    rot = jnp.kron(jnp.eye(k // 2, dtype=x0.dtype), _rotation(pr.frame))
    return jnp.einsum("ij,wjk,lk->wil", rot, Z, rot), stats


def _bodies(R, radial_clearance, kw):
    """``impedance``'s bodies for the keyword arguments ``kw`` of :func:`finite_journal_bearing`:
    the pressure pattern is fixed in space, so it moves at -omega relative to each body."""
    housing, shaft = bodies_at(R, radial_clearance, kw.get("housing"), kw.get("shaft"), kw.get("temperature"),
                               kw.get("shift"))
    return ((housing, R, -kw.get("omega_housing", 0.0)), (shaft, R - radial_clearance, -kw.get("omega_shaft", 0.0)))


def tilt_coefficients(R, radial_clearance, viscosity, load, length, *, whirl=None, initial=None, throw=True, **kw):
    """Steady :class:`FiniteJournalResult` and the 4 x 4 stiffness and damping in the journal's
    position and tilt (:func:`impedance` with ``tilt``; absolute axes), for a rotor model that
    carries the journal's angular motion (a misaligned or short, stiff bearing): dQ = -(K dq +
    C dq/dt) for q = (X, Y, gamma_x, gamma_y), Q = (F_x, F_y, M_x, M_y). ``whirl`` None: K and C
    (4, 4) at rest (rigid bodies: at every whirl frequency); an array (k,) (rad/s): (k, 4, 4),
    deformable bodies' at their own frequencies. ``kw``: the keyword arguments of
    :func:`finite_journal_bearing`."""
    if kw.get("cavitation", "reynolds") in ("half_sommerfeld", "jfo"):
        raise ValueError(f"cavitation={kw['cavitation']!r}: the tilt coefficients take 'reynolds' or 'sommerfeld'")
    at = jnp.atleast_1d(jnp.asarray(0.0 if whirl is None else whirl, jnp.result_type(float)))
    if at.ndim != 1:
        raise ValueError(f"whirl must be a number or a 1-D array of whirl frequencies (rad/s), got shape {at.shape}")
    checks.finite("whirl", at)
    steady, _, K, C = _solved_coefficients("tilt_coefficients", R, radial_clearance, viscosity, load, length, at,
                                           True, initial, throw, kw)
    return (steady, K[0], C[0]) if whirl is None else (steady, K, C)


def _solved_coefficients(caller, R, radial_clearance, viscosity, load, length, whirl, tilt, initial, throw, kw):
    """The steady solve of the keyword arguments ``kw`` of :func:`finite_journal_bearing` and its
    :func:`coefficients` (steady, Z, K, C); a failed whirl solve reported under ``caller``."""
    steady = finite_journal_bearing(R, radial_clearance, viscosity, load, length, initial=initial, throw=throw, **kw)
    pr, cfg = setup(R, radial_clearance, viscosity, load, length, **kw)
    Z, K, C, stats = coefficients(steady, pr, cfg, _bodies(R, radial_clearance, kw), whirl, tilt)
    _solve.report(f"{caller} (the finite bearing's whirl solves)", stats, throw)
    return steady, Z, K, C


def coefficients(steady: FiniteJournalResult, pr: Params, cfg: Config, bodies, whirl, tilt: bool = False):
    """(Z, K, C, stats) (complex N/m, N/m, N s/m; (k, 2, 2), or (k, 4, 4) with ``tilt``; absolute
    axes; the :class:`~vjax._solve.Stats` of :func:`impedance`'s solves) at the whirl frequencies
    ``whirl`` (k,) about a converged :class:`FiniteJournalResult` of the bearing ``pr``, ``cfg``
    (the steady solve of the same arguments; ``bodies`` as in :func:`impedance`); its pressure
    recovered for the half-Sommerfeld film (whose result holds the clipped pressure) by one more
    solve. C = Im Z / Omega, at Omega = 0 its limit d(Im Z)/dOmega."""
    # "jfo": the universal unknown, the film fraction - 1 in the cavity
    x0 = _as_unknowns(steady.pressure / pr.p_ref + (steady.film_fraction - 1.0), steady.position, pr, cfg)
    if cfg.cavitation == "half_sommerfeld":
        x0, _ = solve(dataclasses.replace(pr, x0=jax.lax.stop_gradient(x0)), cfg)
    Z, dZ, stats = jax.jvp(lambda w: impedance(x0, pr, cfg, bodies, w, tilt), (whirl,), (jnp.ones_like(whirl),),
                           has_aux=True)
    at_rest = (whirl == 0)[:, None, None]
    C = jnp.where(at_rest, dZ.imag, Z.imag / jnp.where(at_rest, 1.0, whirl[:, None, None]))
    return Z, Z.real, C, stats


def finite_coefficients(R, radial_clearance, viscosity, load, length, whirl, *, initial=None, throw=True, **kw):
    """Steady :class:`FiniteJournalResult` and its (Z, K, C) (complex N/m, N/m, N s/m; (k, 2, 2),
    absolute axes) at the whirl frequencies ``whirl`` (k,) for
    ``vjax.journal_coefficients(..., length=L)``; ``kw``: the keyword arguments of
    :func:`finite_journal_bearing` (rigid bodies and no "jfo" cavity: K, C independent of the whirl)."""
    return _solved_coefficients("journal_coefficients", R, radial_clearance, viscosity, load, length, whirl,
                                False, initial, throw, kw)


@partial(jax.jit, static_argnums=(2,))
def force_at(x, pr: Params, cfg: Config, motion):
    """Film force on the journal (N, grid axes) with the journal held at the position of x
    (its last two entries, e/c) plus ``motion`` (dX, dY, dX/dt, dY/dt) (m, m/s): the nonlinear
    cell equations solved by Newton for the pressures from x's (the position control the
    dynamic coefficients linearize); returns (force, :class:`~vjax._solve.Stats`). Rigid
    bodies only: a deformable body's first mode is tied to the load (:func:`deformations`),
    which position control does not hold."""
    if not _rigid(pr):
        raise ValueError("force_at: rigid bodies only (housing=None, shaft=None)")
    N = _unknowns(cfg)
    cells = lambda pz: cell_residual(jnp.concatenate([pz, x[N:]]), pr, cfg, motion)[0]
    linear_solve = lambda pz, state, r: _pressure_solver(cells, pz, cfg)(-r)    # noqa: E731
    pz, _, stats = _solve.newton(lambda pz, s: (cells(pz), s, True), x[:N], None, tol=cfg.tol,
                                 max_iter=cfg.max_iter, linear_solve=linear_solve)
    return cell_residual(jnp.concatenate([pz, x[N:]]), pr, cfg, motion)[1], stats
