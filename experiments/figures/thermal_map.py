"""The film's temperature map of a finite journal bearing (level 2), for the main job's "thermal" stage.

Run::

    python -m experiments.figures.thermal_map [out_dir]

The ISO 7902 case of the thermal tests: journal diameter 100 mm in a bore of 50.075 mm radius
(c = 75 um), L/D = 1, ISO VG 32 supplied at 40 C through an axial groove opposite the load,
3000 rpm, 1 MPa, rigid and aligned, Reynolds cavitation, 64 x 16 cells; the groove mixes 0.8 of
the oil arriving at it with supply oil; the bush adiabatic, or conducting through a 5 mm
polymer liner (0.25 W/(m K)) to a housing at 40 C (docs/validation.md compares level 1 and
ROSS). :func:`temperature_map` draws the film's
temperature over the land, with the pressure's contours, and returns its checks.
"""
from __future__ import annotations

import math
import sys

from experiments import _common

_common.enable_x64()

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

R, C, L, RPM, P_SPEC = 0.050075, 75e-6, 0.1, 3000.0, 1e6
OIL = vjax.Lubricant.iso_vg(32)
OPTIONS = vjax.FiniteJournalOptions(n=64, m=16)
# the adiabatic bush as a bush of zero heat-transfer coefficient to the same housing temperature:
# the same pytree as the liner's (FilmHeat(T_supply=40.0) alone has T_housing None), so that both
# bushes run one set of compiled programs, not two
HEATS = (("adiabatic bush", vjax.FilmHeat(T_supply=40.0, bush=0.0, T_housing=40.0)),
         ("5 mm liner to a 40 C housing", vjax.FilmHeat.liner(0.25, 5e-3, T_housing=40.0, T_supply=40.0)))


def solve(heat):
    return vjax.thermal_film_bearing(R, C, OIL, P_SPEC * L * 2 * (R - C), heat, length=L,
                                     omega_shaft=RPM * 2 * math.pi / 60, options=OPTIONS)


def temperature_map(out):
    """Draw ``thermal_map.png`` and write ``thermal_map.csv`` into ``out``; returns (text, checks)."""
    results = [(name, solve(heat)) for name, heat in HEATS]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4), sharey=True, layout="constrained")
    lo = 40.0
    hi = max(float(r.max_temperature) for _, r in results)
    for ax, (name, r) in zip(axes, results):
        theta = np.degrees(np.asarray(r.scene.theta))
        z = 1e3 * np.asarray(r.scene.z)
        T = np.asarray(r.temperature)
        im = ax.contourf(theta, z, T.T, levels=np.linspace(lo, hi, 25), cmap="inferno")
        p = np.asarray(r.scene.pressure) / 1e6
        cs = ax.contour(theta, z, p.T, levels=np.linspace(0.5, p.max(), 5), colors="w", linewidths=0.6)
        ax.clabel(cs, fmt="%.1f MPa", fontsize=7)
        ax.axvline(180.0, color="c", ls="--", lw=0.8)
        ax.set(xlabel="theta from the load line (deg), rotation +")
        ax.set_title(f"{name}: T_max {float(r.max_temperature):.1f} C, mean {float(r.mean_temperature):.1f} C",
                     fontsize=9)
    axes[0].set_ylabel("z (mm)")
    fig.colorbar(im, ax=axes, label="film temperature (C)")
    fig.suptitle("Film temperature, ISO VG 32 supplied at 40 C, 3000 rpm, 1 MPa, L/D = 1 (dashed: the groove)",
                 fontsize=9)
    _common.save_figure(fig, out / "thermal_map.png")
    header = ("bush", "eccentricity", "T_max (C)", "T_mean (C)", "T_groove mean (C)", "T_out (C)", "power (W)",
              "ends (W)", "groove discharge (W)", "bush (W)", "rounds")
    rows = [(name, float(r.scene.eccentricity), float(r.max_temperature), float(r.mean_temperature),
             float(np.mean(np.asarray(r.groove_temperature))), float(r.outlet_temperature), float(r.power),
             float(r.heat_ends), float(r.heat_groove), float(r.heat_bush), int(r.iterations)) for name, r in results]
    _common.write_csv(out / "thermal_map.csv", header, rows)
    text = _common.format_table(header, rows)
    print(text, flush=True)
    balance = max(abs(float(r.heat_ends + r.heat_groove + r.heat_bush + r.heat_journal) / float(r.power) - 1)
                  for _, r in results)
    adiabatic, cooled = results[0][1], results[1][1]
    checks = (
        _common.Check("film temperature field: |heat out (ends, groove, bush) / power - 1|, worst of two bushes",
                      balance, 1e-10, 0, "energy conservation of the finite-volume energy equation", "max"),
        _common.Check("film temperature field: T_max of the liner-cooled film below the adiabatic one's (1 = yes)",
                      float(cooled.max_temperature < adiabatic.max_temperature), 1.0, 0, "heat leaves through the "
                      "bush", "min"),
    )
    return text, checks


if __name__ == "__main__":
    out = _common.setup(sys.argv[1] if len(sys.argv) > 1 else "experiments/out") / "thermal"
    out.mkdir(parents=True, exist_ok=True)
    temperature_map(out)
