"""The bonded cylindrical layer in 3D (vjax.layer3d): Bessel helpers against scipy, the modal
compliance against the plane-strain layer (k -> 0), the flat bonded layer and the oedometric
limit (t/R -> 0), the half-space (large k t), and one mode against 3D finite elements; the hole
in an infinite body (kind "hole") against the plane hole (k -> 0, mode 1's log), the half-space
and a very thick liner.

Every call of ``modes`` below has the same shapes (8 orders x 4 wavenumbers, orders below 2048),
so the module compiles the layer's program once (liner and sleeve share it; ``hole`` likewise)."""
import time

import jax
import jax.numpy as jnp
import numpy as np
import pytest
import scipy.special as sp

from vjax import green, layer3d

N_ORDERS, N_WAVES = 8, 4


def modes(kind, n, kR, nu, tau):
    """c (len(n), len(kR)) through one compiled shape: pads n and kR by repeating their last entry."""
    n, kR = np.atleast_1d(n), np.atleast_1d(np.asarray(kR, dtype=float))
    assert len(n) <= N_ORDERS and len(kR) <= N_WAVES
    pn = np.concatenate([n, np.full(N_ORDERS - len(n), n[-1])])
    pk = np.concatenate([kR, np.full(N_WAVES - len(kR), kR[-1])])
    c = layer3d.layer_modes(kind, pn, pk, nu, tau, n_max=2048)
    return np.asarray(c)[: len(n), : len(kR)]


def flat_layer(K, t, nu):
    """Normal displacement (E = 1) of a flat elastic layer of thickness t bonded to a rigid base
    under the surface pressure cos(K x) (no shear): the plane-strain Fourier solution of the layer
    (four constants, Airy / Papkovich), kappa = 3 - 4 nu, s = K t:

        u = 2 (1 - nu^2) / K * (kappa sinh 2s - 2s) / (kappa cosh 2s + 2 s^2 + (1 + kappa^2) / 2),

    -> the half-space 2 (1 - nu^2) / K as s -> oo, -> the oedometric t (1+nu)(1-2nu)/(1-nu) as
    s -> 0. A load cos(k_x x) cos(k_z z) is two such plane waves of |K| = sqrt(k_x^2 + k_z^2)."""
    s, kap = K * t, 3 - 4 * nu
    return 2 * (1 - nu**2) / K * (kap * np.sinh(2 * s) - 2 * s) / (kap * np.cosh(2 * s) + 2 * s * s + (1 + kap**2) / 2)


# ------------------------------------------------------------------------------ Bessel helpers
def test_bessel_helpers_match_scipy():
    """K_0 e^x, K_1 e^x; log I_m, I_(m+1)/I_m; log K_m, K_(m-1)/K_m for x in [1e-9, 1e4] and
    orders 0..600 (wherever scipy's ive, kve are finite and nonzero): ratios to 2e-12, logs to 4e-12
    absolute (log K_m + x loses eps x to the cancellation at x = 1e4)."""
    x = np.geomspace(1e-9, 1e4, 120)
    k0, k1 = layer3d.k01e(jnp.asarray(x))
    np.testing.assert_allclose(k0, sp.kve(0, x), rtol=1e-13)
    np.testing.assert_allclose(k1, sp.kve(1, x), rtol=1e-13)
    logI, rI = jax.jit(layer3d.i_table, static_argnums=1)(jnp.asarray(x), 600)
    logK, qK = jax.jit(layer3d.k_table, static_argnums=1)(jnp.asarray(x), 600)
    m = np.arange(601)[:, None]
    with np.errstate(all="ignore"):
        ive, kve = sp.ive(m, x), sp.kve(m, x)
        ok_i = (ive > 1e-300) & np.isfinite(ive)
        ok_k = (kve < 1e300) & np.isfinite(kve)
        np.testing.assert_allclose(np.asarray(logI - x)[ok_i], np.log(ive[ok_i]), rtol=1e-13, atol=4e-12)
        np.testing.assert_allclose(np.asarray(logK + x)[ok_k], np.log(kve[ok_k]), rtol=1e-13, atol=4e-12)
        ratio_i = sp.ive(m + 1, x) / ive
        ratio_k = sp.kve(np.abs(m - 1), x) / kve
    ok = ok_i & (sp.ive(m + 1, x) > 1e-300)
    np.testing.assert_allclose(np.asarray(rI)[ok], ratio_i[ok], rtol=2e-12)
    ok = ok_k & np.isfinite(ratio_k)
    np.testing.assert_allclose(np.asarray(qK)[ok], ratio_k[ok], rtol=2e-12)
    assert ok_i.sum() > 15000 and ok_k.sum() > 15000        # the comparison covers the table


# ------------------------------------------------------------------------------ k -> 0: plane strain
@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_long_wave_limit_is_the_plane_strain_layer(kind):
    """c(n, k R -> 0) -> the 2D plane-strain layer (Michell, vjax.green.mode_compliance): at
    k R = 1e-6 within 1e-8 (relative) for n = 0, 1, 2, 3, 7, 30, t/R = 0.02, 0.3, 0.8 and
    nu = 0.1, 0.3, 0.45, 0.499; the deviation at k R = 0.01, 0.02 is O(k^2) (ratio 4), so the
    3D solution itself tends to the limit (k = 0 exactly is the plane-strain value, by
    construction); measured within 2.5e-3 of 4."""
    n = np.array([0, 1, 2, 3, 7, 30])
    for tau in (0.02, 0.3, 0.8):
        for nu in (0.1, 0.3, 0.45, 0.499):
            c2 = np.asarray(green.mode_compliance(kind, n, nu, thickness_ratio=tau))
            c3 = modes(kind, n, [1e-6, 1e-2, 2e-2, 0.0], nu, tau)
            assert np.max(np.abs(c3[:, 0] / c2 - 1)) < 1e-8, (tau, nu)
            d1, d2 = c3[:, 1] - c2, c3[:, 2] - c2
            big = np.abs(d2) > 1e-9 * np.abs(c2)                   # resolved deviations
            np.testing.assert_allclose(d2[big] / d1[big], 4.0, rtol=5e-3)
            np.testing.assert_allclose(c3[:, 3], c2, rtol=1e-9)


def test_incompressible_long_wave_limit():
    """nu = 0.5 exactly (the tractions use lambda div u = 4 mu nu div B, finite): n >= 1 tends to
    the plane-strain layer (1e-8 at k R = 1e-6); n = 0, whose plane-strain compliance is zero
    (no change of area against the bond), has an O(k^2) compliance (axial flow)."""
    n = np.array([0, 1, 2, 3, 7, 30])
    for kind in ("liner", "sleeve"):
        for tau in (0.05, 0.5):
            c2 = np.asarray(green.mode_compliance(kind, n, 0.5, thickness_ratio=tau))
            c3 = modes(kind, n, [1e-6, 1e-2, 2e-2], 0.5, tau)
            np.testing.assert_allclose(c3[1:, 0], c2[1:], rtol=1e-8)
            assert abs(c3[0, 0]) < 1e-10 * tau and c3[0, 1] > 0
            assert c3[0, 2] / c3[0, 1] == pytest.approx(4.0, rel=1e-3)


# ------------------------------------------------------------------------------ thin layers
@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_thin_layer_is_the_flat_bonded_layer(kind):
    """t/R -> 0 with K t = O(1), K = sqrt((n/R)^2 + k^2): the flat bonded layer's closed form
    (two plane-wave directions, the same |K|). The curvature's correction is O(t/R): within
    0.5 t/R at t/R = 1e-2 and 1e-3 (measured up to 0.4 t/R), the sign opposite for liner and sleeve."""
    for tau in (1e-2, 1e-3):
        n = np.array([0, 3, int(0.5 / tau), int(2 / tau)])
        kR = np.array([0.3, 1.0, 2.0]) / tau
        for nu in (0.3, 0.45):
            c = modes(kind, n, kR, nu, tau)
            K = np.hypot(n[:, None], kR[None, :])
            assert np.max(np.abs(c / flat_layer(K, tau, nu) - 1)) < 0.5 * tau, (tau, nu)


@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_thin_layer_long_wave_is_oedometric(kind):
    """Wavelength >> t (K t ~ 1e-3) and t/R -> 0: the oedometric Winkler layer
    u = t (1+nu)(1-2nu) / ((1-nu) E), within 0.5 t/R at t/R = 1e-2 and 1e-3."""
    for tau in (1e-2, 1e-3):
        for nu in (0.1, 0.3, 0.45):
            c = modes(kind, np.array([0, 1, 2]), [0.1, 0.5, 1.0], nu, tau)
            oed = tau * (1 + nu) * (1 - 2 * nu) / (1 - nu)
            assert np.max(np.abs(c / oed - 1)) < 0.5 * tau, (tau, nu)


# ------------------------------------------------------------------------------ half-space
@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_short_wave_is_the_half_space(kind):
    """K t >> 1 and K R >> 1: the elastic half-space's 2 (1 - nu^2) / (E K) (c = that over R),
    with a curvature correction O(1/(K R)): |c / c_hs - 1| < 0.5 / (K R) for K R = 400 and 1600
    (t/R = 0.4, nu = 0.3; measured up to 0.42 / (K R)), and the correction converges (K R times
    it changes by less than 3% from 400 to 1600)."""
    nu, tau = 0.3, 0.4
    dev = []
    for KR in (400, 1600):
        n = np.array([0, KR // 2, KR])
        kR = np.array([0.6, 1.0]) * KR
        c = modes(kind, n, kR, nu, tau)
        K = np.hypot(n[:, None], kR[None, :])
        d = (c * K / (2 * (1 - nu**2)) - 1) * K
        assert np.max(np.abs(d)) < 0.5
        dev.append(d)
    np.testing.assert_allclose(dev[0], dev[1], atol=0.03 * np.max(np.abs(dev[1])))


# ------------------------------------------------------------------------------ float32
def test_float32_runs_without_nan():
    """float32 in: float32 out, finite everywhere (k = 0 to 1000, n to 300, nu = 0.5, t/R = 1e-3,
    the worst conditioned corner) and within 1e-4 of float64 for a moderate sleeve."""
    n = np.array([0, 1, 2, 3, 50, 300, 301, 302])
    c32 = layer3d.layer_modes("liner", n, np.array([0.0, 1e-2, 30.0, 1000.0], np.float32), np.float32(0.5),
                              np.float32(1e-3), n_max=2048)
    assert c32.dtype == jnp.float32 and bool(jnp.all(jnp.isfinite(c32)))
    k = np.array([0.0, 2.0, 20.0, 100.0])
    c32 = layer3d.layer_modes("sleeve", n // 3, k.astype(np.float32), np.float32(0.45), np.float32(0.1), n_max=2048)
    np.testing.assert_allclose(c32, modes("sleeve", n // 3, k, 0.45, 0.1), rtol=1e-4)


# ------------------------------------------------------------------------------ finite elements
@pytest.mark.slow
@pytest.mark.parametrize("kind, mesh", [("liner", (4, 8, 8)), ("sleeve", (3, 6, 6))])
def test_one_mode_matches_3d_finite_elements(kind, mesh):
    """n = 2, k R = 4, nu = 0.45, t/R = 0.25 (c 42% / 26% above the plane-strain layer's): a
    quarter-ring sector (symmetry planes theta = 0, pi/2) half a wavelength long (u_z = 0 on
    both ends), triquadratic hexahedra with curved geometry (scikit-fem,
    experiments/studies/layer3d_fem.py), r x theta x z elements as given: the surface displacement
    within 0.5% of the peak at every node of the loaded surface (measured 0.30% liner, 0.23%
    sleeve; the experiment refines further)."""
    pytest.importorskip("skfem")
    from experiments.studies.layer3d_fem import CASE, fem_mode
    t0 = time.perf_counter()
    theta, z, u, _ = fem_mode(kind, CASE["n"], CASE["kR"], CASE["nu"], CASE["tau"], *mesh)
    seconds = time.perf_counter() - t0
    c = modes(kind, np.array([CASE["n"]]), [CASE["kR"]], CASE["nu"], CASE["tau"])[0, 0]
    err = np.max(np.abs(u - c * np.cos(CASE["n"] * theta) * np.cos(CASE["kR"] * z))) / abs(c)
    assert err < 5e-3, err
    c2 = float(green.mode_compliance(kind, np.array([CASE["n"]]), CASE["nu"], thickness_ratio=CASE["tau"])[0])
    assert abs(c / c2 - 1) > 0.2                   # the check sees the axial coupling
    print(f"{kind} {mesh}: FE {seconds:.1f} s, error / peak {err:.2e}")


# ------------------------------------------------------------------------------ the hole (kind "hole")
def hole(n, kR, nu, ref=None):
    """c (len(n), len(kR)) of the 3D hole, one compiled shape as :func:`modes`."""
    n, kR = np.atleast_1d(n), np.atleast_1d(np.asarray(kR, dtype=float))
    pn = np.concatenate([n, np.full(N_ORDERS - len(n), n[-1])])
    pk = np.concatenate([kR, np.full(N_WAVES - len(kR), kR[-1])])
    c = layer3d.layer_modes("hole", pn, pk, nu, n_max=2048, ref_length_ratio=ref)
    return np.asarray(c)[: len(n), : len(kR)]


def test_hole_long_wave_limit_is_the_plane_hole():
    """c(n, k R -> 0) -> the plane hole (A.45, vjax.green.mode_compliance) for n = 0, 2, 3, 5, 10,
    nu = 0.1, 0.3, 0.45, 0.5: within 1e-8 (relative) at k R = 1e-6 and 1e-5, 1e-7 at 1e-4; the
    deviation is O((kR)^2) (n = 2: O((kR)^2 log kR), the K_1 family: a fall of 100 log(1e-4) / log(1e-5)
    ~ 80), so from 1e-4 to 1e-5 it falls by at least 60 (measured: at most 1.4e-11 at 1e-6, 1.2e-9 at
    1e-5, 9.5e-8 at 1e-4, all at n = 2, nu = 0.1; falls 80.8 to 99.3). k = 0 exactly is the plane
    hole with the given reference length (mode 1 included)."""
    n = np.array([0, 2, 3, 5, 10])
    for nu in (0.1, 0.3, 0.45, 0.5):
        c2 = np.asarray(green.mode_compliance("hole", n, nu))
        dev = np.abs(hole(n, [1e-6, 1e-5, 1e-4], nu) / c2[:, None] - 1)
        assert np.max(dev[:, :2]) < 1e-8 and np.max(dev[:, 2]) < 1e-7, (nu, dev)
        assert np.all(dev[:, 2] > 60 * dev[:, 1]), (nu, dev)
    c0 = hole(np.array([0, 1, 2, 7]), [0.0], 0.3, ref=20.0)[:, 0]
    np.testing.assert_allclose(c0, green.mode_compliance("hole", np.array([0, 1, 2, 7]), 0.3, ref_length_ratio=20.0),
                               rtol=1e-14)


def test_hole_mode_1_grows_like_the_plane_translation_log():
    """Mode 1 (a rigid translation in plane strain) has no k -> 0 limit: the plane hole's mode-1
    compliance is w_cos * pi with w_cos = -(1+nu)/(2 pi) kappa/(kappa+1) (2 log(R/ref) + 1)
    (vjax.green._coefficients "hole", the cos weight, whose mode-1 integral is pi), i.e.
    -(1+nu) kappa/(kappa+1) per unit log R; in 3D the reference length becomes ~ 1/k, so
    c(1, kR) - c(1, kR/10) -> -(1+nu) kappa/(kappa+1) log 10. The log coefficient is first checked on
    green itself (c_1 at R/ref = e against 1); then the 3D difference converges to it, the
    error falling as (kR)^2 (within 1e-6 at kR = 1e-4, 1e-8 at 1e-6; measured up to 2.6e-7, 5.5e-11,
    nu = 0)."""
    for nu in (0.0, 0.3, 0.5):
        kap = 3 - 4 * nu
        slope = -(1 + nu) * kap / (kap + 1)
        w = green._coefficients("hole", np.e, nu, 1.0)[0] - green._coefficients("hole", 1.0, nu, 1.0)[0]
        assert float(w) * np.pi == pytest.approx(slope, rel=1e-14)
        plane = green.mode_compliance("hole", [1], nu, ref_length_ratio=np.exp(-1.0)) - \
            green.mode_compliance("hole", [1], nu, ref_length_ratio=1.0)
        assert float(plane[0]) == pytest.approx(slope, rel=1e-14)
        errs = []
        for kR in (1e-2, 1e-4, 1e-6):
            c = hole(np.array([1]), [kR, kR / 10], nu)[0]
            errs.append(abs(c[0] - c[1] - slope * np.log(10)))
        assert errs[1] < 1e-6 and errs[2] < 1e-8 and errs[0] > errs[1] > errs[2], (nu, errs)


def test_hole_short_wave_is_the_half_space():
    """K R >> 1 (K = sqrt(k^2 + (n/R)^2)): the half-space 2 (1 - nu^2) / (E K), the relative error
    O(1/(K R)) from the curvature: within 0.5 / (K R) at K R = 400 and 1600 (nu = 0.3; measured up to
    0.404 / (K R), 0.401 / (K R)) and the largest error falls by more than 3.5 from 400 to 1600
    (measured 1.68e-3 to 4.18e-4: 4.03)."""
    nu, err = 0.3, []
    for KR in (400, 1600):
        n = np.array([0, KR // 2, KR])
        kR = np.array([0.6, 1.0]) * KR
        K = np.hypot(n[:, None], kR[None, :])
        rel = np.abs(hole(n, kR, nu) * K / (2 * (1 - nu**2)) - 1)
        assert np.max(rel * K) < 0.5, (KR, rel * K)
        err.append(np.max(rel))
    assert err[0] / err[1] > 3.5, err


def test_very_thick_liner_is_the_hole():
    """A liner t/R = 20, 50 thick tends to the hole (k R = 0.5, 2; n = 0, 1, 2, 3, 7, 30): the bond's
    reflection decays like exp(-2 k t) (with a polynomial factor): within (2 k t)^2 exp(-2 k t) + 1e-13
    (measured 1.1e-7 (nu = 0.3), 2.8e-7 (nu = 0.5) at k t = 10, against 8.2e-7; round-off, 4e-15,
    elsewhere)."""
    n = np.array([0, 1, 2, 3, 7, 30])
    kR = np.array([0.5, 2.0])
    for nu in (0.3, 0.5):
        c = hole(n, kR, nu)
        for tau in (20.0, 50.0):
            dev = np.abs(modes("liner", n, kR, nu, tau) / c - 1)
            bound = (2 * kR * tau) ** 2 * np.exp(-2 * kR * tau) + 1e-13
            assert np.all(dev < bound[None, :]), (nu, tau, dev)


def test_hole_incompressible_and_gradients():
    """nu = 0.5 is finite (n = 0 to 30, k R = 1e-3 to 50) and positive; d c / d(kR) and d c / d nu
    (jax) against central differences within 1e-6 (measured 1.2e-8) at k R = 0.3, 3, 30."""
    n = np.array([0, 1, 2, 3, 7, 30])
    c = hole(n, [1e-3, 0.5, 2.0, 50.0], 0.5)
    assert np.all(np.isfinite(c)) and np.all(c > 0)
    n = np.array([0, 1, 2, 5])
    f = jax.jit(lambda kR, nu: layer3d.layer_modes("hole", n, kR, nu, n_max=16))
    for x in (0.3, 3.0, 30.0):
        g = jax.jacfwd(lambda y: f(y[None], 0.3)[:, 0])(jnp.asarray(x))
        h = 1e-5 * x
        fd = (f(jnp.asarray([x + h]), 0.3) - f(jnp.asarray([x - h]), 0.3))[:, 0] / (2 * h)
        np.testing.assert_allclose(g, fd, rtol=1e-6)
        gn = jax.jacfwd(lambda v: f(jnp.asarray([x]), v)[:, 0])(0.3)
        fdn = (f(jnp.asarray([x]), 0.3 + 1e-6) - f(jnp.asarray([x]), 0.3 - 1e-6))[:, 0] / 2e-6
        np.testing.assert_allclose(gn, fdn, rtol=1e-6)
    with pytest.raises(ValueError, match="thickness_ratio"):
        layer3d.layer_modes("liner", n, [1.0], 0.3)
