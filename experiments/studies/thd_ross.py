"""The film's temperature field (level 2) against ROSS 3.1's adiabatic THD bearing, case by case.

    python -m experiments.studies.thd_ross [out_dir] [--grid 64x16]

The 12 bearings of issue 40's level 2 (D = 100 mm, c = 75 um, L/D = 0.5 and 1, 1500, 3000 and
6000 rpm, 1 and 2.5 MPa; ISO VG 32 supplied at 40 C; one axial groove opposite the load; rigid,
aligned, Reynolds cavitation, adiabatic walls, the groove mixing 0.8 of the arriving oil with
supply oil), solved by :func:`vjax.thermal_film_bearing` twice: with the Walther oil of the
cases, and with ROSS's own viscosity law (an exponential through the two Walther points the
peer gave it, ``lubricant_ross`` in the JSON: within 8 % of Walther over 40-100 C). ROSS's
numbers are read from ``experiments/peers/ross_thd_cases.json`` (written by
``experiments/peers/ross_thd_peer.py`` in ROSS's own interpreter; its docstring states what
ROSS solves). Writes ``thd_ross.csv`` and ``thd_ross.md``: eccentricity, attitude, maximum and
mean film temperature and power, vjax against ROSS, and the band issue 40 holds them to
(eccentricity 0.05, maximum film temperature 10 K).
"""
from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

from experiments import _common

_common.enable_x64()

import numpy as np  # noqa: E402

import vjax  # noqa: E402

PEER = Path(__file__).resolve().parents[1] / "peers" / "ross_thd_cases.json"
R, C = 0.050075, 75e-6
WALTHER = vjax.Lubricant.walther(32.0, 5.34, 40.0, 100.0, rho=874.0, c_p=1949.0)


def ross_oil(peer):
    """ROSS's law: mu1 exp(beta (T - T1)) through (T1, mu1), (T2, mu2) (K, Pa s)."""
    lub = peer["lubricant_ross"]
    T1, T2 = lub["temperature1"] - 273.15, lub["temperature2"] - 273.15
    beta = math.log(lub["liquid_viscosity2"] / lub["liquid_viscosity1"]) / (T2 - T1)
    return vjax.Lubricant.exponential(lub["liquid_viscosity1"], -beta, T1, rho=lub["liquid_density"],
                                      c_p=lub["liquid_specific_heat"])


def solve(case, oil, options):
    D = 2 * (R - C)
    L = case["l_over_d"] * D
    return vjax.thermal_film_bearing(R, C, oil, case["specific_load_MPa"] * 1e6 * L * D,
                                     vjax.FilmHeat(T_supply=40.0, carry_over=0.8), length=L,
                                     omega_shaft=case["speed_rpm"] * math.pi / 30, options=options)


def main(out_dir="experiments/out", grid="64x16"):
    out = _common.setup(out_dir) / "thd_ross"
    out.mkdir(parents=True, exist_ok=True)
    n, m = (int(v) for v in grid.split("x"))
    options = vjax.FiniteJournalOptions(n=n, m=m)
    peer = json.loads(PEER.read_text())
    oils = (("Walther", WALTHER), ("ROSS's law", ross_oil(peer)))
    rows = []
    for case in peer["cases"]:
        if case.get("thermal_type") != "adiabatic" or not case.get("ok"):
            continue
        row = [case["l_over_d"], case["speed_rpm"], case["specific_load_MPa"], case["eccentricity"],
               case["t_max_C"], case["t_film_mean_C"], case["power_W"]]
        for _, oil in oils:
            t = time.perf_counter()
            r = solve(case, oil, options)
            row += [float(r.scene.eccentricity), float(r.max_temperature), float(r.mean_temperature), float(r.power)]
            print(f"L/D {case['l_over_d']}, {case['speed_rpm']:.0f} rpm, {case['specific_load_MPa']} MPa: eps "
                  f"{float(r.scene.eccentricity):.4f} (ROSS {case['eccentricity']:.4f}), T_max "
                  f"{float(r.max_temperature):.2f} C (ROSS {case['t_max_C']:.2f}), {int(r.iterations)} rounds, "
                  f"{time.perf_counter() - t:.1f} s", flush=True)
        rows.append(row)
    header = ("L/D", "rpm", "MPa", "eps ROSS", "T_max ROSS", "T_mean ROSS", "P ROSS (W)",
              "eps vjax", "T_max vjax", "T_mean vjax", "P vjax (W)",
              "eps vjax (ROSS law)", "T_max vjax (ROSS law)", "T_mean vjax (ROSS law)", "P vjax (ROSS law)")
    _common.write_csv(out / "thd_ross.csv", header, rows)
    a = np.array(rows, float)
    d_eps = np.abs(a[:, 7] - a[:, 3]), np.abs(a[:, 11] - a[:, 3])
    d_T = a[:, 8] - a[:, 4], a[:, 12] - a[:, 4]
    summary = (f"{n} x {m} cells. |eps vjax - eps ROSS|: max {d_eps[0].max():.4f} (Walther), {d_eps[1].max():.4f} "
               f"(ROSS's law); band 0.05.\nT_max vjax - T_max ROSS: {d_T[0].min():+.2f} .. {d_T[0].max():+.2f} K "
               f"(Walther), {d_T[1].min():+.2f} .. {d_T[1].max():+.2f} K (ROSS's law); band 10 K.\n")
    text = f"{summary}\n{_common.format_table(header, rows)}\n"
    _common.atomic_write_text(out / "thd_ross.md", text)
    print(text)
    return rows


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    grid = next((sys.argv[i + 1] for i, a in enumerate(sys.argv) if a == "--grid"), "64x16")
    main(args[0] if args else "experiments/out", grid)
