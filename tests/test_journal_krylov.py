"""The matrix-free Newton-Krylov solve of the journal bearing (JournalOptions(linear_solver="krylov"))
against the dense LU solve: the same solutions (they solve the same equations; only the
Newton step's linear solve differs) and the same implicit derivatives, forward and reverse,
for every cavitation condition, groove and kind of body; and the preconditioner's
building blocks against dense matrices."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import JournalOptions, journal_bearing
from vjax.films import banded as _banded

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
SLS = vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4)
THESIS = dict(R=0.1, radial_clearance=5e-4, viscosity=1e-3, load=220.0, omega_shaft=-0.4, omega_housing=0.2,
              housing=vjax.Material.sls(1e6, 1e8, 1.0, 0.5))
CASES = {
    "rigid reynolds": dict(R=R, radial_clearance=C, viscosity=ETA, load=1e5, omega_shaft=WJ),
    "rigid sommerfeld": dict(R=R, radial_clearance=C, viscosity=ETA, load=1e5, omega_shaft=WJ,
                             cavitation="sommerfeld"),
    "half sommerfeld, fixed groove": dict(R=R, radial_clearance=C, viscosity=ETA, load=1e5, omega_shaft=WJ,
                                          cavitation="half_sommerfeld", groove="fixed", supply_angle=3.0),
    "jfo, fixed groove": dict(R=R, radial_clearance=C, viscosity=ETA, load=1e5, omega_shaft=WJ, cavitation="jfo",
                              groove="fixed", supply_angle=2.0),
    "thesis HS (soft SLS bore)": THESIS,
    "liner and sleeve": dict(R=R, radial_clearance=C, viscosity=ETA, load=3e5, omega_shaft=WJ,
                             housing=vjax.liner(SLS, 2e-3), shaft=vjax.sleeve(SLS, 3e-3)),
}


# n = 64 with the preconditioner's compliance on 8 modes: the same share of the spectrum left to
# GMRES as the default 32 modes at n = 256 (a quarter), and no nested coarse start to compile
N, MODES = 64, 8


def solve(case, solver, n=N, krylov_modes=MODES, **kw):
    return journal_bearing(**CASES[case], options=JournalOptions(n=n, linear_solver=solver,
                                                                 krylov_modes=krylov_modes, **kw))


@pytest.mark.parametrize("case", list(CASES))
def test_same_solution_as_dense(case):
    dense, krylov = solve(case, "dense"), solve(case, "krylov")
    assert bool(krylov.converged)
    assert abs(float(krylov.eccentricity - dense.eccentricity)) < 1e-9 * max(1.0, abs(float(dense.eccentricity)))
    assert abs(float(krylov.attitude_angle - dense.attitude_angle)) < 1e-9
    scale = float(jnp.max(jnp.abs(dense.pressure)))
    assert np.max(np.abs(np.asarray(krylov.pressure - dense.pressure))) < 1e-8 * scale


@pytest.mark.slow
def test_few_modes_still_converge():
    """With the compliance kept on only its lowest mode (of 32) the preconditioner is poorer;
    GMRES makes up the rest and the solution is the same."""
    a = solve("thesis HS (soft SLS bore)", "krylov", krylov_modes=2)
    b = solve("thesis HS (soft SLS bore)", "dense")
    assert abs(float(a.eccentricity - b.eccentricity)) < 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("case", ["thesis HS (soft SLS bore)", "jfo, fixed groove"])
def test_implicit_derivatives_match_dense(case):
    """d(eps, attitude)/d(viscosity, load) by jacfwd and by grad (the transposed GMRES solve)."""
    base = dict(CASES[case])
    # Newton starts from the steady solution: the derivatives are implicit, at the root, so the
    # start does not enter them
    start = solve(case, "dense")   # the program test_same_solution_as_dense compiled (same options)

    def out(params, solver):
        kw = dict(base, viscosity=params[0], load=params[1])
        s = journal_bearing(**kw, initial=start, options=JournalOptions(n=N, linear_solver=solver, krylov_modes=MODES))
        return jnp.stack([s.eccentricity, s.attitude_angle])

    @jax.jit
    def krylov_derivatives(q):
        """Forward mode (the Jacobian) and reverse mode (the transpose of the same linearization,
        what jax.grad runs: the transposed GMRES solve) from one solve in one program."""
        y, linear = jax.linearize(lambda q: out(q, "krylov"), q)
        (g,) = jax.linear_transpose(linear, q)(jnp.zeros_like(y).at[0].set(1.0))
        return jax.vmap(linear, out_axes=1)(jnp.eye(q.shape[0], dtype=q.dtype)), g

    p = jnp.array([base["viscosity"], base["load"]])
    # jitted: traced and compiled as one program each, not op by op
    Jd = np.asarray(jax.jit(jax.jacfwd(lambda q: out(q, "dense")))(p))
    Jk, gk = (np.asarray(a) for a in krylov_derivatives(p))
    assert np.allclose(Jk, Jd, rtol=1e-7, atol=0)
    assert np.allclose(gk, Jd[0], rtol=1e-7, atol=0)


@pytest.mark.slow
def test_banded_blocks_against_dense():
    rng = np.random.default_rng(1)
    for n in (9, 10, 11):                      # n mod 3 = 0, 1, 2: the colouring's wrap-around
        lower, diag, upper = rng.normal(size=(3, n))
        T = np.diag(diag + 4) + np.diag(lower[1:], -1) + np.diag(upper[:-1], 1)
        T[0, -1], T[-1, 0] = lower[0], upper[-1]
        fn = lambda x: jnp.asarray(T) @ x + 0.1 * x**3
        x = jnp.asarray(rng.normal(size=n))
        J = np.asarray(jax.jacfwd(fn)(x))
        d = _banded.cyclic_diagonals(fn, x)
        v = rng.normal(size=(n, 2))
        assert np.allclose(np.asarray(_banded.cyclic_matvec(d, jnp.asarray(v))), J @ v, atol=1e-12)
        U, V = rng.normal(size=(2, n, 3))
        e = np.eye(n)
        Uc = np.concatenate([U, np.stack([d[0][0] * e[0], d[2][-1] * e[-1]], 1)], 1)
        Vc = np.concatenate([V, np.stack([e[-1], e[0]], 1)], 1)
        solve, solve_t = _banded.woodbury(d, jnp.asarray(Uc), jnp.asarray(Vc))
        M = J + U @ V.T
        b = rng.normal(size=n)
        assert np.allclose(np.asarray(solve(jnp.asarray(b))), np.linalg.solve(M, b), atol=1e-10)
        assert np.allclose(np.asarray(solve_t(jnp.asarray(b))), np.linalg.solve(M.T, b), atol=1e-10)
