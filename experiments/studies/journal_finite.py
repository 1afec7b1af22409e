"""Finite-length rigid journal bearing (issue 27): the heavier checks the tests keep small.

Run::

    PYTHONPATH=. python -m experiments.studies.journal_finite [out_dir] [--quick]

Writes ``journal_finite.txt`` (and prints it): Raimondi and Boyd's table (L/D = 1, 0.5,
Reynolds conditions) on two grids; Ocvirk's short bearing (load ratio at L/D = 0.05, 0.1,
0.2 on two axial grids); the long-bearing limit (eccentricity against D/L and its
extrapolation); warm time, Newton steps and time per step of one rigid point and of one with
a polymer liner for grids from 64 x 16 to 1024 x 256, against the exact block solve and the
dense LU in the same run (the baseline), and the dynamic
coefficients at 16 whirl frequencies, rigid and lined (compile apart; the machine's load
average next to them), and the lined bearing's whirl solves alone from 32 x 8 to 256 x 64
(matrix-free GMRES against the dense complex LU in the same run); a grid study of the rigid
bearing's K and C from 32 x 8 to 512 x 128 at L/D = 0.5 and 1, eps about 0.3 to 0.7
(``--grid-study``: that section alone, ``journal_finite_grid.txt`` and ``.png``). Case:
R = 50 mm, c = 50 um, eta = 0.01 Pa s, journal at 100 rad/s.

ROSS: if the environment variable ``VJAX_ROSS_PYTHON`` names a Python interpreter with ROSS 3.x
(``ross-rotordynamics``; it needs Python >= 3.13, so a side venv), the rigid point of the timings
is also solved by ROSS's ``PlainJournal`` in that interpreter, a separate process
(``experiments/peers/ross_peer.py``), on vjax's largest rigid grid and on ROSS's default grid (40 x 20):
its first and warm times (without its import) and its eccentricity and attitude next to vjax's.
Unset, or if that run fails, the text says ROSS was not timed and why.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

from experiments import _common

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
V = 0.5 * WJ * (R - C)
D = 2 * R
N_REV = WJ / (2 * 3.141592653589793)
# Raimondi and Boyd (ASLE Trans. 1, 1958), full bearing, Reynolds conditions, as reproduced in
# Shigley's Mechanical Engineering Design (ch. 12): eps, S, attitude (deg), (r/c) f,
# Q/(r c N L), Qs/Q, P/p_max.
RAIMONDI_BOYD = {1.0: [(0.2, 0.631, 74.02, 12.8, 3.59, 0.280, 0.529), (0.4, 0.264, 63.10, 5.79, 3.99, 0.497, 0.484),
                       (0.6, 0.121, 50.58, 3.22, 4.33, 0.680, 0.415), (0.8, 0.0446, 36.24, 1.70, 4.62, 0.842, 0.313)],
                 0.5: [(0.2, 2.03, 74.94, 40.9, 3.72, 0.318, 0.506), (0.4, 0.779, 61.45, 17.0, 4.29, 0.552, 0.441),
                       (0.6, 0.319, 48.14, 8.10, 4.85, 0.730, 0.365), (0.8, 0.0923, 33.31, 3.26, 5.41, 0.874, 0.267)]}


def ross_lines(load, eccentricity, attitude_deg, grid, ross_grids=((256, 64), (40, 20)), timeout=900):
    """Lines on ROSS's PlainJournal for the rigid point (``experiments/peers/ross_peer.py`` run by
    ``$VJAX_ROSS_PYTHON``, one process per grid in ``ross_grids``) next to vjax's ``eccentricity``
    and ``attitude_deg`` on ``grid``, or a line saying why ROSS was not timed. Never raises."""
    python = os.environ.get("VJAX_ROSS_PYTHON")
    if not python:
        return ["ROSS was not timed: VJAX_ROSS_PYTHON is not set (see the module docstring)."]
    script = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "peers", "ross_peer.py")
    head, lines = [], []
    for n, m in ross_grids:
        try:
            cmd = [python, script, "--load", repr(load), "--groove", "opposite-load", "--n-theta", str(n),
                   "--n-z", str(m)]
            run = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
            if run.returncode:
                raise RuntimeError(f"exit status {run.returncode}: {(run.stderr.strip().splitlines() or [''])[-1]}")
            r = json.loads(run.stdout.strip().splitlines()[-1])
        except Exception as e:  # the benchmark goes on without ROSS
            lines.append(f"ROSS {n}x{m} was not timed: {python} experiments/peers/ross_peer.py failed: {e}")
            continue
        head = [f"ROSS {r['ross_version']} PlainJournal, the same rigid point (load {load:.1f} N), in a separate "
                f"process (Python {r['python']}; its times include no import, its first is its process's first "
                "solve); one 359-degree land, its groove opposite the load as vjax's, given load / (1 - 1/ny^2) "
                "for its cross-film integration:"]
        lines.append(f"ROSS {r['n_theta']}x{r['n_z']} (ny {r['ny']}): first {r['wall_first_s']:.2f} s, warm "
                     f"{r['wall_median_s']:.3f} s (median of 3); eccentricity {r['eccentricity']:.5f} "
                     f"(vjax {grid[0]}x{grid[1]}: {eccentricity:.5f}), attitude {r['attitude_deg']:.2f} deg "
                     f"(vjax {attitude_deg:.2f})"
                     + ("" if r["mesh_ok"] else f"; h_min/ny {r['hmin_over_ny_um']:.2f} um < 1 um: ROSS unreliable"))
    return head + lines


def grid_study(out, quick=False):
    """Grid convergence of the rigid finite bearing's K and C under Reynolds conditions, the
    groove fixed at the maximum film (found by two passes on the coarsest grid, then moved to
    the nearest node of that grid, which is a node of every grid, and held: one bearing), L/D = 0.5 and 1, the load that puts the long bearing at eps 0.3
    and 0.7, times L / 4; grids 32 x 8 ... 512 x 128 (64 x 16 quick). Each 2 x 2 matrix over its
    largest entry; the change is the largest from the grid before. Returns the text's lines
    and writes ``journal_finite_grid.png`` (change against grid)."""
    import matplotlib.pyplot as plt
    import numpy as np
    import vjax
    from vjax import FiniteJournalOptions, reference
    grids = [(32, 8), (64, 16)] if quick else [(32, 8), (64, 16), (128, 32), (256, 64), (512, 128)]
    lines = ["Grid study of K and C (rigid, Reynolds, the rupture within its cell, groove fixed at the maximum "
             "film; each 2 x 2 matrix over its largest entry): the largest change from the grid before"]
    fig, ax = plt.subplots(figsize=(6, 4))
    for LD, eps in ((1.0, 0.3), (1.0, 0.7), (0.5, 0.3), (0.5, 0.7)):
        L = LD * D
        W = float(reference.long_bearing(eps, R, C, ETA, V, "reynolds")["load"]) * L / 4
        phi = 0.6
        for _ in range(2):          # the groove at the maximum film: opposite the line of centres
            phi = float(vjax.journal_bearing(R, C, ETA, W, omega_shaft=WJ, length=L, supply_angle=np.pi + phi,
                                             options=FiniteJournalOptions(n=32, m=8)).attitude_angle)
        # on a node of the coarsest grid, hence of every grid: a groove snapped to each grid's
        # nearest cell would move by up to half a cell from grid to grid (an O(dtheta) change)
        step = 2 * np.pi / grids[0][0]
        phi = step * round((np.pi + phi) / step) - np.pi
        previous, changes = None, []
        for n, m in grids:
            t = time.perf_counter()
            co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=WJ, length=L, supply_angle=np.pi + phi,
                                           options=FiniteJournalOptions(n=n, m=m, max_iter=100))
            K, Cd = (np.asarray(a).reshape(2, 2) for a in (co.stiffness, co.damping))
            scaled = np.concatenate([K.ravel() / np.abs(K).max(), Cd.ravel() / np.abs(Cd).max()])
            change = ""
            if previous is not None:
                changes.append(np.max(np.abs(scaled - previous)))
                change = f", change {changes[-1]:.2e}"
            lines.append(f"L/D {LD}, eps {float(co.steady.eccentricity):.3f}, {n}x{m}: K (MN/m) "
                         f"{np.array2string(K.ravel() / 1e6, precision=3)}, C (kN s/m) "
                         f"{np.array2string(Cd.ravel() / 1e3, precision=2)}{change} "
                         f"({time.perf_counter() - t:.1f} s)")
            print(lines[-1], flush=True)
            previous = scaled
        ax.loglog([n for n, _ in grids[1:]], changes, "o-", label=f"L/D {LD}, long-bearing eps {eps}")
    ax.axhline(3e-3, color="0.5", ls="--", label="0.3 %")
    ax.set_xlabel("n (cells in theta; m = n / 4 across)")
    ax.set_ylabel("largest change of K, C from the grid before")
    ax.set_title("Finite bearing, Reynolds: K and C against the grid")
    ax.legend(fontsize=8)
    fig.tight_layout()
    _common.save_figure(fig, out / "journal_finite_grid.png")
    plt.close(fig)
    return lines


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    import dataclasses

    import jax
    import jax.numpy as jnp
    import numpy as np
    import vjax
    from vjax import FiniteJournalOptions, JournalOptions, reference
    from vjax.scenes.journal.finite import coefficients as finite_coefficients, film as finite_film, setup as finite_setup

    lines = [f"# finite journal bearing (issue 27); {_common.device_note()}", ""]
    grids = [(48, 16)] if quick else [(48, 16), (96, 32)]
    lines.append("Raimondi-Boyd (computed / table): eps, attitude deg, (r/c)f, Q/(rcNL), Qs/Q, P/pmax")
    for n, m in grids:
        opt = FiniteJournalOptions(n=n, m=m, max_iter=200)
        for LD, rows in RAIMONDI_BOYD.items():
            L = LD * D
            for eps, S, phi, fv, qv, qs, pm in rows:
                W = (R / C) ** 2 * ETA * N_REV * 2 * R * L / S
                s = vjax.journal_bearing(R, C, ETA, W, omega_shaft=WJ, length=L, supply_angle=np.pi + np.radians(phi),
                                         options=opt, throw=False)
                Q = float(s.inlet_flow)
                got = (float(s.eccentricity), np.degrees(float(s.attitude_angle)), abs(float(s.torque_shaft)) / (W * C),
                       Q / (R * C * N_REV * L), float(s.side_leakage) / Q, W / (2 * R * L) / float(s.max_pressure))
                ref = (eps, phi, fv, qv, qs, pm)
                lines.append(f"{n}x{m} L/D {LD}: " + "  ".join(f"{g:.4g}/{r:.4g}" for g, r in zip(got, ref))
                             + ("" if bool(s.converged) else f"  NOT CONVERGED ({int(s.iterations)} steps)"))
    lines += ["", "Ocvirk: load ratio W_ocvirk(eps)/W (Reynolds; half-Sommerfeld)"]
    for m in ([16] if quick else [16, 32, 64]):
        opt = FiniteJournalOptions(n=48, m=m)
        for LD in (0.05, 0.1, 0.2):
            L = LD * D
            W = float(reference.short_bearing(0.5, R, C, ETA, V, L)["load"])
            ratio = []
            for cav in ("reynolds", "half_sommerfeld"):
                s = vjax.journal_bearing(R, C, ETA, W, omega_shaft=WJ, length=L, supply_angle=None, cavitation=cav,
                                         options=opt)
                ratio.append(float(reference.short_bearing(float(s.eccentricity), R, C, ETA, V, L)["load"]) / W)
            lines.append(f"48x{m} L/D {LD}: {ratio[0]:.5f}; {ratio[1]:.5f}")
    lines += ["", "Long-bearing limit (Reynolds, groove fixed opposite the load, n = 48, m = 32 cosine): "
              "eps / eps_long - 1"]
    W1 = float(reference.long_bearing(0.6, R, C, ETA, V, "reynolds")["load"])
    e0 = float(vjax.journal_bearing(R, C, ETA, W1, omega_shaft=WJ, groove="fixed",
                                    options=JournalOptions(n=48)).eccentricity)
    opt = FiniteJournalOptions(n=48, m=32, spacing="cosine")
    eps = {}
    for LD in (12.5, 25.0, 50.0, 100.0):
        eps[LD] = float(vjax.journal_bearing(R, C, ETA, W1 * LD * D, omega_shaft=WJ, length=LD * D,
                                             options=opt).eccentricity)
        lines.append(f"L/D {LD}: {eps[LD] / e0 - 1:.4e}")
    lines.append(f"extrapolated from 50 and 100: {(2 * eps[100.0] - eps[50.0]) / e0 - 1:.2e}")
    W = 0.5 * float(reference.long_bearing(0.5, R, C, ETA, V, "reynolds")["load"]) * D
    liner = vjax.liner(vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4), 2e-3)

    def timing(n, m, housing, baseline=False):
        """One point's first call and the median of three warm ones (loads 1-3 % higher); the
        baseline: the solver before the half width and the multigrid (the whole width, a zero
        tilt given; the exact block solve for a rigid film, the dense LU with a liner)."""
        solver_setting(baseline)
        solver = "dense" if baseline else "auto"
        opt = FiniteJournalOptions(n=n, m=m, linear_solver=solver)
        run = lambda w: vjax.journal_bearing(R, C, ETA, w, omega_shaft=WJ, length=D, housing=housing,  # noqa: E731
                                             options=opt, tilt=(0.0, 0.0) if baseline else None)
        t = time.perf_counter()
        run(W).eccentricity.block_until_ready()
        first = time.perf_counter() - t
        times = []
        for k in range(3):
            t = time.perf_counter()
            s = run(W * (1 + 0.01 * (k + 1)))
            s.eccentricity.block_until_ready()
            times.append(time.perf_counter() - t)
        its, med = int(s.iterations), float(np.median(times))
        N = n * (m - 1) if baseline else n * m // 2          # the cell unknowns
        per_step = med / max(its, 1)
        return (f"{'baseline ' if baseline else ''}{n}x{m} (N = {N}): first {first:.1f} s, warm {med:.3f} s, "
                f"{its} Newton steps, {per_step * 1e3:.1f} ms per step, {per_step / (N * np.log2(N)) * 1e9:.0f} ns "
                f"per N log2 N")
    def solver_setting(baseline):
        """The baseline's exact block solve at every width, or today's setting (the solvers read it
        when they are traced: JAX's caches are cleared at each switch)."""
        if baseline != solver_setting.baseline:
            jax.clear_caches()
            finite_film.EXACT_WIDTH = 10**9 if baseline else EXACT_WIDTH
            solver_setting.baseline = baseline
    solver_setting.baseline = False
    EXACT_WIDTH = finite_film.EXACT_WIDTH

    grids = [(64, 16), (128, 32)] if quick else [(64, 16), (128, 32), (256, 64), (512, 128), (1024, 256)]
    lines += ["", f"Warm time per point (L/D = 1, Reynolds, the aligned bearing's half width: N = n m / 2 cell "
              f"unknowns), load average {os.getloadavg()[0]:.1f}. Newton's steps: the exact block solve up to "
              f"{EXACT_WIDTH} cells across the half width, GMRES with the multigrid V-cycle above; with the liner, "
              "GMRES preconditioned by the film's block solve (or the V-cycle). Baseline in the same run, the solver "
              "before: the whole width (N = n (m - 1)), the exact block solve (rigid), the dense LU (liner)."]
    lines += ["rigid:"] + [timing(n, m, None) for n, m in grids]
    grid = grids[min(2, len(grids) - 1)]            # 256 x 64 (128 x 32 quick), as the timing's
    rigid = vjax.journal_bearing(R, C, ETA, W, omega_shaft=WJ, length=D,
                                 options=FiniteJournalOptions(n=grid[0], m=grid[1]))
    ross = ross_lines(W, float(rigid.eccentricity), float(np.degrees(rigid.attitude_angle)), grid,
                      ross_grids=(grid, (40, 20)))
    lines += [timing(n, m, None, baseline=True) for n, m in grids[:3]]
    lines += ross
    lines += ["2 mm polymer liner:"] + [timing(n, m, liner) for n, m in grids]
    lines += [timing(n, m, liner, baseline=True) for n, m in [(32, 8), (48, 16), (64, 16)][:2 if quick else 3]]
    solver_setting(False)           # the sections below: today's solver
    lines += [""] + grid_study(out, quick)
    whirl = np.linspace(0.0, 2.0 * WJ, 16)
    lines += ["", "Dynamic coefficients at 16 whirl frequencies (0 ... 2 omega), L/D = 1, 32 x 8, warm (first):"]
    for name, body in (("rigid", None), ("liner", liner)):
        call = lambda: vjax.journal_coefficients(R, C, ETA, W, whirl, omega_shaft=WJ, length=D,  # noqa: E731
                                                 housing=body, options=FiniteJournalOptions(n=32, m=8))
        t = time.perf_counter()
        call().stiffness.block_until_ready()
        first = time.perf_counter() - t
        t = time.perf_counter()
        call().stiffness.block_until_ready()
        lines.append(f"{name}: {time.perf_counter() - t:.3f} s ({first:.1f} s)")
    lines += ["", "The lined bearing's whirl solves alone (about its converged steady state, 16 frequencies), median "
              "of 3 warm calls (first call apart): matrix-free GMRES, one solve per frequency and load column, "
              "against the dense complex LU of the same system (the baseline, the solver before) in the same run"]
    for n, m in [(32, 8), (64, 16)] if quick else [(32, 8), (64, 16), (128, 32), (256, 64)]:
        kw = dict(omega_shaft=WJ, housing=liner, options=FiniteJournalOptions(n=n, m=m))
        steady = vjax.journal_bearing(R, C, ETA, W, length=D, **kw)
        pr, cfg = finite_setup.setup(R, C, ETA, W, D, **kw)
        bodies = ((liner, R, 0.0), (None, R - C, -WJ))
        row = f"{n}x{m} (N = {n * (m - 1)}):"
        for dense in (False, True) if n * (m - 1) <= 1000 else (False,):
            go = lambda: finite_coefficients.coefficients(  # noqa: E731
                steady, pr, dataclasses.replace(cfg, krylov=not dense), bodies, jnp.asarray(whirl))
            t = time.perf_counter()
            result = go()
            result[1].block_until_ready()
            first = time.perf_counter() - t
            times = []
            for _ in range(3):
                t = time.perf_counter()
                go()[1].block_until_ready()
                times.append(time.perf_counter() - t)
            residual = "" if dense else f", largest GMRES residual {float(np.max(result[3].residual)):.1e}"
            row += f" {'dense LU' if dense else 'GMRES'} {np.median(times):.3f} s (first {first:.1f} s){residual};"
        lines.append(row)
    text = "\n".join(lines)
    print(text)
    _common.atomic_write_text(out / "journal_finite.txt", text + "\n")
    return text


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if "--grid-study" in sys.argv:      # that section alone
        out = _common.setup(args[0] if args else "experiments/out")
        _common.atomic_write_text(out / "journal_finite_grid.txt", "\n".join(grid_study(out, "--quick" in sys.argv)) + "\n")
    else:
        main(*(args[:1] or ["experiments/out"]), quick="--quick" in sys.argv)
