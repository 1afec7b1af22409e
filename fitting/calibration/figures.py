"""The figures of a calibration, drawn in this process or in parallel worker processes.

:func:`save_all` writes the six PNGs of a frequency-domain calibration (three for relaxation
data) with the functions of :mod:`fitting.calibration.plots`. Importing this module imports neither
matplotlib nor JAX.

Drawing is matplotlib's Python: about 0.2 s per figure, plus 0.6 s to import matplotlib, on
a two-core machine; together most of a ``vjax-fit`` call once its compiled functions are
cached. :func:`start_workers`, called first thing by the command line, starts a fork server
that imports matplotlib (and JAX, vjax, :mod:`fitting.calibration.plots`) on another core while the calling
process imports JAX and fits; :func:`save_all` then forks one worker per core from it and the
figures are drawn side by side. Without workers (not started, one core, or a platform without
``fork``) the figures are drawn in this process, with the same files as result.
"""
from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

__all__ = ["save_all", "start_workers"]

_context = None     # the fork-server context once start_workers has run


def _cores() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def start_workers() -> bool:
    """Start the fork server that the drawing workers are forked from; returns whether
    :func:`save_all` will draw in parallel. Call it before the long work that the server's
    imports should overlap (the command line calls it before importing JAX). As with any
    start method but ``fork``, each worker imports the caller's main module: a script that
    calls this must guard its work with ``if __name__ == "__main__":``."""
    global _context
    if _context is None and _cores() > 1 and "forkserver" in multiprocessing.get_all_start_methods():
        from multiprocessing import forkserver
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(["fitting.calibration.figure_server"])
        try:
            forkserver.ensure_running()
        except OSError:     # no server (e.g. no free file descriptors): draw in this process
            return False
        _context = context
    return _context is not None


def _draw(name, args):
    from fitting.calibration import plots
    return getattr(plots, name)(*args)


def _on_host(args):
    """``args`` with JAX arrays as numpy arrays: a worker unpickles them without starting JAX."""
    import jax
    import numpy as np
    return jax.tree.map(lambda a: np.asarray(a) if isinstance(a, jax.Array) else a, args)


def save_all(out_dir, stem, table, material, shift, data_shift, laws=None) -> list:
    """Write the plots as ``<stem>_master.png``, ``_shift.png``, ``_residuals.png``,
    ``_spectrum.png``, ``_tsweep.png`` (E', E'', tan delta versus T at 1 and 10 Hz) and
    ``_vgp.png`` (van Gurp-Palmen) in ``out_dir``; returns their paths in this order.
    Relaxation data get ``_master.png`` (:func:`fitting.calibration.plots.relaxation_curve`),
    ``_shift.png`` and ``_spectrum.png``. ``laws``: the closed-form laws for the shift plot
    (see :func:`fitting.calibration.plots.shift_factors`). Errors of a plot (bad input) are raised here,
    also from a worker."""
    path = lambda name: os.path.join(out_dir, f"{stem}_{name}.png")
    if getattr(table, "domain", "frequency") == "time":
        calls = [("relaxation_curve", (table, material, shift, path("master"))),
                 ("shift_factors", (data_shift, shift, path("shift"), laws)),
                 ("spectrum", (material, path("spectrum")))]
    else:
        calls = [("master_curve", (table, material, shift, path("master"))),
                 ("shift_factors", (data_shift, shift, path("shift"), laws)),
                 ("residuals", (table, material, shift, path("residuals"))),
                 ("spectrum", (material, path("spectrum"))),
                 ("temperature_sweep", (table, material, shift, (1.0, 10.0), path("tsweep"))),
                 ("van_gurp_palmen", (table, material, shift, path("vgp")))]
    if _context is not None:
        try:
            with ProcessPoolExecutor(min(_cores(), len(calls)), mp_context=_context) as pool:
                # the widest figures (three and two panels) first, so that the cores finish together
                order = sorted(range(len(calls)), key=lambda i: calls[i][0] not in ("temperature_sweep", "master_curve"))
                futures = {i: pool.submit(_draw, calls[i][0], _on_host(calls[i][1])) for i in order}
                return [futures[i].result() for i in range(len(calls))]
        except BrokenProcessPool:   # a worker died (killed, out of memory): draw here instead
            pass
    return [_draw(name, args) for name, args in calls]
