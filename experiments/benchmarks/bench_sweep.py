"""Benchmark of :func:`vjax.sweep`: a 1000-point pin-joint design sweep on 1 and 2 CPU devices.

The design sweep: friction torque, pin offset and contact angle of a polymer pin joint
(:func:`vjax.pin_in_hole`, SLS plane E0 = 1 MPa, Einf = 10 MPa, tau = 0.01 s, nu = 0.5,
hole R = 0.08 m) over 10 patch speeds x 10 loads x 10 clearances = 1000 points at n = 256
elements, in chunks of 100 points.

Each device count runs in its own subprocess, because the number of simulated CPU devices
(``XLA_FLAGS=--xla_force_host_platform_device_count=D``) is fixed when JAX starts. The runs
alternate (1, 2, 2-auto, 1, ...) so that a change of the machine's load affects both alike; the
table reports the best and the median of the repeats. Points per second exclude
compilation (reported separately). Memory per chunk is XLA's ``memory_analysis`` of the
compiled chunk function per device (arguments + outputs + temporaries); the chunk's total
is that times the number of devices.

Caveat (reported in the output): this machine has 2 cores shared with other jobs, so two
simulated devices can at best double the throughput, and only if both cores are free;
XLA's CPU backend may also already use both cores for one device.

Two partitionings with 2 devices: ``shard_map`` (vjax.sweep's default; each device runs its
block independently) and ``auto`` (XLA SPMD partitioning of the jitted vmap, whose
vmapped solver loops then synchronise the devices at every iteration).

Run: ``python -m experiments.benchmarks.bench_sweep [--quick]``.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from experiments import _common

ROOT = Path(__file__).resolve().parents[2]   # the repository root


def pin_design(points_per_axis: int, n: int, points: int | None = None):
    """The pin-joint design sweep: ``(params, point)`` for :func:`vjax.sweep` over
    ``points_per_axis``^3 combinations of patch speed, load and clearance (the first
    ``points`` of them if given), each a :func:`vjax.pin_in_hole` solve on n elements."""
    import numpy as np
    import vjax

    m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)
    R = 0.08
    k = points_per_axis
    omega = np.linspace(1.0, 300.0, k)                 # patch speed, rad/s (omega~ 0.01..3)
    load = np.linspace(1500.0, 3500.0, k)              # N/m (F~ 0.019..0.044)
    clearance = np.linspace(3e-3, 7e-3, k)             # dR, m
    W, L, C = np.meshgrid(omega, load, clearance, indexing="ij")
    params = {"omega": W.ravel()[:points], "load": L.ravel()[:points], "clearance": C.ravel()[:points]}

    def point(p):
        c = p["clearance"]
        r = vjax.pin_in_hole(m, R, c, p["load"], omega_shaft=vjax.pin_shaft_speed(p["omega"], R, c),
                             options=vjax.PinOptions(n=n), throw=False)
        return {"torque": r.torque, "offset": r.pin_offset, "angle": r.contact_angle,
                "converged": r.converged, "iterations": r.iterations}

    return params, point


def _worker(points_per_axis: int, n: int, chunk: int, partition: str = "shard_map") -> dict:
    """Runs inside the subprocess: one sweep, returns its numbers."""
    _common.enable_x64()
    import jax
    import numpy as np
    import vjax

    params, point = pin_design(points_per_axis, n)
    t0 = time.perf_counter()
    out, info = vjax.sweep(point, params, chunk_size=chunk, desc=f"{len(jax.devices())} dev {partition}",
                           return_info=True, partition=partition)
    wall = time.perf_counter() - t0
    return {"partition": partition, "devices": info.devices, "points": info.points, "chunk": info.chunk_size, "chunks": info.chunks,
            "padded": info.padded, "compile_s": info.compile_s, "run_s": info.run_s,
            "points_per_s": info.points_per_s, "wall_s": wall,
            "mem_total": (info.memory or {}).get("total", float("nan")),
            "mem_temp": (info.memory or {}).get("temp", float("nan")),
            "converged": int(np.sum(out["converged"])), "mean_iterations": float(np.mean(out["iterations"])),
            "torque_checksum": float(np.sum(out["torque"])), "n": n}


def _run(devices: int, points_per_axis: int, n: int, chunk: int, partition: str) -> dict:
    env = dict(os.environ, XLA_FLAGS=f"--xla_force_host_platform_device_count={devices}", JAX_PLATFORMS="cpu",
               PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "experiments.benchmarks.bench_sweep", "--worker", str(points_per_axis), str(n), str(chunk),
           "--partition", partition]
    r = subprocess.run(cmd, env=env, cwd=ROOT, capture_output=True, text=True, timeout=1800)
    if r.returncode != 0:
        raise RuntimeError(f"bench_sweep worker with {devices} devices failed:\n{r.stderr[-3000:]}")
    line = [ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1]
    return json.loads(line[len("RESULT "):])


def main(out_dir="experiments/out", quick: bool = False) -> dict:
    out = _common.setup(out_dir)
    print(f"device: {_common.device_note()}", flush=True)
    k, n, chunk, repeats = (4, 64, 16, 1) if quick else (10, 256, 100, 2)
    configs = [(1, "shard_map"), (2, "shard_map"), (2, "auto")]
    runs = []
    for rep in range(repeats):
        for d, part in configs:
            res = _run(d, k, n, chunk, part)
            res["repeat"] = rep
            runs.append(res)
            print(f"  devices={d} {part} repeat={rep}: {res['points_per_s']:.1f} pts/s "
                  f"(compile {res['compile_s']:.1f} s)", flush=True)
    rows = []
    summary = {}
    for d, part in configs:
        rs = [r for r in runs if r["devices"] == d and r["partition"] == part]
        best = max(r["points_per_s"] for r in rs)
        med = statistics.median(r["points_per_s"] for r in rs)
        r0 = rs[0]
        summary[(d, part)] = {"best": best, "median": med}
        rows.append([d, part, r0["points"], r0["n"], r0["chunk"], r0["chunks"], r0["padded"],
                     statistics.median(r["compile_s"] for r in rs), best, med,
                     r0["mem_total"] / 2**20, d * r0["mem_total"] / 2**20, r0["converged"], r0["mean_iterations"]])
    one, two, auto = (summary[c] for c in configs)
    speedup_best = two["best"] / one["best"]
    speedup_med = two["median"] / one["median"]
    header = ["devices", "partition", "points", "n", "chunk", "chunks", "padded", "compile_s", "pts_per_s_best",
              "pts_per_s_median", "mem_per_dev_MiB", "mem_chunk_MiB", "converged", "mean_iter"]
    try:
        load = os.getloadavg()
    except OSError:
        load = (float("nan"),) * 3
    notes = ["pin_in_hole design sweep: speed x load x clearance, SLS 1/10 MPa tau 0.01 s, R 0.08 m",
             f"CPU cores: {os.cpu_count()}, load average at the end: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}",
             f"speed-up 1 -> 2 devices (shard_map): {speedup_best:.2f}x (best runs), {speedup_med:.2f}x (median); "
             f"with XLA auto partitioning: {auto['best'] / one['best']:.2f}x (best); repeats per configuration: "
             f"{repeats}",
             "points/s exclude compilation; memory = XLA memory_analysis (args + outputs + temp) per device, and x devices per chunk",
             "checksums of the torque agree between device counts: " +
             str(len({round(r['torque_checksum'], 9) for r in runs}) == 1)]
    _common.write_csv(out / "bench_sweep.csv", header, rows, comments=notes)
    text = _common.print_table(header, rows, title="vjax.sweep benchmark")
    _common.atomic_write_text(out / "bench_sweep.txt", text + "\n" + "\n".join(notes) + "\n")
    print("\n".join(notes))
    return {"runs": runs, "speedup_best": speedup_best, "speedup_median": speedup_med,
            "summary": {f"{d}-{p}": v for (d, p), v in summary.items()}}


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--worker", nargs=3, type=int, metavar=("K", "N", "CHUNK"), help=argparse.SUPPRESS)
    ap.add_argument("--partition", default="shard_map", help=argparse.SUPPRESS)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default="experiments/out")
    a = ap.parse_args()
    if a.worker:
        print("RESULT " + json.dumps(_worker(*a.worker, partition=a.partition)), flush=True)
    else:
        main(a.out, quick=a.quick)
