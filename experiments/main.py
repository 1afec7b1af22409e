"""The main job: calibrate the shipped DMA data, reproduce the thesis's figures, write a summary.

    python -m experiments.main [--out experiments/out] [--quick] [--only STAGE ...] [--jobs N] [--no-cache]

Stages (each writes PNG + CSV into ``<out>/<stage>/`` and returns a short text):

1. ``calibration``: Prony series + shift law fitted to the shipped pyvisco DMA example
   (``fitting/data/pyvisco``), saved as ``material.json`` with its plots;
2. ``foundation``: material laws and the ring Green's functions (Figs. 2.3, A.4, A.6);
3. ``pin``: pin in a hole (Figs. 2.5-2.10);
4. ``roller``: needle roller bearing (Figs. 2.14-2.21);
5. ``journal``: visco-elastohydrodynamic journal bearing (Figs. 3.4-3.8);
6. ``bodies``: bushings and liners of finite thickness against the infinite plane (the
   thesis's test bearing as built, a pin in a thin bushing, a water-lubricated journal bearing);
7. ``dynamics``: journal bearings' stiffness and damping versus whirl frequency (rigid against
   the closed forms, a polymer liner, the thesis case) and the oil-whirl threshold;
8. ``bores``: journal bearings in a nearly rigid and a soft Prony bore, the soft one over two
   decades of speed and load: where the solver converges, in how many steps, and its message
   where the bore's deformation leaves small-strain theory;
9. ``stribeck``: a finite journal bearing with rough surfaces from boundary friction through
   mixed lubrication to a full film, rigid and lined, against today's smooth film;
10. ``thermal``: a lined journal bearing at its own temperature against the isothermal one
    (effective temperature and friction against speed), and a film's temperature map.

``<out>/summary.md`` opens with what was computed and a table of every stage's checks
(value, reference, tolerance, PASS/FAIL), defines the symbols, then gives each stage's
description, figures and output. The job exits with status 1 if a check fails; a stage that
raises stops it (files are written atomically, so nothing half-written is left behind).

The stages run side by side, ``--jobs`` at a time (default: one per CPU), longest first, each
printing its lines prefixed with its name; they share vjax's persistent compilation cache
unless ``--no-cache``. A stage is XLA compiling its solvers (one core's work) and running
them, each stage with its own XLA flags (:data:`STAGE_XLA_FLAGS`), in a worker process that
runs stage after stage of the same flags on a core of its own; the workers are forked from a
server that has imported jax, vjax and matplotlib once. The full run took 54.4 s wall from an
empty cache on a quiet 2-core machine whose calibration total
(``experiments/benchmarks/calibrate.py``) was 5.0-5.2 s around it (docs/benchmarks.md,
"2026-11-28 (evening: ...)").
"""
from __future__ import annotations

import os

# One BLAS thread per process: stages run side by side, one per core, and the OpenBLAS that
# jaxlib's dense LU calls would otherwise oversubscribe the cores (10-20x slower solves).
# Before numpy loads it; the stages' worker processes inherit it.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
# float64 and matplotlib's file backend from the start: the workers' fork server imports jax, vjax
# and pyplot before a stage could turn them on (vjax warns on import without float64)
os.environ.setdefault("JAX_ENABLE_X64", "1")
os.environ.setdefault("MPLBACKEND", "Agg")

import argparse  # noqa: E402
import atexit
import concurrent.futures
from concurrent.futures.process import BrokenProcessPool
import gc
import importlib
import io
import multiprocessing
import sys
import time
from pathlib import Path

from experiments import _common

STAGES = [
    ("calibration", "experiments.main", "calibration_stage"),
    ("foundation", "experiments.figures.foundation_figures", "main"),
    ("pin", "experiments.figures.pin_figures", "main"),
    ("roller", "experiments.figures.roller_figures", "main"),
    ("journal", "experiments.figures.journal_figures", "main"),
    ("bodies", "experiments.figures.bodies_figures", "main"),
    ("dynamics", "experiments.figures.journal_dynamics", "main"),
    ("bores", "experiments.figures.journal_bores", "stage"),
    ("stribeck", "experiments.figures.stribeck_figures", "stage"),
    ("thermal", "experiments.figures.thermal_figures", "stage"),
]
# the order stages start in when they run side by side: longest first (wall seconds of each stage
# beside another, empty cache, its STAGE_XLA_FLAGS, a quiet machine at calibration 5.0-5.2 s:
# bodies 17, journal 16, roller 16, stribeck 13, thermal 13, dynamics 12, pin 8, bores 4,
# foundation 3), so that the last to finish are short ones; calibration first, bodies after it (it
# waits for it; roller, without XLA flags, starts beside calibration while the flags are probed).
# On two cores the slots then run calibration, journal, stribeck, dynamics, pin and roller,
# bodies, thermal, bores, foundation: 52 and 54 s of stages; the first four after calibration
# share one worker (one flag set). A stage of STAGES not named here starts right after
# calibration (its cost unknown: early, so that it does not finish last).
ORDER = ("calibration", "journal", "bodies", "roller", "stribeck", "dynamics", "thermal", "pin", "bores",
         "foundation")
PRIORITY = ([s for s in STAGES if s[0] == ORDER[0]] + [s for s in STAGES if s[0] not in ORDER]
            + [s for name in ORDER[1:] for s in STAGES if s[0] == name])
DEPENDS = {"bodies": ("calibration",)}    # bodies reads the calibrated material.json


def calibration_stage(out_dir, quick=False):
    """Fit the shipped pyvisco example (tensile, 21 temperatures) at T_ref = 25 C."""
    from fitting import calibrate
    from fitting.measurements import dma
    material, shift, report = calibrate(dma.default_data("pyvisco"), 25.0, out_dir, stem="material",
                                        max_iter=60 if quick else 300)
    text = (f"material written to {Path(out_dir) / 'material.json'}\n"
            f"E0 = {float(material.E0):.4g} Pa, Einf = {float(material.Einf):.4g} Pa, "
            f"{material.times.shape[0]} Prony terms\n{report.table()}")
    print(text)
    e = report.errors
    checks = (
        _common.Check("storage modulus: median abs(log10(fit / measured)) on the raw points", e["storage_median"], 0.01, 0,
                      "the DMA data (1 decade = factor 10)", "max"),
        _common.Check("loss modulus: median abs(log10(fit / measured)) on the raw points", e["loss_median"], 0.03, 0,
                      "the DMA data", "max"),
        _common.Check("local extrema of the fitted loss modulus over the data's reduced frequencies",
                      float(e["loss_extrema"]), 3.0, 0, "one loss peak and a secondary relaxation at most", "max"),
        _common.Check("end-to-end refinement converged (1 = yes)", float(report.converged), 1.0, 0, "solver report", "min"),
    )
    figures = (("material_master.png", "Master curve at 25 C: data coloured by temperature, fitted Prony series"),
               ("material_shift.png", "Shift factors log a_T per temperature with the fitted laws"),
               ("material_residuals.png", "Residuals log10(fit/measured) on the raw points"),
               ("material_spectrum.png", "Relaxation spectrum (Prony moduli versus relaxation times)"))
    about = ("A Prony series and a shift law fitted to the shipped DMA data (pyvisco example, tensile, "
             "21 temperatures), saved as material JSON: relaxation times on a fixed grid at 3 per decade, "
             "smoothness penalty chosen by generalized cross-validation (a loss modulus without ringing), "
             "WLF and Arrhenius fitted next to the chosen law.")
    return _common.StageReport(text, about, checks, figures)


INTRO = """vjax computed the thesis's cases with its boundary-element method on steady-state
viscoelastic Green's functions of circular bodies: a material calibrated from DMA data, the
ring operators, a pin in a hole, a needle roller bearing, a lubricated journal bearing, and
bushings and liners of finite thickness beside the thesis's infinite plane.
Each stage below says what it computes, then lists its checks (value, what it is compared
with, tolerance, PASS or FAIL), its figures with their cases, and its raw output. The table
right below collects every check; the job exits with status 1 if one fails.
Conventions and equations: docs/conventions.md, docs/theory.md (in the repository)."""

SYMBOLS = """| symbol | meaning | unit |
|---|---|---|
| F~ | load over E0 R (R: bore or outer raceway radius) | - |
| omega~ | patch speed relative to the deformable body times the relaxation time tau | - |
| omega~_B, omega~_J | bearing and journal speeds times tau (journal bearing) | - |
| p~ = p/E0 | pressure over the rubbery modulus | - |
| C~ | friction torque over F R | - |
| R* | friction radius, torque over force | m |
| theta* | angle of the net force from the load line | rad |
| E0, Einf, tau, nu | rubbery and glassy moduli, relaxation time, Poisson ratio | Pa, Pa, s, - |
| eps, eps_eff | eccentricity ratio of the journal centre, first Fourier mode of the film over c | - |
| c, h | radial clearance, film thickness | m |
| H | Hersey number eta v R_B / F | - |
| memory | "periodic": exact steady state; "thesis": load history of one revolution | |"""


def _summary(reports, times, quick, total):
    checks = [(name, c) for name, r in reports.items() for c in r.checks]
    failed = sum(not c.passed for _, c in checks)
    lines = [f"# vjax main job ({'quick' if quick else 'full'} run, {total:.0f} s)", "", INTRO, "",
             f"**{len(checks) - failed} of {len(checks)} checks passed.**", "",
             "| stage | check | value | expected | against | result |", "|---|---|---|---|---|---|"]
    lines += [f"| {name} | {c.what} | {float(c.value):.4g} | {c.expected()} | {c.reference} | "
              f"{'PASS' if c.passed else '**FAIL**'} |" for name, c in checks]
    lines += ["", "## Symbols", "", SYMBOLS, ""]
    for name, r in reports.items():
        lines += [f"## {name} ({times[name]:.1f} s)", "", r.about, ""]
        if r.figures:
            lines += ["Figures (in `" + name + "/`):", ""] + [f"- `{f}`: {cap}" for f, cap in r.figures] + [""]
        lines += ["```", r.text.rstrip(), "```", ""]
    return "\n".join(lines), failed


class _Prefixed(io.TextIOBase):
    """A stage worker's stdout: each line prefixed with the stage's name (stages run side by
    side, their progress lines interleave)."""

    def __init__(self, stream, prefix):
        self.stream, self.prefix, self.at_line_start = stream, prefix, True

    def write(self, text):
        for piece in text.splitlines(keepends=True):
            self.stream.write((self.prefix if self.at_line_start else "") + piece)
            self.at_line_start = piece.endswith("\n")
        self.stream.flush()
        return len(text)


# XLA flags of each stage's worker process (the main job's only: vjax sets none). Measured per
# stage, alone, from an empty cache (CPU seconds; docs/benchmarks.md, "Main job (issue 42)"):
# - XLA:CPU's classic fusion emitters compile the journal bearings' and the pin's programs
#   about 1.4x faster than the MLIR ones, to the same results up to round-off; not the roller's
#   (its stage: 89 -> 114 s with them);
# - optimization level 0 compiles 2-4x faster and runs slower: kept where the stage is mostly
#   compiling and its outputs agree with the default level's to round-off (largest difference
#   1e-11 of a column's largest value, every check the same), not where the runs cost more than
#   the compiles save (roller 49 -> 128 CPU-s, bodies 42 -> 43, bores 12 -> 15);
# - none for calibration (brief): it starts while the flags are probed.
CLASSIC, O0 = _common.CLASSIC_FUSION_EMITTERS, _common.OPTIMIZATION_LEVEL_0
STAGE_XLA_FLAGS = {"calibration": (), "foundation": (CLASSIC,), "pin": (CLASSIC, O0), "roller": (),
                   "journal": (CLASSIC, O0), "bodies": (CLASSIC,), "dynamics": (CLASSIC, O0), "bores": (CLASSIC,),
                   "stribeck": (CLASSIC, O0), "thermal": (CLASSIC, O0)}


def _run_stage(name, out, quick, cache, prefix=True):
    """Run one stage (in a worker process, or in this one); returns (report, seconds)."""
    # JAX's tracing makes millions of short-lived objects: at Python's default threshold (700
    # allocations) the cyclic collector runs ~1000 times a stage, ~4 % of its time; the stages
    # make few cycles
    gc.set_threshold(50_000)
    _common.enable_x64()
    if cache:
        from fitting.shared import jax_cache
        jax_cache.enable()
    module, func = next(((m, f) for s, m, f in STAGES if s == name), (None, None))
    if module is None:
        raise ValueError(f"name: no stage {name!r} (stages: {', '.join(s[0] for s in STAGES)})")
    stdout = sys.stdout
    if prefix:
        sys.stdout = _Prefixed(stdout, f"[{name}] ")
    try:
        t0 = time.perf_counter()
        report = getattr(importlib.import_module(module), func)(str(Path(out) / name), quick=quick)
        return report, time.perf_counter() - t0
    finally:
        sys.stdout = stdout


def _start_worker(flags, slot, slots):
    """A worker process's set-up: the core of its ``slot`` of ``slots`` alone
    (:func:`experiments._common.pin_to_core`), its XLA flags, and an end without Python's
    finalization (about 1 s with JAX loaded, paid by every worker when the job closes its pools
    after the last stage; a worker's outputs are written by then)."""
    _common.pin_to_core(slot, slots)
    _common.add_xla_flags(flags)
    gc.freeze()      # the modules the fork server imported: never garbage, out of the collector's passes
    atexit.register(_exit_now)


def _exit_now():
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


# imported once by the fork server, whose forks are the workers: none of them starts JAX's
# backend (or a thread), which a fork would not carry over
PRELOAD = ["numpy", "matplotlib.pyplot", "jax", "vjax", "fitting", "experiments._common"]


def _worker_context():
    """Workers forked from a server that has imported :data:`PRELOAD` (~1 s of imports once, not
    in every worker), where the platform has one; spawned (each importing anew) elsewhere.
    Never a plain fork of this process: JAX's runtime threads do not survive it."""
    if "forkserver" in multiprocessing.get_all_start_methods():
        from multiprocessing import forkserver
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(PRELOAD)
        try:
            forkserver.ensure_running()
            return ctx
        except OSError:      # no server (e.g. no free file descriptors): spawned workers
            pass
    return multiprocessing.get_context("spawn")


def _run_stages(names, out, quick, jobs, cache):
    """Run the stages, ``jobs`` at a time in worker processes (each stage is mostly XLA
    compiling its solvers, one core's work), longest first, a stage only after those it reads
    (DEPENDS). The workers share JAX's persistent compilation cache (``cache``): a solver one
    stage compiled, another loads. A stage that raises stops the job."""
    reports, times = {}, {}
    if jobs <= 1:
        for name in names:
            print(f"=== {name} ===", flush=True)
            reports[name], times[name] = _run_stage(name, out, quick, cache, prefix=False)
            print(f"[{name}: {times[name]:.1f} s]", flush=True)
        return reports, times
    pending, running = list(names), {}
    free = list(range(jobs))        # slots, each with a core of its own where there are as many
    ctx = _worker_context()
    # one worker process per slot and set of XLA flags (XLA reads them when its backend starts),
    # which runs stage after stage of its set in its slot, its compiled programs shared by them
    # (a pool of one: with more, which worker takes a stage would be left to chance, and a stage
    # in a fresh worker compiles again what another stage of its set already had). Whether this
    # jaxlib knows the flags is probed in a worker-like process while the stages without flags start.
    flags = sorted({f for v in STAGE_XLA_FLAGS.values() for f in v})
    prober = concurrent.futures.ThreadPoolExecutor(1)
    probe = prober.submit(_common.xla_flags_accepted, flags, ctx)
    pools = {}

    def key(name):      # a stage without flags does not wait for the probe
        flags = tuple(STAGE_XLA_FLAGS.get(name, ()))
        return flags if flags and probe.result() else ()

    def pool(name, slot):
        k = key(name), slot
        if k not in pools:
            pools[k] = concurrent.futures.ProcessPoolExecutor(1, mp_context=ctx, initializer=_start_worker,
                                                              initargs=(k[0], slot, jobs))
        return pools[k]

    try:
        while pending or running:
            ready = [s for s in pending if all(d in reports or d not in names for d in DEPENDS.get(s, ()))
                     and (probe.done() or not STAGE_XLA_FLAGS.get(s))]
            for name in ready[:jobs - len(running)]:
                pending.remove(name)
                slot = free.pop(0)
                print(f"=== {name} (started) ===", flush=True)
                running[pool(name, slot).submit(_run_stage, name, out, quick, cache)] = name, slot, (key(name), slot)
            waiting = list(running) + ([] if probe.done() else [probe])
            done, _ = concurrent.futures.wait(waiting, return_when=concurrent.futures.FIRST_COMPLETED)
            for future in done:
                if future is probe:
                    continue
                name, slot, k = running.pop(future)
                free.append(slot)
                try:
                    reports[name], times[name] = future.result()      # a stage that raised stops the job
                except BrokenProcessPool:
                    # its worker died (killed, out of memory, a crash in compiled code): once
                    # more here, and the next stage of its set in a new worker
                    print(f"[{name}: its worker process ended abruptly; running the stage again in this process]",
                          flush=True)
                    pools.pop(k).shutdown(wait=False)
                    reports[name], times[name] = _run_stage(name, out, quick, cache)
                print(f"[{name}: {times[name]:.1f} s]", flush=True)
    finally:
        # every pool told first (stages not started are cancelled), then waited for: their workers
        # end side by side
        for p in pools.values():
            p.shutdown(wait=False, cancel_futures=True)
        for p in pools.values():
            p.shutdown()
        prober.shutdown()
    return {n: reports[n] for n in names}, times


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="experiments/out", help="output directory")
    parser.add_argument("--quick", action="store_true", help="small grids: a smoke run in about a minute")
    parser.add_argument("--only", nargs="*", choices=[s[0] for s in STAGES], help="run only these stages")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="stages run side by side in this many processes (default: one per CPU; 1: in this process)")
    parser.add_argument("--no-cache", action="store_true",
                        help="do not use vjax's persistent compilation cache (~/.cache/vjax/jax)")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error(f"--jobs must be >= 1, got {args.jobs}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    names = [s[0] for s in PRIORITY if not args.only or s[0] in args.only]
    t_start = time.perf_counter()
    reports, times = _run_stages(names, out, args.quick, args.jobs, not args.no_cache)
    reports = {s[0]: reports[s[0]] for s in STAGES if s[0] in reports}      # the summary in stage order
    summary, failed = _summary(reports, times, args.quick, time.perf_counter() - t_start)
    _common.atomic_write_text(out / "summary.md", summary)
    print(f"summary written to {out / 'summary.md'} ({time.perf_counter() - t_start:.0f} s)")
    for name, r in reports.items():
        for c in r.checks:
            if not c.passed:
                print(f"FAILED check ({name}): {c.what} = {float(c.value):.4g}, expected {c.expected()}",
                      file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
