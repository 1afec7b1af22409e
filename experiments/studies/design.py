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

**Finite polymer-lined journal bearing** (``--only finite``). R = 50 mm, load 2 kN (the
weight of a 204 kg rotor share), journal at 1000 rad/s, oil 0.01 Pa s, a liner of an SLS
polymer (0.3 / 3 GPa, 1 ms, nu 0.4) bonded in a rigid housing, groove fixed opposite the
load; 48 x 12 grid (32 x 8 quick). Design variables: L/D in [0.25, 1], radial clearance in
[50, 150] um, liner thickness in [0.5, 3] mm (on their logarithms). Objective: power loss
(W). Constraints: minimum film >= 25 um; oil-whirl margin: the critical mass of Lund's
threshold (:func:`vjax.journal_dynamics.lund`, K and C of the lined bearing at the
half-frequency whirl) at least 1.5 times the rotor mass per bearing. Gradient method: SLSQP
from three starts across the box (the feasible set is not convex), the exact 3-column
Jacobian by forward mode through the implicit derivatives of the steady solve and the
linearization; baseline: random search with the same number of calls (and four times as many).

**Lined journal bearing at its own temperature** (``--only thermal``). A hub lined with 2 mm of
the SLS polymer above (WLF 8.86 / 101.6 at 40 C) turning at 3000 rpm about a fixed shaft, R =
50 mm, load 10 kN, ISO VG 32 supplied at 40 C, groove opposite the load, 32 x 8 grid. Design
variables: L/D in [0.3, 1] and radial clearance in [40, 120] um (on their logarithms).
Objective: power loss (W: film shear with the striated cavity, and the liner's hysteresis).
Three problems with SLSQP and exact gradients (forward mode through the implicit derivatives
of :func:`vjax.thermal_journal_bearing`'s thermal root and of the scene; one compiled program,
hA is its argument): isothermal at the supply temperature (hA = inf) without constraints and
with h_min >= 3 sigma; level 1 thermal (ISO 7902's effective temperature, the side leakage and
hA = 5 W/K carrying the heat; the oil's viscosity and the liner's moduli at T_eff) with T_eff
<= 60 C (the liner's stated maximum) and h_min >= 3 sigma = 4.84 um (lambda >= 3 with a
composite roughness sigma = 1.61 um: a ground journal, Rq 0.2 um, on a turned liner, Rq 1.6
um). SLSQP from two starts (the thermal landscape is not convex). Every optimum is then run
at its own temperature. At 3000 rpm the isothermal optimum is the box's corner (L/D 0.3, c
120 um, 999 W, h_min 7.9 um); run hot it settles at 45.9 C, where the softened liner (WLF)
and the thinner oil leave a film of 1.0 um (lambda 0.65), and 1040 W. The thermal optimum
moves to L/D 0.33 (c 120 um): 965 W at 45.1 C, h_min 5.0 um. From the other start SLSQP ends
on both constraints (L/D 0.36, c 41 um, T_eff 60 C, h_min 4.84 um, 1073 W). Outputs:
``design_thermal.csv`` (the table), ``design_thermal_landscape.csv`` (a 4 x 4 grid, thermal and
isothermal), ``design_thermal.png``. About 95 s on two shared cores, half of it compiling.

**Needle roller bearing.** Rings of a calibrated polymer on both sides (enumerated:
the pyvisco and the dmasuite DMA data sets, Prony + WLF fitted at 10-100 C), D = 2 mm
rigid rollers, radial load 2e4 N/m, outer ring fixed. Design variables: diametral
clearance P_d in [-10, 40] um (negative = preload) and inner raceway radius R_I in
[3.5, 5] mm (R_O = R_I + D + P_d/2), continuous; number of rollers Z in {8, 10, 12} and
the material, enumerated. Objective: friction torque on the outer ring averaged over 300
and 3000 rpm at 40 and 70 C (four roller solves, one vmapped call, n = 2048 per ring: the
contacts of these stiff polymers are ~1% of the ring radius wide, 5-15 elements).
Constraints over the same conditions: peak contact pressure <= 170 MPa (parabolic sub-grid
peak, so it is continuous in the design) and largest roller load <= 12 kN/m. Gradient method: SLSQP
on each enumerated (material, Z) from the middle of the box, with the exact 2-column
Jacobian of (torque, peak, roller load) by forward mode through the implicit derivatives
of :func:`vjax.roller_bearing`. Baseline: random search over all four variables (material
and Z uniformly) with the same number of solver calls. A solver call is one design
evaluation (four bearing solves); an evaluation where a solve fails is infeasible.

Run: ``python -m experiments.studies.design [--quick] [--only journal|finite|thermal|roller]``.
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
    speeds = dict(omega_shaft=-0.4, omega_housing=0.2)
    ref = vjax.journal_bearing(R_B, 5e-4, 1e-3, load, housing=bearing, **speeds, options=vjax.JournalOptions(n=n))
    cache = []            # (x, solution) of converged solves, for warm starts
    calls = {"n": 0}

    def nearest(x):
        if not cache:
            return ref
        d = [np.sum((np.asarray(cx) - x) ** 2) for cx, _ in cache]
        return cache[int(np.argmin(d))][1]

    def f(y, init):
        s = vjax.journal_bearing(R_B, jnp.exp(y[0]), jnp.exp(y[1]), load, housing=bearing, **speeds, initial=init,
                                 options=vjax.JournalOptions(n=n, strategy="newton"), throw=False)
        return jnp.stack([s.dissipation_fluid + s.dissipation_housing, s.min_film]), s

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

    scale_P = float(ref.dissipation_fluid + ref.dissipation_housing)
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


# ---- finite polymer-lined journal bearing ---------------------------------------------
FINITE = dict(R=0.05, viscosity=0.01, load=2e3, omega_shaft=1000.0, h_lim=25e-6, margin=1.5,
              box=((0.25, 1.0), (50e-6, 150e-6), (0.5e-3, 3e-3)))
STARTS = ((0.3, 140e-6, 2e-3), (0.6, 100e-6, 1.5e-3), (0.9, 60e-6, 1e-3))     # (L/D, c, t) of the SLSQP starts


def finite_journal_design(out, quick=False):
    """SLSQP with implicit gradients against random search on the finite lined bearing: the
    variables y = log(L/D, c, t), the power loss, the minimum film and the whirl margin
    g = 1 - margin M W^2 / K_eq (Lund's K_eq and W^2 from K, C at the half-frequency whirl)."""
    import jax
    import jax.numpy as jnp
    import vjax
    from scipy.optimize import minimize
    from vjax.journal_dynamics import lund

    cfg = FINITE
    R, W, speed, h_lim, margin = cfg["R"], cfg["load"], cfg["omega_shaft"], cfg["h_lim"], cfg["margin"]
    mass = W / 9.81                      # per bearing: the rotor's weight is the load
    liner = vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4)
    options = vjax.FiniteJournalOptions(n=32, m=8) if quick else vjax.FiniteJournalOptions(n=48, m=12)
    lo, hi = np.log(np.array(cfg["box"]).T)
    whirl = jnp.array([0.5 * speed])     # oil whirl: the liner's coefficients at half the speed

    def f(y, init):
        LD, c, t = jnp.exp(y[0]), jnp.exp(y[1]), jnp.exp(y[2])
        co = vjax.journal_coefficients(R, c, cfg["viscosity"], W, whirl, omega_shaft=speed, length=LD * 2 * R,
                                       housing=vjax.liner(liner, t), initial=init, options=options, throw=False)
        Keq, W2 = lund(co.stiffness[0], co.damping[0])
        s = co.steady
        return jnp.stack([s.power_loss, s.min_film, 1.0 - margin * mass * W2 / Keq]), s

    x0 = np.log([0.6, 100e-6, 1.5e-3])
    LD0, c0, t0_ = np.exp(x0)
    ref = vjax.journal_bearing(R, c0, cfg["viscosity"], W, omega_shaft=speed, length=LD0 * 2 * R,
                               housing=vjax.liner(liner, t0_), options=options)
    # value and 3-column Jacobian in one program (forward mode through the implicit derivatives
    # of the steady solve and the linearization); the random search calls it too: one compile
    val_jac = jax.jit(lambda y, init: (f(y, init)[0], jax.jacfwd(lambda z: f(z, init), has_aux=True)(y)))
    cache, calls = [], {"n": 0}

    def solve(x):
        calls["n"] += 1
        init = ref if not cache else cache[int(np.argmin([np.sum((cx - x) ** 2) for cx, _ in cache]))][1]
        v, (J, s) = val_jac(jnp.asarray(x, float), init)
        ok = bool(s.converged) and bool(np.all(np.isfinite(np.asarray(J))))
        if ok:
            cache.append((np.asarray(x), s))
        return np.asarray(v), np.asarray(J), ok

    t0 = time.perf_counter()
    v_ref, J_ref, _ = solve(x0)
    t_first = time.perf_counter() - t0
    # the gradient against central differences of the same program, once (a check the user sees)
    h = 1e-5
    fd = np.stack([(solve(x0 + h * e)[0] - solve(x0 - h * e)[0]) / (2 * h) for e in np.eye(3)], axis=1)
    grad_error = float(np.max(np.abs(fd - J_ref) / (np.abs(J_ref).max(axis=1, keepdims=True))))
    calls["n"] = 0

    memo = {}

    def ev(x):
        key = tuple(np.round(x, 12))
        if key not in memo:
            memo[key] = solve(np.asarray(x))
        return memo[key]

    P0 = float(v_ref[0])
    obj = lambda x: ev(x)[0][0] / P0 if ev(x)[2] else 1e3                                  # noqa: E731
    obj_j = lambda x: ev(x)[1][0] / P0 if ev(x)[2] else np.zeros(3)                        # noqa: E731
    cons = [{"type": "ineq", "fun": lambda x: (ev(x)[0][1] - h_lim) / h_lim if ev(x)[2] else -1.0,
             "jac": lambda x: ev(x)[1][1] / h_lim if ev(x)[2] else np.zeros(3)},
            {"type": "ineq", "fun": lambda x: ev(x)[0][2] if ev(x)[2] else -1.0,
             "jac": lambda x: ev(x)[1][2] if ev(x)[2] else np.zeros(3)}]
    feasible = lambda v, ok: ok and v[1] >= h_lim * (1 - 1e-3) and v[2] >= -1e-3            # noqa: E731
    # the feasible set is not convex (the whirl margin holds at low and at high eccentricity,
    # not between): SLSQP from three starts across the box, the best feasible end kept
    t0 = time.perf_counter()
    ends = []
    for start in STARTS:
        res = minimize(obj, np.log(start), jac=obj_j, method="SLSQP", bounds=list(zip(lo, hi)), constraints=cons,
                       options={"maxiter": 6 if quick else 20, "ftol": 1e-6})
        v, _, ok = ev(res.x)
        ends.append((not feasible(v, ok), v[0], res))
    t_grad, n_grad = time.perf_counter() - t0, calls["n"]
    res = min(ends, key=lambda e: e[:2])[2]
    vg, _, okg = ev(res.x)
    history = [(k, *np.exp(key), *v, ok) for k, (key, (v, _, ok)) in enumerate(memo.items())]

    rng = np.random.default_rng(0)
    best, best4, rs_rows = None, None, []
    t0 = time.perf_counter()
    for k in range(4 * n_grad):
        x = lo + (hi - lo) * rng.uniform(size=3)
        v, _, ok = solve(x)
        rs_rows.append((k, *np.exp(x), *v, ok))
        if feasible(v, ok) and (best4 is None or v[0] < best4[1][0]):
            best4 = (x, v)
        if k + 1 == n_grad:
            best, t_rand = best4, time.perf_counter() - t0
    t_rand4 = time.perf_counter() - t0

    def row(method, calls_, found, wall):
        if found is None:
            return [method, calls_] + [float("nan")] * 6 + [False, wall]
        x, v = found
        LD, c, t = np.exp(x)
        return [method, calls_, LD, c * 1e6, t * 1e3, v[0], v[1] * 1e6, v[2], True, wall]

    rows = [row("SLSQP + implicit gradients", n_grad, (res.x, vg), t_grad)]
    rows[0][-2] = bool(feasible(vg, okg))
    rows += [row("random search", n_grad, best, t_rand), row("random search, 4x calls", 4 * n_grad, best4, t_rand4)]
    header = ["method", "solver_calls", "L_over_D", "clearance_um", "liner_mm", "power_W", "min_film_um",
              "whirl_margin", "feasible", "wall_s"]
    notes = [f"finite polymer-lined journal bearing: R = {R} m, W = {W:g} N (rotor {mass:.0f} kg per bearing), "
             f"{speed:g} rad/s, oil {cfg['viscosity']} Pa s, SLS liner (0.3 / 3 GPa, 1 ms, nu 0.4), grid "
             f"{options.n} x {options.m}",
             f"constraints: min film >= {h_lim * 1e6:g} um; critical mass (Lund, coefficients at the half-frequency "
             f"whirl) >= {margin} x rotor mass, as g = 1 - {margin} M W^2 / K_eq >= 0",
             f"box: L/D {cfg['box'][0]}, c {cfg['box'][1]} m, liner {cfg['box'][2]} m",
             f"start L/D 0.6, c 100 um, liner 1.5 mm: power {P0:.1f} W; first call (compile) {t_first:.1f} s; "
             f"implicit gradient vs central differences: {grad_error:.1e} (max over outputs, of each row's largest)",
             "SLSQP from (L/D, c, t) = " + ", ".join(f"({a}, {b * 1e6:g} um, {c * 1e3:g} mm)" for a, b, c in STARTS)
             + ": " + "; ".join(f"{e[2].message} ({e[2].nit} it., power {e[1]:.0f} W{'' if not e[0] else ', infeasible'})"
                                for e in ends)]
    _common.write_csv(out / "design_finite_journal.csv", header, rows, comments=notes)
    _common.write_csv(out / "design_finite_journal_history.csv",
                      ["k", "L_over_D", "c_m", "liner_m", "power_W", "min_film_m", "whirl_margin", "converged"],
                      history + [("random",) + r[1:] for r in rs_rows])
    text = _common.print_table(header, rows, title="finite lined journal bearing design: gradient vs random search")
    print("\n".join(notes))
    return text + "\n" + "\n".join(notes), rows, rs_rows, history, grad_error


# ---- the lined journal bearing at its own temperature --------------------------------------
SIGMA = math.hypot(0.2e-6, 1.6e-6)       # composite roughness (m): ground journal Rq 0.2 um, turned liner Rq 1.6 um
THERMAL = dict(R=0.05, load=10e3, rpm=3000.0, T_supply=40.0, hA=5.0, T_max=60.0, h_lim=3 * SIGMA, t_liner=2e-3,
               box=((0.3, 1.0), (40e-6, 120e-6)), starts=((0.6, 60e-6), (0.6, 110e-6)))


def thermal_design(out, quick=False):
    """Where the optimum moves when the bearing heats itself: SLSQP with implicit gradients on
    (log L/D, log c) of the lined hub bearing (see the module docstring), three problems with
    one compiled program (hA is an argument): isothermal at the supply temperature (hA = inf)
    without constraints and with h_min >= h_lim, and level 1 thermal (hA = 5 W/K) with T_eff
    <= T_max and h_min >= h_lim. Each optimum is then evaluated thermally. Returns (text, rows,
    paths, settings)."""
    import jax
    import jax.numpy as jnp
    import vjax
    from scipy.optimize import minimize

    cfg = THERMAL
    R, W, T_in, hA, T_max, h_lim = (cfg[k] for k in ("R", "load", "T_supply", "hA", "T_max", "h_lim"))
    omega = cfg["rpm"] * math.pi / 30
    oil = vjax.Lubricant.iso_vg(32)
    liner = vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4)
    shift = vjax.WLF(8.86, 101.6, 40.0)
    options = vjax.FiniteJournalOptions(n=32, m=8)
    lo, hi = np.log(np.array(cfg["box"]).T)

    def f(y, hA):
        LD, c = jnp.exp(y[0]), jnp.exp(y[1])
        r = vjax.thermal_journal_bearing(R, c, oil, W, vjax.HeatTransfer(T_in, hA=hA), length=LD * 2 * R,
                                         housing=vjax.liner(liner.with_shift(shift), cfg["t_liner"]), omega_housing=omega,
                                         options=options, throw=False)
        v = jnp.stack([r.power, r.temperature, r.scene.min_film])
        return v, (v, r.converged)

    # values and the 2-column Jacobian in one program (forward mode through the implicit
    # derivatives of the thermal root and of the scene); hA = inf runs the same program
    val_jac = jax.jit(lambda y, hA: jax.jacfwd(lambda z: f(z, hA), has_aux=True)(y))
    calls = {"n": 0}

    def solve(x, h):
        calls["n"] += 1
        J, (v, ok) = val_jac(jnp.asarray(x, float), h)
        v, J = np.asarray(v), np.asarray(J)
        return v, J, bool(ok) and bool(np.all(np.isfinite(J)))

    t0 = time.perf_counter()
    v0, _, _ = solve(np.log(cfg["starts"][0]), hA)
    t_compile = time.perf_counter() - t0
    # the landscape for the figure: power, T_eff and h_min on a grid, thermal and isothermal
    k = 3 if quick else 4          # coarse: each thermal point is a full root (~1 s); contours interpolate
    t0 = time.perf_counter()
    grid = np.stack(np.meshgrid(np.linspace(lo[0], hi[0], k), np.linspace(lo[1], hi[1], k), indexing="ij"), -1)
    landscape = {name: np.array([[solve(x, h)[0] for x in line] for line in grid])
                 for name, h in (("thermal", hA), ("isothermal", np.inf))}
    t_grid, calls["n"] = time.perf_counter() - t0, 0
    problems = (("isothermal (40 C), unconstrained", np.inf, False),
                ("isothermal (40 C), h_min >= h_lim", np.inf, True),
                ("thermal, T_eff <= T_max and h_min >= h_lim", hA, True))
    rows, paths, messages = [], {}, []
    for name, h, constrained in problems:
        memo = {}

        def ev(x, h=h, memo=memo):
            key = tuple(np.round(x, 12))
            if key not in memo:
                memo[key] = solve(np.asarray(x), h)
            return memo[key]

        P0 = float(v0[0])
        obj = lambda x: ev(x)[0][0] / P0 if ev(x)[2] else 1e3                        # noqa: E731
        obj_j = lambda x: ev(x)[1][0] / P0 if ev(x)[2] else np.zeros(2)              # noqa: E731
        cons = [{"type": "ineq", "fun": lambda x: (ev(x)[0][2] - h_lim) / h_lim if ev(x)[2] else -1.0,
                 "jac": lambda x: ev(x)[1][2] / h_lim if ev(x)[2] else np.zeros(2)}]
        if np.isfinite(h):
            cons.append({"type": "ineq", "fun": lambda x: (T_max - ev(x)[0][1]) / 10.0 if ev(x)[2] else -1.0,
                         "jac": lambda x: -ev(x)[1][1] / 10.0 if ev(x)[2] else np.zeros(2)})
        # the thermal landscape is not convex: SLSQP from two starts, the best feasible end kept
        t0, n0 = time.perf_counter(), calls["n"]
        ends = []
        for start in cfg["starts"]:
            res = minimize(obj, np.log(start), jac=obj_j, method="SLSQP", bounds=list(zip(lo, hi)),
                           constraints=cons if constrained else (),
                           options={"maxiter": 8 if quick else 20, "ftol": 1e-6})
            ends.append((min(0.0, *(c["fun"](res.x) for c in cons)) < -1e-3 if constrained else False,
                         obj(res.x), res))
        res = min(ends, key=lambda e: e[:2])[2]
        wall, n_calls = time.perf_counter() - t0, calls["n"] - n0
        v, _, ok = ev(res.x)
        hot, _, ok_hot = solve(res.x, hA)        # the design as it runs: at its own temperature
        LD, c = np.exp(res.x)
        rows.append([name, n_calls, LD, c * 1e6, v[0], v[2] * 1e6, hot[0], hot[1], hot[2] * 1e6,
                     bool(ok_hot and hot[1] <= T_max + 1e-3 and hot[2] >= h_lim * (1 - 1e-3)), wall])
        paths[name] = np.array([np.exp(k) for k in memo], float)
        messages.append(f"SLSQP {name}: " + "; ".join(f"from ({s_[0]}, {s_[1] * 1e6:g} um): "
                                                       f"{e[2].message} ({e[2].nit} it., power x {e[1]:.4f}"
                                                       f"{', infeasible' if e[0] else ''})"
                                                       for e, s_ in zip(ends, cfg["starts"])) + f"; {n_calls} calls")
        print(f"  {name}: L/D {LD:.3f}, c {c * 1e6:.1f} um; as designed: power {v[0]:.0f} W, h_min "
              f"{v[2] * 1e6:.2f} um; at its own temperature: {hot[1]:.1f} C, power {hot[0]:.0f} W, h_min "
              f"{hot[2] * 1e6:.2f} um ({n_calls} calls, {wall:.1f} s)", flush=True)
    header = ["design", "solver_calls", "L_over_D", "clearance_um", "power_as_designed_W", "min_film_as_designed_um",
              "power_thermal_W", "T_eff_C", "min_film_thermal_um", "feasible_when_heated", "wall_s"]
    notes = [f"lined hub bearing: R = {R} m, W = {W:g} N, hub at {cfg['rpm']:g} rpm about a fixed shaft, ISO VG 32 "
             f"supplied at {T_in:g} C, 2 mm SLS liner (0.3 / 3 GPa, 1 ms, nu 0.4, WLF 8.86 / 101.6 at 40 C), "
             f"grid {options.n} x {options.m}; thermal: ISO 7902 effective temperature, side leakage and "
             f"hA = {hA:g} W/K",
             f"constraints: T_eff <= {T_max:g} C (the liner's stated maximum); h_min >= {h_lim * 1e6:.2f} um = "
             f"3 sigma (lambda >= 3, sigma = {SIGMA * 1e6:.2f} um: a ground journal Rq 0.2 um against a turned "
             f"liner Rq 1.6 um)",
             f"box: L/D {cfg['box'][0]}, c {tuple(b * 1e6 for b in cfg['box'][1])} um; first call (compile) "
             f"{t_compile:.1f} s; the figure's {k} x {k} landscape, thermal and isothermal: {t_grid:.1f} s",
             "every design evaluated at its own temperature (the thermal columns): the isothermal ones as they "
             "would run"]
    notes += messages
    _common.write_csv(out / "design_thermal.csv", header, rows, comments=notes)
    th, iso = landscape["thermal"], landscape["isothermal"]
    _common.write_csv(out / "design_thermal_landscape.csv",
                      ["L_over_D", "c_m", "power_thermal_W", "T_eff_C", "min_film_thermal_m", "power_40C_W",
                       "min_film_40C_m"],
                      [(*np.exp(grid[i, j]), *th[i, j], iso[i, j, 0], iso[i, j, 2])
                       for i in range(k) for j in range(k)])
    text = _common.print_table(header, rows, title="lined journal bearing design: isothermal against thermal")
    print("\n".join(notes))
    return text + "\n" + "\n".join(notes), rows, paths, (lo, hi, T_max, h_lim, grid, landscape)


def plot_thermal(out, rows, paths, settings):
    import matplotlib.pyplot as plt
    lo, hi, T_max, h_lim, grid, landscape = settings
    fig, axes = plt.subplots(1, 4, figsize=(16, 4.2), gridspec_kw=dict(width_ratios=(1.8, 1, 1, 1)))
    colors = ("0.5", "tab:blue", "tab:red")
    X, Y = np.exp(grid[..., 0]), np.exp(grid[..., 1]) * 1e6
    hot, iso = landscape["thermal"], landscape["isothermal"]
    cf = axes[0].contourf(X, Y, hot[..., 0], 12, cmap="viridis")
    fig.colorbar(cf, ax=axes[0], label="power loss at its own temperature (W)")
    axes[0].contour(X, Y, hot[..., 1], [T_max], colors="tab:red")
    axes[0].contour(X, Y, hot[..., 2], [h_lim], colors="tab:red", linestyles="--")
    axes[0].contour(X, Y, iso[..., 2], [h_lim], colors="tab:blue", linestyles="--")
    outside = lambda v, level: "" if v.min() < level < v.max() else " (not in the box)"   # noqa: E731
    axes[0].plot([], [], color="tab:red", label=f"thermal: T_eff = {T_max:g} C" + outside(hot[..., 1], T_max))
    axes[0].plot([], [], "--", color="tab:red", label="thermal: h_min = 3 sigma" + outside(hot[..., 2], h_lim))
    axes[0].plot([], [], "--", color="tab:blue", label="isothermal: h_min = 3 sigma" + outside(iso[..., 2], h_lim))
    for (name, path), row, color, size in zip(paths.items(), rows, colors, (20, 13, 16)):
        axes[0].plot(path[:, 0], path[:, 1] * 1e6, ".", color=color, ms=5, clip_on=False)
        axes[0].plot(row[2], row[3], "*", color=color, ms=size, mec="w", label=name, clip_on=False)
    axes[0].set(xlim=np.exp([lo[0], hi[0]]), ylim=np.exp([lo[1], hi[1]]) * 1e6, xlabel="L / D",
                ylabel="radial clearance (um)", title=f"SLSQP iterates (.) and optima (*); contours from a "
                                                      f"{X.shape[0]} x {X.shape[1]} grid")
    axes[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    x = np.arange(len(rows))
    short = ["iso", "iso + h_min", "thermal"]
    for ax, k_design, k_hot, label, limit in ((axes[1], 4, 6, "power loss (W)", None),
                                              (axes[2], None, 7, "T_eff (C)", T_max),
                                              (axes[3], 5, 8, "minimum film (um)", h_lim * 1e6)):
        if k_design is not None:
            ax.bar(x - 0.2, [r[k_design] for r in rows], 0.4, color="0.8", label="as designed")
        ax.bar(x + (0.2 if k_design is not None else 0), [r[k_hot] for r in rows], 0.4, color=colors,
               label="at its own temperature")
        if limit is not None:
            ax.axhline(limit, color="k", ls="--", lw=0.8, label="limit")
        ax.set_xticks(x, short, fontsize=8)
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
    fig.suptitle("lined journal bearing design: the isothermal optimum, and where T_eff <= T_max and h_min >= "
                 "3 sigma move it", fontsize=9)
    fig.tight_layout()
    _common.save_figure(fig, out / "design_thermal.png")


# ---- needle roller bearing -----------------------------------------------------------
def _peak(p):
    """Peak of a sampled pressure by a parabola through the largest node and its two
    neighbours. Differentiable, and far smoother in the design than max(p): when the
    largest node changes it jumps only by the asymmetry of the profile's third differences
    (zero for a parabola), not by the grid error of the peak."""
    import jax
    import jax.numpy as jnp
    n = p.shape[0]
    i = jnp.argmax(jax.lax.stop_gradient(p))
    pm, p0, pp = p[(i - 1) % n], p[i], p[(i + 1) % n]
    curv = pm - 2 * p0 + pp
    safe = jnp.where(curv < 0, curv, -1.0)
    return p0 - jnp.where(curv < 0, (pp - pm) ** 2 / (8 * safe), 0.0)


ROLLER = dict(D=2e-3, load=2e4, rpm=(300.0, 3000.0), T=(40.0, 70.0), p_lim=170e6, Q_lim=12e3,
              lo=(-10.0, 3.5), hi=(40.0, 5.0), Z=(8, 10, 12))


def _same_shape(mats):
    """The materials padded to the same number of Prony terms (zero-modulus arms add nothing to
    any modulus), so that one compiled function takes any of them as an argument."""
    import dataclasses

    import jax.numpy as jnp
    K = max(m.moduli.shape[0] for m, _ in mats.values())

    def pad(m):
        extra = K - m.moduli.shape[0]
        return dataclasses.replace(m, moduli=jnp.concatenate([m.moduli, jnp.zeros(extra, m.moduli.dtype)]),
                                   times=jnp.concatenate([m.times, jnp.ones(extra, m.times.dtype)]))
    return {name: (pad(m), shift) for name, (m, shift) in mats.items()}


def roller_design(out, quick=False):
    """Gradient (SLSQP per enumerated material and Z) versus random search; see the module
    docstring. Returns (text, rows, samples, paths, settings)."""
    import jax
    import jax.numpy as jnp
    import vjax
    from scipy.optimize import minimize
    from experiments.studies.torque_twin import twin_material

    c = dict(ROLLER)
    n = 128 if quick else 2048
    Zs = (10,) if quick else c["Z"]
    mats = {"pyvisco": twin_material(quick)[:2]}
    if not quick:
        mats["dmasuite"] = twin_material(quick, data="dmasuite", density=1.0)[:2]
    mats = _same_shape(mats)
    W, T = (a.ravel() for a in np.meshgrid(np.asarray(c["rpm"]) * 2 * np.pi / 60, c["T"]))
    W, T = jnp.asarray(W), jnp.asarray(T)
    lo, hi = np.asarray(c["lo"]), np.asarray(c["hi"])

    def evaluate(y, mat, shift, Z):
        """(mean torque N m/m, peak pressure Pa, max roller load N/m) at y = (P_d um, R_I mm)."""
        def one(w, t):
            Pd, RI = y[0] * 1e-6, y[1] * 1e-3
            ring = mat.with_shift(shift)
            r = vjax.roller_bearing(ring, ring, RI + c["D"] + Pd / 2, RI, c["D"], Z, c["load"], diametral_clearance=Pd,
                                    omega_shaft=w, temperature=t, options=vjax.RollerOptions(n=n),
                                    throw=False)
            peak = jnp.maximum(_peak(r.pressure), _peak(r.pressure_shaft))
            return jnp.stack([r.torque, peak, jnp.max(r.roller_loads[0])]), r.converged
        v, ok = jax.vmap(one)(W, T)
        return jnp.stack([jnp.mean(v[:, 0]), jnp.max(v[:, 1]), jnp.max(v[:, 2])]), jnp.all(ok)

    # compiled once per Z (a shape) and kind, outside the clocks: forward only, and value +
    # Jacobian; the materials are arguments, so every material reuses the same function
    compiled, compile_s = {}, [0.0]

    def function(Z, grad):
        key = (Z, grad)
        if key not in compiled:
            def f(z, mat, shift):
                return evaluate(z, mat, shift, Z)

            def value_and_jacobian(z, mat, shift):
                # one forward pass carries the values and both tangents
                def with_values(q):
                    out = f(q, mat, shift)
                    return out[0], out
                return jax.jacfwd(with_values, has_aux=True)(z)[::-1]

            g = jax.jit(value_and_jacobian if grad else f)
            t0 = time.perf_counter()
            jax.block_until_ready(g(jnp.asarray((lo + hi) / 2), *next(iter(mats.values()))))
            compile_s[0] += time.perf_counter() - t0
            compile_s.append((Z, grad, time.perf_counter() - t0))
            compiled[key] = g
        return compiled[key]

    calls = {"n": 0}

    def solve(y, name, Z, grad):
        """One solver call: (values, Jacobian or None, all solves converged)."""
        calls["n"] += 1
        out = function(Z, grad)(jnp.asarray(y, float), *mats[name])
        (v, ok), J = out if grad else (out, None)
        return np.asarray(v), (None if J is None else np.asarray(J)), bool(ok)

    def feasible(v, ok):
        return ok and v[1] <= c["p_lim"] * (1 + 1e-3) and v[2] <= c["Q_lim"] * (1 + 1e-3)

    # ---- gradient: SLSQP on each enumerated (material, Z) ----
    t_grad, best, paths, messages = 0.0, None, {}, []
    for name in mats:
        for Z in Zs:
            memo = {}

            def ev(y, name=name, Z=Z, memo=memo):
                key = tuple(np.round(y, 10))
                if key not in memo:
                    memo[key] = solve(y, name, Z, grad=True)
                return memo[key]

            function(Z, grad=True)
            t0 = time.perf_counter()
            v0, _, ok0 = ev((lo + hi) / 2)
            scale = abs(v0[0]) if ok0 and np.isfinite(v0[0]) and v0[0] != 0 else 1.0
            obj = lambda y: ev(y)[0][0] / scale if ev(y)[2] else 1e3
            obj_j = lambda y: ev(y)[1][0] / scale if ev(y)[2] else np.zeros(2)
            cons = lambda y: (np.array([1 - ev(y)[0][1] / c["p_lim"], 1 - ev(y)[0][2] / c["Q_lim"]])
                              if ev(y)[2] else -np.ones(2))
            cons_j = lambda y: (np.stack([-ev(y)[1][1] / c["p_lim"], -ev(y)[1][2] / c["Q_lim"]])
                                if ev(y)[2] else np.zeros((2, 2)))
            res = minimize(obj, (lo + hi) / 2, jac=obj_j, method="SLSQP", bounds=list(zip(lo, hi)),
                           constraints=[{"type": "ineq", "fun": cons, "jac": cons_j}],
                           options={"maxiter": 3 if quick else 12, "ftol": 1e-5})
            t_grad += time.perf_counter() - t0
            v, _, ok = ev(res.x)
            paths[(name, Z)] = [(k, *y, *vv, okk) for k, (y, (vv, _, okk)) in enumerate(memo.items())]
            messages.append(f"SLSQP {name} Z={Z}: {res.message} ({res.nit} iterations, {len(memo)} calls)")
            print(f"  SLSQP {name:8s} Z={Z:2d}: P_d {res.x[0]:6.2f} um, R_I {res.x[1]:.3f} mm, torque {v[0]:.4g} "
                  f"N m/m, peak {v[1] / 1e6:.1f} MPa, Q_max {v[2]:.0f} N/m, feasible {feasible(v, ok)}, "
                  f"{len(memo)} calls; SLSQP: {res.message}", flush=True)
            if feasible(v, ok) and (best is None or v[0] < best[3][0]):
                best = (name, Z, res.x, v)
    n_grad = calls["n"]

    # ---- random search over (material, Z, P_d, R_I) with the same number of calls ----
    rng = np.random.default_rng(0)
    samples, rbest, t_rand = [], None, 0.0
    # --quick (a smoke run) evaluates the random samples with the gradient's program, Jacobian
    # discarded: one compiled function instead of two; its timings then mean nothing
    values_only = not quick
    for k in range(n_grad):
        name = list(mats)[rng.integers(len(mats))]
        Z = int(Zs[rng.integers(len(Zs))])
        y = lo + (hi - lo) * rng.uniform(size=2)
        function(Z, grad=not values_only)
        t0 = time.perf_counter()
        v, _, ok = solve(y, name, Z, grad=not values_only)
        t_rand += time.perf_counter() - t0
        samples.append((name, Z, *y, *v, ok, feasible(v, ok)))
        if feasible(v, ok) and (rbest is None or v[0] < rbest[3][0]):
            rbest = (name, Z, y, v)
    print(f"  random search: {n_grad} calls, {sum(s[-1] for s in samples)} feasible", flush=True)

    def row(method, b, wall):
        if b is None:
            return [method, n_grad, "-", "-", float("nan"), float("nan"), float("nan"), float("nan"),
                    float("nan"), False, wall]
        name, Z, y, v = b
        return [method, n_grad, name, Z, y[0], y[1], v[0], v[1] / 1e6, v[2], True, wall]

    rows = [row("SLSQP + implicit gradients (enumerated material, Z)", best, t_grad),
            row("random search", rbest, t_rand)]
    header = ["method", "solver_calls", "material", "Z", "clearance_um", "R_inner_mm", "torque_N_m_per_m",
              "peak_pressure_MPa", "max_roller_load_N_per_m", "feasible", "wall_s"]
    notes = [f"needle roller bearing, n={n} per ring, D={c['D'] * 1e3:g} mm, load {c['load']:g} N/m, outer ring fixed; "
             f"torque = mean over {c['rpm']} rpm x {c['T']} C",
             f"constraints over the same conditions: peak pressure <= {c['p_lim'] / 1e6:g} MPa, roller load <= "
             f"{c['Q_lim']:g} N/m; P_d in [{lo[0]:g}, {hi[0]:g}] um, R_I in [{lo[1]:g}, {hi[1]:g}] mm, Z in {Zs}, "
             f"materials {list(mats)}",
             "a solver call = one design evaluation = four vmapped bearing solves (SLSQP: + its 2-column Jacobian)",
             f"compile time (excluded from wall_s): {compile_s[0]:.1f} s for {len(compiled)} functions (one per Z "
             f"and kind, shared by the materials); the first step's: {compile_s[1][2]:.1f} s"] + messages
    _common.write_csv(out / "design_roller.csv", header, rows, comments=notes)
    hist = [("SLSQP", name, Z) + tuple(p[1:]) for (name, Z), ps in paths.items() for p in ps]
    hist += [("random",) + s[:-1] for s in samples]
    _common.write_csv(out / "design_roller_history.csv",
                      ["method", "material", "Z", "clearance_um", "R_inner_mm", "torque_N_m_per_m", "peak_pressure_Pa",
                       "max_roller_load_N_per_m", "converged"], hist)
    text = _common.print_table(header, rows, title="roller bearing design: gradient vs random search")
    print("\n".join(notes))
    return text + "\n" + "\n".join(notes), rows, samples, paths, (list(mats), Zs, lo, hi)


def plot_roller(out, samples, paths, settings):
    import matplotlib.pyplot as plt
    names, Zs, lo, hi = settings
    fig, axes = plt.subplots(len(names), len(Zs), figsize=(4.2 * len(Zs), 3.6 * len(names)), squeeze=False,
                             sharex=True, sharey=True)
    tq = [s[4] for s in samples if s[-1]] + [p[3] for ps in paths.values() for p in ps if p[-1]]
    vmin, vmax = (min(tq), max(tq)) if tq else (0, 1)
    for i, name in enumerate(names):
        for j, Z in enumerate(Zs):
            ax = axes[i, j]
            pts = np.array([s[2:6] + (s[-1],) for s in samples if s[0] == name and s[1] == Z], float).reshape(-1, 5)
            f = pts[:, 4] > 0
            sc = ax.scatter(pts[f, 0], pts[f, 1], c=pts[f, 2], vmin=vmin, vmax=vmax, marker="o", s=25)
            ax.scatter(pts[~f, 0], pts[~f, 1], c="0.6", marker="x", s=20)
            path = np.array([p[1:3] for p in paths.get((name, Z), [])], float).reshape(-1, 2)
            ax.plot(path[:, 0], path[:, 1], "k.-", lw=0.8)
            if len(path):
                ax.plot(path[-1, 0], path[-1, 1], "r*", ms=12)
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[1], hi[1])
            ax.set_title(f"{name}, Z = {Z}", fontsize=9)
            if i == len(names) - 1:
                ax.set_xlabel("diametral clearance (um)")
            if j == 0:
                ax.set_ylabel("inner raceway radius (mm)")
    fig.colorbar(sc, ax=axes, label="mean friction torque (N m/m)")
    fig.suptitle("roller design: random samples (o feasible, x infeasible), SLSQP path (.-) and end point (*)",
                 fontsize=9)
    _common.save_figure(fig, out / "design_roller.png")


def main(out_dir="experiments/out", quick: bool = False, only=None) -> dict:
    out = _common.setup(out_dir)
    result, texts = {}, []
    if only in (None, "journal"):
        text, rows, rs_rows, history, settings = journal_design(out, quick)
        plot_journal(out, rows, rs_rows, history, settings)
        result["journal"] = rows
        texts.append(text)
    if only in (None, "finite"):
        text, rows, rs_rows, history, _ = finite_journal_design(out, quick)
        plot_finite_journal(out, rows, rs_rows, history)
        result["finite"] = rows
        texts.append(text)
    if only in (None, "thermal"):
        text, rows, paths, settings = thermal_design(out, quick)
        plot_thermal(out, rows, paths, settings)
        result["thermal"] = rows
        texts.append(text)
    if only in (None, "roller"):
        text, rows, samples, paths, settings = roller_design(out, quick)
        plot_roller(out, samples, paths, settings)
        result["roller"] = rows
        texts.append(text)
    _common.atomic_write_text(out / f"design_summary{'' if only is None else '_' + only}.txt",
                              "\n\n".join(texts) + "\n")
    return result


def plot_journal(out, rows, rs_rows, history, settings):
    import matplotlib.pyplot as plt
    lo, hi, h_lim = settings
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


def plot_finite_journal(out, rows, rs_rows, history):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    rr = np.array([r[1:8] for r in rs_rows], float)          # L/D, c, t, P, h_min, margin, ok
    hh = np.array([h[1:8] for h in history], float)
    feas = (rr[:, 6] > 0) & (rr[:, 4] >= FINITE["h_lim"]) & (rr[:, 5] >= 0)
    sc = ax.scatter(rr[feas, 0], rr[feas, 1] * 1e6, c=rr[feas, 3], marker="o", label="random (feasible)")
    ax.scatter(rr[~feas, 0], rr[~feas, 1] * 1e6, c="0.7", marker="x", label="random (infeasible)")
    ax.plot(hh[:, 0], hh[:, 1] * 1e6, "k.-", lw=0.8, label="SLSQP iterates")
    ax.plot(rows[0][2], rows[0][3], "r*", ms=14, label="gradient optimum")
    fig.colorbar(sc, ax=ax, label="power loss (W)")
    ax.set_xlabel("L / D")
    ax.set_ylabel("radial clearance (um)")
    ax.legend(fontsize=7)
    _common.save_figure(fig, out / "design_finite_journal.png")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", choices=("journal", "finite", "thermal", "roller"), default=None)
    ap.add_argument("--out", default="experiments/out")
    a = ap.parse_args()
    main(a.out, quick=a.quick, only=a.only)
