"""Grid convergence of a Stribeck curve: how fine a finite bearing's grid must be in mixed lubrication.

    python -m experiments.studies.stribeck_grid [out_dir] [--quick]

The main job's rigid bearing (:mod:`experiments.figures.stribeck_figures`: R = 25.05 mm,
c = 50 um, L/D = 1, sigma = 1 um, W = 2 kN, no groove) over 13 speeds from 1e-3 to 1e2 rad/s
on 32 x 16, 64 x 16, 128 x 32 and 256 x 64 cells (``--quick``: the first three). Each curve's
friction coefficient, asperity share and eccentricity against the finest grid's; the lift-off
speed of each. Writes ``stribeck_grid.csv``, ``stribeck_grid.md`` and ``stribeck_grid.png``.
"""
from __future__ import annotations

import sys
import time

from experiments import _common

_common.enable_x64()

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402
from experiments.figures.stribeck_figures import C, ETA, L, R, ROUGH, W  # noqa: E402

GRIDS = ((32, 16), (64, 16), (128, 32), (256, 64))


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir) / "stribeck_grid"
    out.mkdir(parents=True, exist_ok=True)
    speeds = np.logspace(-3, 2, 13)
    curves = {}
    for n, m in GRIDS[:3] if quick else GRIDS:
        t = time.perf_counter()
        curves[(n, m)] = vjax.stribeck_curve(R, C, ETA, W, speeds, length=L, roughness=ROUGH, supply_angle=None,
                                             options=vjax.FiniteJournalOptions(n=n, m=m))
        c = curves[(n, m)]
        print(f"{n} x {m}: {int(c.converged.sum())}/{speeds.size} converged, lift-off "
              f"{c.lift_off_speed if c.lift_off_speed is None else round(c.lift_off_speed, 4)} rad/s "
              f"({time.perf_counter() - t:.1f} s)", flush=True)
    finest = curves[max(curves)]
    rows = []
    for (n, m), c in curves.items():
        mu_err = np.nanmax(np.abs(c.friction_coefficient / finest.friction_coefficient - 1))
        share_err = np.nanmax(np.abs(c.asperity_share - finest.asperity_share))
        eps_err = np.nanmax(np.abs(c.eccentricity / finest.eccentricity - 1))
        rows.append((f"{n} x {m}", int(c.converged.sum()), mu_err, share_err, eps_err,
                     float("nan") if c.lift_off_speed is None else c.lift_off_speed))
    header = ("grid", "converged", "max |mu / mu_finest - 1|", "max |share - share_finest|",
              "max |eps / eps_finest - 1|", "lift-off (rad/s)")
    _common.write_csv(out / "stribeck_grid.csv", header, rows)
    text = (f"Stribeck curve on four grids against the finest ({max(curves)[0]} x {max(curves)[1]}), 13 speeds "
            f"1e-3..1e2 rad/s\n\n{_common.format_table(header, rows)}\n")
    _common.atomic_write_text(out / "stribeck_grid.md", text)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (n, m), c in curves.items():
        a.loglog(c.hersey, c.friction_coefficient, "o-", ms=3, label=f"{n} x {m}")
        b.semilogx(c.hersey, c.asperity_share, "o-", ms=3, label=f"{n} x {m}")
    a.set(xlabel="Hersey number eta omega / p_mean", ylabel="friction coefficient")
    b.set(xlabel="Hersey number eta omega / p_mean", ylabel="asperity share")
    a.legend(fontsize=8)
    fig.suptitle("Stribeck curve against the grid (rigid bush, sigma = 1 um, L/D = 1)")
    _common.save_figure(fig, out / "stribeck_grid.png")
    print(text)
    return rows


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
