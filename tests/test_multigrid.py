"""The finite bearing's Newton systems on large grids: GMRES preconditioned by an aggregation
multigrid V-cycle (:mod:`vjax._multigrid`) instead of the exact block solve.

References: the dense Jacobian from jax.jacfwd and its LU solve (independent of the stencil,
the aggregation and the Krylov solve); the Galerkin product P^T A P formed densely.
"""
import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

import vjax
from vjax import _blocks, _multigrid, journal_finite

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
D = 2 * R


def test_multigrid_gmres_solves_the_newton_system(monkeypatch):
    """A rigid finite bearing (L/D = 1, 32 x 32, the half width: 32 x 16 cell unknowns) at the
    solver's rigid estimate, its Newton system solved as on a large grid: the V-cycle with
    three levels (16, 8 and 4 cells across).

    - The coloured stencil of the cell equations is their dense Jacobian (to round-off: each
      entry from a product over several columns), the transposed stencil its transpose, the
      coarse stencil P^T A P for the 2 x 2 aggregation P.
    - The Newton step and the transposed (adjoint) solve of :func:`journal_finite.linear_model`
      equal the dense LU's to 1e-8.
    - GMRES needs few steps: 20 without restart bring the residual below 1e-9 with the V-cycle
      (measured 2e-12), where they leave it above 1e-2 without."""
    monkeypatch.setattr(journal_finite, "EXACT_WIDTH", 8)
    monkeypatch.setattr(_multigrid, "COARSEST_WIDTH", 4)
    W = 0.5 * float(vjax.reference.long_bearing(0.5, R, C, ETA, 0.5 * WJ * (R - C), "reynolds")["load"]) * D
    pr, cfg = journal_finite.setup(R, C, ETA, W, D, omega_shaft=WJ, options=vjax.FiniteJournalOptions(n=32, m=32))
    cfg = dataclasses.replace(cfg, half=True)
    n, k, N = cfg.n, cfg.m // 2, journal_finite._unknowns(cfg)
    full = lambda y: journal_finite.equations(y, pr, cfg)[0]     # noqa: E731
    dense = lambda St, size: jax.jacfwd(lambda v: _multigrid.apply(St, v.reshape(size)).ravel())(  # noqa: E731
        jnp.zeros(size[0] * size[1]))

    @jax.jit
    def run(x, b):
        J = jax.jacfwd(full)(x)
        S = _blocks.stencil(lambda pz: full(jnp.concatenate([pz, x[N:]]))[:N], x[:N], n, k)
        stencils = dense(S, (n, k)), dense(_multigrid.transpose(S), (n, k)), dense(_multigrid.coarsened(S), (n // 2, k // 2))
        solve, solve_t = journal_finite.linear_model(x, pr, cfg)
        M = _multigrid.bordered(S, 2)[0]
        gmres = lambda M_: jax.scipy.sparse.linalg.gmres(lambda v: J @ v, b, M=M_, restart=20, maxiter=1,  # noqa
                                                         tol=0.0, atol=0.0, solve_method="incremental")[0]
        return J, stencils, (solve(b), solve_t(b)), (gmres(M), gmres(None))

    b = jnp.asarray(np.random.default_rng(0).standard_normal(N + 2))
    J, (AS, AT, Ac), (step, adjoint), (twenty, plain) = jax.tree.map(np.asarray, run(journal_finite._guess(pr, cfg), b))
    A = J[:N, :N]
    scale = np.abs(A).max()
    assert np.max(np.abs(AS - A)) < 1e-14 * scale
    assert np.max(np.abs(AT - A.T)) < 1e-14 * scale
    P = np.kron(np.kron(np.eye(n // 2), np.ones((2, 1))), np.kron(np.eye(k // 2), np.ones((2, 1))))
    assert np.max(np.abs(Ac - P.T @ A @ P)) < 1e-13 * scale
    for got, want in ((step, np.linalg.solve(J, b)), (adjoint, np.linalg.solve(J.T, b))):
        assert np.max(np.abs(got - want)) < 1e-8 * np.abs(want).max()
    relres = lambda y: np.linalg.norm(J @ y - b) / np.linalg.norm(b)     # noqa: E731
    assert relres(twenty) < 1e-9
    assert relres(plain) > 1e-2
