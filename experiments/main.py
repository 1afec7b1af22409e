"""The main job: calibrate the shipped DMA data, reproduce the thesis's figures, write a summary.

    python -m experiments.main [--out experiments/out] [--quick]

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
   where the bore's deformation leaves small-strain theory.

``<out>/summary.md`` opens with what was computed and a table of every stage's checks
(value, reference, tolerance, PASS/FAIL), defines the symbols, then gives each stage's
description, figures and output. The job exits with status 1 if a check fails; a stage that
raises stops it (files are written atomically, so nothing half-written is left behind).
"""
from __future__ import annotations

import argparse
import importlib
import sys
import time
from pathlib import Path

from experiments import _common

STAGES = [
    ("calibration", "experiments.main", "calibration_stage"),
    ("foundation", "experiments.foundation_figures", "main"),
    ("pin", "experiments.pin_figures", "main"),
    ("roller", "experiments.roller_figures", "main"),
    ("journal", "experiments.journal_figures", "main"),
    ("bodies", "experiments.bodies_figures", "main"),
    ("dynamics", "experiments.journal_dynamics", "main"),
    ("bores", "experiments.journal_bores", "stage"),
]


def calibration_stage(out_dir, quick=False):
    """Fit the shipped pyvisco example (tensile, 21 temperatures) at T_ref = 25 C."""
    from fitting import calibrate, dma
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


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="experiments/out", help="output directory")
    parser.add_argument("--quick", action="store_true", help="small grids: a smoke run in about a minute")
    parser.add_argument("--only", nargs="*", choices=[s[0] for s in STAGES], help="run only these stages")
    args = parser.parse_args(argv)
    _common.enable_x64()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    reports, times, t_start = {}, {}, time.perf_counter()
    for name, module, func in STAGES:
        if args.only and name not in args.only:
            continue
        print(f"=== {name} ===", flush=True)
        t0 = time.perf_counter()
        reports[name] = getattr(importlib.import_module(module), func)(str(out / name), quick=args.quick)
        times[name] = time.perf_counter() - t0
        print(f"[{name}: {times[name]:.1f} s]", flush=True)   # each stage prints its own text
    summary, failed = _summary(reports, times, args.quick, time.perf_counter() - t_start)
    _common.atomic_write_text(out / "summary.md", summary)
    print(f"summary written to {out / 'summary.md'}")
    for name, r in reports.items():
        for c in r.checks:
            if not c.passed:
                print(f"FAILED check ({name}): {c.what} = {float(c.value):.4g}, expected {c.expected()}",
                      file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
