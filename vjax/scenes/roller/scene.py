"""Scene: needle roller bearing with viscoelastic rings and rigid rollers (thesis Section 2.3).

``n_rollers`` rigid rollers of diameter D sit between an outer ring, the ``housing`` (a hole of
radius R_O in an infinite plane, Green's function A.45, for a bare Material), and an inner
ring, the ``shaft`` (a disc of radius R_I fixed at its centre, A.60, for a bare Material).
Either ring may be viscoelastic, elastic, or rigid (``None``: no operator is built for it). A radial load ``load`` (N/m) along the direction ``load_angle``
pushes the inner ring; its centre moves by the ring shift delta_r along that direction (the
perpendicular motion is held, as in the thesis, and its force is a reaction). Roller j sits
at the angle psi_j = roller_angle + 2 pi j / Z (roller 1, index 0, on the load line by
default, numbering counter-clockwise as in Fig. 2.12).

**Geometry and equations** (:mod:`vjax.scenes.roller.geometry`, :mod:`vjax.scenes.roller.balance`).
Exact circles: each roller's overlap with each undeformed ring along every ray; on the
centre line the penetrations delta_j^O = rho_j + r - R_O and delta_j^I = R_I + r -
|rho_j e_j - C| sum to first order to Eq. 2.26, delta_j = delta_r cos psi_j - P_d/2, with the
diametral clearance P_d = 2 (R_O - R_I - D). A given ``diametral_clearance`` is realized by
the roller size (matched roller sets): the contact uses rollers of diameter R_O - R_I - P_d/2.
Each ring is one contact problem holding all roller patches (:func:`~vjax.solve_contact`;
the patches interact through the ring). The unknowns are the outer penetrations (Eq. 2.37)
and the ring shift; the equations each roller's radial balance and the load balance, written
so that unloaded rollers keep the Jacobian regular.

**Solve and derivatives.** The core's damped Newton (:func:`vjax._core.solve.newton`) with the
exact Jacobian (``jax.jacfwd`` through both contact solves, whose own derivatives are
implicit); derivatives of the result come from the implicit function theorem at the
converged root (:func:`vjax._core.solve.implicit_root`), then from the contact solves at that
root: nothing is differentiated through the iterations.

**Cost.** Each Newton iteration solves both rings (warm-started from the previous
iterate's pressures: one or two active-set steps) and 2 (Z + 1) tangent Krylov solves for
the Jacobian, which dominate at large n. From a cold start Newton takes 3-5 iterations;
continuing from a nearby solution (``initial=``, e.g. along a speed sweep) 1-3.

**Kinematics (Section 2.3.1).** With the shaft (inner ring) at omega_I = ``omega_shaft`` and the
housing (outer ring) at omega_O = ``omega_housing``, pure rolling gives the cage speed
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

**Outputs.** Forces and torques are those the contact pressure exerts on each ring, Eq.
2.38-2.40 on the deformed profile R +- u(theta), whose slope u' is taken spectrally: then
R sum p u' dtheta is exactly the power the ring dissipates divided by the patch speed (zero
for an elastic ring on any grid), and the torque is resolved even when the patches are a few
elements wide (n = 256: within 15% of n = 4096 for omega~ >= 0.04). ``force`` and ``torque``
are the housing's (outer ring, pushed along +load; torque about the bearing centre O,
counter-clockwise positive: with the housing fixed and the shaft turning at omega_I > 0 it is
positive, the housing is dragged along, and the torque a motor must supply is about the
same); ``force_shaft`` and ``torque_shaft`` the inner ring's (pushed along -load; torque
about O, including the moment C x F of its offset). ``force_angle`` is the angle of the
housing's net force from the load line, ``friction_angle`` = arccos(|F_r|/|F|) and
``friction_radius`` = |torque|/|force| (Section 2.3.1).
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

from ..._core import checks, scene as _scene, solve as _solve, xla
from . import balance
from ...bodies.body import as_body, check_fits, disc, hole
from ...contact.solve import ContactOptions
from ...bodies.operator import grid, memory_revolutions, spectral_derivative

HOUSINGS = ("hole", "liner")
SHAFTS = ("disc", "sleeve")


@dataclasses.dataclass(frozen=True)
class RollerOptions:
    """Static options of :func:`roller_bearing`: ``n`` elements per ring, the Newton tolerance
    ``tol`` (max-norm of the balance equations scaled by load/Z and load) and cap ``max_iter``
    (Newton steps), and the ring contact solves' :class:`~vjax.ContactOptions`."""

    n: int = 1024
    tol: float = 1e-10
    max_iter: int = 40
    contact: ContactOptions = ContactOptions(window=False)   # patches all round the rings

    def __post_init__(self):
        checks.option_count("n", self.n, 16)
        checks.option_number("tol", self.tol)
        checks.option_count("max_iter", self.max_iter)
        checks.instance("contact", self.contact, ContactOptions, "a vjax.ContactOptions")


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class RollerResult(_scene.SceneResult):
    """Solution of :func:`roller_bearing`. Lengths in m, angles in rad, forces in N/m,
    torques in N m/m, per unit axial length.

    theta: (n,) element centres (the inner ring's angles are about its own centre).
    pressure, displacement: (n,) on the outer ring (housing) (Pa, m, positive into the ring;
    zeros for a rigid ring); pressure_shaft, displacement_shaft: (n,) the inner ring's.
    force: (2,) net force on the housing (x, y); force_shaft: (2,) on the inner ring.
    torque: friction torque on the housing about O; torque_shaft: on the inner ring about O
    (see the module docstring for signs). force_angle, friction_angle, friction_radius: of
    the housing's force (rad, rad, m).
    roller_angles: psi_j (Z,). roller_loads: (2, Z) radial force of the outer and inner ring on
    each roller (equal rows at convergence). penetration_outer, penetration_inner: delta_j^O,
    delta_j^I (Z,), centre-line overlaps with the undeformed rings; deflection: their sum
    (Eq. 2.26 to first order). ring_shift: delta_r. u_at_rollers: (2, Z) ring displacements
    at psi_j. gaps: (Z,) clearance at the roller centre line, g(psi_j) = u_O + u_I - delta_j
    (zero while loaded). min_gaps: (Z,) smallest gap between roller and rings. active: (Z,)
    the roller carries load. cage_speed: omega_c; patch_speed: (omega_c - omega_O,
    omega_c - omega_I) (rad/s). jacobian: (Z + 1, Z + 1) the balance equations' Jacobian last
    used by Newton (scaled equations per m), passed on by ``initial=``.
    iterations, residual, result: the Newton solve's report (Newton steps; the residual is the
    max-norm of the scaled equations; a failed ring contact solve makes a trial point
    invalid); ``converged`` is ``result == 0``.
    """

    theta: jax.Array
    pressure: jax.Array
    displacement: jax.Array
    pressure_shaft: jax.Array
    displacement_shaft: jax.Array
    force: jax.Array
    force_shaft: jax.Array
    torque: jax.Array
    torque_shaft: jax.Array
    force_angle: jax.Array
    friction_angle: jax.Array
    friction_radius: jax.Array
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
    cage_speed: jax.Array
    patch_speed: jax.Array
    jacobian: jax.Array
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array


def roller_patch_speeds(omega_shaft, omega_housing, R_inner, R_outer):
    """Cage speed omega_c and patch speeds relative to (outer, inner) ring (rad/s).

    omega_c = (omega_I R_I + omega_O R_O) / (R_I + R_O) (pure rolling, Section 2.3.1); the
    pattern moves at omega_c - omega_O relative to the outer ring and omega_c - omega_I
    relative to the inner ring (the sign convention of :func:`~vjax.ring_operator`).
    """
    wc = (omega_shaft * R_inner + omega_housing * R_outer) / (R_inner + R_outer)
    return wc, wc - omega_housing, wc - omega_shaft


def _ring_outputs(name, o, geo, psi):
    """Force (2,) and torque about O of the pressure on one deformable ring, Eq. 2.38-2.40,
    and its displacement and gap at the rollers."""
    th, p, u, R = o["theta"], o["p"], o["u"], o["R"]
    # slope u' of the deformed profile, spectral: then R sum p u' is exactly the modal
    # dissipation / patch speed (zero for an elastic ring on any grid). The exact roller
    # slope inside the patches is not: on a grid not symmetric about the rollers it leaves a
    # torque of O(h) (170% of it at n = 256, 10-20% at 1024).
    du = spectral_derivative(u)
    er = jnp.stack([jnp.cos(th), jnp.sin(th)])
    et = jnp.stack([-jnp.sin(th), jnp.cos(th)])
    dth = 2 * o["alpha"]
    if name == "O":
        # into-body (outward) normal R e_r - u' e_theta; P = (R + u) e_r
        F = dth * jnp.sum(p * (R * er - du * et), axis=1)
        T = -dth * jnp.sum(p * (R + u) * du)
        at = psi
    else:
        # inward normal -R e_r - u' e_theta; P = C + (R - u) e_r
        F = dth * jnp.sum(p * (-R * er - du * et), axis=1)
        T = -dth * jnp.sum(p * (R - u) * du) + (geo["C"][0] * F[1] - geo["C"][1] * F[0])
        at = geo["psi_i"]
    u_at = jnp.interp(at, th, u, period=2 * jnp.pi)
    g_at = jnp.where(o["F"] > 0, 0.0, jnp.interp(at, th, o["g"], period=2 * jnp.pi))
    return F, T, p, u, u_at, g_at


def _outputs(x, P, cfg, warm, stats, speeds, jacobian):
    Z, n = cfg.Z, cfg.n
    _, (out, geo, FO, FI, gap) = balance.equations(x, P, cfg, warm)
    zeros_n, zeros_z = jnp.zeros(n, x.dtype), jnp.zeros(Z, x.dtype)
    if "O" in out:
        F_O, T_O, p_O, u_O, ua_O, ga_O = _ring_outputs("O", out["O"], geo, P.psi)
    else:  # rigid outer ring: the rollers push it along their radii
        F_O, T_O = jnp.sum(FI[:, None] * geo["e"], axis=0), jnp.zeros((), x.dtype)
        p_O = u_O = zeros_n
        ua_O = ga_O = zeros_z
    if "I" in out:
        F_I, T_I, p_I, u_I, ua_I, ga_I = _ring_outputs("I", out["I"], geo, P.psi)
    else:  # rigid inner ring: pushed along the lines of centres
        ei = jnp.stack([jnp.cos(geo["psi_i"]), jnp.sin(geo["psi_i"])], axis=1)
        F_I = -jnp.sum(FO[:, None] * ei, axis=0)
        T_I = geo["C"][0] * F_I[1] - geo["C"][1] * F_I[0]
        p_I = u_I = zeros_n
        ua_I = ga_I = zeros_z
    eL = geo["eL"]
    along, across = F_O @ eL, F_O @ jnp.stack([-eL[1], eL[0]])
    loads = jnp.stack([FO, FI])
    # with a rigid ring the roller rests on it: only the other side can open
    gaps = ga_O + ga_I if len(out) == 2 else gap
    wc, wO, wI = speeds
    return RollerResult(
        theta=grid(n)[0], pressure=p_O, displacement=u_O, pressure_shaft=p_I, displacement_shaft=u_I,
        force=F_O, force_shaft=F_I, torque=T_O, torque_shaft=T_I,
        force_angle=jnp.arctan2(across, along), friction_angle=jnp.arctan2(jnp.abs(across), jnp.abs(along)),
        friction_radius=jnp.abs(T_O) / jnp.hypot(along, across), roller_angles=P.psi, roller_loads=loads,
        penetration_outer=geo["dO"], penetration_inner=geo["dI"], deflection=geo["dO"] + geo["dI"],
        ring_shift=x[Z], u_at_rollers=jnp.stack([ua_O, ua_I]), gaps=gaps, min_gaps=gap,
        active=jnp.max(loads, axis=0) > 0, cage_speed=wc, patch_speed=jnp.stack([wO, wI]),
        jacobian=jacobian, iterations=stats.iterations, residual=stats.residual, result=stats.result)


@xla.jit(static_argnums=(3, 4), options={}, required=xla.NOT_LEVEL_0)
def _solve_bearing(P, start, speeds, cfg, options):
    """Newton at the root with implicit derivatives, then the outputs (compiled once per config)."""
    def solver(params):
        prm, start = params

        def equations(x, warm):
            r, (out, *_) = balance.equations(x, prm, cfg, warm)
            return r, balance.pressures(out, cfg.n, x.dtype), balance.contacts_converged(out)

        # from a nearby solution (a starting point only), Jacobians kept; a start that is not
        # finite (a cold start: NaN) is an exact Newton from the initial guess, in the same program
        x0, p0, J0 = jax.lax.stop_gradient(start)
        warm_start = jnp.all(jnp.isfinite(x0))
        x0 = jnp.where(warm_start, x0, balance.initial_guess(prm, cfg))
        p0, J0 = jnp.where(warm_start, p0, 0.0), jnp.where(warm_start, J0, 0.0)
        x, warm, stats, J = _solve.newton(equations, x0, p0, tol=options.tol, max_iter=options.max_iter,
                                          max_step=jnp.full(x0.shape, 0.1) * prm.r, jacobian=J0,
                                          keep_jacobian=warm_start, return_jacobian=True)
        return x, (warm, stats, J)

    # the derivative's contact solves start from the converged pressures
    # (the start rides in the parameters, with no part in the residual: a closure over it would
    # leak its tracer out of implicit_root's custom_jvp under linearize)
    residual = lambda x, aux, params: balance.equations(x, params[0], cfg, aux[0])[0]
    x, (warm, stats, J) = _solve.implicit_root(solver, residual)((P, start))
    return _outputs(x, P, cfg, warm, stats, speeds, J)


def roller_bearing(housing, shaft, R_outer, R_inner, roller_diameter, n_rollers: int, load, *,
                   diametral_clearance=None, load_angle=0.0, roller_angle=None, omega_shaft=0.0,
                   omega_housing=0.0, memory="periodic", temperature=None, shift=None,
                   initial: "RollerResult | None" = None, options: RollerOptions = RollerOptions(),
                   throw: bool = True) -> RollerResult:
    """Needle roller bearing: load sharing, ring deformation and viscoelastic friction torque.

    Args:
      housing: body of the outer ring: a :class:`~vjax.Material` (a hole in an infinite
        plane, A.45), a hole or a :func:`~vjax.liner`, or ``None`` for a rigid ring.
      shaft: body of the inner ring: a :class:`~vjax.Material` (a disc fixed at its centre,
        A.60), a disc or a :func:`~vjax.sleeve`, or ``None`` for a rigid ring (not both).
      R_outer: outer raceway radius R_O > R_I (m).
      R_inner: inner raceway radius R_I (m).
      roller_diameter: D (m).
      n_rollers: Z (static), equally spaced; they must fit on the pitch circle.
      load: radial load on the inner ring (N/m), > 0, along ``load_angle`` (rad).
      diametral_clearance: P_d (m), default 2 (R_O - R_I - D) (Eq. 2.26); negative means
        preload; it must exceed -D. When given, the contact uses rollers of diameter
        R_O - R_I - P_d/2 (matched sets), so it takes precedence over ``roller_diameter``.
      roller_angle: angle of roller 1 (rad), default ``load_angle`` (a roller on the load line).
      omega_shaft: inner ring speed (rad/s).
      omega_housing: outer ring speed (rad/s); the patch speeds follow from pure rolling
        (:func:`roller_patch_speeds`).
      memory: "periodic" (default), "thesis" or a number of revolutions (:mod:`vjax.bodies.operator`).
      temperature: the rings' temperature (C): each ring whose material has a shift law
        (:meth:`~vjax.Material.with_shift`) and no temperature of its own answers at it.
      shift: deprecated since 0.3 (a DeprecationWarning): the shift law of every material that
        has none; give each material its own instead.
      initial: a :class:`RollerResult` of the same bearing at nearby parameters (e.g. the
        previous speed of a sweep): Newton starts from its deflections and the contact
        solves from its pressures. Only the speed of convergence depends on it. A result whose
        deflections are not finite (NaN) starts cold, in the same compiled program (the first
        point of a ``lax.scan`` sweep).
      options: :class:`RollerOptions` (grid, Newton tolerance and cap, contact options; static).
      throw: raise :class:`~vjax.ConvergenceError` on failure (inside jit too); with False
        inspect ``converged`` and ``result``.

    Differentiable (jit, vmap, grad, jacfwd) in the bodies, radii, diameter, clearance,
    load, angles and speeds, by implicit differentiation at the converged solution.

    >>> from vjax import Material
    >>> m = Material.sls(1e6, 1e7, 0.01, 0.5)
    >>> r = roller_bearing(m, m, 6e-3, 4e-3, 2e-3, 9, 6.5e-3 * 1e6 * 6e-3, options=RollerOptions(n=256))
    >>> bool(r.converged), [round(float(f), 1) for f in r.roller_loads[0, :3]]
    (True, [17.5, 13.7, 2.9])
    """
    housing = as_body("housing", housing, hole, HOUSINGS)
    shaft = as_body("shaft", shaft, disc, SHAFTS)
    if housing is None and shaft is None:
        raise ValueError("housing and shaft cannot both be None: at least one ring must be deformable")
    checks.instance("options", options, RollerOptions, "a vjax.RollerOptions")
    _scene.scalars(checks.positive, R_outer=R_outer, R_inner=R_inner, roller_diameter=roller_diameter, load=load)
    _scene.scalars(checks.finite, load_angle=load_angle, omega_shaft=omega_shaft, omega_housing=omega_housing)
    if roller_angle is not None:
        _scene.scalars(checks.finite, roller_angle=roller_angle)
    if diametral_clearance is not None:
        _scene.scalars(checks.finite, diametral_clearance=diametral_clearance)
    if not isinstance(n_rollers, (int, np.integer)) or n_rollers < 2:
        raise ValueError(f"n_rollers must be an integer >= 2, got {n_rollers!r}")
    memory_revolutions(memory)
    Z = int(n_rollers)
    _check_fit(R_outer, R_inner, roller_diameter, diametral_clearance, Z)
    check_fits("housing", housing, R_outer)
    check_fits("shaft", shaft, R_inner)
    housing, shaft = _scene.at_temperature(temperature, shift, housing, shaft)

    Pd = 2 * (R_outer - R_inner - roller_diameter) if diametral_clearance is None else diametral_clearance
    speeds = roller_patch_speeds(omega_shaft, omega_housing, R_inner, R_outer)
    _, wO, wI = speeds
    psi0 = load_angle if roller_angle is None else roller_angle
    n = options.n
    # stiffness scale of the gap terms: it only places unloaded rollers (no derivative needed);
    # one scale, the softer ring's E0, for both: a stiffness contrast would only hurt Newton
    k = jnp.min(jnp.stack([jax.lax.stop_gradient(b.material.E0) for b in (housing, shaft) if b is not None]))
    f = lambda v: jnp.asarray(v, jnp.result_type(float))
    P = balance.Params(
        R_O=f(R_outer), R_I=f(R_inner), r=f(0.5 * (R_outer - R_inner - 0.5 * Pd)), Pd=f(Pd), load=f(load),
        load_angle=f(load_angle), psi=psi0 + 2 * jnp.pi * jnp.arange(Z) / Z, k=f(k),
        op_outer=None if housing is None else housing.operator(R_outer, n, wO, memory),
        op_inner=None if shaft is None else shaft.operator(R_inner, n, wI, memory))
    dtype = jnp.result_type(float)
    start = (jnp.full(Z + 1, jnp.nan, dtype), jnp.zeros((2, n), dtype), jnp.zeros((Z + 1, Z + 1), dtype))  # cold
    if initial is not None:
        if not isinstance(initial, RollerResult) or initial.pressure.shape != (n,) or \
                initial.roller_angles.shape != (Z,):
            raise ValueError("initial must be a RollerResult of the same bearing (n_rollers and n)")
        start = (jnp.concatenate([initial.penetration_outer, jnp.atleast_1d(initial.ring_shift)]),
                 jnp.stack([initial.pressure, initial.pressure_shaft]), initial.jacobian)
    res = _solve_bearing(P, start, speeds, balance.Config(n, Z, options.contact), options)
    _solve.report("roller_bearing", res, throw)
    return res


def _check_fit(R_outer, R_inner, roller_diameter, clearance, Z):
    """Concrete geometry must leave room for Z rollers (the checks skip traced values)."""
    ro, ri, D = (checks.values(k, v) for k, v in (("R_outer", R_outer), ("R_inner", R_inner),
                                                    ("roller_diameter", roller_diameter)))
    pd = None if clearance is None else checks.values("diametral_clearance", clearance)
    if ro is not None and ri is not None and not np.all(ri < ro):
        raise ValueError(f"R_inner must be smaller than R_outer, got R_inner={R_inner!r} >= R_outer={R_outer!r}")
    if ro is None or ri is None or D is None:
        return
    if pd is not None and not np.all(pd > -D):
        raise ValueError(f"diametral_clearance must exceed -roller_diameter = {-float(np.max(D)):.4g} m "
                         f"(a preload larger than the rollers), got {clearance!r}")
    d_eff = D if pd is None else ro - ri - pd / 2
    if not np.all(d_eff > 0):
        raise ValueError(f"diametral_clearance={clearance!r} leaves no room for rollers (R_outer - R_inner - "
                         f"clearance/2 <= 0)")
    if pd is None and not np.all(D > 0.5 * (ro - ri)):
        raise ValueError(f"roller_diameter={roller_diameter!r} is less than half the radial space "
                         f"R_outer - R_inner: the diametral clearance exceeds the roller size")
    pitch = 0.5 * (ro + ri)
    if not np.all(2 * pitch * np.sin(np.pi / Z) > d_eff):
        raise ValueError(f"n_rollers={Z} rollers of diameter {float(np.max(d_eff)):.4g} m do not fit on "
                         f"the pitch circle of radius {float(np.min(pitch)):.4g} m (need Z D < "
                         f"2 pi R_pitch, exactly 2 R_pitch sin(pi/Z) > D)")
