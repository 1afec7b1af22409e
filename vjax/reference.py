"""Analytical reference solutions, documented and tested once (``tests/test_reference.py``).

Every validation in the project (tests, experiments, the main job) calls these instead of
re-coding them. SI units, plane strain, per unit axial length; jax.numpy throughout.

- :func:`hertz_line_contact`: a cylinder on a flat, or two cylinders (Johnson, *Contact
  Mechanics*, CUP 1985, Section 4.3).
- :func:`lame_displacement`: uniform pressure on a hole in an infinite plane or on a solid
  cylinder (Lame; the n = 0 modes of the ring kernels A.45 and A.60).
- :func:`winkler_pin`: a pin in a thin bushing modelled as a bed of independent springs (the
  limit a thin bonded liner must approach), with :func:`oedometric_stiffness`.
- Pin in a clearance hole in an incompressible elastic plane, rigid pin (the reference of
  thesis Figs. 2.5-2.6, after Persson's 1964 thesis): :func:`persson_pressure`,
  :func:`persson_load_parameter`, :func:`persson_b_from_load`, :func:`persson_limit_b`. The
  closed form is derived in the project (module section below, and docs/theory.md).
- Infinitely long rigid journal bearing (Pinkus & Sternlicht, *Theory of Hydrodynamic
  Lubrication*, 1961, ch. 3; Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film
  Lubrication*, 2004, ch. 10): :func:`long_bearing` with "sommerfeld", "half_sommerfeld" or
  "reynolds" conditions gives load, attitude angle and rupture angle for an eccentricity
  ratio; :func:`half_sommerfeld_eccentricity` inverts the half-Sommerfeld load;
  :func:`long_bearing_coefficients` gives its stiffness and damping for the full-Sommerfeld
  film and the pi film (derived in docs/theory.md, journal dynamics).
- Short rigid journal bearing (Ocvirk 1952; Hamrock, Schmid & Jacobson 2004, ch. 10):
  :func:`short_bearing`, the limit L/D -> 0 of the finite bearing (totals for a length L).
"""
from __future__ import annotations

import functools

import jax
import jax.numpy as jnp
import numpy as np

from ._core import checks
from ._core.solve import bisect

__all__ = ["hertz_line_contact", "lame_displacement", "winkler_pin", "oedometric_stiffness", "persson_shape_functions", "persson_coefficients",
           "persson_pressure", "persson_load_parameter", "persson_b_from_load", "persson_limit_b",
           "long_bearing", "half_sommerfeld_load", "half_sommerfeld_eccentricity", "long_bearing_coefficients",
           "short_bearing"]


# ------------------------------------------------------------------------------ Hertz
def hertz_line_contact(load, R1, E1, nu1, R2=None, E2=None, nu2=None):
    """Hertz line contact of two cylinders (``R2=None``: a flat; ``E2=None``: rigid).

    1/R = 1/R1 + 1/R2 (R2 < 0 for a concave surface: a pin in a hole), 1/E* = (1 - nu1^2)/E1
    + (1 - nu2^2)/E2. Returns ``(a, p0, pressure)``: the half-width a = sqrt(4 F R / (pi E*))
    (m), the peak p0 = 2 F / (pi a) (Pa) and ``pressure(x) = p0 sqrt(1 - x^2/a^2)`` (0 for
    |x| > a), for the load F (N/m).
    """
    checks.positive("load", load)
    curvature = 1.0 / R1 + (0.0 if R2 is None else 1.0 / R2)
    if checks.is_concrete(curvature) and not np.all(np.asarray(curvature) > 0):
        raise ValueError(f"R1, R2 must give a positive relative curvature 1/R1 + 1/R2, got R1={R1!r}, R2={R2!r}")
    compliance = (1 - nu1**2) / E1 + (0.0 if E2 is None else (1 - nu2**2) / E2)
    a = jnp.sqrt(4 * load / (curvature * jnp.pi / compliance))
    p0 = 2 * load / (jnp.pi * a)

    def pressure(x):
        s = 1.0 - (jnp.asarray(x) / a) ** 2
        return p0 * jnp.sqrt(jnp.where(s > 0, s, 0.0))
    return a, p0, pressure


# ------------------------------------------------------------------------------ Lame
def lame_displacement(kind: str, pressure, R, E, nu):
    """Radial displacement (m, positive into the body) of a uniform ``pressure`` (Pa) on
    a hole of radius R in an infinite plane (``kind="hole"``: p R (1 + nu) / E) or on the
    surface of a solid cylinder (``kind="disc"``: p R (1 + nu)(1 - 2 nu) / E), plane strain."""
    checks.one_of("kind", kind, ("hole", "disc"))
    factor = (1 + nu) if kind == "hole" else (1 + nu) * (1 - 2 * nu)
    return pressure * R * factor / E


# ------------------------------------------------------------------------------ Winkler
def oedometric_stiffness(E, nu, thickness):
    """Spring stiffness (Pa/m) of a thin layer bonded on one side: the constrained modulus
    E (1 - nu) / ((1 + nu)(1 - 2 nu)) over the thickness (nu < 0.5)."""
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * thickness)


def winkler_pin(load, R, radial_clearance, stiffness):
    """A pin of radius R - c in a bore of radius R lined with independent springs (Pa/m),
    small displacements: p = k (e cos(theta) - c) where positive. The contact half-angle
    alpha (cos alpha = c / e) solves F = R k c (alpha - sin alpha cos alpha) / cos alpha.
    Returns ``(alpha, e, pressure(theta))``; theta from the load line."""
    _scalars_positive(load=load, R=R, radial_clearance=radial_clearance, stiffness=stiffness)
    c, k = radial_clearance, stiffness
    f = lambda a: R * k * c * (a - jnp.sin(a) * jnp.cos(a)) / jnp.cos(a) - load
    alpha = bisect(f, jnp.asarray(1e-12), jnp.asarray(jnp.pi / 2 - 1e-12), 100)
    e = c / jnp.cos(alpha)

    def pressure(theta):
        return k * jnp.maximum(e * jnp.cos(jnp.asarray(theta)) - c, 0.0)
    return alpha, e, pressure


# ------------------------------------------------------------------------------ Persson
# Rigid pin of radius R - dR in a hole of radius R in an incompressible (nu = 1/2) plane,
# plane strain, small displacements. Derivation (Persson's route):
# 1. Hole kernel (A.39): Fourier compliance (1+nu) n/(n^2-1) R/E for n >= 2, (1+nu) R/E for
#    n = 0; n = 1 is a rigid translation absorbed by the pin offset e.
# 2. On the arc |theta| < alpha the pin imposes u = e cos(theta) - dR. Applying
#    (d^2/dtheta^2 + 1) removes e and turns the symbol into minus the derivative of a
#    Hilbert transform: (H p)' = K + P0/(2 pi) + F/(pi R) cos(theta), K = E dR/((1+nu) R),
#    P0 = int p dtheta, F = R int p cos(theta) dtheta (the load).
# 3. t = tan(theta/2), b = tan(alpha/2), q = p/(1+t^2): a finite-interval Cauchy equation
#    whose bounded solution (smooth edges) is, with w = sqrt(b^2 - t^2), S = sqrt(1 + b^2):
#        p = (2K + P0/pi) gK + (P0/2pi) gC + (2F/(pi R)) gB,
#        gK = artanh(w/S) - w ln(S)/S,  gC = w/S,  gB = (w/S)(cos^2(theta/2) - b^2/(2 S^2)).
# 4. The definitions of P0 and F close a 2 x 2 linear system for P0/K and F/(R K), functions
#    of b alone; E' dR/F = 2 R K/F (E' = E/(1-nu^2)). The neat fit (E' dR/F = 0) is where the
#    system is singular: the limiting contact angle.
# Checked against an independent Gauss-Chebyshev solution of the same equation (1e-13) and
# against Hertz's conforming contact at small loads (tests/test_reference.py).
PERSSON_NU = 0.5


def persson_shape_functions(theta, b):
    """The shape functions (gK, gC, gB) of the Persson pressure at ``theta`` (rad), zero off
    the contact arc |theta| < 2 arctan(b)."""
    th = jnp.angle(jnp.exp(1j * jnp.asarray(theta, dtype=float)))
    t = jnp.tan(th / 2)
    S = jnp.sqrt(1.0 + b * b)
    inside = jnp.abs(t) < b
    w = jnp.sqrt(jnp.where(inside, b * b - t * t, 0.0))
    gK = jnp.arctanh(w / S) - w * jnp.log(S) / S
    gC = w / S
    gB = w / S * (1.0 / (1.0 + t * t) - b * b / (2.0 * S * S))
    return tuple(jnp.where(inside, g, 0.0) for g in (gK, gC, gB))


@functools.lru_cache(maxsize=None)
def _gauss_legendre(n):
    return np.polynomial.legendre.leggauss(n)


def _persson_system(b, n=400):
    """(I - M) x = a for x = (P0/K, F/(R K)); the moments of the shape functions by
    Gauss-Legendre in phi (t = b sin phi: analytic integrands, exact to rounding)."""
    x, wq = _gauss_legendre(n)
    phi = 0.5 * np.pi * x
    t = b * jnp.sin(phi)
    jac = 0.5 * np.pi * wq * 2.0 * b * jnp.cos(phi) / (1.0 + t * t)      # dtheta = 2 dt / (1 + t^2)
    theta = 2.0 * jnp.arctan(t)
    g = jnp.stack(persson_shape_functions(theta, b))
    m0, m1 = g @ jac, g @ (jac * jnp.cos(theta))
    a = jnp.stack([2.0 * m0[0], 2.0 * m1[0]])
    M = jnp.array([[(2.0 * m0[0] + m0[1]) / (2.0 * jnp.pi), 2.0 * m0[2] / jnp.pi],
                   [(2.0 * m1[0] + m1[1]) / (2.0 * jnp.pi), 2.0 * m1[2] / jnp.pi]])
    return jnp.eye(2) - M, a


def persson_coefficients(b):
    """(P0/K, F/(R K)) for b = tan(alpha/2): P0 = int p dtheta, F the load, K = E dR/((1+nu) R)."""
    A, a = _persson_system(b)
    return jnp.linalg.solve(A, a)


def persson_load_parameter(b):
    """E' dR / F (E' = E/(1 - nu^2) = 4E/3) as a function of b = tan(alpha/2) (scalar or
    array): decreasing, zero at the neat fit :func:`persson_limit_b`, negative beyond."""
    def one(bi):
        A, a = _persson_system(bi)
        # Cramer, so that det -> 0 is smooth: E' dR/F = det / (F/(R K) det) / (1 - nu)
        return jnp.linalg.det(A) / (A[0, 0] * a[1] - A[1, 0] * a[0]) / (1.0 - PERSSON_NU)
    b = jnp.asarray(b, dtype=float)
    return jnp.reshape(jnp.stack([one(bi) for bi in b.ravel()]), b.shape)


@functools.lru_cache(maxsize=None)
def persson_limit_b() -> float:
    """b_c = tan(alpha_c/2) of the limiting (neat-fit, infinite-load) contact angle."""
    det = lambda b: jnp.linalg.det(_persson_system(b)[0])
    return float(bisect(det, jnp.asarray(0.2), jnp.asarray(5.0), 100))


def persson_b_from_load(load, E, R, dR):
    """b = tan(alpha/2) for the load F (N/m), plate modulus E (Pa), hole radius R and radial
    clearance dR (m): inverts :func:`persson_load_parameter`."""
    _scalars_positive(load=load, E=E, R=R, dR=dR)
    target = E / (1.0 - PERSSON_NU**2) * dR / load
    return float(_persson_b(jnp.asarray(target, jnp.result_type(float)), jnp.asarray(persson_limit_b() * (1 - 1e-12))))


@jax.jit      # compiled once (an eager bisection over a new closure would compile at every call)
def _persson_b(target, b_max):
    return bisect(lambda b: persson_load_parameter(b) - target, jnp.full_like(target, 1e-6), b_max, 100)


def persson_pressure(theta, b, E, R, dR):
    """Pressure p(theta) (Pa) for the contact semi-angle tan(alpha/2) = b, centred at
    theta = 0, zero off the arc."""
    K = E * dR / ((1.0 + PERSSON_NU) * R)
    p0, f = persson_coefficients(b)
    gK, gC, gB = persson_shape_functions(theta, b)
    return K * ((2.0 + p0 / jnp.pi) * gK + p0 / (2.0 * jnp.pi) * gC + 2.0 * f / jnp.pi * gB)


def _scalars_positive(**values):
    for name, v in values.items():
        checks.positive(name, v)
        checks.scalar(name, v)


# ------------------------------------------------------------------------------ long journal bearing
CONDITIONS = ("sommerfeld", "half_sommerfeld", "reynolds")


def half_sommerfeld_load(eps):
    """G(eps) = |W| c^2 / (12 eta |v| R^2) of the rigid half-Sommerfeld bearing (increasing
    from 0 to infinity), v the entrainment speed (omega_B R_B + omega_J R_J)/2:
    G = eps sqrt(pi^2 (1 - eps^2) + 4 eps^2) / ((2 + eps^2)(1 - eps^2))."""
    return eps * jnp.sqrt(jnp.pi**2 * (1 - eps**2) + 4 * eps**2) / ((2 + eps**2) * (1 - eps**2))


@jax.jit      # compiled once: the journal scene calls it outside jit, for its start
def half_sommerfeld_eccentricity(G):
    """The eccentricity ratio whose half-Sommerfeld load is G (element-wise, >= 0)."""
    G = jnp.asarray(G, dtype=float)
    return bisect(lambda e: half_sommerfeld_load(e) - G, jnp.zeros_like(G), jnp.full_like(G, 0.9999), 60)


def long_bearing(eps, R, radial_clearance, viscosity, speed, conditions: str = "reynolds", n_quad: int = 2000):
    """Rigid infinitely long journal bearing at eccentricity ratio ``eps``.

    Film h = c (1 - eps cos theta), theta from the line of centres (0 at the smallest gap),
    entrainment speed ``speed`` v = (omega_B R_B + omega_J R_J)/2 > 0 (m/s), lubricant
    supplied at theta = pi at zero pressure. Returns a dict with ``load`` |W| (N/m),
    ``attitude`` (rad, angle between load line and line of centres), ``rupture`` (rad,
    where the film ruptures; the pressure's downstream zero for Sommerfeld) and
    ``pressure(theta)`` (Pa):

    - "sommerfeld": full film, W = 24 pi eta v R^2 eps / (c^2 (2 + eps^2) sqrt(1 - eps^2)),
      attitude pi/2;
    - "half_sommerfeld": the negative half clipped, W = 12 eta v R^2 G(eps) / c^2
      (:func:`half_sommerfeld_load`), tan(attitude) = pi sqrt(1 - eps^2) / (2 eps);
    - "reynolds": Swift-Stieber, p = dp/dtheta = 0 at the rupture angle theta_2 in (0, pi):
      p(theta) = 12 eta v R int_{-pi}^{theta} (h - h_2)/h^3 with h_2 = h(theta_2), theta_2 the
      root of p(theta_2) = 0 (bisection); load and attitude by Gauss-Legendre quadrature
      with ``n_quad`` points.
    """
    checks.one_of("conditions", conditions, CONDITIONS)
    _scalars_positive(R=R, radial_clearance=radial_clearance, viscosity=viscosity, speed=speed)
    e = checks.values("eps", eps)
    if e is not None and not (0 < e < 1):
        raise ValueError(f"eps must be in (0, 1), got {eps!r}")
    c, eta, v = radial_clearance, viscosity, speed
    scale = 12 * eta * v * R**2 / c**2
    if conditions != "reynolds":
        def p_full(theta):
            return (-6 * eta * v * R / c**2 * 2 * eps * jnp.sin(theta) * (2 - eps * jnp.cos(theta))
                    / ((2 + eps**2) * (1 - eps * jnp.cos(theta)) ** 2))
        if conditions == "sommerfeld":
            load = 2 * scale * jnp.pi * eps / ((2 + eps**2) * jnp.sqrt(1 - eps**2))
            return dict(load=load, attitude=jnp.pi / 2, rupture=jnp.asarray(jnp.pi), pressure=p_full)
        return dict(load=scale * half_sommerfeld_load(eps),
                    attitude=jnp.arctan2(jnp.pi * jnp.sqrt(1 - eps**2), 2 * eps), rupture=jnp.asarray(0.0),
                    pressure=lambda theta: jnp.maximum(p_full(jnp.angle(jnp.exp(1j * theta))), 0.0))
    we = 2 * v / R
    t2, Fx, Fy = _reynolds_film(eps, 0.0, we, n_quad)
    B = 6 * eta * R**3 / c**2

    def pressure(theta):
        theta = jnp.angle(jnp.exp(1j * jnp.asarray(theta, dtype=float)))
        return jnp.where(theta < t2, B / R * _reynolds_p(theta, t2, eps, 0.0, we, n_quad), 0.0)
    return dict(load=B * jnp.hypot(Fx, Fy), attitude=jnp.arctan2(Fy, -Fx), rupture=t2, pressure=pressure)


def _reynolds_p(theta, t2, eps, eps_dot, omega_e, n_quad):
    """p R / B at ``theta`` (B = 6 eta R^3 / c^2) of the film of :func:`_reynolds_film` with its
    rupture at ``t2``: the integral of dp/dtheta from the groove at -pi (Gauss-Legendre)."""
    x, w = _gauss_legendre(n_quad)
    t2 = jnp.broadcast_to(t2, jnp.shape(theta))[..., None]
    H = lambda t: 1 - eps * jnp.cos(t)     # noqa: E731
    t = 0.5 * (theta + jnp.pi)[..., None] * x + 0.5 * (theta - jnp.pi)[..., None]
    f = (omega_e * (H(t) - H(t2)) - 2 * eps_dot * (jnp.sin(t) - jnp.sin(t2))) / H(t) ** 3
    return 0.5 * (theta + jnp.pi) * jnp.sum(w * f, axis=-1)


@functools.partial(jax.jit, static_argnums=3)
def _reynolds_film(eps, eps_dot, omega_e, n_quad=600):
    """The long bearing's film under Reynolds conditions with a squeeze: film c (1 - eps cos theta)
    in the frame of the line of centres, its rate -c eps_dot cos theta, effective angular speed
    omega_e = 2 (v / R - gamma') (rad/s), p = 0 at the groove theta = -pi. Integrating Reynolds'
    equation once from the rupture theta_2, where p = dp/dtheta = 0,

        dp/dtheta = (6 eta R^2 / c^2) [omega_e (H - H_2) - 2 eps_dot (sin theta - sin theta_2)] / H^3,

    H = 1 - eps cos theta, and theta_2 in (0, pi) is the root of p(theta_2) = 0 (bisection, then
    one Newton step from it, through which the derivatives in eps, eps_dot and omega_e flow:
    those of the implicit root). Gauss-Legendre quadrature with ``n_quad`` points (600: the
    forces and their derivatives equal 2000 points' to all printed digits). Returns
    (theta_2, F_x / B, F_y / B), B = 6 eta R^3 / c^2, F the force on the journal along the line
    of centres and 90 degrees ahead of it."""
    x, w = _gauss_legendre(n_quad)
    at_itself = lambda t: _reynolds_p(t, t, eps, eps_dot, omega_e, n_quad)     # noqa: E731
    t2 = jax.lax.stop_gradient(bisect(at_itself, jnp.asarray(1e-6), jnp.asarray(jnp.pi - 1e-6), 60))
    t2 = t2 - at_itself(t2) / jax.grad(at_itself)(t2)
    # forces of the pressure on the journal, by the same quadrature (p = 0 past theta_2)
    th = 0.5 * (t2 + jnp.pi) * x + 0.5 * (t2 - jnp.pi)           # nodes on (-pi, theta_2)
    p_nodes = _reynolds_p(th, t2, eps, eps_dot, omega_e, n_quad)
    weight = 0.5 * (t2 + jnp.pi) * w
    return t2, -jnp.sum(weight * p_nodes * jnp.cos(th)), -jnp.sum(weight * p_nodes * jnp.sin(th))


def _long_bearing_forces(eps, eps_dot, omega_e, conditions):
    """Film force on the journal over B = 6 eta R^3 / c^2, (radial along the line of centres,
    tangential), for eccentricity ratio eps, its rate eps_dot (1/s) and the effective
    angular speed omega_e = 2 (v / R - gamma') (rad/s), gamma' the whirl rate of the line of
    centres; lubricant at zero pressure at theta = pi of the moving line of centres."""
    beta = jnp.sqrt(1 - eps**2)
    if conditions == "reynolds":
        return jnp.stack(_reynolds_film(eps, eps_dot, omega_e)[1:])
    if conditions == "sommerfeld":      # full film: the integrals over the whole circle
        return jnp.stack([-eps_dot * 2 * jnp.pi / beta**3,
                          omega_e * 2 * jnp.pi * eps / ((2 + eps**2) * beta)])
    # pi film: the positive half (-pi, 0) of the rotation part; the squeeze part
    # (eps_dot / eps)((1 - eps cos)^-2 - (1 + eps)^-2) over the same half
    return jnp.stack([-omega_e * 2 * eps**2 / ((2 + eps**2) * beta**2) - eps_dot * jnp.pi / beta**3,
                      omega_e * jnp.pi * eps / ((2 + eps**2) * beta) + eps_dot * 4 / ((1 - eps) * (1 + eps) ** 2)])


def long_bearing_coefficients(eps, R, radial_clearance, viscosity, speed, conditions: str = "half_sommerfeld"):
    """Stiffness K (N/m^2) and damping C (N s/m^2) per unit length of the rigid infinitely long
    bearing of :func:`long_bearing` ("sommerfeld", "half_sommerfeld": the pi film, or
    "reynolds": the film of :func:`_reynolds_film`, its rupture moving with the motion), in the
    line-of-centres frame (X from the bore's centre to the journal's, Y 90 degrees ahead),
    convention dF = -(K dx + C dx/dt) for the film force F on the journal.

    Pressure (theta from the line of centres, film c (1 - eps cos theta), datum p(pi) = 0):
    p = -6 eta R^2 omega_e eps sin(theta)(2 - eps cos theta) / (c^2 (2 + eps^2)(1 - eps cos theta)^2)
        + 6 eta R^2 (eps' / eps)((1 - eps cos theta)^-2 - (1 + eps)^-2) / c^2,
    omega_e = 2 (v/R - gamma'); the forces (radial, tangential) over B = 6 eta R^3 / c^2 are
    pi film:  (-2 omega_e eps^2 / ((2 + eps^2)(1 - eps^2)) - pi eps' / (1 - eps^2)^(3/2),
               pi omega_e eps / ((2 + eps^2) sqrt(1 - eps^2)) + 4 eps' / ((1 - eps)(1 + eps)^2));
    full film: (-2 pi eps' / (1 - eps^2)^(3/2), 2 pi omega_e eps / ((2 + eps^2) sqrt(1 - eps^2))).
    A motion (dX, dY) changes eps by dX / c and turns the line of centres by dY / (eps c),
    which also turns the steady force: K_XX = -dF_r/deps / c, K_XY = F_t / (eps c),
    K_YX = -dF_t/deps / c, K_YY = -F_r / (eps c); C_XX = -dF_r/deps' / c,
    C_YX = -dF_t/deps' / c, C_XY = 2 dF_r/domega_e / (eps c), C_YY = 2 dF_t/domega_e / (eps c)
    (derivatives of the closed forms, taken by JAX).
    """
    checks.one_of("conditions", conditions, CONDITIONS)
    _scalars_positive(R=R, radial_clearance=radial_clearance, viscosity=viscosity, speed=speed)
    e = checks.values("eps", eps)
    if e is not None and not (0 < e < 1):
        raise ValueError(f"eps must be in (0, 1), got {eps!r}")
    c = radial_clearance
    B = 6 * viscosity * R**3 / c**2
    we = 2 * speed / R
    force = lambda x: B * _long_bearing_forces(x[0], x[1], x[2], conditions)  # noqa: E731
    x = jnp.stack([jnp.asarray(eps, float), 0.0, we])
    F = force(x)
    D = jax.jacfwd(force)(x)        # columns: d/deps, d/deps', d/domega_e
    K = jnp.array([[-D[0, 0] / c, F[1] / (eps * c)], [-D[1, 0] / c, -F[0] / (eps * c)]])
    C = jnp.array([[-D[0, 1] / c, 2 * D[0, 2] / (eps * c)], [-D[1, 1] / c, 2 * D[1, 2] / (eps * c)]])
    return K, C


# ------------------------------------------------------------------------------ short journal bearing
def short_bearing(eps, R, radial_clearance, viscosity, speed, length, conditions: str = "half_sommerfeld"):
    """Rigid short journal bearing (Ocvirk's solution: the circumferential pressure flow dropped
    against the axial one, the limit L/D -> 0), eccentricity ratio ``eps``, entrainment speed
    ``speed`` v = (omega_B R_B + omega_J R_J)/2 > 0 (m/s), axial ``length`` L (m), ambient
    pressure at z = +-L/2. With U = 2 v and theta from the line of centres (0 at the smallest gap):

        p(theta, z) = (3 eta U / (R c^2)) (L^2/4 - z^2) (-eps sin theta) / (1 - eps cos theta)^3

    "half_sommerfeld": the positive half (-pi < theta < 0); the force on the journal, along the
    line of centres and 90 degrees ahead of it (N, totals over L),
    W_r = eta U L^3 eps^2 / (c^2 (1 - eps^2)^2), W_t = pi eta U L^3 eps / (4 c^2 (1 - eps^2)^(3/2)),
    tan(attitude) = pi sqrt(1 - eps^2) / (4 eps);
    "sommerfeld": the whole antisymmetric film, W_r = 0, W_t twice the above, attitude pi/2.
    Returns a dict ``load`` |W| (N), ``attitude`` (rad), ``pressure(theta, z)`` (Pa).
    """
    checks.one_of("conditions", conditions, ("sommerfeld", "half_sommerfeld"))
    _scalars_positive(R=R, radial_clearance=radial_clearance, viscosity=viscosity, speed=speed, length=length)
    e = checks.values("eps", eps)
    if e is not None and not (0 < e < 1):
        raise ValueError(f"eps must be in (0, 1), got {eps!r}")
    c, L, U = radial_clearance, length, 2 * speed
    scale = viscosity * U * L**3 / c**2
    Wt = scale * jnp.pi * eps / (4 * (1 - eps**2) ** 1.5)
    Wr = scale * eps**2 / (1 - eps**2) ** 2

    def full(theta, z):
        theta = jnp.asarray(theta)
        return (3 * viscosity * U / (R * c**2) * (L**2 / 4 - jnp.asarray(z) ** 2) * (-eps * jnp.sin(theta))
                / (1 - eps * jnp.cos(theta)) ** 3)
    if conditions == "sommerfeld":
        return dict(load=2 * Wt, attitude=jnp.pi / 2, pressure=full)
    return dict(load=jnp.hypot(Wr, Wt), attitude=jnp.arctan2(Wt, Wr),
                pressure=lambda theta, z: jnp.maximum(full(theta, z), 0.0))
