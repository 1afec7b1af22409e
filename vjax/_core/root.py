"""A scalar root searched upwards for its bracket (internal): secant steps safeguarded by bisection.

For residuals that are expensive (each one a whole scene's solve: a heat balance's r(T) =
T - T*(T), docs/theory.md §19) and known to be <= 0 at the search's floor ``lo``: the root is
the first sign change above it, up to the bound ``hi``. No sign change below ``hi`` is
:data:`~vjax._core.solve.RUNAWAY`. Plain bisection of a known bracket: :func:`.solve.bisect`.
"""
from __future__ import annotations

import jax
import jax.numpy as jnp

from .checks import is_concrete
from .solve import INNER_FAILED, MAX_ITERATIONS, RUNAWAY, SUCCESS, Stats


def rising_root(residual, lo, hi, tol, max_iter):
    """Root of ``residual(x) -> (r, valid)`` on [lo, hi], r(lo) <= 0 expected (r(lo) >= -tol:
    lo is the root).

    Secant steps from the last two points, kept inside the bracket (bisection otherwise) once
    a positive r is known; before that, upwards: the secant's point if it lies ahead, else
    x + 2 (x - lo) + 1 (at least tripling the distance from lo; x in units where 1 is a
    modest step, kelvin for a temperature), up to ``hi``. A point where ``valid`` is False or r
    is not finite closes the bracket from above (the search goes back below it; the secant
    keeps the last good point). Converged when |r| <= tol or the bracket is narrower than tol. Result codes:
    SUCCESS; MAX_ITERATIONS after ``max_iter`` residuals; INNER_FAILED when r(lo) is invalid;
    RUNAWAY when r < 0 at ``hi`` (no root below it). Returns (x, :class:`Stats`: iterations
    counts the residuals, residual is |r| at x).

    No derivative flows through it (wrap it in :func:`.solve.implicit_root`). Outside a trace
    the iterations run in Python (each residual the caller's own compiled program, nothing new
    compiled); under one, in a ``lax.while_loop``."""
    f = jnp.result_type(float)
    lo, hi = jnp.asarray(lo, f), jnp.asarray(hi, f)

    def r_at(x):
        r, valid = residual(x)
        return r, valid & ~jnp.isnan(r)

    r0, v0 = r_at(lo)
    done0 = v0 & (r0 >= -tol)
    x1 = jnp.clip(lo - r0, lo, hi)
    x1 = jnp.where(jnp.isfinite(x1), x1, hi)
    res0 = jnp.where(done0, SUCCESS, jnp.where(v0, MAX_ITERATIONS, INNER_FAILED))
    # carry: k, bracket (a, b), b_known, (xp, rp) the last good point, x the candidate, x found, |r|, result
    carry = (jnp.asarray(1), lo, hi, jnp.asarray(False), lo, r0, x1, lo, jnp.abs(r0), res0)

    def cond(c):
        return (c[-1] == MAX_ITERATIONS) & (c[0] < max_iter)

    def body(c):
        k, a, b, known, xp, rp, x, _, _, _ = c
        r, valid = r_at(x)
        ok = valid & jnp.isfinite(r)
        up = ok & (r < 0)
        a = jnp.where(up, x, a)
        b, known = jnp.where(up, b, x), known | ~up
        success = ok & (jnp.abs(r) <= tol) | ok & known & (b - a <= tol)
        runaway = up & (x >= hi)
        s = x - r * (x - xp) / (r - rp)
        s = jnp.where(ok & jnp.isfinite(rp) & jnp.isfinite(s), s, jnp.nan)
        inside = (s > a) & (s < b)
        bracketed = jnp.where(inside, s, 0.5 * (a + b))
        # no positive r yet: the secant's point if it lies ahead, else at least twice as far from lo
        ahead = jnp.minimum(jnp.where(s > x, s, x + 2.0 * (x - lo) + 1.0), hi)
        nxt = jnp.where(known, bracketed, ahead)
        result = jnp.where(success, SUCCESS, jnp.where(runaway, RUNAWAY, MAX_ITERATIONS))
        xp, rp = jnp.where(ok, x, xp), jnp.where(ok, r, rp)
        return (k + 1, a, b, known, xp, rp, nxt, x, jnp.where(ok, jnp.abs(r), jnp.inf), result)

    if is_concrete((lo, hi, r0)):
        while bool(cond(carry)):
            carry = body(carry)
    else:
        carry = jax.lax.while_loop(cond, body, carry)
    k, *_, x, res, result = carry
    x = jnp.where(done0, lo, x)
    res = jnp.where(done0, jnp.abs(r0), res)
    return x, Stats(k, res, result)
