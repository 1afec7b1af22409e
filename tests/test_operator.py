"""The FFT steady-state operator: memory models, limits, dense matrix, gradients."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax import Material, effective_compliance, green, grid, ring_operator

SLS = Material.sls(1e6, 1e7, 0.01, 0.5)   # thesis Fig. A.4 material
R = 0.08


def test_fft_application_equals_dense_matrix_and_is_not_symmetric():
    op = ring_operator("hole", SLS, R, 32, omega=100.0)
    sigma = jnp.asarray(np.random.default_rng(0).random(32))
    M = op.dense()
    assert np.allclose(op(sigma), M @ sigma, rtol=1e-12, atol=1e-20)
    assert not np.allclose(M, M.T, rtol=1e-3, atol=0)   # viscoelastic: the steady state is not symmetric
    elastic = ring_operator("hole", Material.elastic(1e6, 0.5), R, 32).dense()
    assert np.allclose(elastic, elastic.T, rtol=1e-12, atol=0)


def test_dense_matrix_of_elastic_operator_is_the_element_kernel():
    n = 16
    theta, alpha = grid(n)
    E = 2e6
    M = np.asarray(ring_operator("cylinder", Material.elastic(E, 0.3), R, n).dense())
    for i in range(n):
        for k in range(n):
            Lik = float(green.element_kernel("cylinder", theta[i] - theta[k], alpha, R, 0.3))
            assert np.isclose(M[i, k], R / E * Lik, rtol=1e-10, atol=1e-22)


@pytest.mark.parametrize("omega_tilde", [0.01, 0.1, 1.0, 10.0])
def test_thesis_kernel_equals_direct_quadrature_of_eq_2_16(omega_tilde):
    """Eq. 2.16 with one retardation time: J0 L(S) + C int_0^{2pi/(w lam)} e^-z L(S + w lam z) dz.

    The FFT version shifts the discrete kernel by trigonometric interpolation, so the two
    agree to the discretization accuracy, which is O(1/N) (the element kernel has x log x
    kinks): measured 8e-3, 2e-3, 2e-4, 4e-6 at N = 128 and 2e-3, 5e-4, 5e-5, 2e-6 at N = 512
    for omega~ = 0.01, 0.1, 1, 10.
    """
    spec = SLS.creep_spectrum()
    lam, C, J0 = float(spec.retardation_times[0]), float(spec.C[0]), float(spec.J0)
    omega = omega_tilde / 0.01
    Z = 2 * np.pi / (omega * lam)
    x, w = np.polynomial.legendre.leggauss(1500)
    z, wz = (x + 1) / 2 * Z, w * Z / 2
    errors = []
    for n in (128, 512):
        theta, alpha = grid(n)
        L = jax.jit(lambda t: green.element_kernel("hole", t, alpha, R, 0.5))
        col = np.asarray(ring_operator("hole", SLS, R, n, omega=omega, memory="thesis").kernel) / R
        shifted = np.asarray(L(theta[:, None] + omega * lam * z[None, :]))
        direct = J0 * np.asarray(L(theta)) + C * (shifted * (wz * np.exp(-z))).sum(axis=1)
        errors.append(np.max(np.abs(col - direct)) / np.max(np.abs(direct)))
    # at high speed both are ~1e-5, at the level of the quadrature of the kinked kernel
    assert errors[1] < 3e-3 and (errors[1] < errors[0] or errors[1] < 1e-4)


def test_periodic_is_the_limit_of_many_revolutions():
    modes = jnp.arange(64)
    omega = 30.0
    periodic = effective_compliance(SLS, modes, omega, "periodic")
    prev = None
    for m in (1.0, 3.0, 10.0, 100.0):
        err = float(jnp.max(jnp.abs(effective_compliance(SLS, modes, omega, m) - periodic)))
        assert prev is None or err < prev
        prev = err
    assert prev < 1e-12 * 1e-6 and np.allclose(effective_compliance(SLS, modes, omega, 1.0),
                                                effective_compliance(SLS, modes, omega, "thesis"))


@pytest.mark.parametrize("memory", ["periodic", "thesis", 5.0])
def test_rubbery_and_glassy_limits(memory):
    n = 64
    slow = ring_operator("hole", SLS, R, n, omega=1e-9, memory=memory).symbol
    fast = ring_operator("hole", SLS, R, n, omega=1e9, memory=memory).symbol
    rubbery = ring_operator("hole", Material.elastic(1e6, 0.5), R, n).symbol
    glassy = ring_operator("hole", Material.elastic(1e7, 0.5), R, n).symbol
    assert np.allclose(slow, rubbery, rtol=1e-6)
    assert np.allclose(fast[1:], glassy[1:], rtol=1e-6)
    # mode 0: static in the periodic steady state (rubbery); glassy with finite memory
    expected0 = rubbery[0] if memory == "periodic" else glassy[0]
    assert np.isclose(fast[0], expected0, rtol=1e-6)


def test_trailing_edge_shows_the_larger_displacement():
    """omega > 0 moves the load towards +theta: the material lags, the side at theta < 0 sinks more."""
    n = 256
    sigma = jnp.zeros(n).at[0].set(1.0)
    u = np.asarray(ring_operator("hole", SLS, R, n, omega=100.0)(sigma))
    k = 5
    assert u[-k] > u[k]


def test_grad_through_operator_matches_finite_differences():
    sigma = jnp.asarray(np.random.default_rng(1).random(64)) * 1e4

    def f(p):
        E0, E1, tau, nu = p
        m = Material.prony(E0, jnp.stack([E1]), jnp.stack([tau]), nu)
        u = ring_operator("hole", m, R, 64, omega=30.0, memory="thesis")(sigma)
        return jnp.sum(u * jnp.cos(jnp.arange(64) * 0.3))

    p = jnp.array([1e6, 9e6, 0.01, 0.4])
    g = np.asarray(jax.grad(f)(p))
    for i, h in enumerate(p * 1e-5):
        fd = (f(p.at[i].add(h)) - f(p.at[i].add(-h))) / (2 * h)
        assert np.isclose(g[i], fd, rtol=1e-6), (i, g[i], fd)


def test_bad_arguments():
    with pytest.raises(ValueError, match="memory"):
        ring_operator("hole", SLS, R, 64, memory="forever")
    with pytest.raises(ValueError, match="kind"):
        ring_operator("ellipse", SLS, R, 64)
    with pytest.raises(ValueError, match="R"):
        ring_operator("hole", SLS, -1.0, 64)
    with pytest.raises(ValueError, match="n"):
        ring_operator("hole", SLS, R, 2)


def test_float32_runs_without_nan():
    m = Material.sls(np.float32(1e6), np.float32(1e7), np.float32(0.01), np.float32(0.5))
    with jax.enable_x64(False):
        for memory in ("periodic", "thesis"):
            u = ring_operator("hole", m, np.float32(R), 256, omega=np.float32(50.0), memory=memory)(
                jnp.ones(256, jnp.float32))
            assert u.dtype == jnp.float32 and np.all(np.isfinite(u))


def test_a_traced_memory_serves_every_model_in_one_program():
    """The memory as a traced number of revolutions (inf: periodic): one compiled program gives
    the periodic operator (the complex compliance 1/E*), the thesis's (one revolution of the
    creep spectrum) and, at a long memory, a truncated history that tends to the periodic one
    (two independent formulas: the creep spectrum's against the Prony modulus)."""
    from vjax.bodies.operator import memory_revolutions
    n, omega = 64, 30.0
    traced = jax.jit(lambda m: ring_operator("hole", SLS, R, n, omega=omega, memory=m).symbol)
    for memory in ("periodic", "thesis", 3.0):
        np.testing.assert_allclose(traced(memory_revolutions(memory)),
                                   ring_operator("hole", SLS, R, n, omega=omega, memory=memory).symbol, rtol=1e-14)
    assert traced._cache_size() == 1
    periodic = np.asarray(traced(np.inf))
    long = np.asarray(traced(1e4))      # exp(-2 pi 1e4 / (omega lambda)) = 0 for every retardation time here
    np.testing.assert_allclose(long, periodic, rtol=1e-10)
    assert not np.allclose(np.asarray(traced(1.0)), periodic, rtol=1e-3)     # the thesis's mode 0 is not rubbery
    g = jax.grad(lambda m: jnp.real(ring_operator("hole", SLS, R, n, omega=omega, memory=m).symbol[1]))
    assert np.isfinite(float(g(jnp.inf))) and float(g(jnp.inf)) == 0.0
