"""Grid convergence of the dynamic coefficients under Reynolds cavitation conditions (issue 27,
item 5): where the rupture boundary falls within its cell.

Run::

    PYTHONPATH=. python -m experiments.studies.rupture_convergence [out_dir] [--quick] [--no-2d] [--no-1d]

Writes ``rupture_convergence.txt`` (and prints it):

- the rigid infinitely long bearing (R = 50 mm, c = 50 um, eta = 0.01 Pa s, journal at
  100 rad/s, Reynolds conditions, the load of eps = 0.5 and 0.3 in the closed form), groove
  turning with the line of centres (default) and fixed in the bearing: the dimensionless
  K c / W and C c omega / W (line-of-centres frame: xx, xy, yx, yy), the rupture angle and
  where it falls in its cell, for n = 128 ... 2048; then the change from n to 2n (the largest
  entry change over the largest entry of K, of C);
- the rigid finite bearing (L/D = 1, the load of eps ~ 0.5) from 32 x 8 to 256 x 64, each grid
  doubling in both directions, the same measures.
"""
from __future__ import annotations

import sys
import time

from experiments import _common

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
V = 0.5 * WJ * (R - C)
D = 2 * R
NS = (128, 192, 256, 384, 512, 640, 768, 1024, 1536, 2048)
GRIDS_2D = ((32, 8), (64, 16), (128, 32), (256, 64))


def long_bearing(n, eps, groove):
    """(K c / W, C c omega / W) (2 x 2, line of centres), the rupture angle (rad) and the
    rupture's position in its cell (0 at the last pressurized cell's centre, 1 at the next)."""
    import numpy as np
    import vjax
    from vjax import JournalOptions, reference
    W = float(reference.long_bearing(eps, R, C, ETA, V, "reynolds")["load"])
    co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=WJ, groove=groove,
                                   options=JournalOptions(n=n, max_iter=200))
    K, Cd = (np.asarray(a[0]) for a in co.in_line_of_centres())
    rup = float(co.steady.rupture_angle)
    dth = 2 * np.pi / n
    # the rupture's position relative to the grid of the pressure (the line-of-centres frame)
    th = np.asarray(co.steady.theta)
    i = int(np.argmin(np.abs(np.angle(np.exp(1j * (th - rup))))))
    frac = float(np.angle(np.exp(1j * (rup - th[i]))) / dth)
    return K * C / W, Cd * C * WJ / W, rup, frac


def finite_bearing(n, m, eps=0.5):
    import numpy as np
    import vjax
    from vjax import FiniteJournalOptions, reference
    W = 0.5 * float(reference.long_bearing(eps, R, C, ETA, V, "reynolds")["load"]) * D
    co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=WJ, length=D,
                                   options=FiniteJournalOptions(n=n, m=m))
    K, Cd = (np.asarray(a[0]) for a in co.in_line_of_centres())
    return K * C / W, Cd * C * WJ / W, float(co.steady.eccentricity)


def change(a, b):
    """Largest entry change over the largest entry (of b)."""
    import numpy as np
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def study_1d(ns=NS, eps_values=(0.5, 0.3), grooves=("line_of_centres", "fixed")):
    """Lines of the 1D table, and {(eps, groove): {n: (K, C)}}."""
    import numpy as np
    fmt = lambda A: " ".join(f"{v:8.5f}" for v in np.ravel(A))  # noqa: E731
    lines, out = [], {}
    for eps in eps_values:
        for groove in grooves:
            lines += ["", f"long bearing, Reynolds, load of eps {eps} (closed form), groove {groove}: "
                          "K c/W (xx xy yx yy) | C c omega/W (xx xy yx yy) | rupture (deg) | its place in the cell"]
            res = {}
            for n in ns:
                t = time.perf_counter()
                K, Cd, rup, frac = long_bearing(n, eps, groove)
                res[n] = (K, Cd)
                lines.append(f"n {n:5d}: {fmt(K)} | {fmt(Cd)} | {np.degrees(rup):9.4f} | {frac:+.3f}"
                             f"   ({time.perf_counter() - t:.1f} s)")
                print(lines[-1], flush=True)
            lines.append("change from n to 2n (K; C):")
            for n in ns:
                if 2 * n in res:
                    lines.append(f"  {n:5d} -> {2 * n:5d}: {change(res[n][0], res[2 * n][0]):.2e}; "
                                 f"{change(res[n][1], res[2 * n][1]):.2e}")
            lines.append("change from the grid before (K; C): " + ", ".join(
                f"{b}: {change(res[a][0], res[b][0]):.1e}; {change(res[a][1], res[b][1]):.1e}"
                for a, b in zip(ns[:-1], ns[1:])))
            out[(eps, groove)] = res
    return lines, out


def study_2d(grids=GRIDS_2D):
    import numpy as np
    fmt = lambda A: " ".join(f"{v:8.5f}" for v in np.ravel(A))  # noqa: E731
    lines = ["", "finite bearing, L/D = 1, Reynolds, groove fixed opposite the load, load of eps ~ 0.5: "
                 "K c/W | C c omega/W (line of centres: xx xy yx yy) | eps | change from the grid before (K; C)"]
    previous = None
    for n, m in grids:
        t = time.perf_counter()
        K, Cd, e = finite_bearing(n, m)
        ch = "" if previous is None else f" | {change(previous[0], K):.2e}; {change(previous[1], Cd):.2e}"
        lines.append(f"{n:4d} x {m:3d}: {fmt(K)} | {fmt(Cd)} | {e:.5f}{ch}   ({time.perf_counter() - t:.1f} s)")
        print(lines[-1], flush=True)
        previous = (K, Cd)
    return lines


def main(out_dir="experiments/out", quick=False, one_d=True, two_d=True):
    out = _common.setup(out_dir)
    lines = [f"# rupture boundary and grid convergence of K, C (issue 27, item 5); {_common.device_note()}"]
    if one_d:
        lines += study_1d(NS[:6] if quick else NS)[0]
    if two_d:
        lines += study_2d(GRIDS_2D[:3] if quick else GRIDS_2D)
    text = "\n".join(lines)
    print(text)
    _common.atomic_write_text(out / "rupture_convergence.txt", text + "\n")
    return text


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(*(args[:1] or ["experiments/out"]), quick="--quick" in sys.argv, one_d="--no-1d" not in sys.argv,
         two_d="--no-2d" not in sys.argv)
