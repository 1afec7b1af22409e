"""A Stribeck sweep against today's full-film sweep of the same speeds (issue 43's benchmark).

    python -m experiments.benchmarks.bench_stribeck [out_dir] [--quick] [--repeats 3]

The bearing of issue 43 (R = 25.05 mm, c = 50 um, L/D = 1, eta = 0.03 Pa s, W = 2 kN, no
groove) on 128 x 32 cells, 20 journal speeds from 1e-3 to 1e2 rad/s, warm-started from the
highest down: with rough surfaces (sigma = 1 um, :func:`vjax.stribeck_curve`) and smooth ones
(``roughness=None``, each point from the last converged one; below the speed where the smooth
film would close its points fail, and are timed as they fail). The first sweep of each
includes compiling and is reported apart; the sweep times are medians over ``repeats`` warm
repeats. Prints the calibration line (:mod:`experiments.benchmarks.calibrate`'s workload is
not rerun here: run it beside) and writes ``bench_stribeck.md``.
"""
from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from experiments import _common

_common.enable_x64()

import numpy as np  # noqa: E402

import vjax  # noqa: E402

R, C, ETA, W = 25.05e-3, 50e-6, 0.03, 2000.0
L = 2 * R


def smooth_sweep(speeds, options):
    last, ok = None, 0
    for w in speeds[::-1]:
        r = vjax.journal_bearing(R, C, ETA, W, omega_shaft=float(w), length=L, supply_angle=None, options=options,
                                 initial=last, throw=False)
        if not bool(r.converged) and last is not None:     # a long step: from the rigid estimate instead
            r = vjax.journal_bearing(R, C, ETA, W, omega_shaft=float(w), length=L, supply_angle=None,
                                     options=options, throw=False)
        if bool(r.converged):
            last, ok = r, ok + 1
    return ok


def rough_sweep(speeds, options):
    rough = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
    curve = vjax.stribeck_curve(R, C, ETA, W, speeds, length=L, roughness=rough, supply_angle=None, options=options)
    return int(curve.converged.sum())


def main(out_dir="experiments/out", quick=False, repeats=3):
    out = _common.setup(out_dir) / "bench_stribeck"
    out.mkdir(parents=True, exist_ok=True)
    options = vjax.FiniteJournalOptions(n=64, m=16) if quick else vjax.FiniteJournalOptions(n=128, m=32)
    speeds = np.logspace(-3, 2, 20)
    rows = []
    for name, sweep in (("full film (smooth)", smooth_sweep), ("Stribeck (rough)", rough_sweep)):
        t = time.perf_counter()
        converged = sweep(speeds, options)
        first = time.perf_counter() - t
        times = []
        for _ in range(repeats):
            t = time.perf_counter()
            sweep(speeds, options)
            times.append(time.perf_counter() - t)
        rows.append((name, converged, first, statistics.median(times)))
        print(f"{name}: {converged}/{speeds.size} converged, first sweep {first:.1f} s, "
              f"warm sweep median {statistics.median(times):.2f} s over {repeats}", flush=True)
    ratio = rows[1][3] / rows[0][3]
    grid = f"{options.n} x {options.m}"
    table = _common.format_table(("sweep", "converged", "first sweep (s, compiling)", "warm sweep (s, median)"), rows)
    text = (f"20 speeds 1e-3..1e2 rad/s, {grid} cells, warm-started\n\n{table}\n\n"
            f"Stribeck / full-film warm sweep: {ratio:.2f} (goal: at most 2)\n")
    _common.atomic_write_text(out / "bench_stribeck.md", text)
    print(text)
    return rows


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out_dir", nargs="?", default="experiments/out")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args()
    main(a.out_dir, a.quick, a.repeats)
