"""Argument checks shared by the public constructors of vjax and fitting (a message naming the
argument and the problem).

Checks run only on concrete values: inside ``jit``/``vmap``/``grad`` the arguments are
tracers and are passed through unchecked (the solvers report non-convergence instead).
"""
from __future__ import annotations

import os
import sys
import warnings

import numpy as np
import jax


def is_concrete(x) -> bool:
    """True when ``x`` (and every leaf in it) has a value we can inspect now."""
    return not any(isinstance(leaf, jax.core.Tracer) for leaf in jax.tree_util.tree_leaves(x))


def values(name: str, x):
    """``x`` as a numpy array, or ``None`` when it is traced. Refuses NaN and inf."""
    if isinstance(x, str):
        raise ValueError(f"{name} must be a number, got the string {x!r}")
    # Tracers, abstract values and PyTree placeholders (None, object()) seen while JAX
    # rebuilds a PyTree are not inspectable: they pass unchecked.
    if not isinstance(x, (int, float, complex, np.ndarray, np.generic, list, tuple, jax.Array)):
        return None
    if not is_concrete(x):
        return None
    a = np.asarray(x)
    if a.dtype == object or not np.issubdtype(a.dtype, np.number):
        raise ValueError(f"{name} must be numeric, got {x!r}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {x!r}")
    return a


def positive(name: str, x) -> None:
    a = values(name, x)
    if a is not None and not np.all(a > 0):
        raise ValueError(f"{name} must be > 0, got {x!r}")


def nonnegative(name: str, x) -> None:
    a = values(name, x)
    if a is not None and not np.all(a >= 0):
        raise ValueError(f"{name} must be >= 0, got {x!r}")


def poisson(name: str, nu) -> None:
    a = values(name, nu)
    if a is not None and not np.all((a > -1.0) & (a <= 0.5)):
        raise ValueError(f"{name} (Poisson's ratio) must lie in (-1, 0.5], got {nu!r}")


def finite(name: str, x) -> None:
    values(name, x)


def load(x) -> None:
    """A bearing's ``load``: a positive magnitude or a non-zero vector (Fx, Fy)."""
    shape = np.shape(x)
    if shape == ():
        positive("load", x)
    elif shape == (2,):
        a = values("load", x)
        if a is not None and not np.hypot(*a) > 0:
            raise ValueError(f"load must be a non-zero vector, got {x!r}")
    else:
        raise ValueError(f"load must be a magnitude or a vector (Fx, Fy), got shape {shape}")


def one_of(name: str, x, options) -> None:
    if x not in options:
        raise ValueError(f"{name} must be one of {sorted(map(str, options))}, got {x!r}")


def scalar(name: str, x) -> None:
    """A concrete ``x`` must be a single number (0-d); traced values pass (vmap batches them)."""
    a = values(name, x)
    if a is not None and a.ndim != 0:
        raise ValueError(f"{name} must be a scalar, got an array of shape {a.shape}")


def instance(name: str, x, cls, what: str) -> None:
    """``x`` must be an instance of ``cls`` (``what`` describes it in the message)."""
    if not isinstance(x, cls):
        raise ValueError(f"{name} must be {what}, got {type(x).__name__}")


def option_number(name: str, x) -> None:
    """A static option that must be a finite float > 0 (a Python number, not an array)."""
    if isinstance(x, bool) or not (isinstance(x, (int, float, np.floating)) and np.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {x!r}")


def option_count(name: str, x, minimum: int = 1) -> None:
    """A static option that must be an integer >= ``minimum``."""
    if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or x < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {x!r}")



def deprecated(message: str) -> None:
    """A DeprecationWarning pointing at the first caller outside vjax (however deep the call)."""
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep
    frame, level = sys._getframe(1), 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(package):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, DeprecationWarning, stacklevel=level)
