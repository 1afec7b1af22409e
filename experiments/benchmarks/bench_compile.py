"""Compile-time budget of each scene's common calls, today against a baseline commit.

Each case runs in a new interpreter (nothing compiled yet, no persistent cache), ``repeats``
times; with ``--baseline REF`` each of today's runs is followed by the same case on the code
of git commit REF (a temporary worktree), so that both see the same machine load. Per case
(medians over the repeats):

* ``first_s``: wall time of the first call: tracing, lowering to XLA, XLA compilation, one run;
* ``trace_s``, ``lower_s``, ``compile_s``: the three parts of compiling, summed over every
  function the call compiled (JAX's monitoring events), and ``programs``, how many;
* ``warm_s``: median of five warm calls (same shapes, same parameters);
* ``cpu_s``: CPU time of the first call (less sensitive to other jobs than wall time).

Cases (float64): ``pin`` (thesis pin, n = 512), ``roller`` (9 rollers, n = 256), journal bearings
at n = 256 with the dense Newton step (``journal_rigid``: rigid, Reynolds; ``journal_soft``:
the thesis HS bore, with its nested n = 64 start; ``journal_jfo``: rigid, JFO, fixed groove),
``journal_krylov`` (the HS bore at n = 2048, matrix-free GMRES), ``journal_finite`` and
``journal_finite_256`` (a rigid finite bearing, L/D = 0.5, eps ~ 0.82, on the default 64 x 16
grid and on 256 x 64, which starts from the 64 x 16 solution), ``journal_coefficients`` (rigid,
n = 128, four whirl frequencies) and ``fit`` (the smooth Prony + shift fit of vjax-fit on the
shipped pyvisco example, no files).

    python -m experiments.benchmarks.bench_compile [out_dir] [--baseline REF] [--repeats 3] [--only CASE ...]

Writes ``bench_compile.csv``, ``bench_compile.md`` and ``bench_compile.png`` into
``out_dir`` (default ``experiments/out/bench_compile``).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

from experiments import _common

ROOT = Path(__file__).resolve().parents[2]   # the repository root

SETUP = {
    "pin": ("m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)",
            "vjax.pin_in_hole(m, 0.08, 0.005, 2800.0, omega_shaft=-6.67, options=vjax.PinOptions(n=512)).torque"),
    "roller": ("m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)",
               "vjax.roller_bearing(m, m, 6e-3, 4e-3, 2e-3, 9, 39.0, options=vjax.RollerOptions(n=256)).torque"),
    "journal_rigid": ("", "vjax.journal_bearing(0.05, 5e-5, 0.01, 1e5, omega_shaft=100.0, "
                          "options=vjax.JournalOptions(n=256, linear_solver='dense')).torque"),
    "journal_soft": ("hs = dict(housing=vjax.Material.sls(1e6, 1e8, 1.0, 0.5), omega_shaft=-0.4, omega_housing=0.2)",
                     "vjax.journal_bearing(0.1, 5e-4, 1e-3, 220.0, **hs, "
                     "options=vjax.JournalOptions(n=256, linear_solver='dense')).torque"),
    "journal_jfo": ("", "vjax.journal_bearing(0.05, 5e-5, 0.01, 1e5, omega_shaft=100.0, cavitation='jfo', "
                        "groove='fixed', supply_angle=2.0, options=vjax.JournalOptions(n=256)).torque"),
    "journal_krylov": ("hs = dict(housing=vjax.Material.sls(1e6, 1e8, 1.0, 0.5), omega_shaft=-0.4, omega_housing=0.2)",
                       "vjax.journal_bearing(0.1, 5e-4, 1e-3, 220.0, **hs, "
                       "options=vjax.JournalOptions(n=2048, linear_solver='krylov')).torque"),
    "journal_finite": ("", "vjax.journal_bearing(0.05, 5e-5, 0.01, 1e4, length=0.05, omega_shaft=100.0).torque"),
    "journal_finite_256": ("", "vjax.journal_bearing(0.05, 5e-5, 0.01, 1e4, length=0.05, omega_shaft=100.0, "
                               "options=vjax.FiniteJournalOptions(n=256, m=64)).torque"),
    "journal_coefficients": ("", "vjax.journal_coefficients(0.05, 5e-5, 0.01, 2e4, [0.0, 50.0, 100.0, 200.0], "
                                 "omega_shaft=100.0, options=vjax.JournalOptions(n=128)).stiffness"),
    "fit": ("from fitting import calibrate\nfrom fitting.measurements import dma\ndata = dma.default_data('pyvisco')",
            "calibrate(data, 25.0)[0].Einf"),
}
CASES = tuple(SETUP)

# the probe: run in a new interpreter with the tree under test first on the import path
PROBE = r'''
import collections, json, resource, statistics, sys, time
import jax
jax.config.update("jax_enable_x64", True)
from jax import monitoring
events = collections.defaultdict(float)
count = [0]
def listen(event, duration, **kw):
    events[event] += duration
    count[0] += event == "/jax/core/compile/backend_compile_duration"
monitoring.register_event_duration_secs_listener(listen)
import vjax
{setup}
cpu = lambda: sum(resource.getrusage(resource.RUSAGE_SELF)[:2])
c0, t0 = cpu(), time.perf_counter()
jax.block_until_ready({call})
first, first_cpu = time.perf_counter() - t0, cpu() - c0
compiled = dict(events), count[0]
warm = []
for _ in range(5):
    t0 = time.perf_counter()
    jax.block_until_ready({call})
    warm.append(time.perf_counter() - t0)
e, programs = compiled
print(json.dumps(dict(first_s=first, cpu_s=first_cpu, trace_s=e.get("/jax/core/compile/jaxpr_trace_duration", 0.0),
                      lower_s=e.get("/jax/core/compile/jaxpr_to_mlir_module_duration", 0.0),
                      compile_s=e.get("/jax/core/compile/backend_compile_duration", 0.0), programs=programs,
                      warm_s=statistics.median(warm))))
'''
FIELDS = ("first_s", "trace_s", "lower_s", "compile_s", "programs", "cpu_s", "warm_s")


def probe(case: str, tree: Path) -> dict:
    """One fresh-interpreter measurement of ``case`` on the code in ``tree``."""
    setup, call = SETUP[case]
    code = PROBE.format(setup=setup, call=call)
    env = dict(os.environ, PYTHONPATH=str(tree), VJAX_NO_CACHE="1", OPENBLAS_NUM_THREADS="1")
    env.pop("JAX_COMPILATION_CACHE_DIR", None)
    p = subprocess.run([sys.executable, "-c", code], cwd=tree, env=env, capture_output=True, text=True)
    if p.returncode:
        raise RuntimeError(f"{case} failed on {tree}:\n{p.stderr[-2000:]}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(out_dir="experiments/out/bench_compile", baseline=None, repeats=3, only=None):
    cases = only or CASES
    unknown = set(cases) - set(CASES)
    if unknown:
        raise ValueError(f"only: unknown cases {sorted(unknown)}; choose from {CASES}")
    if repeats < 1:
        raise ValueError(f"repeats must be >= 1, got {repeats}")
    trees = {"today": ROOT}
    with (_common.worktree_at(baseline) if baseline else contextlib.nullcontext()) as base_tree:
        if baseline:
            trees[baseline] = Path(base_tree)
        samples = {(case, label): [] for case in cases for label in trees}
        for r in range(repeats):
            for case in cases:
                for label, tree in trees.items():
                    s = probe(case, tree)
                    samples[case, label].append(s)
                    print(f"[{r + 1}/{repeats}] {case:22s} {label:>10s}: first {s['first_s']:6.2f} s "
                          f"(XLA {s['compile_s']:5.2f} s, {s['programs']} programs), warm {s['warm_s'] * 1e3:8.2f} ms",
                          flush=True)
    rows = []
    for case in cases:
        for label in trees:
            med = {f: statistics.median(s[f] for s in samples[case, label]) for f in FIELDS}
            rows.append([case, label] + [med[f] for f in FIELDS])
    header = ["case", "code"] + list(FIELDS)
    out = Path(out_dir)
    comments = [f"medians of {repeats} fresh interpreters per case and code; {_common.device_note()}",
                f"load average at the end: {os.getloadavg()[0]:.2f}",
                "seconds; compile parts summed over every program the first call compiled"]
    _common.write_csv(out / "bench_compile.csv", header, rows, comments)
    table = _common.format_table(["case", "code", "first call s", "trace s", "lower s", "XLA compile s", "programs",
                                  "CPU s", "warm ms"],
                                 [[r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8] * 1e3] for r in rows])
    _common.atomic_write_text(out / "bench_compile.md", "\n".join(f"<!-- {c} -->" for c in comments) + "\n\n"
                              + table + "\n")
    print(table)
    _plot(rows, list(trees), out / "bench_compile.png")
    return rows


def _plot(rows, labels, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    cases = list(dict.fromkeys(r[0] for r in rows))
    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.8 / len(labels)
    for j, label in enumerate(labels):
        first = [next(r[2] for r in rows if r[0] == c and r[1] == label) for c in cases]
        xla = [next(r[5] for r in rows if r[0] == c and r[1] == label) for c in cases]
        x = np.arange(len(cases)) + j * width
        ax.bar(x, first, width, label=f"{label}: first call", alpha=0.5, color=f"C{j}")
        ax.bar(x, xla, width, label=f"{label}: of which XLA compile", color=f"C{j}")
    ax.set_xticks(np.arange(len(cases)) + 0.4 - width / 2, cases, rotation=30, ha="right")
    ax.set_ylabel("seconds (median, fresh interpreter)")
    ax.set_title("First call of each scene: compile time, today and baseline")
    ax.legend(fontsize=8)
    _common.save_figure(fig, path)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default="experiments/out/bench_compile")
    parser.add_argument("--baseline", help="git commit to compare with (same run, interleaved)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only", nargs="*", choices=CASES)
    a = parser.parse_args()
    _common.enable_x64()
    main(a.out_dir, a.baseline, a.repeats, a.only)
