"""Gradient-based bearing design versus random search at an equal number of solver calls.

**Journal bearing (VEHL).** The thesis HS bearing (R_B = 0.1 m, soft SLS liner E0 = 1 MPa,
Einf = 100 MPa, tau = 1 s, nu = 0.5, rigid journal, F = 2.2e-3 E0 R_B, omega_J = -0.4,
omega_B = 0.2 rad/s). Design variables: radial clearance c in [0.2, 1.0] mm and viscosity
eta in [0.5, 5] mPa s. Objective: power loss P = fluid + liner dissipation (W/m).
Constraint: minimum film h_min >= h_lim (4.5 um). Gradient method: SLSQP (scipy) on
(log c, log eta) with the exact gradients of P and h_min from :func:`vjax.journal_bearing`
(forward-mode Jacobian through the implicit derivatives of its Newton solve); each
iteration costs one solve + its 2-column Jacobian, counted as one solver call. Baseline:
uniform random search in (log c, log eta) with the same number of solves, best feasible
point (and, for scale, with four times as many).

Each solve starts from the nearest converged solution (``initial=``); a point whose solve
fails counts as a call and as infeasible.

The roller-bearing design of the issue is not here: the roller scene's torque does not yet
vanish in the elastic limit at n = 256 (about 1e-2 N m/m at omega~ = 0.004 in the thesis
case), so minimizing it would optimize a discretization artefact; see the report.

Run: ``python -m experiments.design [--quick]``.
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np

from experiments import _common


def journal_design(out, quick=False):
    import jax
    import jax.numpy as jnp
    import vjax
    from scipy.optimize import minimize

    bearing = vjax.Material.sls(1e6, 1e8, 1.0, 0.5)
    R_B = 0.1
    load = 2.2e-3 * 1e6 * R_B
    n = 64 if quick else 128
    h_lim = 4.5e-6
    lo = np.log([2e-4, 5e-4])
    hi = np.log([1e-3, 5e-3])
    ref = vjax.journal_bearing(R_B, 5e-4, 1e-3, omega_journal=-0.4, omega_bearing=0.2, load=load,
                               bearing=bearing, n=n)
    cache = []            # (x, solution) of converged solves, for warm starts
    calls = {"n": 0}

    def nearest(x):
        if not cache:
            return ref
        d = [np.sum((np.asarray(cx) - x) ** 2) for cx, _ in cache]
        return cache[int(np.argmin(d))][1]

    def f(y, init):
        s = vjax.journal_bearing(R_B, jnp.exp(y[0]), jnp.exp(y[1]), omega_journal=-0.4, omega_bearing=0.2,
                                 load=load, bearing=bearing, n=n, throw=False, initial=init, solver="newton")
        return jnp.stack([s.dissipation_fluid + s.dissipation_bearing, s.min_film]), s

    # compiled once: value and 2-column Jacobian (forward mode through the implicit derivatives)
    val_jac = jax.jit(lambda y, init: (f(y, init)[0], jax.jacfwd(lambda z: f(z, init), has_aux=True)(y)))

    def solve(x, grad=True):
        """Power, film and (optionally) their gradients in (log c, log eta); one solver call."""
        calls["n"] += 1
        init = nearest(x)
        y = jnp.asarray(x, float)
        if grad:
            v, (J, s) = val_jac(y, init)
        else:
            v, s = f(y, init)
            J = None
        ok = bool(s.converged) and bool(s.eccentricity_effective > 0)
        if ok:
            cache.append((np.asarray(x), s))
        return np.asarray(v), (None if J is None else np.asarray(J)), ok

    # ---- gradient-based: SLSQP with exact gradients ----
    memo = {}

    def ev(x):
        key = tuple(np.round(x, 12))
        if key not in memo:
            memo[key] = solve(x)
        return memo[key]

    scale_P = float(ref.dissipation_fluid + ref.dissipation_bearing)
    obj = lambda x: ev(x)[0][0] / scale_P if ev(x)[2] else 1e3
    obj_j = lambda x: ev(x)[1][0] / scale_P if ev(x)[2] else np.zeros(2)
    con = lambda x: (ev(x)[0][1] - h_lim) / h_lim if ev(x)[2] else -1.0
    con_j = lambda x: ev(x)[1][1] / h_lim if ev(x)[2] else np.zeros(2)
    x0 = np.log([5e-4, 1e-3])
    t0 = time.perf_counter()
    max_iter = 6 if quick else 20
    res = minimize(obj, x0, jac=obj_j, method="SLSQP", bounds=list(zip(lo, hi)),
                   constraints=[{"type": "ineq", "fun": con, "jac": con_j}],
                   options={"maxiter": max_iter, "ftol": 1e-6})
    t_grad = time.perf_counter() - t0
    n_grad = calls["n"]
    xg = res.x
    vg, _, okg = ev(xg)
    history = [(k, *np.exp(key), v[0], v[1], ok) for k, (key, (v, _, ok)) in enumerate(memo.items())]

    # ---- random search with the same number of solver calls ----
    # (and, for scale, with four times as many)
    rng = np.random.default_rng(0)
    t0 = time.perf_counter()
    best, best4 = None, None
    rs_rows = []
    for k in range(4 * n_grad):
        x = lo + (hi - lo) * rng.uniform(size=2)
        v, _, ok = solve(x, grad=False)
        feas = ok and v[1] >= h_lim
        rs_rows.append((k, *np.exp(x), v[0], v[1], ok))
        if feas and (best4 is None or v[0] < best4[1][0]):
            best4 = (x, v)
        if k + 1 == n_grad:
            best, t_rand = best4, time.perf_counter() - t0
    t_rand4 = time.perf_counter() - t0

    rows = [["SLSQP + implicit gradients", n_grad, math.exp(xg[0]) * 1e3, math.exp(xg[1]) * 1e3, vg[0],
             vg[1] * 1e6, bool(okg and vg[1] >= h_lim * (1 - 1e-3)), t_grad]]
    if best is not None:
        rows.append(["random search", n_grad, math.exp(best[0][0]) * 1e3, math.exp(best[0][1]) * 1e3, best[1][0],
                     best[1][1] * 1e6, True, t_rand])
    else:
        rows.append(["random search", n_grad, float("nan"), float("nan"), float("nan"), float("nan"), False, t_rand])
    if best4 is not None:
        rows.append(["random search, 4x calls", 4 * n_grad, math.exp(best4[0][0]) * 1e3, math.exp(best4[0][1]) * 1e3,
                     best4[1][0], best4[1][1] * 1e6, True, t_rand4])
    header = ["method", "solver_calls", "clearance_mm", "viscosity_mPa_s", "power_W_per_m", "min_film_um",
              "feasible", "wall_s"]
    notes = [f"journal HS bearing, n={n}; min film >= {h_lim * 1e6:g} um; c in [0.2, 1] mm, eta in [0.5, 5] mPa s",
             f"start c = 0.5 mm, eta = 1 mPa s: power {scale_P:.5g} W/m, min film {float(ref.min_film) * 1e6:.3f} um",
             f"SLSQP: {res.message} ({res.nit} iterations)"]
    _common.write_csv(out / "design_journal.csv", header, rows, comments=notes)
    _common.write_csv(out / "design_journal_history.csv", ["k", "c_m", "eta_Pa_s", "power_W_per_m", "min_film_m",
                                                            "converged"], history + [("random",) + r[1:] for r in rs_rows])
    text = _common.print_table(header, rows, title="journal bearing design: gradient vs random search")
    print("\n".join(notes))
    return text + "\n" + "\n".join(notes), rows, rs_rows, history, (lo, hi, h_lim)


def main(out_dir="experiments/out", quick: bool = False) -> dict:
    out = _common.setup(out_dir)
    import matplotlib.pyplot as plt
    text, rows, rs_rows, history, (lo, hi, h_lim) = journal_design(out, quick)
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    rr = np.array([r[1:5] for r in rs_rows], float)
    hh = np.array([h[1:5] for h in history], float)
    feas = rr[:, 3] >= h_lim
    ax.scatter(rr[feas, 0] * 1e3, rr[feas, 1] * 1e3, c=rr[feas, 2], marker="o", label="random (feasible)")
    ax.scatter(rr[~feas, 0] * 1e3, rr[~feas, 1] * 1e3, c="0.7", marker="x", label="random (film too thin)")
    ax.plot(hh[:, 0] * 1e3, hh[:, 1] * 1e3, "k.-", lw=0.8, label="SLSQP iterates")
    ax.plot(rows[0][2], rows[0][3], "r*", ms=14, label="gradient optimum")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("clearance (mm)")
    ax.set_ylabel("viscosity (mPa s)")
    ax.legend(fontsize=7)
    _common.save_figure(fig, out / "design_journal.png")
    _common.atomic_write_text(out / "design_summary.txt", text + "\n")
    return {"journal": rows}


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default="experiments/out")
    a = ap.parse_args()
    main(a.out, quick=a.quick)
