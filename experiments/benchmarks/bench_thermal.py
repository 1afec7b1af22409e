"""The film's temperature field (level 2) against the isothermal finite bearing (issue 40's benchmark).

    python -m experiments.benchmarks.bench_thermal [out_dir] [--quick] [--repeats 5]

The ISO 7902 case of the thermal tests (D = 100 mm, c = 75 um, L/D = 1, ISO VG 32 supplied at
40 C, 3000 rpm, 1 MPa), rigid and aligned, groove opposite the load, on 128 x 32 cells:
:func:`vjax.thermal_film_bearing` (adiabatic, carry-over 0.8) against
:func:`vjax.journal_bearing` at the supply temperature's viscosity. First calls (compiling
included) each in a fresh process, so that neither reuses the other's compiled programs; warm
calls as the median of ``repeats`` in this one. Writes ``bench_thermal.md``; quote the line of
``python -m experiments.benchmarks.calibrate`` beside it.
"""
from __future__ import annotations

import argparse
import math
import statistics
import subprocess
import sys
import time

from experiments import _common

_common.enable_x64()

import vjax  # noqa: E402

R, C, L, RPM, P_SPEC = 0.050075, 75e-6, 0.1, 3000.0, 1e6
OIL = vjax.Lubricant.iso_vg(32)


def run(case, n, m):
    options = vjax.FiniteJournalOptions(n=n, m=m)
    w, W = RPM * 2 * math.pi / 60, P_SPEC * L * 0.1
    if case == "isothermal":
        r = vjax.journal_bearing(R, C, OIL.viscosity(40.0), W, length=L, omega_shaft=w, options=options)
        return float(r.eccentricity), ""
    r = vjax.thermal_film_bearing(R, C, OIL, W, vjax.FilmHeat(T_supply=40.0), length=L, omega_shaft=w,
                                  options=options)
    return float(r.scene.eccentricity), f"{int(r.iterations)} rounds, T_max {float(r.max_temperature):.2f} C"


def first_call(case, n, m):
    code = ("import time; t = time.perf_counter(); from experiments.benchmarks import bench_thermal as b; "
            f"b.run({case!r}, {n}, {m}); print(time.perf_counter() - t)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip().splitlines()[-1])


def main(out_dir="experiments/out", quick=False, repeats=5):
    out = _common.setup(out_dir) / "bench_thermal"
    out.mkdir(parents=True, exist_ok=True)
    n, m = (64, 16) if quick else (128, 32)
    rows = []
    for case in ("isothermal", "film temperature (level 2)"):
        key = "isothermal" if case == "isothermal" else "level2"
        first = first_call(key, n, m)
        run(key, n, m)
        times = []
        for _ in range(repeats):
            t = time.perf_counter()
            eps, note = run(key, n, m)
            times.append(time.perf_counter() - t)
        rows.append((case, f"{eps:.5f}", note, first, statistics.median(times)))
        print(f"{case}: eps {eps:.5f} {note}, first call {first:.2f} s, warm median {rows[-1][-1]:.3f} s", flush=True)
    table = _common.format_table(("solve", "eccentricity", "", "first call (s, fresh process)",
                                  f"warm (s, median of {repeats})"), rows)
    text = (f"{n} x {m} cells, 3000 rpm, 1 MPa, L/D = 1\n\n{table}\n\n"
            f"level 2 / isothermal: first call {rows[1][3] / rows[0][3]:.2f}, warm {rows[1][4] / rows[0][4]:.1f} "
            f"(goal: at most 3)\n")
    _common.atomic_write_text(out / "bench_thermal.md", text)
    print(text)
    return rows


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out_dir", nargs="?", default="experiments/out")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args()
    main(a.out_dir, a.quick, a.repeats)
