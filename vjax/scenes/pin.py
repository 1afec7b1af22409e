"""Scene: rigid pin rolling in a hole in a viscoelastic body (thesis Section 2.2).

A pin of radius R - c rolls without slip inside a bore of radius ``R`` (radial clearance
``c``), pushed by the load ``load`` (N/m) along ``load_angle``; the pin is free along the
load (its offset ``e`` is solved for) and held across it (that force is a reaction). Rolling
moves the contact patch relative to the housing at (:func:`pin_patch_speed`, after Eq. 2.9)

    Omega = -(omega_shaft - omega_housing) (R - c) / c.

The housing is a :func:`~vjax.hole` in an infinite plane (a bare Material) or a bonded
layer; the pin is rigid. The exact circle geometry sets the overlap (phi = load_angle):

    d(theta) = e cos(theta - phi) + sqrt((R - c)^2 - e^2 sin^2(theta - phi)) - R.

Outputs are those of the scene contract: ``force`` is the force the pin exerts **on the
housing** (x, y; its component along the load equals the load), ``torque`` the friction
torque on the housing about its centre, Eq. 2.24, counter-clockwise positive (it drags the
housing along with the shaft: the sign of omega_shaft - omega_housing). Load control
imposes the full Eq. 2.21, slope terms included: in the thesis case they are not small (u'/R
reaches 0.1, about 1% of the load).
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp

from .._core import checks, scene as _scene, solve as _solve, xla
from ..bodies.body import Body, as_body, check_fits, hole
from ..contact.solve import ContactOptions, solve_contact, solve_with_fallback
from ..bodies.operator import grid, memory_revolutions, spectral_derivative

HOUSINGS = ("hole", "liner")


@dataclasses.dataclass(frozen=True)
class PinOptions(ContactOptions):
    """Static options of :func:`pin_in_hole`: ``n`` elements on the bore, and the contact
    solve's options (``tol``, ``max_iter`` active-set steps, Krylov settings; see
    :class:`~vjax.ContactOptions`)."""

    n: int = 1024

    def __post_init__(self):
        super().__post_init__()
        checks.option_count("n", self.n, 16)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class PinResult(_scene.SceneResult):
    """Solution of :func:`pin_in_hole`. Angles in rad, lengths in m, per unit axial length.

    theta: (n,) element centres. pressure: (n,) p(theta) on the bore (Pa). displacement: (n,)
    u_r(theta) of the bore, positive into the housing (m). force: (Fx, Fy) the pin exerts on
    the housing (N/m, Eq. 2.21-2.22 with the sign of the housing). torque: friction torque on
    the housing about its centre (N m/m, Eq. 2.24, counter-clockwise positive). force_angle:
    angle of ``force`` from the load line (rad, Eq. 2.23). friction_radius: |torque|/|force|
    (m, Eq. 2.25). pin_offset: e, the pin centre's offset along the load (m). patch_speed:
    Omega (rad/s). contact_mask: (n,) elements in contact; contact_angle: contact semi-angle
    of a single patch (rad). iterations, residual, result: the contact solve's report
    (active-set steps on the final grid); ``converged`` is ``result == 0``.
    """

    theta: jax.Array
    pressure: jax.Array
    displacement: jax.Array
    force: jax.Array
    torque: jax.Array
    force_angle: jax.Array
    friction_radius: jax.Array
    pin_offset: jax.Array
    patch_speed: jax.Array
    contact_mask: jax.Array
    contact_angle: jax.Array
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array


def pin_patch_speed(omega_shaft, omega_housing, R, radial_clearance):
    """Angular velocity (rad/s) of the contact patch relative to the housing for a pin
    rolling in the bore: -(omega_shaft - omega_housing) (R - c) / c."""
    return -(omega_shaft - omega_housing) * (R - radial_clearance) / radial_clearance


def pin_shaft_speed(patch_speed, R, radial_clearance, omega_housing=0.0):
    """The pin speed (rad/s) that moves the patch at ``patch_speed`` relative to the housing:
    the inverse of :func:`pin_patch_speed` (the thesis's omega~ = |Omega| tau is a patch speed)."""
    return omega_housing - patch_speed * radial_clearance / (R - radial_clearance)


def _prolong(values, factor: int):
    """Periodic linear interpolation from a grid of elements to one ``factor`` times finer
    (both with an element centre at theta = 0)."""
    w = jnp.arange(factor) / factor
    return ((1 - w) * values[:, None] + w * jnp.roll(values, -1)[:, None]).reshape(-1)


def _pin_interference(q, args):
    R, R_pin, theta = args
    e = q[0]
    # A ray from the hole centre that misses the pin (only possible for e > R_pin, e.g. a
    # Newton step at huge load) has no overlap: far away, not NaN ("double where").
    s = R_pin**2 - (e * jnp.sin(theta)) ** 2
    hit = s > 0
    return jnp.where(hit, e * jnp.cos(theta) + jnp.sqrt(jnp.where(hit, s, 1.0)) - R, -R)


def _pin_force(sigma, u, args):
    """Force on the housing along the load, -(Eq. 2.21): R dtheta sum p (cos + u'/R sin)."""
    R, _, theta = args
    du = spectral_derivative(u)
    return (2 * jnp.pi / theta.shape[0]) * jnp.sum(sigma * (R * jnp.cos(theta) + du * jnp.sin(theta)))[None]


def pin_in_hole(housing, R, radial_clearance, load, *, omega_shaft=0.0, omega_housing=0.0, load_angle=0.0,
                memory="periodic", temperature=None, shift=None, initial: "PinResult | None" = None,
                options: PinOptions = PinOptions(), throw: bool = True) -> PinResult:
    """Rigid pin rolling in the bore of a viscoelastic housing under the load ``load``.

    Args:
      housing: the housing's body: a :class:`~vjax.Material` (a hole in an infinite plane,
        :func:`~vjax.hole` with ``ref_length`` 1 m), a hole, or a :func:`~vjax.liner` (a
        bushing bonded into a rigid holder).
      R: bore radius (m).
      radial_clearance: c = R - R_pin (m), 0 < c < R.
      load: force on the pin (N/m), > 0, along ``load_angle`` (rad from the x axis).
      omega_shaft: angular velocity of the pin (rad/s).
      omega_housing: angular velocity of the housing (rad/s); the patch moves at
        :func:`pin_patch_speed` relative to the housing (thesis omega~ = |Omega| tau).
      memory: "periodic" (default), "thesis" or revolutions (see :mod:`vjax.bodies.operator`).
      temperature: the housing's temperature (C), when its material has a shift law
        (:meth:`~vjax.Material.with_shift`) and no temperature of its own.
      shift: deprecated since 0.3 (a DeprecationWarning): the material's shift law; give the
        material its own instead.
      initial: a :class:`PinResult` of the same pin (same n) at nearby parameters: the solve
        starts from its pressure and offset (fewer active-set steps; no derivative flows).
      options: :class:`PinOptions` (grid and contact solve; static).
      throw: raise :class:`~vjax.ConvergenceError` when the solve fails (inside jit too);
        with False, inspect ``converged`` and ``result``.

    The hole's ``ref_length`` sets the absolute pin offset (the plane's rigid mode 1) and,
    through the exact circle geometry and the slope terms of Eq. 2.21, changes the pressure
    at second order in e/R: 1.9% of the peak in the Persson case (c = 4e-5 m, F~ = 2.3e-2)
    between 1 m and the small-displacement choice e = c.

    Differentiable (jit, vmap, grad, jacfwd) in the body, radii, load, angle and speeds;
    compiled once per options and material shape.

    >>> from vjax import Material
    >>> m = Material.sls(1e6, 1e7, 0.01, 0.5)
    >>> r = pin_in_hole(m, 0.08, 0.005, 3.5e-2 * 1e6 * 0.08, omega_shaft=-100.0 / 15, options=PinOptions(n=512))
    >>> bool(r.converged), round(float(r.force[0]) / 2800.0, 12), round(float(r.patch_speed), 9)
    (True, 1.0, 100.0)
    """
    housing = as_body("housing", housing, hole, HOUSINGS)
    if housing is None:
        raise ValueError("housing must be a deformable body: a rigid pin in a rigid hole has no contact solution")
    checks.instance("options", options, PinOptions, "a vjax.PinOptions")
    _scene.scalars(checks.positive, R=R, radial_clearance=radial_clearance, load=load)
    _scene.scalars(checks.finite, omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle)
    r_, c_ = checks.values("R", R), checks.values("radial_clearance", radial_clearance)
    if r_ is not None and c_ is not None and not c_ < r_:
        raise ValueError(f"radial_clearance must be smaller than the bore radius R, got "
                         f"radial_clearance={radial_clearance!r} >= R={R!r}")
    check_fits("housing", housing, R)
    (housing,) = _scene.at_temperature(temperature, shift, housing)
    start = None
    if initial is not None:
        if not isinstance(initial, PinResult) or initial.pressure.shape != (options.n,):
            raise ValueError(f"initial must be a PinResult of the same pin (n = {options.n})")
        start = (initial.pin_offset, initial.pressure)
    omega = pin_patch_speed(omega_shaft, omega_housing, R, radial_clearance)
    R, radial_clearance, load, load_angle, omega = _scene.canonical(R, radial_clearance, load, load_angle, omega)
    # the memory as a traced number of revolutions (inf: periodic): one program for every model
    memory = jnp.asarray(memory_revolutions(memory), jnp.result_type(float))
    result = solve_with_fallback(
        lambda opts: _pin_in_hole(housing, R, radial_clearance, load, load_angle, omega, start, memory, opts),
        options)
    _solve.report("pin_in_hole", result, throw)
    return result


@xla.jit(static_argnums=(8,))
def _pin_in_hole(housing: Body, R, c, load, load_angle, omega, start, memory, options):
    n = options.n
    R_pin = R - c

    def solve(n_, q0, sigma_init, tol=None):
        op = housing.operator(R, n_, omega, memory)
        # the grid measured from the load line: the pin moves along theta = 0
        theta = grid(n_)[0] - load_angle
        F = jnp.asarray(load, q0.dtype)[None]
        opts = options if tol is None else dataclasses.replace(options, tol=tol)
        return solve_contact(op, _pin_interference, (R, R_pin, theta), q0, _pin_force, F, opts,
                             sigma_init=sigma_init)

    def nested(n_, e0):
        """A start for the grid n_ from the solution on an 8x coarser grid, itself started the
        same way down to >= 64 elements (a cold start takes ~10 active-set steps; the coarsest
        level 4, the next 2-3 cheap ones; the fine grid then needs 2-3). Only a starting
        point: no derivative flows through it, and a coarse tolerance of 1e-6 is plenty."""
        if n_ // 8 < 64:
            # the coarsest grid starts from a Hertz-like pressure, sqrt of the overlap, that
            # carries the load: 4 active-set steps instead of 6 from zero pressure
            theta = grid(n_)[0] - load_angle
            bump = jnp.sqrt(jnp.maximum(_pin_interference(e0, (R, R_pin, theta)), 0.0))
            return e0, bump * (load / _pin_force(bump, jnp.zeros_like(bump), (R, R_pin, theta))[0])
        e0c, sigma_c = nested(n_ // 8, e0)
        coarse = solve(n_ // 8, e0c, sigma_c, tol=max(options.tol, 1e-6))
        return jnp.where(coarse.converged, coarse.q, e0), _prolong(coarse.pressure, 8)

    if start is not None:
        e0, sigma_init = jnp.atleast_1d(start[0]), start[1]
    else:
        e0 = jnp.asarray(c + 0.5 * load / housing.material.E0, jnp.result_type(float))[None]   # some overlap
        e0, sigma_init = nested(n, e0)
    sol = solve(n, e0, sigma_init)
    theta, alpha = grid(n)

    p, u = sol.pressure, sol.displacement
    du = spectral_derivative(u)
    dtheta = 2 * alpha
    # Force on the housing = -(Eq. 2.21, 2.22): p (e_r + u'/R e_theta) R dtheta.
    Fx = R * dtheta * jnp.sum(p * (jnp.cos(theta) + du / R * jnp.sin(theta)))
    Fy = R * dtheta * jnp.sum(p * (jnp.sin(theta) - du / R * jnp.cos(theta)))
    torque = R * dtheta * jnp.sum(p * du)                                   # Eq. 2.24
    mask = p > 0
    return PinResult(theta=theta, pressure=p, displacement=u, force=jnp.stack([Fx, Fy]), torque=torque,
                     force_angle=jnp.angle(jnp.exp(1j * (jnp.arctan2(Fy, Fx) - load_angle))),
                     friction_radius=jnp.abs(torque) / jnp.hypot(Fx, Fy), pin_offset=sol.q[0],
                     patch_speed=jnp.asarray(omega, p.dtype), contact_mask=mask,
                     contact_angle=jnp.sum(mask) * alpha, iterations=sol.iterations, residual=sol.residual,
                     result=sol.result)
