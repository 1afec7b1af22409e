import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax import Arrhenius, Material, WLF


def wide_prony(K=40, decades=20, seed=0):
    rng = np.random.default_rng(seed)
    times = np.logspace(-10, -10 + decades, K)
    moduli = 10 ** rng.uniform(5, 8, K)
    return Material.prony(2e5, moduli, times, 0.4)


def test_sls_limits_and_peak():
    m = Material.sls(1e6, 1e7, 0.01, 0.5)
    assert np.isclose(m.storage(1e-9), 1e6, rtol=1e-9)
    assert np.isclose(m.storage(1e9), 1e7, rtol=1e-9)
    # SLS loss peak at omega = 1/(tau sqrt(Einf/E0)) (Eq. 1.41 retardation vs relaxation)
    w = np.logspace(-1, 4, 20001)
    peak = w[np.argmax(np.asarray(m.tan_delta(w)))]
    assert np.isclose(peak, 1 / (0.01 * np.sqrt(10.0)), rtol=1e-3)
    assert np.allclose(m.compliance(3.0) * m.modulus(3.0), 1.0)


def test_creep_spectrum_of_sls_is_analytic():
    E0, Einf, tau = 1e6, 1e7, 0.01
    spec = Material.sls(E0, Einf, tau, 0.5).creep_spectrum()
    assert np.allclose(spec.retardation_times, Einf / E0 * tau, rtol=1e-12)  # Eq. 1.41
    assert np.allclose(spec.C, 1 / E0 - 1 / Einf, rtol=1e-12)
    assert np.isclose(spec.J0, 1 / Einf)


def test_creep_spectrum_wide_prony():
    m = wide_prony()
    spec = m.creep_spectrum()
    assert np.all(np.asarray(spec.C) > 0) and np.all(np.asarray(spec.retardation_times) > 0)
    w = np.logspace(-14, 14, 561)
    direct, creep = np.asarray(m.compliance(w)), np.asarray(spec.compliance(w))
    assert np.max(np.abs(creep - direct) / np.abs(direct)) < 1e-8
    # interlacing: tau_k < lambda_k < tau_{k+1}
    t, lam = np.sort(np.asarray(m.times)), np.sort(np.asarray(spec.retardation_times))
    assert np.all(lam > t) and np.all(lam[:-1] < t[1:])


def test_creep_spectrum_gradient_matches_finite_differences():
    def f(logE):
        m = Material.prony(1e6, 10 ** logE, jnp.array([1e-3, 1e-1, 10.0]), 0.3)
        s = m.creep_spectrum()
        return jnp.sum(s.C * s.retardation_times) + jnp.sum(jnp.log(s.retardation_times))
    x = jnp.array([6.5, 7.0, 6.0])
    g = jax.grad(f)(x)
    h = 1e-6
    fd = np.array([(f(x.at[i].add(h)) - f(x.at[i].add(-h))) / (2 * h) for i in range(3)])
    assert np.allclose(g, fd, rtol=1e-6)


def test_elastic_has_no_memory():
    m = Material.elastic(2e9, 0.3)
    assert m.is_elastic
    assert np.allclose(m.modulus(np.array([0.0, 1.0, 1e9])), 2e9)


@pytest.mark.parametrize("call, name", [
    (lambda: Material.elastic(-1.0, 0.3), "E"),
    (lambda: Material.elastic(1.0, 0.6), "nu"),
    (lambda: Material.elastic(1.0, -1.0), "nu"),
    (lambda: Material.sls(1e6, 1e5, 1.0, 0.3), "Einf"),
    (lambda: Material.sls(1e6, 1e7, 0.0, 0.3), "tau"),
    (lambda: Material.prony(1e6, [1e6, -1.0], [1.0, 2.0], 0.3), "moduli"),
    (lambda: Material.prony(1e6, [1e6, 1.0], [1.0, 1.0], 0.3), "times"),
    (lambda: Material.prony(1e6, [1e6, 1.0], [1.0], 0.3), "moduli and times"),
    (lambda: Material.prony(np.nan, [1e6], [1.0], 0.3), "E0"),
    (lambda: WLF(8.0, 100.0, 20.0).log10_aT(-80.0), "asymptote"),
    (lambda: WLF(-8.0, 100.0, 20.0), "C1"),
    (lambda: Arrhenius(0.0, 20.0), "Ea"),
])
def test_bad_parameters_name_the_problem(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_shift_laws_and_tts():
    wlf = WLF(17.44, 51.6, 20.0)
    assert wlf.log10_aT(20.0) == 0.0
    assert wlf.log10_aT(10.0) > 0 > wlf.log10_aT(40.0)   # colder = slower = larger a_T
    arr = Arrhenius(100e3, 20.0)
    expected = 100e3 / (8.314462618 * np.log(10)) * (1 / 303.15 - 1 / 293.15)
    assert np.isclose(arr.log10_aT(30.0), expected)
    m = Material.sls(1e6, 1e7, 0.01, 0.5)
    hot = m.with_shift(wlf).at_temperature(40.0)
    aT = 10 ** float(wlf.log10_aT(40.0))
    w = np.logspace(-3, 5, 9)
    assert np.allclose(hot.modulus(w), m.modulus(aT * w), rtol=1e-12)


def test_material_is_a_pytree_under_jit_vmap_grad():
    m = Material.sls(1e6, 1e7, 0.01, 0.5)
    assert np.isclose(jax.jit(lambda m: m.storage(1.0))(m), m.storage(1.0))
    E0s = jnp.array([1e6, 2e6])
    out = jax.vmap(lambda e: Material.sls(e, 1e7, 0.01, 0.5).loss(30.0))(E0s)
    assert out.shape == (2,)
    g = jax.grad(lambda tau: Material.sls(1e6, 1e7, tau, 0.5).loss(30.0))(0.01)
    h = 1e-7
    fd = (Material.sls(1e6, 1e7, 0.01 + h, 0.5).loss(30.0) - Material.sls(1e6, 1e7, 0.01 - h, 0.5).loss(30.0)) / (2 * h)
    assert np.isclose(g, fd, rtol=1e-6)
