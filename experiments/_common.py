"""Small helpers shared by the experiment scripts (kept small and stable: others reuse them).

- :func:`setup` / :func:`enable_x64`: float64 JAX and the non-interactive Agg backend.
- :func:`atomic_write_text`, :func:`save_figure`, :func:`write_csv`: write to a temporary
  file in the destination directory, then ``os.replace`` it, so a reader (or a crash)
  never sees a half-written file.
- :func:`time_fn`: first-call time (tracing + compilation + one run) separated from the
  median of warm calls, each synchronised with ``block_until_ready``.
- :func:`format_table` / :func:`print_table`: a plain fixed-width text table.
- :func:`run_at_commit`: run a snippet against the project as it was at a git commit (a
  temporary worktree), for a baseline timed in the same run as today's code.

Call :func:`enable_x64` (or :func:`setup`) **before** importing vjax or running any JAX
computation, e.g. at the top of a script::

    from experiments import _common
    _common.enable_x64()
    import vjax  # noqa: E402
"""
from __future__ import annotations

import contextlib
import csv
import dataclasses
import io
import math
import statistics
import time
from pathlib import Path

from fitting.shared import files

__all__ = ["Check", "StageReport", "enable_x64", "setup", "atomic_write_text", "save_figure",
           "write_csv", "time_fn", "format_table", "print_table", "run_at_commit"]


CLASSIC_FUSION_EMITTERS = "--xla_cpu_use_fusion_emitters=false"
OPTIMIZATION_LEVEL_0 = "--xla_backend_optimization_level=0"


def xla_flags_accepted(flags=(CLASSIC_FUSION_EMITTERS,), context=None) -> bool:
    """Whether a JAX process starts and computes with ``flags`` added to XLA_FLAGS: one
    subprocess, about a second; a process of the multiprocessing ``context`` if given (a fork
    server's, its imports done: a fraction of that). An XLA flag the installed jaxlib does not
    know aborts the process, so it is probed first."""
    import os
    import subprocess
    import sys
    if context is not None:
        process = context.Process(target=_compute_with_flags, args=(tuple(flags),))
        process.start()
        process.join()
        return process.exitcode == 0
    env = dict(os.environ, XLA_FLAGS=" ".join([os.environ.get("XLA_FLAGS", ""), *flags]).strip())
    probe = subprocess.run([sys.executable, "-c", "import jax.numpy as jnp; jnp.zeros(2).block_until_ready()"],
                           env=env, capture_output=True, timeout=300)
    return probe.returncode == 0


def _compute_with_flags(flags):
    import os
    os.dup2(os.open(os.devnull, os.O_WRONLY), 2)     # a rejected flag's abort message is not the caller's
    add_xla_flags(flags)
    import jax.numpy as jnp
    jnp.zeros(2).block_until_ready()


def classic_fusion_emitters_accepted() -> bool:
    """Whether a JAX process starts and computes with XLA:CPU's classic fusion emitters
    (:data:`CLASSIC_FUSION_EMITTERS` added to XLA_FLAGS; :func:`xla_flags_accepted`).

    Why: vjax's solver programs (the journal bearings' Newton loops above all) compile about
    1.4x faster with the classic emitters than with the newer MLIR ones, to the same results
    up to round-off; the roller's compile a little slower. The test suite and the main job,
    which are mostly XLA compiling, use them; vjax itself never sets XLA flags."""
    return xla_flags_accepted((CLASSIC_FUSION_EMITTERS,))


def pin_to_core(index: int, count: int) -> bool:
    """Put this process on the ``index``-th of the cores it may use, if it may use at least
    ``count`` (one process per core: ``count`` of them side by side); returns whether it did.
    Call it before JAX's backend starts: XLA sizes its thread pools by the cores a process may
    use, and processes free to use every core interrupt each other (a main-job stage beside
    another: 7 % slower unpinned; docs/benchmarks.md). Not where the platform or a sandbox
    forbids it."""
    import os
    if not hasattr(os, "sched_getaffinity"):
        return False
    cores = sorted(os.sched_getaffinity(0))
    if count > len(cores):
        return False
    try:
        os.sched_setaffinity(0, {cores[index % len(cores)]})
    except OSError:
        return False
    return True


def add_xla_flags(flags) -> None:
    """Add each of ``flags`` ("--name=value") to XLA_FLAGS in this process's environment
    (inherited by the processes it starts; effective for this one only before JAX's backend
    starts), unless XLA_FLAGS already sets that name."""
    import os
    for flag in flags:
        current = os.environ.get("XLA_FLAGS", "")
        if flag.split("=")[0] not in current:
            os.environ["XLA_FLAGS"] = f"{current} {flag}".strip()


def use_classic_fusion_emitters() -> None:
    """Add :data:`CLASSIC_FUSION_EMITTERS` to XLA_FLAGS (:func:`add_xla_flags`), unless
    XLA_FLAGS already chooses the emitters."""
    add_xla_flags((CLASSIC_FUSION_EMITTERS,))


def enable_x64() -> None:
    """Turn on float64 in JAX and select matplotlib's Agg backend (idempotent)."""
    import jax
    jax.config.update("jax_enable_x64", True)
    import matplotlib
    matplotlib.use("Agg")


@dataclasses.dataclass(frozen=True)
class Check:
    """One check of the main job: ``what`` was compared with ``reference``; ``value`` must lie
    within ``tolerance`` of ``target`` (absolute), or be >= / <= a bound (``kind``)."""

    what: str
    value: float
    target: float
    tolerance: float
    reference: str
    kind: str = "abs"        # "abs": |value - target| <= tolerance; "max": value <= target; "min": value >= target

    @property
    def passed(self) -> bool:
        v = float(self.value)
        if not math.isfinite(v):
            return False
        if self.kind == "max":
            return v <= self.target
        if self.kind == "min":
            return v >= self.target
        return abs(v - self.target) <= self.tolerance

    def expected(self) -> str:
        if self.kind == "max":
            return f"<= {self.target:.4g}"
        if self.kind == "min":
            return f">= {self.target:.4g}"
        return f"{self.target:.4g} +- {self.tolerance:.2g}"


@dataclasses.dataclass(frozen=True)
class StageReport:
    """What a stage of the main job returns: its plain-text output, what it computes (one
    paragraph for the summary), its checks and its figures with their captions."""

    text: str
    about: str = ""
    checks: tuple = ()
    figures: tuple = ()      # (file name, caption)

    def __str__(self):
        return self.text


def setup(out_dir="experiments/out") -> Path:
    """Enable float64 and Agg (:func:`enable_x64`), create ``out_dir`` and return it as a Path."""
    enable_x64()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return out


def device_note() -> str:
    """Where a benchmark ran: JAX version, backend and device kind, device count, CPUs."""
    import os
    import platform

    import jax
    devices = jax.devices()
    return (f"jax {jax.__version__} on {devices[0].platform} ({devices[0].device_kind}) x {len(devices)} "
            f"device(s), {os.cpu_count()} CPUs, {platform.machine()}")


@contextlib.contextmanager
def worktree_at(ref: str):
    """The project as it was at git commit ``ref``, checked out in a temporary worktree
    (removed afterwards); yields its path. Raises RuntimeError if ``ref`` is not a commit of
    this checkout."""
    import os
    import subprocess
    import tempfile

    root = Path(__file__).resolve().parent.parent
    with tempfile.TemporaryDirectory() as tmp:
        tree = os.path.join(tmp, "tree")
        add = subprocess.run(["git", "-C", str(root), "worktree", "add", "--detach", "-f", tree, ref],
                             capture_output=True, text=True)
        if add.returncode:
            raise RuntimeError(f"cannot check out {ref!r} for the baseline: {add.stderr.strip()}")
        try:
            yield tree
        finally:
            subprocess.run(["git", "-C", str(root), "worktree", "remove", "--force", tree], capture_output=True)


def run_at_commit(ref: str, code: str, timeout: float = 3600.0) -> str:
    """Run the Python snippet ``code`` in a new interpreter with the project as it was at git
    commit ``ref`` (:func:`worktree_at`) first on the import path; returns its standard
    output. Raises RuntimeError with the end of its standard error if it fails (or if ``ref``
    is not a commit of this checkout)."""
    import os
    import subprocess
    import sys

    with worktree_at(ref) as tree:
        p = subprocess.run([sys.executable, "-c", code], cwd=tree, env=dict(os.environ, PYTHONPATH=tree),
                           capture_output=True, text=True, timeout=timeout)
    if p.returncode:
        raise RuntimeError(f"the baseline at {ref} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return p.stdout


def atomic_write_text(path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically (:func:`fitting.shared.files.write_atomic`),
    creating its folder."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return files.write_atomic(path, text)


def save_figure(fig, path, dpi: int = 150, close: bool = True) -> Path:
    """Save a matplotlib figure atomically (format from the suffix of ``path``); close it. A
    figure with a layout engine (``layout="constrained"``) is saved as laid out; one without
    is cropped to its artists (``bbox_inches="tight"``, which lays the figure out twice: a
    third of the main job's drawing time).

    The figure as saved is checked by :mod:`experiments.figures.layout` (no clipped text,
    no overlapping labels, a legend only for what is drawn, whole-number ticks for whole
    numbers, legible text): on a breach the file is written all the same (to look at) and
    :class:`~experiments.figures.layout.LayoutError` names it with every problem."""
    from experiments.figures import layout
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        tight = "tight" if fig.get_layout_engine() is None else None
        data, found = layout.render(fig, path.suffix.lstrip(".") or "png", dpi=dpi, bbox_inches=tight)
        files.write_atomic(path, data)
    finally:
        if close:
            import matplotlib.pyplot as plt
            plt.close(fig)
    if found:
        raise layout.LayoutError(path, found)
    return path


def _cell(x):
    """CSV cell: floats as their shortest exact repr (round-trips), everything else as is."""
    if isinstance(x, float):
        return repr(float(x))  # np.float64 is a float whose repr is "np.float64(...)"
    if hasattr(x, "item") and getattr(x, "ndim", None) == 0:  # numpy / jax scalar
        return _cell(x.item())
    return x


def write_csv(path, header, rows, comments=()) -> Path:
    """Write a CSV atomically: optional ``# comment`` lines, one header row, then ``rows``.

    ``rows`` is an iterable of sequences; floats are written exactly (shortest repr).
    Comment lines (units, parameters, provenance) start with '#' so that
    ``numpy.genfromtxt(..., comments='#')`` and ``pandas.read_csv(comment='#')`` skip them.
    """
    buf = io.StringIO()
    for c in comments:
        buf.write(f"# {c}\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(header))
    for r in rows:
        w.writerow([_cell(x) for x in r])
    return atomic_write_text(path, buf.getvalue())


def _block(x):
    import jax
    return jax.block_until_ready(x)


def time_fn(fn, *args, repeats: int = 50, number: int = 1):
    """Time ``fn(*args)``: returns ``(first_call_s, median_s)``.

    ``first_call_s`` is the wall time of the first call (for a jitted function: tracing +
    XLA compilation + one run); it is a compile-time measurement only if ``fn`` has not
    been called with these shapes before. ``median_s`` is the median over ``repeats``
    samples of warm calls, each sample timing ``number`` back-to-back calls (divided by
    ``number``) and ending in ``block_until_ready``. At microsecond scale the median
    includes Python dispatch overhead (a few microseconds), as a user calling it would see.
    """
    if repeats < 1 or number < 1:
        raise ValueError(f"repeats and number must be >= 1, got {repeats}, {number}")
    t0 = time.perf_counter()
    _block(fn(*args))
    first = time.perf_counter() - t0
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(number):
            out = fn(*args)
        _block(out)
        samples.append((time.perf_counter() - t0) / number)
    return first, statistics.median(samples)


def _fmt(x):
    if isinstance(x, float):
        if math.isnan(x):
            return "-"
        return f"{x:.4g}"
    return str(x)


def format_table(header, rows) -> str:
    """Fixed-width text table (floats as 4 significant digits, NaN as '-')."""
    cells = [[str(h) for h in header]] + [[_fmt(x) for x in r] for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(header))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def print_table(header, rows, title=None) -> str:
    """Print :func:`format_table` (with an optional title line) and return the text."""
    text = format_table(header, rows)
    if title:
        text = f"{title}\n{text}"
    print(text)
    return text
