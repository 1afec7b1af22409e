"""Rough surfaces on a lined finite bearing solved by GMRES (issue 43): the 128 x 32 lined mixed point.

    python -m experiments.benchmarks.bench_mixed_krylov [--repeats 3] [--dense]

The bearing of issue 43 (R = 25.05 mm, c = 50 um, L/D = 1, eta = 0.03 Pa s, W = 2 kN, no groove,
sigma = 1 um) in a 2 mm polymer liner (SLS 1.5/3 GPa, 0.01 s, nu = 0.4), the journal at 0.1 rad/s
(the asperities carry about a third of the load), on 128 x 32 cells: Newton over film cells,
position and one asperity pressure per node (4226 unknowns in the half-width solve), each step
by GMRES (:func:`vjax.scenes.journal.finite.film.linear_model`). Times: the first call
(compiling), then the median of ``repeats`` compiled calls of the cold solve (the rigid
estimate on 64 x 16, its continuation, then 128 x 32 from it) and of a warm-started one (from
the solution at 0.12 rad/s). Then, in a counting pass (its programs traced again, a host
callback per GMRES product), Newton steps and GMRES products per solve on each grid.
``--dense``: the dense LU against GMRES on 64 x 16 (the dense LU's largest grid). Run
:mod:`experiments.benchmarks.calibrate` just before.
"""
from __future__ import annotations

import argparse
import statistics
import time

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402

import vjax  # noqa: E402
import vjax._core.krylov as _krylov  # noqa: E402

R, C, ETA, W = 25.05e-3, 50e-6, 0.03, 2000.0
L = 2 * R
ROUGH = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
LINER = vjax.liner(vjax.Material.sls(1.5e9, 3e9, 0.01, 0.4), 2e-3)
OMEGA = 0.1


def solve(omega, solver="auto", n=128, m=32, **kw):
    r = vjax.journal_bearing(R, C, ETA, W, omega_shaft=omega, length=L, supply_angle=None, housing=LINER,
                             roughness=ROUGH, options=vjax.FiniteJournalOptions(n=n, m=m, linear_solver=solver),
                             **kw)
    jax.block_until_ready(r.eccentricity)
    return r


def timed(fn, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        r = fn()
        times.append(time.perf_counter() - t)
    return r, statistics.median(times), times


def counting():
    """Patch GMRES to count its solves and products per system size (host callbacks)."""
    counts = {}
    plain = _krylov.gmres

    def counted(matvec, b, precond, tol, maxiter):
        size = b.shape[0]
        slot = counts.setdefault(size, {"solves": 0, "products": 0})

        def product(v):
            jax.debug.callback(lambda: slot.__setitem__("products", slot["products"] + 1))
            return matvec(v)
        jax.debug.callback(lambda: slot.__setitem__("solves", slot["solves"] + 1))
        return plain(product, b, precond, tol, maxiter)
    _krylov.gmres = counted
    return counts, lambda: setattr(_krylov, "gmres", plain)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--dense", action="store_true")
    a = ap.parse_args()
    t = time.perf_counter()
    r = solve(OMEGA)
    print(f"first call {time.perf_counter() - t:.1f} s: converged {bool(r.converged)}, eps {float(r.eccentricity):.6f}, "
          f"share {float(r.asperity_share):.4f}, friction coefficient {float(r.friction_coefficient):.5f}, "
          f"{int(r.iterations)} Newton steps on 128 x 32", flush=True)
    r, med, times = timed(lambda: solve(OMEGA), a.repeats)
    print(f"cold solve (compiled): median {med:.2f} s of {[round(x, 2) for x in times]}", flush=True)
    near = solve(0.12)
    solve(OMEGA, initial=near)
    w, med, times = timed(lambda: solve(OMEGA, initial=near), a.repeats)
    print(f"warm-started from 0.12 rad/s: median {med:.2f} s of {[round(x, 2) for x in times]}, "
          f"{int(w.iterations)} Newton steps, |d eps| vs cold {abs(float(w.eccentricity - r.eccentricity)):.1e}",
          flush=True)
    jax.clear_caches()       # the counting pass traces its programs again, with the callbacks
    counts, restore = counting()
    try:
        r = solve(OMEGA)
        cold = {k: dict(v) for k, v in counts.items()}
        counts.clear()
        w = solve(OMEGA, initial=near)
        warm = {k: dict(v) for k, v in counts.items()}
    finally:
        restore()
    for name, c in (("cold", cold), ("warm-started", warm)):
        for size, v in sorted(c.items()):
            # each solve's count includes GMRES's final residual product
            print(f"{name}: {size} unknowns: {v['solves']} GMRES solves, {v['products']} products, "
                  f"{v['products'] / max(v['solves'], 1) - 1:.1f} iterations per solve", flush=True)
    if a.dense:          # on 64 x 16, the largest grid the dense LU was used on
        for solver in ("dense", "krylov"):
            near = solve(0.12, solver, 64, 16)
            solve(OMEGA, solver, 64, 16, initial=near)
            cold, med_c, _ = timed(lambda: solve(OMEGA, solver, 64, 16), a.repeats)
            warm, med_w, _ = timed(lambda: solve(OMEGA, solver, 64, 16, initial=near), a.repeats)
            print(f"64 x 16 {solver}: cold solve median {med_c:.2f} s ({int(cold.iterations)} Newton steps), "
                  f"warm-started {med_w:.3f} s ({int(warm.iterations)} steps), eps {float(cold.eccentricity):.12f}",
                  flush=True)

if __name__ == "__main__":
    main()
