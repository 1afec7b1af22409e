"""Fitted materials and shift laws evaluated on the host, in numpy.

A calibration evaluates its results many times outside any derivative: the errors on the raw
points, the loss modulus's extrema, the distances between shift laws, every curve of the
plots. Through JAX, each of these is a function traced and lowered once per process (the
persistent compilation cache of the command-line tools skips only XLA's compilation): about
0.4 s of a cached ``vjax-fit`` call. The same formulas in numpy take microseconds.

The formulas are those of :class:`vjax.Material` (Prony series), :class:`~vjax.WLF`,
:class:`~vjax.Arrhenius` and :class:`fitting.calibration.master.ShiftTable` (the table's
interpolation as :meth:`~fitting.calibration.master.ShiftTable.log10_aT` computes it); any other law is evaluated
through one jitted function. Importing this module does not import vjax or JAX (so that
:mod:`fitting.calibration.plots` does not either; see :mod:`fitting`).
"""
from __future__ import annotations

import functools
import math

import numpy as np

_SAMPLES = 4096      # loss-modulus samples of loss_extrema: >= 100 per decade over 40 decades

__all__ = ["count_extrema", "loss_extrema", "log10_aT", "table_log10_aT", "modulus", "loss", "relaxation", "raw_errors", "errors_at", "tensile_over_shear"]


def _float(a):
    return np.asarray(a, dtype=float)


def table_log10_aT(x, y, T):
    """:meth:`fitting.calibration.master.ShiftTable.log10_aT` in numpy: linear between the temperatures
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
    from vjax import Arrhenius, WLF
    from vjax.materials import GAS_CONSTANT, KELVIN
    T = _float(T)
    if hasattr(law, "values") and hasattr(law, "T"):     # a fitting.calibration.master.ShiftTable (not imported:
        return table_log10_aT(_float(law.T), _float(law.values), T)   # master imports this module)
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


def raw_errors(material, shift, table) -> dict:
    """Errors on the raw unshifted points of a :class:`fitting.measurements.dma.DMATable`: median and 90th
    percentile of |log10(pred/meas)| for storage and loss separately, plus the rms of all
    log10 residuals (:func:`fitting.calibration.prony.log_residual` is the JAX version for derivatives)."""
    return errors_at(material, table.omega * 10.0 ** log10_aT(shift, table.T), table.storage, table.loss)


def errors_at(material, omega_r, storage, loss) -> dict:
    """:func:`raw_errors` of points at reduced angular frequencies ``omega_r`` (rad/s)."""
    E = modulus(material, omega_r)
    r = np.concatenate([np.log10(E.real / storage), np.log10(E.imag / loss)])
    n = len(omega_r)
    rs, rl = np.abs(r[:n]), np.abs(r[n:])
    return {"storage_median": float(np.median(rs)), "storage_p90": float(np.percentile(rs, 90)),
            "loss_median": float(np.median(rl)), "loss_p90": float(np.percentile(rl, 90)),
            "rms": float(np.sqrt(np.mean(r ** 2)))}


def tensile_over_shear(nu) -> float:
    """E / G = 2 (1 + nu) for an isotropic material with constant Poisson ratio ``nu``: the
    package's one conversion between tensile and shear moduli."""
    return 2.0 * (1.0 + float(nu))


def count_extrema(y) -> int:
    """Number of interior local extrema of the sampled curve ``y`` (sign changes of its
    differences, exact plateaus skipped)."""
    d = np.sign(np.diff(np.asarray(y, float)))
    d = d[d != 0]
    return int(np.count_nonzero(d[1:] != d[:-1]))


def loss_extrema(material, omega_min: float, omega_max: float) -> int:
    """Local extrema of the loss modulus E''(omega) of ``material`` between ``omega_min`` and
    ``omega_max`` (rad/s, reduced), sampled at 4096 log-spaced points (>= 100 per decade up
    to 40 decades; more beyond)."""
    if not (0 < omega_min < omega_max):
        raise ValueError(f"need 0 < omega_min < omega_max, got {omega_min!r}, {omega_max!r}")
    decades = math.log10(omega_max / omega_min)
    n = _SAMPLES if decades <= 40 else int(100 * decades) + 1
    return count_extrema(loss(material, 10.0 ** np.linspace(math.log10(omega_min), math.log10(omega_max), n)))
