"""The main job: calibrate the shipped DMA data, reproduce the thesis's figures, write a summary.

    python -m experiments.main [--out experiments/out] [--quick]

Stages (each writes PNG + CSV into ``<out>/<stage>/`` and returns a short text):

1. ``calibration``: Prony series + shift law fitted to the shipped pyvisco DMA example
   (``fitting/data/pyvisco``), saved as ``material.json`` with its plots;
2. ``foundation``: material laws and the ring Green's functions (Figs. 2.3, A.4, A.6);
3. ``pin``: pin in a hole (Figs. 2.5-2.10);
4. ``roller``: needle roller bearing (Figs. 2.14-2.21);
5. ``journal``: visco-elastohydrodynamic journal bearing (Figs. 3.4-3.8).

``<out>/summary.md`` collects every stage's text and its wall time. A stage that fails
stops the job with a non-zero exit code (its files are written atomically, so nothing
half-written is left behind).
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
    return text


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="experiments/out", help="output directory")
    parser.add_argument("--quick", action="store_true", help="small grids: a smoke run in about a minute")
    parser.add_argument("--only", nargs="*", choices=[s[0] for s in STAGES], help="run only these stages")
    args = parser.parse_args(argv)
    _common.enable_x64()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    sections, t_start = [], time.perf_counter()
    for name, module, func in STAGES:
        if args.only and name not in args.only:
            continue
        print(f"=== {name} ===", flush=True)
        t0 = time.perf_counter()
        text = getattr(importlib.import_module(module), func)(str(out / name), quick=args.quick)
        dt = time.perf_counter() - t0
        text = text if isinstance(text, str) else "(see the CSV files)"
        print(f"[{name}: {dt:.1f} s]", flush=True)   # each stage prints its own text
        sections.append(f"## {name} ({dt:.1f} s)\n\n```\n{text}\n```\n")
    summary = (f"# vjax main job ({'quick' if args.quick else 'full'} run, "
               f"{time.perf_counter() - t_start:.0f} s)\n\n" + "\n".join(sections))
    _common.atomic_write_text(out / "summary.md", summary)
    print(f"summary written to {out / 'summary.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
