"""Aggregation multigrid for films on n x k cells: the preconditioner of large finite-bearing grids (internal).

A finite-volume film on n x k cells (theta-major, cyclic in theta) couples each cell to its
3 x 3 neighbourhood, so its Jacobian is a 9-point stencil,
C[a + 1, b + 1, i, j] = dF_ij / dx_(i + a mod n, j + b) (:func:`vjax.films.blocks.stencil`). The
exact block solve (:mod:`vjax.films.blocks`) factors it in O(n k^3); this V-cycle costs O(n k)
per application: on each level one sweep of line relaxation along theta (a tridiagonal
solve per axial position) and one along z (per angle), before and after the coarse
correction; coarse levels by Galerkin aggregation (2 x 2 cells into one: piecewise-constant
prolongation P, restriction P^T, coarse stencil P^T A P, itself 9-point, from coloured
products of the linear map); the coarsest level (at most COARSEST_WIDTH cells across, or n
odd) solved exactly by the block solve. It is a fixed linear map: a preconditioner for
GMRES. Applied to A^T, the same cycle on the transposed stencils. A few global unknowns
bordering the film (the journal's position) are left to GMRES (:func:`bordered`).
"""
from __future__ import annotations

import jax
import jax.numpy as jnp

from . import blocks as _blocks

COARSEST_WIDTH = 16      # coarsen while the cells across the width exceed this (and n stays even)


def shifted(v, a: int, b: int):
    """v[i + a mod n, j + b] on an (n, k) array (zero where j + b is outside 0..k - 1)."""
    v = jnp.roll(v, -a, axis=0)
    if b == 0:
        return v
    pad = jnp.zeros_like(v[:, :1])
    return jnp.concatenate([v[:, 1:], pad], axis=1) if b == 1 else jnp.concatenate([pad, v[:, :-1]], axis=1)


def apply(C, v):
    """A v for the stencil C (3, 3, n, k) and v (n, k)."""
    return sum(C[a + 1, b + 1] * shifted(v, a, b) for a in (-1, 0, 1) for b in (-1, 0, 1))


def transpose(C):
    """The stencil of A^T: C^T[a, b, i, j] = C[-a, -b, i + a, j + b]."""
    return jnp.stack([jnp.stack([shifted(C[1 - a, 1 - b], a, b) for b in (-1, 0, 1)]) for a in (-1, 0, 1)])


def _prolong(vc, k: int):
    """P vc: each coarse cell's value on its 2 x 2 fine cells (k fine cells across)."""
    return jnp.repeat(jnp.repeat(vc, 2, axis=0), 2, axis=1)[:, :k]


def _restrict(v):
    """P^T v: the sums over each 2 x 2 aggregate (the last, when k is odd, 2 x 1)."""
    n, k = v.shape
    v = jnp.pad(v, ((0, 0), (0, k % 2)))
    return v.reshape(n // 2, 2, -1, 2).sum(axis=(1, 3))


def coarsened(C):
    """The Galerkin stencil P^T A P of 2 x 2 aggregates ((n / 2, ceil(k / 2)) cells)."""
    _, _, n, k = C.shape
    nc, kc = n // 2, (k + 1) // 2
    galerkin = lambda vc: _restrict(apply(C, _prolong(vc.reshape(nc, kc), k))).ravel()    # noqa: E731
    return _blocks.stencil(galerkin, jnp.zeros(nc * kc, C.dtype), nc, kc)


def _thomas(lower, diag, upper, r):
    """Solves of tridiagonal systems along the last axis (lower[..., 0], upper[..., -1]
    ignored), batched over the others: the Thomas algorithm in two scans. Plain XLA, not
    LAPACK's gtsv: a custom call in the Krylov loop of a large grid stalled XLA:CPU's runtime
    (a grid of 1024 x 128: every thread idle)."""
    move = lambda a: jnp.moveaxis(a, -1, 0)     # noqa: E731
    lower, diag, upper, r = map(move, (lower, diag, upper, r))

    def forward(carry, row):
        c_prev, d_prev = carry
        a, b, c, d = row
        pivot = b - a * c_prev
        c_new, d_new = c / pivot, (d - a * d_prev) / pivot
        return (c_new, d_new), (c_new, d_new)
    zero = jnp.zeros_like(r[0])
    _, (cs, ds) = jax.lax.scan(forward, (zero, zero), (lower, diag, upper, r))

    def backward(x_next, row):
        c, d = row
        x = d - c * x_next
        return x, x
    _, xs = jax.lax.scan(backward, zero, (cs, ds), reverse=True)
    return jnp.moveaxis(xs, 0, -1)


def _relax_theta(C, r):
    """Line relaxation along theta: per axial position, the tridiagonal of the theta
    neighbours (the ring's two corner entries left out) solved for the residual r."""
    return _thomas(C[0, 1].T, C[1, 1].T, C[2, 1].T, r.T).T


def _relax_z(C, r):
    """Line relaxation along z: per angle, the tridiagonal of the axial neighbours."""
    return _thomas(C[1, 0], C[1, 1], C[1, 2], r)


def hierarchy(C):
    """The stencils of the levels, finest first, down to the coarsest (solved exactly)."""
    levels = [C]
    while levels[-1].shape[3] > COARSEST_WIDTH and levels[-1].shape[2] % 2 == 0 and levels[-1].shape[2] >= 8:
        levels.append(coarsened(levels[-1]))
    return levels


def v_cycle(levels):
    """b (n, k) -> the V-cycle's approximation of A^-1 b, A the finest stencil of ``levels``."""
    exact = _blocks.ring_solver(_blocks.stencil_blocks(levels[-1]))

    def cycle(level, b):
        if level == len(levels) - 1:
            return exact(b.ravel()).reshape(b.shape)
        C = levels[level]
        x = _relax_theta(C, b)
        x = x + _relax_z(C, b - apply(C, x))
        x = x + _prolong(cycle(level + 1, _restrict(b - apply(C, x))), b.shape[1])
        x = x + _relax_z(C, b - apply(C, x))
        return x + _relax_theta(C, b - apply(C, x))

    return lambda b: cycle(0, b)


def bordered(C, g: int, transposed: bool = False):
    """The preconditioner ``b -> M b``: the V-cycle of A (``transposed``: of A^T, the cycle of
    the transposed stencils) on the first n k unknowns, the identity on the last g (a matrix
    bordered by g columns and rows differs from the block diagonal of its stencil and an
    identity by rank 2 g at most: GMRES converges in at most 2 g more steps)."""
    _, _, n, k = C.shape
    N = n * k
    cycle = v_cycle(hierarchy(transpose(C) if transposed else C))
    return lambda b: jnp.concatenate([cycle(b[:N].reshape(n, k)).ravel(), b[N:]])
