"""Large parameter sweeps: ``jax.vmap`` in chunks, each chunk sharded over all JAX devices.

:func:`sweep` evaluates a pure function ``fn(point) -> outputs`` at every point of a batch
``params`` (any PyTree whose leaves share a leading batch axis of length B) and returns the
outputs stacked along that axis, as NumPy arrays on the host.

How it works:

- ``jax.jit(jax.vmap(fn))`` is compiled **once**, for one chunk of ``chunk_size`` points
  (rounded up to a multiple of the number of devices D). The batch is cut into chunks;
  the last one is padded by repeating its last point (a valid parameter set, so a solver
  never sees zeros it cannot handle) and the padding is dropped from the result.
- Each chunk is laid out over a 1-D :class:`jax.sharding.Mesh` of the D devices with
  ``NamedSharding(mesh, PartitionSpec("batch"))``: device d gets points
  ``[d*chunk/D, (d+1)*chunk/D)`` of the chunk.
- ``partition="shard_map"`` (default) runs ``jax.vmap(fn)`` on each device's block with
  :func:`jax.shard_map`: the devices never talk to each other. ``partition="auto"`` lets
  XLA's SPMD partitioner split ``jit(vmap(fn))`` by the input sharding instead; for the
  iterative solvers of vjax that is slower, because a vmapped ``while_loop`` runs until
  *every* point of the batch has converged, and partitioned automatically its stopping
  test becomes a cross-device reduction at every iteration of every nested loop (the
  devices advance in lock step). With shard_map each device stops when its own points
  have converged.
- Only one chunk's inputs, outputs and intermediates live on the devices at a time: the
  chunk size bounds device memory (:attr:`SweepInfo.memory` reports XLA's estimate per device
  for one chunk). Outputs are copied to the host after each chunk.
- A text progress bar over chunks goes to stderr (no extra dependency); only process 0
  prints.

Devices: the same code runs on one CPU, on several CPU devices
(``XLA_FLAGS=--xla_force_host_platform_device_count=2``, set before JAX starts), on GPUs,
and on several processes or hosts. Several processes: call :func:`initialize_processes` on
every process first (it wraps ``jax.distributed.initialize`` and selects the gloo
collectives on CPU) and run the same script everywhere with the same ``params``;
``jax.devices()`` then lists all processes' devices, each process builds its shards of a
chunk with :func:`jax.make_array_from_callback` (it only touches its own devices), evaluates
them, and the outputs are gathered to every process with
``jax.experimental.multihost_utils.process_allgather``: every process returns the whole
result, and only process 0 draws the progress bar. ``experiments/distributed_sweep.py``
launches such a run on one machine and checks it against one process (tested).

If a process dies, the others block in the next gather until the coordination service
misses its heartbeats (``heartbeat_timeout`` s) and then stop with JAX's error naming the
missing task: a sweep never returns a partial result.

Points that a solver fails on are not special: pass ``throw=False`` to the scene inside
``fn`` and return its ``converged`` flag, then inspect it (a ``throw=True`` scene raises
from a host callback, which stops the whole chunk).

>>> import jax.numpy as jnp
>>> out = sweep(lambda p: p["a"] * p["b"], {"a": jnp.arange(5.0), "b": jnp.ones(5)},
...             chunk_size=2, progress=False)
>>> out.tolist()
[0.0, 1.0, 2.0, 3.0, 4.0]
"""
from __future__ import annotations

import dataclasses
import math
import sys
import time

import jax
import numpy as np
from jax.sharding import Mesh, NamedSharding, PartitionSpec

__all__ = ["sweep", "SweepInfo", "batch_size", "initialize_processes"]


@dataclasses.dataclass(frozen=True)
class SweepInfo:
    """What a :func:`sweep` did.

    points: B. chunk_size: points per chunk (a multiple of ``devices``). chunks: number of
    chunks. padded: points added to the last chunk. devices: D. compile_s: tracing and
    compilation of the chunk function (the first chunk's extra time). run_s: wall time of
    all chunks after compilation. points_per_s: B / run_s. memory: bytes for one chunk **per
    device** from XLA's ``memory_analysis`` of the compiled (SPMD-partitioned) function
    (argument, output, temp, total = their sum; multiply by ``devices`` for the whole
    chunk), or None where the backend does not report it.
    """

    points: int
    chunk_size: int
    chunks: int
    padded: int
    devices: int
    compile_s: float
    run_s: float
    points_per_s: float
    memory: dict | None


def initialize_processes(coordinator_address: str | None = None, num_processes: int | None = None,
                         process_id: int | None = None, heartbeat_timeout: int = 30) -> None:
    """Join this process to a multi-process JAX run (call before any JAX computation).

    ``coordinator_address`` "host:port" of process 0, ``num_processes`` and this
    ``process_id`` (0-based); all None on a cluster JAX detects (SLURM, Open MPI, ...: it then
    reads them from the scheduler's environment). On CPU the cross-process collectives are
    gloo's (TCP). ``heartbeat_timeout``: seconds after which the others give up on a process
    that died (JAX's default is 100).
    """
    # CPU devices' collectives only (GPUs use NCCL either way)
    jax.config.update("jax_cpu_collectives_implementation", "gloo")
    jax.distributed.initialize(coordinator_address=coordinator_address, num_processes=num_processes,
                               process_id=process_id, heartbeat_timeout_seconds=int(heartbeat_timeout))


def batch_size(params) -> int:
    """Length of the common leading axis of the leaves of ``params`` (ValueError otherwise)."""
    leaves = jax.tree_util.tree_leaves(params)
    if not leaves:
        raise ValueError("params has no array leaves: nothing to sweep over")
    sizes = set()
    for x in leaves:
        shape = np.shape(x)
        if len(shape) == 0:
            raise ValueError("every leaf of params needs a leading batch axis; found a scalar leaf")
        sizes.add(shape[0])
    if len(sizes) != 1:
        raise ValueError(f"leaves of params have different leading (batch) sizes: {sorted(sizes)}")
    return sizes.pop()


class _Progress:
    """A one-line text progress bar on stderr, redrawn with carriage returns."""

    def __init__(self, total, desc, enabled, width=30):
        self.total, self.desc, self.width = total, desc, width
        self.enabled = enabled and jax.process_index() == 0
        self.t0 = time.perf_counter()

    def update(self, done, points):
        if not self.enabled:
            return
        frac = done / self.total
        fill = int(round(self.width * frac))
        dt = time.perf_counter() - self.t0
        rate = points / dt if dt > 0 else float("nan")
        eta = (self.total - done) * dt / done if done else float("nan")
        sys.stderr.write(f"\r{self.desc} [{'#' * fill}{'.' * (self.width - fill)}] {done}/{self.total} chunks "
                         f"{points} pts {rate:.1f} pts/s eta {eta:.0f} s")
        if done == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def _memory(compiled):
    try:
        m = compiled.memory_analysis()
    except Exception:  # noqa: BLE001 - backends without the analysis
        return None
    if m is None:
        return None
    keys = ("argument_size_in_bytes", "output_size_in_bytes", "temp_size_in_bytes", "generated_code_size_in_bytes")
    d = {k.replace("_size_in_bytes", ""): int(getattr(m, k, 0) or 0) for k in keys}
    d["total"] = d["argument"] + d["output"] + d["temp"]
    return d


def _shard_map(f, mesh, in_specs, out_specs):
    """jax.shard_map (JAX >= 0.6) or jax.experimental.shard_map (older JAX), unchecked."""
    if hasattr(jax, "shard_map"):
        return jax.shard_map(f, mesh=mesh, in_specs=in_specs, out_specs=out_specs, check_vma=False)
    from jax.experimental.shard_map import shard_map
    return shard_map(f, mesh=mesh, in_specs=in_specs, out_specs=out_specs, check_rep=False)


def _to_host(x):
    if jax.process_count() > 1:
        from jax.experimental import multihost_utils
        return np.asarray(multihost_utils.process_allgather(x, tiled=True))
    return np.asarray(x)


def sweep(fn, params, *, chunk_size: int | None = None, devices=None, progress: bool = True,
          desc: str = "sweep", return_info: bool = False, partition: str = "shard_map"):
    """Evaluate ``fn`` at every point of the batch ``params``, vmapped, chunked and sharded.

    Args:
      fn: pure function of one point (a PyTree like ``params`` without the batch axis)
        returning a PyTree of arrays. It is vmapped and jitted once; static settings (grid
        size, memory model, ...) belong in a closure, parameters in ``params``.
      params: PyTree whose array leaves all have the batch size B as leading axis.
      chunk_size: points evaluated at once (bounds memory); rounded up to a multiple of the
        number of devices. Default: all B points in one chunk (rounded up likewise).
      devices: sequence of JAX devices, default ``jax.devices()`` (all devices of all
        processes).
      progress: draw a progress bar over chunks on stderr.
      desc: label of the progress bar.
      return_info: also return a :class:`SweepInfo`.
      partition: "shard_map" (default; independent per-device blocks) or "auto" (XLA SPMD
        partitioning of the jitted vmap), see the module docstring.

    Returns the outputs of ``fn`` stacked along a leading axis of length B (NumPy arrays,
    same PyTree structure), and the :class:`SweepInfo` when ``return_info``.
    """
    B = batch_size(params)
    devices = list(jax.devices() if devices is None else devices)
    D = len(devices)
    if D == 0:
        raise ValueError("no devices to run on")
    if chunk_size is None:
        chunk_size = B
    if not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be a positive integer, got {chunk_size!r}")
    chunk = int(math.ceil(min(int(chunk_size), B) / D) * D)
    n_chunks = int(math.ceil(B / chunk))
    padded = n_chunks * chunk - B

    mesh = Mesh(np.asarray(devices), ("batch",))
    sharding = NamedSharding(mesh, PartitionSpec("batch"))
    host = jax.tree_util.tree_map(np.asarray, params)
    # every output leaf is split along its batch axis like the inputs
    if partition == "shard_map":
        spec = PartitionSpec("batch")
        f = jax.jit(_shard_map(jax.vmap(fn), mesh, (spec,), spec), in_shardings=(sharding,), out_shardings=sharding)
    elif partition == "auto":
        f = jax.jit(jax.vmap(fn), in_shardings=(sharding,), out_shardings=sharding)
    else:
        raise ValueError(f"partition must be 'shard_map' or 'auto', got {partition!r}")

    def chunk_arrays(i):
        lo, hi = i * chunk, min((i + 1) * chunk, B)

        def take(x):
            part = x[lo:hi]
            if hi - lo < chunk:  # pad with copies of the last point (valid parameters)
                part = np.concatenate([part, np.repeat(part[-1:], chunk - (hi - lo), axis=0)], axis=0)
            # each process fills only the shards of its own devices (multi-host safe)
            return jax.make_array_from_callback(part.shape, sharding, lambda idx: part[idx])

        return jax.tree_util.tree_map(take, host)

    bar = _Progress(n_chunks, desc, progress)
    t0 = time.perf_counter()
    first = chunk_arrays(0)
    compiled = f.lower(first).compile()
    compile_s = time.perf_counter() - t0
    memory = _memory(compiled)
    if jax.process_count() > 1:   # start together: run_s then excludes the others' compilation
        from jax.experimental import multihost_utils
        multihost_utils.sync_global_devices("vjax.sweep: compiled")

    outs = []
    t_run = time.perf_counter()
    bar.t0 = t_run
    nxt = first
    for i in range(n_chunks):
        cur = nxt
        res = compiled(cur)  # asynchronous: prepare the next chunk's inputs while it runs
        if i + 1 < n_chunks:
            nxt = chunk_arrays(i + 1)
        outs.append(jax.tree_util.tree_map(_to_host, res))
        bar.update(i + 1, min((i + 1) * chunk, B))
    run_s = time.perf_counter() - t_run

    out = jax.tree_util.tree_map(lambda *xs: np.concatenate(xs, axis=0)[:B], *outs)
    if not return_info:
        return out
    info = SweepInfo(points=B, chunk_size=chunk, chunks=n_chunks, padded=padded, devices=D,
                     compile_s=compile_s, run_s=run_s, points_per_s=B / run_s if run_s > 0 else math.inf,
                     memory=memory)
    return out, info
