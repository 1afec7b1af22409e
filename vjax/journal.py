"""Visco-elastohydrodynamic (VEHL) infinitely long journal bearing (thesis Chapter 3).

Geometry and frames
-------------------
Bearing bore (the ``housing``) of radius ``R`` (centre O), journal (the ``shaft``) of radius
R_J = R - c with c the ``radial_clearance`` (centre O'). The ring grid theta_i = 2 pi i / n is attached to the **line of
centres**: theta = 0 points from O towards O' (where the rigid gap is smallest). The load
line is at absolute angle ``load_angle`` (x axis = 0, counter-clockwise positive); the line
of centres is at absolute angle ``load_angle + attitude_angle``. Everything is rotationally
invariant (circulant rings, uniform surface speeds), so this frame loses nothing.

Film (positive-into-the-body convention of :mod:`vjax.operator`)
----------------------------------------------------------------
    h(theta) = c (1 - eps cos theta) + u_B(theta) + u_J(theta)

u_B: radial displacement of the bore, positive outward (into the bearing body); u_J: of
the journal, positive inward (into the journal). Fluid pressure pushes both surfaces away
from the film, so both *increase* h. The thesis writes h = h0 + g0 + u_r^B - u_r^J with
both u_r positive along the outward radius: the same thing (u_J = -u_r^J).
Deformations are the steady-state viscoelastic ring operators of each body at the speed
of the pressure pattern relative to it: the pattern is fixed in space, so it moves at
-omega_housing relative to the bearing (a bare Material: :func:`~vjax.hole`, A.45) and at
-omega_shaft relative to the journal (a bare Material: :func:`~vjax.disc`, A.60), or with
:func:`~vjax.half_plane` bodies (the comparison of Fig. 3.4). A hole's or disc's log
reference length ``ref_length`` (1 m as in the thesis) sets the n = 1 (rigid translation)
part of its response: it shifts ``eccentricity`` (which can exceed 1 with a soft liner) but
not ``eccentricity_effective`` (first Fourier mode of h over c).

Reynolds equation and cavitation (Eq. 3.41)
-------------------------------------------
Finite volumes on the ring with ``cavitation`` "reynolds" (default, Swift-Stieber as a
Fischer-Burmeister complementarity), "jfo" (mass-conserving Jakobsson-Floberg-Olsson /
Elrod-Adams conditions: pressure and film fraction as one universal unknown),
"half_sommerfeld" or "sommerfeld": :mod:`vjax.reynolds`. With "jfo" the cavity is a
striated film of liquid fraction ``film_fraction`` < 1 that carries only the Couette flow of
its liquid, so the shear stress of the Couette flow there acts on that fraction too.
The entrainment speed is v = (omega_B R_B + omega_J R_J)/2.

**Pressure datum.** A lubricant supply groove at ``supply_angle`` (snapped to the nearest
element) holds ``supply_pressure`` (gauge, Pa; default 0 = ambient) and supplies whatever
flow the film needs. Without it the 360-degree problem with Reynolds conditions is
degenerate: any constant can be added to the pressure of a full film and the cavitated
state is not fixed, so there is no unique solution. Where the groove is (``groove=``):

- ``"line_of_centres"`` (default, the classical theory): the groove turns with the line of
  centres, ``supply_angle`` measured from it (default pi, the largest rigid clearance);
- ``"fixed"``: the groove is fixed in the bearing, ``supply_angle`` measured from the load
  direction (default pi: opposite the load, the usual design). The grid is then attached to
  the load line and the line of centres turns over it: the film is
  c (1 - eps cos(theta - attitude)) + u_B + u_J on the grid angle theta. The result's
  arrays are on that grid, their ``theta`` given from the line of centres (theta_grid -
  attitude) as for the default.

Load control: the pressure force on the journal balances ``load`` (N/m, the external force
on the journal); the eccentricity ratio ``eps`` and the attitude angle are unknowns.
Viscous shear forces on the journal are O(c/R) of the load and are not included in
this balance (nor in classical theory).

Torques, dissipation (Eq. 3.43-3.46)
------------------------------------
All torques are exerted **by the fluid on the body**, counter-clockwise positive, N m/m.
``force`` is the pressure force the film exerts on the housing (absolute x, y; equal to the
load at equilibrium).
Shear tractions (3.45) at the faces: tau_B = -h/2 dp/ds - eta (U_B - U_J)/h,
tau_J = -h/2 dp/ds + eta (U_B - U_J)/h (U = omega R, surface speeds), on the film arc
ds = R_B dtheta. The pressure on a *deformed* profile has a moment about the body's
centre: -R_B int p du/dtheta dtheta (central differences); this is the viscoelastic
torque ``torque_viscoelastic`` (housing) / ``torque_viscoelastic_shaft``, and
-omega times it is the hysteretic dissipation (Eq. 3.46 with the sign fixed so that it is
non-negative for both bodies: power into a body = int p du/dt ds, du/dt = -Omega du/dtheta
for a pattern moving at Omega relative to it):

- ``torque`` (on the housing) about O: R_B^2 int tau_B dtheta + torque_viscoelastic.
- ``torque_shaft`` about the journal's own centre O': R_J R_B int tau_J dtheta +
  torque_viscoelastic_shaft. ``torque_shaft_about_O`` = torque_shaft + e x F (the
  thesis's choice, = -torque up to O(c/R) by the fluid's moment balance).
- Power balance (exact for the discrete equations with Reynolds/Sommerfeld conditions):
  -omega_B torque - omega_J torque_shaft + p_s Q_s + sum_i p_i (q_{i+1/2} - q_{i-1/2})
  = dissipation_fluid + dissipation_housing + dissipation_shaft, the sum (over the cells but
  the groove's) the pressure energy of the flow let out within the rupture's cell, the only
  pressurized cell with a net outflow (:func:`vjax.reynolds.rupture_outflow`; ~1e-8 of the power).

Solver
------
Unknowns p/p_ref (n values), eps, attitude: n + 2 equations (cell balances / FB, groove
datum, two force components). The core's damped Newton (:func:`vjax._solve.newton`; steps
giving h <= 0 are rejected), each step solved (``options.linear_solver``) with the exact
dense AD Jacobian (LU, O(n^3)) or matrix-free by GMRES (Jacobian-vector products,
O(n log n)) preconditioned by the film's cyclic tridiagonal Jacobian plus the bodies' compliance on
its lowest Fourier modes (:func:`vjax._journal_film.linear_model`; exact for rigid bodies); "auto" switches to
GMRES above n = 1024, and the implicit derivatives use the same solve. The bodies'
deformation takes its Fourier mode 1 (a rigid translation) from the load, which the film
force equals at the root, not from the iterate's pressure: the same root, without a
translation of up to hundreds of clearances for Newton to find (docs/theory.md §10).
``options.strategy="auto"`` first tries Newton from the rigid half-Sommerfeld estimate (with
bodies on n >= 128 elements, rigid on n >= 512, from the solution on a 4x coarser grid,
interpolated by C1 cubics: a second compiled solver, which pays only where the direct start
needs many steps or fails; or from ``initial``, e.g. the previous point of a sweep); if it fails or lands on the spurious
branch (effective eccentricity <= 0: the supply at the minimum gap), it continues from a
rigid solution at a higher entrainment speed (such that the rigid eccentricity is about
0.6), ramping the compliance in and the speed down over at most ``options.stages`` Newton
solves. Derivatives of the converged solution are implicit
(:func:`vjax._solve.implicit_root`), not through the iterations.

Convergence: ``iterations`` (Newton steps on the final grid, summed over continuation
stages), ``stages`` (continuation stages used, 0 = direct), ``residual`` (max-norm of the
scaled equations), ``result`` (0 = converged on the physical branch). ``throw=True``
raises :class:`~vjax.ConvergenceError` on failure, inside ``jit`` too.
"""
from __future__ import annotations

import dataclasses
import math
from functools import partial

import jax
import jax.numpy as jnp

from . import _scene, _solve, checks, journal_finite, reference, reynolds
from . import _journal_film as film
from .operator import RingOperator

NESTED_MIN_N = 128   # "auto" cold starts on n >= this many elements begin on a 4x coarser grid,
NESTED_MIN_N_RIGID = 512   # rigid ones from this many (direct: 19 steps at n = 256, 27 at 512, > 40 at 1024)
KRYLOV_MIN_N = 1024  # linear_solver="auto": dense LU up to this many elements, GMRES above


@dataclasses.dataclass(frozen=True)
class JournalOptions:
    """Static options of :func:`journal_bearing`: ``n`` elements (even, >= 16), Newton
    tolerance ``tol`` (max-norm of the scaled equations; None: 1e-10 in float64, raised to
    the round-off floor 4 eps (n / 2 pi)^2 of the cell balances above n ~ 4000 (a second
    difference of pressures over a cell width squared); 1e-4 in float32), ``max_iter``
    Newton steps per solve, at most ``stages`` continuation solves,
    ``strategy`` "auto" (direct Newton, continuation if that fails), "newton" or
    "continuation"; ``linear_solver`` of each Newton step: "dense" (LU of the AD Jacobian,
    O(n^3)), "krylov" (matrix-free GMRES preconditioned by the film's tridiagonal Jacobian
    plus the bodies' compliance on its lowest ``krylov_modes`` Fourier modes, O(n log n)
    per product) or "auto" (Krylov above n = 1024)."""

    n: int = 256
    tol: float | None = None
    max_iter: int = 40
    stages: int = 40
    strategy: str = "auto"
    linear_solver: str = "auto"
    krylov_modes: int = 32

    def __post_init__(self):
        checks.option_count("n", self.n, 16)
        if self.n % 2:
            raise ValueError(f"n must be even, got {self.n}")
        if self.tol is not None:
            checks.option_number("tol", self.tol)
        checks.option_count("max_iter", self.max_iter)
        checks.option_count("stages", self.stages)
        checks.one_of("strategy", self.strategy, ("auto", "newton", "continuation"))
        checks.one_of("linear_solver", self.linear_solver, ("auto", "dense", "krylov"))
        checks.option_count("krylov_modes", self.krylov_modes, 2)

    @property
    def krylov(self) -> bool:
        return self.linear_solver == "krylov" or (self.linear_solver == "auto" and self.n > KRYLOV_MIN_N)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class JournalResult(_scene.SceneResult):
    """Solution of :func:`journal_bearing` (SI units, per unit axial length).

    Arrays on the ring grid (line-of-centres frame, theta = 0 at the smallest rigid gap):
    ``theta`` (rad), ``pressure`` (Pa, gauge), ``film`` h (m), ``displacement`` of the
    housing's bore u_B (m, outward, into the housing), ``displacement_shaft`` u_J (m, inward,
    into the journal).

    ``force``: pressure force of the film on the housing (N/m, absolute x, y; the load at
    equilibrium). ``film_fraction``: liquid fraction of the film (1 in a full film, below 1
    in a "jfo" cavity; 1 everywhere for the other conditions). ``torque``: by the fluid on
    the housing about O; ``torque_shaft``: on the journal about O'; ``torque_shaft_about_O``; ``torque_viscoelastic``,
    ``torque_viscoelastic_shaft``: the pressure-on-deformed-profile parts (N m/m, CCW
    positive; see the module docstring). ``friction_radius``: |torque|/|force| (m).
    ``eccentricity`` eps = e/c of the journal centre; ``eccentricity_effective`` first Fourier
    mode of h over c (positive on the physical branch; independent of the log reference
    length); ``attitude_angle`` (rad, signed angle from the load line to the line of centres,
    counter-clockwise positive); ``line_of_centres_angle`` (absolute, rad); ``min_film`` (m);
    ``rupture_angle`` (rad, line-of-centres frame, where the film cavitates; for "sommerfeld"
    the downstream zero of p); dissipation (W/m) ``dissipation_fluid``,
    ``dissipation_housing``, ``dissipation_shaft``; ``supply_flow`` Q_s (m^2/s, net outflow of
    the groove cell; can be negative: the Swift-Stieber cavity does not conserve mass);
    ``hersey`` H = eta v R_B/|F| (signed, as the thesis).

    Convergence: ``iterations`` (Newton steps on this grid, summed over stages; a nested
    coarse-grid start is not counted), ``stages`` (continuation stages, 0 = direct),
    ``residual`` (max-norm of the scaled equations), ``result``; ``converged`` is ``result == 0``.
    """

    theta: jax.Array
    pressure: jax.Array
    film: jax.Array
    displacement: jax.Array
    displacement_shaft: jax.Array
    film_fraction: jax.Array
    force: jax.Array
    torque: jax.Array
    torque_shaft: jax.Array
    torque_shaft_about_O: jax.Array
    torque_viscoelastic: jax.Array
    torque_viscoelastic_shaft: jax.Array
    friction_radius: jax.Array
    eccentricity: jax.Array
    eccentricity_effective: jax.Array
    attitude_angle: jax.Array
    line_of_centres_angle: jax.Array
    min_film: jax.Array
    rupture_angle: jax.Array
    dissipation_fluid: jax.Array
    dissipation_housing: jax.Array
    dissipation_shaft: jax.Array
    supply_flow: jax.Array
    hersey: jax.Array
    iterations: jax.Array
    stages: jax.Array
    residual: jax.Array
    result: jax.Array


def _staged(pr: film.Params, t):
    """Problem at continuation parameter t in [0, 2].

    t in [0, 1]: compliance ramped in (factor t) at M times the entrainment speed, with M
    such that the rigid bearing runs at eps ~ 0.6 (thick film, mild coupling);
    t in [1, 2]: full compliance, speed M^(2 - t) (geometric) down to the target.
    """
    M = jnp.maximum(1.0, film.load_number(pr) / reference.half_sommerfeld_load(0.6))
    m = M ** jnp.clip(2.0 - t, 0.0, 1.0)
    s = jnp.clip(t, 0.0, 1.0)
    scale = lambda op: None if op is None else RingOperator(op.symbol * s, op.n)
    return dataclasses.replace(pr, v=pr.v * m, q_ref=pr.q_ref * m, op_B=scale(pr.op_B), op_J=scale(pr.op_J)), m


def _continuation(pr, cfg, x0=None, subcell=True):
    """Adaptive continuation in t (see :func:`_staged`, :func:`vjax._solve.continuation`): at most
    ``stages`` Newton solves; with ``x0`` (``strategy="auto"``) a direct solve from it first;
    ``subcell`` as :func:`_solve_steady`."""
    n = pr.x0.shape[0] - 2
    guess = film.guess(_staged(pr, 0.0)[0], n, cfg)
    # the intermediate stages are only starts: their rupture on a face will do
    solve = lambda x, t: film.newton(x, _staged(pr, t)[0], cfg, subcell=subcell & (t >= 2.0))     # noqa: E731
    return _solve.continuation(solve, guess, x0, cfg.options.stages)


def _jfo_start(x, pr: film.Params, cfg: film.Config):
    """JFO unknowns from a Reynolds solution x: its pressure where positive; in the cavity the
    film fraction that carries the flow leaving the pressurized film (the flux at the
    pressure peak) as a Couette flow, f = Q / (v h), as the universal variable f - 1."""
    n = x.shape[0] - 2
    f = film.fields(x, pr, dataclasses.replace(cfg, cavitation="reynolds"))
    flow = f["q"][jnp.argmax(f["p"])]
    fraction = jnp.clip(flow / (pr.v * f["h"]), 0.0, 1.0)
    cavity = f["p"] <= 1e-9 * jnp.max(f["p"])
    return x.at[:n].set(jnp.where(cavity, fraction - 1.0, x[:n]))


def _solver(pr: film.Params, cfg: film.Config):
    """Steady solution; "jfo" starts from the Reynolds solution (the same pressure where the
    film re-forms only at the groove), whose cavity it fills with the mass-conserving film."""
    if cfg.cavitation != "jfo":
        return _solve_steady(pr, cfg)
    n = pr.x0.shape[0] - 2
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
    """Steady solution: Newton, or continuation (compliant bodies); ``subcell`` False leaves a
    Reynolds rupture on a cell face (a start for JFO, :func:`vjax._journal_film.newton`)."""
    compliant = pr.op_B is not None or pr.op_J is not None
    x0 = jax.lax.stop_gradient(pr.x0)
    strategy = cfg.options.strategy if compliant else "newton"
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


def _outputs(x, pr: film.Params, cfg: film.Config, stats, stages):
    n = x.shape[0] - 2
    f = film.fields(x, pr, cfg)
    p, h, hf, dpds, th, dth = f["p"], f["h"], f["hf"], f["dpds"], f["theta"], f["dth"]
    R, RJ, eta, c = pr.R, pr.RJ, pr.eta, pr.c
    eps, phi = x[n], x[n + 1]
    pres = f["p_load"]
    dU = pr.omega_B * R - pr.omega_J * RJ
    # a striated ("jfo") cavity shears only its liquid: the upwind fraction of each face
    liquid = reynolds.face_fraction(f["fraction"], pr.v)
    tauB = -0.5 * hf * dpds - liquid * eta * dU / hf
    tauJ = -0.5 * hf * dpds + liquid * eta * dU / hf
    central = lambda u: 0.5 * (jnp.roll(u, -1) - jnp.roll(u, 1))
    CvB = -R * jnp.sum(pres * central(f["uB"]))
    CvJ = -R * jnp.sum(pres * central(f["uJ"]))
    CB = R * R * dth * jnp.sum(tauB) + CvB
    CJ = RJ * R * dth * jnp.sum(tauJ) + CvJ
    # pressure force on the journal in the line-of-centres frame (th: angles from it); the
    # housing gets minus it
    off = film.offset(x, cfg)
    th = th - off
    Fx = -R * dth * jnp.sum(pres * jnp.cos(th))
    Fy = -R * dth * jnp.sum(pres * jnp.sin(th))
    Df = R * dth * jnp.sum(hf**3 * dpds**2 / (12 * eta) + liquid * eta * dU**2 / hf)
    g = pr.groove
    gamma = pr.load_angle + phi
    rot = jnp.array([[jnp.cos(gamma), -jnp.sin(gamma)], [jnp.sin(gamma), jnp.cos(gamma)]])
    force = -rot @ jnp.stack([Fx, Fy])
    return JournalResult(
        theta=th, pressure=pres, film=h, displacement=f["uB"], displacement_shaft=f["uJ"],
        film_fraction=f["fraction"], force=force,
        torque=CB, torque_shaft=CJ, torque_shaft_about_O=CJ + eps * c * Fy, torque_viscoelastic=CvB,
        torque_viscoelastic_shaft=CvJ, friction_radius=jnp.abs(CB) / jnp.hypot(Fx, Fy), eccentricity=eps,
        eccentricity_effective=film.effective_eps(h, c, off), attitude_angle=phi,
        line_of_centres_angle=jnp.angle(jnp.exp(1j * gamma)), min_film=jnp.min(h),
        # half-Sommerfeld: the zero crossing of the unclipped (full-Sommerfeld) pressure
        rupture_angle=reynolds.rupture_angle(p, th, pr.v, "sommerfeld" if cfg.cavitation == "half_sommerfeld"
                                             else cfg.cavitation),
        dissipation_fluid=Df, dissipation_housing=-pr.omega_B * CvB, dissipation_shaft=-pr.omega_J * CvJ,
        supply_flow=f["q"][g] - f["q"][(g - 1) % n], hersey=eta * pr.v * R / pr.W,
        iterations=stats.iterations, stages=stages, residual=stats.residual, result=stats.result)


@partial(jax.jit, static_argnums=(1,))
def _run(pr: film.Params, cfg: film.Config):
    residual = lambda x, aux, prm: film.equations(x, prm, cfg)[0]
    linear_solver = None
    if cfg.options.krylov:
        def linear_solver(x, aux, prm):
            solve, solve_t, matvec, matvec_t = film.linear_model(x, prm, cfg)
            return film.gmres(matvec, solve), film.gmres(matvec_t, solve_t)
    x, (stats, stages) = _solve.implicit_root(lambda prm: _solver(prm, cfg), residual, linear_solver)(pr)
    return _outputs(x, pr, cfg, stats, stages)


def journal_bearing(R, radial_clearance, viscosity, load, *, housing=None, shaft=None, omega_shaft=0.0,
                    omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic", cavitation: str = "reynolds",
                    supply_angle=math.pi, supply_pressure=0.0, groove: str | None = None, temperature=None,
                    shift=None, initial: "JournalResult | None" = None, options: JournalOptions = JournalOptions(),
                    throw: bool = True, length=None, tilt=None, supply_width=1.0) -> JournalResult:
    """Steady state of an infinitely long (visco)elastic journal bearing under a given load.

    See the module docstring for the equations, conventions and solver. Configurations of
    thesis Section 3.2: HS (``housing=`` soft, ``shaft=None``), SH, SS; both ``None`` is
    the rigid bearing.

    Args:
      R: bore radius R_B (m). radial_clearance: c = R_B - R_J (m), 0 < c < R.
      viscosity: lubricant viscosity eta (Pa s), isoviscous.
      load: external force on the journal (N/m): a vector (Fx, Fy), or a magnitude with
        ``load_angle`` (rad, default -pi/2: downward).
      housing, shaft: bodies of the bearing and the journal: a :class:`~vjax.Material` (hole,
        resp. disc, with ``ref_length`` 1 m), a body (housing: hole, liner or half_plane; shaft:
        disc, sleeve or half_plane), or None (rigid, the default).
      omega_shaft, omega_housing: angular velocities of journal and bearing (rad/s, CCW > 0).
        Their entrainment speed v = (omega_B R_B + omega_J R_J)/2 must not be zero.
      memory: "periodic", "thesis" or a number of revolutions (see :mod:`vjax.operator`).
      cavitation: "reynolds" (default), "jfo" (mass-conserving), "half_sommerfeld" or
        "sommerfeld".
      supply_angle: groove position (rad, default pi), from the line of centres or, with
        ``groove="fixed"``, from the load direction (pi: opposite the load).
      supply_pressure: groove gauge pressure (Pa, default 0).
      groove: "line_of_centres" (the groove turns with it, the classical theory; the default
        of the infinitely long bearing) or "fixed" (in the bearing, as in a real bearing; the
        default of a finite one, which also takes "circumferential": a groove round the
        mid-width at ``supply_pressure``); see the module docstring.
      temperature, shift: evaluate the materials at ``temperature`` (C) under ``shift``.
      initial: a previous :class:`JournalResult` (same n) to start Newton from (sweeps).
      options: :class:`JournalOptions` (grid, tolerance, iteration caps, strategy; static).
      throw: raise :class:`~vjax.ConvergenceError` on failure (inside jit too); with False
        inspect ``converged`` and ``result``.
      length: axial length L (m) of a finite bearing (None: infinitely long, per unit length).
        With it the film covers the land (:mod:`vjax.journal_finite`): ``load`` is the total
        (N), the groove is fixed in the bearing at ``supply_angle`` from the load (None: no
        groove) over the central fraction ``supply_width`` of L (a feed hole: its diameter over
        L) or runs round the mid-width (``groove="circumferential"``), the journal may be tilted by
        ``tilt`` (gamma_x, gamma_y) (rad), ``options`` is a :class:`~vjax.FiniteJournalOptions`,
        the bodies deform as plane-strain slices (each axial section as the ring under its own
        pressure); returns a :class:`~vjax.FiniteJournalResult` (SI totals).

    >>> import jax; jax.config.update("jax_enable_x64", True)
    >>> sol = journal_bearing(0.05, 5e-5, 0.01, 2e4, omega_shaft=100.0, options=JournalOptions(n=64))
    >>> bool(sol.converged), 0 < float(sol.eccentricity) < 1
    (True, True)
    """
    if length is not None or tilt is not None or supply_width != 1.0:
        return journal_finite.from_journal_arguments(
            R, radial_clearance, viscosity, load, length=length, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
            omega_housing=omega_housing, load_angle=load_angle, memory=memory, cavitation=cavitation,
            supply_angle=supply_angle, supply_pressure=supply_pressure, supply_width=supply_width, groove=groove,
            tilt=tilt, temperature=temperature, shift=shift, initial=initial, throw=throw,
            options=journal_finite.FiniteJournalOptions() if options == JournalOptions() else options)
    groove = "line_of_centres" if groove is None else groove
    checks.instance("options", options, JournalOptions, "a vjax.JournalOptions")
    pr, cfg, housing, shaft = film.setup(
        R, radial_clearance, viscosity, load, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
        omega_housing=omega_housing, load_angle=load_angle, memory=memory, cavitation=cavitation,
        supply_angle=supply_angle, supply_pressure=supply_pressure, temperature=temperature, shift=shift,
        options=options, groove=groove)
    n, p_ref, dtype = options.n, pr.p_ref, pr.x0.dtype
    if initial is not None:
        if not isinstance(initial, JournalResult) or any(a.shape != (n,) for a in (initial.pressure,
                                                                                   initial.film_fraction)):
            raise ValueError(f"initial must be a JournalResult of the same bearing (n = {n})")
        x0 = film.start(initial.pressure, initial.film_fraction, initial.eccentricity, initial.attitude_angle, p_ref)
    elif options.strategy == "auto" and n % 4 == 0 and n >= (NESTED_MIN_N if housing is not None or shaft is not None
                                                             else NESTED_MIN_N_RIGID):
        # Nested start: solve on a 4x coarser grid, interpolate. Most Newton steps from a
        # cold start are spent far from the solution, where a coarse grid is as good and
        # (n/4)^3 cheaper. If the coarse start misleads, "auto" still falls back.
        coarse = journal_bearing(
            R, radial_clearance, viscosity, load, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
            omega_housing=omega_housing, load_angle=load_angle, memory=memory, cavitation=cavitation,
            supply_angle=supply_angle, supply_pressure=supply_pressure, groove=groove,
            options=dataclasses.replace(options, n=n // 4), throw=False)
        x0 = film.start(_refine_periodic(coarse.pressure, n), 1.0, coarse.eccentricity, coarse.attitude_angle, p_ref)
    else:
        x0 = film.guess(pr, n, cfg)
    sol = _run(dataclasses.replace(pr, x0=jax.lax.stop_gradient(x0).astype(dtype)), cfg)
    # the hint only for a failure it can explain (concrete values; its eager operations
    # would otherwise compile on every first call)
    failed = throw and checks.is_concrete(sol.result) and int(sol.result) != _solve.SUCCESS
    _solve.report("journal_bearing" + (_failure_hint(pr, n) if failed else ""), sol, throw)
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


