"""Dynamic coefficients of journal bearings (issue 15): rigid against the closed forms, a
polymer-lined bearing over four decades of whirl frequency, the thesis case, and the oil-whirl
threshold of a rigid rotor on them.

Run::

    PYTHONPATH=. python -m experiments.figures.journal_dynamics [out_dir] [--quick]

Cases (per unit length; bearings of length 0.05 m for the rotor):

- rigid long bearing, R = 50 mm, c = 50 um, eta = 0.01 Pa s, journal at 100 rad/s, pi film
  (half-Sommerfeld): K and C at eps = 0.1..0.9 against
  :func:`vjax.reference.long_bearing_coefficients`;
- the same bearing with a 2 mm polymer liner bonded in a rigid housing (standard linear
  solid: E0 = 0.3 GPa, Einf = 3 GPa, tau = 1 ms, nu = 0.4), at the load that puts the rigid
  bearing at eps = 0.5, Reynolds conditions: K(Omega), C(Omega) for Omega = 1..1e4 rad/s
  next to the rigid bearing's, and the whirl threshold of each (Lund's rigid rotor);
- mass-conserving cavitation (``cavitation="jfo"``) against Reynolds conditions on the rigid
  bearing with a groove fixed 2 rad from the load direction (in the diverging film): the
  pressure and film fraction, and K(Omega), which for JFO depends on the whirl frequency;
- the thesis's HS case (docs/theory.md §11: SLS bore, omega_B = 0.2, omega_J = -0.4 rad/s):
  K(Omega), C(Omega) over 1e-3..1e3 rad/s, where the bore's rotation makes modes m and -m
  respond at different frequencies.

Outputs: ``dynamics_rigid.csv`` (errors against the closed forms), ``dynamics_liner.csv``
and ``dynamics_rigid_table.csv`` (ROSS-style tables: speed, frequency, kxx..cyy for 0.05 m),
``dynamics_thesis.csv``, ``dynamics_coefficients.png``, ``dynamics_jfo.png``, ``dynamics_summary.txt``.
"""
from __future__ import annotations

import os
import sys
import time

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402
from vjax import JournalOptions, reference  # noqa: E402

R, C, ETA, WJ, LENGTH = 0.05, 5e-5, 0.01, 100.0, 0.05
V = 0.5 * WJ * (R - C)
LINER = vjax.liner(vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4), 2e-3)


# The closed forms, each one compiled program (eager, each of their operations compiles its own
# small program: about 40 of them).
_closed_form_load = jax.jit(lambda eps: reference.long_bearing(eps, R, C, ETA, V, "half_sommerfeld")["load"])
_closed_form_coefficients = jax.jit(lambda eps: reference.long_bearing_coefficients(eps, R, C, ETA, V,
                                                                                    "half_sommerfeld"))


def _in_line_of_centres(co, A):
    """A 2 x 2 coefficient matrix of ``co`` turned into the line-of-centres frame (X from the
    bore's centre to the journal's, Y 90 degrees counter-clockwise from it): as
    ``JournalCoefficients.in_line_of_centres``, in numpy (no small programs to compile)."""
    g = float(co.steady.line_of_centres_angle)
    rot = np.array([[np.cos(g), -np.sin(g)], [np.sin(g), np.cos(g)]])
    return rot.T @ np.asarray(A) @ rot


def rigid_against_closed_form(n, eps_values):
    rows = []
    for eps in eps_values:
        load = float(_closed_form_load(eps))
        # strategy "newton": a direct Newton from the rigid half-Sommerfeld estimate, which for the pi
        # film is the solution up to the film's discretization; "auto" would first solve a 4x
        # coarser grid, one more compiled program for a start that is no better
        co = vjax.journal_coefficients(R, C, ETA, load, [0.0, 50.0], omega_shaft=WJ, cavitation="half_sommerfeld",
                                       options=JournalOptions(n=n, strategy="newton"))
        K, Cd = (_in_line_of_centres(co, a[1]) for a in (co.stiffness, co.damping))
        Kr, Cr = (np.asarray(a) for a in _closed_form_coefficients(co.steady.eccentricity))
        rows.append([eps, float(co.steady.eccentricity), *(K.ravel() / 1e9), *(Cd.ravel() / 1e6),
                     np.abs(K - Kr).max() / np.abs(Kr).max(), np.abs(Cd - Cr).max() / np.abs(Cr).max()])
    return rows


def liner_sweep(n, whirl):
    load = float(reference.long_bearing(0.5, R, C, ETA, V, "reynolds")["load"])
    out = {"rigid": vjax.journal_coefficients(R, C, ETA, load, whirl, omega_shaft=WJ, options=JournalOptions(n=n))}
    # the lined bearing starts from the rigid one's solution: a cold start would first solve a 4x
    # coarser grid (one more compiled program) for a start no better than this one
    out["polymer liner 2 mm"] = vjax.journal_coefficients(R, C, ETA, load, whirl, housing=LINER, omega_shaft=WJ,
                                                          initial=out["rigid"].steady, options=JournalOptions(n=n))
    return load, out


def thesis_sweep(n, whirl):
    sls = vjax.Material.sls(1e6, 1e8, 1.0, 0.5)
    # continuation from the rigid estimate: "auto" would first solve a 4x coarser grid, one more
    # compiled program
    return vjax.journal_coefficients(0.1, 5e-4, 1e-3, 2.2e-3 * 1e6 * 0.1, whirl, housing=sls, omega_shaft=-0.4,
                                     omega_housing=0.2, options=JournalOptions(n=n, strategy="continuation"))


def jfo_against_reynolds(n, whirl, supply_angle=2.0, load=1e5):
    """Steady solutions and coefficients under JFO and Reynolds conditions, groove fixed in
    the bearing at ``supply_angle`` from the load direction."""
    return {cav: vjax.journal_coefficients(R, C, ETA, load, whirl, omega_shaft=WJ, cavitation=cav, groove="fixed",
                                           supply_angle=supply_angle, options=JournalOptions(n=n))
            for cav in ("reynolds", "jfo")}


def _plot_jfo(path, cases):
    fig, (ax, axk) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    axf = ax.twinx()
    for (cav, co), style in zip(cases.items(), ("--", "-")):
        s = co.steady
        from_load = (np.asarray(s.theta) + float(s.attitude_angle)) % (2 * np.pi)
        order = np.argsort(from_load)
        th = np.degrees(from_load[order])
        ax.plot(th, np.asarray(s.pressure)[order] / 1e6, style, color="C0", label=f"pressure, {cav}")
        axf.plot(th, np.asarray(s.film_fraction)[order], style, color="C3", label=f"film fraction, {cav}")
        W = np.asarray(co.whirl)
        for (i, j), color in zip(((0, 0), (0, 1), (1, 0), (1, 1)), ("C0", "C1", "C2", "C3")):
            axk.plot(W, np.asarray(co.stiffness)[:, i, j] / 1e9, style, color=color, label=f"K{'xy'[i]}{'xy'[j]}, {cav}")
    ax.axvline(np.degrees(2.0), color="0.5", lw=0.8)
    ax.set_xlabel("angle from the load direction (deg); groove at the grey line")
    ax.set_ylabel("pressure (MPa)")
    axf.set_ylabel("liquid film fraction")
    axf.set_ylim(0, 1.05)
    ax.legend(loc="upper left", fontsize=7)
    axf.legend(loc="upper right", fontsize=7)
    ax.set_title("groove fixed 2 rad from the load: JFO (solid) re-forms later", fontsize=10)
    axk.set_xscale("symlog", linthresh=1.0)
    axk.set_xlabel("whirl frequency Ω (rad/s)")
    axk.set_ylabel("K (1e9 N/m²)")
    axk.legend(fontsize=7, ncol=2)
    axk.set_title("stiffness: Reynolds (dashed) flat, JFO (solid) with the cavity's delay", fontsize=10)
    _common.save_figure(fig, path)


def _plot(path, sweeps):
    fig, axes = plt.subplots(2, len(sweeps), figsize=(5.5 * len(sweeps), 7.5), layout="constrained", squeeze=False)
    for col, (title, curves) in enumerate(sweeps):
        for label, co, style in curves:
            W = np.asarray(co.whirl)
            for row, (A, unit) in enumerate(((co.stiffness, "K (N/m²)"), (co.damping, "C (N s/m²)"))):
                ax = axes[row, col]
                for (i, j), color in zip(((0, 0), (0, 1), (1, 0), (1, 1)), ("C0", "C1", "C2", "C3")):
                    ax.plot(W, np.asarray(A)[:, i, j], style, color=color,
                            label=f"{'xy'[i]}{'xy'[j]}, {label}")
                ax.set_xscale("log")
                # linear below the power of ten under 1e-3 of the largest value: the decades the
                # locator labels then start at the linear range's ends, a decade's height from
                # 0 (a threshold off a power of ten puts a label inside it, crowding 0)
                big = float(np.abs(np.asarray(A)).max())
                ax.set_yscale("symlog", linthresh=10.0 ** np.floor(np.log10(big * 1e-3)))
                ax.set_xlabel("whirl frequency Ω (rad/s)")
                ax.set_ylabel(unit)
        axes[0, col].set_title(title, fontsize=10)
        axes[0, col].legend(fontsize=7, ncol=2)
    _common.save_figure(fig, path)


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    t0 = time.perf_counter()
    n = 128 if quick else 512
    rigid = rigid_against_closed_form(n, (0.1, 0.5, 0.9) if quick else (0.1, 0.3, 0.5, 0.7, 0.9))
    head = ["eps target", "eps", "Kxx", "Kxy", "Kyx", "Kyy", "Cxx", "Cxy", "Cyx", "Cyy", "K rel. error",
            "C rel. error"]
    _common.write_csv(out / "dynamics_rigid.csv", head, rigid,
                      comments=[f"rigid long bearing, pi film, n = {n}; line-of-centres frame; K in 1e9 N/m^2, "
                                "C in 1e6 N s/m^2; errors: max |vjax - closed form| / max |closed form|"])
    whirl = np.logspace(0, 4, 9 if quick else 17)
    load, liner = liner_sweep(64 if quick else 256, whirl)
    for name, co in liner.items():
        co.save_csv(out / f"dynamics_{'rigid_table' if name == 'rigid' else 'liner'}.csv", length=LENGTH)
    thresholds = {name: vjax.stability_threshold(co, length=LENGTH) for name, co in liner.items()}
    thesis = thesis_sweep(64 if quick else 128, np.logspace(-3, 3, 13 if quick else 25))
    _common.write_csv(out / "dynamics_thesis.csv", ["whirl", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"],
                      [[w, *k.ravel(), *c.ravel()] for w, k, c in
                       zip(np.asarray(thesis.whirl), np.asarray(thesis.stiffness), np.asarray(thesis.damping))],
                      comments=["thesis HS case per unit length: K in N/m^2, C in N s/m^2, absolute frame"])
    _plot(out / "dynamics_coefficients.png",
          [(f"R = 50 mm, c = 50 µm, 100 rad/s, load {load:.3g} N/m:\nrigid (dashed) and a 2 mm polymer liner",
            [("rigid", liner["rigid"], "--"), ("liner", liner["polymer liner 2 mm"], "-")]),
           ("thesis HS case\n(SLS bore, ω_B = 0.2, ω_J = -0.4 rad/s)", [("thesis", thesis, "-")])])
    jfo = jfo_against_reynolds(64 if quick else 256, np.concatenate([[0.0], np.logspace(-1, 3, 9 if quick else 17)]))
    _plot_jfo(out / "dynamics_jfo.png", jfo)
    lines = [f"Rigid long bearing, pi film, n = {n}: max relative error against the closed forms "
             f"K {max(r[-2] for r in rigid):.2e}, C {max(r[-1] for r in rigid):.2e} (eps {rigid[0][0]}..{rigid[-1][0]})",
             f"Bearing with a 2 mm polymer liner (SLS 0.3/3 GPa, tau = 1 ms) at {load:.4g} N/m, whirl 1..1e4 rad/s:"]
    for name, co in liner.items():
        th = thresholds[name]
        K, Cd = np.asarray(co.stiffness), np.asarray(co.damping)
        lines.append(f"  {name}: eps {float(co.steady.eccentricity):.4f}; Kyy {K[0, 1, 1]:.4g} -> {K[-1, 1, 1]:.4g} "
                     f"N/m^2, Cyy {Cd[0, 1, 1]:.4g} -> {Cd[-1, 1, 1]:.4g} N s/m^2; whirl threshold: "
                     + (f"whirl ratio {th['whirl_ratio']:.4f}, critical mass {th['critical_mass']:.4g} kg per "
                        f"{LENGTH} m bearing" if th["whirl"] else "none (stable at any mass)"))
    rey_s, jfo_s = jfo["reynolds"].steady, jfo["jfo"].steady
    flow = float(np.mean(np.asarray(jfo_s.film) * np.asarray(jfo_s.film_fraction))) * V    # the film's flow, in order
    Kj = np.asarray(jfo["jfo"].stiffness)
    lines.append(f"Groove fixed 2 rad from the load (1e5 N/m): eps {float(rey_s.eccentricity):.4f} (Reynolds), "
                 f"{float(jfo_s.eccentricity):.4f} (JFO); net groove flow {float(rey_s.supply_flow):.3e} (Reynolds: "
                 f"its cavity loses flow), {float(jfo_s.supply_flow):.1e} m^2/s (JFO) of a film flow ~{flow:.3e}; "
                 f"JFO Kyy {Kj[0, 1, 1]:.4g} N/m^2 at Omega = 0, {Kj[-1, 1, 1]:.4g} at 1e3 rad/s")
    K = np.asarray(thesis.stiffness)
    lines.append(f"Thesis HS case: Kyy {K[0, 1, 1]:.4g} N/m^2 at 1e-3 rad/s, {K[len(K) // 2, 1, 1]:.4g} at 1 rad/s, "
                 f"{K[-1, 1, 1]:.4g} at 1e3 rad/s")
    lines.append(f"total {time.perf_counter() - t0:.1f} s")
    text = "\n".join(lines) + "\n"
    _common.atomic_write_text(out / "dynamics_summary.txt", text)
    print(text)
    checks = (
        _common.Check("rigid pi film: max relative error of K against the closed form", max(r[-2] for r in rigid),
                      1e-2 if quick else 1e-3, 0, "vjax.reference.long_bearing_coefficients", "max"),
        _common.Check("rigid pi film: max relative error of C against the closed form", max(r[-1] for r in rigid),
                      1e-2 if quick else 1e-3, 0, "vjax.reference.long_bearing_coefficients", "max"),
        _common.Check("rigid bearing: whirl frequency ratio at the threshold",
                      thresholds["rigid"]["whirl_ratio"] or float("nan"), 0.5, 0, "oil whirl below half speed", "max"),
        _common.Check("JFO: net groove flow over the film flow (mass conservation)", abs(float(jfo_s.supply_flow)) / flow,
                      1e-9, 0, "zero: no side leakage", "max"),
    )
    figures = (("dynamics_coefficients.png", "Stiffness and damping versus whirl frequency: rigid and polymer-lined "
                                             "bearing, and the thesis HS case"),
               ("dynamics_jfo.png", "Mass-conserving (JFO) against Reynolds cavitation with a groove fixed in the "
                                    "bearing: pressure, film fraction and stiffness versus whirl frequency"))
    about = ("Dynamic coefficients K(Omega) + i Omega C(Omega) of journal bearings for rotor models: rigid bearings "
             "against the closed-form pi-film coefficients, a polymer-lined bearing and the thesis case over four "
             "decades of whirl frequency, and the oil-whirl threshold of a rigid rotor on them.")
    return _common.StageReport(text, about, checks, figures)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
