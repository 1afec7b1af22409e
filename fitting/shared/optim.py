"""Small solvers used by the fitting package: NNLS (numpy), Levenberg-Marquardt (one rule,
:func:`lm_decide`, driven by a jitted JAX loop or from the host) and covariances.

Kept in one module so that the package depends on neither scipy nor the unmaintained jaxopt.
JAX is imported only by what needs it (the jitted loop; steps on JAX arrays): the host
driver, NNLS and covariances run in numpy, so ``vjax-export`` loads no JAX.
"""
from __future__ import annotations

import dataclasses
from typing import Callable

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


@dataclasses.dataclass(frozen=True)
class LMSolution:
    """Result of :func:`levenberg_marquardt`: the parameters ``x``, the cost 0.5*||r||^2,
    the Jacobian at ``x``, the residual ``r``, ``iterations`` and ``converged``."""

    x: object
    cost: object
    residual: object
    jacobian: object
    iterations: object
    converged: object


def _register():
    """LMSolution as a JAX pytree (on first use of the jitted loop, which imports JAX)."""
    import jax
    if not getattr(_register, "done", False):
        jax.tree_util.register_dataclass(LMSolution, data_fields=[f.name for f in dataclasses.fields(LMSolution)],
                                         meta_fields=[])
        _register.done = True


def _xp(*arrays):
    """numpy for host values (the host driver's small problems: no JAX dispatch per
    operation), jax.numpy for JAX arrays and tracers."""
    if all(isinstance(a, (np.ndarray, np.generic, float, int, bool)) for a in arrays):
        return np
    import jax.numpy as jnp
    return jnp


def marquardt_step(J, r, lam, floor=1e-12, active=None):
    """The Levenberg-Marquardt step -(J^T J + lam D)^-1 J^T r for residual ``r`` and Jacobian
    ``J``, with Marquardt scaling D = diag(J^T J) floored at ``floor`` times its largest
    entry (a parameter the residual hardly sees still gets damped instead of wandering
    along the null directions of J). ``active`` (0/1): frozen parameters get a zero step."""
    xp = _xp(J, r, lam)
    act = xp.ones(J.shape[1], J.dtype) if active is None else active
    Ja = J * act[None, :]
    # host: einsum's own loops, not a BLAS call whose threads, on a busy machine, make these
    # small products (hundreds of rows, tens of columns) twenty times slower
    H, g = (xp.einsum("ij,ik->jk", Ja, Ja), xp.einsum("ij,i->j", Ja, r)) if xp is np else (Ja.T @ Ja, Ja.T @ r)
    d = xp.diag(H)
    d = xp.maximum(d, floor * xp.max(d) + 1e-300)
    return -xp.linalg.solve(H + lam * xp.diag(d) + xp.diag(1.0 - act), g) * act


def next_damping(lam, accepted):
    """Damping after a trial step: divided by 3 after an accepted one, times 4 otherwise."""
    xp = _xp(lam, accepted)
    return xp.where(accepted, xp.maximum(lam / 3.0, 1e-12), lam * 4.0)


LAM_MAX = 1e12      # damping beyond which no step lowers the cost: stop


def lm_decide(x, step, cost, new_cost, lam, ftol, xtol, usable=True):
    """The Levenberg-Marquardt rule, the one both drivers below follow: a trial step is
    accepted when its cost is finite, ``usable`` and lower; the damping is updated by
    :func:`next_damping`; the iteration stops once an accepted step lowers the cost by no
    more than ``ftol`` of it or moves x by no more than ``xtol`` of |x|, or the damping
    exceeds :data:`LAM_MAX`. Works on traced and host values alike.
    Returns ``(accepted, next damping, done, stuck)``."""
    xp = _xp(x, step, cost, new_cost, lam)
    ok = usable & xp.isfinite(new_cost) & (new_cost < cost)
    small = ok & (((cost - new_cost) <= ftol * cost)
                  | (xp.linalg.norm(step) <= xtol * (xp.linalg.norm(x) + xtol)))
    lam = next_damping(lam, ok)
    stuck = lam > LAM_MAX
    return ok, lam, small | stuck, stuck


def levenberg_marquardt(fun: Callable, x0, args=(), max_iter: int = 200, xtol: float = 1e-10,
                        ftol: float = 1e-12, active=None, resid_jac: Callable | None = None) -> LMSolution:
    """Minimize 0.5 ||fun(x, *args)||^2 by Levenberg-Marquardt with Marquardt scaling.

    ``fun`` maps a 1-D parameter vector to a 1-D residual; its Jacobian comes from
    ``jax.jacfwd`` (few parameters, many residuals). Never raises: ``converged`` tells
    whether the relative cost decrease or step fell below ``ftol``/``xtol`` before
    ``max_iter`` iterations. Jit-compatible (``max_iter`` static). ``active`` (optional 0/1
    vector like ``x0``): parameters with 0 are frozen (padding of a fixed-size vector).
    ``resid_jac`` (optional): ``x -> (residual, Jacobian)`` replacing ``fun`` and ``jacfwd``.
    The accept/damp/stop rule is :func:`lm_decide`; :func:`levenberg_marquardt_host` runs the
    same iteration on the host.
    """
    import jax
    import jax.numpy as jnp
    _register()
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
    state = (x0, r0, J0, c0, jnp.asarray(1e-3, x0.dtype), jnp.asarray(0), jnp.asarray(False), jnp.asarray(False))

    def cond(s):
        return (s[5] < max_iter) & ~s[6]

    def body(s):
        x, r, J, c, lam, k, _, _ = s
        step = marquardt_step(J, r, lam, active=act)
        xn = x + step
        rn, Jn, cn = lin(xn)
        ok, lam, done, stuck = lm_decide(x, step, c, cn, lam, ftol, xtol)
        x, r, J = jax.tree_util.tree_map(lambda a, b: jnp.where(ok, a, b), (xn, rn, Jn), (x, r, J))
        c = jnp.where(ok, cn, c)
        return (x, r, J, c, lam, k + 1, done, stuck)

    x, r, J, c, lam, k, done, stuck = jax.lax.while_loop(cond, body, state)
    return LMSolution(x, c, r, J, k, done & ~stuck)


def levenberg_marquardt_host(resid_jac: Callable, x0, max_iter: int = 200, xtol: float = 1e-10,
                             ftol: float = 1e-12, floor: float = 1e-12, usable: Callable | None = None,
                             on_accept: Callable | None = None, lam0: float = 1e-3, start=None):
    """:func:`levenberg_marquardt` driven from Python, for residuals that are not one jitted
    function (the torque fit's bearing solves) or are small numpy problems (the compact FEM
    spectra). ``resid_jac(x) -> (r, J, aux)``; ``usable(aux)`` may reject a trial (e.g. a
    solve that did not converge); ``on_accept(iteration, cost, x, aux)`` is called after each
    accepted step; ``start``: ``resid_jac(x0)`` when the caller has it already. Same steps
    (:func:`marquardt_step`) and rule (:func:`lm_decide`).
    Returns ``(x, r, J, aux, cost, iterations, converged)``; the cost is 0.5 ||r||^2."""
    x = np.asarray(x0, float)
    r, J, aux = resid_jac(x) if start is None else start
    r, J = np.asarray(r, float), np.asarray(J, float)
    c, lam, done, stuck, k = 0.5 * float(r @ r), lam0, False, False, 0
    while k < max_iter and not done:
        step = marquardt_step(J, r, lam, floor=floor)
        rn, Jn, auxn = resid_jac(x + step)
        rn, Jn = np.asarray(rn, float), np.asarray(Jn, float)
        cn = 0.5 * float(rn @ rn)
        ok, lam, done, stuck = (np.asarray(v).item() for v in
                                lm_decide(x, step, c, cn, lam, ftol, xtol, bool(usable(auxn)) if usable else True))
        k += 1
        if ok:
            x, r, J, aux, c = x + step, rn, Jn, auxn, cn
            if on_accept is not None:
                on_accept(k, c, x, aux)
    return x, r, J, aux, c, k, done and not stuck


def covariance(J, rcond: float = 1e-7):
    """(J^T J)^+ by the SVD of ``J`` (rows: residuals, columns: parameters): directions with a
    singular value below ``rcond`` times the largest are dropped. A penalized problem passes
    its penalty rows stacked under J (then this is (J^T J + P^T P)^+). Returns ``(cov, sd,
    resolved)``: the covariance, sqrt of its diagonal, and per parameter the share of its
    unit vector in the kept directions (1: fully determined; below 1 some of it lies where
    the data say nothing). The caller scales by the residual variance s^2."""
    J = np.asarray(J, float)
    _, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > rcond * (s[0] if s.size else 0.0)
    inv = np.where(keep, 1.0 / np.where(keep, s, 1.0) ** 2, 0.0)
    cov = (Vt.T * inv) @ Vt
    resolved = np.sum(Vt[keep] ** 2, axis=0) if np.any(keep) else np.zeros(J.shape[1])
    return cov, np.sqrt(np.clip(np.diag(cov), 0, None)), resolved
