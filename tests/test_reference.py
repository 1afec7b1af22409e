"""vjax.reference against independent evaluations: quadrature, limits, collocation, identities.

Nothing here re-uses the library's formulas: the checks integrate, differentiate or solve the
defining equations another way (scipy quadrature and root finding, Gauss-Chebyshev
collocation, the ring kernels' element integrals).
"""
import warnings

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy import integrate, optimize

import vjax
from vjax import reference as ref

E, R, DR = 1e6, 0.08, 4e-5          # thesis Figs. 2.5-2.6


# ------------------------------------------------------------------------------ Hertz
def test_hertz_pressure_carries_the_load_and_obeys_the_curvature_identity():
    F, Rc, Ec, nu = 120.0, 0.01, 2e9, 0.3
    a, p0, p = ref.hertz_line_contact(F, Rc, Ec, nu)
    total = integrate.quad(lambda x: float(p(x)), -a, a, epsabs=0, epsrel=1e-12)[0]
    assert total == pytest.approx(F, rel=1e-9)
    # Johnson (4.43b): p0 = E* a / (2 R); and p vanishes at the edge
    assert float(p0) == pytest.approx(Ec / (1 - nu**2) * float(a) / (2 * Rc), rel=1e-12)
    assert float(p(1.0001 * a)) == 0.0
    # two equal elastic cylinders (R1 = R2 = Rc): half the relative radius, twice the
    # compliance, the same half-width
    a2, _, _ = ref.hertz_line_contact(F, Rc, Ec, nu, Rc, Ec, nu)
    assert float(a2) == pytest.approx(float(a), rel=1e-12)


def test_hertz_gradient_matches_finite_differences():
    half_width = lambda F: ref.hertz_line_contact(F, 0.01, 2e9, 0.3)[0]
    g = float(jax.grad(half_width)(100.0))
    fd = (float(half_width(100.0 + 1e-3)) - float(half_width(100.0 - 1e-3))) / 2e-3
    assert g == pytest.approx(fd, rel=1e-8)


# ------------------------------------------------------------------------------ Lame
@pytest.mark.parametrize("nu", [0.3, 0.45, 0.5])
def test_lame_is_mode_zero_of_the_ring_operators(nu):
    m = vjax.Material.elastic(2e6, nu)
    for kind, green in (("hole", "hole"), ("disc", "cylinder")):
        u = vjax.ring_operator(green, m, 0.05, 64)(jnp.full(64, 1e4))
        assert np.allclose(np.asarray(u), float(ref.lame_displacement(kind, 1e4, 0.05, 2e6, nu)), rtol=1e-10,
                           atol=1e-18)


# ------------------------------------------------------------------------------ Winkler
def test_winkler_pin_carries_the_load_and_closes_at_the_edge():
    R, c, k, F = 0.02, 5e-5, 1e12, 3e4
    alpha, e, p = ref.winkler_pin(F, R, c, k)
    assert float(p(float(alpha))) == pytest.approx(0.0, abs=1e-9 * float(p(0.0)))
    total = R * integrate.quad(lambda th: float(p(th)) * np.cos(th), -float(alpha), float(alpha), epsrel=1e-12)[0]
    assert total == pytest.approx(F, rel=1e-9)
    # small contact: the parabolic (Hertz-like) limit, F ~ (2/3) R k c alpha^3
    a_small, _, _ = ref.winkler_pin(1e-3, R, c, k)
    assert 2 / 3 * R * k * c * float(a_small) ** 3 == pytest.approx(1e-3, rel=1e-4)
    assert float(ref.oedometric_stiffness(2e6, 0.3, 1e-3)) == pytest.approx(2e6 * 0.7 / (1.3 * 0.4 * 1e-3))


# ------------------------------------------------------------------------------ Persson
def _gauss_chebyshev_pressure(b, m=60):
    """The arc equation of the Persson problem (K = 1) by Gauss-Chebyshev collocation:
    q = p/(1+s^2) = w(s) sum c_j U_j(s/b), with P0 and F/R as two more unknowns and their
    definitions as two more equations. Returns (theta nodes, p at nodes, P0, F/R)."""
    k = np.arange(1, m + 1)
    y = np.cos(np.pi * k / (m + 1))
    t = b * y
    j = np.arange(m)
    T = np.cos((j[None, :] + 1) * np.arccos(y)[:, None])
    A = np.zeros((m + 2, m + 2))
    rhs = np.zeros(m + 2)
    A[:m, :m] = b * T
    A[:m, m] = -(np.arctan(t) / np.pi + t / (2.0 * np.pi)) / (1.0 + t * t)
    A[:m, m + 1] = -2.0 / np.pi * t / (1.0 + t * t) ** 2
    rhs[:m] = 2.0 * np.arctan(t) / (1.0 + t * t)
    nq = 4 * m
    xq = np.cos(np.pi * np.arange(1, nq + 1) / (nq + 1))
    wq = np.pi / (nq + 1) * np.sin(np.pi * np.arange(1, nq + 1) / (nq + 1)) ** 2
    U = np.sin((j[None, :] + 1) * np.arccos(xq)[:, None]) / np.sqrt(1 - xq**2)[:, None]
    s = b * xq
    base = (wq[:, None] * U) * b * b
    A[m, :m], A[m, m] = 2.0 * base.sum(0), -1.0
    A[m + 1, :m], A[m + 1, m + 1] = 2.0 * (base * ((1 - s**2) / (1 + s**2))[:, None]).sum(0), -1.0
    sol = np.linalg.solve(A, rhs)
    Uy = np.sin((j[None, :] + 1) * np.arccos(y)[:, None]) / np.sqrt(1 - y**2)[:, None]
    q = b * np.sqrt(1 - y**2) * (Uy @ sol[:m])
    return 2.0 * np.arctan(t), q * (1.0 + t * t), sol[m], sol[m + 1]


def test_persson_closed_form_matches_collocation():
    for b in (0.1, 0.4, 0.7, 1.0):
        theta, p_gc, p0_gc, f_gc = _gauss_chebyshev_pressure(b)
        p0, f = (float(v) for v in ref.persson_coefficients(b))
        K = E * DR / (1.5 * R)
        p = np.asarray(ref.persson_pressure(theta, b, E, R, DR)) / K
        assert np.max(np.abs(p - p_gc)) <= 1e-11 * np.max(np.abs(p_gc))
        assert p0 == pytest.approx(p0_gc, rel=1e-11) and f == pytest.approx(f_gc, rel=1e-11)


def test_persson_shape_function_moments_in_closed_form():
    """int gC = 2 pi (S-1)/S, int gC cos = 2 pi (S-1)/S^2, int gB = pi b^2/S^3 (S = sqrt(1+b^2))."""
    for b in (0.05, 0.4, 0.73):
        S, alpha = np.sqrt(1 + b * b), 2 * np.arctan(b)
        g = lambda th, i: float(ref.persson_shape_functions(th, b)[i])
        quad = lambda f: integrate.quad(f, -alpha, alpha, epsabs=0, epsrel=1e-12, limit=200)[0]
        assert quad(lambda th: g(th, 1)) == pytest.approx(2 * np.pi * (S - 1) / S, rel=1e-10)
        assert quad(lambda th: g(th, 1) * np.cos(th)) == pytest.approx(2 * np.pi * (S - 1) / S**2, rel=1e-10)
        assert quad(lambda th: g(th, 2)) == pytest.approx(np.pi * b * b / S**3, rel=1e-10)


def test_persson_limiting_angle_thesis_angle_and_hertz_limit():
    b = ref.persson_b_from_load(2.3e-2 * E * R, E, R, DR)
    assert 2 * np.arctan(b) == pytest.approx(1.24, abs=5e-3)                # thesis: 1.24 rad
    bc = ref.persson_limit_b()
    assert 2 * np.arctan(bc) == pytest.approx(1.26272, abs=1e-5)           # neat fit, F -> inf
    lp = np.asarray(ref.persson_load_parameter(np.array([0.05, 0.3, 0.6, bc, bc * 1.01])))
    assert np.all(np.diff(lp) < 0) and abs(lp[3]) < 1e-9 and lp[4] < 0
    # small loads: Hertz's conforming contact, a rigid pin of radius R - dR in the hole
    F = E / (1 - 0.5**2) * DR / float(ref.persson_load_parameter(0.01))
    a, _, _ = ref.hertz_line_contact(F, R - DR, E, 0.5, -R)
    assert R * 2 * np.arctan(0.01) == pytest.approx(float(a), rel=2e-3)


# ------------------------------------------------------------------------------ long bearing
RJ, CJ, ETA, V = 0.05, 5e-5, 0.01, 0.5 * 100.0 * (0.05 - 5e-5)


def _reynolds_by_quadrature(eps):
    """Swift-Stieber long bearing by scipy quadrature and brentq (groove at theta = pi)."""
    h = lambda t: CJ * (1 - eps * np.cos(t))

    def p(t, t2):
        return 12 * ETA * RJ * V * integrate.quad(lambda s: (h(s) - h(t2)) / h(s) ** 3, -np.pi, t,
                                                  epsabs=0, epsrel=1e-12, limit=200)[0]

    t2 = optimize.brentq(lambda t2: p(t2, t2), 1e-6, np.pi - 1e-6, xtol=1e-14)
    Fx = -RJ * integrate.quad(lambda t: p(t, t2) * np.cos(t), -np.pi, t2, epsrel=1e-11, limit=200)[0]
    Fy = -RJ * integrate.quad(lambda t: p(t, t2) * np.sin(t), -np.pi, t2, epsrel=1e-11, limit=200)[0]
    return np.hypot(Fx, Fy), np.arctan2(Fy, -Fx), t2


@pytest.mark.parametrize("eps", [0.3, 0.8])
def test_reynolds_long_bearing_against_quadrature(eps):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # quad's roundoff notes near the 1e-12 target
        W, phi, t2 = _reynolds_by_quadrature(eps)
    r = ref.long_bearing(eps, RJ, CJ, ETA, V, "reynolds")
    assert float(r["load"]) == pytest.approx(W, rel=1e-9)
    assert float(r["attitude"]) == pytest.approx(phi, abs=1e-9)
    assert float(r["rupture"]) == pytest.approx(t2, abs=1e-9)
    # Reynolds condition: p = dp/dtheta = 0 at the rupture angle (one-sided difference)
    t, h = float(r["rupture"]), 1e-5
    assert abs(float(r["pressure"](t - h))) < 1e-6 * float(jnp.max(r["pressure"](jnp.linspace(-3, t, 200))))


@pytest.mark.parametrize("conditions", ["sommerfeld", "half_sommerfeld"])
def test_closed_form_loads_are_the_integrals_of_their_pressures(conditions):
    r = ref.long_bearing(0.6, RJ, CJ, ETA, V, conditions)
    p = lambda t: float(r["pressure"](t))
    tol = 1e-12 * float(r["load"]) / RJ     # Fx vanishes for Sommerfeld: an absolute tolerance
    Fx = -RJ * integrate.quad(lambda t: p(t) * np.cos(t), -np.pi, np.pi, epsabs=tol, epsrel=1e-12, limit=400)[0]
    Fy = -RJ * integrate.quad(lambda t: p(t) * np.sin(t), -np.pi, np.pi, epsabs=tol, epsrel=1e-12, limit=400)[0]
    assert float(r["load"]) == pytest.approx(np.hypot(Fx, Fy), rel=1e-9)
    assert float(r["attitude"]) == pytest.approx(np.arctan2(Fy, -Fx), abs=1e-8)


def test_half_sommerfeld_inverse_and_small_eccentricity_limit():
    eps = jnp.array([0.05, 0.3, 0.6, 0.9])
    back = ref.half_sommerfeld_eccentricity(ref.half_sommerfeld_load(eps))
    assert np.allclose(np.asarray(back), np.asarray(eps), rtol=0, atol=1e-12)
    # eps -> 0: the half film carries half the full film's load, G ~ pi eps / 2
    assert float(ref.half_sommerfeld_load(1e-6)) == pytest.approx(np.pi / 2 * 1e-6, rel=1e-6)


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="conditions"):
        ref.long_bearing(0.5, RJ, CJ, ETA, V, "jfo")
    with pytest.raises(ValueError, match="eps"):
        ref.long_bearing(1.2, RJ, CJ, ETA, V)
    with pytest.raises(ValueError, match="load"):
        ref.hertz_line_contact(-1.0, 0.01, 2e9, 0.3)
    with pytest.raises(ValueError, match="kind"):
        ref.lame_displacement("ring", 1.0, 1.0, 1.0, 0.3)
    with pytest.raises(ValueError, match="dR"):
        ref.persson_b_from_load(100.0, E, R, -1e-5)
