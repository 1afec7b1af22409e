"""Rough surfaces in a thin film: Patir-Cheng average flow and Greenwood-Tripp asperity contact.

Pure, differentiable functions of the nominal gap h (m) or of the film parameter H = h / sigma,
and :class:`Roughness`, the JAX PyTree that carries a pair of surfaces' parameters. The model
and the conventions chosen where authors differ are in docs/theory.md ("Mixed lubrication:
rough surfaces"). Sources:

- N. Patir, H.S. Cheng, An average flow model for determining effects of three-dimensional
  roughness on partial hydrodynamic lubrication, ASME J. Lubr. Technol. 100 (1978) 12-17:
  pressure and shear flow factors (fits of their Tables 1 and 2).
- N. Patir, H.S. Cheng, Application of average flow model to lubrication between rough sliding
  surfaces, ASME J. Lubr. Technol. 101 (1979) 220-230: the shear stress factors phi_f,
  phi_fs, phi_fp.
- J.A. Greenwood, J.H. Tripp, The contact of two nominally flat rough surfaces, Proc. IMechE
  185 (1970) 625-633: the asperity pressure p_a = K E' F_{5/2}(H).
- X. Lu, M.M. Khonsari, On the lift-off speed in journal bearings, Tribol. Lett. 20 (2005)
  299-305; X. Lu, M.M. Khonsari, E.R.M. Gelinck, The Stribeck curve: experimental results and
  theoretical prediction, ASME J. Tribol. 128 (2006) 789-794: this model in a journal bearing.

>>> round(float(asperity_integral(0.0)), 6)           # F_n(0) = 2^((n-1)/2) Gamma((n+1)/2) / sqrt(2 pi)
0.616634
>>> rough = Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)   # smooth steel journal, rough polymer bush
>>> float(rough.Vr), round(float(rough.E) / 1e9, 4)   # bush rough: Vr = -1; 1/E' = sum (1 - nu^2)/E
(-1.0, 3.517)
"""
from __future__ import annotations

import dataclasses
import functools
import math

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks

# ---- Patir and Cheng's fits -------------------------------------------------------------------
# The orientation parameter gamma (Peklenik's number: the ratio of the autocorrelation lengths
# along and across the flow, 1 isotropic, > 1 ridges along the flow, < 1 across it) selects a
# row; the papers tabulate these seven values and no law between them, so no other is accepted.
GAMMAS = (1 / 9, 1 / 6, 1 / 3, 1.0, 3.0, 6.0, 9.0)

# Pressure flow factor (Patir and Cheng 1978, Eq. 23 and Table 1):
#   phi_x = 1 - C exp(-r H)  for gamma <= 1,   phi_x = 1 + C H^-r  for gamma > 1,
# fitted for H above H_min. gamma: (C, r, H_min). The isotropic row (0.90, 0.56) is quoted
# the same by every later user; the other rows agree within 0.2-4.3 % with the smooth fits in gamma
# that some codes use instead (C = 0.89679 - 0.26591 ln gamma, r = 0.43006 - 0.10828 gamma +
# 0.23821 gamma^2 for gamma < 1; C = 0.1075 gamma - 0.10667, r = 1.5 for gamma > 1).
PRESSURE_FLOW = {
    1 / 9: (1.48, 0.42, 1.0),
    1 / 6: (1.38, 0.42, 1.0),
    1 / 3: (1.18, 0.42, 0.75),
    1.0: (0.90, 0.56, 0.5),
    3.0: (0.225, 1.5, 0.5),
    6.0: (0.520, 1.5, 0.5),
    9.0: (0.870, 1.5, 0.5),
}

# Shear flow factor of one rough surface (Patir and Cheng 1978, Eq. 26 and Table 2):
#   Phi_s = A1 H^a1 exp(-a2 H + a3 H^2)  for H <= 5,   A2 exp(-0.25 H)  for H > 5.
# gamma: (A1, a1, a2, a3, A2). Each row's two branches meet at H = 5 within 0.1 % (tested).
SHEAR_FLOW = {
    1 / 9: (2.046, 1.12, 0.78, 0.03, 1.856),
    1 / 6: (1.962, 1.08, 0.77, 0.03, 1.754),
    1 / 3: (1.858, 1.01, 0.76, 0.03, 1.561),
    1.0: (1.899, 0.98, 0.92, 0.05, 1.126),
    3.0: (1.560, 0.85, 1.13, 0.08, 0.556),
    6.0: (1.290, 0.62, 1.09, 0.08, 0.388),
    9.0: (1.011, 0.54, 1.07, 0.08, 0.295),
}

# Shear stress factors (Patir and Cheng 1979, Eqs. 34-35 and their table), isotropic row only:
#   phi_fp = 1 - D exp(-s H)  (H > 0.5),   Phi_fs = A3 H^a4 exp(-a5 H + a6 H^2)  (0.5 < H < 7),
# Phi_fs = 0 for H >= 7. gamma: (D, s, A3, a4, a5, a6). Only gamma = 1 is carried: the other
# rows were not checked against a copy of the paper.
SHEAR_STRESS = {
    1.0: (1.40, 0.66, 11.1, 2.31, 2.38, 0.11),
}
SHEAR_STRESS_H_MAX = 7.0
FRICTION_CUTOFF = 1.0 / 300.0    # phi_f: its 1/h_local singularity cut at h_local = 3 sigma / 300

# ---- F_n: the Greenwood-Tripp integral -----------------------------------------------------------
_LAGUERRE_NODES = 64    # H >= 1
_LAGUERRE_H_MIN = 1.0
_KUMMER_TERMS = 128     # -10 < H < 1
_KUMMER_H_MIN = -10.0
_ASYMPTOTIC_TERMS = 16  # H <= -10


@functools.lru_cache(maxsize=None)
def _laguerre(alpha: float, N: int):
    """Gauss-Laguerre nodes and log-weights for the weight u^alpha e^-u on (0, inf), from the
    eigen-decomposition of the Jacobi matrix (Golub and Welsch), in float64."""
    k = np.arange(N, dtype=np.float64)
    off = np.sqrt(k[1:] * (k[1:] + alpha))
    J = np.diag(2 * k + alpha + 1) + np.diag(off, 1) + np.diag(off, -1)
    x, V = np.linalg.eigh(J)
    return x, math.lgamma(alpha + 1) + 2 * np.log(np.abs(V[0]))


def _log_F_laguerre(n, H):
    """log F_n(H) for H >= 1 (any H >= 0 is finite). With s = H + t, F_n = e^{-H^2/2} (2 pi)^-1/2
    int_0^inf t^n e^{-H t - t^2/2} dt; t = u / lam puts the integrand's decay rate on the
    weight u^n e^-u (lam = (H + sqrt(H^2 + 4(n + 1)))/2: H for large H, where e^{-H t}
    dominates), leaving exp(u (1 - H/lam) - u^2/(2 lam^2)) smooth and slowly varying. In
    log space: no underflow before the final exp (F_{5/2}(40) ~ e^-800)."""
    x, logw = _laguerre(float(n), _LAGUERRE_NODES)
    x, logw = jnp.asarray(x, H.dtype), jnp.asarray(logw, H.dtype)
    lam = 0.5 * (H + jnp.sqrt(H * H + 4.0 * (n + 1.0)))
    g = logw + x * (1.0 - H / lam)[..., None] - 0.5 * (x / lam[..., None]) ** 2
    return (-0.5 * math.log(2 * math.pi) - (n + 1.0) * jnp.log(lam) - 0.5 * H * H
            + jax.scipy.special.logsumexp(g, axis=-1))


def _F_kummer(n, H):
    """F_n(H) for -10 < H < 1 through Kummer's M (Abramowitz and Stegun 19.3.1, 19.12.3 with
    F_n(H) = Gamma(n+1) (2 pi)^-1/2 e^{-H^2/4} D_{-n-1}(H)):
    F_n = Gamma(n+1) 2^{-(n+1)/2} (2 pi)^-1/2 e^{-z} [sqrt(pi)/Gamma(1+n/2) M((n+1)/2, 1/2, z)
    - sqrt(2 pi) H/Gamma((n+1)/2) M(1+n/2, 3/2, z)], z = H^2/2. For H < 0 both terms are
    positive series: no cancellation (0 <= H < 1: mild); 128 terms reach 1e-14 for z <= 50."""
    z = 0.5 * H * H
    logz = jnp.log(jnp.maximum(z, jnp.finfo(H.dtype).tiny))     # z = 0: the k = 0 term alone
    k = np.arange(_KUMMER_TERMS)
    lg = np.vectorize(math.lgamma)

    def m(a, b):     # e^-z M(a, b, z), summed in log space
        # log((a)_k / ((b)_k k!)): constants of the static n, computed here, not in the program
        log_coefficients = jnp.asarray(lg(a + k) - lg(a) - lg(b + k) + lg(b) - lg(k + 1.0), H.dtype)
        lt = log_coefficients + k.astype(H.dtype) * logz[..., None] - z[..., None]
        return jnp.exp(jax.scipy.special.logsumexp(lt, axis=-1))

    pre = math.exp(math.lgamma(n + 1) - 0.5 * (n + 1) * math.log(2) - 0.5 * math.log(2 * math.pi))
    return pre * (math.sqrt(math.pi) / math.gamma(1 + n / 2) * m((n + 1) / 2, 0.5)
                  - math.sqrt(2 * math.pi) / math.gamma((n + 1) / 2) * H * m(1 + n / 2, 1.5))


def _F_asymptotic(n, H):
    """F_n(H) for H <= -10: with a = -H, (s + a)^n expanded in s/a and integrated against the
    Gaussian, F_n = sum_k C(n, 2k) (2k-1)!! a^{n-2k} (the part s < -a, e^{-a^2/2} ~ 2e-22
    relative, dropped); 16 terms: the series' truncation below 1e-15 for a >= 10."""
    a = -H
    coefficients = jnp.asarray([math.prod((n - j) / (j + 1) for j in range(2 * k))      # C(n, 2k), n real
                                * math.prod(range(2 * k - 1, 0, -2))                    # (2k-1)!!, 1 for k = 0
                                for k in range(_ASYMPTOTIC_TERMS)], H.dtype)
    # the terms as one array (a program a tenth the size of a Horner loop unrolled over them),
    # summed smallest first (for a >= 10 each is a small fraction of the one before)
    powers = (a * a)[..., None] ** -jnp.arange(_ASYMPTOTIC_TERMS - 1, -1, -1, dtype=H.dtype)
    return jnp.sum(coefficients[::-1] * powers, axis=-1) * a ** n


def _F(n: float, H):
    Hl = jnp.maximum(H, _LAGUERRE_H_MIN)
    Hk = jnp.clip(H, _KUMMER_H_MIN, _LAGUERRE_H_MIN)       # keep the unused branches finite
    Ha = jnp.minimum(H, _KUMMER_H_MIN)
    return jnp.where(H >= _LAGUERRE_H_MIN, jnp.exp(_log_F_laguerre(n, Hl)),
                     jnp.where(H > _KUMMER_H_MIN, _F_kummer(n, Hk), _F_asymptotic(n, Ha)))


@functools.partial(jax.custom_jvp, nondiff_argnums=(0,))
def _F_jvp(n, H):
    return _F(n, H)


@_F_jvp.defjvp
def _F_jvp_rule(n, primals, tangents):
    (H,), (dH,) = primals, tangents
    F = _F_jvp(n, H)
    # dF_n/dH = -n F_{n-1} (n > 0: exact, no cancellation); for n <= 0 the equal form
    # -(F_{n+1} + H F_n) (F_{n-1} would not be integrable)
    dF = -n * _F_jvp(n - 1.0, H) if n > 0 else -(_F_jvp(n + 1.0, H) + H * F)
    return F, dF * dH


def asperity_integral(H, n: float = 2.5):
    """Greenwood and Tripp's F_n(H) = (2 pi)^-1/2 int_H^inf (s - H)^n exp(-s^2/2) ds: the
    n-th moment of a unit Gaussian's excess over H (dimensionless), n > -1 (static).

    F_{5/2} gives the asperity pressure (:meth:`Roughness.asperity_pressure`), F_{3/2} the
    Greenwood-Williamson load, F_1(-H) the expected gap (:func:`expected_gap`). Closed form:
    F_n(H) = Gamma(n+1) (2 pi)^-1/2 exp(-H^2/4) D_{-n-1}(H), D the parabolic cylinder function.

    Method, by range (all in jnp, jit/vmap-able, fixed cost):
      - H >= 1: Gauss-Laguerre quadrature (64 nodes, weight t^n e^-t: the endpoint power exact)
        after s = H + t and a scaling of t that follows the integrand's decay, in log space;
      - -10 < H < 1: the Kummer-function series above (128 terms, all positive for H < 0);
      - H <= -10: the asymptotic series sum_k C(n, 2k) (2k-1)!! (-H)^{n-2k} (16 terms).
    Relative error against adaptive quadrature (tests/test_roughness.py): below 1e-13 for n =
    5/2, 3/2, 1/2 and 2e-13 for n = -1/2 on [-40, 12] (1e-14 on [0, 6]); F underflows to 0 in
    float64 above H ~ 37.5 (F_{5/2}(37) ~ 2e-303) and in float32 above H ~ 12.5, and grows as
    (-H)^n below.

    Derivatives (any order) from dF_n/dH = -n F_{n-1} (exact, a custom JVP): finite
    everywhere, 0 where F has underflowed.
    """
    n = float(n)
    if not n > -1.0:
        raise ValueError(f"n must be > -1 (the integral diverges at s = H otherwise), got {n}")
    H = jnp.asarray(H)
    if not jnp.issubdtype(H.dtype, jnp.floating):
        H = H.astype(jnp.result_type(float))
    return _F_jvp(n, H)


# ---- the Gaussian expected gap ----------------------------------------------------------------
def expected_gap(H):
    """The expected local gap over the nominal gap's roughness scale, h_T / sigma, for Gaussian
    heights (dimensionless): E[max(h + delta, 0)] / sigma with delta ~ N(0, sigma^2), i.e.
    h_T = (sigma/2) [H + H erf(H/sqrt 2) + sqrt(2/pi) exp(-H^2/2)] = sigma F_1(-H).
    Tends to H for large H (within e^{-H^2/2}) and to 0 as H -> -inf (surfaces in contact
    everywhere); d(h_T/sigma)/dH = (1 + erf(H/sqrt 2))/2 (the probability of a gap)."""
    H = jnp.asarray(H)
    # H Phi(H) + phi(H) with Phi from erfc: no cancellation in Phi itself for H < 0
    return H * 0.5 * jax.scipy.special.erfc(-H / math.sqrt(2)) + jnp.exp(-0.5 * H * H) / math.sqrt(2 * math.pi)


# ---- Patir and Cheng's flow factors ----------------------------------------------------------
def _row(table: dict, gamma, what: str):
    for g, row in table.items():
        if math.isclose(float(gamma), g, rel_tol=1e-9):
            return row
    names = ", ".join(f"{g:.4g}" for g in table)
    raise ValueError(f"gamma must be one of the values Patir and Cheng tabulate for {what} "
                     f"({names}), got {gamma!r}")


def pressure_flow_factor(H, gamma: float = 1.0):
    """Patir and Cheng's (1978) pressure flow factor phi_x(H) (dimensionless) along the sliding
    direction, for the orientation ``gamma`` (static, one of :data:`GAMMAS`): 1 - C e^{-r H}
    (gamma <= 1), 1 + C H^{-r} (gamma > 1), table :data:`PRESSURE_FLOW`. The fits hold for H
    above 0.5-1 (H_min in the table); below, callers clip H (:class:`Roughness`). Tends to 1
    (smooth surfaces) as H -> inf. The cross-flow factor phi_y is phi_x at 1/gamma."""
    C, r, _ = _row(PRESSURE_FLOW, gamma, "the pressure flow factor")
    H = jnp.asarray(H)
    if gamma <= 1.0:
        return 1.0 - C * jnp.exp(-r * H)
    return 1.0 + C * H ** (-r)


def shear_flow_factor(H, gamma: float = 1.0):
    """Patir and Cheng's (1978) shear flow factor Phi_s(H) of one rough surface sliding
    (dimensionless): A1 H^a1 exp(-a2 H + a3 H^2) for H <= 5, A2 exp(-0.25 H) beyond (table
    :data:`SHEAR_FLOW`). Fitted for H >= 0.5; tends to 0 as H -> inf. For two surfaces of
    the same gamma the film sees Vr Phi_s, Vr = (sigma_1^2 - sigma_2^2)/sigma^2."""
    A1, a1, a2, a3, A2 = _row(SHEAR_FLOW, gamma, "the shear flow factor")
    H = jnp.asarray(H)
    Hs = jnp.clip(H, 1e-30, 5.0)     # the power branch only where it is used: finite gradients
    return jnp.where(H <= 5.0, A1 * Hs ** a1 * jnp.exp(-a2 * Hs + a3 * Hs * Hs), A2 * jnp.exp(-0.25 * H))


# ---- Patir and Cheng's shear stress factors -----------------------------------------------------
_PHI_F_SERIES = 24      # z > 2: terms of sum_k E[x^2k] z^-2k


def _phi_f_moments():
    """E[x^2k] of the density (35/32)(1 - x^2)^3 on [-1, 1]: B(k + 1/2, 4) / B(1/2, 4)."""
    return [math.exp(math.lgamma(k + 0.5) + math.lgamma(4.5) - math.lgamma(0.5) - math.lgamma(k + 4.5))
            for k in range(_PHI_F_SERIES)]


def friction_factor(H):
    """Patir and Cheng's (1979) shear stress factor phi_f(H) (dimensionless): the mean of
    h / h_local over the heights, with their polynomial density (35/32)(1 - x^2)^3 of
    x = delta/(3 sigma) on |x| < 1 (a Gaussian's stand-in, variance sigma^2). With z = H/3 and
    h/h_local = z/(z + x) = Q(x) + (1 - z^2)^3/(z + x), Q a polynomial: where the surfaces may
    touch (z < 1), Q is averaged over the positive gaps x > -z and the 1/(z + x) singularity
    is cut off at z + x = 1/300 (a local gap of sigma/100, :data:`FRICTION_CUTOFF`):

      z <= 1: (35/32) z {(1 - z^2)^3 ln(300 (z + 1)) + (1/60)[-55 + z(132 + z(345 + z(-160
              + z(-405 + z(60 + 147 z)))))]}
      z > 1:  (35/32) z {(1 - z^2)^3 ln((z + 1)/(z - 1)) + (z/15)[66 + z^2 (30 z^2 - 80)]},

    the latter for z > 2 summed as its convergent series 1 + sum_k E[x^2k] z^-2k (the closed
    form cancels ~z^6-fold). Tends to 1 (smooth) as H -> inf; continuous at z = 1 (35/30);
    0 at H = 0 and negative below (callers clip H)."""
    z = jnp.asarray(H) / 3.0
    za = jnp.clip(z, 0.0, 1.0)
    low = (35 / 32) * za * ((1 - za * za) ** 3 * jnp.log((za + 1) / FRICTION_CUTOFF)
                            + (-55 + za * (132 + za * (345 + za * (-160 + za * (-405 + za * (60 + 147 * za)))))) / 60)
    zb = jnp.clip(z, 1.0 + 1e-9, 2.0)
    mid = (35 / 32) * zb * ((1 - zb * zb) ** 3 * jnp.log((zb + 1) / (zb - 1))
                            + zb / 15 * (66 + zb * zb * (30 * zb * zb - 80)))
    zc = jnp.maximum(z, 2.0)
    high = jnp.zeros_like(zc)
    for m in reversed(_phi_f_moments()):
        high = high / (zc * zc) + m
    return jnp.where(z <= 1.0, low, jnp.where(z <= 2.0, mid, high))


def shear_stress_factors(H, gamma: float = 1.0):
    """Patir and Cheng's (1979) shear stress factors (Phi_fs, phi_fp)(H) (dimensionless) for
    one rough surface: Phi_fs = A3 H^a4 exp(-a5 H + a6 H^2) for H < 7 and 0 beyond (the
    paper's range: the fit turns up again past H ~ 11; the step at 7 is 0.013), phi_fp = 1 - D
    exp(-s H); fitted for H > 0.5 (table :data:`SHEAR_STRESS`, gamma = 1 only). phi_fp -> 1
    and Phi_fs -> 0 (smooth) as H -> inf."""
    D, s, A3, a4, a5, a6 = _row(SHEAR_STRESS, gamma, "the shear stress factors (1979)")
    H = jnp.asarray(H)
    Hs = jnp.clip(H, 1e-30, SHEAR_STRESS_H_MAX)
    fs = jnp.where(H < SHEAR_STRESS_H_MAX, A3 * Hs ** a4 * jnp.exp(-a5 * Hs + a6 * Hs * Hs), 0.0)
    return fs, 1.0 - D * jnp.exp(-s * H)


# ---- the composite modulus ---------------------------------------------------------------------
def composite_modulus(E1, nu1, E2, nu2):
    """The asperities' composite modulus E' (Pa) with 1/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
    (Greenwood and Williamson's and Greenwood and Tripp's E'; Hertz's E* of many texts is 2E'
    with the 2/E* convention and goes with K/2, see :class:`Roughness`). E in Pa."""
    for name, v in (("E1", E1), ("E2", E2)):
        checks.positive(name, v)
    checks.poisson("nu1", nu1)
    checks.poisson("nu2", nu2)
    return 1.0 / ((1.0 - nu1 ** 2) / E1 + (1.0 - nu2 ** 2) / E2)


GREENWOOD_TRIPP = 16.0 * math.sqrt(2.0) * math.pi / 15.0     # K = this (eta_s beta sigma)^2 sqrt(sigma/beta)
COUETTE = ("expected", "nominal")


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Roughness:
    """Two rough surfaces in a film: the Patir-Cheng flow and shear stress factors and the
    Greenwood-Tripp asperity pressure, with the conventions below (a PyTree: jit, vmap and grad
    see the numbers; ``gamma``, ``clip`` and ``couette`` are static).

    Attributes:
      sigma: composite rms roughness sqrt(sigma_1^2 + sigma_2^2) (m), Gaussian heights.
      E: the composite modulus E' (Pa), 1/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
        (:func:`composite_modulus`); it belongs to the asperities, so a rigid body in the film
        still has one.
      eta_beta_sigma: eta_s beta sigma (dimensionless), eta_s the asperity density (1/m^2),
        beta their tip radius (m). Default 0.05.
      sigma_over_beta: sigma / beta (dimensionless). Default 0.005. (Greenwood and Williamson
        found eta_s beta sigma of 0.03-0.05 and sigma/beta of 1e-4 to 1e-2 on engineering
        surfaces; the defaults are the issue-43 reference case's.)
      Vr: (sigma_1^2 - sigma_2^2)/sigma^2 in [-1, 1], surface 1 the moving one (the journal),
        2 the stationary one (the bore): -1 when only the bore is rough (default), +1 when only
        the journal is, 0 for equal roughness. It sets the sign of the shear flow and of the
        shear stress factor Phi_fs; a rotating sleeve on a fixed shaft swaps the roles.
      mu_b: boundary friction coefficient on the asperity pressure (default 0.1).
      gamma (static): Peklenik's orientation parameter, one of :data:`GAMMAS` (default 1,
        isotropic; the 1979 shear stress factors only for 1).
      clip (static): the flow and shear stress factors are evaluated at H_c = max(h/sigma,
        clip) and the Poiseuille and shear gaps at h_c = sigma H_c (default 0.5, the lower end
        of the isotropic fits; the choice matters in mixed lubrication: 1.0 instead moves the
        mid-mixed friction by up to 88 % in the issue-43 cases).
      couette (static): the gap carried by the mean surface speed: "expected" (default) the
        Gaussian expected gap h_T (unclipped) as Patir and Cheng, or "nominal" h, as some
        later authors; the shear flow term sigma Vr Phi_s(H_c) is added to either.

    The pressure of the asperities is p_a = K E' F_{5/2}(h/sigma), unclipped, with K = (16
    sqrt 2 pi/15)(eta_s beta sigma)^2 sqrt(sigma/beta) (with E' of the 1/E' convention; the
    2/E' convention's modulus is twice as large and goes with 8 sqrt 2 pi / 15).

    Build it with :meth:`from_surfaces` (two surfaces' sigma, E and nu) or directly.
    """

    sigma: jax.Array
    E: jax.Array
    eta_beta_sigma: jax.Array = 0.05
    sigma_over_beta: jax.Array = 0.005
    Vr: jax.Array = -1.0
    mu_b: jax.Array = 0.1
    gamma: float = dataclasses.field(default=1.0, metadata=dict(static=True))
    clip: float = dataclasses.field(default=0.5, metadata=dict(static=True))
    couette: str = dataclasses.field(default="expected", metadata=dict(static=True))

    def __post_init__(self):
        checks.positive("sigma", self.sigma)
        checks.positive("E", self.E)
        checks.positive("eta_beta_sigma", self.eta_beta_sigma)
        checks.positive("sigma_over_beta", self.sigma_over_beta)
        checks.nonnegative("mu_b", self.mu_b)
        vr = checks.values("Vr", self.Vr)
        if vr is not None and not np.all(np.abs(vr) <= 1.0 + 1e-12):
            raise ValueError(f"Vr = (sigma_1^2 - sigma_2^2)/sigma^2 must lie in [-1, 1], got {self.Vr!r}")
        if isinstance(self.gamma, (int, float)):     # PyTree rebuilds pass placeholders
            _row(PRESSURE_FLOW, self.gamma, "the flow factors")
        if isinstance(self.clip, (int, float)):
            checks.option_number("clip", self.clip)
        if isinstance(self.couette, str):
            checks.one_of("couette", self.couette, COUETTE)

    # ---- constructors ----------------------------------------------------------------------
    @classmethod
    def from_surfaces(cls, sigma_journal, sigma_bore, E_journal, nu_journal, E_bore, nu_bore, **kw):
        """From each surface's rms roughness (m; 0 for a smooth one, not both), Young's modulus
        (Pa) and Poisson's ratio: sigma = sqrt(sigma_j^2 + sigma_b^2), Vr = (sigma_j^2 -
        sigma_b^2)/sigma^2 (the journal the moving surface), E' by :func:`composite_modulus`.
        Other attributes by keyword."""
        checks.nonnegative("sigma_journal", sigma_journal)
        checks.nonnegative("sigma_bore", sigma_bore)
        s2 = jnp.asarray(sigma_journal) ** 2 + jnp.asarray(sigma_bore) ** 2
        if checks.values("sigma", s2) is not None and not np.all(np.asarray(s2) > 0):
            raise ValueError("sigma_journal and sigma_bore are both 0: give at least one surface a roughness")
        Vr = (jnp.asarray(sigma_journal) ** 2 - jnp.asarray(sigma_bore) ** 2) / s2
        return cls(jnp.sqrt(s2), composite_modulus(E_journal, nu_journal, E_bore, nu_bore), Vr=Vr, **kw)

    @classmethod
    def from_asperities(cls, sigma, eta_s, beta, E, **kw):
        """From the asperity density ``eta_s`` (1/m^2) and tip radius ``beta`` (m) with
        ``sigma`` (m) and ``E`` (Pa); other attributes by keyword."""
        checks.positive("eta_s", eta_s)
        checks.positive("beta", beta)
        checks.positive("sigma", sigma)
        return cls(sigma, E, eta_beta_sigma=eta_s * beta * sigma, sigma_over_beta=sigma / beta, **kw)

    # ---- the model -------------------------------------------------------------------------
    @property
    def K(self):
        """Greenwood and Tripp's K = (16 sqrt 2 pi/15)(eta_s beta sigma)^2 sqrt(sigma/beta)."""
        return GREENWOOD_TRIPP * self.eta_beta_sigma ** 2 * jnp.sqrt(self.sigma_over_beta)

    def film_parameter(self, h):
        """H = h / sigma (dimensionless), unclipped."""
        return h / self.sigma

    def clipped(self, h):
        """(H_c, h_c) = (max(h/sigma, clip), sigma H_c): where the fits are evaluated."""
        Hc = jnp.maximum(h / self.sigma, self.clip)
        return Hc, self.sigma * Hc

    def asperity_pressure(self, h):
        """p_a = K E' F_{5/2}(h/sigma) (Pa) at the nominal gap ``h`` (m; any sign: h < 0 is
        an asperity layer compressed beyond its mean planes)."""
        return self.K * self.E * asperity_integral(h / self.sigma, 2.5)

    def boundary_shear(self, h):
        """The asperities' friction stress mu_b p_a (Pa)."""
        return self.mu_b * self.asperity_pressure(h)

    def poiseuille(self, h):
        """The Poiseuille conductance's gap term phi_x(H_c) h_c^3 (m^3), to replace h^3 in
        d/dx(h^3/(12 eta) dp/dx). Isotropic roughness: the same along and across the sliding."""
        Hc, hc = self.clipped(h)
        return pressure_flow_factor(Hc, self.gamma) * hc ** 3

    def poiseuille_across(self, h):
        """phi_y(H_c) h_c^3 (m^3) across the sliding: phi_x at 1/gamma."""
        Hc, hc = self.clipped(h)
        return pressure_flow_factor(Hc, _reciprocal(self.gamma)) * hc ** 3

    def couette_gap(self, h):
        """The gap the mean surface speed carries (m): h_T + Vr sigma Phi_s(H_c) ("expected")
        or h + Vr sigma Phi_s(H_c) ("nominal"); the Couette flux is (U/2) times it."""
        Hc, _ = self.clipped(h)
        base = self.sigma * expected_gap(h / self.sigma) if self.couette == "expected" else h
        return base + self.Vr * self.sigma * shear_flow_factor(Hc, self.gamma)

    def expected_gap(self, h):
        """The Gaussian expected gap h_T (m), unclipped (:func:`expected_gap`)."""
        return self.sigma * expected_gap(h / self.sigma)

    def journal_shear(self, h, viscosity, U, dpdx):
        """The film's mean shear stress resisting the journal's motion (Pa):
        eta U/h_c (phi_f - Vr Phi_fs) + phi_fp (h_c/2) dp/dx, all at H_c, x along the journal
        surface's motion, U its speed (m/s), ``viscosity`` eta (Pa s), ``dpdx`` (Pa/m). For a
        smooth film (phi_f = phi_fp = 1, Phi_fs = 0) the familiar eta U/h + (h/2) dp/dx."""
        Hc, hc = self.clipped(h)
        fs, fp = shear_stress_factors(Hc, self.gamma)
        return viscosity * U / hc * (friction_factor(Hc) - self.Vr * fs) + fp * 0.5 * hc * dpdx


def _reciprocal(gamma: float) -> float:
    for g in GAMMAS:
        if math.isclose(g * gamma, 1.0, rel_tol=1e-9):
            return g
    return gamma
