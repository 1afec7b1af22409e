"""Helpers to compare the numerical pin in a hole with the analytical (Persson) solution.

The analytical solution itself, with its derivation, is :mod:`vjax.reference`
(``persson_pressure``, ``persson_b_from_load``, ...). Here: a pin solve in the linear
(small-displacement) setting of that solution, and the contact angle of a sampled pressure.
"""
from __future__ import annotations

import numpy as np

__all__ = ["small_displacement_pin", "edge_angle"]


def edge_angle(theta, p, npts=4):
    """Contact semi-angle from a sampled pressure, to sub-element accuracy.

    Near a smooth (Hertz-like) edge p^2 is linear in theta: fit the last ``npts`` loaded
    elements on each side and extrapolate p^2 = 0; returns the mean of both sides.
    """
    th = np.angle(np.exp(1j * np.asarray(theta, dtype=float)))
    p = np.asarray(p, dtype=float)
    out = []
    for sign in (1.0, -1.0):
        side = (sign * th >= 0) & (p > 0)
        x, y = sign * th[side], p[side] ** 2
        idx = np.argsort(x)[-npts:]
        c = np.polyfit(x[idx], y[idx], 1)
        out.append(-c[1] / c[0])
    return 0.5 * (out[0] + out[1])


def small_displacement_pin(material, R, dR, load, n, iterations=6, **kw):
    """``vjax.pin_in_hole`` with the rigid-body reference chosen so that the pin offset e = dR.

    The infinite plane's mode-1 (rigid) displacement is fixed by the log-R reference length
    and is physically arbitrary. Persson's theory is linear in the displacements
    (interference e cos(theta) - dR, load R int p cos). pin_in_hole keeps two
    finite-displacement terms: the exact circle geometry, with e^2 sin^2(theta)/(2 R_pin),
    and the slope terms u'/R of Eq. 2.21. Both depend on that reference. Choosing
    ``ref_length`` so that e = dR (the contact region of the hole does not translate)
    makes them O(dR^2/R) and recovers the linear problem; the pressure is then
    independent of the reference. Fixed-slope iteration on log(ref_length) (2-3 solves).
    Returns (PinResult, ref_length).
    """
    import vjax

    def offset(log_ref):
        # throw=False: the solver's residual can stall just above its 1e-10 default
        # tolerance at small loads; the caller checks ``residual``.
        # e = dR needs a negative mode-1 compliance (ref_length < R), so the operator is
        # indefinite and a Krylov solve can break down (NaN) at isolated reference
        # lengths; e is continuous in ref_length, so nudge it and retry.
        for k in range(5):
            # a Python float, as the default ref_length and the loads of the callers: an np.float64
            # (strong type) here would compile the solver a second time
            housing = vjax.hole(material, ref_length=float(R * np.exp(log_ref + 1e-6 * k)))
            r = vjax.pin_in_hole(housing, R, dR, load, options=vjax.PinOptions(n=n, **kw), throw=False)
            if np.isfinite(float(r.pin_offset)):
                break
        return float(r.pin_offset) - dR, r

    # e is linear in log(ref_length) up to the O(e^2/R) terms: changing the reference adds
    # a rigid translation (mode 1), de/dlog(ref) = (ds_1/dlog(ref)) F / (pi E0) with s_1
    # the mode-1 element symbol. Start at ref_length = R and iterate with that slope.
    s_r = vjax.element_symbol("hole", n, R, float(material.nu), R)[1]
    s_e = vjax.element_symbol("hole", n, R, float(material.nu), R * np.e)[1]
    slope = float(s_e - s_r) * load / (np.pi * float(material.E0))
    l1 = 0.0
    f1, r = offset(l1)
    for _ in range(iterations):
        if not abs(f1) > 1e-7 * dR:       # e to 1e-7 dR: far below every tolerance
            break
        l1 = l1 - f1 / slope
        f1, r = offset(l1)
    return r, R * np.exp(l1)
