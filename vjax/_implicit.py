"""Implicit differentiation of a root ``residual(x, params) = 0`` (internal helper).

:func:`implicit_root` wraps a solver ``solver(params) -> (x, stats)`` so that ``x`` is
differentiated by the implicit function theorem at the returned point,

    dx = -J^{-1} (d residual / d params) dparams,    J = d residual / d x,

with a dense ``J`` from ``jax.jacfwd`` (meant for systems of at most a few thousand
unknowns). Nothing is differentiated through the solver's iterations. Forward mode is
the rule above; reverse mode is its transpose (one transposed dense solve), so
``jax.jvp``, ``jax.jacfwd``, ``jax.grad`` and ``jax.vjp`` all work. ``stats`` (iteration
counts, flags, residual norms) get zero tangents.

``params`` must be a PyTree of floating-point arrays; pass static configuration by
closure (it is not differentiated). If the solver did not converge the derivative is
that of the linearization at the returned point: meaningful only with ``converged``.
"""
from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np


def _zero_tangent(x):
    x = jnp.asarray(x)
    if jnp.issubdtype(x.dtype, jnp.inexact):
        return jnp.zeros_like(x)
    return np.zeros(x.shape, dtype=jax.dtypes.float0)


def implicit_root(residual, solver):
    """Return ``solve(params) -> (x, stats)`` with implicit derivatives of ``x``.

    Args:
      residual: ``residual(x, params) -> r`` with ``r`` of the shape of ``x`` (1-D).
      solver: ``solver(params) -> (x, stats)``; ``x`` a 1-D float array.
    """

    @jax.custom_jvp
    def solve(params):
        return solver(params)

    @solve.defjvp
    def _solve_jvp(primals, tangents):
        (params,), (dparams,) = primals, tangents
        x, stats = solve(params)
        jac = jax.jacfwd(residual, argnums=0)(x, params)
        _, dr = jax.jvp(lambda q: residual(x, q), (params,), (dparams,))
        dx = jnp.linalg.solve(jac, -dr)
        return (x, stats), (dx, jax.tree_util.tree_map(_zero_tangent, stats))

    return solve
