"""Visco-elastohydrodynamic (VEHL) infinitely long journal bearing (thesis Chapter 3).

Geometry and frames
-------------------
Bearing bore of radius ``R_bearing`` (centre O), journal of radius R_J = R_bearing -
``clearance`` (centre O'). The ring grid theta_i = 2 pi i / n is attached to the **line of
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
-omega_bearing relative to the bearing (Green's function A.45, hole in a plane) and at
-omega_journal relative to the journal (A.60, cylinder fixed at its centre), or both with
the half-plane kernel (``green="half_plane"``, the comparison of Fig. 3.4). The log terms'
reference length ``ref_length`` (default 1 m as in the thesis) sets the n = 1 (rigid
translation) part of each ring's response: it shifts ``eccentricity`` (which can exceed 1
with a soft liner) but not ``eccentricity_effective`` (first Fourier mode of h over c).

Reynolds equation and cavitation (Eq. 3.41)
-------------------------------------------
    d/ds (h^3/(12 eta) dp/ds) = v dh/ds,  s = R_B theta,  v = (omega_B R_B + omega_J R_J)/2

discretized by finite volumes on the ring (pressure at the element centres, fluxes
q = -h^3/(12 eta) dp/ds + v h at the faces with h at a face the mean of its neighbours):
second order. Cavitation (``cavitation=``):

- ``"reynolds"`` (default): Swift-Stieber / Reynolds conditions (p >= 0, p = dp/ds = 0 at
  rupture) as the linear complementarity problem p >= 0, w >= 0, p w = 0 with w the net
  outflow of a cell, written as the Fischer-Burmeister equation
  p + w - sqrt(p^2 + w^2) = 0 (a semismooth equation: Newton with an AD Jacobian works and
  the converged solution is differentiable where the cavitated set does not change).
- ``"half_sommerfeld"``: the full-Sommerfeld pressure with negative values set to zero.
- ``"sommerfeld"``: full Sommerfeld, negative pressures kept.

**Pressure datum.** A lubricant supply groove at ``supply_angle`` (measured in the
line-of-centres frame, snapped to the nearest element; default pi, the largest rigid
clearance, as in the classical theory) holds ``supply_pressure`` (gauge, Pa; default 0 =
ambient) and supplies whatever flow the film needs. Without it the 360-degree problem
with Reynolds conditions is degenerate: any constant can be added to the pressure of a
full film and the cavitated state is not fixed, so there is no unique solution.
The groove rotates with the line of centres (a groove fixed in the bearing at an
angle beta from the load line is at beta - attitude_angle in this frame; not supported).

Load control: the pressure force on the journal balances ``load`` (N/m, the external force
on the journal); the eccentricity ratio ``eps`` and the attitude angle are unknowns.
Viscous shear forces on the journal are O(c/R) of the load and are not included in
this balance (nor in classical theory).

Torques, dissipation (Eq. 3.43-3.46)
------------------------------------
All torques are exerted **by the fluid on the body**, counter-clockwise positive, N m/m.
Shear tractions (3.45) at the faces: tau_B = -h/2 dp/ds - eta (U_B - U_J)/h,
tau_J = -h/2 dp/ds + eta (U_B - U_J)/h (U = omega R, surface speeds), on the film arc
ds = R_B dtheta. The pressure on a *deformed* profile has a moment about the body's
centre: -R_B int p du/dtheta dtheta (central differences); this is the viscoelastic
torque ``torque_viscoelastic`` (bearing) / ``torque_viscoelastic_journal``, and
-omega times it is the hysteretic dissipation (Eq. 3.46 with the sign fixed so that it is
non-negative for both bodies: power into a body = int p du/dt ds, du/dt = -Omega du/dtheta
for a pattern moving at Omega relative to it):

- ``torque_bearing`` about O: R_B^2 int tau_B dtheta + torque_viscoelastic.
- ``torque_journal`` about the journal's own centre O': R_J R_B int tau_J dtheta +
  torque_viscoelastic_journal. ``torque_journal_about_O`` = torque_journal + e x F (the
  thesis's choice, = -torque_bearing up to O(c/R) by the fluid's moment balance).
- Power balance (exact for the discrete equations with Reynolds/Sommerfeld conditions):
  -omega_B torque_bearing - omega_J torque_journal + p_s Q_s
  = dissipation_fluid + dissipation_bearing + dissipation_journal.

Solver
------
Unknowns p/p_ref (n values), eps, attitude: n + 2 equations (cell balances / FB, groove
datum, two force components). Newton with the exact dense AD Jacobian and a backtracking
line search on 0.5 |r|^2 (steps giving h <= 0 are rejected). ``solver="auto"`` first
tries Newton from the rigid half-Sommerfeld estimate (for n >= 512 from the solution on a
4x coarser grid, interpolated; or from ``initial``, e.g. the previous point of a sweep);
if it fails or
lands on the spurious branch (effective eccentricity <= 0: the supply at the minimum
gap), it continues from a rigid solution at a higher entrainment speed (such that the rigid
eccentricity is about 0.6), ramping the compliance in and the speed down over
``stages`` Newton solves. Derivatives of the converged solution are implicit
(:mod:`vjax._implicit`), not through the iterations.

Convergence: ``iterations``, ``stages`` (continuation stages used, 0 = direct),
``residual`` (max-norm of the scaled equations) and ``converged`` (also requires the
physical branch). Under ``jit`` a failure is only flagged; outside, ``throw=True``
(default) raises RuntimeError, and :meth:`JournalSolution.check` does the same later.
"""
from __future__ import annotations

import dataclasses
import math
from functools import partial
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

from . import _checks
from ._implicit import implicit_root
from .material import Material
from .operator import grid, memory_revolutions, ring_operator

CAVITATION = ("reynolds", "half_sommerfeld", "sommerfeld")
NESTED_MIN_N = 512  # "auto" cold starts on n >= this many elements begin on a 4x coarser grid
GREENS = ("circular", "half_plane")


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class JournalSolution:
    """Solution of :func:`journal_bearing` (SI units, per unit axial length).

    Arrays on the ring grid (line-of-centres frame, theta = 0 at the smallest rigid gap):
    ``theta`` (rad), ``pressure`` (Pa, gauge), ``film`` h (m), ``displacement_bearing``
    u_B (m, outward), ``displacement_journal`` u_J (m, inward).

    Scalars: ``eccentricity`` eps = e/c of the journal centre; ``eccentricity_effective``
    first Fourier mode of h over c (positive on the physical branch; independent of the
    log reference length); ``attitude_angle`` (rad, signed angle from the load line to the
    line of centres, positive counter-clockwise); ``line_of_centres_angle`` (absolute,
    rad); ``min_film`` (m); ``rupture_angle`` (rad, line-of-centres frame, where the film
    cavitates; for "sommerfeld" the downstream zero of p); ``force`` fluid pressure force on
    the journal (N/m, absolute x, y); torques (N m/m, by the fluid on the body, CCW positive)
    ``torque_bearing`` (about O), ``torque_journal`` (about O'), ``torque_journal_about_O``,
    ``torque_viscoelastic`` (pressure-on-deformed-bearing part of torque_bearing, from the
    dissipated power Eq. 3.46), ``torque_viscoelastic_journal``; dissipation (W/m)
    ``dissipation_fluid``, ``dissipation_bearing``, ``dissipation_journal``;
    ``supply_flow`` Q_s (m^2/s, net outflow of the groove cell; the Swift-Stieber model
    lets the cavity carry a full-film Couette flow, i.e. it does not conserve mass across
    the cavity, so Q_s can be negative); ``hersey`` H = eta v R_B/|F| (signed, as the thesis);
    ``ref_length`` (m) used by the Green's functions.

    Convergence: ``iterations`` (Newton steps in total on this grid; a nested coarse-grid
    start is not counted), ``stages`` (continuation stages,
    0 = direct), ``residual`` (max-norm of the scaled equations), ``converged``.
    """

    theta: jax.Array
    pressure: jax.Array
    film: jax.Array
    displacement_bearing: jax.Array
    displacement_journal: jax.Array
    eccentricity: jax.Array
    eccentricity_effective: jax.Array
    attitude_angle: jax.Array
    line_of_centres_angle: jax.Array
    min_film: jax.Array
    rupture_angle: jax.Array
    force: jax.Array
    torque_bearing: jax.Array
    torque_journal: jax.Array
    torque_journal_about_O: jax.Array
    torque_viscoelastic: jax.Array
    torque_viscoelastic_journal: jax.Array
    dissipation_fluid: jax.Array
    dissipation_bearing: jax.Array
    dissipation_journal: jax.Array
    supply_flow: jax.Array
    hersey: jax.Array
    ref_length: jax.Array
    iterations: jax.Array
    stages: jax.Array
    residual: jax.Array
    converged: jax.Array

    def check(self) -> "JournalSolution":
        """Raise RuntimeError if the solve did not converge (concrete results only)."""
        if not _checks.is_concrete(self.converged):
            raise RuntimeError("check() needs a concrete result (call it outside jit)")
        bad = ~np.asarray(self.converged)
        if np.any(bad):
            raise RuntimeError(
                f"journal_bearing did not converge: {int(np.max(self.iterations))} Newton "
                f"iterations, {int(np.max(self.stages))} continuation stages, residual "
                f"{float(np.max(self.residual)):.3e} (or the solution is on the spurious "
                f"branch with eccentricity_effective <= 0: "
                f"{float(np.min(self.eccentricity_effective)):.3g})")
        return self


class _Config(NamedTuple):
    n: int
    cavitation: str
    groove: int
    has_bearing: bool
    has_journal: bool
    solver: str
    stages: int
    maxiter: int
    tol: float


# --------------------------------------------------------------------------------------
# helpers


def _fb(a, b):
    """Fischer-Burmeister a + b - sqrt(a^2 + b^2): zero iff a >= 0, b >= 0, a b = 0.
    Double where: at (0, 0) the derivative is (1, 1), an element of its generalized Jacobian."""
    s = a * a + b * b
    ok = s > 0
    return a + b - jnp.where(ok, jnp.sqrt(jnp.where(ok, s, 1.0)), 0.0)


def _apply(symbol, sigma, n):
    return jnp.fft.irfft(symbol * jnp.fft.rfft(sigma), n)


def _half_sommerfeld_g(eps):
    """|W| c^2 / (12 eta |v| R^2) of the rigid half-Sommerfeld bearing."""
    return eps * jnp.sqrt(jnp.pi**2 * (1 - eps**2) + 4 * eps**2) / ((2 + eps**2) * (1 - eps**2))


def _rigid_eps(G):
    """Invert the half-Sommerfeld load g(eps) = G by bisection (g increases from 0 to inf)."""
    def body(_, lohi):
        lo, hi = lohi
        mid = 0.5 * (lo + hi)
        big = _half_sommerfeld_g(mid) > G
        return jnp.where(big, lo, mid), jnp.where(big, mid, hi)
    lo, hi = jax.lax.fori_loop(0, 60, body, (jnp.zeros_like(G), jnp.full_like(G, 0.9999)))
    return 0.5 * (lo + hi)


def _guess(pr, cfg, speed_factor=1.0):
    """Rigid half-Sommerfeld estimate of the unknowns [p/p_ref, eps, attitude]."""
    theta, _ = grid(cfg.n)
    v = pr["v"] * speed_factor
    G = pr["W"] * pr["c"] ** 2 / (12 * pr["eta"] * jnp.abs(v) * pr["R"] ** 2)
    eps = jnp.minimum(_rigid_eps(G), 0.95)
    phi = jnp.sign(v) * jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 2 * eps)
    p = (-12 * pr["eta"] * v * pr["R"] * eps * jnp.sin(theta) * (2 - eps * jnp.cos(theta))
         / (pr["c"] ** 2 * (2 + eps**2) * (1 - eps * jnp.cos(theta)) ** 2))
    # A small positive offset everywhere: with p = 0 exactly in the future cavity, the FB
    # Newton step can only grow the pressurized zone by one cell per iteration.
    p = jnp.maximum(p, 0.0) / pr["p_ref"] + 0.1
    return jnp.concatenate([p, jnp.stack([eps, phi])])


def _fields(x, pr, cfg):
    """Pressure, film, displacements and face fluxes for unknowns x."""
    n = cfg.n
    theta, alpha = grid(n)
    dth = 2 * alpha
    p = x[:n] * pr["p_ref"]
    eps = x[n]
    p_load = jnp.maximum(p, 0.0) if cfg.cavitation == "half_sommerfeld" else p
    zero = jnp.zeros_like(p)
    uB = _apply(pr["symB"], p_load, n) if cfg.has_bearing else zero
    uJ = _apply(pr["symJ"], p_load, n) if cfg.has_journal else zero
    h = pr["c"] * (1 - eps * jnp.cos(theta)) + uB + uJ
    hf = 0.5 * (h + jnp.roll(h, -1))
    dpds = (jnp.roll(p, -1) - p) / (pr["R"] * dth)
    q = -hf**3 * dpds / (12 * pr["eta"]) + pr["v"] * hf
    return dict(theta=theta, dth=dth, p=p, p_load=p_load, uB=uB, uJ=uJ, h=h, hf=hf, dpds=dpds, q=q)


def _residual_and_hmin(x, pr, cfg):
    n = cfg.n
    f = _fields(x, pr, cfg)
    # net outflow of each cell, scaled to O(1) per unit angle
    w = (f["q"] - jnp.roll(f["q"], 1)) / (pr["q_ref"] * f["dth"])
    r = _fb(x[:n], w) if cfg.cavitation == "reynolds" else w
    r = r.at[cfg.groove].set(x[cfg.groove] - pr["ps"] / pr["p_ref"])
    phi = x[n + 1]
    th = f["theta"]
    Fx = -pr["R"] * f["dth"] * jnp.sum(f["p_load"] * jnp.cos(th))
    Fy = -pr["R"] * f["dth"] * jnp.sum(f["p_load"] * jnp.sin(th))
    bal = jnp.stack([Fx / pr["W"] + jnp.cos(phi), Fy / pr["W"] - jnp.sin(phi)])
    return jnp.concatenate([r, bal]), jnp.min(f["h"])


def _residual(x, pr, cfg):
    return _residual_and_hmin(x, pr, cfg)[0]


def _effective_eps(h, c, n):
    theta, _ = grid(n)
    a1 = 2.0 / n * jnp.sum(h * jnp.cos(theta))
    b1 = 2.0 / n * jnp.sum(h * jnp.sin(theta))
    return -jnp.sign(a1) * jnp.sqrt(a1**2 + b1**2) / c


def _newton(x0, pr, cfg):
    """Damped Newton; returns x, iterations, max|r|, converged (incl. physical branch)."""
    n = cfg.n
    dtype = x0.dtype

    def merit(x):
        r, hmin = _residual_and_hmin(x, pr, cfg)
        m = 0.5 * jnp.sum(r * r)
        bad = ~jnp.isfinite(m) | (hmin <= 0) | ~jnp.all(jnp.isfinite(x))
        return jnp.where(bad, jnp.inf, m), r

    m0, r0 = merit(x0)

    def cond(s):
        k, x, r, m, status = s
        return (status == 0) & (k < cfg.maxiter)

    def body(s):
        k, x, r, m, status = s
        J = jax.jacfwd(_residual)(x, pr, cfg)
        dx = jnp.linalg.solve(J, -r)
        # a trust cap on the two geometric unknowns (eps, attitude)
        big = jnp.max(jnp.abs(dx[n:]))
        dx = dx * jnp.minimum(1.0, 0.3 / jnp.where(big > 0, big, 1.0))
        finite = jnp.all(jnp.isfinite(dx))
        dx = jnp.where(finite, dx, 0.0)

        def ls_cond(t_state):
            t, mt, rt, j = t_state
            return (~(mt <= (1 - 1e-4 * t) * m)) & (j < 40)

        def ls_body(t_state):
            t, mt, rt, j = t_state
            t = 0.5 * t
            mt, rt = merit(x + t * dx)
            return t, mt, rt, j + 1

        m1, r1 = merit(x + dx)
        t, mt, rt, j = jax.lax.while_loop(ls_cond, ls_body, (jnp.asarray(1.0, dtype), m1, r1, 0))
        accepted = (mt <= (1 - 1e-4 * t) * m) & finite
        x_new = jnp.where(accepted, x + t * dx, x)
        r_new = jnp.where(accepted, rt, r)
        m_new = jnp.where(accepted, mt, m)
        done = jnp.max(jnp.abs(r_new)) < cfg.tol
        status = jnp.where(done, 1, jnp.where(accepted, 0, 2))
        return k + 1, x_new, r_new, m_new, status

    status0 = jnp.where(jnp.isfinite(m0), jnp.where(jnp.max(jnp.abs(r0)) < cfg.tol, 1, 0), 2)
    k, x, r, m, status = jax.lax.while_loop(cond, body, (0, x0, r0, m0, status0))
    f = _fields(x, pr, cfg)
    physical = _effective_eps(f["h"], pr["c"], n) > 0
    res = jnp.where(jnp.isfinite(m), jnp.max(jnp.abs(r)), jnp.inf)
    return x, k, res, (status == 1) & physical


def _staged(pr, cfg, t):
    """Problem at continuation parameter t in [0, 2].

    t in [0, 1]: compliance ramped in (factor t) at M times the entrainment speed, with M
    such that the rigid bearing runs at eps ~ 0.6 (thick film, mild coupling);
    t in [1, 2]: full compliance, speed M^(2 - t) (geometric) down to the target.
    """
    G = pr["W"] * pr["c"] ** 2 / (12 * pr["eta"] * jnp.abs(pr["v"]) * pr["R"] ** 2)
    M = jnp.maximum(1.0, G / _half_sommerfeld_g(0.6))
    q = dict(pr)
    m = M ** jnp.clip(2.0 - t, 0.0, 1.0)
    s = jnp.clip(t, 0.0, 1.0)
    q["v"] = pr["v"] * m
    q["q_ref"] = pr["q_ref"] * m
    if cfg.has_bearing:
        q["symB"] = pr["symB"] * s
    if cfg.has_journal:
        q["symJ"] = pr["symJ"] * s
    return q, m


def _continuation(pr, cfg):
    """Adaptive continuation in t (see :func:`_staged`): a failed stage halves the step,
    a converged one lets it grow by 1.5. At most ``cfg.stages`` Newton solves."""
    q0, m0 = _staged(pr, cfg, 0.0)
    x0, k0, _, ok0 = _newton(_guess(pr, cfg, m0), q0, cfg)

    def cond(s):
        t, dt, x, its, nst, res, ok = s
        return (t < 2.0) & (nst < cfg.stages) & (dt > 1e-3) & ok0

    def body(s):
        t, dt, x, its, nst, res, ok = s
        t1 = jnp.minimum(t + dt, 2.0)
        q, _ = _staged(pr, cfg, t1)
        x1, k, res1, conv = _newton(x, q, cfg)
        t = jnp.where(conv, t1, t)
        x = jnp.where(conv, x1, x)
        dt = jnp.where(conv, jnp.minimum(1.5 * dt, 0.5), 0.5 * dt)
        return t, dt, x, its + k, nst + 1, res1, conv

    dtype = x0.dtype
    init = (jnp.asarray(0.0, dtype), jnp.asarray(0.25, dtype), x0, k0, 1,
            jnp.asarray(jnp.inf, dtype), ok0)
    t, dt, x, its, nst, res, ok = jax.lax.while_loop(cond, body, init)
    return x, its, res, ok & (t >= 2.0), nst


def _solver(pr, x_init, cfg):
    compliant = cfg.has_bearing or cfg.has_journal
    x, k, res, conv = _newton(x_init, pr, cfg)
    stages = jnp.asarray(0)
    if cfg.solver == "continuation" and compliant:
        x, k, res, conv, stages = _continuation(pr, cfg)
    elif cfg.solver == "auto" and compliant:
        def fallback(_):
            x2, k2, res2, conv2, st2 = _continuation(pr, cfg)
            return x2, k + k2, res2, conv2, st2
        x, k, res, conv, stages = jax.lax.cond(
            conv, lambda _: (x, k, res, conv, stages), fallback, None)
    # report the residual of the target problem at the returned point (after a failed
    # continuation x belongs to an intermediate stage)
    r = jnp.max(jnp.abs(_residual(x, pr, cfg)))
    res = jnp.where(jnp.isfinite(r), r, jnp.inf)
    conv = conv & (res < cfg.tol)
    return x, dict(iterations=jnp.asarray(k), stages=stages, residual=res, converged=conv)


def _rupture_angle(p, theta, v, cavitation):
    """Angle (line-of-centres frame) where p first reaches 0 downstream of its maximum."""
    n = p.shape[0]
    dth = 2 * jnp.pi / n
    imax = jnp.argmax(p)
    direction = jnp.where(v >= 0, 1, -1)
    idx = (imax + direction * jnp.arange(n)) % n
    pk = p[idx]
    thr = 1e-9 * jnp.max(jnp.abs(p))
    kc = jnp.maximum(jnp.argmax(pk <= thr), 2)
    a, b, z = pk[kc - 2], pk[kc - 1], pk[kc]
    if cavitation == "sommerfeld":  # p changes sign between kc - 1 and kc: interpolate
        den = b - z
        frac = jnp.where(den > 0, b / jnp.where(den > 0, den, 1.0), 0.0)
    else:
        # the last two pressurized nodes, extrapolated: p ~ (theta_r - theta)^2 before a
        # Reynolds rupture (sqrt(p) linear), p linear at a half-Sommerfeld zero
        f = jnp.sqrt if cavitation == "reynolds" else (lambda y: y)
        sa, sb = f(jnp.maximum(a, 0.0)), f(jnp.maximum(b, 0.0))
        den = sa - sb
        frac = jnp.where(den > 0, sb / jnp.where(den > 0, den, 1.0), 0.0)
    # the discrete free boundary lies within the first cavitated cell: frac <= 1.5
    ang = theta[imax] + direction * (kc - 1 + jnp.clip(frac, 0.0, 1.5)) * dth
    return jnp.angle(jnp.exp(1j * ang))


def _outputs(x, pr, cfg, stats, ref_length):
    n = cfg.n
    f = _fields(x, pr, cfg)
    p, h, hf, dpds, th, dth = f["p"], f["h"], f["hf"], f["dpds"], f["theta"], f["dth"]
    R, RJ, eta, c = pr["R"], pr["RJ"], pr["eta"], pr["c"]
    eps, phi = x[n], x[n + 1]
    pres = f["p_load"]
    dU = pr["omegaB"] * R - pr["omegaJ"] * RJ
    tauB = -0.5 * hf * dpds - eta * dU / hf
    tauJ = -0.5 * hf * dpds + eta * dU / hf

    def central(u):
        return 0.5 * (jnp.roll(u, -1) - jnp.roll(u, 1))

    CvB = -R * jnp.sum(pres * central(f["uB"]))
    CvJ = -R * jnp.sum(pres * central(f["uJ"]))
    CB = R * R * dth * jnp.sum(tauB) + CvB
    CJ = RJ * R * dth * jnp.sum(tauJ) + CvJ
    Fx = -R * dth * jnp.sum(pres * jnp.cos(th))
    Fy = -R * dth * jnp.sum(pres * jnp.sin(th))
    CJ_O = CJ + eps * c * Fy
    Df = R * dth * jnp.sum(hf**3 * dpds**2 / (12 * eta) + eta * dU**2 / hf)
    g = cfg.groove
    Qs = f["q"][g] - f["q"][(g - 1) % n]
    gamma = pr["psi"] + phi
    rot = jnp.array([[jnp.cos(gamma), -jnp.sin(gamma)], [jnp.sin(gamma), jnp.cos(gamma)]])
    return JournalSolution(
        theta=th, pressure=pres, film=h, displacement_bearing=f["uB"],
        displacement_journal=f["uJ"], eccentricity=eps,
        eccentricity_effective=_effective_eps(h, c, n), attitude_angle=phi,
        line_of_centres_angle=jnp.angle(jnp.exp(1j * gamma)), min_film=jnp.min(h),
        # half-Sommerfeld: the zero crossing of the unclipped (full-Sommerfeld) pressure
        rupture_angle=_rupture_angle(p, th, pr["v"], "reynolds" if cfg.cavitation == "reynolds"
                                     else "sommerfeld"),
        force=rot @ jnp.stack([Fx, Fy]), torque_bearing=CB, torque_journal=CJ,
        torque_journal_about_O=CJ_O, torque_viscoelastic=CvB,
        torque_viscoelastic_journal=CvJ, dissipation_fluid=Df,
        dissipation_bearing=-pr["omegaB"] * CvB, dissipation_journal=-pr["omegaJ"] * CvJ,
        supply_flow=Qs, hersey=eta * pr["v"] * R / pr["W"],
        ref_length=jnp.asarray(ref_length, dtype=p.dtype),
        iterations=stats["iterations"], stages=stats["stages"], residual=stats["residual"],
        converged=stats["converged"])


def _symbol(kind, material, R, n, omega, memory, ref_length):
    if material is None:
        return None
    return ring_operator(kind, material, R, n, omega=omega, memory=memory,
                         ref_length=ref_length).symbol


@partial(jax.jit, static_argnames=("cfg", "memory", "green"))
def _run(scalars, bearing, journal, x_init, cfg, memory, green, ref_length):
    R, c, eta, wB, wJ, Wx, Wy, ps = (scalars[k] for k in
                                     ("R", "c", "eta", "wB", "wJ", "Wx", "Wy", "ps"))
    RJ = R - c
    W = jnp.sqrt(Wx**2 + Wy**2)
    kindB, kindJ = ("hole", "cylinder") if green == "circular" else ("half_plane", "half_plane")
    pr = dict(
        symB=_symbol(kindB, bearing, R, cfg.n, -wB, memory, ref_length),
        symJ=_symbol(kindJ, journal, RJ, cfg.n, -wJ, memory, ref_length),
        R=R, RJ=RJ, c=c, eta=eta, v=0.5 * (wB * R + wJ * RJ), W=W, psi=jnp.arctan2(Wy, Wx),
        ps=ps, omegaB=wB, omegaJ=wJ)
    pr = {k: v for k, v in pr.items() if v is not None}
    pr["p_ref"] = W / (2 * R)
    pr["q_ref"] = c**3 * pr["p_ref"] / (12 * eta * R) + jnp.abs(pr["v"]) * c
    # The starting point travels with the parameters (the residual ignores it), so that
    # the custom derivative closes over no traced value.
    pr["x0"] = _guess(pr, cfg) if x_init is None else x_init

    def solver(prm):
        return _solver(prm, jax.lax.stop_gradient(prm["x0"]), cfg)

    x, stats = implicit_root(lambda xx, prm: _residual(xx, prm, cfg), solver)(pr)
    return _outputs(x, pr, cfg, stats, ref_length)


def journal_bearing(R_bearing, clearance, viscosity, omega_journal, omega_bearing=0.0, load=None,
                    *, load_angle=-math.pi / 2, bearing: Material | None = None,
                    journal: Material | None = None, memory="periodic", n: int = 256,
                    green: str = "circular", ref_length=1.0, cavitation: str = "reynolds",
                    supply_angle=math.pi, supply_pressure=0.0, initial: JournalSolution | None = None,
                    solver: str = "auto", stages: int = 40, maxiter: int = 40, tol=None,
                    throw: bool = True) -> JournalSolution:
    """Steady state of an infinitely long (visco)elastic journal bearing under a given load.

    See the module docstring for the equations, conventions and solver. Configurations of
    thesis Section 3.2: HS (``bearing=`` soft, ``journal=None``), SH, SS; both ``None`` is
    the rigid bearing.

    Args:
      R_bearing: bore radius R_B (m). clearance: radial clearance c = R_B - R_J (m).
      viscosity: lubricant viscosity eta (Pa s), isoviscous.
      omega_journal, omega_bearing: angular velocities of the bodies (rad/s, CCW > 0).
        Their entrainment speed v = (omega_B R_B + omega_J R_J)/2 must not be zero.
      load: external force on the journal (N/m): a vector (Fx, Fy), or a magnitude with
        ``load_angle`` (rad, default -pi/2: downward).
      bearing, journal: :class:`~vjax.Material` or None (rigid).
      memory: "periodic", "thesis" or a number of revolutions (see :mod:`vjax.operator`).
      n: elements on the ring (even, >= 16; static). green: "circular" (A.45/A.60) or
        "half_plane" (Fig. 3.4). ref_length: reference length of the log terms (m).
      cavitation: "reynolds" (default), "half_sommerfeld" or "sommerfeld".
      supply_angle: groove position in the line-of-centres frame (rad, default pi).
      supply_pressure: groove gauge pressure (Pa, default 0).
      initial: a previous :class:`JournalSolution` (same n) to start Newton from (sweeps).
      solver: "auto" (direct Newton, continuation if that fails), "newton" or
        "continuation". stages: continuation stages. maxiter: Newton steps per solve.
      tol: max-norm tolerance of the scaled equations (default 1e-10 in float64, 1e-4 in
        float32).
      throw: raise RuntimeError when a concrete result did not converge.

    >>> import jax; jax.config.update("jax_enable_x64", True)
    >>> sol = journal_bearing(0.05, 5e-5, 0.01, omega_journal=100.0, load=2e4, n=64)
    >>> bool(sol.converged), 0 < float(sol.eccentricity) < 1
    (True, True)
    """
    for name, val in (("R_bearing", R_bearing), ("clearance", clearance), ("viscosity", viscosity)):
        _checks.positive(name, val)
    for name, val in (("omega_journal", omega_journal), ("omega_bearing", omega_bearing),
                      ("load_angle", load_angle), ("supply_angle", supply_angle)):
        _checks.finite(name, val)
    _checks.nonnegative("supply_pressure", supply_pressure)
    _checks.positive("ref_length", ref_length)
    for name, val in (("R_bearing", R_bearing), ("clearance", clearance), ("viscosity", viscosity),
                      ("omega_journal", omega_journal), ("omega_bearing", omega_bearing),
                      ("load_angle", load_angle), ("supply_pressure", supply_pressure),
                      ("ref_length", ref_length)):
        _checks.scalar(name, val)
    if tol is not None and not (isinstance(tol, (int, float, np.floating)) and math.isfinite(tol) and tol > 0):
        raise ValueError(f"tol must be a finite number > 0 (or None for the default), got {tol!r}")
    if initial is not None and not isinstance(initial, JournalSolution):
        raise ValueError(f"initial must be a JournalSolution of the same bearing (or None), "
                         f"got {type(initial).__name__}")
    Rv, cv = _checks.values("R_bearing", R_bearing), _checks.values("clearance", clearance)
    if Rv is not None and cv is not None and not np.all(cv < Rv):
        raise ValueError(f"clearance must be < R_bearing, got clearance={clearance!r}, R_bearing={R_bearing!r}")
    if load is None:
        raise ValueError("load (N/m, a vector or a magnitude with load_angle) is required")
    load = jnp.asarray(load)
    if load.ndim == 0:
        _checks.positive("load", load)
        Wx, Wy = load * jnp.cos(load_angle), load * jnp.sin(load_angle)
    elif load.shape == (2,):
        lv = _checks.values("load", load)
        if lv is not None and not np.hypot(*lv) > 0:
            raise ValueError(f"load must be a non-zero vector, got {load!r}")
        Wx, Wy = load[0], load[1]
    else:
        raise ValueError(f"load must be a magnitude or a vector (Fx, Fy), got shape {load.shape}")
    if not isinstance(n, (int, np.integer)) or n < 16 or n % 2:
        raise ValueError(f"n must be an even integer >= 16, got {n!r}")
    _checks.one_of("green", green, GREENS)
    _checks.one_of("cavitation", cavitation, CAVITATION)
    _checks.one_of("solver", solver, ("auto", "newton", "continuation"))
    if not isinstance(stages, (int, np.integer)) or stages < 1:
        raise ValueError(f"stages must be an integer >= 1, got {stages!r}")
    if not isinstance(maxiter, (int, np.integer)) or maxiter < 1:
        raise ValueError(f"maxiter must be an integer >= 1, got {maxiter!r}")
    for name, mat in (("bearing", bearing), ("journal", journal)):
        if mat is not None and not isinstance(mat, Material):
            raise ValueError(f"{name} must be a vjax.Material or None (rigid), got {type(mat).__name__}")
    memory_revolutions(memory)
    wB, wJ = jnp.asarray(omega_bearing), jnp.asarray(omega_journal)
    vals = [_checks.values(k, v) for k, v in (("omega_bearing", omega_bearing), ("omega_journal", omega_journal))]
    if all(v is not None for v in vals) and Rv is not None and cv is not None:
        if np.any(vals[0] * Rv + vals[1] * (Rv - cv) == 0):
            raise ValueError("omega_bearing R_B + omega_journal R_J = 0: zero entrainment speed, "
                             "no hydrodynamic load capacity (omega_journal, omega_bearing)")
    sa = _checks.values("supply_angle", supply_angle)
    if sa is None:
        raise ValueError("supply_angle must be a concrete number (it selects a grid element)")
    groove = int(round(float(sa) % (2 * math.pi) / (2 * math.pi / n))) % n
    dtype = jnp.result_type(float)
    if tol is None:
        tol = 1e-10 if dtype == jnp.float64 else 1e-4
    cfg = _Config(int(n), cavitation, groove, bearing is not None, journal is not None, solver,
                  int(stages), int(maxiter), float(tol))
    x_init = None
    p_ref = jnp.sqrt(Wx**2 + Wy**2) / (2 * R_bearing)
    if initial is not None:
        if initial.pressure.shape[-1] != n:
            raise ValueError(f"initial has {initial.pressure.shape[-1]} elements, n is {n}")
        x_init = jnp.concatenate([initial.pressure / p_ref,
                                  jnp.stack([initial.eccentricity, initial.attitude_angle])])
    elif solver == "auto" and n >= NESTED_MIN_N and n % 4 == 0:
        # Nested start: solve on a 4x coarser grid, interpolate. Most Newton steps from a
        # cold start are spent far from the solution, where a coarse grid is as good and
        # (n/4)^3 cheaper. If the coarse start misleads, "auto" still falls back.
        coarse = journal_bearing(
            R_bearing, clearance, viscosity, omega_journal, omega_bearing, load=load,
            load_angle=load_angle, bearing=bearing, journal=journal, memory=memory, n=n // 4,
            green=green, ref_length=ref_length, cavitation=cavitation, supply_angle=supply_angle,
            supply_pressure=supply_pressure, solver=solver, stages=stages, maxiter=maxiter,
            tol=tol, throw=False)
        theta_f, _ = grid(n)
        p0 = jnp.interp(theta_f, coarse.theta, coarse.pressure, period=2 * jnp.pi)
        x_init = jnp.concatenate([p0 / p_ref, jnp.stack([coarse.eccentricity, coarse.attitude_angle])])
    if x_init is not None:  # a starting point only: no derivative flows through it
        x_init = jax.lax.stop_gradient(x_init)
    scalars = dict(R=R_bearing, c=clearance, eta=viscosity, wB=wB, wJ=wJ, Wx=Wx, Wy=Wy,
                   ps=supply_pressure)
    scalars = {k: jnp.asarray(v, dtype) for k, v in scalars.items()}
    mem = memory if isinstance(memory, str) else float(memory)
    sol = _run(scalars, bearing, journal, x_init, cfg, mem, green, jnp.asarray(ref_length, dtype))
    if throw and _checks.is_concrete(sol.converged):
        sol.check()
    return sol
