"""Preconditioned Krylov solves that report how well they did (internal).

``jax.scipy.sparse.linalg.bicgstab`` returns no status, so a contact solve could not tell a
Krylov breakdown from a slow outer iteration. This BiCGSTAB (van der Vorst 1992, right
preconditioned) returns its relative residual (that of its recurrence); GMRES (JAX's, which
never breaks down, the fallback) gets its residual measured after the fact.
"""
from __future__ import annotations

import jax
import jax.numpy as jnp
from jax.scipy.sparse.linalg import gmres as _gmres


def bicgstab(matvec, b, precond, tol: float, maxiter: int):
    """Solve ``A x = b`` (1-D, real). Returns ``(x, |b - A x| / |b|)``; x = 0 for b = 0.

    Stops at ``tol`` or ``maxiter``; a breakdown (rho or omega = 0) stops it with the last
    iterate, whose residual then tells the caller.
    """
    bnorm = jnp.linalg.norm(b)
    safe = jnp.where(bnorm > 0, bnorm, 1.0)
    b = b / safe
    tiny = jnp.finfo(b.dtype).tiny

    def cond(s):
        k, x, r, *_ , rnorm, broke = s
        return (k < maxiter) & (rnorm > tol) & ~broke

    def body(s):
        k, x, r, r0, p, v, rho, alpha, omega, _, _ = s
        rho_new = jnp.vdot(r0, r)
        beta = (rho_new / rho) * (alpha / omega)
        p = r + beta * (p - omega * v)
        ph = precond(p)
        v = matvec(ph)
        alpha = rho_new / jnp.vdot(r0, v)
        s_ = r - alpha * v
        sh = precond(s_)
        t = matvec(sh)
        omega_new = jnp.vdot(t, s_) / jnp.maximum(jnp.vdot(t, t), tiny)
        x = x + alpha * ph + omega_new * sh
        r = s_ - omega_new * t
        broke = (jnp.abs(rho_new) <= tiny) | (jnp.abs(omega_new) <= tiny) | ~jnp.isfinite(alpha)
        return k + 1, x, r, r0, p, v, rho_new, alpha, omega_new, jnp.linalg.norm(r), broke

    one = jnp.ones((), b.dtype)
    zero = jnp.zeros_like(b)
    init = (0, zero, b, b, zero, zero, one, one, one, jnp.linalg.norm(b), jnp.asarray(False))
    _, x, *_, rnorm, _ = jax.lax.while_loop(cond, body, init)
    # The recurrence's residual (free) rather than a true one (one more operator application):
    # the contact solve refines iteratively and measures its own true residual anyway.
    ok = jnp.all(jnp.isfinite(x))
    return jnp.where(ok, x, 0.0) * safe, jnp.where(ok, rnorm, jnp.inf)


def gmres(matvec, b, precond, tol: float, maxiter: int):
    """Restarted GMRES(20) with the same contract as :func:`bicgstab`."""
    bnorm = jnp.linalg.norm(b)
    safe = jnp.where(bnorm > 0, bnorm, 1.0)
    x, _ = _gmres(matvec, b / safe, M=precond, tol=tol, atol=0.0, restart=20,
                  maxiter=max(maxiter // 20, 2), solve_method="incremental")
    return x * safe, jnp.where(bnorm > 0, jnp.linalg.norm(b / safe - matvec(x)), 0.0)
