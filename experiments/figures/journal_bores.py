"""Journal bearings in Prony bores: where the solver converges, how fast, and what it says where not.

Run::

    PYTHONPATH=. python -m experiments.figures.journal_bores [out_dir] [--quick]

The bearing: R = 50 mm, c = 50 um, eta = 0.01 Pa s, rigid journal turning, bore at rest, n =
256, Reynolds conditions, default options. Two bores, Prony series with E0 and three arms of
3 E0 each at 1 ms, 10 ms and 100 ms:

- **nearly rigid**: E0 = 1 GPa, nu = 0.4, at 2e4 N/m and 100 and 1000 rad/s: its rigid-body
  (mode 1) displacement is about a third of the clearance, its film barely deforms;
- **soft**: E0 = 1 MPa, nu = 0.5, over two decades of journal speed (10..1000 rad/s) and of
  load (2e2..2e4 N/m).

For every point: the result code, Newton steps, continuation stages, the warm time per call
(second call, compilation apart), eps, h_min / c, the largest bore displacement over R, and
the film-shape deformation number D = |M_2| (W / 2R) / c (the bore's mode-2 compliance times
the mean pressure, in clearances: the scale on which the bore changes the film's shape). The
message of each failure is kept. Where D reaches tens of clearances the bore's displacement is
a sizeable fraction of R: a soft conformal contact, beyond Newton's reach from any start here
and beyond the small strains of linear viscoelasticity; the solver says so in its error.

Outputs: ``journal_bores.csv``, ``journal_bores.png`` (the soft bore's map), ``journal_bores.txt``.
:func:`stage` is the main job's "bores" stage (``--quick``: every other speed and load).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

from experiments import _common

_common.enable_x64()

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

R, C, ETA, N = 0.05, 5e-5, 0.01, 256
SPEEDS = (10.0, 31.6, 100.0, 316.0, 1000.0)
LOADS = (2e2, 6.32e2, 2e3, 6.32e3, 2e4)


def bore(E0, nu):
    """Prony bore: E0 (Pa) and three arms of 3 E0 at 1, 10 and 100 ms."""
    return vjax.Material.prony(E0, [3 * E0] * 3, [1e-3, 1e-2, 1e-1], nu)


def deformation_number(material, load):
    """D = |M_2| (load / 2R) / c: mode 2 of the bore at rest (relaxed) under the mean pressure,
    in clearances."""
    op = vjax.ring_operator("hole", material, R, N)
    return float(abs(complex(op.symbol[2]))) * load / (2 * R) / C


def point(material, omega, load):
    """One bearing: a dict of the row's values. A converged point is solved again and that call
    timed (a bore's first call compiles its program); a failed one is solved once, its message
    and unconverged result taken from the error (that call is warm: each bore's first point
    converges)."""
    kw = dict(housing=material, omega_shaft=omega, options=vjax.JournalOptions(n=N))
    message = ""
    t0 = time.perf_counter()
    try:
        s = vjax.journal_bearing(R, C, ETA, load, **kw)
    except vjax.ConvergenceError as e:
        message, s = str(e), e.solution
    s.eccentricity.block_until_ready()
    wall = time.perf_counter() - t0
    if not message:
        t0 = time.perf_counter()
        s = vjax.journal_bearing(R, C, ETA, load, **kw)
        s.eccentricity.block_until_ready()
        wall = time.perf_counter() - t0
    return dict(omega=omega, load=load, converged=bool(s.converged), result=int(s.result),
                iterations=int(s.iterations), stages=int(s.stages), time_s=wall, eps=float(s.eccentricity),
                hmin_over_c=float(s.min_film) / C, umax_over_R=float(np.max(np.abs(np.asarray(s.displacement)))) / R,
                D=deformation_number(material, load), message=message)


def plot(path, soft, speeds, loads):
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.4), layout="constrained")
    ns, nl = len(speeds), len(loads)
    grid = np.array([[soft[i * nl + j]["converged"] for j in range(nl)] for i in range(ns)], float)
    ax[0].imshow(grid.T, origin="lower", cmap="RdYlGn", vmin=-0.3, vmax=1.3, aspect="auto")
    for i in range(ns):
        for j in range(nl):
            r = soft[i * nl + j]
            ax[0].text(i, j, f"{r['iterations']} steps\n{r['stages']} stages\nD={r['D']:.2g}", ha="center",
                       va="center", fontsize=7)
    ax[0].set_xticks(range(ns), [f"{w:g}" for w in speeds])
    ax[0].set_yticks(range(nl), [f"{w:g}" for w in loads])
    ax[0].set_xlabel("journal speed (rad/s)")
    ax[0].set_ylabel("load (N/m)")
    ax[0].set_title("soft Prony bore (E0 = 1 MPa): green converged, red failed", fontsize=10)
    for i, w in enumerate(speeds):
        rows = soft[i * nl:(i + 1) * nl]
        ok = [r for r in rows if r["converged"]]
        if ok:
            ax[1].plot([r["load"] for r in ok], [r["hmin_over_c"] for r in ok], "o-", label=f"{w:g} rad/s")
    ax[1].set_xscale("log")
    ax[1].set_xticks(loads, [f"{v:g}" for v in loads])
    ax[1].minorticks_off()
    ax[1].set_xlabel("load (N/m)")
    ax[1].set_ylabel("minimum film / clearance")
    ax[1].set_title("converged points: the soft bore opens the film")
    ax[1].legend(fontsize=8)
    _common.save_figure(fig, path)


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    print(f"device: {_common.device_note()}", flush=True)
    speeds, loads = (SPEEDS[::2], LOADS[::2]) if quick else (SPEEDS, LOADS)
    rows = []
    for omega in (100.0, 1000.0):
        rows.append(dict(point(bore(1e9, 0.4), omega, 2e4), bore="nearly rigid"))
        print(f"nearly rigid bore, {omega:g} rad/s: converged {rows[-1]['converged']}, {rows[-1]['iterations']} steps, "
              f"{rows[-1]['time_s']:.3f} s", flush=True)
    soft = []
    for omega in speeds:
        for load in loads:
            soft.append(dict(point(bore(1e6, 0.5), omega, load), bore="soft"))
            r = soft[-1]
            print(f"soft bore, {omega:g} rad/s, {load:g} N/m: converged {r['converged']}, {r['iterations']} steps, "
                  f"{r['stages']} stages, D = {r['D']:.3g}, {r['time_s']:.3f} s", flush=True)
    rows += soft
    cols = ["bore", "omega", "load", "converged", "result", "iterations", "stages", "time_s", "eps", "hmin_over_c",
            "umax_over_R", "D"]
    _common.write_csv(out / "journal_bores.csv", cols, [[r[c] for c in cols] for r in rows],
                      comments=[f"R={R} m, c={C} m, eta={ETA} Pa s, n={N}, Reynolds conditions, bore at rest; "
                                "Prony bores E0 + 3 arms of 3 E0 at 1, 10, 100 ms", "time_s: a warm call (converged: the second call; failed: the only one, its bore compiled by an earlier point)",
                                "D: mode-2 compliance x load/(2R) / c (film-shape deformation in clearances)"])
    plot(out / "journal_bores.png", soft, speeds, loads)
    conv = [r for r in soft if r["converged"]]
    failed = [r for r in soft if not r["converged"]]
    lines = [_common.format_table(cols, [[r[c] for c in cols] for r in rows]),
             f"soft bore: {len(conv)} of {len(soft)} points converged, D up to "
             f"{max((r['D'] for r in conv), default=float('nan')):.3g}; failed at D >= "
             f"{min((r['D'] for r in failed), default=float('nan')):.3g} (bore displacement up to "
             f"{max((r['umax_over_R'] for r in failed), default=float('nan')):.2g} R)"]
    if failed:
        lines.append(f"the solver's message at {failed[-1]['omega']:g} rad/s, {failed[-1]['load']:g} N/m: "
                     f"{failed[-1]['message']}")
    text = "\n".join(lines)
    print(text)
    _common.atomic_write_text(out / "journal_bores.txt", text + "\n")
    return rows


def stage(out_dir, quick=False):
    """The main job's stage: :func:`main` and its checks."""
    rows = main(out_dir, quick)
    rigid = [r for r in rows if r["bore"] == "nearly rigid"]
    soft = [r for r in rows if r["bore"] == "soft"]
    modest = [r for r in soft if r["D"] <= 25]
    huge = [r for r in soft if r["D"] >= 100]
    checks = (
        _common.Check("nearly rigid bore: largest number of Newton steps (100 and 1000 rad/s, direct)",
                      max(r["iterations"] + 100 * r["stages"] for r in rigid), 15, 0,
                      "a few Newton steps from a good start (both stages: the rupture on a face, then within "
                      "its cell)", "max"),
        _common.Check("soft bore: fraction of points with film-shape deformation <= 25 clearances that converged",
                      sum(r["converged"] for r in modest) / len(modest), 1.0, 0, "all of them", "min"),
        _common.Check("soft bore: failures at >= 100 clearances whose error names the cause (fraction)",
                      sum("clearances under this load" in r["message"] for r in huge) / max(len(huge), 1), 1.0, 0,
                      "every failure says why", "min"),
    )
    about = ("Journal bearings (R = 50 mm, c = 50 um, eta = 0.01 Pa s, n = 256) in Prony bores: a nearly rigid one "
             "(E0 = 1 GPa) at 2e4 N/m, and a soft one (E0 = 1 MPa) over two decades of journal speed and load. D is "
             "the bore's film-shape deformation in clearances (mode-2 compliance x mean pressure / c); where it "
             "reaches ~100 the bore's displacement is a large fraction of R, outside linear viscoelasticity, and the "
             "solver's error says so.")
    text = (Path(out_dir) / "journal_bores.txt").read_text()
    return _common.StageReport(text, about, checks, (("journal_bores.png", "soft bore: converged (green) or "
                                                      "failed (red), Newton steps, stages, D; minimum film "
                                                      "over clearance"),))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
