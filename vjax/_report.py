"""Turning a solver's ``converged`` flag into a clear error, outside and inside jit."""
from __future__ import annotations

import jax
import numpy as np

from ._checks import is_concrete


class ConvergenceError(RuntimeError):
    """A solver did not reach its tolerance within its iteration limit."""


def _raise(what, converged, iterations, residual):
    converged = np.asarray(converged)
    if not np.all(converged):
        bad = np.flatnonzero(~converged.ravel())
        raise ConvergenceError(
            f"{what} did not converge at {bad.size} of {converged.size} point(s) (first: flat index "
            f"{bad[0]}): {np.ravel(iterations)[bad[0]]} iterations, residual "
            f"{np.ravel(residual)[bad[0]]:.3e}. Pass throw=False to inspect the result, or relax the solver options.")


def check_converged(what: str, converged, iterations, residual, throw: bool) -> None:
    """Raise :class:`ConvergenceError` if any point failed; under jit via a host callback."""
    if not throw:
        return
    if is_concrete((converged, iterations, residual)):
        _raise(what, converged, iterations, residual)
    else:
        jax.debug.callback(lambda c, i, r: _raise(what, c, i, r), converged, iterations, residual)
