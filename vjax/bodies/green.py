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

import functools

import jax.numpy as jnp
import numpy as np

KINDS = ("hole", "cylinder", "diametral", "half_plane")

# Integral over one period of each basis function [cos, beta cos, A sin, 1].
_PERIOD_INTEGRALS = (0.0, -jnp.pi, -jnp.pi, 2.0 * jnp.pi)


def _wrap(phi, xp=jnp):
    """Angle to [-pi, pi)."""
    return phi - 2.0 * np.pi * xp.floor((phi + np.pi) / (2.0 * np.pi))


def _safe_log(x, xp=jnp):
    """log(x) for x > 0 and 0 where x == 0, with finite gradients ("double where")."""
    ok = x > 0
    return xp.where(ok, xp.log(xp.where(ok, x, 1.0)), 0.0)


def _basis(theta):
    """Point values of the basis functions (beta cos is -inf at theta = 0)."""
    t = _wrap(theta)
    beta = jnp.log(2.0 * jnp.abs(jnp.sin(t / 2)))
    saw = t / 2 - jnp.pi / 2 * jnp.sign(t)
    return (jnp.cos(t), beta * jnp.cos(t), saw * jnp.sin(t), jnp.ones_like(t))


def _primitives(phi, xp=jnp):
    """Antiderivatives of the basis functions, continuous on the real line.

    On [-pi, pi): integral cos = sin; integral beta cos = sin beta - phi/2 - sin/2 (by
    parts, sin * beta' = cos^2(phi/2)); integral A sin = -A cos + sin/2 - s pi/2 (the
    -s pi/2 removes the jump of A at 0). Outside, add whole periods. ``xp``: jax.numpy, or
    numpy for the geometry-only tables of :func:`element_basis_symbols`.
    """
    t = _wrap(phi, xp)
    periods = xp.round((phi - t) / (2.0 * np.pi))
    s, c, sgn = xp.sin(t), xp.cos(t), xp.sign(t)
    sin_beta = s * _safe_log(2.0 * xp.abs(xp.sin(t / 2)), xp)  # x log x -> 0 at t = 0
    saw = t / 2 - np.pi / 2 * sgn
    local = (s, sin_beta - t / 2 - s / 2, -saw * c + s / 2 - sgn * np.pi / 2, t)
    return tuple(p + periods * w for p, w in zip(local, _PERIOD_INTEGRALS))


@functools.lru_cache(maxsize=32)
def element_basis_symbols(n: int, pair: bool = False) -> np.ndarray:
    """(4, n // 2 + 1): the real FFT, over a grid of n elements, of the element integrals of
    the basis [cos, beta cos, A sin, 1] (of a pair of loads at 0 and pi when ``pair``, the
    diametral case). Geometry only, so computed once per n, in float64 numpy: an element
    symbol is their combination with the weights of R, nu and ref_length (A.45, A.60, A.69),
    with no transcendental function or FFT at n points per call."""
    theta, alpha = 2.0 * np.pi * np.arange(n) / n, np.pi / n
    kernels = 0.0
    for shift in ((0.0, np.pi) if pair else (0.0,)):
        hi, lo = _primitives(theta - shift + alpha, np), _primitives(theta - shift - alpha, np)
        kernels = kernels + np.stack([h - l for h, l in zip(hi, lo)])
    return np.fft.rfft(kernels, axis=-1).real


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



# ---------------------------------------------------------------------- modal compliances
LAYERS = ("liner", "sleeve")
LAYER_MODES = 1 << 16    # modes summed in a layer's element symbol: enough for t/R >= 1e-3


def _basis_modes(m):
    """int_{-pi}^{pi} b(theta) cos(m theta) dtheta of the basis [cos, beta cos, A sin, 1], m >= 0."""
    m = jnp.asarray(m, dtype=float)
    safe = jnp.where(m >= 2, m, 3.0)
    hi = jnp.where(m >= 2, -jnp.pi / 2 * (1 / (safe - 1) + 1 / (safe + 1)), 0.0)
    a_hi = jnp.where(m >= 2, jnp.pi / 2 * (1 / (safe - 1) - 1 / (safe + 1)), 0.0)
    one = m == 1
    zero = m == 0
    return (jnp.where(one, jnp.pi, 0.0),
            jnp.where(zero, -jnp.pi, jnp.where(one, -jnp.pi / 4, hi)),
            jnp.where(zero, -jnp.pi, jnp.where(one, -jnp.pi / 4, a_hi)),
            jnp.where(zero, 2 * jnp.pi, 0.0))


def _solve_small(A, b):
    """x with A x = b for a batch of small systems, A (..., k, k), b (..., k): Gaussian
    elimination with partial pivoting (as LAPACK's getrf), unrolled over the k columns.

    Not ``jnp.linalg.solve``: on CPU, jaxlib's LAPACK kernels spread a batch over XLA's thread
    pool from inside that pool and wait for it, so two batched solves running side by side in
    one program (a liner's and a sleeve's 65536 modes) can leave no free thread: with two
    cores, jaxlib 0.10.2 was seen to deadlock there."""
    k = A.shape[-1]
    rows = jnp.arange(k)
    M = jnp.concatenate([A, b[..., None]], axis=-1)                   # augmented (..., k, k + 1)
    for j in range(k):
        p = j + jnp.argmax(jnp.abs(M[..., j:, j]), axis=-1)          # pivot row
        swap = jnp.where(rows == j, p[..., None], jnp.where(rows == p[..., None], j, rows))
        M = jnp.take_along_axis(M, swap[..., None], axis=-2)
        below = jnp.where(rows[:, None] > j, M[..., :, j:j + 1] / M[..., j:j + 1, j:j + 1], 0.0)
        M = M - below * M[..., j:j + 1, :]
    x = []
    for i in reversed(range(k)):
        x.insert(0, (M[..., i, k] - sum(M[..., i, i + 1 + q] * x[q] for q in range(len(x)))) / M[..., i, i])
    return jnp.stack(x, -1)


def _michell_modes(kind, m, nu, tau):
    """c_m of a layer of thickness ratio tau (Michell's solution, plane strain, E = 1, R = 1).

    Liner: loaded at rho = 1 (sigma_rr = -cos m theta, sigma_rtheta = 0), bonded at 1 + tau;
    sleeve: loaded at rho = 1, bonded at 1 - tau. Mode m >= 1 uses the four power solutions
    r^(m+1), r^(m-1), r^(1-m), r^(-m-1) (for m = 1 the third is replaced by the log
    solution), each scaled to at most 1 on the layer; m = 0 is Lame's u = A r + B / r.
    """
    kap = 3.0 - 4.0 * nu
    mu = 1.0 / (2.0 * (1.0 + nu))
    rb = 1.0 + tau if kind == "liner" else 1.0 - tau
    lo, hi = (1.0, rb) if kind == "liner" else (rb, 1.0)
    n = jnp.maximum(jnp.asarray(m, dtype=float), 1.0)
    first = n == 1
    n3 = jnp.where(first, 3.0, n)                     # keeps the unused m = 1 branch finite

    def power(s, b, srr, srt, rho):
        ref = jnp.where(s > 0, hi, lo)
        f = jnp.exp(s * jnp.log(rho / ref))
        return jnp.stack([f, b * f, mu * srr * f / rho, mu * srt * f / rho], -1)

    def columns(rho):
        c1 = power(n + 1, -(n + kap + 1) / (n - kap + 1), 2 * (n - 2) * (n + 1) / (n + 1 - kap),
                   -2 * n * (n + 1) / (n + 1 - kap), rho)
        c2 = power(n - 1, -1.0, 2 * (n - 1), -2 * (n - 1), rho)
        c3 = power(1 - n3, (n3 - kap - 1) / (n3 + kap - 1), -2 * (n3 - 1) * (n3 + 2) / (kap + n3 - 1),
                   -2 * n3 * (n3 - 1) / (kap + n3 - 1), rho)
        L = jnp.log(rho) * jnp.ones_like(n)
        c3_log = jnp.stack([L, -(kap * L + 1) / kap, mu * (kap + 3) / (kap * rho) * jnp.ones_like(n),
                            mu * (1 - kap) / (kap * rho) * jnp.ones_like(n)], -1)
        c3 = jnp.where(first[..., None], c3_log, c3)
        c4 = power(-n - 1, 1.0, -2 * (n + 1), -2 * (n + 1), rho)
        return jnp.stack([c1, c2, c3, c4], -1)           # (..., [u_r, u_t, s_rr, s_rt], basis)

    loaded, bonded = columns(1.0), columns(rb)
    A = jnp.concatenate([loaded[..., 2:, :], bonded[..., :2, :]], axis=-2)
    rhs = jnp.broadcast_to(jnp.array([-1.0, 0.0, 0.0, 0.0], dtype=A.dtype), A.shape[:-1])
    coef = _solve_small(A, rhs)
    u = jnp.sum(loaded[..., 0, :] * coef, -1)
    c_m = u if kind == "liner" else -u                   # into the body
    c_0 = (kap - 1) * jnp.abs(rb**2 - 1) / (2 * mu * (2 + (kap - 1) * rb**2))
    return jnp.where(jnp.asarray(m) == 0, c_0, c_m)


def mode_compliance(kind: str, modes, nu, thickness_ratio=None, ref_length_ratio=None):
    """Dimensionless modal compliances c_n (plane strain) of the loaded surface of a body.

    A pressure cos(n theta) (Pa) on the loaded surface of radius R gives the radial
    displacement into the body c_n (R / E) cos(n theta), E the Young modulus:

    - "hole": hole in an infinite plane (A.39); n >= 2: (1+nu)/2 [kappa/(n-1) + 1/(n+1)],
      n = 0: 1 + nu; n = 1 (a rigid translation) depends on ``ref_length_ratio`` =
      ref_length / R (default 1: the reference length equal to the radius);
    - "disc": solid cylinder fixed at its centre (A.56 with A' = -A): n >= 2:
      (1+nu)/2 [1/(n-1) + kappa/(n+1)], n = 0: (1+nu)(1-2nu);
    - "liner": a layer of thickness t = ``thickness_ratio`` R loaded on its bore, its outer
      surface bonded to a rigid housing;
    - "sleeve": a layer loaded on its outer surface, bonded on its inner surface (radius
      R - t) to a rigid core.

    Liners and sleeves follow from Michell's general solution with the bonded and loaded
    boundary conditions, one 4 x 4 solve per mode (vectorized, differentiable in nu and the
    thickness). Thick liners tend to the hole, thin layers to the oedometric
    t (1+nu)(1-2nu) / ((1-nu) E) (nu < 0.5) and, incompressible, to c_n ~ n^2 (t/R)^3.
    """
    modes = jnp.abs(jnp.asarray(modes))
    if kind in LAYERS:
        if thickness_ratio is None:
            raise ValueError(f"a {kind} needs thickness_ratio = t / R")
        return _michell_modes(kind, modes, nu, thickness_ratio)
    if kind not in ("hole", "disc"):
        raise ValueError(f"kind must be one of hole, disc, liner, sleeve, got {kind!r}")
    ratio = 1.0 if ref_length_ratio is None else ref_length_ratio
    w = _coefficients("hole" if kind == "hole" else "cylinder", 1.0, nu, ratio)
    return sum(wk * g for wk, g in zip(w, _basis_modes(modes)))


def layer_element_symbol(kind: str, n: int, R, nu, thickness):
    """Element symbol (real FFT of the first column of the element matrix, modes 0..n/2)
    of a liner or sleeve of ``thickness`` (m) loaded on radius ``R`` (m).

    The element operator is the continuous one integrated over the elements: mode k collects
    every m = k (mod n) with the element factor sinc(m pi / n). The sum converges slowly
    alone (c_m ~ 1/m), so it is written as the exact closed-form symbol of the unbounded body
    (a hole for a liner, a disc for a sleeve, reference length R) plus the aliased sum of the
    difference, which decays like exp(-2 m t / R): ``LAYER_MODES`` terms suffice for
    t / R >= 1e-3.
    """
    base = "hole" if kind == "liner" else "cylinder"
    theta, alpha = jnp.arange(n) * 2.0 * jnp.pi / n, jnp.pi / n
    exact = jnp.fft.rfft(element_kernel(base, theta, alpha, R, nu, R)).real
    m = jnp.arange(LAYER_MODES + 1, dtype=float)
    diff = (mode_compliance(kind, m, nu, thickness_ratio=thickness / R)
            - mode_compliance("hole" if kind == "liner" else "disc", m, nu, ref_length_ratio=1.0))
    weight = diff * jnp.sinc(m / n)                      # sin(m alpha) / (m alpha)
    signed = jnp.concatenate([weight, weight[1:]])       # m >= 0 and m <= -1
    bins = jnp.concatenate([jnp.arange(LAYER_MODES + 1), -jnp.arange(1, LAYER_MODES + 1)]) % n
    folded = jnp.zeros(n, weight.dtype).at[bins].add(signed)
    return exact + folded[: n // 2 + 1]
