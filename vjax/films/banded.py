"""Tridiagonal-plus-low-rank matrices: the preconditioner of the matrix-free bearing Newton (internal).

A finite-volume film on a ring couples each cell to its two neighbours (a cyclic tridiagonal
Jacobian); everything else - the ring's two corner entries, the bodies' compliance
truncated to its lowest Fourier modes, the rows and columns of a few global unknowns - is a
low-rank correction. ``M = T + U V^T`` (T tridiagonal, not cyclic; U, V n x k) is solved by
the Woodbury identity with k + 1 tridiagonal solves and one k x k factorization, O(n k).
"""
from __future__ import annotations

import jax
import jax.numpy as jnp


def cyclic_diagonals(fn, x):
    """Diagonals (lower, diag, upper) of the Jacobian of ``fn`` (R^n -> R^n) at ``x``, known to
    be cyclic tridiagonal: lower[i] = J[i, i - 1], upper[i] = J[i, i + 1] (indices mod n). Five
    or fewer Jacobian-vector products: columns coloured i mod 3, the last n mod 3 columns
    with colours of their own so that the wrap-around never mixes two columns in one row."""
    n = x.shape[0]
    full = n - n % 3
    colour = jnp.concatenate([jnp.arange(full) % 3, 3 + jnp.arange(n - full)])
    seeds = (colour[None, :] == jnp.arange(3 + n - full)[:, None]).astype(x.dtype)
    _, jvp = jax.linearize(fn, x)
    columns = jax.vmap(jvp)(seeds)                      # (colours, n): sum of coloured columns
    rows = jnp.arange(n)
    entry = lambda shift: columns[colour[(rows + shift) % n], rows]
    return entry(-1), entry(0), entry(1)


def cyclic_matvec(diagonals, v):
    """Product of the cyclic tridiagonal matrix with ``diagonals`` and v (n,) or (n, k)."""
    lower, diag, upper = (d.reshape(d.shape + (1,) * (v.ndim - 1)) for d in diagonals)
    return lower * jnp.roll(v, 1, axis=0) + diag * v + upper * jnp.roll(v, -1, axis=0)


def woodbury(diagonals, U, V):
    """``(solve, solve_transpose)`` for M = T + U V^T, T the tridiagonal with ``diagonals``
    (lower[0] and upper[-1] are ignored: put a ring's corners into U, V)."""
    lower, diag, upper = diagonals
    dl, du = lower.at[0].set(0.0), upper.at[-1].set(0.0)
    # the transpose of T: its sub-diagonal is T's super-diagonal, shifted
    dl_t, du_t = jnp.roll(du, 1).at[0].set(0.0), jnp.roll(dl, -1).at[-1].set(0.0)
    tri = lambda a, b, c, B: jax.lax.linalg.tridiagonal_solve(a, b, c, B)
    Z = tri(dl, diag, du, U)
    lu = jax.scipy.linalg.lu_factor(jnp.eye(U.shape[1], dtype=U.dtype) + V.T @ Z)

    def solve(b):
        y = tri(dl, diag, du, b[:, None])[:, 0]
        return y - Z @ jax.scipy.linalg.lu_solve(lu, V.T @ y)

    def solve_transpose(b):
        # (T + U V^T)^T = T^T + V U^T; its capacitance matrix is the transpose of the above
        Zt = tri(dl_t, diag, du_t, V)
        y = tri(dl_t, diag, du_t, b[:, None])[:, 0]
        return y - Zt @ jax.scipy.linalg.lu_solve(lu, U.T @ y, trans=1)

    return solve, solve_transpose
