"""What every scene shares (internal): the result record's behaviour and the common arguments.

Every scene result has ``pressure``, ``displacement``, ``force``, ``torque``, ``iterations``,
``residual``, ``result`` and the property ``converged`` (see the README's scene table), a
short ``repr`` and :meth:`SceneResult.summary`.
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

from . import checks, solve as _solve


class SceneResult:
    """Mixin for the frozen result dataclasses of the scenes (declared with ``repr=False``)."""

    @property
    def converged(self):
        """``result == 0``: the scene's solve met its tolerance."""
        return self.result == _solve.SUCCESS

    def _describe(self, sep):
        parts = []
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            shape = np.shape(v)
            if not checks.is_concrete(v):
                parts.append(f"{f.name}=<traced {shape}>")
            elif shape == () and f.name != "result":
                parts.append(f"{f.name}={np.asarray(v).item():.6g}")
            elif f.name != "result":
                parts.append(f"{f.name}=<array {shape}>")
        if checks.is_concrete(self.result) and np.shape(self.result) == ():
            parts.append(f"status: {_solve.MESSAGES[int(self.result)]}")
        return sep.join(parts)

    def summary(self) -> str:
        """Scalars and convergence, one per line; arrays as their shapes."""
        return f"{type(self).__name__}\n  " + self._describe("\n  ")

    def __repr__(self):
        return f"{type(self).__name__}({self._describe(', ')})"


def at_temperature(temperature, shift, *bodies):
    """The bodies (None = rigid) at ``temperature`` (C) under ``shift``; both or neither."""
    if (temperature is None) != (shift is None):
        raise ValueError("temperature and shift must be given together (shift: a WLF/Arrhenius law)")
    if temperature is None:
        return bodies
    checks.finite("temperature", temperature)
    checks.scalar("temperature", temperature)
    return tuple(None if b is None else b.at_temperature(shift, temperature) for b in bodies)


def canonical(*values):
    """Concrete numbers (Python, numpy, JAX) as arrays of the default float dtype, traced values
    and None as they are: jit's cache tells 0.05 (a weakly typed Python number) from
    np.float64(0.05) and float32 from float64, and would compile a scene's program once for each."""
    f = jnp.result_type(float)
    return tuple(v if v is None or isinstance(v, jax.core.Tracer) else jnp.asarray(v, f) for v in values)


def scalars(checker, **values):
    """Check each named value with ``checker`` (e.g. ``checks.positive``) and that it is a scalar."""
    for name, v in values.items():
        checker(name, v)
        checks.scalar(name, v)
