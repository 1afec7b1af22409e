"""Benchmark of the dry contact solver (issue 3): pin in a hole and Hertz on a half-plane.

Run::

    PYTHONPATH=. python -m experiments.benchmarks.bench_pin [out_dir] [--quick]

**Pin in a hole**, the thesis's viscoelastic case (R = 0.08 m, R' = 0.075 m, SLS E0 = 1 MPa,
Einf = 10 MPa, tau = 0.01 s, nu = 0.5, F~ = 3.5e-2, omega~ = omega tau = 1, periodic
memory, float64, default :class:`vjax.PinOptions`). For N = 2^8 ... 2^16:

- ``fwd``: ``pin_in_hole`` jitted with the material and omega as traced arguments. We
  report the first call (trace + compile + run), the median warm solve time, the
  active-set iterations, and the relative errors of torque and pin offset against the
  finest N. ``fwd_ops`` is the warm time divided by the time of one jitted operator
  application u = op(sigma) at that N, i.e. the solve's cost in operator applications.
- ``grad``: reverse-mode ``jax.grad`` of the torque with respect to every material
  parameter (E0, E_k, tau_k, nu), by the solver's implicit derivative. We report the
  first call, the warm median and the ratio to the forward solve.
- ``dense``: a baseline in the thesis's style (Section 2.1: "elements with negative
  pressure are removed, those with compenetration are added"), in numpy with one BLAS
  thread (see the note at the imports), for N <= 2^12.
  The matrix is the dense N x N ``op.dense()`` (assembly timed separately). For a fixed
  pin offset, LAPACK solves M_AA p_A = d_A on the contact set and the set is updated
  until it stops changing. An outer secant iteration on the offset meets the load (the
  same Eq. 2.21 force as pin_in_hole). We report the time, the number of dense solves,
  and the torque difference against the FFT solver at the same N.

Targets (issue 3, this 2-core CPU, float64): N = 4096 warm solve < 30 ms and < 100 operator
applications, gradient < 3x forward, compile < 10 s.

**Half-plane mode**: ``solve_contact`` with ``ring_operator("half_plane", ...)`` on a
periodic cell of length L = 1 m (ring radius L/2pi), rigid cylinder of radius 0.5 m (parabolic
profile, as Hertz), E = 1 MPa, nu = 0.3, load such that the Hertz half-width is a =
0.025 L. We report the errors of the peak pressure and of the half-width (edge found by
extrapolating p^2 to zero, :func:`experiments.figures.persson.edge_angle`) against Hertz, and the
median time, for N = 2^10 ... 2^16. The vjax kernel is the log kernel truncated to the
cell, which is exact for every pair of points in one contact (|x - x'| < L/2). The same
problem goes to **tamaas** (``PolonskyKeerRey``, basic_1d, tol 1e-12) when it is installed.
Its Westergaard kernel is truly periodic, i.e. an array of cylinders, which differs from
one Hertz contact by O((a/L)^2) ~ 1e-3.

Outputs in ``out_dir``: ``bench_pin.csv``, ``bench_pin_halfplane.csv``, ``bench_pin.png``,
``bench_pin.txt``.
"""
from __future__ import annotations

import os
import platform
import sys
import time

# The dense baseline runs numpy/LAPACK. With OpenBLAS's default threads next to JAX's own
# thread pool on this 2-core machine, a 200 x 200 solve took 36 ms instead of 0.7 ms
# (oversubscription). One BLAS thread gives the baseline its fair single-core speed.
# This only works if numpy is not imported yet, i.e. when run as a script.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

from experiments import _common  # noqa: E402

_common.enable_x64()

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402
from experiments.figures import persson  # noqa: E402
from vjax import reference  # noqa: E402


def _write_csv(path, header, rows, comments=()):
    """_common.write_csv with numpy scalars turned into Python numbers first (under numpy 2,
    repr(np.float64(x)) is 'np.float64(x)', which _common._cell would write verbatim)."""
    py = lambda x: x.item() if isinstance(x, np.generic) else x
    return _common.write_csv(path, header, [[py(x) for x in r] for r in rows], comments=comments)

R, R_PIN, E0, EINF, TAU, NU, F_TILDE, OMEGA_TILDE = 0.08, 0.075, 1e6, 1e7, 0.01, 0.5, 3.5e-2, 1.0
LOAD = F_TILDE * E0 * R
TARGETS = dict(n=4096, fwd_ms=30.0, fwd_ops=100.0, grad_ratio=3.0, compile_s=10.0)


def material():
    return vjax.Material.sls(E0, EINF, TAU, NU)


def pin(m, omega, n, **options):
    """The benchmark pin at patch speed ``omega`` (rad/s relative to the plane), not raising."""
    c = R - R_PIN
    return vjax.pin_in_hole(m, R, c, LOAD, omega_shaft=vjax.pin_shaft_speed(omega, R, c),
                            options=vjax.PinOptions(n=n, **options), throw=False)


def _pin_fn(n):
    @jax.jit
    def fwd(m, omega):
        r = pin(m, omega, n)
        return r.torque, r.pin_offset, r.iterations, r.converged, r.pressure
    return fwd


def _grad_fn(n):
    return jax.jit(jax.grad(lambda m, omega: pin(m, omega, n).torque))


def _op_time(n, repeats):
    op = vjax.ring_operator("hole", material(), R, n, OMEGA_TILDE / TAU)
    apply = jax.jit(lambda o, s: o(s))
    sigma = jnp.asarray(np.random.default_rng(0).random(n))
    return _common.time_fn(apply, op, sigma, repeats=repeats, number=20)[1]


# ------------------------------------------------------------- dense active-set baseline
def _spectral_derivative(u):
    n = u.shape[-1]
    k = np.arange(n // 2 + 1)
    k = np.where(k == n // 2, 0, k)
    return np.fft.irfft(1j * k * np.fft.rfft(u), n)


def dense_active_set(M, n, e0, max_outer=30, max_inner=50):
    """Thesis-style solve: direct dense solve on the contact set, add/remove; secant on e.

    Returns (pressure, e, number of dense solves, outer iterations).
    """
    theta = 2 * np.pi * np.arange(n) / n
    dth = 2 * np.pi / n
    solves = 0

    def at_offset(e):
        nonlocal solves
        d = e * np.cos(theta) + np.sqrt(R_PIN**2 - (e * np.sin(theta)) ** 2) - R
        act = d > 0
        p = np.zeros(n)
        for _ in range(max_inner):
            p = np.zeros(n)
            if act.any():
                p[act] = np.linalg.solve(M[np.ix_(act, act)], d[act])
                solves += 1
            neg = act & (p < 0)
            if neg.any():                       # remove tensile elements first
                act = act & ~neg
                continue
            g = M @ p - d
            pen = (~act) & (g < -1e-12 * np.max(np.abs(d)))
            if not pen.any():
                break
            act = act | pen
        u = M @ p
        force = dth * np.sum(p * (R * np.cos(theta) + _spectral_derivative(u) * np.sin(theta)))
        return p, force - LOAD

    e_a, (p, f_a) = e0, at_offset(e0)
    e_b = e0 * 1.05
    p, f_b = at_offset(e_b)
    it = 0
    for it in range(1, max_outer + 1):
        if abs(f_b) <= 1e-10 * LOAD or f_b == f_a:
            break
        e_a, e_b, f_a = e_b, e_b - f_b * (e_b - e_a) / (f_b - f_a), f_b
        p, f_b = at_offset(e_b)
    return p, e_b, solves, it


# ------------------------------------------------------------------- half-plane / Hertz
L_CELL, R_CYL, E_HP, NU_HP, A_OVER_L = 1.0, 0.5, 1e6, 0.3, 0.025


def hertz():
    """Load, half-width and peak pressure of the Hertz case: the load that gives a = A_OVER_L L."""
    a = A_OVER_L * L_CELL
    F = a * a * np.pi * E_HP / (1 - NU_HP**2) / (4 * R_CYL)      # inverts a^2 = 4 F R / (pi E*)
    a_ref, p0, _ = reference.hertz_line_contact(F, R_CYL, E_HP, NU_HP)
    return F, float(a_ref), float(p0)


def _hp_interference(q, args):
    x, Rc = args
    return q[0] - x**2 / (2 * Rc)


def _hp_force(sigma, u, args):
    x, _ = args
    return (L_CELL / x.shape[0]) * jnp.sum(sigma)[None]


def _hp_fn(n):
    Rring = L_CELL / (2 * np.pi)
    F, a, _ = hertz()

    @jax.jit
    def solve(m):
        op = vjax.ring_operator("half_plane", m, Rring, n, 0.0)
        th, _ = vjax.grid(n)
        x = Rring * jnp.angle(jnp.exp(1j * th))
        # start from a third of Hertz's approach: the active set has to grow to the answer
        sol = vjax.solve_contact(op, _hp_interference, (x, R_CYL), jnp.array([0.3 * a * a / (2 * R_CYL)]), _hp_force,
                                 jnp.array([F]))
        return sol.pressure, sol.converged, sol.iterations
    return solve


def tamaas_hertz(n, repeats):
    """Same problem with tamaas; None when tamaas is not importable."""
    try:
        import tamaas as tm
    except Exception:                 # noqa: BLE001 - any import failure means: skip
        return None
    tm.set_log_level(tm.LogLevel.error)
    F, a, p0 = hertz()
    x = (np.arange(n) - n // 2) * L_CELL / n
    surf = -(x**2) / (2 * R_CYL)

    def run():
        model = tm.ModelFactory.createModel(tm.model_type.basic_1d, [L_CELL], [n])
        model.E, model.nu = E_HP, NU_HP
        solver = tm.PolonskyKeerRey(model, surf, 1e-12, tm.PolonskyKeerRey.pressure, tm.PolonskyKeerRey.pressure)
        solver.solve(F / L_CELL)
        return np.array(model.traction).ravel()

    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        p = run()
        times.append(time.perf_counter() - t0)
    a_num = persson.edge_angle(2 * np.pi * x / L_CELL, p) * L_CELL / (2 * np.pi)
    return p.max() / p0 - 1, a_num / a - 1, float(np.median(times)), tm.__version__


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    print(f"device: {_common.device_note()}", flush=True)
    ns = [2**k for k in ((8, 9) if quick else range(8, 17))]
    dense_max = 2**8 if quick else 2**12
    m, omega = material(), OMEGA_TILDE / TAU
    rows = {}
    for n in ns:
        reps = 3 if quick else (30 if n <= 4096 else 7)
        fwd = _pin_fn(n)
        first, med = _common.time_fn(fwd, m, omega, repeats=reps)
        torque, offset, iters, conv, p = jax.block_until_ready(fwd(m, omega))
        t_op = _op_time(n, reps)
        g = _grad_fn(n)
        gfirst, gmed = _common.time_fn(g, m, omega, repeats=max(3, reps // 2))
        grads = g(m, omega)
        finite = all(bool(jnp.all(jnp.isfinite(x))) for x in jax.tree_util.tree_leaves(grads))
        rows[n] = dict(n=n, fwd_first_s=first, fwd_ms=med * 1e3, iterations=int(iters), converged=bool(conv),
                       op_us=t_op * 1e6, fwd_ops=med / t_op, torque=float(torque), offset=float(offset),
                       grad_first_s=gfirst, grad_ms=gmed * 1e3, grad_ratio=gmed / med, grad_finite=finite,
                       dense_assembly_s=np.nan, dense_s=np.nan, dense_solves=np.nan, dense_torque_rel=np.nan)
        if n <= dense_max:
            op = vjax.ring_operator("hole", m, R, n, omega)
            t0 = time.perf_counter()
            M = np.asarray(jax.jit(lambda o: o.dense())(op))
            rows[n]["dense_assembly_s"] = time.perf_counter() - t0
            e0 = float(offset) * 1.02
            t0 = time.perf_counter()
            pd, e_d, solves, _ = dense_active_set(M, n, e0)
            rows[n]["dense_s"] = time.perf_counter() - t0
            rows[n]["dense_solves"] = solves
            ud = M @ pd
            th = 2 * np.pi * np.arange(n) / n
            tq = R * (2 * np.pi / n) * np.sum(pd * _spectral_derivative(ud))
            rows[n]["dense_torque_rel"] = abs(tq / float(torque) - 1)
        print(f"N={n}: fwd {rows[n]['fwd_ms']:.3g} ms ({rows[n]['fwd_ops']:.3g} op apps, {int(iters)} it), "
              f"grad {rows[n]['grad_ms']:.3g} ms, dense {rows[n]['dense_s']:.3g} s", flush=True)
    ref = rows[ns[-1]]
    for r in rows.values():
        r["torque_err"] = abs(r["torque"] / ref["torque"] - 1) if r["n"] != ns[-1] else np.nan
        r["offset_err"] = abs(r["offset"] / ref["offset"] - 1) if r["n"] != ns[-1] else np.nan
    cols = ["n", "fwd_first_s", "fwd_ms", "iterations", "op_us", "fwd_ops", "torque_err", "offset_err",
            "grad_first_s", "grad_ms", "grad_ratio", "dense_assembly_s", "dense_s", "dense_solves",
            "dense_torque_rel"]
    table_rows = [[rows[n][c] for c in cols] for n in ns]
    _write_csv(out / "bench_pin.csv", cols + ["torque_Nm_per_m", "pin_offset_m", "converged", "grad_finite"],
                      [[rows[n][c] for c in cols] + [rows[n]["torque"], rows[n]["offset"], rows[n]["converged"],
                                                      rows[n]["grad_finite"]] for n in ns],
                      comments=[f"pin in hole: R={R}, R'={R_PIN}, SLS E0={E0}, Einf={EINF}, tau={TAU}, nu={NU}, "
                                f"F~={F_TILDE}, omega~={OMEGA_TILDE}, periodic memory, float64",
                                f"{platform.processor() or platform.machine()}, {os.cpu_count()} cpus, jax "
                                f"{jax.__version__}, backend {jax.default_backend()}",
                                "errors relative to the finest N; fwd_ops = fwd time / one jitted op application",
                                "dense: numpy active-set with direct solves on the contact set (thesis style)"])

    # half-plane Hertz
    hp_ns = [2**k for k in ((10,) if quick else range(10, 17))]
    F, a, p0 = hertz()
    mhp = vjax.Material.elastic(E_HP, NU_HP)
    hp_rows = []
    tam_note = None
    for n in hp_ns:
        reps = 3 if quick else (10 if n <= 8192 else 5)
        fn = _hp_fn(n)
        first, med = _common.time_fn(fn, mhp, repeats=reps)
        p, conv, it = fn(mhp)
        p = np.asarray(p)
        th = np.asarray(vjax.grid(n)[0])
        a_num = persson.edge_angle(th, p) * L_CELL / (2 * np.pi)
        row = [n, p.max() / p0 - 1, a_num / a - 1, med * 1e3, first, int(it), bool(conv)]
        tam = tamaas_hertz(n, reps)
        if tam is None:
            tam_note = "tamaas not importable: skipped"
            row += [np.nan, np.nan, np.nan]
        else:
            row += [tam[0], tam[1], tam[2] * 1e3]
            tam_note = f"tamaas {tam[3]} (PolonskyKeerRey, tol 1e-12, periodic Westergaard kernel)"
        hp_rows.append(row)
    hp_cols = ["n", "vjax_peak_err", "vjax_halfwidth_err", "vjax_ms", "vjax_first_s", "vjax_iterations",
               "vjax_converged", "tamaas_peak_err", "tamaas_halfwidth_err", "tamaas_ms"]
    _write_csv(out / "bench_pin_halfplane.csv", hp_cols, hp_rows,
                      comments=[f"Hertz line contact: cell L={L_CELL} m, cylinder R={R_CYL} m, E={E_HP}, "
                                f"nu={NU_HP}, a/L={A_OVER_L}, F={F:.6g} N/m, p0={p0:.6g} Pa", tam_note])

    lines = [_common.format_table(cols, table_rows)]
    t = rows.get(TARGETS["n"])
    if t is not None:
        checks = [("warm solve < 30 ms", t["fwd_ms"], t["fwd_ms"] < TARGETS["fwd_ms"]),
                  ("< 100 operator applications", t["fwd_ops"], t["fwd_ops"] < TARGETS["fwd_ops"]),
                  ("gradient < 3x forward", t["grad_ratio"], t["grad_ratio"] < TARGETS["grad_ratio"]),
                  ("compile < 10 s (forward first call)", t["fwd_first_s"], t["fwd_first_s"] < TARGETS["compile_s"]),
                  ("compile < 10 s (gradient first call)", t["grad_first_s"],
                   t["grad_first_s"] < TARGETS["compile_s"])]
        lines.append("Targets at N = 4096:\n" + "\n".join(f"  {name}: {val:.4g} -> {'met' if ok else 'NOT met'}"
                                                          for name, val, ok in checks))
    else:
        lines.append("Targets at N = 4096: not run (quick)")
    errs = [(r["n"], r["torque_err"]) for r in rows.values() if np.isfinite(r["torque_err"])]
    if len(errs) >= 3:
        x, y = np.log([e[0] for e in errs]), np.log([max(e[1], 1e-300) for e in errs])
        lines.append(f"observed order of the torque error (fit over N <= {errs[-1][0]}): {-np.polyfit(x, y, 1)[0]:.2f}")
    lines.append(_common.format_table(hp_cols, hp_rows))
    lines.append(f"half-plane: {tam_note}")
    lines.append(f"machine: {os.cpu_count()} cpus, load average at the end {os.getloadavg()[0]:.2f} "
                 "(other processes share the cores: medians at small N are noisy)")
    text = "\n\n".join(lines)
    print(text)
    _common.atomic_write_text(out / "bench_pin.txt", text + "\n")

    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), constrained_layout=True)
    nn = np.array(ns)
    ax = axes[0]
    ax.loglog(nn, [rows[n]["fwd_ms"] for n in ns], "o-", label="FFT active set (fwd)")
    ax.loglog(nn, [rows[n]["grad_ms"] for n in ns], "s-", label="reverse grad (all material params)")
    dn = [n for n in ns if n <= dense_max]
    ax.loglog(dn, [rows[n]["dense_s"] * 1e3 for n in dn], "^-", label="dense active set (numpy)")
    ax.axhline(TARGETS["fwd_ms"], color="0.6", ls=":", lw=1)
    ax.set(xlabel="N", ylabel="median time (ms)", title="pin in hole, omega~ = 1")
    ax.legend(fontsize=8)
    ax = axes[1]
    ax.loglog(nn[:-1], [rows[n]["torque_err"] for n in ns[:-1]], "o-", label="torque")
    ax.loglog(nn[:-1], [rows[n]["offset_err"] for n in ns[:-1]], "s-", label="pin offset")
    ax.set(xlabel="N", ylabel=f"relative error vs N = {ns[-1]}", title="refinement")
    ax.legend(fontsize=8)
    ax = axes[2]
    hr = np.array([[r[0], abs(r[1]), abs(r[2]), r[3], r[7], r[8], r[9]] for r in hp_rows], dtype=float)
    ax.loglog(hr[:, 0], hr[:, 1], "o-", color="C0", label="vjax |peak err|")
    ax.loglog(hr[:, 0], hr[:, 2], "o--", color="C0", label="vjax |half-width err|")
    if np.isfinite(hr[:, 4]).any():
        ax.loglog(hr[:, 0], np.abs(hr[:, 4]), "s-", color="C1", label="tamaas |peak err|")
        ax.loglog(hr[:, 0], np.abs(hr[:, 5]), "s--", color="C1", label="tamaas |half-width err|")
    ax.set(xlabel="N", ylabel="relative error vs Hertz", title="half-plane Hertz line contact")
    ax.legend(fontsize=7)
    _common.save_figure(fig, out / "bench_pin.png")
    return text


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
