"""Tests of the independent mixed-lubrication peer (tests/mixed_peer.py) itself: its roughness
functions against quadrature and the published closed forms, its friction against the exact
concentric film, its smooth limit, and its boundary limit (the wrap factor)."""
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import mixed_peer as mp

GAUSS = 1 / np.sqrt(2 * np.pi)


def F52_quad(H):
    return quad(lambda s: (s - H) ** 2.5 * np.exp(-s * s / 2), H, np.inf, epsabs=0, epsrel=1e-13, limit=200)[0] * GAUSS


@pytest.mark.parametrize("H", [0.0, 0.3, 1.0, 2.0, 3.5, 5.0, 6.0, -0.5, -2.0, -7.9, -8.1, -25.0, 9.0])
def test_F52_against_quadrature(H):
    """Relative error within 1e-8 (the issue's bound on [0, 6]) everywhere tested."""
    assert abs(float(mp.F52(H)) / F52_quad(H) - 1) < 1e-8


def test_F52_limits():
    """F_{5/2}(0) = 2^{3/4} Gamma(7/4)/sqrt(2 pi) (the moment of a half Gaussian); 0 far above;
    (-H)^{5/2} (1 + 15/(8 H^2) + ...) far below."""
    from scipy.special import gamma
    assert float(mp.F52(0.0)) == pytest.approx(2**0.75 * gamma(1.75) * GAUSS, rel=1e-13)
    assert float(mp.F52(50.0)) == 0.0
    H = -200.0
    assert float(mp.F52(H)) == pytest.approx((-H) ** 2.5 * (1 + 15 / 8 / H**2), rel=1e-8)


@pytest.mark.parametrize("H", [-3.0, -0.5, 0.0, 0.7, 2.0, 5.0])
def test_expected_gap_is_the_mean_positive_gap(H):
    """h_T/sigma = E[max(H + s, 0)] over s ~ N(0, 1)."""
    ref = quad(lambda s: (H + s) * np.exp(-s * s / 2), -H, np.inf, epsabs=0, epsrel=1e-13)[0] * GAUSS
    assert float(mp.expected_gap(H)) == pytest.approx(ref, rel=1e-12)


def test_flow_factor_fits():
    """Patir-Cheng 1978 (gamma = 1): phi_x -> 1 and Phi_s -> 0 for smooth films, the two branches of
    Phi_s meet at H = 5 within 0.1 %, and the fits' values at H = 1 and 3."""
    assert float(mp.phi_x(60.0)) == pytest.approx(1.0, abs=1e-12)
    assert float(mp.phi_x(1.0)) == pytest.approx(1 - 0.90 * np.exp(-0.56), rel=1e-15)
    below, above = 1.899 * 5**0.98 * np.exp(-0.92 * 5 + 0.05 * 25), 1.126 * np.exp(-1.25)
    assert abs(below / above - 1) < 1e-3
    assert float(mp.Phi_s(5.0)) == pytest.approx(below, rel=1e-15)
    assert float(mp.Phi_s(3.0)) == pytest.approx(1.899 * 3**0.98 * np.exp(-2.76 + 0.45), rel=1e-14)
    assert float(mp.Phi_s(200.0)) < 1e-20
    assert float(mp.Phi_fs(7.0)) == 0.0 and float(mp.Phi_fs(6.99)) == pytest.approx(0.0128, abs=2e-4)
    assert float(mp.phi_fp(0.5)) == pytest.approx(1 - 1.40 * np.exp(-0.33), rel=1e-15)


def phi_f_closed(H):
    """Patir and Cheng's (1979) published closed form of phi_f (z = H/3), written out here."""
    z = H / 3
    if z <= 1:
        poly = -55 + z * (132 + z * (345 + z * (-160 + z * (-405 + z * (60 + 147 * z)))))
        return 35 / 32 * z * ((1 - z * z) ** 3 * np.log(300 * (z + 1)) + poly / 60)
    return 35 / 32 * z * ((1 - z * z) ** 3 * np.log((z + 1) / (z - 1)) + z / 15 * (66 + z * z * (30 * z * z - 80)))


def phi_f_quad(H):
    """phi_f as the integral it is: (35/32) z [(1 - z^2)^3 int dx/(z + x) + int q dx] over the gaps
    x > -z, the log part cut at z + x = 1/300 where surfaces touch (z <= 1), by adaptive quadrature
    (for z > 1.5 the mean of z/(z + x) itself: the split form cancels ~z^6-fold)."""
    z = H / 3
    if z > 1.5:                    # no contact: the mean of z/(z + x) directly (the split cancels)
        return quad(lambda x: 35 / 32 * (1 - x * x) ** 3 * z / (z + x), -1, 1, epsabs=0, epsrel=1e-13)[0]
    a = max(-z, -1.0)
    q = quad(lambda x: ((1 - x * x) ** 3 - (1 - z * z) ** 3) / (z + x), a, 1, epsabs=0, epsrel=1e-13)[0]
    lo = -z + 1 / 300 if z <= 1 else -1.0
    log = quad(lambda x: 1 / (z + x), lo, 1, epsabs=0, epsrel=1e-13, limit=200)[0]
    return 35 / 32 * z * ((1 - z * z) ** 3 * log + q)


@pytest.mark.parametrize("H", [0.5, 1.0, 2.0, 2.999, 3.0, 3.2, 4.5, 6.0, 6.01, 9.0, 30.0])
def test_phi_f_against_its_integral_and_the_closed_form(H):
    assert float(mp.phi_f(H)) == pytest.approx(phi_f_quad(H), rel=1e-10)
    if H < 20:                     # the closed form cancels ~z^6-fold beyond
        assert float(mp.phi_f(H)) == pytest.approx(phi_f_closed(H), rel=1e-10)


def test_phi_f_limits():
    """35/30 at H = 3 (both sides), 1 + E[x^2]/z^2 = 1 + 1/(9 z^2) far out (the density's variance 1/9)."""
    assert float(mp.phi_f(3.0)) == pytest.approx(35 / 30, rel=1e-12)
    assert float(mp.phi_f(3.0 + 1e-9)) == pytest.approx(35 / 30, rel=1e-7)
    z = 1e3
    assert float(mp.phi_f(3 * z)) == pytest.approx(1 + 1 / (9 * z * z), rel=1e-13)


@pytest.mark.parametrize("sigma", [None, 1e-6])
def test_friction_of_the_concentric_film(sigma):
    """At e = 0 the film is uniform (h = c), the pressure 0, the shear eta U/h_c (phi_f - Vr Phi_fs)
    everywhere: the friction force is that times the land's area 2 pi R L (Petroff for smooth)."""
    b = mp.Bearing(1.0, sigma, n=16, m=8)
    out = b.outputs(np.zeros(2), 50.0)
    U, area = 50.0 * mp.R_J, 2 * np.pi * mp.R * b.L
    factor = 1.0 if sigma is None else float(mp.phi_f(mp.C / sigma) + mp.Phi_fs(mp.C / sigma))
    assert np.max(np.abs(out["pressure"])) == 0.0
    assert out["friction_viscous"] == pytest.approx(mp.ETA * U / mp.C * factor * area, rel=1e-13)
    sa = 0.0 if sigma is None else mp.K_GT * mp.E_PRIME * float(mp.F52(mp.C / sigma))
    assert out["friction_boundary"] == pytest.approx(mp.MU_B * sa * area, rel=1e-13, abs=1e-300)


def test_smooth_limit():
    """sigma -> 0 (1e-10 m: H ~ 1e5) reproduces the smooth-film peer (h^3, h, eta U/h + h/2 dp/dx)."""
    om = [100.0, 10.0]
    smooth = mp.stribeck(0.5, None, om)
    rough = mp.stribeck(0.5, 1e-10, om)
    for key in ("eccentricity", "attitude", "friction_coefficient", "h_min"):
        assert np.allclose(rough[key], smooth[key], rtol=1e-8, atol=0), key
    assert np.all(rough["asperity_share"] == 0.0)


def test_boundary_limit():
    """As omega -> 0 the asperities carry the load and the friction coefficient tends to
    mu_b times the wrap factor int p_a dA / |int p_a n dA| (a little above 1: the contact arc)."""
    r = mp.stribeck(1.0, 1e-6, [100.0, 10.0, 1.0, 0.1, 1e-2, 1e-3, 1e-4])
    assert r["asperity_share"][-1] > 0.999
    assert np.all(np.diff(r["asperity_share"][3:]) > 0)
    assert 1.0 < r["wrap"][-1] < 1.02
    assert r["friction_coefficient"][-1] == pytest.approx(mp.MU_B * r["wrap"][-1], rel=2e-3)
    # the asperity friction alone is mu_b times the wrap factor times the asperity share, exactly
    assert np.allclose(r["friction_boundary"] / mp.LOAD, mp.MU_B * r["wrap"] * r["asperity_share"], rtol=1e-12)


def test_bad_input():
    with pytest.raises(ValueError, match="L_over_D"):
        mp.Bearing(0.0, 1e-6)
    with pytest.raises(ValueError, match="sigma"):
        mp.Bearing(1.0, -1e-6)
    with pytest.raises(ValueError, match="omegas"):
        mp.stribeck(1.0, 1e-6, [1.0, -1.0])
