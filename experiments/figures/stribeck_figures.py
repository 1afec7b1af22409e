"""Stribeck curves of a finite journal bearing: boundary friction, mixed lubrication, full film.

Run::

    python -m experiments.figures.stribeck_figures [out_dir] [--quick]

The bearing (issue 43's): journal radius 25 mm in a bore of R = 25.05 mm, c = 50 um, L/D = 1,
eta = 0.03 Pa s, W = 2 kN, no groove (the film periodic, ambient at both ends), Reynolds
cavitation, 32 x 16 cells: a coarse grid for the main job's time, which shows the curves' shape,
not their values (against 256 x 64 its friction coefficient is off by up to 154 % in the mixed
regime and its asperity share by 0.19; 128 x 32 is within 4.8 % and 0.02 and the lift-off speed
within 0.6 %: ``python -m experiments.studies.stribeck_grid``). A smooth steel journal in a rough bush: sigma = 1 um, eta_s beta
sigma = 0.05, sigma/beta = 0.005, E' from steel (210 GPa, 0.3) and polymer (3 GPa, 0.4),
mu_b = 0.1. Three curves over the journal's speed: a rigid bush and a 2 mm polymer liner
(SLS 1.5 -> 3 GPa, 10 ms), both with Patir-Cheng average flow and Greenwood-Tripp asperities
(:func:`vjax.stribeck_curve`), and today's smooth full film (roughness None), which stops
where its film would close. Friction coefficient and asperity share against the Hersey
number eta omega / p_mean, p_mean = W / (L D).

Outputs: ``stribeck.csv``, ``stribeck.png``, ``stribeck.txt``. :func:`stage` is the main job's
"stribeck" stage (``--quick``: 7 speeds instead of 13).
"""
from __future__ import annotations

import sys
from pathlib import Path

from experiments import _common

_common.enable_x64()

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

R, C, ETA, W = 25.05e-3, 50e-6, 0.03, 2000.0
L = 2 * R
ROUGH = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
LINER = vjax.liner(vjax.Material.sls(1.5e9, 3e9, 0.01, 0.4), 2e-3)
BEARING = dict(length=L, supply_angle=None, options=vjax.FiniteJournalOptions(n=32, m=16))


def smooth_curve(speeds, rough):
    """Today's smooth full film, warm-started down from the highest speed: (friction
    coefficient, converged) per speed (NaN where it fails: its film would close, and below).
    ``rough``: the rough rigid sweep (a :class:`vjax.StribeckCurve` on the same speeds and
    grid), whose point at each speed starts the smooth one where the last smooth point does
    not (at the top speed, and after a failure): the smooth film is then one compiled program
    (Newton from a given start), not two (a cold start from the rigid estimate is another)."""
    mu, ok, last = np.full(speeds.size, np.nan), np.zeros(speeds.size, bool), None
    for i in range(speeds.size - 1, -1, -1):
        r = None
        for start in ([last] if last is not None else []) + [rough.results[i]]:
            r = vjax.journal_bearing(R, C, ETA, W, omega_shaft=float(speeds[i]), initial=start, throw=False,
                                     **BEARING)
            if bool(r.converged):
                break
        if not bool(r.converged):      # the film closes here: at lower speeds too
            break
        ok[i], mu[i], last = True, float(r.friction_coefficient), r
    return mu, ok


def wrap_factor(r):
    """int p_a dA / |int p_a n dA| of a result's asperity pressure (trapezoidal in z)."""
    theta, z, p_a = np.asarray(r.theta), np.asarray(r.z), np.asarray(r.asperity_pressure)
    d = np.diff(z)
    dA = 0.5 * (np.concatenate([[0.0], d]) + np.concatenate([d, [0.0]]))[None, :]
    return np.sum(p_a * dA) / np.hypot(np.sum(p_a * np.cos(theta)[:, None] * dA), np.sum(p_a * np.sin(theta)[:, None] * dA))


def main(out_dir="experiments/out", quick=False, folder="stribeck"):
    """The figure and its table in ``<out_dir>/<folder>/`` (the main job's stage: ``folder`` "",
    its ``out_dir`` the stage's folder already)."""
    out = _common.setup(out_dir) / folder
    out.mkdir(parents=True, exist_ok=True)
    speeds = np.logspace(-3, 2, 7 if quick else 13)
    rigid = vjax.stribeck_curve(R, C, ETA, W, speeds, roughness=ROUGH, **BEARING)
    lined = vjax.stribeck_curve(R, C, ETA, W, speeds, roughness=ROUGH, housing=LINER, **BEARING)
    smooth, smooth_ok = smooth_curve(speeds, rigid)
    hersey = rigid.hersey
    rows = [(speeds[k], hersey[k], rigid.friction_coefficient[k], rigid.asperity_share[k], rigid.eccentricity[k],
             lined.friction_coefficient[k], lined.asperity_share[k], lined.eccentricity[k], smooth[k])
            for k in range(speeds.size)]
    header = ("omega (rad/s)", "Hersey", "mu rigid", "share rigid", "eps rigid", "mu lined", "share lined",
              "eps lined", "mu smooth")
    _common.write_csv(out / "stribeck.csv", header, rows)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    for curve, label, style in ((rigid, "rough, rigid bush", "o-"), (lined, "rough, 2 mm polymer liner", "s-")):
        a.loglog(curve.hersey, curve.friction_coefficient, style, label=label)
        b.semilogx(curve.hersey, curve.asperity_share, style, label=label)
        if curve.lift_off_speed is not None:
            b.axvline(ETA * curve.lift_off_speed / (W / (L * 2 * R)), ls=":", color=a.lines[-1].get_color())
    a.loglog(hersey[smooth_ok], smooth[smooth_ok], "k--", label="smooth full film (today's)")
    a.set(xlabel="Hersey number eta omega / p_mean", ylabel="friction coefficient")
    b.set(xlabel="Hersey number eta omega / p_mean", ylabel="asperity share of the load", ylim=(-0.02, 1.02))
    a.legend(fontsize=8)
    b.legend(fontsize=8, title="dotted: lift-off (1 %)")
    fig.suptitle("Stribeck curves: L/D = 1, c = 50 um, sigma = 1 um, W = 2 kN, eta = 0.03 Pa s")
    _common.save_figure(fig, out / "stribeck.png")
    lines = [_common.format_table(header, rows), ""]
    for name, curve in (("rigid", rigid), ("lined", lined)):
        lines.append(f"{name}: {curve!r}; Stribeck minimum at "
                     f"{'none' if curve.minimum_speed is None else f'{curve.minimum_speed:.3g} rad/s'}; "
                     f"wrap factor at the slowest point {wrap_factor(curve.results[0]):.4f}")
    text = "\n".join(lines)
    _common.atomic_write_text(out / "stribeck.txt", text + "\n")
    print(text)
    return rigid, lined, smooth, smooth_ok


def stage(out_dir, quick=False):
    """The main job's stage: :func:`main` and its checks."""
    rigid, lined, smooth, smooth_ok = main(out_dir, quick, folder="")
    slow = rigid.results[0]
    top = -1
    checks = (
        _common.Check("Stribeck sweeps: fraction of points converged (rigid and lined, boundary to full film)",
                      (rigid.converged.sum() + lined.converged.sum()) / (2 * rigid.speed.size), 1.0, 0,
                      "every point, warm-started", "min"),
        _common.Check("boundary limit (rigid, 0.001 rad/s): friction coefficient / (mu_b x wrap factor)",
                      rigid.friction_coefficient[0] / (float(ROUGH.mu_b) * wrap_factor(slow)), 1.0, 0.01,
                      "dry sliding: mu_b times int p_a dA / |int p_a n dA| as the asperities carry all the load"),
        _common.Check("full-film limit (100 rad/s): rough / smooth friction coefficient - 1",
                      rigid.friction_coefficient[top] / smooth[top] - 1.0, 0.0, 0.01,
                      "at lambda ~ 20 the average-flow film is the smooth one"),
    )
    about = ("A finite journal bearing (L/D = 1, c = 50 um, W = 2 kN, eta = 0.03 Pa s) from boundary friction through "
             "mixed lubrication to a full film: Patir-Cheng average flow with Greenwood-Tripp asperities (sigma = 1 um, "
             "mu_b = 0.1), a rigid bush and a 2 mm polymer liner loaded by the film and the asperities together, "
             "against today's smooth film, which stops where it would close. On 32 x 16 cells, which show the curves' "
             "shape, not their values (128 x 32 or finer for numbers: experiments/studies/stribeck_grid.py).")
    text = (Path(out_dir) / "stribeck.txt").read_text()
    return _common.StageReport(text, about, checks, (("stribeck.png", "friction coefficient and asperity share "
                                                      "against the Hersey number; lift-off where 1 % of the load "
                                                      "is on the asperities"),))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
