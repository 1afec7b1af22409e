"""Benchmark of the needle roller bearing scene: the thesis case's 60-speed sweep at n = 4096.

Run::

    PYTHONPATH=. python -m experiments.benchmarks.bench_roller [out_dir] [--quick] [--no-vmap] [--errors-only]
                                                    [--baseline REF]

Thesis case (R_O = 6 mm, R_I = 4 mm, D = 2 mm, Z = 9, zero clearance, SLS E0 = 1 MPa,
Einf = 10 MPa, tau = 0.01 s, nu = 0.5, F~ = 6.5e-3, periodic memory), omega~ = omega_c tau
from 1e-4 to 1e4 (60 speeds), n elements per ring. Three ways to run the sweep:

- ``scan``: one jitted ``lax.scan`` over the speeds with continuation (each speed starts
  Newton and the contact solves from the previous solution, ``roller_bearing(initial=)``);
- ``loop``: a Python loop over a jitted single solve (cold start each time);
- ``vmap``: one jitted ``jax.vmap`` over the speeds (cold starts, all Newton and active-set
  loops run in lock step until the slowest speed has converged).

Reported: compile time (first call: tracing + XLA compilation + one run) and the median
of warm runs of the whole sweep. ``--baseline REF`` also times the ``scan`` sweep with the
code of git commit REF (a temporary worktree, a separate process, in the same run), e.g.
``--baseline 395f6b5``, the last commit before the solver core kept Jacobians and loosened
the active-set steps' inner solves. Then the discretization error: at five speeds, n = 1024,
2048 and 4096 against a 4x finer grid (n = 16384): roller loads (max error / max load),
ring shift (relative) and outer-ring torque (relative to the sweep's peak torque), with
the observed order. Outputs ``bench_roller.csv`` and ``bench_roller.txt``.
"""
from __future__ import annotations

import os
import statistics
import time

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

RO, RI, D, Z = 6e-3, 4e-3, 2e-3, 9
SLS = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)
LOAD = 6.5e-3 * 1e6 * RO
TAU = 0.01
# omega~ = 1e-4 is left out: from a cold start at n = 16384 Newton stalls there (merit 1.5
# after its line search gives up, 200 s); at 4096 and below it converges
ERR_SPEEDS = (3e-3, 0.1, 1.4, 100.0, 1e4)


def shaft(w_tilde):
    return w_tilde / TAU * (RI + RO) / RI


def _solve(n, w, initial=None, tol=1e-10):
    return vjax.roller_bearing(SLS, SLS, RO, RI, D, Z, LOAD, omega_shaft=w, initial=initial,
                               options=vjax.RollerOptions(n=n, tol=tol, max_iter=15), throw=False)


def _summary(r):
    return dict(loads=r.roller_loads[0], torque=r.torque, shift=r.ring_shift, converged=r.converged,
                iterations=r.iterations)


def make(n):
    single = jax.jit(lambda w: _summary(_solve(n, w)))

    @jax.jit
    def scan(ws):
        r0 = _solve(n, ws[0])

        def step(prev, w):
            r = _solve(n, w, initial=prev)
            return r, _summary(r)
        return jax.lax.scan(step, r0, ws)[1]

    vmapped = jax.jit(jax.vmap(lambda w: _summary(_solve(n, w))))

    def loop(ws):
        return [single(w) for w in ws]
    return dict(scan=scan, loop=loop, vmap=vmapped, single=single)


def _time(fn, arg, repeats):
    t0 = time.perf_counter()
    out = jax.block_until_ready(fn(arg))
    first = time.perf_counter() - t0
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = jax.block_until_ready(fn(arg))
        samples.append(time.perf_counter() - t0)
    return first, (statistics.median(samples) if samples else float("nan")), out


_BASELINE = """
try:
    from experiments.benchmarks import bench_roller as br
except ImportError:   # a baseline commit from before experiments/ had folders
    from experiments import bench_roller as br
import jax.numpy as jnp, numpy as np
ws = jnp.asarray(br.shaft(np.logspace(-4, 4, {nw})))
first, med, res = br._time(br.make({n})["scan"], ws, 2)
print("BASELINE", first, med, bool(np.all(res["converged"])), float(np.mean(res["iterations"])))
"""


def baseline_scan(ref, n, nw):
    """(first call s, warm median s, converged, mean Newton steps) of the scan sweep at commit ref."""
    out = _common.run_at_commit(ref, _BASELINE.format(n=n, nw=nw))
    first, med, conv, its = out.split("BASELINE")[-1].split()
    return float(first), float(med), conv == "True", float(its)


def main(out_dir="experiments/out", quick=False, vmap=True, timings=True, baseline=None):
    out = _common.setup(out_dir)
    print(f"device: {_common.device_note()}", flush=True)
    n = 1024 if quick else 4096
    nw = 20 if quick else 60
    ws = jnp.asarray(shaft(np.logspace(-4, 4, nw)))
    lines = [f"bench_roller: thesis case, {nw} speeds omega~ = 1e-4..1e4, n = {n} per ring, periodic memory, "
             f"{os.cpu_count()} CPU(s), jax {jax.__version__}"]
    fns = make(n)
    rows = []
    variants = ([("scan", 2), ("loop", 1)] + ([("vmap", 1)] if vmap else [])) if timings else []
    for name, rep in variants:
        first, med, res = _time(fns[name], ws, rep)
        if name == "loop":
            conv = all(bool(r["converged"]) for r in res)
            its = [int(r["iterations"]) for r in res]
            compile_s = first - med      # the first call of the loop compiled the single solve once
        else:
            conv = bool(np.all(res["converged"]))
            its = list(np.asarray(res["iterations"]))
            compile_s = first - med
        lines.append(f"  {name:5s}: compile ~ {compile_s:6.1f} s (first call {first:6.1f} s), warm median "
                     f"{med:6.2f} s over {rep} run(s) = {1e3 * med / nw:6.1f} ms/speed; converged {conv}; "
                     f"Newton iterations {min(its)}-{max(its)} (mean {np.mean(its):.2f})")
        rows.append([name, n, nw, compile_s, first, med, 1e3 * med / nw, conv])
        print(lines[-1], flush=True)
    if baseline is not None and timings:
        first, med, conv, its = baseline_scan(baseline, n, nw)
        now = next(r for r in rows if r[0] == "scan")
        lines.append(f"  scan at {baseline} (same run): compile ~ {first - med:6.1f} s, warm median {med:6.2f} s "
                     f"({1e3 * med / nw:.1f} ms/speed, converged {conv}, mean Newton steps {its:.2f}); "
                     f"today / baseline = {now[5] / med:.2f}")
        rows.append([f"scan@{baseline}", n, nw, first - med, first, med, 1e3 * med / nw, conv])
        print(lines[-1], flush=True)
    lines.append(f"  target: under 10 s warm for the sweep; load average during the run {os.getloadavg()[0]:.1f}")

    # discretization error against a 4x finer grid
    ref_n = 4 * n
    ladder = [n // 4, n // 2, n]
    w_err = jnp.asarray(shaft(np.array(ERR_SPEEDS)))
    ref = [jax.device_get(make(ref_n)["single"](w)) for w in w_err]
    peak_T = max(abs(float(r["torque"])) for r in ref)
    err_rows = []
    errs = {}
    for m in ladder:
        single = make(m)["single"] if m != n else fns["single"]
        e_l, e_s, e_t = [], [], []
        for w, r_ref, wt in zip(w_err, ref, ERR_SPEEDS):
            r = jax.device_get(single(w))
            el = float(np.max(np.abs(np.asarray(r["loads"]) - np.asarray(r_ref["loads"])))) / float(np.max(r_ref["loads"]))
            es = abs(float(r["shift"]) / float(r_ref["shift"]) - 1)
            et = abs(float(r["torque"]) - float(r_ref["torque"])) / peak_T
            e_l.append(el), e_s.append(es), e_t.append(et)
            if not (bool(r["converged"]) and bool(r_ref["converged"])):
                lines.append(f"  NOT CONVERGED: n = {m} or {ref_n} at omega~ = {wt:g}")
            err_rows.append([m, ref_n, wt, el, es, et])
        errs[m] = (max(e_l), max(e_s), max(e_t))
        print(f"  n = {m}: done", flush=True)
        lines.append(f"  n = {m:5d} vs {ref_n}: max over {len(ERR_SPEEDS)} speeds: loads {max(e_l):.2e}, ring shift "
                     f"{max(e_s):.2e}, torque/peak {max(e_t):.2e}")
    for k, name in enumerate(("loads", "ring shift", "torque")):
        e = np.array([errs[m][k] for m in ladder])
        if np.all(e > 0):
            order = -np.polyfit(np.log(ladder), np.log(e), 1)[0]
            lines.append(f"  observed order ({name}): {order:.2f}")
    text = "\n".join(lines)
    print(text)
    if rows:
        _common.write_csv(out / "bench_roller.csv", ["variant", "n", "speeds", "compile_s", "first_call_s", "median_s",
                                                 "ms_per_speed", "converged"], rows,
                          comments=["thesis roller bearing sweep; times in s"])
    _common.write_csv(out / "bench_roller_error.csv", ["n", "n_ref", "omega_tilde", "err_loads", "err_ring_shift",
                                                       "err_torque_over_peak"],
                      [[a, b, float(c), float(d), float(e), float(f)] for a, b, c, d, e, f in err_rows],
                      comments=["errors against the 4x finer grid n_ref"])
    _common.atomic_write_text(out / "bench_roller.txt", text + "\n")
    return text


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir", nargs="?", default="experiments/out")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--no-vmap", action="store_true")
    ap.add_argument("--errors-only", action="store_true")
    ap.add_argument("--baseline", metavar="REF", help="also time the scan sweep at this git commit")
    a = ap.parse_args()
    main(a.out_dir, quick=a.quick, vmap=not a.no_vmap, timings=not a.errors_only, baseline=a.baseline)
