"""The fit's log-parametrization of a Prony material, its WLF shift and scene parameters
(:class:`Params`)."""
from __future__ import annotations

import dataclasses
import math

import jax.numpy as jnp
import numpy as np

from vjax import Material, WLF


# the scene parameters a model may take as keywords, fitted on their logarithms: mixed
# lubrication's boundary friction coefficient and composite rms roughness (m); the rig's heat
# transfer coefficient times area (W/K for the journal, W/(m K) for the pin and roller)
EXTRAS = ("mu_b", "sigma", "hA")


@dataclasses.dataclass(frozen=True)
class Params:
    """Log-parametrization of a Prony material + WLF shift, and of scene parameters.

    x = [log E0, log E_1..E_K, (log tau_1..tau_K if fit_times), log C1, log C2, log extras...];
    T_ref and nu are fixed; ``extras`` names scene parameters of :data:`EXTRAS` fitted with the
    material ("mu_b", "sigma" of a rough journal model; "hA" of a thermal model), passed to the
    model as keywords. :meth:`unpack` builds the material and shift from x inside jit (no
    checks), :meth:`unpack_extras` the keywords.
    """

    K: int
    fit_times: bool
    times: np.ndarray
    nu: float
    T_ref: float
    extras: tuple = ()

    @classmethod
    def of(cls, material: Material, shift: WLF, fit_times: bool = False, extras=()):
        if not isinstance(shift, WLF):
            raise ValueError(f"torque fitting refines a WLF shift law, got {type(shift).__name__}")
        extras = tuple(extras)
        for e in extras:
            if e not in EXTRAS:
                raise ValueError(f"extras: {e!r} is not a fittable scene parameter; choose from {EXTRAS}")
        if len(set(extras)) != len(extras):
            raise ValueError(f"extras: a name repeated in {extras}")
        return cls(int(material.moduli.shape[0]), bool(fit_times), np.asarray(material.times, float),
                   float(material.nu), float(shift.T_ref), extras)

    @property
    def n_material(self):
        """Number of material and shift log-parameters (the extras follow them in x)."""
        return 1 + self.K * (2 if self.fit_times else 1) + 2

    def names(self):
        K = self.K
        n = ["E0"] + [f"E_{k + 1}" for k in range(K)]
        if self.fit_times:
            n += [f"tau_{k + 1}" for k in range(K)]
        return n + ["C1", "C2"] + list(self.extras)

    def pack(self, material: Material, shift: WLF, extras=None) -> np.ndarray:
        """x from the material, shift and a dict of the extras' values (> 0)."""
        parts = [[float(material.E0)], np.asarray(material.moduli, float)]
        if self.fit_times:
            parts.append(np.asarray(material.times, float))
        parts.append([float(shift.C1), float(shift.C2)])
        extras = extras or {}
        missing = [e for e in self.extras if e not in extras]
        if missing:
            raise ValueError(f"extras: no start value for {missing}")
        for e in self.extras:
            if not (float(extras[e]) > 0 and math.isfinite(float(extras[e]))):
                raise ValueError(f"extras: {e} must be a finite number > 0 to be fitted on its logarithm, "
                                 f"got {extras[e]!r}")
        parts.append([float(extras[e]) for e in self.extras])
        return np.log(np.concatenate([np.ravel(p) for p in parts]))

    def unpack(self, x):
        K, n = self.K, self.n_material
        v = jnp.exp(x)
        tau = v[1 + K:1 + 2 * K] if self.fit_times else jnp.asarray(self.times)
        mat = Material(v[0], v[1:1 + K], tau, jnp.asarray(self.nu, v.dtype))
        return mat, WLF(v[n - 2], v[n - 1], jnp.asarray(self.T_ref, v.dtype))

    def unpack_extras(self, x):
        """The extras' values (dict name -> value) from x (traceable)."""
        v = jnp.exp(x[self.n_material:])
        return {e: v[i] for i, e in enumerate(self.extras)}

    def physical(self, x):
        """(Material, WLF) with concrete, checked values."""
        v = np.exp(np.asarray(x, float))
        K, n = self.K, self.n_material
        tau = v[1 + K:1 + 2 * K] if self.fit_times else self.times
        return (Material.prony(v[0], v[1:1 + K], tau, self.nu),
                WLF(float(v[n - 2]), float(v[n - 1]), self.T_ref))

    def physical_extras(self, x):
        """The extras' values (dict name -> float)."""
        return {e: float(v) for e, v in zip(self.extras, np.exp(np.asarray(x, float)[self.n_material:]))}
