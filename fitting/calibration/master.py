"""Master curve: horizontal shift factors from the data, and WLF / Arrhenius fits.

Time-temperature superposition (docs/theory.md §14): E*(omega, T) = E*(a_T(T) omega, T_ref),
so the sweep at temperature T, plotted against the reduced frequency a_T omega, lies on the
master curve at T_ref. Hotter sweeps have a_T < 1 (log10 a_T < 0).

:func:`shift_factors` estimates log10 a_T per sweep from the overlap of the data alone:

1. For pairs of sweeps (neighbours and next-neighbours in temperature), the relative shift d
   minimizes the mean squared difference of **both** log10 E' and log10 E'' between the two
   curves (each linearly interpolated in log-log space onto the other's points where they
   overlap). A grid search over d (0.01 decade step, so no local minimum traps it) is
   refined by a parabola through the three best grid points.
2. Each pair shift gets the weight n * c / mse (n overlapping points, c the curvature of the
   mismatch at its minimum, mse its value): flat, noisy overlaps count little.
3. The per-sweep log10 a_T solve the weighted least-squares problem
   L_j - L_i = d_ij, which spreads pairwise errors instead of accumulating them.
4. The curve is referred to T_ref: at a measured temperature L(T_ref) = 0 exactly; between
   or beyond measured temperatures, L(T_ref) is interpolated (extrapolated) linearly in T.

:func:`fit_wlf` and :func:`fit_arrhenius` fit the shift laws of vjax (:class:`vjax.WLF`, :class:`vjax.Arrhenius`) to
these factors; :class:`ShiftTable` is the "table" law (user-given or measured factors).
"""
from __future__ import annotations

import csv
import dataclasses
import math
import os

import jax
import jax.numpy as jnp
import numpy as np

from vjax import Arrhenius, WLF
from vjax.materials import GAS_CONSTANT, KELVIN

from fitting.measurements.dma import DMATable, DMAFormatError
from fitting.shared.evaluate import table_log10_aT

__all__ = ["ShiftTable", "segment", "shift_factors", "fit_wlf", "fit_arrhenius", "fit_law", "read_shift_file",
           "pair_shift"]


def segment(x, T):
    """Where ``T`` lies on the table's temperatures ``x`` (increasing, at least two):
    ``(i, t)`` with the interpolant y[i-1] + t (y[i] - y[i-1]) linear between the
    temperatures and the end segments extended beyond them (t < 0 or > 1 there)."""
    i = jnp.clip(jnp.searchsorted(x, T, side="right"), 1, x.shape[0] - 1)
    return i, (T - x[i - 1]) / (x[i] - x[i - 1])


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class ShiftTable:
    """Tabulated shift law: log10 a_T at temperatures ``T`` (C), linear in T between them and
    linearly extrapolated beyond (from the two end points). ``T_ref`` (C) is where
    log10 a_T = 0. A PyTree: it can be passed to :meth:`vjax.Material.at_temperature`.
    """

    T: jax.Array
    values: jax.Array
    T_ref: jax.Array

    def log10_aT(self, T):
        """log10 a_T at temperature(s) ``T`` (C)."""
        T = jnp.asarray(T, dtype=jnp.result_type(self.T, float))
        x, y = self.T, self.values
        if x.shape[0] == 1:
            return jnp.zeros_like(T) + y[0]
        i, t = segment(x, T)
        return y[i - 1] + t * (y[i] - y[i - 1])

    @classmethod
    def make(cls, T, log10_aT, T_ref) -> "ShiftTable":
        """Build from measured/user factors; re-references them so that log10 a_T(T_ref) = 0.

        ``T`` (C) need not be sorted but must be distinct and finite."""
        T, y = np.asarray(T, float).ravel(), np.asarray(log10_aT, float).ravel()
        if T.shape != y.shape or T.size == 0:
            raise ValueError(f"T and log10_aT must be non-empty and of equal length, got {T.size} and {y.size}")
        if not (np.all(np.isfinite(T)) and np.all(np.isfinite(y)) and np.isfinite(T_ref)):
            raise ValueError("shift table values must be finite")
        order = np.argsort(T)
        T, y = T[order], y[order]
        if np.any(np.diff(T) == 0):
            raise ValueError(f"shift table has repeated temperatures: {T[np.flatnonzero(np.diff(T) == 0)]}")
        off = float(table_log10_aT(T, y, np.float64(T_ref)))     # numpy: no JAX dispatch
        return cls(jnp.asarray(T), jnp.asarray(y - off), jnp.asarray(float(T_ref)))


# ---- pairwise shifts --------------------------------------------------------------------
def _curve(table: DMATable, s: int):
    m = table.set == s
    x = np.log10(table.omega[m])
    o = np.argsort(x)
    return x[o], np.log10(table.storage[m])[o], np.log10(table.loss[m])[o]


def pair_shift(a, b, max_shift=12.0, step=0.01, min_overlap=0.2, loss_weight=1.0):
    """Shift d (decades) to add to log10 omega of curve ``b`` so that it overlays curve ``a``.

    ``a``, ``b``: tuples (log10 omega sorted increasing, log10 storage, log10 loss). Returns
    ``(d, weight, n_overlap)``; weight 0 when the curves never overlap by ``min_overlap``
    of the shorter log-frequency range (then d is NaN). ``loss_weight`` scales the loss part
    of the mismatch (0: storage only, as pyvisco does).
    """
    xa, sa, la = a
    xb, sb, lb = b
    d = np.arange(-max_shift, max_shift + step / 2, step)
    width = min(xa[-1] - xa[0], xb[-1] - xb[0])
    # only shifts with enough overlap can score (elsewhere the mismatch is inf): evaluate those
    # (an interval) and one grid point either side, which the parabola below looks at
    feasible = np.flatnonzero(np.minimum(xa[-1], xb[-1] + d) - np.maximum(xa[0], xb[0] + d) >= min_overlap * width)
    if feasible.size:
        d = d[max(feasible[0] - 1, 0):feasible[-1] + 2]

    def mismatch(d):
        xs = xb[None, :] + d[:, None]                       # b shifted, shape (G, nb)
        in_a = (xs >= xa[0]) & (xs <= xa[-1])
        # a's values at b's shifted points ...
        rs = np.interp(xs, xa, sa) - sb
        rl = np.interp(xs, xa, la) - lb
        e1 = np.where(in_a, rs ** 2 + loss_weight * rl ** 2, 0.0).sum(1)
        n1 = in_a.sum(1)
        # ... and b's values at a's points (symmetric, so neither curve is privileged)
        xa_b = xa[None, :] - d[:, None]
        in_b = (xa_b >= xb[0]) & (xa_b <= xb[-1])
        rs2 = np.interp(xa_b, xb, sb) - sa
        rl2 = np.interp(xa_b, xb, lb) - la
        e2 = np.where(in_b, rs2 ** 2 + loss_weight * rl2 ** 2, 0.0).sum(1)
        n2 = in_b.sum(1)
        n = n1 + n2
        ov = np.minimum(xa[-1], xb[-1] + d) - np.maximum(xa[0], xb[0] + d)
        ok = (ov >= min_overlap * width) & (n1 >= 2) & (n2 >= 2)
        mse = np.where(ok, (e1 + e2) / np.maximum(2 * n, 1), np.inf)
        return mse, n

    mse, n = mismatch(d)
    if not np.any(np.isfinite(mse)):
        return math.nan, 0.0, 0
    i = int(np.argmin(mse))
    d0, m0 = d[i], mse[i]
    # parabola through the best grid point and its neighbours
    if 0 < i < len(d) - 1 and np.isfinite(mse[i - 1]) and np.isfinite(mse[i + 1]):
        c2 = (mse[i - 1] - 2 * m0 + mse[i + 1]) / (2 * step ** 2)
        if c2 > 0:
            d0 = d0 - (mse[i + 1] - mse[i - 1]) / (4 * c2 * step)
    # curvature on a wider stencil (0.1 decade) is less sensitive to interpolation kinks
    h = 0.1
    mm, _ = mismatch(np.array([d0 - h, d0, d0 + h]))
    curv = (mm[0] - 2 * mm[1] + mm[2]) / h ** 2 if np.all(np.isfinite(mm)) else 0.0
    curv = max(curv, 1e-12)
    weight = n[i] * curv / max(mm[1] if np.isfinite(mm[1]) else m0, 1e-10)
    return float(d0), float(weight), int(n[i])


def shift_factors(table: DMATable, T_ref: float, neighbours: int = 2, max_shift: float = 12.0,
                  loss_weight: float = 1.0) -> ShiftTable:
    """log10 a_T of every sweep of ``table`` from data overlap, referred to ``T_ref`` (C).

    See the module docstring for the method. ``neighbours``: pairs (i, i+1..i+neighbours)
    enter the least-squares solve. ``loss_weight``: weight of the loss modulus in the pair
    mismatch (see :func:`pair_shift`). Raises ValueError for a single temperature, or when some
    sweep overlaps no other.
    """
    n = table.n_sets
    Ts = table.temperatures
    if n < 2:
        raise ValueError(f"shifting needs sweeps at two or more temperatures; the data have one (T = {Ts[0]:g} C) "
                         f"from {', '.join(table.files) or 'arrays'}")
    if not np.isfinite(T_ref):
        raise ValueError(f"T_ref must be finite, got {T_ref!r}")
    curves = [_curve(table, s) for s in range(n)]
    rows, rhs, w = [], [], []
    for i in range(n):
        for k in range(1, neighbours + 1):
            j = i + k
            if j >= n:
                break
            d, wt, _ = pair_shift(curves[i], curves[j], max_shift=max_shift, loss_weight=loss_weight)
            if wt > 0 and np.isfinite(d):
                r = np.zeros(n)
                r[j], r[i] = 1.0, -1.0
                rows.append(r)
                rhs.append(d)
                w.append(wt)
    A = np.array(rows).reshape(-1, n)
    # connectivity: every sweep must be linked to the first one
    linked = {0}
    changed = True
    while changed:
        changed = False
        for r in A:
            i, j = np.flatnonzero(r < 0)[0], np.flatnonzero(r > 0)[0]
            if (i in linked) != (j in linked):
                linked |= {i, j}
                changed = True
    if len(linked) < n:
        lone = [f"{Ts[s]:g} C" for s in range(n) if s not in linked]
        raise ValueError(f"cannot shift: the sweeps at {', '.join(lone)} overlap no other sweep in modulus; "
                         "give shift factors (shifts=...) instead")
    w = np.asarray(w)
    w = w / np.median(w)
    w = np.clip(w, 1e-3, 1e3)  # one pathological pair must not dominate
    sw = np.sqrt(w)[:, None]
    # gauge: L_0 = 0 (re-referenced to T_ref below)
    L = np.zeros(n)
    L[1:] = np.linalg.lstsq((A * sw)[:, 1:], np.asarray(rhs) * sw[:, 0], rcond=None)[0]
    # hotter sweeps shift to lower reduced frequency: d = L_j - L_i is the shift of j onto i,
    # i.e. b is moved by +d to lie on a, so log10 a_T(T_j) - log10 a_T(T_i) = d.
    return ShiftTable.make(Ts, L, T_ref)


# ---- shift laws -------------------------------------------------------------------------
def fit_wlf(T, log10_aT, T_ref, weights=None):
    """Least-squares WLF fit: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref).

    C1 is linear for fixed C2, so C2 is found by a dense search over log C2 (above the
    asymptote: C2 > T_ref - min T) followed by golden-section refinement, and C1 in closed
    form. Returns ``(WLF, rms)`` with rms the root-mean-square residual (decades).
    """
    T, y = np.asarray(T, float), np.asarray(log10_aT, float)
    wts = np.ones_like(T) if weights is None else np.asarray(weights, float)
    x = T - T_ref
    c2_min = max(0.0, -x.min()) + 1e-3

    def solve(c2):
        g = -x / (c2 + x)
        c1 = np.sum(wts * g * y) / max(np.sum(wts * g * g), 1e-300)
        c1 = max(c1, 1e-9)
        return c1, np.sum(wts * (c1 * g - y) ** 2)

    grid = c2_min + np.geomspace(1e-2, 1e5, 400)
    errs = np.array([solve(c)[1] for c in grid])
    i = int(np.argmin(errs))
    a, b = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    phi = (math.sqrt(5) - 1) / 2
    for _ in range(80):
        c, d = b - phi * (b - a), a + phi * (b - a)
        if solve(c)[1] < solve(d)[1]:
            b = d
        else:
            a = c
    c2 = 0.5 * (a + b)
    c1, sse = solve(c2)
    return WLF(float(c1), float(c2), float(T_ref)), math.sqrt(sse / np.sum(wts))


def fit_arrhenius(T, log10_aT, T_ref, weights=None):
    """Least-squares Arrhenius fit, log10 a_T = Ea/(R ln10) (1/T - 1/T_ref) with T in K
    (input in C); closed form. Returns ``(Arrhenius, rms)``; Ea in J/mol."""
    T, y = np.asarray(T, float), np.asarray(log10_aT, float)
    wts = np.ones_like(T) if weights is None else np.asarray(weights, float)
    g = (1.0 / (T + KELVIN) - 1.0 / (T_ref + KELVIN)) / (GAS_CONSTANT * math.log(10.0))
    Ea = max(np.sum(wts * g * y) / np.sum(wts * g * g), 1.0)
    return Arrhenius(float(Ea), float(T_ref)), math.sqrt(np.sum(wts * (Ea * g - y) ** 2) / np.sum(wts))


def fit_law(table: ShiftTable, law: str = "WLF"):
    """Fit ``law`` ('WLF', 'Arrhenius' or 'table') to a :class:`ShiftTable`; returns (law object, rms)."""
    T, y, Tr = np.asarray(table.T), np.asarray(table.values), float(table.T_ref)
    if law == "WLF":
        return fit_wlf(T, y, Tr)
    if law == "Arrhenius":
        return fit_arrhenius(T, y, Tr)
    if law == "table":
        return table, 0.0
    raise ValueError(f"shift law must be 'WLF', 'Arrhenius' or 'table', got {law!r}")


def read_shift_file(path, T_ref=None) -> ShiftTable:
    """Read user shift factors: a CSV with columns T (C) and log10 a_T (header names such as
    ``T,log_aT``; an optional unit row like ``C,-`` is skipped). Re-referenced to ``T_ref``
    when given, else to the temperature where log10 a_T = 0."""
    path = os.fspath(path)
    with open(path, encoding="utf-8-sig", errors="replace") as fh:
        rows = [r for r in csv.reader(fh) if any(c.strip() for c in r)]
    if not rows:
        raise DMAFormatError(path, None, "empty shift factor file")
    Ts, ys = [], []
    for ln, r in enumerate(rows, 1):
        if len(r) < 2:
            raise DMAFormatError(path, ln, "expected two columns: T [C], log10 a_T")
        try:
            Ts.append(float(r[0]))
            ys.append(float(r[1]))
        except ValueError:
            if Ts:
                raise DMAFormatError(path, ln, f"not a number: {r[:2]}")
            continue  # header or unit row
    if T_ref is None:
        zero = [t for t, y in zip(Ts, ys) if y == 0.0]
        if not zero:
            raise DMAFormatError(path, None, "no row with log10 a_T = 0: give T_ref")
        T_ref = zero[0]
    try:
        return ShiftTable.make(Ts, ys, T_ref)
    except ValueError as e:
        raise DMAFormatError(path, None, str(e)) from None
