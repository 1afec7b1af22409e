"""Rough surfaces on a deformable body in the finite journal bearing solved by GMRES (issue 43):
the Newton steps over film cells, position and asperity pressures with matrix-free products,
preconditioned by the asperity unknowns eliminated node by node (each node's own compliance)
and the film's stencil solve of the rest. Against the dense LU of the whole Jacobian: the same
solutions and implicit derivatives (the same equations; only the linear solve differs); the
linear solves against the AD Jacobian; the preconditioner's transpose against its own products.
The bearing is test_mixed.py's (c = 50 um, L/D = 1, 2 kN, a 2 mm polymer liner, sigma = 1 um)."""
import dataclasses
import time

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
import vjax._core.krylov as _krylov
from vjax.scenes.journal.finite import film as finite_film, setup as finite_setup, steady as finite_steady

R, C, ETA, W = 25.05e-3, 50e-6, 0.03, 2000.0
L = 2 * R
ROUGH = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
LINER = vjax.liner(vjax.Material.sls(1.5e9, 3e9, 0.01, 0.4), 2e-3)     # a 2 mm polymer liner (Pa, Pa, s)
SMALL = vjax.FiniteJournalOptions(n=32, m=8, tol=1e-12)


def solve(omega, solver, options=SMALL, roughness=ROUGH, **kw):
    return vjax.journal_bearing(R, C, ETA, W, omega_shaft=omega, length=L, supply_angle=None, housing=LINER,
                                roughness=roughness, options=dataclasses.replace(options, linear_solver=solver), **kw)


@pytest.mark.parametrize("half", [pytest.param(True, marks=pytest.mark.slow), False],
                         ids=["half width", "whole width"])
def test_linear_solves_against_the_ad_jacobian(half):
    """At a mixed state (the rigid estimate at 0.1 rad/s, perturbed), the GMRES solve and its
    transpose invert the Jacobian of the equations from jacfwd; the preconditioner's transpose
    is the transpose of its products (v . M u = M^T v . u)."""
    pr, cfg = finite_setup.setup(R, C, ETA, W, L, housing=LINER, omega_shaft=0.1, supply_angle=None,
                                 roughness=ROUGH, options=vjax.FiniteJournalOptions(n=16, m=4, linear_solver="krylov"))
    cfg = dataclasses.replace(cfg, half=half)
    assert cfg.krylov and finite_film.solved_by_linear_model(pr, cfg)
    x = finite_steady._guess(pr, cfg)
    size = finite_film.unknowns(cfg) + 2 + finite_film.asperity_unknowns(pr, cfg)
    assert x.shape == (size,) and finite_film.asperity_unknowns(pr, cfg) > 0
    x = x * (1 + 0.05 * jax.random.uniform(jax.random.PRNGKey(0), x.shape))
    b, u, v = jax.random.normal(jax.random.PRNGKey(1), (3, size))

    @jax.jit
    def run(x, b, u, v):
        solve, solve_t = finite_film.linear_model(x, pr, cfg)
        J = jax.jacfwd(lambda y: finite_film.equations(y, pr, cfg)[0])(x)
        M = finite_film._asperity_preconditioner(x, pr, cfg)
        return J, solve(b), solve_t(b), v @ M()(u), M(True)(v) @ u, J @ M()(u)

    J, s, st, vMu, MTvu, JMu = run(x, b, u, v)
    assert float(jnp.max(jnp.abs(J[finite_film.unknowns(cfg):-2]))) > 0      # the asperity rows are there
    np.testing.assert_allclose(J @ s, b, atol=1e-8 * float(jnp.max(jnp.abs(b))))
    np.testing.assert_allclose(J.T @ st, b, atol=1e-8 * float(jnp.max(jnp.abs(b))))
    np.testing.assert_allclose(float(vMu), float(MTvu), rtol=1e-10)
    # a preconditioner, not the identity: J M is far closer to I than J is
    assert float(jnp.linalg.norm(JMu - u)) < 0.5 * float(jnp.linalg.norm(J @ u - u))


# the mixed regime (the asperities carry ~half the load) and near boundary lubrication (~95 %)
SPEEDS = {"mixed": (0.1, 0.3, 0.7), "near boundary": (0.003, 0.9, 0.99)}


@pytest.mark.slow
@pytest.mark.parametrize("regime", list(SPEEDS))
def test_same_solution_as_dense(regime):
    omega, low, high = SPEEDS[regime]
    dense, krylov = solve(omega, "dense"), solve(omega, "krylov")
    assert bool(dense.converged) and bool(krylov.converged)
    assert low < float(dense.asperity_share) < high
    for name in ("eccentricity", "attitude_angle", "asperity_share", "friction_coefficient", "min_film"):
        a, b = float(getattr(krylov, name)), float(getattr(dense, name))
        assert abs(a - b) <= 1e-8 * max(abs(b), 1e-3), (name, a, b)
    scale = float(jnp.max(dense.asperity_pressure))
    np.testing.assert_allclose(krylov.asperity_pressure, dense.asperity_pressure, atol=1e-8 * scale)


@pytest.mark.slow
def test_same_derivatives_as_dense():
    """d(friction coefficient, eccentricity, asperity share) w.r.t. sigma and the speed, by
    implicit differentiation through GMRES (forward and reverse) and through the dense LU."""
    start = solve(0.1, "dense")
    assert 0.3 < float(start.asperity_share) < 0.7

    def outputs(solver):
        def f(sigma, omega):
            r = solve(omega, solver, roughness=dataclasses.replace(ROUGH, sigma=sigma), initial=start)
            return jnp.stack([r.friction_coefficient, r.eccentricity, r.asperity_share])
        return f

    x = (1e-6, 0.1)
    dense = np.asarray(jax.jacfwd(outputs("dense"), argnums=(0, 1))(*x)).T
    krylov = np.asarray(jax.jacfwd(outputs("krylov"), argnums=(0, 1))(*x)).T
    reverse = np.asarray(jax.grad(lambda *a: outputs("krylov")(*a)[0], argnums=(0, 1))(*x))
    assert np.all(np.abs(dense) > 0)
    np.testing.assert_allclose(krylov, dense, rtol=1e-6)
    np.testing.assert_allclose(reverse, dense[0], rtol=1e-6)


@pytest.mark.slow
def test_a_lined_mixed_bearing_on_128_by_32():
    """The grid the Stribeck curves need, out of a dense LU's reach (~4400 unknowns): solved
    by GMRES from its nested coarse start; Newton steps and GMRES products reported."""
    counts = {"solves": 0, "products": 0}
    plain = _krylov.gmres

    def counted(matvec, b, precond, tol, maxiter):
        def product(v):
            jax.debug.callback(lambda: counts.__setitem__("products", counts["products"] + 1))
            return matvec(v)
        jax.debug.callback(lambda: counts.__setitem__("solves", counts["solves"] + 1))
        return plain(product, b, precond, tol, maxiter)

    options = vjax.FiniteJournalOptions(n=128, m=32)
    try:
        _krylov.gmres = counted
        t = time.perf_counter()
        r = solve(0.1, "auto", options=options)
        t = time.perf_counter() - t
    finally:
        _krylov.gmres = plain
    assert bool(r.converged)
    assert 0.2 < float(r.asperity_share) < 0.9
    np.testing.assert_allclose(np.asarray(r.force), [0.0, -W], atol=1e-8 * W)
    per_step = counts["products"] / max(counts["solves"], 1)
    print(f"\n128 x 32 lined mixed: share {float(r.asperity_share):.3f}, {int(r.iterations)} Newton steps on "
          f"128 x 32, {counts['solves']} GMRES solves (coarse start included), {per_step:.1f} products per solve, "
          f"{t:.1f} s (first call)")
    assert per_step < 30      # the preconditioner leaves GMRES a few iterations per Newton step
