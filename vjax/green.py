"""Radial displacement Green's functions of circular bodies (thesis Appendix A), plane strain.

Every kernel here is ``E * u_rr`` for a unit radial force (N/m) on the boundary at theta = 0,
so it is dimensionless and the displacement under a pressure sigma (Pa) is

    u(theta) = J * R * integral G(theta - theta') sigma(theta') dtheta'        (Eq. 2.15-2.18)

with J = 1/E the compliance. **Sign: u and sigma are positive into the body** (a pressure
pushing on the surface, a displacement along it), for every geometry. The element
integrals ``L(theta) = integral_{theta-alpha}^{theta+alpha} G`` are the closed forms
(A.45, A.60, A.69), written as differences of one antiderivative so that the Heaviside
bookkeeping of the printed formulas is not needed.

All point kernels are combinations of four even 2*pi-periodic basis functions of theta in
[-pi, pi):

    cos(theta),  beta(theta) cos(theta),  A(theta) sin(theta),  1

with beta = log(2 |sin(theta/2)|) = B(theta)/2 and the sawtooth
A(theta) = arg(1/2 - i/2 cot(theta/2)) = theta/2 - (pi/2) sign(theta). Their Fourier
series (beta = -sum cos(n theta)/n, A = -sum sin(n theta)/n) give the per-mode compliances
in closed form; tests compare them with the Michell (Airy stress function) solution.

- ``hole``: hole in an infinite plane, A.39 / A.45. Mode n >= 2 compliance
  (1+nu)/2 [kappa/(n-1) + 1/(n+1)] R/E; n = 0 gives Lame's p R (1+nu)/E.
- ``cylinder``: cylinder fixed at its centre, A.56 / A.60 with A'(theta) = -A(theta)
  (the principal branch of the printed A' is wrong for nu != 0.5, docs/theory.md §5).
  Mode n >= 2: (1+nu)/2 [1/(n-1) + kappa/(n+1)] R/E; n = 0: (1+nu)(1-2nu) R/E (zero for
  an incompressible disc).
- ``diametral``: cylinder under two opposite radial forces at 0 and pi (A.67 / A.69),
  built as the superposition of two ``cylinder`` kernels (the pair is self-equilibrated,
  so the centre fixing carries nothing and the log R terms cancel). The printed A.67 has the
  mode pattern of a hole and the wrong sign of its n-dependent part; the superposition
  is checked against Michell instead.
- ``half_plane``: elastic half-plane, -(2 (1-nu^2)/pi) log(|R theta| / ref_length), used on
  the ring's arc length for the comparison of Chapter 3.

``ref_length`` (m) is the length that fixes the rigid-body displacement of the n = 1 mode
(the thesis's "log R" with R in metres is log(R / 1 m)). It changes only mode n = 1 of the
hole and the cylinder, and only the mean (n = 0) of the half-plane.
"""
from __future__ import annotations

import jax.numpy as jnp

KINDS = ("hole", "cylinder", "diametral", "half_plane")

# Integral over one period of each basis function [cos, beta cos, A sin, 1].
_PERIOD_INTEGRALS = (0.0, -jnp.pi, -jnp.pi, 2.0 * jnp.pi)


def _wrap(phi):
    """Angle to [-pi, pi)."""
    return phi - 2.0 * jnp.pi * jnp.floor((phi + jnp.pi) / (2.0 * jnp.pi))


def _safe_log(x):
    """log(x) for x > 0 and 0 where x == 0, with finite gradients ("double where")."""
    ok = x > 0
    return jnp.where(ok, jnp.log(jnp.where(ok, x, 1.0)), 0.0)


def _basis(theta):
    """Point values of the basis functions (beta cos is -inf at theta = 0)."""
    t = _wrap(theta)
    beta = jnp.log(2.0 * jnp.abs(jnp.sin(t / 2)))
    saw = t / 2 - jnp.pi / 2 * jnp.sign(t)
    return (jnp.cos(t), beta * jnp.cos(t), saw * jnp.sin(t), jnp.ones_like(t))


def _primitives(phi):
    """Antiderivatives of the basis functions, continuous on the real line.

    On [-pi, pi): integral cos = sin; integral beta cos = sin beta - phi/2 - sin/2 (by
    parts, sin * beta' = cos^2(phi/2)); integral A sin = -A cos + sin/2 - s pi/2 (the
    -s pi/2 removes the jump of A at 0). Outside, add whole periods.
    """
    t = _wrap(phi)
    periods = jnp.round((phi - t) / (2.0 * jnp.pi))
    s, c, sgn = jnp.sin(t), jnp.cos(t), jnp.sign(t)
    sin_beta = s * _safe_log(2.0 * jnp.abs(jnp.sin(t / 2)))  # x log x -> 0 at t = 0
    saw = t / 2 - jnp.pi / 2 * sgn
    local = (s, sin_beta - t / 2 - s / 2, -saw * c + s / 2 - sgn * jnp.pi / 2, t)
    return tuple(p + periods * w for p, w in zip(local, _PERIOD_INTEGRALS))


def _coefficients(kind, R, nu, ref_length):
    """Weights of [cos, beta cos, A sin, 1] in G = E u_rr for a unit radial force."""
    kappa = 3.0 - 4.0 * nu
    log_r = jnp.log(R / ref_length)
    pre = (1.0 + nu) / (2.0 * jnp.pi)
    if kind == "hole":  # A.39, sign as printed (u positive into the plane).
        c_cos = -kappa / (kappa + 1.0) * (2.0 * log_r + 1.0)
        return tuple(pre * w for w in (c_cos, -(kappa + 1.0), kappa - 1.0, 0.0 * nu))
    if kind == "cylinder":  # A.56 with A' = -A.
        c_cos = (1.0 - (kappa**2 + 1.0) * log_r) / (kappa + 1.0) - 1.0
        return tuple(pre * w for w in (c_cos, -(kappa + 1.0), -(kappa - 1.0), -(kappa + 1.0) / 2.0))
    raise ValueError(f"no basis expansion for kind {kind!r}")


def _check_kind(kind):
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")


def point_kernel(kind, theta, R, nu, ref_length=1.0):
    """G(theta) = E u_rr(theta) for a unit radial force at theta = 0 (Eq. A.39, A.56, A.67).

    Args:
      kind: "hole", "cylinder", "diametral" or "half_plane".
      theta: angle (rad), any shape; singular (log) at theta = 0.
      R: radius (m). nu: Poisson's ratio. ref_length: reference length of the log terms (m).
    """
    _check_kind(kind)
    theta = jnp.asarray(theta)
    if kind == "half_plane":
        return -2.0 * (1.0 - nu**2) / jnp.pi * jnp.log(R * jnp.abs(_wrap(theta)) / ref_length)
    if kind == "diametral":
        return point_kernel("cylinder", theta, R, nu, ref_length) + point_kernel(
            "cylinder", theta - jnp.pi, R, nu, ref_length)
    return sum(w * b for w, b in zip(_coefficients(kind, R, nu, ref_length), _basis(theta)))


def element_kernel(kind, theta, alpha, R, nu, ref_length=1.0):
    """L(theta) = integral of G over [theta - alpha, theta + alpha] (per radian of the load).

    The closed forms A.45 (hole), A.60 (cylinder), A.69 (diametral) and the half-plane
    analogue; finite everywhere, with finite gradients. ``alpha`` is the element half-angle
    (pi/N on a grid of N elements).
    """
    _check_kind(kind)
    theta = jnp.asarray(theta)
    if kind == "half_plane":
        def prim(phi):
            t = _wrap(phi)
            periods = jnp.round((phi - t) / (2.0 * jnp.pi))
            # integral of log(R|t|/l) dt = t log(R|t|/l) - t; its period integral:
            per = 2.0 * jnp.pi * (jnp.log(R * jnp.pi / ref_length) - 1.0)
            x_log = jnp.where(t != 0, t * _safe_log(R * jnp.abs(t) / ref_length), 0.0)
            return -2.0 * (1.0 - nu**2) / jnp.pi * (x_log - t + periods * per)
        return prim(theta + alpha) - prim(theta - alpha)
    if kind == "diametral":
        return element_kernel("cylinder", theta, alpha, R, nu, ref_length) + element_kernel(
            "cylinder", theta - jnp.pi, alpha, R, nu, ref_length)
    w = _coefficients(kind, R, nu, ref_length)
    hi, lo = _primitives(theta + alpha), _primitives(theta - alpha)
    return sum(wk * (h - l) for wk, h, l in zip(w, hi, lo))

