"""Linear viscoelastic material laws: generalized Maxwell (Prony) series.

Convention (thesis Section 1.2): harmonic fields go as ``exp(i omega t)``, so the complex
modulus of a generalized Maxwell solid (Eq. 1.43-1.44) is

    E*(omega) = E0 + sum_k E_k * i omega tau_k / (1 + i omega tau_k)

with ``E0`` the rubbery (relaxed, omega -> 0) modulus, ``E_k`` the arm moduli and ``tau_k``
the **relaxation** times. The glassy modulus is ``Einf = E0 + sum_k E_k``. The standard
linear solid (Eq. 1.35, 1.42) is the one-arm case; an elastic material has no arms and
skips every memory term downstream.

The compliance 1/E* has the retardation (creep) form of Eq. 2.3-2.4,

    J*(omega) = J0 + sum_k C_k / (1 + i omega lambda_k),    J0 = 1/Einf,

whose retardation times ``lambda_k`` are the zeros ``s_k = -1/lambda_k`` of the Laplace
modulus E(s) = E0 + sum E_k s tau_k/(1 + s tau_k). They interlace the poles ``-1/tau_k``
(docs/theory.md §1), so :meth:`Material.creep_spectrum` brackets each one between
consecutive poles and bisects in log|s|; polynomial root finding fails for spectra that
span many decades.

Time-temperature superposition (Section 1.2): E*(omega, T) = E*(a_T(T) omega, T_ref). With
a Prony series this is a rescaling of the relaxation times, tau_k -> a_T tau_k. A material
carries its shift law (:meth:`Material.with_shift`) and the temperature its times hold at:
:meth:`Material.at_temperature` returns the same material at another temperature, and a scene's
``temperature=`` moves every body whose material has a law and no temperature of its own.
"""
from __future__ import annotations

import dataclasses
import math
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks, solve as _solve

GAS_CONSTANT = 8.314462618  # J/(mol K)
KELVIN = 273.15


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class CreepSpectrum:
    """Retardation form of the compliance, Eq. 2.3-2.4: J(t) = J0 + sum C_k (1 - exp(-t/lambda_k)).

    Attributes: ``J0`` = 1/Einf (1/Pa), ``C`` (1/Pa, all > 0), ``retardation_times`` (s).
    """

    J0: jax.Array
    C: jax.Array
    retardation_times: jax.Array

    def compliance(self, omega):
        """J*(omega) = J0 + sum_k C_k / (1 + i omega lambda_k) (1/Pa), omega in rad/s."""
        w = jnp.asarray(omega)[..., None]
        return self.J0 + jnp.sum(self.C / (1.0 + 1j * w * self.retardation_times), axis=-1)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Material:
    """A generalized Maxwell solid in plane strain. A PyTree: jit, vmap and grad see the arrays.

    Attributes:
      E0: rubbery (relaxed) Young's modulus (Pa).
      moduli: Maxwell arm moduli E_k (Pa), shape (K,); K = 0 for an elastic material.
      times: relaxation times tau_k (s), shape (K,), at ``temperature``.
      nu: Poisson's ratio (plane strain Kolosov constant kappa = 3 - 4 nu).
      shift: its time-temperature shift law (:class:`WLF`, :class:`Arrhenius`, or any object
        with ``log10_aT(T)``), or None (the material does not change with temperature).
      temperature: the temperature (C) at which ``times`` hold; None: the shift law's reference
        temperature (or no law). A scene's ``temperature=`` moves only materials whose
        temperature is None: a material put at its own temperature keeps it.

    Build it with :meth:`elastic`, :meth:`sls` or :meth:`prony` (they check the values), give
    it a shift law with :meth:`with_shift` and a temperature with :meth:`at_temperature`.

    >>> m = Material.sls(E0=1e6, Einf=1e7, tau=0.01, nu=0.5)
    >>> float(m.Einf)
    10000000.0
    >>> round(float(m.modulus(0.0).real))
    1000000
    >>> hot = m.with_shift(WLF(8.86, 101.6, 20.0)).at_temperature(40.0)
    >>> float(hot.temperature), round(float(hot.times[0]), 7)
    (40.0, 0.0003489)
    """

    E0: jax.Array
    moduli: jax.Array
    times: jax.Array
    nu: jax.Array
    shift: "WLF | Arrhenius | None" = None
    temperature: jax.Array | None = None

    # ---- constructors -------------------------------------------------------------
    @classmethod
    def elastic(cls, E, nu) -> "Material":
        """Elastic solid, Young's modulus ``E`` (Pa)."""
        checks.positive("E", E)
        checks.poisson("nu", nu)
        checks.scalar("E", E)
        checks.scalar("nu", nu)
        empty = jnp.zeros((0,), dtype=jnp.result_type(E, float))
        return cls(jnp.asarray(E, dtype=empty.dtype), empty, empty, jnp.asarray(nu, dtype=empty.dtype))

    @classmethod
    def sls(cls, E0, Einf, tau, nu) -> "Material":
        """Standard linear solid (Eq. 1.35, 1.42): rubbery ``E0``, glassy ``Einf`` > E0 (Pa),
        **relaxation** time ``tau`` (s). Its retardation time is (Einf/E0) tau (Eq. 1.41)."""
        checks.positive("E0", E0)
        checks.positive("tau", tau)
        for name, val in (("E0", E0), ("Einf", Einf), ("tau", tau)):
            checks.scalar(name, val)
        e0, einf = checks.values("E0", E0), checks.values("Einf", Einf)
        if e0 is not None and einf is not None and not np.all(einf > e0):
            raise ValueError(f"Einf must be > E0 for a standard linear solid, got Einf={Einf!r}, E0={E0!r}")
        return cls.prony(E0, jnp.atleast_1d(jnp.asarray(Einf) - jnp.asarray(E0)), jnp.atleast_1d(tau), nu)

    @classmethod
    def prony(cls, E0, moduli, times, nu) -> "Material":
        """Generalized Maxwell solid (Eq. 1.43-1.44): E(t) = E0 + sum_k E_k exp(-t/tau_k).

        ``moduli`` (Pa) and ``times`` (s) are 1-D of equal length, all > 0, times distinct.
        """
        checks.positive("E0", E0)
        checks.positive("moduli", moduli)
        checks.positive("times", times)
        checks.poisson("nu", nu)
        checks.scalar("E0", E0)
        checks.scalar("nu", nu)
        moduli, times = jnp.atleast_1d(jnp.asarray(moduli)), jnp.atleast_1d(jnp.asarray(times))
        if moduli.ndim != 1 or moduli.shape != times.shape:
            raise ValueError(
                f"moduli and times must be 1-D of equal length, got shapes {moduli.shape} and {times.shape}")
        t = checks.values("times", times)
        if t is not None and len(np.unique(t)) != len(t):
            raise ValueError("times must be distinct (merge Prony terms with equal relaxation times)")
        dtype = jnp.result_type(E0, moduli, times, float)
        return cls(jnp.asarray(E0, dtype), moduli.astype(dtype), times.astype(dtype), jnp.asarray(nu, dtype))

    # ---- properties ---------------------------------------------------------------
    @property
    def is_elastic(self) -> bool:
        """Static: True when there are no Maxwell arms (no memory terms anywhere)."""
        return self.times.shape[-1] == 0

    @property
    def Einf(self):
        """Glassy (instantaneous) modulus E0 + sum E_k (Pa)."""
        return self.E0 + jnp.sum(self.moduli, axis=-1)

    @property
    def kappa(self):
        """Kolosov constant, plane strain: 3 - 4 nu."""
        return 3.0 - 4.0 * self.nu

    # ---- frequency domain ---------------------------------------------------------
    def modulus(self, omega):
        """Complex modulus E*(omega) (Pa); ``omega`` in rad/s, any shape. E*(-w) = conj E*(w)."""
        w = jnp.asarray(omega)[..., None]
        iwt = 1j * w * self.times
        return self.E0 + jnp.sum(self.moduli * iwt / (1.0 + iwt), axis=-1)

    def compliance(self, omega):
        """Complex compliance J*(omega) = 1/E*(omega) (1/Pa)."""
        return 1.0 / self.modulus(omega)

    def storage(self, omega):
        """Storage modulus E'(omega) (Pa)."""
        return self.modulus(omega).real

    def loss(self, omega):
        """Loss modulus E''(omega) (Pa); positive for omega > 0."""
        return self.modulus(omega).imag

    def tan_delta(self, omega):
        """Loss factor E''/E'."""
        e = self.modulus(omega)
        return e.imag / e.real

    def relaxation(self, t):
        """Relaxation modulus E(t) = E0 + sum E_k exp(-t/tau_k) (Pa), t in s."""
        t = jnp.asarray(t)[..., None]
        return self.E0 + jnp.sum(self.moduli * jnp.exp(-t / self.times), axis=-1)

    # ---- creep form ---------------------------------------------------------------
    def creep_spectrum(self, iterations: int = 120) -> CreepSpectrum:
        """Retardation spectrum (J0, C_k, lambda_k) of Eq. 2.3-2.4, differentiable.

        Each zero s_k = -1/lambda_k of E(s) lies between consecutive poles -1/tau_k (and the
        last between -1/tau_max and 0), where E(s) increases monotonically from -inf to
        +inf. Bisection in x = log(-s) finds it for spectra spanning any number of decades;
        one final Newton step carries the implicit-function derivative ds/dp = -E_p/E_s
        (the bisection itself has zero derivative). C_k = lambda_k / E'(s_k) > 0.
        Compiled once per number of terms (also when called outside jit).
        """
        return _creep_spectrum(self, iterations)

    # ---- temperature --------------------------------------------------------------
    def with_shift(self, shift) -> "Material":
        """The same material with the time-temperature shift law ``shift`` (:class:`WLF`,
        :class:`Arrhenius`, or any object with ``log10_aT(T)``), referred to the temperature at
        which its ``times`` hold: the law's T_ref. Its own temperature is cleared (None)."""
        _check_shift_law(shift)
        return dataclasses.replace(self, shift=shift, temperature=None)

    def at_temperature(self, T, *deprecated) -> "Material":
        """The material at temperature ``T`` (C) under its own shift law:
        E*(omega, T) = E*(a_T(T) omega, T_ref), i.e. tau_k -> a_T(T) tau_k (a_T relative to the
        temperature its times hold at now). The result keeps its law and carries ``T`` as its
        own temperature, so a scene's ``temperature=`` leaves it there.

        The 0.2 form ``at_temperature(shift, T)`` still works for one version
        (a DeprecationWarning): it is ``with_shift(shift).at_temperature(T)``.
        """
        if deprecated or (callable(getattr(T, "log10_aT", None))):
            if len(deprecated) != 1:
                raise TypeError("at_temperature takes the temperature T (C); the 0.2 form is at_temperature(shift, T)")
            checks.deprecated("Material.at_temperature(shift, T) is deprecated since vjax 0.3: give the material its "
                              "law once, material.with_shift(shift).at_temperature(T)")
            return self.with_shift(T).at_temperature(deprecated[0])
        if self.shift is None:
            raise ValueError("at_temperature: this material has no shift law; give it one first, "
                             "material.with_shift(WLF(C1, C2, T_ref)) (or Arrhenius(Ea, T_ref))")
        checks.finite("T", T)
        log_aT = self.shift.log10_aT(T)
        if self.temperature is not None:
            log_aT = log_aT - self.shift.log10_aT(self.temperature)
        T = jnp.asarray(T, dtype=jnp.result_type(self.times))
        return dataclasses.replace(self, times=self.times * 10.0 ** log_aT, temperature=T)


def _check_shift_law(shift):
    if not callable(getattr(shift, "log10_aT", None)):
        raise ValueError(f"shift must be a shift law with log10_aT (WLF, Arrhenius, a fitted table), "
                         f"got {type(shift).__name__}")


@partial(jax.jit, static_argnums=1)
def _creep_spectrum(mat: Material, iterations: int) -> CreepSpectrum:
    """See :meth:`Material.creep_spectrum`."""
    order = jnp.argsort(jax.lax.stop_gradient(mat.times))
    mat = dataclasses.replace(mat, moduli=mat.moduli[order], times=mat.times[order])

    def modulus(x, m):
        # E(s) at s = -exp(x) on the negative axis, one s per interval (broadcast against tau).
        st = -jnp.exp(x)[:, None] * m.times
        return m.E0 + jnp.sum(m.moduli * st / (1.0 + st), axis=-1)

    # Interval k lies between -1/tau_k and -1/tau_{k+1} (or 0 for the last one): in
    # x = log(-s), between log(1/tau_{k+1}) (E -> +inf side, or -inf log for s -> 0)
    # and log(1/tau_k), a pole (E -> -inf side). E decreases with x: E > 0 at the low end.
    def bracketed_roots(m):
        x_hi = -jnp.log(m.times)
        x_lo = jnp.concatenate([x_hi[1:], x_hi[-1:] - 60.0])
        return _solve.bisect(lambda x: modulus(x, m), x_lo, x_hi, iterations, sign_lo=1.0), None

    x, _ = _solve.implicit_root(bracketed_roots, lambda x, _, m: modulus(x, m))(mat)
    s = -jnp.exp(x)
    lam = -1.0 / s
    slope = jnp.sum(mat.moduli * mat.times / (1.0 + s[:, None] * mat.times) ** 2, axis=-1)
    return CreepSpectrum(1.0 / mat.Einf, lam / slope, lam)


# ---- time-temperature shift laws ----------------------------------------------------
def _checked_pytree(cls):
    """Register a frozen dataclass whose ``__init__`` checks user input as a PyTree that JAX
    rebuilds **without** calling ``__init__``: JAX fills it with tracers, placeholders and
    cotangents (a gradient with respect to C2 may well be negative), none of them user input."""
    names = tuple(f.name for f in dataclasses.fields(cls))

    def unflatten(_, leaves):
        obj = object.__new__(cls)
        for name, leaf in zip(names, leaves):
            object.__setattr__(obj, name, leaf)
        return obj

    jax.tree_util.register_pytree_with_keys(
        cls, lambda obj: ([(jax.tree_util.GetAttrKey(k), getattr(obj, k)) for k in names], None), unflatten)
    return cls


@_checked_pytree
@dataclasses.dataclass(frozen=True)
class WLF:
    """Williams-Landel-Ferry shift: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref); T in C.

    Valid only above the asymptote T_ref - C2; ``log10_aT`` refuses temperatures at or below
    it when they are concrete.
    """

    C1: jax.Array
    C2: jax.Array
    T_ref: jax.Array

    def __init__(self, C1, C2, T_ref):
        checks.positive("C1", C1)
        checks.positive("C2", C2)
        checks.finite("T_ref", T_ref)
        object.__setattr__(self, "C1", C1)
        object.__setattr__(self, "C2", C2)
        object.__setattr__(self, "T_ref", T_ref)

    def log10_aT(self, T):
        dT = jnp.asarray(T) - self.T_ref
        t, c2 = checks.values("T", T), checks.values("C2", self.C2)
        if t is not None and c2 is not None and checks.is_concrete(self.T_ref):
            if np.any(t - np.asarray(self.T_ref) <= -c2):
                raise ValueError(
                    f"T={T!r} C is at or below the WLF asymptote T_ref - C2 = {float(np.asarray(self.T_ref) - c2):.4g} C")
        return -self.C1 * dT / (self.C2 + dT)


@_checked_pytree
@dataclasses.dataclass(frozen=True)
class Arrhenius:
    """Arrhenius shift: log10 a_T = Ea / (R ln 10) (1/T - 1/T_ref), Ea in J/mol, T in C."""

    Ea: jax.Array
    T_ref: jax.Array

    def __init__(self, Ea, T_ref):
        checks.positive("Ea", Ea)
        checks.finite("T_ref", T_ref)
        t = checks.values("T_ref", T_ref)
        if t is not None and np.any(t <= -KELVIN):
            raise ValueError(f"T_ref must be above absolute zero, got {T_ref!r} C")
        object.__setattr__(self, "Ea", Ea)
        object.__setattr__(self, "T_ref", T_ref)

    def log10_aT(self, T):
        t = checks.values("T", T)
        if t is not None and np.any(t <= -KELVIN):
            raise ValueError(f"T must be above absolute zero (-273.15 C), got {T!r}")
        inv = 1.0 / (jnp.asarray(T) + KELVIN) - 1.0 / (self.T_ref + KELVIN)
        return self.Ea / (GAS_CONSTANT * math.log(10.0)) * inv
