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


def responds(body) -> bool:
    """Whether a scene's ``temperature=`` moves this body (a Body or a bare Material): its material
    has a shift law and no temperature of its own (None, a rigid body, does not)."""
    material = getattr(body, "material", body)
    return body is not None and getattr(material, "shift", None) is not None and material.temperature is None


def at_temperature(temperature, shift, *bodies, oil: bool = False):
    """The bodies (None = rigid) at the scene's ``temperature`` (C): each body whose material
    has a shift law and no temperature of its own (:func:`responds`); the others keep theirs.

    ``shift``: the 0.2 argument (a DeprecationWarning), the law of every material that has none.
    ``oil``: the scene's lubricant takes ``temperature`` too, so no body needs to respond.
    """
    if shift is not None:
        checks.deprecated("shift= is deprecated since vjax 0.3: give each material its law, "
                          "material.with_shift(shift), and the scene temperature= alone")
        if temperature is None:
            raise ValueError("shift= needs temperature= (C): the temperature the materials are evaluated at")
        bodies = tuple(b if b is None or b.material.shift is not None
                       else dataclasses.replace(b, material=b.material.with_shift(shift)) for b in bodies)
    if temperature is None:
        return bodies
    checks.finite("temperature", temperature)
    checks.scalar("temperature", temperature)
    if not oil and not any(responds(b) for b in bodies):
        raise ValueError("temperature= moves no body: no material has a shift law of its own (give it one, "
                         "material.with_shift(WLF(C1, C2, T_ref)), or put it at its temperature, "
                         "material.at_temperature(T))")
    return tuple(b.at_temperature(temperature) if responds(b) else b for b in bodies)


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
