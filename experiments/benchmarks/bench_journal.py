"""Work-precision benchmark of :func:`vjax.journal_bearing` (issue 5).

Run::

    PYTHONPATH=. python -m experiments.benchmarks.bench_journal [out_dir] [--quick]

Case: the thesis's HS bearing (Fig. 3.5 HS, periodic memory): R_B = 0.1 m, c = 5e-4 m,
eta = 1e-3 Pa s, SLS E0 = 1 MPa, Einf = 100 MPa, tau = 1 s, nu = 0.5, F~ = 2.2e-3,
omega~_B = 0.2, omega~_J = -0.4. For each n:

- ``compile_s``: first call (tracing + XLA compilation + one solve);
- ``point_s``: median warm time of one load point from the default (cold) start;
- ``sweep_s``: warm time of a 20-speed sweep omega~_J = -0.4 ... -10 (geometric), each
  point started from the previous solution (``initial=``), and ``sweep_point_s`` = sweep_s/20;
- errors of eps, attitude angle, bearing torque and minimum film against the same problem
  on a 4x finer grid (started from the coarse solution, interpolated).

Scaling (``bench_journal_scaling.csv``, ``bench_journal_scaling.png``): warm time per solve
(median, compile apart) and Newton steps for n = 256 ... 8192 with each Newton linear solve,
dense LU (n <= 2048) and matrix-free GMRES (``linear_solver="krylov"``), for the HS case and
a rigid bearing (R = 50 mm, c = 50 um, eta = 0.01 Pa s, 1e5 N/m, 100 rad/s), and the ratio of
GMRES at n = 4096 to dense LU at n = 512.

Target of the issue: one point at n = 512 under 1 s warm on the 2-core CPU. The machine's
load average is written next to the timings (other jobs share the two cores).
"""
from __future__ import annotations

import os

# jaxlib's dense LU (the Newton step) calls the OpenBLAS bundled with scipy; its threads
# oversubscribe a loaded 2-core machine (a 514 x 514 solve: 7 ms single-threaded, 60-130 ms
# threaded). Only effective before numpy/scipy/jax are imported.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
import time

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

RB, C, ETA = 0.1, 5e-4, 1e-3
SLS = vjax.Material.sls(1e6, 1e8, 1.0, 0.5)
LOAD = 2.2e-3 * 1e6 * RB
WB, WJ = 0.2, -0.4


def _point(n, omega_j=WJ, initial=None, tol=None, throw=True):
    return vjax.journal_bearing(RB, C, ETA, LOAD, housing=SLS, omega_shaft=omega_j, omega_housing=WB, initial=initial,
                                options=vjax.JournalOptions(n=n, tol=tol), throw=throw)


def _sweep(n, speeds):
    prev, out = None, []
    for wj in speeds:
        prev = _point(n, wj, prev)
        out.append(prev)
    return out


def _rigid(n, solver):
    return vjax.journal_bearing(0.05, 5e-5, 0.01, 1e5, omega_shaft=100.0,
                                options=vjax.JournalOptions(n=n, linear_solver=solver))


def scaling(out, quick):
    """Time per solve against n for the dense and the matrix-free Newton step."""
    import matplotlib.pyplot as plt
    ns = (128, 256) if quick else (256, 512, 1024, 2048, 4096, 8192)
    dense_max = 256 if quick else 2048
    repeats = 2 if quick else 3
    rows, times = [], {}
    for case, fn in (("HS thesis", lambda n, s: _point_with(n, s)), ("rigid", _rigid)):
        for solver in ("dense", "krylov"):
            for n in ns:
                if solver == "dense" and n > dense_max:
                    continue
                first, warm = _common.time_fn(lambda: fn(n, solver), repeats=repeats)
                sol = fn(n, solver)
                times[case, solver, n] = warm
                rows.append([case, solver, n, first, warm, int(sol.iterations), float(sol.eccentricity)])
                print(f"scaling {case} {solver} n={n}: first {first:.2f} s, warm {warm:.4f} s, "
                      f"{int(sol.iterations)} Newton steps", flush=True)
    header = ["case", "linear_solver", "n", "first_call_s", "warm_s", "newton_steps", "eps"]
    big, small = (ns[-1], ns[0]) if quick else (4096, 512)
    ratios = {case: times[case, "krylov", big] / times[case, "dense", small] for case in ("HS thesis", "rigid")}
    comments = [f"warm: median of {repeats} calls; first: compile + one call (nested coarse levels included)",
                *(f"{case}: krylov n={big} / dense n={small} = {r:.2f}" for case, r in ratios.items())]
    _common.write_csv(out / "bench_journal_scaling.csv", header, rows, comments=comments)
    fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
    for (case, style) in (("HS thesis", "-"), ("rigid", "--")):
        for solver, color in (("dense", "C0"), ("krylov", "C1")):
            pts = sorted((n, t) for (c, s_, n), t in times.items() if c == case and s_ == solver)
            ax.loglog(*zip(*pts), style, marker="o", color=color, label=f"{case}, {solver}")
    ax.set_xticks(ns, [str(n) for n in ns])
    ax.xaxis.set_minor_formatter(plt.NullFormatter())
    ax.set_xlabel("elements n")
    ax.set_ylabel("warm time per solve (s)")
    ax.set_title("journal_bearing: dense LU vs matrix-free GMRES Newton steps", fontsize=10)
    ax.legend(fontsize=8)
    _common.save_figure(fig, out / "bench_journal_scaling.png")
    text = _common.print_table(header, rows, title="journal_bearing scaling") + "\n" + "\n".join(comments[1:])
    print(text)
    return text


def _point_with(n, solver):
    return vjax.journal_bearing(RB, C, ETA, LOAD, housing=SLS, omega_shaft=WJ, omega_housing=WB,
                                options=vjax.JournalOptions(n=n, linear_solver=solver))


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    print(f"device: {_common.device_note()}", flush=True)
    ns = (64, 128) if quick else (256, 512, 1024)
    speeds = list(-np.geomspace(0.4, 10.0, 20))
    repeats = 2 if quick else 3
    rows = []
    for n in ns:
        first, point = _common.time_fn(lambda: _point(n), repeats=repeats)
        sol = _point(n)
        _sweep(n, speeds[:2])                      # compile the warm-started variant
        t0 = time.perf_counter()
        sweep = _sweep(n, speeds)
        jax.block_until_ready(sweep[-1])
        sweep_s = time.perf_counter() - t0
        m = 4 * n
        ref = _point(m)            # a cold start on 4n: nested from n, C1-interpolated
        errs = dict(
            eps=abs(float(sol.eccentricity - ref.eccentricity)),
            attitude=abs(float(sol.attitude_angle - ref.attitude_angle)),
            torque_rel=abs(float(sol.torque / ref.torque - 1)),
            hmin_rel=abs(float(sol.min_film / ref.min_film - 1)))
        rows.append([n, first, point, sweep_s, sweep_s / len(speeds), int(sol.iterations),
                     sum(int(s.iterations) for s in sweep), errs["eps"], errs["attitude"],
                     errs["torque_rel"], errs["hmin_rel"], os.getloadavg()[0]])
        print(f"n={n}: compile {first:.2f} s, point {point:.3f} s, sweep {sweep_s:.2f} s, "
              f"errors {errs}", flush=True)
    header = ["n", "compile_s", "point_s", "sweep_s", "sweep_point_s", "point_iterations",
              "sweep_iterations", "err_eps", "err_attitude_rad", "err_torque_rel", "err_hmin_rel",
              "loadavg_1min"]
    _common.write_csv(out / "bench_journal.csv", header, rows,
                      comments=["HS thesis case (Fig. 3.5), periodic memory; errors against a 4x finer grid",
                                f"{len(speeds)}-speed sweep omega~_J = -0.4 ... -10 with warm starts",
                                f"cpu count {os.cpu_count()}"])
    text = _common.print_table(header, rows, title="journal_bearing work-precision (HS thesis case)")
    text += "\n" + scaling(out, quick)
    _common.atomic_write_text(out / "bench_journal.txt", text + "\n")
    return text


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
