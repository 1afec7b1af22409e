"""Block-tridiagonal-plus-low-rank matrices: the direct Newton solve of a film over theta x z (internal).

A finite-volume film on n x k cells ordered theta-major (cell (i, j) at index i k + j) couples
each cell only to its neighbours within one cell in theta and z: its Jacobian is block
tridiagonal, n blocks of k x k, cyclic in theta. The two corner blocks of the ring and the
rows and columns of a few global unknowns (the journal's position) are a low-rank
correction: M = T + U V^T (T block tridiagonal, not cyclic) is solved by the Woodbury
identity with a block Thomas factorization of T (O(n k^3)) and one small factorization.
The blocks of a film's Jacobian are diagonally dominant (M-matrix rows; Fischer-Burmeister
rows are non-negative combinations of such a row and a unit row), so the factorization does
not pivot.
Against a dense LU (O(n^3 k^3)) this is n^2 times cheaper; the Jacobian comes from 9-15
Jacobian-vector products (a colouring of the 3 x 3 neighbourhood), not n k.
"""
from __future__ import annotations

import jax
import jax.numpy as jnp


def stencil(fn, x, n: int, k: int):
    """The 9-point stencil C (3, 3, n, k) of the Jacobian of ``fn`` (R^{nk} -> R^{nk}) at ``x``,
    known to couple cell (i, j) only to cells (i + a mod n, j + b), |a|, |b| <= 1:
    C[a + 1, b + 1, i, j] = dF_ij / dx_(i + a, j + b) (0 where j + b is outside 0..k - 1).
    Columns coloured (i mod 3, j mod 3), the last n mod 3 rings with colours of their own so
    that the wrap-around never mixes two columns in one row's neighbourhood."""
    colour, seeds = stencil_seeds(n, k, x.dtype)
    _, jvp = jax.linearize(fn, x)
    return stencil_from_products(jax.vmap(jvp)(seeds), colour)


def stencil_seeds(n: int, k: int, dtype):
    """The colouring of :func:`stencil`: ``colour`` (n, k), each cell's colour, and ``seeds``
    (colours, n k), the tangents whose products with the Jacobian give the stencil
    (:func:`stencil_from_products`). For a caller that batches them with tangents of its own
    (one copy of the linearized function in the program)."""
    full = n - n % 3
    ci = jnp.concatenate([jnp.arange(full) % 3, 3 + jnp.arange(n - full)])
    colour = ci[:, None] * 3 + jnp.arange(k)[None, :] % 3                   # (n, k)
    ncol = 3 * (3 + n - full)
    return colour, (colour.ravel()[None, :] == jnp.arange(ncol)[:, None]).astype(dtype)


def stencil_from_products(products, colour):
    """The stencil C (3, 3, n, k) from the Jacobian's products (colours, n k) with the seeds of
    :func:`stencil_seeds`."""
    n, k = colour.shape
    columns = products.reshape(-1, n, k)                     # row (i, j) of each colour's sum
    # all nine neighbours in one gather: nine gathers would each get their own copy of the
    # linearized function's last elementwise steps fused in by XLA (nine copies to compile)
    a = jnp.arange(-1, 2)[:, None, None, None]
    i, j = jnp.arange(n)[:, None], jnp.arange(k)[None, :]
    j2 = j + jnp.arange(-1, 2)[None, :, None, None]          # (1, 3, 1, k)
    ok = (j2 >= 0) & (j2 < k)
    return jnp.where(ok, columns[colour[(i + a) % n, jnp.clip(j2, 0, k - 1)], i, j], 0.0)


def stencil_blocks(C):
    """Blocks (lower, diag, upper), each (n, k, k), of the 9-point stencil C (:func:`stencil`):
    lower[i] = dF_i/dx_{i-1}, diag[i] = dF_i/dx_i, upper[i] = dF_i/dx_{i+1} (ring indices mod n),
    each tridiagonal."""
    k = C.shape[3]
    band = lambda c: (jnp.einsum("nj,jl->njl", c[0], jnp.eye(k, k, -1, dtype=C.dtype))     # noqa: E731
                      + jax.vmap(jnp.diag)(c[1]) + jnp.einsum("nj,jl->njl", c[2], jnp.eye(k, k, 1, dtype=C.dtype)))
    return band(C[0]), band(C[1]), band(C[2])


def neighbourhood_blocks(fn, x, n: int, k: int):
    """Blocks (lower, diag, upper), each (n, k, k), of the Jacobian of ``fn`` (R^{nk} -> R^{nk})
    at ``x``, known to couple cell (i, j) only to cells (i + a mod n, j + b), |a|, |b| <= 1
    (:func:`stencil`, :func:`stencil_blocks`)."""
    return stencil_blocks(stencil(fn, x, n, k))


def _mm(a, b):
    """a @ b for small blocks as a fused multiply-add loop: XLA's CPU dot hands each product to
    its thread pool, and hundreds of tiny products in a scan then wait on the pool at every
    step (tens of times slower on a loaded machine)."""
    return jnp.sum(a[..., :, :, None] * b[..., None, :, :], axis=-2)


def _inverse(A):
    """Inverse of a small block by Gauss-Jordan elimination without pivoting, in plain XLA
    loops: the film's blocks (and their Schur complements) are diagonally dominant, and
    LAPACK's small-matrix calls (OpenBLAS threads) stall on a loaded machine."""
    k = A.shape[0]

    def step(i, M):
        row = M[i] / M[i, i]
        return (M - M[:, i, None] * row[None, :]).at[i].set(row)
    return jax.lax.fori_loop(0, k, step, jnp.concatenate([A, jnp.eye(k, dtype=A.dtype)], axis=1))[:, k:]


def _factor(lower, diag, upper):
    """Block Thomas factorization of the non-cyclic block tridiagonal T (lower[0], upper[-1]
    ignored): per block the inverse of the pivot D_i - L_i C_{i-1} and C_i = pivot^-1 U_i."""
    k = diag.shape[1]
    upper = upper.at[-1].set(0.0)

    def step(C_prev, blocks):
        Li, Di, Ui = blocks
        inv = _inverse(Di - _mm(Li, C_prev))
        C = _mm(inv, Ui)
        return C, (inv, C)
    _, (invs, Cs) = jax.lax.scan(step, jnp.zeros((k, k), diag.dtype), (lower.at[0].set(0.0), diag, upper))
    return invs, Cs


def _solve(factors, lower, B):
    """T^-1 B for B of shape (n, k, r), with the factors of :func:`_factor`."""
    invs, Cs = factors
    lower = lower.at[0].set(0.0)

    def forward(Y_prev, blocks):
        inv, Li, Bi = blocks
        Y = _mm(inv, Bi - _mm(Li, Y_prev))
        return Y, Y
    _, Ys = jax.lax.scan(forward, jnp.zeros(B.shape[1:], B.dtype), (invs, lower, B))

    def backward(X_next, blocks):
        C, Y = blocks
        X = Y - _mm(C, X_next)
        return X, X
    _, Xs = jax.lax.scan(backward, jnp.zeros(B.shape[1:], B.dtype), (Cs, Ys), reverse=True)
    return Xs


def bordered_solver(blocks, columns, rows, corner, transposed: bool = False):
    """``b -> J^-1 b`` (``transposed``: ``J^-T b``) for the (n k + g) square matrix

        J = [[T_cyclic, columns], [rows, corner]]

    with T_cyclic the cyclic block tridiagonal of ``blocks`` = (lower, diag, upper) (n, k, k),
    ``columns`` (n k, g), ``rows`` (g, n k), ``corner`` (g, g): the corners of the ring and the
    border as a rank 2k + 2g correction of the non-cyclic T (plus an identity for the border
    unknowns), solved by Woodbury. Factored when called: a program that solves only with J
    (Newton's loop) neither traces nor compiles the factors of J^T."""
    lower, diag, upper = blocks
    n, k, _ = diag.shape
    g = corner.shape[0]
    N = n * k
    dtype = diag.dtype
    # columns of the identity of order N + g (never the whole of it: N^2 entries)
    unit = lambda start, count: jnp.eye(N + g, count, -start, dtype=dtype)     # noqa: E731
    first, last = unit(0, k), unit(N - k, k)                    # selectors of the first, last ring
    # T_cyclic = T + first lower[0] last^T + last upper[n-1] first^T
    U = [jnp.pad(lower[0], ((0, N + g - k), (0, 0))),
         jnp.pad(upper[-1], ((N - k, g), (0, 0)))]
    V = [last, first]
    # the border: T_ext has an identity on the g border unknowns
    U += [jnp.concatenate([columns, corner - jnp.eye(g, dtype=dtype)]), unit(N, g)]
    V += [unit(N, g), jnp.concatenate([rows.T, jnp.zeros((g, g), dtype)])]
    U, V = jnp.concatenate(U, axis=1), jnp.concatenate(V, axis=1)
    if transposed:      # J^T = T^T + V U^T; block (i, i-1) of T^T is upper[i-1]^T, (i, i+1) lower[i+1]^T
        tr = lambda A: jnp.swapaxes(A, 1, 2)     # noqa: E731
        lower, diag, upper = jnp.roll(tr(upper), 1, axis=0), tr(diag), jnp.roll(tr(lower), -1, axis=0)
        U, V = V, U
    fac = _factor(lower, diag, upper)

    def T_solve(B):         # T_ext^-1 B, B (N + g, r)
        r = B.shape[1]
        top = _solve(fac, lower, B[:N].reshape(n, k, r)).reshape(N, r)
        return jnp.concatenate([top, B[N:]])

    Z = T_solve(U)
    lu = jax.scipy.linalg.lu_factor(jnp.eye(U.shape[1], dtype=dtype) + V.T @ Z)

    def solve(b):
        y = T_solve(b[:, None])[:, 0]
        return y - Z @ jax.scipy.linalg.lu_solve(lu, V.T @ y)
    return solve


def ring_solver(blocks, transposed: bool = False):
    """``b -> T^-1 b`` (or ``T^-T b``) for the cyclic block tridiagonal T of ``blocks`` alone
    (:func:`bordered_solver` with no border)."""
    N, dtype = blocks[1].shape[0] * blocks[1].shape[1], blocks[1].dtype
    empty = jnp.zeros((N, 0), dtype)
    return bordered_solver(blocks, empty, empty.T, jnp.zeros((0, 0), dtype), transposed)
