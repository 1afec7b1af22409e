"""Small solvers used by the fitting package: NNLS (numpy) and Levenberg-Marquardt (JAX).

Kept in one internal module so that the package depends on neither scipy nor the
unmaintained jaxopt.
"""
from __future__ import annotations

import dataclasses
from typing import Callable

import jax
import jax.numpy as jnp
import numpy as np


def nnls(A, b, max_iter=None, tol=None):
    """Non-negative least squares min ||A x - b|| s.t. x >= 0 (Lawson and Hanson 1974, ch. 23).

    Returns ``(x, residual_norm)``. Dense numpy; meant for a few hundred columns at most.
    """
    A, b = np.asarray(A, float), np.asarray(b, float)
    m, n = A.shape
    if m > 2 * n:
        # same minimizer on the n x n triangular factor: ||Ax - b||^2 = ||Rx - Q^T b||^2 + const
        Q, R = np.linalg.qr(A)
        qb = Q.T @ b
        x, _ = nnls(R, qb, max_iter, tol)
        return x, float(np.linalg.norm(A @ x - b))
    max_iter = 3 * n if max_iter is None else max_iter
    tol = 10 * np.finfo(float).eps * np.linalg.norm(A, 1) * max(m, n) if tol is None else tol
    x = np.zeros(n)
    passive = np.zeros(n, bool)
    w = A.T @ (b - A @ x)
    it = 0
    while (~passive).any() and np.max(np.where(passive, -np.inf, w)) > tol and it < max_iter:
        j = int(np.argmax(np.where(passive, -np.inf, w)))
        passive[j] = True
        while True:
            it += 1
            z = np.zeros(n)
            z[passive] = np.linalg.lstsq(A[:, passive], b, rcond=None)[0]
            if np.all(z[passive] > 0) or it > max_iter:
                x = z
                break
            # step back to the boundary and release the variables that hit zero
            q = passive & (z <= 0)
            alpha = np.min(x[q] / (x[q] - z[q]))
            x = x + alpha * (z - x)
            passive &= x > tol
            x[~passive] = 0.0
        w = A.T @ (b - A @ x)
    return x, float(np.linalg.norm(A @ x - b))


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class LMSolution:
    """Result of :func:`levenberg_marquardt`: the parameters ``x``, the cost 0.5*||r||^2,
    the Jacobian at ``x``, the residual ``r``, ``iterations`` and ``converged``."""

    x: jax.Array
    cost: jax.Array
    residual: jax.Array
    jacobian: jax.Array
    iterations: jax.Array
    converged: jax.Array


def marquardt_step(J, r, lam, floor=1e-12, active=None):
    """The Levenberg-Marquardt step -(J^T J + lam D)^-1 J^T r for residual ``r`` and Jacobian
    ``J``, with Marquardt scaling D = diag(J^T J) floored at ``floor`` times its largest
    entry (a parameter the residual hardly sees still gets damped instead of wandering
    along the null directions of J). ``active`` (0/1): frozen parameters get a zero step."""
    act = jnp.ones(J.shape[1], J.dtype) if active is None else active
    Ja = J * act[None, :]
    H = Ja.T @ Ja
    d = jnp.diag(H)
    d = jnp.maximum(d, floor * jnp.max(d) + 1e-300)
    return -jnp.linalg.solve(H + lam * jnp.diag(d) + jnp.diag(1.0 - act), Ja.T @ r) * act


def next_damping(lam, accepted):
    """Damping after a trial step: divided by 3 after an accepted one, times 4 otherwise."""
    return jnp.where(accepted, jnp.maximum(lam / 3.0, 1e-12), lam * 4.0)


def levenberg_marquardt(fun: Callable, x0, args=(), max_iter: int = 200, xtol: float = 1e-10,
                        ftol: float = 1e-12, active=None, resid_jac: Callable | None = None) -> LMSolution:
    """Minimize 0.5 ||fun(x, *args)||^2 by Levenberg-Marquardt with Marquardt scaling.

    ``fun`` maps a 1-D parameter vector to a 1-D residual; its Jacobian comes from
    ``jax.jacfwd`` (few parameters, many residuals). Never raises: ``converged`` tells
    whether the relative cost decrease or step fell below ``ftol``/``xtol`` before
    ``max_iter`` iterations. Jit-compatible (``max_iter`` static). ``active`` (optional 0/1
    vector like ``x0``): parameters with 0 are frozen (padding of a fixed-size vector).
    ``resid_jac`` (optional): ``x -> (residual, Jacobian)`` replacing ``fun`` and ``jacfwd``.
    """
    x0 = jnp.asarray(x0)
    act = jnp.ones_like(x0) if active is None else jnp.asarray(active, x0.dtype)
    if resid_jac is None:
        jac = jax.jacfwd(lambda x: fun(x, *args))
        resid_jac = lambda x: (fun(x, *args), jac(x))  # noqa: E731

    @jax.jit     # one trace and one lowering for its two call sites (the start and the loop body)
    def lin(x):
        r, J = resid_jac(x)
        return r, J, 0.5 * jnp.sum(r * r)

    r0, J0, c0 = lin(x0)
    state = (x0, r0, J0, c0, jnp.asarray(1e-3, x0.dtype), jnp.asarray(0), jnp.asarray(False))

    def cond(s):
        return (s[5] < max_iter) & ~s[6]

    def body(s):
        x, r, J, c, lam, k, _ = s
        step = marquardt_step(J, r, lam, active=act)
        xn = x + step
        rn, Jn, cn = lin(xn)
        ok = jnp.isfinite(cn) & (cn < c)
        small = ok & (((c - cn) <= ftol * c) | (jnp.linalg.norm(step) <= xtol * (jnp.linalg.norm(x) + xtol)))
        x, r, J = jax.tree_util.tree_map(lambda a, b: jnp.where(ok, a, b), (xn, rn, Jn), (x, r, J))
        c = jnp.where(ok, cn, c)
        lam = next_damping(lam, ok)
        stuck = lam > 1e12
        return (x, r, J, c, lam, k + 1, small | stuck)

    x, r, J, c, lam, k, done = jax.lax.while_loop(cond, body, state)
    return LMSolution(x, c, r, J, k, done & (lam <= 1e12))
