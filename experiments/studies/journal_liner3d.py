"""A finite polymer-lined journal bearing with its bodies as plane-strain slices and as bonded
3D layers (issue 27, item 3(b)), side by side.

Run::

    PYTHONPATH=. python -m experiments.studies.journal_liner3d [out_dir] [--quick]

Case: R = 50 mm, c = 50 um, eta = 0.01 Pa s, journal at 100 rad/s, groove fixed opposite the
load at 1e4 Pa, Reynolds conditions, 32 theta cells by m = 16, 32, 48 axial intervals (--quick:
16 only): the minimum film of the 3D layer, at the land's ends, needs the axial refinement (the
pressure's drop to ambient there; a grid study of it from m = 32 to 256 follows the table, not
with --quick). Bodies: an SLS polymer (E0 = 0.3 GPa, E_inf = 3 GPa,
tau = 1 ms, nu = 0.4) as a 5 mm liner bonded in a rigid housing, and a 2 mm liner with a 3 mm
sleeve on the shaft. L/D = 0.5 and 1;
the load is the long bearing's at eps = 0.5 times L times 0.5 (L/D = 1) or 0.25 (L/D = 0.5).
For each: rigid, slices (``axial="slices"``) and 3D (``axial="3d"``): eccentricity, minimum
film and its axial position, peak pressure, shaft torque and its viscoelastic part, and the
3D-to-slices change.
Writes ``journal_liner3d.csv`` and prints the table.
"""
from __future__ import annotations

import sys
import time

from experiments import _common

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
D = 2 * R


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    import vjax
    from vjax import FiniteJournalOptions, reference

    sls = vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4)
    axial_grids = (16,) if quick else (16, 32, 48)
    w_long = float(reference.long_bearing(0.5, R, C, ETA, 0.5 * WJ * (R - C), "reynolds")["load"])
    bodies = {"liner 5 mm": lambda ax: dict(housing=vjax.liner(sls, 5e-3, axial=ax)),
              "liner 2 mm + sleeve 3 mm": lambda ax: dict(housing=vjax.liner(sls, 2e-3, axial=ax),
                                                          shaft=vjax.sleeve(sls, 3e-3, axial=ax))}
    header = ["L/D", "m", "bodies", "model", "eccentricity", "min_film_um", "min_film_z_over_L", "max_pressure_MPa",
              "torque_shaft_Nm",
              "torque_viscoelastic_shaft_Nm", "converged", "seconds"]
    rows = []
    for LD, share in ((1.0, 0.5), (0.5, 0.25)):
        L = LD * D
        W = share * w_long * L
        cases = [("rigid", "rigid", {})] + [(name, ax, make(ax)) for name, make in bodies.items()
                                            for ax in ("slices", "3d")]
        for (name, model, kw), m in ((c, m) for c in cases for m in axial_grids):
            opt = FiniteJournalOptions(n=32, m=m, max_iter=100)
            t0 = time.perf_counter()
            s = vjax.journal_bearing(R, C, ETA, W, omega_shaft=WJ, length=L, supply_pressure=1e4, options=opt,
                                     throw=False, **kw)
            rows.append([LD, m, name, model, float(s.eccentricity), 1e6 * float(s.min_film), float(s.min_film_z) / L,
                         1e-6 * float(s.max_pressure),
                         float(s.torque_shaft), float(s.torque_viscoelastic_shaft), bool(s.converged),
                         round(time.perf_counter() - t0, 1)])
            print(rows[-1], flush=True)
    lines = [f"# finite polymer-lined journal bearing: slices vs 3D layer; {_common.device_note()}",
             f"# grids 32 x {axial_grids}; change = 3D / slices - 1", ""]
    lines.append(_common.format_table(header, rows))
    lines += ["", "3D / slices - 1: eccentricity, min film, peak pressure, shaft torque"]
    by = {(r[0], r[1], r[2], r[3]): r for r in rows}
    for LD in (1.0, 0.5):
        for name in bodies:
            for m in axial_grids:
                a, b = by[(LD, m, name, "slices")], by[(LD, m, name, "3d")]
                lines.append(f"L/D {LD} m {m} {name}: " + "  ".join(f"{b[i] / a[i] - 1:+.2%}" for i in (4, 5, 7, 8)))
    if not quick:
        lines += ["", end_film_study(R, C, ETA, WJ, D, sls, w_long)]
    text = "\n".join(lines)
    print(text)
    _common.atomic_write_text(out / "journal_liner3d.txt", text + "\n")
    _common.write_csv(out / "journal_liner3d.csv", header, rows,
                      comments=[f"R={R} m, c={C} m, eta={ETA} Pa s, omega_shaft={WJ} rad/s, SLS(0.3 GPa, 3 GPa, 1 ms, 0.4), "
                                f"grids 32 x {axial_grids}, Reynolds, groove opposite the load at 1e4 Pa"])
    return rows


def end_film_study(R, C, ETA, WJ, D, sls, w_long, axial_grids=(32, 64, 128, 256)):
    """The 3D layer's minimum film (at the land's ends) against the axial grid, the 5 mm liner at
    L/D = 1 on 32 x m: each doubling's change, their ratio (4: second order) and the Richardson
    extrapolation of the last two grids at the observed ratio."""
    import vjax
    from vjax import FiniteJournalOptions
    films = []
    for m in axial_grids:
        s = vjax.journal_bearing(R, C, ETA, 0.5 * w_long * D, omega_shaft=WJ, length=D, supply_pressure=1e4,
                                 options=FiniteJournalOptions(n=32, m=m, max_iter=100), throw=False,
                                 housing=vjax.liner(sls, 5e-3, axial="3d"))
        films.append(1e6 * float(s.min_film))
        print(f"end film, m = {m}: {films[-1]:.4f} um (converged {bool(s.converged)})", flush=True)
    changes = [b - a for a, b in zip(films, films[1:])]
    ratio = changes[-2] / changes[-1]
    limit = films[-1] + changes[-1] / (ratio - 1)
    return (f"3D liner's minimum film at the land's ends (5 mm, L/D = 1, 32 x m), m = {axial_grids}: "
            + ", ".join(f"{f:.3f}" for f in films) + " um; changes " + ", ".join(f"{c:+.3f}" for c in changes)
            + f" (last ratio {ratio:.2f}); extrapolated {limit:.3f} um, the finest grid {films[-1] / limit - 1:+.2%}")


if __name__ == "__main__":
    main(*[a for a in sys.argv[1:2] if not a.startswith("--")], quick="--quick" in sys.argv)
