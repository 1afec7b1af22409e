"""The solver core: Newton with kept (Broyden-updated) Jacobians, vjax._core.solve.newton(jacobian=);
the rising root (vjax._core.root.rising_root) and the failure path's hint (vjax._core.solve.report)."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax._core import root, solve as _solve

A = jnp.array([[4.0, 1.0, 0.0], [1.0, 3.0, 0.5], [0.0, 0.5, 2.0]])
B = jnp.array([1.0, -2.0, 0.5])


def equations(x, state):
    """r = A x + x^3 - b (a root near A^-1 b); state counts the accepted points."""
    return A @ x + x ** 3 - B, state + 1, jnp.asarray(True)


def exact_root():
    x, _, stats = _solve.newton(equations, jnp.zeros(3), 0, tol=1e-14, max_iter=50)
    assert int(stats.result) == _solve.SUCCESS
    return x


@pytest.mark.parametrize("name", ["exact at another point", "zeros", "wrong sign", "none (exact Newton)"])
def test_kept_jacobian_reaches_the_same_root(name):
    x0 = jnp.array([0.3, -0.4, 0.2])
    J_far = jax.jacfwd(lambda x: equations(x, 0)[0])(jnp.array([1.0, 1.0, 1.0]))
    J0 = {"exact at another point": J_far, "zeros": jnp.zeros((3, 3)), "wrong sign": -J_far,
          "none (exact Newton)": None}[name]
    x, _, stats, J = jax.jit(lambda x0, J0: _solve.newton(equations, x0, 0, tol=1e-12, max_iter=60, jacobian=J0,
                                                          return_jacobian=True))(x0, J0)
    assert int(stats.result) == _solve.SUCCESS, name
    np.testing.assert_allclose(np.asarray(x), np.asarray(exact_root()), rtol=0, atol=1e-11)
    # the Jacobian handed back is close to the one at the root (fresh or Broyden-updated)
    J_root = jax.jacfwd(lambda x: equations(x, 0)[0])(x)
    assert float(jnp.max(jnp.abs(J - J_root))) < 0.5 * float(jnp.max(jnp.abs(J_root)))


def test_kept_jacobian_at_the_root_needs_no_recomputation():
    """Started next to the root with its exact Jacobian, Newton converges in chord steps:
    a Jacobian recomputed would show as an exact Newton iterate, which differs."""
    root = exact_root()
    J_root = jax.jacfwd(lambda x: equations(x, 0)[0])(root)
    x0 = root + 1e-3
    x, _, stats, J = _solve.newton(equations, x0, 0, tol=1e-13, max_iter=20, jacobian=J_root)
    assert int(stats.result) == _solve.SUCCESS and int(stats.iterations) <= 4
    # with a kept Jacobian the first step is x0 - J_root^-1 r(x0): one step, no jacfwd
    x1, _, _, _ = _solve.newton(equations, x0, 0, tol=1e-13, max_iter=1, jacobian=J_root)
    np.testing.assert_allclose(np.asarray(x1), np.asarray(x0 - jnp.linalg.solve(J_root, equations(x0, 0)[0])),
                               rtol=1e-14)


def test_keep_jacobian_false_is_exact_newton_in_the_kept_mode_program():
    """keep_jacobian=False (traced) ignores the Jacobian handed in: every iterate is exact
    Newton's (a cold start in the warm start's program); True with the same program keeps it."""
    x0 = jnp.array([0.3, -0.4, 0.2])
    J_far = jax.jacfwd(lambda x: equations(x, 0)[0])(jnp.array([1.0, 1.0, 1.0]))
    run = jax.jit(lambda keep, steps: [_solve.newton(equations, x0, 0, tol=1e-13, max_iter=k, jacobian=J_far,
                                                     keep_jacobian=keep)[0] for k in steps], static_argnums=1)
    steps = (1, 2, 3)
    exact = [_solve.newton(equations, x0, 0, tol=1e-13, max_iter=k)[0] for k in steps]
    for a, b in zip(run(jnp.asarray(False), steps), exact):
        np.testing.assert_allclose(np.asarray(a), np.asarray(b), rtol=1e-14, atol=1e-15)
    kept = run(jnp.asarray(True), steps)[0]
    assert float(jnp.max(jnp.abs(kept - exact[0]))) > 1e-3      # the kept Jacobian's first step differs


def test_a_step_that_fails_with_a_fresh_jacobian_is_reported_stalled():
    """Equations with no root (r = x^2 + 1): the retry rule must not hide a true stall."""
    no_root = lambda x, s: (x ** 2 + 1.0, s, jnp.asarray(True))
    _, _, stats, _ = _solve.newton(no_root, jnp.array([0.5]), 0, tol=1e-12, max_iter=40,
                                   jacobian=jnp.zeros((1, 1)))
    assert int(stats.result) in (_solve.STALLED, _solve.MAX_ITERATIONS, _solve.NONFINITE)


def test_stall_window_stops_a_creeping_newton_and_spares_a_converging_one():
    """r = x^2 + 1 has no root: from x = 3 the line search keeps accepting small decreases
    towards the floor r = 1, which never halves. With stall_window=5 Newton stops there as
    STALLED within the window of its last halving; without it, it creeps on. The converging
    equations above, whose residual halves every step or two, are not stopped by a window of 3."""
    no_root = lambda x, s: (x ** 2 + 1.0, s, jnp.asarray(True))
    _, _, creep = _solve.newton(no_root, jnp.array([3.0]), 0, tol=1e-12, max_iter=40)
    _, _, stopped = _solve.newton(no_root, jnp.array([3.0]), 0, tol=1e-12, max_iter=40, stall_window=5)
    assert int(stopped.result) == _solve.STALLED
    assert int(stopped.iterations) < int(creep.iterations)
    assert int(stopped.iterations) <= 5 + 3        # residual 10 -> halved at most 3 times before the floor
    x, _, stats = _solve.newton(equations, jnp.zeros(3), 0, tol=1e-14, max_iter=50, stall_window=3)
    assert int(stats.result) == _solve.SUCCESS
    np.testing.assert_allclose(np.asarray(x), np.asarray(exact_root()), rtol=0, atol=1e-13)


# ---- the rising root (vjax._core.root) and the failure path's hint -------------------------------------
def substitution_diverges(x):
    """r(x) = x - g(x), g(x) = 20 exp(-x / 2): g' ~ -1.75 at the root, where x <- g(x) diverges."""
    return x - 20.0 * jnp.exp(-x / 2), jnp.asarray(True)


def test_rising_root_against_brentq_eager_and_traced():
    import scipy.optimize as so
    ref = so.brentq(lambda x: x - 20.0 * np.exp(-x / 2), 0.0, 20.0, xtol=1e-15)
    x, stats = root.rising_root(substitution_diverges, 0.0, 250.0, 1e-12, 60)
    assert int(stats.result) == _solve.SUCCESS and abs(float(x) - ref) < 1e-11
    xj, sj = jax.jit(lambda lo: root.rising_root(substitution_diverges, lo, 250.0, 1e-12, 60))(0.0)
    assert float(xj) == float(x) and int(sj.iterations) == int(stats.iterations)
    # an invalid point closes the bracket from above: the search goes back below it
    x, stats = root.rising_root(lambda x: (x - 20.0 * jnp.exp(-x / 2), x < 3.6), 0.0, 250.0, 1e-12, 60)
    assert int(stats.result) == _solve.SUCCESS and abs(float(x) - ref) < 1e-11


def test_rising_root_reports_runaway_an_invalid_floor_and_its_iteration_limit():
    x, stats = root.rising_root(lambda x: (-1.0 - 0.0 * x, jnp.asarray(True)), 0.0, 150.0, 1e-12, 60)
    assert int(stats.result) == _solve.RUNAWAY and float(x) == 150.0
    _, stats = root.rising_root(lambda x: (x - 1.0, x > 0.5), 0.0, 150.0, 1e-12, 60)
    assert int(stats.result) == _solve.INNER_FAILED
    _, stats = root.rising_root(substitution_diverges, 0.0, 250.0, 1e-12, 2)
    assert int(stats.result) == _solve.MAX_ITERATIONS and int(stats.iterations) == 2


def test_the_hint_names_the_failed_points_numbers_inside_and_outside_jit():
    def hint(result, T, T_limit):
        return f" Runaway: reached T = {T:.6g} C, T_limit = {T_limit:.6g} C." if result == _solve.RUNAWAY else " Other."

    def run(T, result):
        stats = _solve.Stats(jnp.full(jnp.shape(result), 3), jnp.full(jnp.shape(result), 0.5), result)
        _solve.report("demo", stats, True, hint=hint, values=dict(T=T, T_limit=150.0))
        return T

    with pytest.raises(_solve.ConvergenceError, match=r"demo did not converge: ran past the bound .* after 3 "
                                                       r"iterations.*Runaway: reached T = 150 C, T_limit = 150 C\.$"):
        run(150.0, _solve.RUNAWAY)
    run(150.0, _solve.SUCCESS)          # converged: nothing raised
    with pytest.raises(Exception, match=r"Runaway: reached T = 151 C, T_limit = 150 C"):
        jax.block_until_ready(jax.jit(run)(151.0, _solve.RUNAWAY))
    # a batch: the first failed point's numbers
    with pytest.raises(_solve.ConvergenceError, match=r"at 1 of 2 points \(first: flat index 1\).* reached T = 2 C"):
        run(jnp.array([1.0, 2.0]), jnp.array([_solve.SUCCESS, _solve.RUNAWAY]))
