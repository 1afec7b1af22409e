"""vjax._core.xla: the solver programs' XLA options must never change what a call computes or
where it may be called, and must leave the user's own XLA_FLAGS in charge (but for an option
a program needs to compute correctly)."""
import os
import subprocess
import sys

import jax
import jax.numpy as jnp
import numpy as np

from vjax._core import xla


def newton_sqrt(a):
    """sqrt(a) by 30 Newton steps in a loop: a small solver-shaped program."""
    return jax.lax.fori_loop(0, 30, lambda i, x: 0.5 * (x + a / x), a)


def test_results_equal_the_plain_program():
    a = jnp.linspace(0.5, 4.0, 7)
    for options in (xla.CLASSIC, xla.START):
        np.testing.assert_allclose(xla.jit(newton_sqrt, options=options)(a), np.sqrt(np.asarray(a)), rtol=1e-15)


def test_inside_transformations_it_is_plain_jit():
    # JAX refuses compiler options on a nested jit: inside jit, grad and vmap the caller's program holds it
    f = xla.jit(newton_sqrt)
    a = jnp.asarray(2.0)
    np.testing.assert_allclose(jax.jit(lambda a: f(a) + 1.0)(a), np.sqrt(2.0) + 1.0, rtol=1e-15)
    np.testing.assert_allclose(jax.grad(f)(a), 0.5 / np.sqrt(2.0), rtol=1e-12)
    np.testing.assert_allclose(jax.vmap(f)(jnp.array([4.0, 9.0])), [2.0, 3.0], rtol=1e-15)


def test_unknown_options_are_dropped_not_raised():
    # an older jaxlib that does not know an option: the program compiles without it
    f = xla.jit(newton_sqrt, options={"xla_no_such_option_in_any_jaxlib": 1})
    np.testing.assert_allclose(f(jnp.asarray(9.0)), 3.0, rtol=1e-15)


def test_the_users_xla_flags_win(monkeypatch):
    items = tuple(sorted({"xla_backend_optimization_level": 1, "xla_cpu_use_fusion_emitters": False}.items()))
    xla._accepted.cache_clear()
    try:
        monkeypatch.setenv("XLA_FLAGS", "--xla_backend_optimization_level=0")
        assert dict(xla._accepted(items)) == {"xla_cpu_use_fusion_emitters": False}
        xla._accepted.cache_clear()
        monkeypatch.setenv("XLA_FLAGS", "")
        assert dict(xla._accepted(items)) == dict(items)
    finally:
        xla._accepted.cache_clear()


def test_a_required_option_is_passed_whatever_xla_flags_says(monkeypatch):
    """NOT_LEVEL_0 (a program XLA:CPU miscompiles at level 0) overrides the user's level 0,
    and the roller, whose Newton has that structure, converges in a process at level 0."""
    items = tuple(sorted({"xla_cpu_use_fusion_emitters": False}.items()))
    required = tuple(sorted(xla.NOT_LEVEL_0.items()))
    xla._accepted.cache_clear()
    try:
        monkeypatch.setenv("XLA_FLAGS", "--xla_backend_optimization_level=0 --xla_cpu_use_fusion_emitters=true")
        assert dict(xla._accepted(items, required)) == xla.NOT_LEVEL_0
    finally:
        xla._accepted.cache_clear()
    code = ("import jax; jax.config.update('jax_enable_x64', True); import vjax; "
            "m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5); "
            "r = vjax.roller_bearing(m, m, 6e-3, 4e-3, 2e-3, 9, 39.0, options=vjax.RollerOptions(n=256), throw=False); "
            "print(int(r.result))")
    env = dict(os.environ, XLA_FLAGS="--xla_backend_optimization_level=0")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=600)
    assert out.stdout.strip().splitlines()[-1] == "0", out.stderr[-2000:]
