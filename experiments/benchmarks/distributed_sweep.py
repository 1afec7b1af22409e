"""A multi-process :func:`vjax.sweep` on JAX's distributed runtime, launched on this machine.

Run::

    python -m experiments.benchmarks.distributed_sweep --processes 2 [--points 1000] [--n 256] [--out DIR]

It starts ``--processes`` Python processes that join one JAX run over 127.0.0.1 (process 0
is the coordinator; CPU collectives over gloo), each evaluating its share of every chunk of
the pin-joint design sweep of :mod:`experiments.benchmarks.bench_sweep` (``--points`` solves of
:func:`vjax.pin_in_hole`), the results gathered to every process; then the same points in
one process. It checks that the results agree (to 1e-12; they are bit-identical when every
process runs the same XLA code) and prints points per second for 1 and P processes
(compilation excluded). Outputs in ``--out``: ``distributed_sweep.npz`` (written by process
0, atomically, only after the whole sweep), ``distributed_sweep.txt``.

On a cluster: run the same script on every host with :func:`vjax.initialize_processes`
called first. Under SLURM (``srun``) JAX reads the coordinator, the process count and each
process's id from the scheduler's environment, so ``vjax.initialize_processes()`` needs no
arguments; elsewhere pass ``coordinator_address="host0:port"``, ``num_processes`` and
``process_id`` (e.g. from ``$RANK``/``$WORLD_SIZE``). Every process gets the whole result; let
process 0 (``jax.process_index() == 0``) write it.

``VJAX_XLA_FLAGS`` is passed to every process as ``XLA_FLAGS`` (e.g.
``--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1`` for one thread each).

When a process dies: here the launcher stops the others at once and exits with a message
naming the process and the tail of its error output; no result file is written. On a
cluster the survivors stop with JAX's error after the heartbeat timeout (30 s by default in
:func:`vjax.initialize_processes`). A sweep never returns partial results.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]   # the repository root
CHUNK = 100


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _worker(process_id: int, processes: int, port: int, points: int, n: int, result_path: str | None,
            die_after_init: bool = False) -> dict:
    """One process of the run: join (if several), sweep, write (process 0), report."""
    import jax
    jax.config.update("jax_enable_x64", True)
    import numpy as np

    import vjax
    from experiments.benchmarks import bench_sweep

    if processes > 1:
        vjax.initialize_processes(f"127.0.0.1:{port}", processes, process_id, heartbeat_timeout=10)
    if die_after_init:                        # for the test of a process dying mid-run
        os._exit(3)
    k = math.ceil(points ** (1 / 3) - 1e-9)
    params, point = bench_sweep.pin_design(k, n, points)
    out, info = vjax.sweep(point, params, chunk_size=CHUNK, desc=f"{processes} process(es)", return_info=True)
    if result_path and jax.process_index() == 0:
        tmp = Path(result_path).with_suffix(".part.npz")
        np.savez(tmp, **out)
        os.replace(tmp, result_path)
    return {"process": jax.process_index(), "processes": jax.process_count(), "devices": info.devices,
            "points": info.points, "compile_s": info.compile_s, "run_s": info.run_s,
            "points_per_s": info.points_per_s}


def launch(processes: int, points: int, n: int, result_path: str | None, timeout: float = 1800.0,
           die: int | None = None) -> list[dict]:
    """Start ``processes`` workers on 127.0.0.1 and wait for all; a failed or hung one stops
    the others and raises RuntimeError naming it. ``die``: that process exits right after
    joining (tests). Returns the workers' reports, by process id."""
    port = _free_port()
    env = dict(os.environ, JAX_PLATFORMS="cpu", PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    # one CPU device per process; VJAX_XLA_FLAGS passes other flags (e.g. one thread each)
    env["XLA_FLAGS"] = os.environ.get("VJAX_XLA_FLAGS", "")
    procs = []
    for i in range(processes):
        cmd = [sys.executable, "-m", "experiments.benchmarks.distributed_sweep", "--worker", str(i), "--processes",
               str(processes), "--port", str(port), "--points", str(points), "--n", str(n)]
        if result_path:
            cmd += ["--result", result_path]
        if die == i:
            cmd += ["--die"]
        # stderr to a file: a pipe nobody reads could fill up and block the progress bar
        err = tempfile.TemporaryFile(mode="w+")
        procs.append((subprocess.Popen(cmd, env=env, cwd=ROOT, stdout=subprocess.PIPE, stderr=err, text=True), err))
    t0 = time.monotonic()
    try:
        while True:
            codes = [p.poll() for p, _ in procs]
            failed = [i for i, c in enumerate(codes) if c not in (None, 0)]
            if failed:
                i = failed[0]
                procs[i][1].seek(0)
                tail = procs[i][1].read()[-2000:]
                raise RuntimeError(f"distributed sweep: process {i} of {processes} exited with code {codes[i]}; "
                                   f"the others were stopped and no result was written. Its error output:\n{tail}")
            if all(c == 0 for c in codes):
                break
            if time.monotonic() - t0 > timeout:
                raise RuntimeError(f"distributed sweep: not finished after {timeout:.0f} s; processes stopped")
            time.sleep(0.2)
    finally:
        for p, _ in procs:
            if p.poll() is None:
                p.kill()
                p.wait()
    reports = []
    for p, err in procs:
        lines = [ln for ln in p.stdout.read().splitlines() if ln.startswith("RESULT ")]
        err.close()
        reports.append(json.loads(lines[-1][len("RESULT "):]))
    return reports


def main(processes=2, points=1000, n=256, out_dir="experiments/out"):
    import numpy as np

    from experiments import _common
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    single_path, multi_path = out / "distributed_sweep_single.npz", out / "distributed_sweep.npz"
    for path in (single_path, multi_path):
        path.unlink(missing_ok=True)
    print(f"{points} pin-joint solves (n = {n}), chunks of {CHUNK}: 1 process, then {processes}", flush=True)
    one = launch(1, points, n, str(single_path))[0]
    many = launch(processes, points, n, str(multi_path))
    a, b = np.load(single_path), np.load(multi_path)
    diff = max(float(np.max(np.abs(a[k].astype(float) - b[k].astype(float)))) for k in a.files)
    identical = all(np.array_equal(a[k], b[k]) for k in a.files)
    single_path.unlink()
    rate = many[0]["points_per_s"]
    lines = [f"device: {_common.device_note()} per process",
             f"1 process: {one['points_per_s']:.1f} points/s (compile {one['compile_s']:.1f} s)",
             f"{processes} processes: {rate:.1f} points/s (compile {max(r['compile_s'] for r in many):.1f} s), "
             f"speed-up {rate / one['points_per_s']:.2f}x on {os.cpu_count()} CPU cores",
             f"results equal to one process: max |difference| = {diff:.3g} (bit-identical: {identical}); "
             f"converged {int(np.sum(b['converged']))} of {points}"]
    text = "\n".join(lines) + "\n"
    _common.atomic_write_text(out / "distributed_sweep.txt", text)
    print(text)
    if not diff <= 1e-12:
        raise SystemExit(f"distributed sweep differs from the single-process run by {diff:.3g}")
    return {"single": one, "multi": many, "max_difference": diff, "identical": identical}


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--processes", type=int, default=2)
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--n", type=int, default=256, help="elements per pin solve")
    ap.add_argument("--out", default="experiments/out")
    ap.add_argument("--worker", type=int, help=argparse.SUPPRESS)
    ap.add_argument("--port", type=int, help=argparse.SUPPRESS)
    ap.add_argument("--result", help=argparse.SUPPRESS)
    ap.add_argument("--die", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args()
    for name in ("processes", "points", "n"):
        if getattr(a, name) < 1:
            ap.error(f"--{name} must be a positive integer, got {getattr(a, name)}")
    if a.worker is not None:
        print("RESULT " + json.dumps(_worker(a.worker, a.processes, a.port, a.points, a.n, a.result, a.die)),
              flush=True)
    else:
        main(a.processes, a.points, a.n, a.out)
