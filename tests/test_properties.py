"""Property-based tests (hypothesis) of the material laws and the ring operators.

Random generalized Maxwell solids (1-4 arms, moduli over 4 decades, relaxation times over up
to 24 decades) and random ring configurations. Few examples each and no deadline: the
shapes (number of arms, n) are drawn from small sets so that the jitted symbol and creep
spectrum compile only a handful of times. The whole file runs in well under a minute.
"""
import jax.numpy as jnp
import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from vjax import WLF, Arrhenius, Material, effective_compliance, ring_operator
from vjax.operator import spectral_derivative

FEW = settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow],
               derandomize=True)
OPS = settings(FEW, max_examples=6)   # each new (kind, memory, arms) configuration compiles a symbol


@st.composite
def materials(draw, terms=(1, 3), decades=24.0):
    """A Prony series with K arms (K from ``terms``: few shapes, few compilations), moduli
    over 4 decades and distinct relaxation times spread over up to ``decades`` decades."""
    k = draw(st.sampled_from(terms))
    E0 = 10.0 ** draw(st.floats(5.0, 9.0))
    ratios = np.array([10.0 ** draw(st.floats(-2.0, 2.0)) for _ in range(k)])
    gaps = np.array([draw(st.floats(0.3, decades / max(k - 1, 1))) for _ in range(k - 1)])
    start = draw(st.floats(-12.0, 12.0 - float(np.sum(gaps))))
    logt = start + np.concatenate([[0.0], np.cumsum(gaps)])
    nu = draw(st.sampled_from([0.0, 0.3, 0.45, 0.5]))
    return Material.prony(E0, ratios * E0, 10.0**logt, nu)


omegas = st.floats(-8.0, 8.0).map(lambda x: 10.0 ** x)


# ---------------------------------------------------------------------- material laws
@FEW
@given(materials(), omegas, st.floats(1.0001, 1e3))
def test_storage_increases_and_loss_is_nonnegative(m, w, factor):
    w2 = w * factor
    e1, e2 = float(m.storage(w)), float(m.storage(w2))
    assert e2 >= e1 * (1 - 1e-12)
    assert float(m.loss(w)) >= 0.0 and float(m.loss(w2)) >= 0.0
    assert float(m.loss(-w)) <= 0.0                         # E*(-w) = conj E*(w)
    assert float(m.E0) * (1 - 1e-12) <= e1 <= float(m.Einf) * (1 + 1e-12)


@FEW
@given(materials(), st.lists(st.floats(-10.0, 10.0), min_size=6, max_size=6))
def test_compliance_times_modulus_is_one(m, logw):
    w = 10.0 ** np.array(logw)
    prod = np.asarray(m.compliance(w) * m.modulus(w))
    np.testing.assert_allclose(prod, 1.0, rtol=1e-13, atol=1e-13)


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(materials(terms=(2, 4), decades=24.0))
def test_creep_spectrum_reproduces_the_compliance(m):
    spec = m.creep_spectrum()
    assert np.all(np.asarray(spec.C) > 0) and np.all(np.asarray(spec.retardation_times) > 0)
    # retardation times interlace the relaxation times (docs/theory.md §1)
    tau, lam = np.sort(np.asarray(m.times)), np.sort(np.asarray(spec.retardation_times))
    assert np.all(lam >= tau * (1 - 1e-12))
    w = np.concatenate([[0.0], 10.0 ** np.linspace(-14, 14, 57)])
    np.testing.assert_allclose(np.asarray(spec.compliance(w)), np.asarray(m.compliance(w)), rtol=1e-9)
    np.testing.assert_allclose(float(spec.J0), 1.0 / float(m.Einf), rtol=1e-14)


def test_creep_spectrum_of_a_60_term_series_over_24_decades():
    rng = np.random.default_rng(1)
    tau = 10.0 ** np.linspace(-12, 12, 60)
    m = Material.prony(1e6, 1e6 * 10.0 ** rng.uniform(-1, 1, 60), tau, 0.5)
    spec = m.creep_spectrum()
    w = 10.0 ** np.linspace(-16, 16, 129)
    np.testing.assert_allclose(np.asarray(spec.compliance(w)), np.asarray(m.compliance(w)), rtol=1e-9)


@FEW
@given(materials(), st.floats(-40.0, 120.0), omegas, st.sampled_from(["WLF", "Arrhenius"]))
def test_at_temperature_is_a_frequency_shift(m, T, w, law):
    shift = WLF(8.86, 101.6, 25.0) if law == "WLF" else Arrhenius(2e5, 25.0)
    aT = 10.0 ** float(shift.log10_aT(T))
    hot = m.with_shift(shift).at_temperature(T)
    np.testing.assert_allclose(complex(hot.modulus(w)), complex(m.modulus(aT * w)), rtol=1e-10)
    same = m.with_shift(shift).at_temperature(25.0)
    np.testing.assert_allclose(np.asarray(same.times), np.asarray(m.times), rtol=1e-15)
    # hotter is faster (shorter relaxation times), colder slower
    assert (aT <= 1.0) if T >= 25.0 else (aT >= 1.0)


# ---------------------------------------------------------------------- operators
memories = st.sampled_from(["periodic", "thesis", 1e6])
kinds = st.sampled_from(["hole", "cylinder"])
sizes = st.sampled_from([16, 48])


@FEW
@given(materials(), omegas, st.booleans(), memories)
def test_effective_compliance_positive_real_part_and_hermitian(m, w, negative, memory):
    w = -w if negative else w
    n = jnp.arange(1, 200, dtype=float)
    J = np.asarray(effective_compliance(m, n, w, memory))
    assert np.all(np.isfinite(J)) and np.all(J.real > 0)
    # Jeff_{-n}(omega) = conj Jeff_n(omega) = Jeff_n(-omega): a real kernel in time
    np.testing.assert_allclose(np.asarray(effective_compliance(m, -n, w, memory)), J.conj(), rtol=1e-12)
    np.testing.assert_allclose(np.asarray(effective_compliance(m, n, -w, memory)), J.conj(), rtol=1e-12)
    # bounded by the glassy and rubbery compliances
    assert np.all(np.abs(J) <= 1.0 / float(m.E0) * (1 + 1e-9))


@OPS
@given(materials(), kinds, st.floats(-4.0, 4.0), st.sampled_from(["periodic", "thesis"]), st.integers(0, 2**31 - 1))
def test_dense_matrix_equals_fft_and_is_real(m, kind, logw, memory, seed):
    n = 32
    w = 10.0 ** logw / np.max(np.asarray(m.times))
    op = ring_operator(kind, m, 0.05, n, omega=w, memory=memory, ref_length=0.05)
    M = np.asarray(op.dense())
    assert M.dtype.kind == "f" and np.all(np.isfinite(M))
    sigma = np.random.default_rng(seed).standard_normal((3, n))
    np.testing.assert_allclose(np.asarray(op(jnp.asarray(sigma))), sigma @ M.T, rtol=1e-10,
                               atol=1e-12 * np.abs(M).max())
    # circulant: constant along the diagonals
    np.testing.assert_allclose(np.roll(np.roll(M, 1, 0), 1, 1), M, rtol=1e-14, atol=0)


@FEW
@given(st.floats(5.0, 9.0), st.sampled_from([0.0, 0.3, 0.5]), kinds, sizes, st.booleans())
def test_elastic_operator_is_symmetric_positive(logE, nu, kind, n, viscoelastic_at_rest):
    if viscoelastic_at_rest:   # a viscoelastic ring at omega = 0 is elastic with E0
        m = Material.sls(10.0**logE, 10.0 ** (logE + 1), 0.01, nu)
    else:
        m = Material.elastic(10.0**logE, nu)
    op = ring_operator(kind, m, 0.05, n, omega=0.0, ref_length=0.05)
    M = np.asarray(op.dense())
    np.testing.assert_allclose(M, M.T, rtol=1e-13, atol=1e-15 * np.abs(M).max())
    # modes n >= 2 are positive (an incompressible disc's mode 0 is zero)
    assert np.all(np.asarray(op.symbol)[2:] > 0)


@OPS
@given(materials(), kinds, st.floats(-3.0, 3.0), st.booleans(), st.sampled_from(["periodic", "thesis"]),
       st.integers(0, 2**31 - 1))
def test_dissipation_has_the_sign_of_the_motion(m, kind, logw, negative, memory, seed):
    """Power into the body, -omega R sum p du/dtheta dtheta (pattern at omega), is >= 0.

    For real sigma, sigma^T (M - M^T) sigma vanishes identically (a skew form); the
    dissipation is the skew part of M seen through the rotation of the pattern,
    -omega sigma^T D M sigma with D the derivative along theta. Modes 0 and 1 carry no
    dissipation (the mean is static, mode 1 is a rigid translation), so the pressure here
    has zero net force and zero mean.
    """
    n = 32
    w = (10.0 ** logw / np.max(np.asarray(m.times))) * (-1 if negative else 1)
    op = ring_operator(kind, m, 0.05, n, omega=w, memory=memory, ref_length=0.05)
    rng = np.random.default_rng(seed)
    s_hat = np.fft.rfft(rng.standard_normal(n))
    s_hat[:2] = 0.0
    sigma = jnp.asarray(np.fft.irfft(s_hat, n))
    u = op(sigma)
    power = -w * float(jnp.sum(sigma * spectral_derivative(u)))
    scale = abs(w) * float(jnp.sum(sigma * u))
    assert power >= -1e-12 * scale
    M = np.asarray(op.dense())
    s = np.asarray(sigma)
    assert abs(s @ (M - M.T) @ s) <= 1e-12 * abs(s @ M @ s)
    # an elastic body does not dissipate
    op_el = ring_operator(kind, Material.elastic(m.E0, m.nu), 0.05, n, omega=w, ref_length=0.05)
    p_el = -w * float(jnp.sum(sigma * spectral_derivative(op_el(sigma))))
    assert abs(p_el) <= 1e-10 * scale


def test_dissipation_is_positive_for_a_moving_pattern():
    """A strict check at omega tau = 1, where the SLS loss is large."""
    m = Material.sls(1e6, 1e7, 0.01, 0.5)
    n = 64
    theta = 2 * np.pi * np.arange(n) / n
    sigma = jnp.asarray(np.maximum(np.cos(theta), 0.0) ** 2 - np.mean(np.maximum(np.cos(theta), 0.0) ** 2))
    for w in (100.0, -100.0):
        op = ring_operator("hole", m, 0.05, n, omega=w, ref_length=0.05)
        assert -w * float(jnp.sum(sigma * spectral_derivative(op(sigma)))) > 0
