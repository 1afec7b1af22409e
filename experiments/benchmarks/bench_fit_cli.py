"""Wall time of the ``vjax-fit`` command line with JAX's persistent compilation cache.

In one run, as separate processes (``python -m fitting.cli.fit``, what the console script runs),
on the shipped pyvisco example (freq_user_raw.csv, 210 points, T_ref = 25 C, default options,
plots written):

* ``python -c "import vjax, fitting"`` (median of ``repeats``): the floor of any call;
* ``vjax-fit`` with a fresh, empty cache directory (first call: every function compiled and
  stored), then again with the same cache (second call), ``repeats`` times each, each time
  with a new empty cache for the first call;
* the second call again with ``--no-plots`` (the six PNGs: matplotlib's import and drawing);
* ``vjax-fit --no-cache`` (the behaviour before the cache);
* pyvisco's default pipeline on the same data (:func:`experiments.studies.dma_fit.run_pyvisco`), in
  this process, when pyvisco is installed;
* with ``--baseline REF``: the second call of the code at git commit REF (a temporary
  worktree, its own cache), each repeat right after today's second call (the machine's
  speed drifts by more than the difference between versions).

The issue's target: second call <= 3 x the import time. Writes ``bench_fit_cli.csv`` and
``bench_fit_cli.md`` to ``out_dir``. ``quick``: one repeat.

    python -m experiments.benchmarks.bench_fit_cli [--quick] [--baseline REF] [--out-dir experiments/out]
"""
from __future__ import annotations

import argparse
import contextlib
import os
import statistics
import subprocess
import sys
import tempfile
import time

from experiments import _common

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))   # the repository root


def _run(args, env, root=ROOT) -> float:
    """Wall time (s) of one subprocess in ``root``; raises with its stderr if it fails."""
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable] + args, env=env, cwd=root, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode:
        raise RuntimeError(f"{' '.join(args)} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return wall


def _env(cache_home, root=ROOT):
    env = dict(os.environ, XDG_CACHE_HOME=cache_home, PYTHONPATH=root + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop("VJAX_NO_CACHE", None)
    return env


def main(out_dir="experiments/out", quick=False, baseline=None):
    """Run the measurements; returns the rows written."""
    from fitting.measurements import dma
    os.makedirs(out_dir, exist_ok=True)
    print(f"device: {_common.device_note()}", flush=True)
    repeats = 1 if quick else 3
    data = os.path.abspath(dma.default_data("pyvisco"))
    rows = []
    with tempfile.TemporaryDirectory() as work, \
            (_common.worktree_at(baseline) if baseline else contextlib.nullcontext()) as tree:
        fit = ["-m", "fitting.cli.fit", data, "--tref", "25", "--out", os.path.join(work, "m.json")]
        imp = [_run(["-c", "import vjax, fitting"], _env(work)) for _ in range(repeats)]
        first, second, second_np, nocache, second_base = [], [], [], [], []
        if tree:
            _run(fit, _env(os.path.join(work, "cache_base"), tree), tree)   # fills the baseline's cache
        for r in range(repeats):
            cache = os.path.join(work, f"cache{r}")
            first.append(_run(fit, _env(cache)))
            second.append(_run(fit, _env(cache)))
            if tree:
                second_base.append(_run(fit, _env(os.path.join(work, "cache_base"), tree), tree))
            second_np.append(_run(fit + ["--no-plots"], _env(cache)))
            nocache.append(_run(fit + ["--no-cache"], _env(cache)))
        size = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(os.path.join(work, "cache0")) for f in fs)
        files = sum(len(fs) for _, _, fs in os.walk(os.path.join(work, "cache0")))
        from experiments.studies.dma_fit import run_pyvisco
        pv = [run_pyvisco(dma.read(data), 25.0, work) for _ in range(repeats)]
    med = statistics.median
    rows = [("import vjax, fitting", med(imp), min(imp), repeats),
            ("vjax-fit, first call (empty cache)", med(first), min(first), repeats),
            ("vjax-fit, second call (cache filled)", med(second), min(second), repeats),
            ("vjax-fit --no-plots, cache filled", med(second_np), min(second_np), repeats),
            ("vjax-fit --no-cache", med(nocache), min(nocache), repeats)]
    if baseline:
        rows.append((f"vjax-fit, second call, code at {baseline}", med(second_base), min(second_base), repeats))
    if pv[0] is not None:
        w = [p["wall_time"] for p in pv]
        rows.append(("pyvisco fit (in process, no import)", med(w), min(w), repeats))
    ratio = med(second) / med(imp)
    header = ("what", "median_s", "min_s", "repeats")
    comments = [f"shipped pyvisco example, {sys.executable}; cache after one first call: {files} files, "
                f"{size / 1e6:.2f} MB", f"second call / import time = {ratio:.2f} (target <= 3)"]
    if baseline:
        comments.append(f"second call today / at {baseline} = {med(second) / med(second_base):.2f}")
    _common.write_csv(os.path.join(out_dir, "bench_fit_cli.csv"), header, rows, comments=comments)
    md = ["# vjax-fit wall time with the persistent compilation cache", "", *[f"- {c}" for c in comments], "",
          "| what | median (s) | min (s) | repeats |", "|---|---|---|---|"]
    md += [f"| {w} | {m:.2f} | {lo:.2f} | {n} |" for w, m, lo, n in rows]
    _common.atomic_write_text(os.path.join(out_dir, "bench_fit_cli.md"), "\n".join(md) + "\n")
    print(_common.format_table(header, rows))
    for c in comments:
        print(c)
    return rows


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out-dir", default="experiments/out")
    ap.add_argument("--baseline", metavar="REF", help="also time the cached call with the code at this git commit")
    a = ap.parse_args()
    main(a.out_dir, a.quick, a.baseline)
