"""Work-precision report (issue 8): error against warm run time for every scene and the DMA fit.

Run::

    PYTHONPATH=. python -m experiments.benchmarks.work_precision [out_dir] [--quick]

Ladders (float64, one solve per point, the median of warm calls; the first call, i.e.
tracing + compilation + one run, is reported separately as ``compile_s``):

- **pin** (a) elastic incompressible plane against the analytical Persson-type solution
  (:mod:`vjax.reference`; R = 0.08 m, dR = 4e-5 m, E = 1 MPa, F~ = 1e-2, the rigid-body
  reference chosen so that the pin offset is dR, see ``persson.small_displacement_pin``):
  error = max |p - p_exact| / p_max over |theta| < 0.9 alpha (the contact edges, where p
  has a square-root profile, cost one element of accuracy), and the contact-angle error.
  pin_in_hole keeps the exact circle geometry and the slope terms of Eq. 2.21, so it
  differs from the linear theory by O(dR/R) (a floor of about 2e-4 here); the same
  problem linearized (interference e cos(theta) - dR) through ``solve_contact`` with the
  same operator isolates the discretization error; (b) the thesis's viscoelastic case (SLS, omega~ = 1,
  :mod:`experiments.benchmarks.bench_pin`) against the finest grid: relative friction-torque error;
  (c) solver tolerance ``options.tol`` at the default n = 1024.
- **roller** the thesis bearing (:mod:`experiments.benchmarks.bench_roller`, Z = 9, F~ = 6.5e-3) at
  omega~ = 1.4 against the finest grid: max roller-load error / max load, torque error;
  Newton tolerance ladder at the default n = 1024.
- **journal** (a) rigid bearing with full-Sommerfeld conditions against the closed form
  W(eps) (eps = 0.6): |eps - 0.6|; (b) the thesis's HS case (:mod:`experiments.benchmarks.bench_journal`)
  against the finest grid: eps and relative bearing-torque errors; (c) Newton tolerance at
  the default n = 256.
- **DMA fit** (pyvisco data, T_ref = 25 C, WLF): Prony density (terms per decade, N = number of
  terms) and refinement iterations; error = median |log10(pred/meas)| of storage and loss
  on the raw points (there is no exact answer: it measures the fit, not a discretization).

``quick=True`` is a smoke run (one or two coarse grids per series, no tolerance ladders, one
DMA fit, the first call only), about a minute of CPU.

Outputs in ``out_dir``: ``work_precision.csv``, ``work_precision_<scene>.png`` (log-log error
against warm time, points labelled with N) and ``work_precision.md`` (observed orders and
the error and time at each scene's default resolution).
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # see bench_journal: dense LU on a shared 2-core CPU

import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

from experiments import _common  # noqa: E402

_common.enable_x64()

import jax.numpy as jnp  # noqa: E402

HEADER = ["scene", "series", "N", "tol", "error", "error_2", "error_measure", "reference", "compile_s", "warm_s",
          "iterations", "converged"]
DEFAULT = {"pin": 1024, "roller": 1024, "journal": 256}


def _fit_order(ns, errs):
    import numpy as np
    pts = [(n, e) for n, e in zip(ns, errs) if e > 0 and math.isfinite(e)]
    if len(pts) < 2:
        return math.nan
    x, y = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return float(-np.polyfit(x, y, 1)[0])



def _md_table(title, header, rows):
    """Lines of a Markdown section: a blank line, the title, a table of ``rows``."""
    return (["", title, "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
            + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows])

def _rel(a, b):
    """|a/b - 1|, NaN when the reference is zero (e.g. a torque on a grid too coarse to see it)."""
    a, b = float(a), float(b)
    return abs(a / b - 1) if b != 0 else math.nan


def _row(scene, series, N, tol, err, err2, measure, ref, first, warm, it, conv):
    return dict(scene=scene, series=series, N=N, tol=tol, error=float(err), error_2=float(err2),
                error_measure=measure, reference=ref, compile_s=first, warm_s=warm, iterations=int(it),
                converged=bool(conv))


# ---------------------------------------------------------------------- pin
def _lin_interference(q, args):
    theta, dR = args
    return q[0] * jnp.cos(theta) - dR


def _lin_force(sigma, u, args):
    theta, _ = args
    return (2 * jnp.pi / theta.shape[0]) * 0.08 * jnp.sum(sigma * jnp.cos(theta))[None]


def _linear_pin_fn(n, R=0.08, DR=4e-5):
    import jax
    import vjax

    @jax.jit
    def solve(m, load):
        op = vjax.ring_operator("hole", m, R, n, 0.0)
        th, _ = vjax.grid(n)
        sol = vjax.solve_contact(op, _lin_interference, (th, DR), jnp.array([DR]), _lin_force, load[None])
        return sol.pressure, sol.iterations, sol.converged
    return solve


def pin_rows(quick):
    import jax
    import jax.numpy as jnp
    import numpy as np
    import vjax
    from experiments.benchmarks import bench_pin
    from experiments.figures import persson
    from vjax import reference
    rows = []
    E, R, DR, Ft = 1e6, 0.08, 4e-5, 1e-2
    m = vjax.Material.elastic(E, 0.5)
    load = Ft * E * R
    b = reference.persson_b_from_load(load, E, R, DR)
    alpha = 2 * np.arctan(b)
    ns = (64, 128) if quick else (128, 256, 512, 1024, 2048, 4096, 8192)
    reps = 2 if quick else 7
    for n in ns:
        _, ref_len = persson.small_displacement_pin(m, R, DR, load, n)
        fn = lambda: vjax.pin_in_hole(vjax.hole(m, ref_length=ref_len), R, DR, load, options=vjax.PinOptions(n=n),
                                      throw=False)
        first, warm = _common.time_fn(fn, repeats=reps)
        r = fn()
        th = np.asarray(r.theta)
        p_an = reference.persson_pressure(th, b, E, R, DR)
        thw = np.abs(np.angle(np.exp(1j * th)))
        deep = thw < 0.9 * alpha          # away from the sqrt-type edges (their error is one element)
        err = float(np.max(np.abs(np.asarray(r.pressure) - p_an)[deep]) / p_an.max())
        err_a = abs(persson.edge_angle(th, np.asarray(r.pressure)) - alpha)
        rows.append(_row("pin", "elastic vs Persson", n, 1e-10, err, err_a,
                         "max|p - p_exact|/p_max over |theta| < 0.9 alpha; error_2 = |contact angle error| (rad)",
                         "analytical (Persson-type)", first, warm, r.iterations, r.converged))
        print(f"pin Persson n={n}: err {err:.3g}, angle err {err_a:.3g}, warm {warm * 1e3:.3g} ms", flush=True)
    # the same problem linearized (interference e cos(theta) - dR, load R int p cos), i.e.
    # exactly Persson's problem, through the same operator and contact solver
    for n in ns:
        fn = _linear_pin_fn(n)
        args = (m, jnp.asarray(load))
        first, warm = _common.time_fn(fn, *args, repeats=reps)
        p, it, conv = fn(*args)
        th = np.asarray(vjax.grid(n)[0])
        p_an = reference.persson_pressure(th, b, E, R, DR)
        deep = np.abs(np.angle(np.exp(1j * th))) < 0.9 * alpha
        err = float(np.max(np.abs(np.asarray(p) - p_an)[deep]) / p_an.max())
        err_a = abs(persson.edge_angle(th, np.asarray(p)) - alpha)
        rows.append(_row("pin", "linearized pin (solve_contact) vs Persson", n, 1e-10, err, err_a,
                         "max|p - p_exact|/p_max over |theta| < 0.9 alpha; error_2 = |contact angle error| (rad)",
                         "analytical (Persson-type)", first, warm, it, conv))
    # viscoelastic thesis case vs the finest grid
    ns_v = (64,) if quick else (128, 256, 512, 1024, 2048, 4096)
    n_ref = 128 if quick else 16384
    mv, omega = bench_pin.material(), bench_pin.OMEGA_TILDE / bench_pin.TAU
    ref = bench_pin._pin_fn(n_ref)(mv, omega)
    tq_ref, off_ref = float(ref[0]), float(ref[1])
    for n in ns_v:
        fn = bench_pin._pin_fn(n)
        first, warm = _common.time_fn(fn, mv, omega, repeats=reps)
        tq, off, it, conv, _ = fn(mv, omega)
        rows.append(_row("pin", "viscoelastic vs finest", n, 1e-10, _rel(tq, tq_ref),
                         _rel(off, off_ref), "|torque/torque_ref - 1|; error_2 = pin offset",
                         f"n = {n_ref}", first, warm, it, conv))
    # solver tolerance at the default n
    n = DEFAULT["pin"]
    tq_n = math.nan if quick else float(bench_pin._pin_fn(n)(mv, omega)[0])
    for tol in (() if quick else (1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12)):
        fn = jax.jit(lambda mm, w, tol=tol: bench_pin.pin(mm, w, n, tol=tol))
        first, warm = _common.time_fn(fn, mv, omega, repeats=reps)
        r = fn(mv, omega)
        rows.append(_row("pin", f"tolerance at n={n}", n, tol, _rel(r.torque, tq_n),
                         _rel(r.torque, tq_ref), "|torque/torque(tol=1e-10) - 1|; error_2 vs finest grid",
                         "same n, tol = 1e-10", first, warm, r.iterations, r.converged))
    return rows


# ---------------------------------------------------------------------- roller
def roller_rows(quick):
    import numpy as np
    from experiments.benchmarks import bench_roller
    rows = []
    w = bench_roller.shaft(1.4)
    ns = (16,) if quick else (128, 256, 512, 1024, 2048)
    n_ref = 32 if quick else 4096
    reps = 2 if quick else 5
    ref = bench_roller._solve(n_ref, w)
    loads_ref, tq_ref = np.asarray(ref.roller_loads[0]), float(ref.torque)
    for n in ns:
        fn = lambda n=n: bench_roller._solve(n, w)
        first, warm = _common.time_fn(fn, repeats=reps)
        r = fn()
        err = float(np.max(np.abs(np.asarray(r.roller_loads[0]) - loads_ref)) / loads_ref.max())
        rows.append(_row("roller", "thesis bearing vs finest", n, 1e-10, err, _rel(r.torque, tq_ref),
                         "max|roller load error|/max load; error_2 = |torque/torque_ref - 1|", f"n = {n_ref}",
                         first, warm, r.iterations, r.converged))
        print(f"roller n={n}: err {err:.3g}, warm {warm:.3g} s", flush=True)
    n = DEFAULT["roller"]
    if quick:   # no tolerance ladder in quick mode (each tolerance is one compilation)
        return rows
    base = bench_roller._solve(n, w, tol=1e-12)
    lb = np.asarray(base.roller_loads[0])
    for tol in (() if quick else (1e-3, 1e-6, 1e-9)):   # tol is static: one compile each
        fn = lambda tol=tol: bench_roller._solve(n, w, tol=tol)
        first, warm = _common.time_fn(fn, repeats=reps)
        r = fn()
        err = float(np.max(np.abs(np.asarray(r.roller_loads[0]) - lb)) / lb.max())
        err2 = float(np.max(np.abs(np.asarray(r.roller_loads[0]) - loads_ref)) / loads_ref.max()) \
            if r.roller_loads.shape == ref.roller_loads.shape else math.nan
        rows.append(_row("roller", f"tolerance at n={n}", n, tol, err, err2,
                         "max|roller load error|/max load vs tol = 1e-12 at the same n; error_2 vs finest grid",
                         "same n, tol = 1e-12", first, warm, r.iterations, r.converged))
    return rows


# ---------------------------------------------------------------------- journal
def journal_rows(quick):
    import numpy as np
    import vjax
    from experiments.benchmarks import bench_journal
    rows = []
    Rj, Cj, ETAj, WJ = 0.05, 5e-5, 0.01, 100.0
    U = WJ * (Rj - Cj)
    eps = 0.6
    W = 12 * np.pi * ETAj * U * Rj**2 * eps / (Cj**2 * (2 + eps**2) * np.sqrt(1 - eps**2))
    reps = 2 if quick else 5
    # above n = 1024 the Newton steps are matrix-free GMRES (JournalOptions.linear_solver="auto")
    for n in ((32, 64) if quick else (32, 64, 128, 256, 512, 1024, 2048, 4096, 8192)):
        fn = lambda n=n: vjax.journal_bearing(Rj, Cj, ETAj, W, omega_shaft=WJ, cavitation="sommerfeld",
                                              options=vjax.JournalOptions(n=n), throw=False)
        first, warm = _common.time_fn(fn, repeats=reps)
        r = fn()
        rows.append(_row("journal", "rigid full-Sommerfeld vs closed form", n, 1e-10, abs(float(r.eccentricity) - eps),
                         abs(abs(float(r.attitude_angle)) - np.pi / 2),
                         "|eps - eps_exact|; error_2 = |attitude - pi/2| (rad)", "closed form (Sommerfeld)",
                         first, warm, r.iterations, r.converged))
        print(f"journal Sommerfeld n={n}: err {rows[-1]['error']:.3g}, warm {warm:.3g} s", flush=True)
    ns = (32,) if quick else (64, 128, 256, 512, 1024, 2048, 4096)
    n_ref = 64 if quick else 16384
    ref = bench_journal._point(n_ref)       # nested cold start
    for n in ns:
        fn = lambda n=n: bench_journal._point(n)
        first, warm = _common.time_fn(fn, repeats=reps)
        r = fn()
        rows.append(_row("journal", "HS thesis case vs finest", n, 1e-10, abs(float(r.eccentricity - ref.eccentricity)),
                         _rel(r.torque, ref.torque),
                         "|eps - eps_ref|; error_2 = |torque/torque_ref - 1|", f"n = {n_ref}", first, warm,
                         r.iterations, r.converged))
        print(f"journal HS n={n}: err {rows[-1]['error']:.3g}, warm {warm:.3g} s", flush=True)
    n = DEFAULT["journal"]
    if quick:
        return rows
    base = bench_journal._point(n, tol=1e-12, throw=False)
    for tol in (() if quick else (1e-2, 1e-4, 1e-6, 1e-8, 1e-10)):
        fn = lambda tol=tol: bench_journal._point(n, tol=tol, throw=False)
        first, warm = _common.time_fn(fn, repeats=reps)
        r = fn()
        rows.append(_row("journal", f"tolerance at n={n}", n, tol, abs(float(r.eccentricity - base.eccentricity)),
                         abs(float(r.eccentricity - ref.eccentricity)),
                         "|eps - eps(tol=1e-12)| at the same n; error_2 vs finest grid", "same n, tol = 1e-12",
                         first, warm, r.iterations, r.converged))
    return rows


# ---------------------------------------------------------------------- DMA fit
def fit_rows(quick):
    from fitting import calibrate
    from fitting.measurements import dma
    rows = []
    path = dma.default_data("pyvisco")
    ladder = [(0.5, 30)] if quick else [(0.5, 300), (0.75, 300), (1.0, 300), (1.5, 300), (2.0, 300), (1.0, 10),
                                        (1.0, 30), (1.0, 100)]
    for density, iters in ladder:
        fn = lambda d=density, k=iters: calibrate(path, 25.0, law="WLF", densities=(d,), max_iter=k)
        t0 = time.perf_counter()
        mat, shift, rep = fn()
        first = warm = time.perf_counter() - t0
        if not quick:   # a second, warm run (quick: the first call only)
            t0 = time.perf_counter()
            mat, shift, rep = fn()
            warm = time.perf_counter() - t0
        e = rep.errors
        rows.append(_row("dma_fit", f"density {density}/decade, max_iter {iters}", rep.terms, iters,
                         0.5 * (e["storage_median"] + e["loss_median"]), 0.5 * (e["storage_p90"] + e["loss_p90"]),
                         "median |log10(pred/meas)| (storage, loss mean); error_2 = 90th percentile",
                         "raw DMA points", first, warm, rep.iterations, rep.converged))
        print(f"fit density {density} iters {iters}: {rep.terms} terms, err {rows[-1]['error']:.4g}, "
              f"{warm:.2f} s", flush=True)
    return rows


# ---------------------------------------------------------------------- report
def _plot(rows, scene, path):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6), constrained_layout=True)
    series = []
    for r in rows:
        if r["scene"] == scene and r["series"] not in series:
            series.append(r["series"])
    for k, s in enumerate(series):
        pts = [r for r in rows if r["scene"] == scene and r["series"] == s and r["error"] > 0]
        if not pts:
            continue
        x = [r["warm_s"] for r in pts]
        y = [r["error"] for r in pts]
        ax.loglog(x, y, "o-" if "tolerance" not in s else "s--", color=f"C{k}", label=s)
        for r in pts:
            lab = f"N={r['N']}" if "tolerance" not in s else f"tol={r['tol']:g}"
            if scene == "dma_fit":
                lab = f"{r['N']} terms"
            ax.annotate(lab, (r["warm_s"], r["error"]), fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set(xlabel="median warm time (s)", ylabel="error (see legend / CSV error_measure)",
           title=f"work-precision: {scene}")
    ax.legend(fontsize=7)
    _common.save_figure(fig, path)


def summary(rows):
    lines = ["# Work-precision report (`python -m experiments.benchmarks.work_precision`)", "",
             "Median warm time of one solve (float64, shared 2-core CPU; compile = first call, separate).", "",
             "## Observed convergence orders (fit of log error against log N)", "",
             "| scene | series | N range | order | error measure |", "|---|---|---|---|---|"]
    seen = []
    for r in rows:
        key = (r["scene"], r["series"])
        if key in seen or "tolerance" in r["series"] or r["scene"] == "dma_fit":
            continue
        seen.append(key)
        pts = [x for x in rows if (x["scene"], x["series"]) == key]
        ns, es = [x["N"] for x in pts], [x["error"] for x in pts]
        o1, o2 = _fit_order(ns, es), _fit_order(ns, [x["error_2"] for x in pts])
        lines.append(f"| {key[0]} | {key[1]} | {min(ns)}..{max(ns)} | {o1:.2f} (error_2: {o2:.2f}) | "
                     f"{pts[0]['error_measure']} |")
    at_default = lambda r: (r["N"] == DEFAULT.get(r["scene"]) and "tolerance" not in r["series"]) or (
        r["scene"] == "dma_fit" and r["series"].startswith("density 1.0/decade, max_iter 300"))
    lines += _md_table("## At the default resolution", ["scene", "series", "N", "error", "error_2", "warm time (s)",
                                                        "compile (s)", "iterations"],
                       [[r["scene"], r["series"], r["N"], f"{r['error']:.3g}", f"{r['error_2']:.3g}",
                         f"{r['warm_s']:.3g}", f"{r['compile_s']:.3g}", r["iterations"]] for r in rows if at_default(r)])
    lines += _md_table("## Solver tolerance", ["scene", "series", "tol", "error vs tight tol", "error vs finest grid",
                                               "warm time (s)", "iterations"],
                       [[r["scene"], r["series"], f"{r['tol']:g}", f"{r['error']:.3g}", f"{r['error_2']:.3g}",
                         f"{r['warm_s']:.3g}", r["iterations"]] for r in rows if "tolerance" in r["series"]])
    fits = [r for r in rows if r["scene"] == "dma_fit"]
    if fits:
        lines += ["", "## DMA fit (pyvisco data, WLF)", "",
                  "| ladder | terms | median err | p90 err | warm time (s) | converged |", "|---|---|---|---|---|---|"]
        lines += [f"| {r['series']} | {r['N']} | {r['error']:.4g} | {r['error_2']:.4g} | {r['warm_s']:.3g} | "
                  f"{r['converged']} |" for r in fits]
    return "\n".join(lines) + "\n"


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    t0 = time.perf_counter()
    rows = []
    for name, fn in (("pin", pin_rows), ("roller", roller_rows), ("journal", journal_rows), ("dma_fit", fit_rows)):
        new = fn(quick)
        rows += new
        _plot(rows, name, out / f"work_precision_{name}.png")
    _common.write_csv(out / "work_precision.csv", HEADER, [[r[h] for h in HEADER] for r in rows],
                      comments=["issue 8 work-precision report: warm_s = median warm time of one solve, compile_s = "
                                "first call (trace + compile + run)", f"quick={quick}; total wall time "
                                f"{time.perf_counter() - t0:.0f} s; load average {os.getloadavg()[0]:.1f} on "
                                f"{os.cpu_count()} cpus"])
    text = summary(rows)
    _common.atomic_write_text(out / "work_precision.md", text)
    print(text)
    return rows


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
