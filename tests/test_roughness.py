"""Rough surfaces (vjax.films.roughness): Greenwood-Tripp's F_n against adaptive quadrature and
the parabolic-cylinder closed form, Patir-Cheng's factors against the published formulas and
their limits, the expected gap and the asperity pressure against direct integration."""
import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy import integrate, special

from vjax.films import roughness as rg
from vjax.films.roughness import Roughness

SQRT2PI = math.sqrt(2 * math.pi)


def F_quad(n, H):
    """F_n(H) = (2 pi)^-1/2 int_0^inf t^n exp(-(t + H)^2/2) dt by adaptive quadrature, split at
    the integrand's peak; for H > 0 with exp(-H^2/2) taken out (no underflow)."""
    if H < 0:
        f = lambda t: t ** n * np.exp(-0.5 * (t + H) ** 2)     # noqa: E731
        scale, cuts = 1.0, (0.0, -H, -H + 1.0, np.inf)
    else:
        f = lambda t: t ** n * np.exp(-H * t - 0.5 * t * t)    # noqa: E731
        scale, cuts = np.exp(-0.5 * H * H), (0.0, 1.0, np.inf)
    total = sum(integrate.quad(f, a, b, epsabs=0.0, epsrel=1e-13, limit=400)[0]
                for a, b in zip(cuts[:-1], cuts[1:]) if b > a)
    return scale * total / SQRT2PI


# ---- F_n -------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [2.5, 1.5])
def test_F_against_quadrature_on_0_6(n):
    H = np.linspace(0.0, 6.0, 61)
    F = np.asarray(rg.asperity_integral(H, n))
    ref = np.array([F_quad(n, h) for h in H])
    assert np.max(np.abs(F / ref - 1)) < 1e-8          # the bound; measured ~1e-14
    assert np.max(np.abs(F / ref - 1)) < 1e-12


@pytest.mark.parametrize("n", [2.5, 1.5, 0.5, -0.5])
def test_F_against_quadrature_everywhere(n):
    # every branch (asymptotic below -10, Kummer series to 1, Laguerre above) and their seams
    H = np.concatenate([[-40.0, -25.0, -10.5, -10.0, -9.99], np.linspace(-9.5, 12.0, 44), [0.99, 1.0, 1.01]])
    F = np.asarray(rg.asperity_integral(H, n))
    ref = np.array([F_quad(n, h) for h in H])
    assert np.max(np.abs(F / ref - 1)) < 1e-11


def test_F_closed_forms():
    for n in (2.5, 1.5, 0.5):     # F_n(0) = 2^((n-1)/2) Gamma((n+1)/2) / sqrt(2 pi)
        assert np.isclose(rg.asperity_integral(0.0, n), 2 ** ((n - 1) / 2) * math.gamma((n + 1) / 2) / SQRT2PI,
                          rtol=1e-14, atol=0)
    # Gamma(n+1) (2 pi)^-1/2 exp(-H^2/4) D_{-n-1}(H) (scipy's parabolic cylinder function, ~1e-9)
    for H in (-3.0, -0.7, 0.4, 2.0, 5.0):
        D = special.pbdv(-3.5, H)[0]
        assert np.isclose(rg.asperity_integral(H), math.gamma(3.5) / SQRT2PI * math.exp(-H * H / 4) * D, rtol=1e-8)
    # far below: (s - H)^n averaged over the Gaussian, (-H)^n (1 + n(n-1)/(2 H^2) + ...)
    H = -40.0
    assert np.isclose(rg.asperity_integral(H), 40 ** 2.5 * (1 + 2.5 * 1.5 / (2 * 1600)), rtol=1e-6)


def test_F_sensible_beyond():
    H = np.linspace(-40.0, 40.0, 4001)
    F = np.asarray(rg.asperity_integral(H))
    assert np.all(np.isfinite(F)) and np.all(F >= 0)
    assert np.all(np.diff(F) <= 0)                     # non-increasing in H
    assert np.all(np.diff(F[F > 1e-300]) < 0)          # strictly while representable
    assert 0 <= float(rg.asperity_integral(40.0)) < 1e-300
    assert np.isfinite(float(jax.grad(rg.asperity_integral)(40.0)))


def test_F_gradient():
    H = np.concatenate([np.linspace(-12.0, 8.0, 41), [-10.0, 0.0, 1.0]])
    g = np.asarray(jax.vmap(jax.grad(rg.asperity_integral))(jnp.asarray(H)))
    d = 1e-5
    fd = (np.asarray(rg.asperity_integral(H + d)) - np.asarray(rg.asperity_integral(H - d))) / (2 * d)
    assert np.max(np.abs(g / fd - 1)) < 1e-6
    # dF_{5/2}/dH = -(5/2) F_{3/2}, the latter by quadrature
    ref = np.array([-2.5 * F_quad(1.5, h) for h in H])
    assert np.max(np.abs(g / ref - 1)) < 1e-11
    # second and third derivatives (through F_{1/2}, F_{-1/2}) against differences of the first
    g2 = jax.vmap(jax.grad(jax.grad(rg.asperity_integral)))(jnp.asarray(H))
    g3 = jax.vmap(jax.grad(jax.grad(jax.grad(rg.asperity_integral))))(jnp.asarray(H))
    dg = jax.vmap(jax.grad(rg.asperity_integral))
    fd2 = (dg(jnp.asarray(H + d)) - dg(jnp.asarray(H - d))) / (2 * d)
    assert np.allclose(g2, fd2, rtol=1e-6, atol=1e-9)
    dg2 = jax.vmap(jax.grad(jax.grad(rg.asperity_integral)))
    fd3 = (dg2(jnp.asarray(H + d)) - dg2(jnp.asarray(H - d))) / (2 * d)
    assert np.allclose(g3, fd3, rtol=1e-5, atol=1e-8)


def test_F_refuses_divergent_order():
    with pytest.raises(ValueError, match="n must be > -1"):
        rg.asperity_integral(1.0, -1.0)


# ---- the expected gap -----------------------------------------------------------------------
def test_expected_gap():
    for H in (-6.0, -2.0, -0.3, 0.0, 0.5, 2.0, 4.0):      # E[max(H + s, 0)], s ~ N(0, 1)
        ref = integrate.quad(lambda s: (H + s) * np.exp(-s * s / 2) / SQRT2PI, -H, np.inf,
                             epsabs=0, epsrel=1e-13)[0]
        assert np.isclose(rg.expected_gap(H), ref, rtol=1e-11, atol=0)
        assert np.isclose(rg.expected_gap(H), rg.asperity_integral(-H, 1.0), rtol=1e-11, atol=0)
    # h_T -> h for large H, -> 0 (from above) as H -> -inf
    assert abs(float(rg.expected_gap(9.0)) - 9.0) < 1e-15
    low = np.asarray(rg.expected_gap(np.linspace(-40.0, -5.0, 200)))
    assert np.all(low >= 0) and np.all(np.diff(low) >= 0) and low[0] == 0 and low[-1] < 1e-7
    # d(h_T/sigma)/dH = Phi(H), the probability of a gap
    H = jnp.linspace(-5.0, 5.0, 11)
    assert np.allclose(jax.vmap(jax.grad(rg.expected_gap))(H), special.ndtr(np.asarray(H)), rtol=1e-12, atol=1e-16)


# ---- Patir and Cheng ---------------------------------------------------------------------------
def test_isotropic_flow_factors_equal_published_fits():
    H = np.linspace(0.5, 12.0, 47)
    # Patir and Cheng 1978, gamma = 1: phi_x = 1 - 0.90 e^{-0.56 H};
    # Phi_s = 1.899 H^0.98 e^{-0.92 H + 0.05 H^2} (H <= 5), 1.126 e^{-0.25 H} (H > 5)
    assert np.allclose(rg.pressure_flow_factor(H), 1 - 0.90 * np.exp(-0.56 * H), rtol=1e-14)
    Phi_s = np.where(H <= 5, 1.899 * H ** 0.98 * np.exp(-0.92 * H + 0.05 * H ** 2), 1.126 * np.exp(-0.25 * H))
    assert np.allclose(rg.shear_flow_factor(H), Phi_s, rtol=1e-14)


@pytest.mark.parametrize("gamma", rg.GAMMAS)
def test_flow_factor_limits_and_table_consistency(gamma):
    big = np.array([300.0, 1000.0])
    assert np.allclose(rg.pressure_flow_factor(big, gamma), 1.0, atol=1e-3)     # smooth limit
    assert np.all(np.asarray(rg.shear_flow_factor(big, gamma)) < 1e-4)
    H = np.linspace(rg.PRESSURE_FLOW[gamma][2], 6.0, 23)     # from the fit's lower end
    phi = np.asarray(rg.pressure_flow_factor(H, gamma))
    # ridges across the flow (gamma < 1) obstruct it, along the flow (gamma > 1) open channels
    assert np.all(phi < 1) if gamma < 1 else np.all(phi > 1) if gamma > 1 else np.all(phi < 1)
    # the table rows against the smooth fits in gamma of a later code (their constants within 5 %)
    C, r, _ = rg.PRESSURE_FLOW[gamma]
    if gamma <= 1:
        assert np.isclose(C, 0.89679 - 0.26591 * math.log(gamma), rtol=0.05)
        assert np.isclose(r, 0.43006 - 0.10828 * gamma + 0.23821 * gamma ** 2, rtol=0.05)
    else:
        assert np.isclose(C, 0.1075 * gamma - 0.10667, rtol=0.05) and r == 1.5
    phi_ref = 1 - C * np.exp(-r * H) if gamma <= 1 else 1 + C * H ** -r      # the published forms
    assert np.allclose(phi, phi_ref, rtol=1e-14)
    # Phi_s: the two published branches of each row meet at H = 5 (a mistyped constant would not)
    A1, a1, a2, a3, A2 = rg.SHEAR_FLOW[gamma]
    assert np.isclose(A1 * 5 ** a1 * math.exp(-5 * a2 + 25 * a3), A2 * math.exp(-1.25), rtol=2e-3)
    assert abs(float(rg.shear_flow_factor(5.0 + 1e-9, gamma)) / float(rg.shear_flow_factor(5.0, gamma)) - 1) < 2e-3


def test_flow_factor_table_refuses_other_gamma():
    with pytest.raises(ValueError, match="gamma must be one of"):
        rg.pressure_flow_factor(1.0, 2.0)
    with pytest.raises(ValueError, match="gamma must be one of"):
        rg.shear_stress_factors(1.0, 3.0)


def test_friction_factor_against_its_definition():
    c = 35 / 32

    def definition(H):     # mean of z/(z + x) over (35/32)(1 - x^2)^3; polynomial part over x > -z,
        z = H / 3           # the 1/(z + x) part cut at z + x = 1/300 where z < 1
        poly = lambda x: ((1 - x * x) ** 3 - (1 - z * z) ** 3) / (z + x)      # noqa: E731
        if z <= 1:
            return c * z * (integrate.quad(poly, -z, 1, epsabs=0, epsrel=1e-13)[0]
                            + (1 - z * z) ** 3 * math.log((1 + z) * 300))
        return integrate.quad(lambda x: c * (1 - x * x) ** 3 * z / (z + x), -1, 1, epsabs=0, epsrel=1e-13)[0]

    for H in (0.3, 1.0, 2.0, 2.9, 3.0, 3.3, 5.0, 5.99, 6.0, 6.01, 9.0, 30.0):
        assert np.isclose(rg.friction_factor(H), definition(H), rtol=1e-11), H
    # the cut-off applied to the whole integrand instead changes phi_f by O(1/300)
    for H in (0.5, 1.5, 2.5):
        z = H / 3
        cut = integrate.quad(lambda x: c * (1 - x * x) ** 3 * z / (z + x), -z + 1 / 300, 1)[0]
        assert abs(float(rg.friction_factor(H)) / cut - 1) < 5e-3
    # smooth limit: 1 + E[x^2]/z^2 + ... = 1 + 1/H^2 + ...
    assert np.isclose(rg.friction_factor(300.0), 1 + 1 / 300.0 ** 2, rtol=1e-9)
    g = jax.vmap(jax.grad(rg.friction_factor))(jnp.linspace(0.5, 20.0, 40))
    assert np.all(np.isfinite(g))


def test_shear_stress_factors_isotropic():
    H = np.linspace(0.5, 12.0, 47)
    fs, fp = (np.asarray(a) for a in rg.shear_stress_factors(H))
    # Patir and Cheng 1979, gamma = 1: phi_fp = 1 - 1.40 e^{-0.66 H}; Phi_fs = 11.1 H^2.31
    # e^{-2.38 H + 0.11 H^2} for 0.5 < H < 7, 0 beyond
    assert np.allclose(fp, 1 - 1.40 * np.exp(-0.66 * H), rtol=1e-14)
    assert np.allclose(fs, np.where(H < 7, 11.1 * H ** 2.31 * np.exp(-2.38 * H + 0.11 * H ** 2), 0.0), rtol=1e-14)
    assert np.all(fs[H >= 7] == 0) and np.isclose(rg.shear_stress_factors(40.0)[1], 1.0, atol=1e-11)


# ---- Roughness -----------------------------------------------------------------------------
def reference_case(sigma=1e-6, **kw):
    """The issue-43 reference case: rough polymer bush (3 GPa, 0.4), smooth steel journal."""
    return Roughness.from_surfaces(0.0, sigma, 210e9, 0.3, 3e9, 0.4, eta_beta_sigma=0.05,
                                   sigma_over_beta=0.005, **kw)


def test_asperity_pressure_against_direct_quadrature():
    rough = reference_case()
    E = 1 / ((1 - 0.3 ** 2) / 210e9 + (1 - 0.4 ** 2) / 3e9)
    assert np.isclose(rough.E, E, rtol=1e-14) and float(rough.Vr) == -1.0
    K = 16 * math.sqrt(2) * math.pi / 15 * 0.05 ** 2 * math.sqrt(0.005)
    for h in (-2e-6, -0.3e-6, 0.0, 0.5e-6, 1.2e-6, 3e-6, 5e-6):
        H = h / 1e-6
        F = integrate.quad(lambda s: (s - H) ** 2.5 * np.exp(-s * s / 2) / SQRT2PI, H, np.inf,
                           epsabs=0, epsrel=1e-13)[0]
        assert np.isclose(rough.asperity_pressure(h), K * E * F, rtol=1e-10)
        assert np.isclose(rough.boundary_shear(h), 0.1 * K * E * F, rtol=1e-10)
    # the same surfaces from the asperities' density and radius
    beta = 1e-6 / 0.005
    other = Roughness.from_asperities(1e-6, 0.05 / (beta * 1e-6), beta, E)
    assert np.isclose(other.asperity_pressure(0.7e-6), rough.asperity_pressure(0.7e-6), rtol=1e-12)


def test_roughness_film_terms_and_clip():
    rough = reference_case()
    s = 1e-6
    for h in (0.2e-6, 0.5e-6, 2e-6):
        Hc = max(h / s, 0.5)
        hc = s * Hc
        assert np.isclose(rough.poiseuille(h), (1 - 0.9 * math.exp(-0.56 * Hc)) * hc ** 3, rtol=1e-13)
        hT = s * (h / s * special.ndtr(h / s) + math.exp(-0.5 * (h / s) ** 2) / SQRT2PI)
        assert np.isclose(rough.couette_gap(h), hT - s * float(rg.shear_flow_factor(Hc)), rtol=1e-13)
    nominal = reference_case(couette="nominal")
    assert np.isclose(nominal.couette_gap(2e-6), 2e-6 - s * float(rg.shear_flow_factor(2.0)), rtol=1e-13)
    # a clip at 1.0 evaluates the factors at H = 1 below it
    assert np.isclose(reference_case(clip=1.0).poiseuille(0.3e-6), (1 - 0.9 * math.exp(-0.56)) * 1e-18, rtol=1e-13)


def test_cross_flow_factor():
    """phi_z is phi_x of the transposed pattern (gamma -> 1/gamma)."""
    h = 1.7e-6
    along = Roughness(1e-6, 3e9, gamma=3.0)
    Hc = 1.7
    assert np.isclose(along.poiseuille(h), (1 + 0.225 * Hc ** -1.5) * h ** 3, rtol=1e-13)
    assert np.isclose(along.poiseuille_across(h), (1 - 1.18 * math.exp(-0.42 * Hc)) * h ** 3, rtol=1e-13)
    iso = Roughness(1e-6, 3e9)
    assert np.isclose(iso.poiseuille_across(h), iso.poiseuille(h), rtol=1e-15)


def test_smooth_limit():
    """sigma -> 0: every film term becomes the smooth film's."""
    rough = reference_case(sigma=1e-12)
    h, eta, U, dpdx = 20e-6, 0.03, 1.25, -3e7
    assert np.isclose(rough.poiseuille(h), h ** 3, rtol=1e-12)
    assert np.isclose(rough.couette_gap(h), h, rtol=1e-12)
    assert np.isclose(rough.journal_shear(h, eta, U, dpdx), eta * U / h + h / 2 * dpdx, rtol=1e-8)
    assert float(rough.asperity_pressure(h)) == 0.0


def test_journal_shear_convention():
    rough = reference_case()
    h, eta, U, dpdx = 1.5e-6, 0.03, 1.25, 2e9
    H = 1.5
    fs, fp = (float(a) for a in rg.shear_stress_factors(H))
    expected = eta * U / h * (float(rg.friction_factor(H)) + fs) + fp * h / 2 * dpdx     # Vr = -1
    assert np.isclose(rough.journal_shear(h, eta, U, dpdx), expected, rtol=1e-13)


def test_roughness_is_a_pytree():
    rough = reference_case()
    leaves = jax.tree_util.tree_leaves(rough)
    assert len(leaves) == 6                         # gamma, clip, couette are static
    f = jax.jit(lambda r, h: r.asperity_pressure(h) + r.boundary_shear(h))
    assert np.isclose(f(rough, 0.8e-6), 1.1 * rough.asperity_pressure(0.8e-6), rtol=1e-13)
    # derivative with respect to sigma against central differences (the mixed regime)
    p = lambda s: reference_case(sigma=s).asperity_pressure(0.8e-6) + reference_case(sigma=s).journal_shear(  # noqa: E731
        0.8e-6, 0.03, 1.0, 1e9)
    g = jax.grad(p)(1e-6)
    d = 1e-12
    assert np.isclose(g, (p(1e-6 + d) - p(1e-6 - d)) / (2 * d), rtol=1e-6)
    sig = jnp.array([0.5e-6, 1e-6])
    assert jax.vmap(lambda s: reference_case(sigma=s).poiseuille(0.8e-6))(sig).shape == (2,)


@pytest.mark.parametrize("kw, message", [
    (dict(sigma=0.0, E=1e9), "sigma must be > 0"),
    (dict(sigma=1e-6, E=-1.0), "E must be > 0"),
    (dict(sigma=1e-6, E=1e9, Vr=1.5), r"Vr .* must lie in \[-1, 1\]"),
    (dict(sigma=1e-6, E=1e9, mu_b=-0.1), "mu_b must be >= 0"),
    (dict(sigma=1e-6, E=1e9, gamma=2.0), "gamma must be one of"),
    (dict(sigma=1e-6, E=1e9, clip=0.0), "clip must be a finite number > 0"),
    (dict(sigma=1e-6, E=1e9, couette="mean"), "couette must be one of"),
    (dict(sigma=1e-6, E=1e9, eta_beta_sigma=float("nan")), "eta_beta_sigma must be finite"),
])
def test_roughness_refuses_bad_input(kw, message):
    with pytest.raises(ValueError, match=message):
        Roughness(**kw)


def test_from_surfaces_checks():
    with pytest.raises(ValueError, match="both 0"):
        Roughness.from_surfaces(0.0, 0.0, 210e9, 0.3, 3e9, 0.4)
    with pytest.raises(ValueError, match="nu2"):
        Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.7)
    both = Roughness.from_surfaces(1e-6, 1e-6, 210e9, 0.3, 210e9, 0.3)
    assert np.isclose(both.sigma, math.sqrt(2) * 1e-6) and float(both.Vr) == 0.0
    assert np.isclose(both.E, 210e9 / (2 * (1 - 0.09)), rtol=1e-14)


def test_float32_runs_without_nan():
    jax.config.update("jax_enable_x64", False)
    try:
        H = jnp.linspace(-40.0, 40.0, 321, dtype=jnp.float32)
        fns = [rg.asperity_integral, rg.expected_gap, rg.pressure_flow_factor, rg.shear_flow_factor,
               rg.friction_factor, lambda x: rg.shear_stress_factors(x)[0]]
        for fn in fns:
            v = fn(H)
            assert v.dtype == jnp.float32 and bool(jnp.all(jnp.isfinite(v)))
        for fn in fns[:2]:
            assert bool(jnp.all(jnp.isfinite(jax.vmap(jax.grad(fn))(H))))
        F = rg.asperity_integral(H)
        assert bool(jnp.all(jnp.diff(F) <= 0))
        ref = np.array([F_quad(2.5, float(h)) for h in H[(H >= -10) & (H <= 6)]])
        assert np.max(np.abs(np.asarray(F[(H >= -10) & (H <= 6)]) / ref - 1)) < 1e-4
        rough = Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
        h = jnp.linspace(-3e-6, 10e-6, 53, dtype=jnp.float32)
        for v in (rough.asperity_pressure(h), rough.poiseuille(h), rough.couette_gap(h),
                  rough.journal_shear(h, 0.03, 1.0, 1e8)):
            assert bool(jnp.all(jnp.isfinite(v)))
    finally:
        jax.config.update("jax_enable_x64", True)
