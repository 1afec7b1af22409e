"""Scene: needle roller bearing with viscoelastic rings and rigid rollers (thesis Section 2.3).

``n_rollers`` rigid rollers of diameter D sit between an outer ring (a hole of radius R_O in
an infinite plane, Green's function A.45) and an inner ring (a cylinder of radius R_I fixed
at its centre, A.60). Either ring may be viscoelastic, elastic, or rigid (``None``: no
operator is built for it). A radial load ``load`` (N/m) along the direction ``load_angle``
pushes the inner ring; its centre moves by the ring shift delta_r along that direction (the
perpendicular motion is held, as in the thesis, and its force is a reaction). Roller j sits
at the angle psi_j = roller_angle + 2 pi j / Z (roller 1, index 0, on the load line by
default, numbering counter-clockwise as in Fig. 2.12).

**Geometry (exact circles, no parabola).** Roller j's centre is at distance rho_j from the
bearing centre O. Its overlap with the undeformed outer ring along the ray theta from O, and
with the undeformed inner ring along the ray theta' from the inner centre C = delta_r e_L, is

    d_O(theta)  = rho cos(theta - psi) + sqrt(r^2 - rho^2 sin^2(theta - psi)) - R_O,
    d_I(theta') = R_I - rho' cos(theta' - psi') + sqrt(r^2 - rho'^2 sin^2(theta' - psi')),

with (rho', psi') the roller centre seen from C. On the centre line these are the
penetrations delta_j^O = rho_j + r - R_O and delta_j^I = R_I + r - |rho_j e_j - C|, whose
sum is to first order Eq. 2.26, delta_j = delta_r cos psi_j - P_d/2, with the diametral
clearance P_d = 2 (R_O - R_I - D). A given ``clearance`` is realized by the roller size
(matched roller sets): the contact uses rollers of diameter R_O - R_I - P_d/2.

**Unknowns and equations.** Each ring is one contact problem holding all roller patches
(:func:`~vjax.solve_contact`, displacement control; the patches interact through the ring).
The unknowns are the split of each roller's deflection, x_j = delta_j^O (Eq. 2.37), and
delta_r. The equations are the radial balance of each roller, F_j^O = F_j^I, where F_j is
the patch resultant projected on the roller's radial direction e_j, and the load balance
R_I int p_I cos(theta' - load_angle) dtheta' = load. A roller that touches neither ring
carries nothing and its position is indeterminate, so each roller's balance is written as

    (F_j^O - k_O g_j^O) - (F_j^I - k_I g_j^I) = 0,

with g_j the smallest gap between the roller and each deformed ring (zero while it
touches, where F_j > 0) and k = E0 of the ring a stiffness scale. Each bracket is
continuous and strictly monotone in x_j, so the equation has one root, equals F^O = F^I
for a loaded roller, and places an unloaded one where k_O g^O = k_I g^I. The Jacobian
stays regular when rollers lose contact, and their derivatives are finite. The load
equation gets the same treatment (minus k times the smallest roller gap, zero as soon as
one roller touches), so a start with no contact is regular too. A rigid ring replaces the
balance of each roller by "touches the rigid ring" and carries what the other ring does.

**Solve and derivatives.** Newton with the exact Jacobian (``jax.jacfwd`` through both
contact solves, whose own derivatives are implicit) and a backtracking line search;
derivatives of the result come from the implicit function theorem at the converged root
(:func:`vjax._implicit.implicit_root`), then from the contact solves at that root: nothing
is differentiated through the iterations.

**Cost.** Each Newton iteration solves both rings (warm-started from the previous
iterate's pressures: one or two active-set steps) and 2 (Z + 1) tangent Krylov solves for
the Jacobian, which dominate at large n. From a cold start Newton takes 3-5 iterations;
continuing from a nearby solution (``initial=``, e.g. along a speed sweep) 1-3.

**Kinematics (Section 2.3.1).** Pure rolling gives the cage speed
omega_c = (omega_I R_I + omega_O R_O) / (R_I + R_O). The roller pattern rotates at omega_c, so
relative to the outer ring it moves at omega_c - omega_O and relative to the inner ring at
omega_c - omega_I (:func:`roller_patch_speeds`; the thesis writes omega_O - omega_c and
omega_I - omega_c, the motion of the ring relative to the patches). The thesis speed is
omega~ = |omega_O,c| tau.

**Snapshot model.** Like the thesis, each ring sees the whole roller pattern frozen at the
angles psi_j and rotating rigidly at the patch speed: a steady state in which every roller
carries the same load at every instant of its passage. In a real bearing a roller's load
changes as it crosses the load zone, so the pattern is not rigid; the snapshot is what the
thesis validated against torque measurements, and it is kept here.

**Outputs.** Forces and torques are those the contact pressure exerts **on each ring**
(index 0 outer, 1 inner), Eq. 2.38-2.40 on the deformed profile R +- u(theta), whose slope
u' is taken spectrally: then R sum p u' dtheta is exactly the power the ring dissipates
divided by the patch speed (zero for an elastic ring on any grid), and the torque is
resolved even when the patches are a few elements wide (n = 256: within 15% of n = 4096
for omega~ >= 0.04). The outer ring is pushed along +load, the inner along -load.
``torque`` is about the bearing centre O (Eq. 2.40; for the inner ring it includes the
moment C x F of its offset). With the outer ring fixed and the shaft turning at
omega_I > 0, the outer ring's torque is positive: the housing is dragged along with the
shaft, and the torque a motor must supply is about the same. ``force_angle`` is the angle
of the ring's net force from the load line (taking the inner ring's force reversed, so both
are measured against +load), ``friction_angle`` = arccos(|F_r|/|F|) and ``friction_radius``
= |C_t|/|F| (Section 2.3.1).
"""
from __future__ import annotations

import dataclasses
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from . import _checks
from ._implicit import implicit_root
from ._report import check_converged
from .contact import SolverOptions, solve_contact
from .material import Material
from .operator import grid, memory_revolutions, ring_operator, spectral_derivative


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class RollerResult:
    """Solution of :func:`roller_bearing`. Lengths in m, angles in rad, forces in N/m,
    torques in N m/m, per unit axial length. Ring-indexed fields: index 0 outer, 1 inner.

    roller_angles: psi_j (Z,). roller_loads: (2, Z) radial force of each ring on each roller
      (equal rows at convergence). penetration_outer, penetration_inner: delta_j^O,
      delta_j^I (Z,), centre-line overlaps of the roller with the undeformed rings (for an
      unloaded roller they depend on where it floats, see the module docstring).
      deflection: delta_j^O + delta_j^I (Z,), the total approach (Eq. 2.26 to first order).
      ring_shift: delta_r. u_at_rollers: (2, Z) ring displacement at psi_j (positive into
      each ring). gaps: (Z,) clearance at the roller centre line, Eq. g(psi_j) =
      u_O(psi_j) + u_I(psi_j) - delta_j (zero while the roller is loaded). min_gaps: (Z,)
      smallest gap between the roller surface and both rings (what Newton uses).
      active: (Z,) the roller carries load.
    theta: (2, n) element centres of each ring (the inner ring's angles are about its own
      centre). pressure, displacement: (2, n) (Pa, m; zeros for a rigid ring).
    force: (2, 2) net force on each ring (x, y). force_angle, friction_angle, torque,
      friction_radius: (2,). cage_speed, patch_speed: omega_c and (omega_c - omega_O,
      omega_c - omega_I) (rad/s).
    iterations, residual, converged: Newton's report (the residual is the max-norm of the
      scaled equations, and includes the contact solves' own convergence).
    """

    roller_angles: jax.Array
    roller_loads: jax.Array
    penetration_outer: jax.Array
    penetration_inner: jax.Array
    deflection: jax.Array
    ring_shift: jax.Array
    u_at_rollers: jax.Array
    gaps: jax.Array
    min_gaps: jax.Array
    active: jax.Array
    theta: jax.Array
    pressure: jax.Array
    displacement: jax.Array
    force: jax.Array
    force_angle: jax.Array
    friction_angle: jax.Array
    torque: jax.Array
    friction_radius: jax.Array
    cage_speed: jax.Array
    patch_speed: jax.Array
    iterations: jax.Array
    residual: jax.Array
    converged: jax.Array


def roller_patch_speeds(omega_inner, omega_outer, R_inner, R_outer):
    """Cage speed omega_c and patch speeds relative to (outer, inner) ring (rad/s).

    omega_c = (omega_I R_I + omega_O R_O) / (R_I + R_O) (pure rolling, Section 2.3.1); the
    pattern moves at omega_c - omega_O relative to the outer ring and omega_c - omega_I
    relative to the inner ring (the sign convention of :func:`~vjax.ring_operator`).
    """
    wc = (omega_inner * R_inner + omega_outer * R_outer) / (R_inner + R_outer)
    return wc, wc - omega_outer, wc - omega_inner


# ---- geometry ----------------------------------------------------------------------
def _safe_sqrt_abs(x):
    """sqrt(|x|) with finite gradients at 0 (double where)."""
    a = jnp.abs(x)
    ok = a > 0
    return jnp.where(ok, jnp.sqrt(jnp.where(ok, a, 1.0)), 0.0)


def _outer_interference(q, args):
    """Overlap of the rollers with the undeformed hole (one roller per element)."""
    rho, cos_d, sin_d, r, R = args
    disc = r**2 - (rho * sin_d) ** 2
    return rho * cos_d + jnp.sign(disc) * _safe_sqrt_abs(disc) - R


def _inner_interference(q, args):
    """Overlap of the rollers with the undeformed inner cylinder (frame of its centre)."""
    rho, cos_d, sin_d, r, R = args
    disc = r**2 - (rho * sin_d) ** 2
    return R - rho * cos_d + jnp.sign(disc) * _safe_sqrt_abs(disc)


def _wrap(phi):
    return phi - 2.0 * jnp.pi * jnp.round(phi / (2.0 * jnp.pi))


@dataclasses.dataclass(frozen=True)
class _Config:
    n_outer: int
    n_inner: int
    Z: int
    outer: bool          # outer ring deformable
    inner: bool          # inner ring deformable
    options: SolverOptions


def _owner(theta, psi, Z):
    """Index of the roller nearest in angle to each element (its Voronoi cell)."""
    psi0 = jax.lax.stop_gradient(psi[0])
    k = jnp.round((jax.lax.stop_gradient(theta) - psi0) / (2.0 * jnp.pi / Z)).astype(int)
    return k % Z


def _fields(x, P, cfg, warm=None):
    """Contact solves of both rings at the unknowns x = (delta^O_1..Z, delta_r)."""
    Z = cfg.Z
    dO, dr = x[:Z], x[Z]
    psi, r = P["psi"], P["r"]
    R_O, R_I = P["R_O"], P["R_I"]
    eL = jnp.stack([jnp.cos(P["load_angle"]), jnp.sin(P["load_angle"])])
    C = dr * eL
    rho = R_O - r + dO
    e = jnp.stack([jnp.cos(psi), jnp.sin(psi)], axis=1)            # (Z, 2)
    v = rho[:, None] * e - C                                       # roller centres seen from C
    rho_i = jnp.linalg.norm(v, axis=1)
    psi_i = jnp.arctan2(v[:, 1], v[:, 0])
    out = {}
    for name, on, n, R, rr, pp, interf in (
            ("O", cfg.outer, cfg.n_outer, R_O, rho, psi, _outer_interference),
            ("I", cfg.inner, cfg.n_inner, R_I, rho_i, psi_i, _inner_interference)):
        if not on:
            continue
        theta, alpha = grid(n)
        own = _owner(theta, psi, Z)
        delta = _wrap(theta - pp[own])
        args = (rr[own], jnp.cos(delta), jnp.sin(delta), r, R)
        sol = solve_contact(P["op" + name], interf, args, options=cfg.options,
                            sigma_init=None if warm is None else warm[int(name == "I")])
        p, u = sol.pressure, sol.displacement
        d = interf(None, args)
        hit = (r**2 - (rr[own] * jnp.sin(delta)) ** 2) > 0
        cells = own[None, :] == jnp.arange(Z)[:, None]             # (Z, n)
        # radial force of each patch along the roller's direction e_j
        proj = jnp.cos(theta - psi[own])
        F = R * 2 * alpha * jnp.sum(jnp.where(cells, p * proj, 0.0), axis=1)
        g = u - d
        big = jnp.asarray(10.0, g.dtype) * R
        gmin = jnp.min(jnp.where(cells & hit, g, big), axis=1)
        gmin = jnp.where(F > 0, 0.0, jnp.maximum(gmin, 0.0))
        out[name] = dict(sol=sol, theta=theta, alpha=alpha, p=p, u=u, g=g, F=F, gmin=gmin, R=R)
    geo = dict(rho=rho, rho_i=rho_i, psi_i=psi_i, C=C, eL=eL, e=e, dO=dO,
               dI=R_I + r - rho_i)
    return out, geo


def _residual_parts(x, P, cfg, warm=None):
    out, geo = _fields(x, P, cfg, warm)
    Z = cfg.Z
    Fs = P["load"] / Z
    zero = jnp.zeros(Z, x.dtype)
    FO = out["O"]["F"] if cfg.outer else None
    FI = out["I"]["F"] if cfg.inner else None
    gO = out["O"]["gmin"] if cfg.outer else zero
    gI = out["I"]["gmin"] if cfg.inner else zero
    if cfg.outer and cfg.inner:
        r_roll = ((FO - P["kO"] * gO) - (FI - P["kI"] * gI)) / Fs
    elif cfg.inner:   # rigid outer ring: the roller rests on it
        r_roll = geo["dO"] * P["kI"] / Fs
    else:             # rigid inner ring: the roller rests on it
        r_roll = geo["dI"] * P["kO"] / Fs
    if not cfg.outer:
        # a gap to the rigid ring can only open on the inner side (the roller rests on it)
        gO = zero
        FO = FI
    if not cfg.inner:
        gI = zero
        FI = FO
    gap = gO + gI
    k = P["kI"] if cfg.inner else P["kO"]
    if cfg.inner:
        o = out["I"]
        Fx = o["R"] * 2 * o["alpha"] * jnp.sum(o["p"] * jnp.cos(o["theta"] - P["load_angle"]))
    else:
        # rigid inner ring: each roller pushes it along the line of centres
        Fx = jnp.sum(FO * jnp.cos(geo["psi_i"] - P["load_angle"]))
    r_load = (Fx - k * jnp.min(gap) - P["load"]) / P["load"]
    return jnp.concatenate([r_roll, r_load[None]]), (out, geo, FO, FI, gap)


def _residual(x, P, cfg):
    return _residual_parts(x, P, cfg)[0]


def _contact_ok(out):
    return jnp.all(jnp.stack([o["sol"].converged for o in out.values()]))


def _guess(P, cfg):
    """Deflections from a linear spring per roller and ring (E0 per unit overlap)."""
    psi = P["psi"]
    c = jnp.cos(psi - P["load_angle"])
    kO, kI = P["kO"], P["kI"]
    k = 1.0 / (cfg.outer / kO + cfg.inner / kI)                    # series springs
    # Stribeck-like: sum_j k max(delta_r cos - Pd/2, 0) cos = load, solved for zero clearance
    pos = jnp.maximum(c, 0.0)
    dr = P["load"] / (k * jnp.sum(pos**2)) + 0.5 * P["Pd"]
    dj = dr * c - 0.5 * P["Pd"]
    share = (1.0 / kO) / (1.0 / kO + 1.0 / kI) if (cfg.outer and cfg.inner) else float(cfg.outer)
    return jnp.concatenate([dj * share, dr[None]])


def _pressures(out, cfg, dtype):
    z = jnp.zeros(cfg.n_outer, dtype)
    return jnp.stack([out["O"]["p"] if cfg.outer else z, out["I"]["p"] if cfg.inner else z])


def _newton(P, cfg, tol, max_iter, start):
    """Newton with the exact Jacobian and backtracking on the max-norm of the residual.

    One loop, one evaluation per pass (it keeps the compiled graph small): each pass
    evaluates the residual and its Jacobian at a trial point x + lam dx, accepts it when the
    merit decreased enough (and then takes a new Newton step), otherwise halves lam. The
    contact solves start from the last accepted pressures (warm start). Evaluating the
    Jacobian only when a step is needed (lax.cond) measured slower on CPU, so it is not.
    """
    def with_aux(xx, warm):
        r, (out, *_) = _residual_parts(xx, P, cfg, warm)
        return r, (r, _contact_ok(out), _pressures(out, cfg, xx.dtype))

    jac_fn = jax.jacfwd(with_aux, has_aux=True)
    merit = lambda r: jnp.max(jnp.abs(r))
    if start is None:
        x0 = _guess(P, cfg)
        p0 = jnp.zeros((2, cfg.n_outer), x0.dtype)
    else:  # continuation from a nearby solution (e.g. the previous speed of a sweep)
        x0, p0 = start
    step_cap = 0.1 * P["r"]
    dtype = x0.dtype

    def cond(s):
        k, j, x, dx, lam, m, ok, _, _ = s
        done = (m <= tol) & ok
        return (k < max_iter) & ~done & (j < 4 * max_iter)

    def body(s):
        k, j, x, dx, lam, m, ok, p, l2 = s
        xt = x + lam * dx
        # contact solves warm-started from the last accepted pressures (zero = cold start)
        J, (r, okt, pt) = jac_fn(xt, p)
        mt = merit(r)
        # Armijo on the 2-norm (smooth); convergence is judged on the max-norm
        lt = jnp.sum(r**2)
        accept = jnp.isfinite(lt) & ((lt <= (1.0 - 1e-4 * lam) * l2) | (lam < 1e-4))
        step = jnp.linalg.solve(J, -r)
        big = jnp.max(jnp.abs(step))
        step = step * jnp.minimum(1.0, step_cap / jnp.where(big > 0, big, 1.0))
        x_new = jnp.where(accept, xt, x)
        dx_new = jnp.where(accept, step, dx)
        lam_new = jnp.where(accept, 1.0, 0.5 * lam)
        m_new = jnp.where(accept, mt, m)
        l2_new = jnp.where(accept, lt, l2)
        ok_new = jnp.where(accept, okt, ok)
        p_new = jnp.where(accept, pt, p)
        return (k + accept.astype(int), j + 1, x_new, dx_new, lam_new, m_new, ok_new, p_new, l2_new)

    init = (0, 0, x0, jnp.zeros_like(x0), jnp.asarray(1.0, dtype), jnp.asarray(jnp.inf, dtype),
            jnp.asarray(False), p0, jnp.asarray(jnp.inf, dtype))
    k, j, x, dx, lam, m, ok, p, _ = jax.lax.while_loop(cond, body, init)
    # k counts accepted points; the first one is the initial guess
    return x, (k - 1, m, (m <= tol) & ok, p)


def _outputs(x, P, cfg, stats):
    Z = cfg.Z
    _, (out, geo, FO, FI, gap) = _residual_parts(x, P, cfg, stats[3])
    psi = P["psi"]
    eL = geo["eL"]
    perp = jnp.stack([-eL[1], eL[0]])
    forces, torques, thetas, pressures, disps, u_at, g_at = [], [], [], [], [], [], []
    for name, on, n, R in (("O", cfg.outer, cfg.n_outer, P["R_O"]), ("I", cfg.inner, cfg.n_inner, P["R_I"])):
        if on:
            o = out[name]
            th, p, u = o["theta"], o["p"], o["u"]
            # slope u' of the deformed profile, spectral: then R sum p u' is exactly the
            # modal dissipation / patch speed (zero for an elastic ring on any grid). The
            # exact roller slope inside the patches is not: on a grid not symmetric about
            # the rollers it leaves a torque of O(h) (170% of it at n = 256, 10-20% at 1024).
            du = spectral_derivative(u)
            er = jnp.stack([jnp.cos(th), jnp.sin(th)])
            et = jnp.stack([-jnp.sin(th), jnp.cos(th)])
            dth = 2 * o["alpha"]
            if name == "O":
                # into-body (outward) normal R e_r - u' e_theta; P = (R + u) e_r
                F = dth * jnp.sum(p * (R * er - du * et), axis=1)
                T = -dth * jnp.sum(p * (R + u) * du)
            else:
                # inward normal -R e_r - u' e_theta; P = C + (R - u) e_r
                F = dth * jnp.sum(p * (-R * er - du * et), axis=1)
                T = -dth * jnp.sum(p * (R - u) * du) + (geo["C"][0] * F[1] - geo["C"][1] * F[0])
            ua = jnp.interp(psi if name == "O" else geo["psi_i"], th, u, period=2 * jnp.pi)
            ga = jnp.interp(psi if name == "O" else geo["psi_i"], th, o["g"], period=2 * jnp.pi)
            ga = jnp.where(o["F"] > 0, 0.0, ga)
        else:
            th, _ = grid(n)
            p = u = jnp.zeros(n, x.dtype)
            loads = FI if name == "O" else FO
            if name == "O":
                F = jnp.sum(loads[:, None] * geo["e"], axis=0)
                T = jnp.zeros((), x.dtype)
                ua = jnp.zeros(Z, x.dtype)
                ga = jnp.zeros(Z, x.dtype)
            else:
                ei = jnp.stack([jnp.cos(geo["psi_i"]), jnp.sin(geo["psi_i"])], axis=1)
                F = -jnp.sum(loads[:, None] * ei, axis=0)
                T = geo["C"][0] * F[1] - geo["C"][1] * F[0]
                ua = jnp.zeros(Z, x.dtype)
                # the gap to the rigid inner ring opens on the outer side only (roller rests on it)
                ga = jnp.zeros(Z, x.dtype)
        forces.append(F)
        torques.append(T)
        thetas.append(th)
        pressures.append(p)
        disps.append(u)
        u_at.append(ua)
        g_at.append(ga)
    force = jnp.stack(forces)
    sgn = jnp.array([1.0, -1.0])[:, None]
    along = jnp.sum(sgn * force * eL, axis=1)
    across = jnp.sum(sgn * force * perp, axis=1)
    mag = jnp.hypot(along, across)
    torque = jnp.stack(torques)
    wc, wO, wI = roller_patch_speeds(P["omega_I"], P["omega_O"], P["R_I"], P["R_O"])
    k, res, ok, _ = stats
    loads = jnp.stack([FO, FI])
    # with a rigid ring the roller rests on it: only the other side can open
    gaps = g_at[0] + g_at[1] if (cfg.outer and cfg.inner) else gap
    return RollerResult(
        roller_angles=psi, roller_loads=loads, penetration_outer=geo["dO"], penetration_inner=geo["dI"],
        deflection=geo["dO"] + geo["dI"], ring_shift=x[Z], u_at_rollers=jnp.stack(u_at), gaps=gaps,
        min_gaps=gap, active=jnp.max(loads, axis=0) > 0, theta=jnp.stack(thetas),
        pressure=jnp.stack(pressures), displacement=jnp.stack(disps), force=force,
        force_angle=jnp.arctan2(across, along), friction_angle=jnp.arctan2(jnp.abs(across), jnp.abs(along)),
        torque=torque, friction_radius=jnp.abs(torque) / mag, cage_speed=wc, patch_speed=jnp.stack([wO, wI]),
        iterations=k, residual=res, converged=ok)


@partial(jax.jit, static_argnums=(2, 3, 4))
def _solve(P, start, cfg, tol, max_iter):
    """Newton at the root with implicit derivatives, then the outputs (compiled once per config)."""
    start = jax.lax.stop_gradient(start)

    def solver(prm):
        return _newton(prm, cfg, tol, max_iter, start)

    x, stats = implicit_root(lambda xx, prm: _residual(xx, prm, cfg), solver)(P)
    return _outputs(x, P, cfg, stats)


def _check_material(name, m):
    if m is not None and not isinstance(m, Material):
        raise ValueError(f"{name} must be a vjax.Material or None (rigid ring), got {type(m).__name__}")


def roller_bearing(outer, inner, R_outer, R_inner, roller_diameter, n_rollers: int, load, *,
                   clearance=None, load_angle=0.0, roller_angle=None, omega_inner=0.0, omega_outer=0.0,
                   memory="periodic", n: int = 1024, temperature=None, shift=None,
                   ref_length=1.0, initial=None, tol: float = 1e-10, max_iter: int = 40, throw: bool = True,
                   options: SolverOptions = SolverOptions()) -> RollerResult:
    """Needle roller bearing: load sharing, ring deformation and viscoelastic friction torque.

    Args:
      outer, inner: materials of the outer ring (hole in an infinite plane, A.45) and the
        inner ring (cylinder fixed at its centre, A.60); ``None`` = rigid ring (not both).
      R_outer, R_inner: raceway radii R_O > R_I (m). roller_diameter: D (m).
      n_rollers: Z (static), equally spaced; they must fit on the pitch circle.
      load: radial load on the inner ring (N/m), > 0, along ``load_angle`` (rad).
      clearance: diametral clearance P_d (m), default 2 (R_O - R_I - D) (Eq. 2.26); negative
        means preload; it must exceed -D. When given, the contact uses rollers of diameter
        R_O - R_I - P_d/2 (matched sets), so it takes precedence over ``roller_diameter``.
      roller_angle: angle of roller 1 (rad), default ``load_angle`` (a roller on the load line).
      omega_inner, omega_outer: ring speeds (rad/s); the patch speeds follow from pure
        rolling (:func:`roller_patch_speeds`).
      memory: "periodic" (default), "thesis" or a number of revolutions (:mod:`vjax.operator`).
      n: elements on each ring (static).
      temperature, shift: evaluate both materials at ``temperature`` with the shift law
        ``shift`` (:meth:`~vjax.Material.at_temperature`; both or neither).
      ref_length: log-R reference length of the Green's functions (m).
      initial: a :class:`RollerResult` of the same bearing at nearby parameters (e.g. the
        previous speed of a sweep): Newton starts from its deflections and the contact
        solves from its pressures. Only the speed of convergence depends on it.
      tol, max_iter: Newton tolerance (max-norm of the equations scaled by load/Z and load)
        and iteration cap. throw: raise :class:`~vjax.ConvergenceError` on failure (inside
        jit too); with False inspect ``converged``. options: the contact solves' options.

    Differentiable (jit, vmap, grad, jacfwd) in the materials, radii, diameter, clearance,
    load, angles and speeds, by implicit differentiation at the converged solution.

    >>> m = Material.sls(1e6, 1e7, 0.01, 0.5)
    >>> r = roller_bearing(m, m, 6e-3, 4e-3, 2e-3, 9, 6.5e-3 * 1e6 * 6e-3, n=256)
    >>> bool(r.converged), [round(float(f), 1) for f in r.roller_loads[0, :3]]
    (True, [17.5, 13.7, 2.9])
    """
    _check_material("outer", outer)
    _check_material("inner", inner)
    if outer is None and inner is None:
        raise ValueError("outer and inner cannot both be None: at least one ring must be deformable")
    if (temperature is None) != (shift is None):
        raise ValueError("temperature and shift must be given together (shift: a WLF/Arrhenius law)")
    for name, val in (("R_outer", R_outer), ("R_inner", R_inner), ("roller_diameter", roller_diameter),
                      ("load", load), ("ref_length", ref_length)):
        _checks.positive(name, val)
    for name, val in (("load_angle", load_angle), ("omega_inner", omega_inner), ("omega_outer", omega_outer)):
        _checks.finite(name, val)
    if roller_angle is not None:
        _checks.finite("roller_angle", roller_angle)
    for name, val in (("R_outer", R_outer), ("R_inner", R_inner), ("roller_diameter", roller_diameter),
                      ("load", load), ("load_angle", load_angle), ("omega_inner", omega_inner),
                      ("omega_outer", omega_outer), ("ref_length", ref_length)):
        _checks.scalar(name, val)
    if not (isinstance(tol, (int, float, np.floating)) and np.isfinite(tol) and tol > 0):
        raise ValueError(f"tol must be a finite number > 0, got {tol!r}")
    if not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    _checks.instance("options", options, SolverOptions, "a vjax.SolverOptions")
    if not isinstance(n_rollers, (int, np.integer)) or n_rollers < 2:
        raise ValueError(f"n_rollers must be an integer >= 2, got {n_rollers!r}")
    if not isinstance(n, (int, np.integer)) or n < 16:
        raise ValueError(f"n (elements per ring) must be an integer >= 16, got {n!r}")
    memory_revolutions(memory)
    Z = int(n_rollers)
    ro, ri, D = (_checks.values(k, v) for k, v in (("R_outer", R_outer), ("R_inner", R_inner),
                                                    ("roller_diameter", roller_diameter)))
    pd = None if clearance is None else _checks.values("clearance", clearance)
    if ro is not None and ri is not None and not np.all(ri < ro):
        raise ValueError(f"R_inner must be smaller than R_outer, got R_inner={R_inner!r} >= R_outer={R_outer!r}")
    if ro is not None and ri is not None and D is not None:
        if pd is not None and not np.all(pd > -D):
            raise ValueError(f"clearance must exceed -roller_diameter = {-float(np.max(D)):.4g} m "
                             f"(a preload larger than the rollers), got {clearance!r}")
        d_eff = D if pd is None else ro - ri - pd / 2
        if not np.all(d_eff > 0):
            raise ValueError(f"clearance={clearance!r} leaves no room for rollers (R_outer - R_inner - "
                             f"clearance/2 <= 0)")
        if pd is None and not np.all(D > 0.5 * (ro - ri)):
            raise ValueError(f"roller_diameter={roller_diameter!r} is less than half the radial space "
                             f"R_outer - R_inner: the diametral clearance exceeds the roller size")
        pitch = 0.5 * (ro + ri)
        if not np.all(2 * pitch * np.sin(np.pi / Z) > d_eff):
            raise ValueError(f"n_rollers={Z} rollers of diameter {float(np.max(d_eff)):.4g} m do not fit on "
                             f"the pitch circle of radius {float(np.min(pitch)):.4g} m (need Z D < "
                             f"2 pi R_pitch, exactly 2 R_pitch sin(pi/Z) > D)")
    if temperature is not None:
        outer = None if outer is None else outer.at_temperature(shift, temperature)
        inner = None if inner is None else inner.at_temperature(shift, temperature)

    Pd = 2 * (R_outer - R_inner - roller_diameter) if clearance is None else jnp.asarray(clearance, float)
    r = 0.5 * (R_outer - R_inner - 0.5 * Pd)
    wc, wO, wI = roller_patch_speeds(omega_inner, omega_outer, R_inner, R_outer)
    psi0 = load_angle if roller_angle is None else roller_angle
    psi = psi0 + 2 * jnp.pi * jnp.arange(Z) / Z
    P = dict(R_O=jnp.asarray(R_outer, float), R_I=jnp.asarray(R_inner, float), r=r, Pd=Pd,
             load=jnp.asarray(load, float), load_angle=jnp.asarray(load_angle, float), psi=psi,
             omega_I=jnp.asarray(omega_inner, float), omega_O=jnp.asarray(omega_outer, float))
    P["opO"] = None if outer is None else ring_operator("hole", outer, R_outer, n, wO, memory, ref_length)
    P["opI"] = None if inner is None else ring_operator("cylinder", inner, R_inner, n, wI, memory, ref_length)
    # stiffness scales of the gap terms: they only place unloaded rollers (no derivative needed)
    # (one scale, the softer ring's E0, for both: a stiffness contrast would only hurt Newton)
    k = jnp.minimum(*(jax.lax.stop_gradient(m.E0) for m in (outer, inner) if m is not None)) \
        if (outer is not None and inner is not None) else jax.lax.stop_gradient((outer or inner).E0)
    P["kO"] = P["kI"] = jnp.asarray(k, float)
    cfg = _Config(int(n), int(n), Z, outer is not None, inner is not None, options)

    start = None
    if initial is not None:
        if not isinstance(initial, RollerResult) or initial.pressure.shape != (2, n) or \
                initial.roller_angles.shape != (Z,):
            raise ValueError("initial must be a RollerResult of the same bearing (n_rollers and n)")
        start = (jnp.concatenate([initial.penetration_outer, jnp.atleast_1d(initial.ring_shift)]),
                 initial.pressure)
    res = _solve(P, start, cfg, float(tol), int(max_iter))
    check_converged("roller_bearing", res.converged, res.iterations, res.residual, throw)
    return res
