"""The restricted solves of the contact solver on a window of the ring (contact arcs of at
most n/8 elements): the arc finder against brute force, and the windowed solves against a
dense LAPACK solve of M_AA, alone and under vmap with arcs of different lengths."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax.contact import solve as contact

N = 512


def _mask(*runs, n=N):
    """Boolean mask with the circular runs (start, length) set."""
    m = np.zeros(n, bool)
    for start, length in runs:
        m[(start + np.arange(length)) % n] = True
    return m


def _shortest_run(mask):
    """Brute force: the shortest circular run (start, length) that holds every True."""
    n = mask.size
    # rolled[start, k] = mask[(start + k) % n]: the run (start, length) holds every True iff
    # rolled[start, length:] has none (every start checked at once: an all-True mask tries
    # all n^2 runs, which one setdiff1d per run made a 46 s test)
    rolled = mask[(np.arange(n)[:, None] + np.arange(n)) % n]
    for length in range(1, n + 1):
        holds = ~rolled[:, length:].any(axis=1)
        if holds.any():
            return int(np.argmax(holds)), length


@pytest.mark.parametrize("runs", [[(10, 5)], [(N - 3, 7)], [(0, 1)], [(N - 1, 1)], [(5, 3), (40, 2)],
                                  [(N - 20, 4), (6, 9)], [(0, N)]])
def test_arc_is_the_shortest_run_holding_every_active_element(runs):
    mask = _mask(*runs)
    start, length = contact._arc(jnp.asarray(mask))
    want_start, want_length = _shortest_run(mask)
    assert int(length) == want_length
    assert want_length == N or int(start) == want_start


def _operator():
    m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)
    return vjax.ring_operator("hole", m, 0.08, N, 30.0)   # viscoelastic: M is not symmetric


def _dense_solve(op, mask, rhs):
    M = np.asarray(op.dense())
    x = np.zeros(N)
    x[mask] = np.linalg.solve(M[np.ix_(mask, mask)], np.asarray(rhs)[mask])
    return x


@pytest.mark.parametrize("runs, on_window", [([(N - 10, 25)], True), ([(200, 64)], True), ([(200, 65)], False),
                                              ([(0, 200)], False), ([(30, 10), (490, 5)], True)])
def test_windowed_restricted_solve_equals_the_dense_solve(runs, on_window):
    op = _operator()
    system = contact._system(op, True)
    mask = _mask(*runs)
    rhs = jnp.asarray(np.random.default_rng(0).standard_normal((2, N)))
    start, length = contact._arc(jnp.asarray(mask))
    assert system.window[0].n == N // 4 and (int(length) <= N // 8) == on_window
    opts = vjax.ContactOptions(krylov_tol=1e-13, krylov=200)
    x, rel = jax.jit(lambda a, b: contact._restricted_solve(system, a, b, opts))(jnp.asarray(mask), rhs)
    assert float(rel) < 1e-12
    for row, b in zip(np.asarray(x), rhs):
        want = _dense_solve(op, mask, b)
        np.testing.assert_allclose(row, want, rtol=0, atol=1e-10 * np.max(np.abs(want)))


def test_windowed_solve_under_vmap_matches_each_members_dense_and_lone_solve():
    """A batch of two short arcs (solved on the window) and then the same with a long one
    (on the whole ring): every member's solution equals its dense solve, and its solve
    alone (the batch does not change a member's path: sweeps split over processes agree)."""
    op = _operator()
    system = contact._system(op, True)
    masks = np.stack([_mask((N - 10, 25)), _mask((100, 300)), _mask((200, 60))])
    rhs = jnp.asarray(np.random.default_rng(1).standard_normal((3, N)))
    opts = vjax.ContactOptions(krylov_tol=1e-13, krylov=200)
    for members in ([0, 2], [0, 1, 2]):
        x, rel = jax.jit(jax.vmap(lambda a, b: contact._restricted_solve(system, a, b, opts)))(
            jnp.asarray(masks[members]), rhs[jnp.asarray(members)])
        assert np.all(np.asarray(rel) < 1e-12)
        for row, i in zip(np.asarray(x), members):
            want = _dense_solve(op, masks[i], rhs[i])
            np.testing.assert_allclose(row, want, rtol=0, atol=1e-10 * np.max(np.abs(want)))
            alone, _ = contact._restricted_solve(system, jnp.asarray(masks[i]), rhs[i], opts)
            np.testing.assert_allclose(row, alone, rtol=0, atol=1e-14 * np.max(np.abs(want)))
