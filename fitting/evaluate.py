"""Fitted materials and shift laws evaluated on the host, in numpy.

A calibration evaluates its results many times outside any derivative: the errors on the raw
points, the loss modulus's extrema, the distances between shift laws, every curve of the
plots. Through JAX, each of these is a function traced and lowered once per process (the
persistent compilation cache of the command-line tools skips only XLA's compilation): about
0.4 s of a cached ``vjax-fit`` call. The same formulas in numpy take microseconds.

The formulas are those of :class:`vjax.material.Material` (Prony series), :class:`~vjax.material.WLF`,
:class:`~vjax.material.Arrhenius` and :class:`fitting.master.ShiftTable` (the table's
interpolation as :meth:`~fitting.master.ShiftTable.log10_aT` computes it); any other law is evaluated
through one jitted function. Importing this module does not import vjax or JAX (so that
:mod:`fitting.plots` does not either; see :mod:`fitting`).
"""
from __future__ import annotations

import functools
import math

import numpy as np

__all__ = ["log10_aT", "modulus", "loss", "relaxation"]


def _float(a):
    return np.asarray(a, dtype=float)


def _table_log10_aT(x, y, T):
    """:meth:`fitting.master.ShiftTable.log10_aT` in numpy: linear between the temperatures
    ``x``, linearly extrapolated from the two end points beyond them."""
    if x.shape[0] == 1:
        return np.zeros_like(T) + y[0]
    i = np.clip(np.searchsorted(x, T, side="right"), 1, x.shape[0] - 1)
    inner = y[i - 1] + ((T - x[i - 1]) / (x[i] - x[i - 1])) * (y[i] - y[i - 1])
    lo = y[0] + (T - x[0]) * (y[1] - y[0]) / (x[1] - x[0])
    hi = y[-1] + (T - x[-1]) * (y[-1] - y[-2]) / (x[-1] - x[-2])
    return np.where(T < x[0], lo, np.where(T > x[-1], hi, inner))


@functools.lru_cache(maxsize=None)
def _jitted(method):
    import jax
    return jax.jit(lambda obj, x: getattr(obj, method)(x))


def log10_aT(law, T) -> np.ndarray:
    """log10 a_T of the shift law ``law`` at the temperatures ``T`` (C), a float array. A WLF
    law refuses temperatures at or below its asymptote, as its own method does."""
    from vjax.material import GAS_CONSTANT, KELVIN, Arrhenius, WLF

    from .master import ShiftTable
    T = _float(T)
    if isinstance(law, ShiftTable):
        return _table_log10_aT(_float(law.T), _float(law.values), T)
    if isinstance(law, WLF):
        C1, C2, T_ref = float(law.C1), float(law.C2), float(law.T_ref)
        if np.any(T - T_ref <= -C2):
            raise ValueError(f"T={T!r} C is at or below the WLF asymptote T_ref - C2 = {T_ref - C2:.4g} C")
        dT = T - T_ref
        return -C1 * dT / (C2 + dT)
    if isinstance(law, Arrhenius):
        T_ref = float(law.T_ref)
        if np.any(T <= -KELVIN):
            raise ValueError(f"T must be above absolute zero (-273.15 C), got {T!r}")
        return float(law.Ea) / (GAS_CONSTANT * math.log(10.0)) * (1.0 / (T + KELVIN) - 1.0 / (T_ref + KELVIN))
    return np.asarray(_jitted("log10_aT")(law, T))


def modulus(material, omega) -> np.ndarray:
    """Complex modulus E*(omega) (Pa) of the Prony material at ``omega`` (rad/s)."""
    iwt = 1j * _float(omega)[..., None] * _float(material.times)
    return float(material.E0) + np.sum(_float(material.moduli) * iwt / (1.0 + iwt), axis=-1)


def loss(material, omega) -> np.ndarray:
    """Loss modulus E''(omega) = sum_k E_k omega tau_k / (1 + (omega tau_k)^2) (Pa): the
    imaginary part of :func:`modulus` in real arithmetic (three times faster)."""
    wt = _float(omega)[..., None] * _float(material.times)
    return np.sum(_float(material.moduli) * wt / (1.0 + wt * wt), axis=-1)


def relaxation(material, t) -> np.ndarray:
    """Relaxation modulus E(t) (Pa) of the Prony material at times ``t`` (s)."""
    return float(material.E0) + np.sum(_float(material.moduli) * np.exp(-_float(t)[..., None] / _float(material.times)),
                                       axis=-1)
