"""The finite bearing's Newton systems on large grids: GMRES preconditioned by an aggregation
multigrid V-cycle (:mod:`vjax.films.multigrid`) instead of the exact block solve.

References: the dense Jacobian from jax.jacfwd and its LU solve (independent of the stencil,
the aggregation and the Krylov solve); the Galerkin product P^T A P formed densely; scipy's
GMRES with and without the V-cycle as its preconditioner.
"""
import dataclasses

import jax
import jax.numpy as jnp
import numpy as np
import pytest
import scipy.sparse.linalg as spla

import vjax
from vjax.films import blocks as _blocks, multigrid as _multigrid
from vjax.scenes.journal.finite import film as finite_film, setup as finite_setup, steady as finite_steady

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
D = 2 * R


@pytest.mark.slow
def test_multigrid_gmres_solves_the_newton_system(monkeypatch):
    """A rigid finite bearing (L/D = 1, 32 x 32, the half width: 32 x 16 cell unknowns) at the
    solver's rigid estimate, its Newton system solved as on a large grid: the V-cycle with
    three levels (16, 8 and 4 cells across).

    - The coloured stencil of the cell equations is their dense Jacobian A (to round-off: each
      entry from a product over several columns), the transposed stencil A^T, the coarse
      stencil P^T A P for the 2 x 2 aggregation P.
    - The Newton step of :func:`vjax.scenes.journal.finite.film.linear_model` (GMRES with the V-cycle) equals
      the dense LU's to 1e-8.
    - The V-cycle makes GMRES fast, for A and for A^T (the adjoint solve of the implicit
      derivatives): 20 steps without restart bring the residual below 1e-9 (measured 7e-14
      and 1.3e-13), where they leave it above 1e-2 without it (measured 2.6e-2 and 3.3e-2)."""
    monkeypatch.setattr(finite_film, "EXACT_WIDTH", 8)
    monkeypatch.setattr(_multigrid, "COARSEST_WIDTH", 4)
    W = 0.5 * float(vjax.reference.long_bearing(0.5, R, C, ETA, 0.5 * WJ * (R - C), "reynolds")["load"]) * D
    pr, cfg = finite_setup.setup(R, C, ETA, W, D, omega_shaft=WJ, options=vjax.FiniteJournalOptions(n=32, m=32))
    cfg = dataclasses.replace(cfg, half=True)
    n, k, N = cfg.n, cfg.m // 2, finite_film.unknowns(cfg)
    full = lambda y: finite_film.equations(y, pr, cfg)[0]     # noqa: E731
    as_matrix = lambda St, size: jax.jacfwd(lambda v: _multigrid.apply(St, v.reshape(size)).ravel())(  # noqa: E731
        jnp.zeros(size[0] * size[1]))

    @jax.jit
    def run(x, b):
        S = _blocks.stencil(lambda pz: full(jnp.concatenate([pz, x[N:]]))[:N], x[:N], n, k)
        ST = _multigrid.transpose(S)
        matrices = as_matrix(S, (n, k)), as_matrix(ST, (n, k)), as_matrix(_multigrid.coarsened(S), (n // 2, k // 2))
        # the V-cycles as matrices: their columns, applied to the identity
        cycles = [jax.vmap(lambda e: _multigrid.v_cycle(_multigrid.hierarchy(St))(e.reshape(n, k)).ravel())(
            jnp.eye(N)).T for St in (S, ST)]
        return jax.jacfwd(full)(x), matrices, cycles, finite_film.linear_model(x, pr, cfg)[0](b)

    b = np.random.default_rng(0).standard_normal(N + 2)
    J, (AS, AT, Ac), (V, VT), step = jax.tree.map(np.asarray, run(finite_steady._guess(pr, cfg), jnp.asarray(b)))
    A = J[:N, :N]
    scale = np.abs(A).max()
    assert np.max(np.abs(AS - A)) < 1e-14 * scale
    assert np.max(np.abs(AT - A.T)) < 1e-14 * scale
    P = np.kron(np.kron(np.eye(n // 2), np.ones((2, 1))), np.kron(np.eye(k // 2), np.ones((2, 1))))
    assert np.max(np.abs(Ac - P.T @ A @ P)) < 1e-13 * scale
    want = np.linalg.solve(J, b)
    assert np.max(np.abs(step - want)) < 1e-8 * np.abs(want).max()
    for matrix, cycle in ((A, V), (A.T, VT)):
        rhs = b[:N]
        relres = lambda y: np.linalg.norm(matrix @ y - rhs) / np.linalg.norm(rhs)     # noqa: E731
        with_cycle = spla.gmres(matrix, rhs, M=cycle, restart=20, maxiter=1, rtol=0.0, atol=0.0)[0]
        plain = spla.gmres(matrix, rhs, restart=20, maxiter=1, rtol=0.0, atol=0.0)[0]
        assert relres(with_cycle) < 1e-9, relres(with_cycle)
        assert relres(plain) > 1e-2, relres(plain)
