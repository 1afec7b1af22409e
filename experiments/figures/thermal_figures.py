"""A journal bearing at its own temperature: effective temperature and friction against speed.

Run::

    python -m experiments.figures.thermal_figures [out_dir] [--quick]

The bearing: a bore of R = 50.075 mm, c = 75 um, L/D = 0.5, one axial groove at ambient
pressure opposite the load, Reynolds cavitation, 32 x 8 cells; ISO VG 32 (Walther through 32.0
and 5.34 cSt at 40 and 100 C, rho = 874 kg/m^3, c_p = 1949 J/(kg K)) supplied at 40 C; a
specific load of 1 MPa (W = 5 kN). The bore is a 2 mm polymer liner (SLS 0.3 -> 3 GPa, 1 ms,
nu 0.4, WLF 8.86 / 101.6 at 40 C) in a rigid hub that turns about a fixed shaft (a wheel or a
planet gear on its pin): the load turns relative to the liner, which dissipates by hysteresis.

Two curves over the hub's speed: isothermal (everything at the 40 C supply, ``hA = inf``) and
level 1 thermal (:func:`vjax.thermal_journal_bearing`: ISO 7902's effective temperature, the
heat leaving with the side leakage and through hA = 5 W/K to 40 C; the oil's viscosity and the
liner's moduli at T_eff). Outputs in ``<out>/thermal/``: ``thermal_speed.csv``,
``thermal_speed.png``, ``thermal.txt`` (``--quick`` leaves the speed figure as it is: small already).
:func:`stage` is the main job's "thermal" stage: one function per figure (:data:`FIGURES`:
:func:`speed_figure`), each returning its text, checks and figures.
"""
from __future__ import annotations

import math
import sys
import time
from pathlib import Path

from experiments import _common

_common.enable_x64()

import jax.numpy as jnp  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

R, C, D = 50.075e-3, 75e-6, 0.1           # bore radius, radial clearance, journal diameter (m)
L = 0.5 * D
W = 1e6 * L * D                           # N: 1 MPa specific load
T_IN, HA = 40.0, 5.0                      # supply and ambient (C); housing and shaft conductance (W/K)
OIL = vjax.Lubricant.walther(32.0, 5.34, 40.0, 100.0, rho=874.0, c_p=1949.0)
SHIFT = vjax.WLF(8.86, 101.6, 40.0)
LINER = vjax.liner(vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4).with_shift(SHIFT), 2e-3)
BEARING = dict(length=L, housing=LINER, options=vjax.FiniteJournalOptions(n=32, m=8))
RPM = (1000.0, 2000.0, 4000.0, 8000.0)


def _thermal(omega, hA):
    """The bearing at ``omega`` (rad/s, the hub) at its effective temperature with hA (W/K)."""
    return vjax.thermal_journal_bearing(R, C, OIL, W, vjax.HeatTransfer(T_IN, hA=hA), omega_housing=omega, **BEARING)


def _isothermal(omega, T):
    """vjax.journal_bearing itself at T (C): the oil's viscosity and the liner's moduli there."""
    return vjax.journal_bearing(R, C, OIL.viscosity(T), W, omega_housing=omega, temperature=T, **BEARING)


def speed_sweep(rpm=RPM):
    """Isothermal (hA = inf) and thermal (hA = HA) results at each speed; progress lines."""
    iso, hot = [], []
    for n in rpm:
        omega = n * math.pi / 30
        t0 = time.perf_counter()
        iso.append(_thermal(omega, jnp.inf))
        hot.append(_thermal(omega, HA))
        r = hot[-1]
        print(f"  {n:6.0f} rpm: T_eff {float(r.temperature):6.2f} C, power {float(r.power):8.1f} W (isothermal "
              f"{float(iso[-1].power):8.1f} W), {int(r.iterations)} scene solves, {time.perf_counter() - t0:.1f} s",
              flush=True)
    return iso, hot


def speed_figure(out, quick=False):
    """Figure 1: effective temperature and friction coefficient against speed, isothermal
    against thermal, with its checks. Returns (text, checks, figures)."""
    rpm = np.asarray(RPM)
    iso, hot = speed_sweep(rpm)
    U = rpm * math.pi / 30 * R
    f = lambda rs, a: np.array([float(getattr(r, a)) for r in rs])      # noqa: E731
    mu_iso, mu_hot = f(iso, "power") / (W * U), f(hot, "power") / (W * U)
    T_hot = f(hot, "temperature")
    rows = [(rpm[k], T_hot[k], f(hot, "outlet_temperature")[k], f(hot, "viscosity")[k] * 1e3, mu_iso[k], mu_hot[k],
             f(iso, "power_housing")[k], f(hot, "power_housing")[k], float(iso[k].scene.eccentricity),
             float(hot[k].scene.eccentricity), float(iso[k].scene.min_film) * 1e6, float(hot[k].scene.min_film) * 1e6,
             f(hot, "heat_oil")[k] / f(hot, "power")[k]) for k in range(rpm.size)]
    header = ("speed (rpm)", "T_eff (C)", "T_out (C)", "eta(T_eff) (mPa s)", "mu isothermal", "mu thermal",
              "liner W iso", "liner W thermal", "eps iso", "eps thermal", "h_min iso (um)", "h_min thermal (um)",
              "oil share of heat")
    _common.write_csv(out / "thermal_speed.csv", header, rows,
                      comments=[f"mu = power / (W U), U = omega R; W = {W:g} N, hA = {HA:g} W/K, supply {T_IN:g} C"])

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    a.plot(rpm, T_hot, "o-", label="thermal: T_eff")
    a.plot(rpm, f(hot, "outlet_temperature"), "s--", label="thermal: T_out")
    a.axhline(T_IN, color="k", ls=":", label="isothermal (supply, 40 C)")
    a.set(xlabel="hub speed (rpm)", ylabel="temperature (C)", xscale="log")
    b.plot(rpm, mu_iso, "k:o", label="isothermal at 40 C")
    b.plot(rpm, mu_hot, "o-", label="thermal (level 1)")
    b.set(xlabel="hub speed (rpm)", ylabel="friction coefficient P / (W U)", xscale="log", yscale="log")
    for ax in (a, b):
        ax.set_xticks(rpm, [f"{n:g}" for n in rpm], minor=False)
        ax.set_xticks([], minor=True)
        ax.legend(fontsize=8)
    fig.suptitle(f"VG 32, 2 mm polymer liner, L/D = 0.5, c = 75 um, {W / 1e3:g} kN: isothermal against "
                 f"ISO 7902 effective temperature (hA = {HA:g} W/K)", fontsize=9)
    _common.save_figure(fig, out / "thermal_speed.png")

    # checks, each against something computed here and not by the balance itself
    balance = max(abs(float(r.power) - 2 * float(OIL.density(r.temperature)) * OIL.c_p * float(r.scene.side_leakage)
                      * (float(r.temperature) - T_IN) - HA * (float(r.temperature) - T_IN)) / float(r.power)
                  for r in hot)
    limit, fixed = 0.0, 0.0
    for k, n in enumerate(rpm):
        omega = n * math.pi / 30
        ref = _isothermal(omega, T_IN)
        limit = max(limit, abs(float(iso[k].scene.eccentricity) / float(ref.eccentricity) - 1),
                    abs(float(iso[k].scene.torque) / float(ref.torque) - 1))
        at = _isothermal(omega, float(hot[k].temperature))
        fixed = max(fixed, abs(float(hot[k].scene.eccentricity) / float(at.eccentricity) - 1))
    checks = (
        _common.Check("energy balance: max over speeds of abs(P - 2 rho c_p Q (T_eff - T_in) - hA (T_eff - T_amb)) / P",
                      balance, 0.0, 1e-10, "heat flows recomputed from the side leakage and the oil's rho, c_p"),
        _common.Check("hA = inf: max relative difference of eccentricity and torque from vjax.journal_bearing at 40 C",
                      limit, 0.0, 1e-10, "the isothermal scene"),
        _common.Check("thermal result vs vjax.journal_bearing re-solved at eta(T_eff), liner at T_eff: max rel. "
                      "difference of eccentricity", fixed, 0.0, 1e-10, "the isothermal scene at T_eff"),
        _common.Check("temperature rise monotone in speed: min over neighbours of T_eff(n+1) - T_eff(n) (K)",
                      float(np.min(np.diff(T_hot))), 0.0, 0, "more shear, more heat", "min"),
    )
    text = _common.format_table(header, rows)
    return text, checks, (("thermal_speed.png", "effective and outlet temperature, and friction coefficient "
                                                "P / (W U), against the hub's speed: isothermal at the 40 C supply "
                                                "against level 1 thermal"),)


def map_figure(out, quick=False):
    """The film's temperature map (level 2, :mod:`experiments.figures.thermal_map`)."""
    from experiments.figures.thermal_map import temperature_map
    text, checks = temperature_map(out)
    return text, checks, (("thermal_map.png", "the film's temperature over the land (level 2: ISO VG 32 at 40 C, "
                                              "3000 rpm, 1 MPa, L/D = 1, carry-over 0.8), adiabatic and liner-cooled "
                                              "bush, with the pressure's contours"),)


FIGURES = (speed_figure, map_figure)      # one function per figure: (out, quick) -> (text, checks, figures)


def run(out, quick=False):
    """Every figure of :data:`FIGURES` into the folder ``out``: (text, checks, figures)."""
    out = _common.setup(out)
    texts, checks, figures = [], [], []
    for figure in FIGURES:
        text, c, f = figure(out, quick)
        texts.append(text)
        checks += c
        figures += f
    text = "\n\n".join(texts)
    _common.atomic_write_text(out / "thermal.txt", text + "\n")
    print(text)
    return text, tuple(checks), tuple(figures)


def main(out_dir="experiments/out", quick=False):
    """Standalone: the figures in ``<out_dir>/thermal/``."""
    return run(Path(out_dir) / "thermal", quick)


def stage(out_dir, quick=False):
    """The main job's "thermal" stage (``out_dir`` is already the stage's folder): every figure
    of :data:`FIGURES` and their checks."""
    text, checks, figures = run(out_dir, quick)
    about = ("A finite journal bearing with a polymer liner in a turning hub (R = 50.075 mm, c = 75 um, L/D = 0.5, "
             "1 MPa, ISO VG 32 supplied at 40 C) at its own temperature: level 1 (ISO 7902's effective temperature, "
             "the heat carried by the side leakage and through hA = 5 W/K; the oil's viscosity and the liner's "
             "moduli at T_eff) against the isothermal bearing at the supply temperature. Then the film's "
             "temperature field of a rigid ISO 7902 bearing (level 2: the energy equation over the land, the "
             "groove mixing 0.8 of the arriving oil with supply oil).")
    return _common.StageReport(text, about, checks, figures)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
