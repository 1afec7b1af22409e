"""Preloaded by the fork server of :mod:`fitting.calibration.figures`: what a drawing worker needs,
imported once, JAX in float64 and no JAX backend started (so the server may fork)."""
import atexit
import os
import sys

import jax

jax.config.update("jax_enable_x64", True)

from fitting.calibration import master  # noqa: E402,F401  (matplotlib; the shift laws and tables the workers unpickle)
from fitting.calibration import plots

# The server ends when its caller does. It has nothing to clean up, and tearing down JAX and
# matplotlib takes it 0.3 s, during which it still holds the caller's stdout and stderr: a
# shell pipe or subprocess.run would wait for that. The last-registered handler runs first.
# (The workers forked from the server leave through os._exit and never run it.)
atexit.register(lambda: (sys.stderr.flush(), os._exit(0)))
