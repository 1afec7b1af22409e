"""Compact Prony series for finite-element codes: the fewest terms that keep a fit's accuracy.

A smooth spectrum (:mod:`fitting.calibration.spectrum`) puts three relaxation times in every decade of
the data's reduced range plus a decade each side: 60 to 100 terms, each of which is internal
state at every integration point of an FEM model. Over the data's window fewer hold the same
accuracy and smoothness. Two kinds of n-term series, every relaxation time within the
window's reduced-time range widened by ``MARGIN_DECADES`` (no term relaxes where nothing was
measured; never 1e-20 s):

* :func:`placed_terms` (smooth): times placed where the loss modulus needs them
  (:func:`placement`), moduli by non-negative least squares on the full fit's storage and loss;
* :func:`fit_terms` (free, accurate with few terms, rippled): free times and moduli,
  Levenberg-Marquardt on log residuals from a non-negative least-squares start
  (:mod:`fitting.shared.optim`), to the DMA points (robust) or to the full series.

Why placement decides smoothness: a Prony loss modulus is a sum of Debye peaks; terms h
decades apart leave a ripple of relative amplitude 2 sech(pi^2 / (h ln 10)) (:func:`ripple`:
5.5 % at h = 1, 1.9 % at 0.8, 23 % at 1.5), which adds local extrema wherever the material's
own log-log loss slope is smaller than the ripple's slope (0.15 at h = 1, 0.06 at 0.8). DMA
loss curves are that flat over much of their reduced range (the shipped sets: |slope| < 0.07
over 13-16 of their 26-40 decades), so a smooth series needs about 1.5 terms a decade there
and fewer where the loss is steep.

How the count is chosen (:func:`choose`): the smallest n at which one of the two series

* is as accurate as the full fit within ``TOLERANCE``: its median |log10(model/measured)| on
  the DMA points is at most ``TOLERANCE`` (1.5) times the full fit's, for storage and loss
  separately (relaxation data: for E(t)); without the data, its median deviation from the full
  fit over the window is at most ``TOLERANCE - 1`` times the full fit's median error recorded
  in the material JSON (a deviation d adds at most |d| to each point's error), and
* is smooth within the data's own scatter: its loss-modulus ripple (:func:`ripple_of`: the
  largest swing, in decades of log10 E'', of a local extremum the full fit does not have) is
  below the scatter of the data about the full fit (:func:`scatter`: the full fit's median
  |log10(E''_fit / E''_measured)| over the DMA points, E(t) for relaxation data; without the
  data the recorded one). A swing smaller than the scatter is one the data cannot tell from
  noise, so it is not counted as an extremum,

is kept (``met`` True). The placed series is tried up to the full fit's count or a cap
``max_terms``, the free one up to ``FREE_MAX_TERMS`` (20: beyond that its Levenberg-Marquardt
costs more than it gains over placement); the counts tried double from 1 until one qualifies,
then bisect below it. With a cap too small for smoothness the smallest accurate count is
kept, or the cap if none is accurate, and :class:`Choice` says so (``met`` False) with the
ripple it has: what the cap costs.

Moduli are in the series' own unit (Pa), times in s, frequencies in rad/s (reduced, at the
material's T_ref).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from fitting.shared import optim
from fitting.shared.evaluate import loss_extrema

__all__ = ["Series", "Choice", "fit_terms", "placed_terms", "placement", "ripple", "ripple_of", "scatter",
           "choose", "deviation", "is_liquid", "FREE_MAX_TERMS", "LIQUID", "TOLERANCE", "MARGIN_DECADES"]

FREE_MAX_TERMS = 20
SAME = 2.0            # a swing within this factor of one of the full fit's is that extremum, not ripple
ROUNDOFF = 1e-9       # decades: swings of log10 E'' below this are rounding, not extrema
LIQUID = 1e-3         # E0 below this share of the storage modulus at the data's lowest frequency: a liquid
TOLERANCE = 1.5
MARGIN_DECADES = 0.5
SAMPLES_PER_DECADE = 10
ROBUST = 0.03         # decades, as fitting.calibration.pipeline.ROBUST
DATA_FIT = dict(robust=ROBUST, weights=(4.0, 1.0))   # fits to DMA points: storage 4:1 (docs/fem_export.md)
LN10 = math.log(10.0)


@dataclasses.dataclass(frozen=True)
class Series:
    """A Prony series M(t) = E0 + sum_k moduli_k exp(-t / times_k): E0 and moduli in the
    modulus' unit (Pa), times in s, times increasing (the attribute names of
    :class:`vjax.Material`, so :mod:`fitting.shared.evaluate` takes it as it is)."""

    E0: float
    moduli: np.ndarray
    times: np.ndarray

    def scaled(self, factor) -> "Series":
        """Every modulus times ``factor`` (e.g. shear to tensile)."""
        return Series(self.E0 * factor, self.moduli * factor, self.times)


@dataclasses.dataclass(frozen=True)
class Choice:
    """What :func:`choose` kept: ``series``; ``met``: it meets the criterion (accurate and
    smooth); ``accurate``: it holds the accuracy; ``errors`` (its accuracy, same keys as
    ``reference``: the full fit's errors on the data), ``extrema`` (local extrema of its loss
    modulus over the window, every one counted), ``ripple`` (:func:`ripple_of`, decades) and
    ``scatter`` (:func:`scatter`, decades) it was held to, ``basis`` ('data': errors on the DMA points, or 'full fit': deviations from it),
    ``tried``: rows (terms, errors, ripple) of each count tried."""

    series: Series
    met: bool
    accurate: bool
    errors: dict
    reference: dict
    extrema: int
    basis: str
    tried: tuple
    ripple: float = 0.0
    scatter: float = 0.0


def _cauchy(r, c):
    """Residuals whose sum of squares is the Cauchy loss sum c^2 ln(1 + (r/c)^2), and their
    derivative with respect to r (1 at r = 0)."""
    u = r / c
    L = np.log1p(u * u)
    small = np.abs(u) < 1e-8
    root = np.sqrt(np.where(small, 1.0, L))
    return np.where(small, r, np.sign(r) * c * root), np.where(small, 1.0, np.abs(u) / ((1 + u * u) * root))


def _arms(w, tau):
    z = w[:, None] * tau[None, :]
    den = 1.0 + z * z
    ps, pl = z * z / den, z / den
    return ps, pl, 2.0 * ps / den, pl * (1.0 - z * z) / den


def _moduli(series: Series, w):
    ps, pl, _, _ = _arms(w, np.asarray(series.times, float))
    Ek = np.asarray(series.moduli, float)
    return series.E0 + ps @ Ek, pl @ Ek


def _window(window):
    """(omega_min, omega_max) of ``window`` (rad/s), checked."""
    lo, hi = (float(v) for v in window)
    if not (0 < lo < hi and math.isfinite(hi)):
        raise ValueError(f"window must be 0 < omega_min < omega_max (rad/s), got {window!r}")
    return lo, hi


def _samples(window, per_decade=SAMPLES_PER_DECADE):
    lo, hi = (math.log10(v) for v in window)
    return 10.0 ** np.linspace(lo, hi, max(int(math.ceil((hi - lo) * per_decade)) + 1, 40))


def is_liquid(series: Series, omega_min: float) -> bool:
    """Whether ``series`` has no equilibrium modulus the data could see: E0 is at most
    ``LIQUID`` (0.1 %) of its storage modulus at ``omega_min`` (rad/s, reduced), the lowest
    frequency of the data, far below any measurement's resolution there. A melt's smooth fit
    keeps E0 near its floor (1e-9 of the glassy modulus); a cross-linked solid's E0 is nearly
    all of the storage modulus at the lowest frequencies."""
    storage = float(_moduli(series, np.array([float(omega_min)]))[0][0])
    return float(series.E0) <= LIQUID * storage


def deviation(series: Series, full: Series, window) -> dict:
    """|log10(series / full)| of storage and loss over ``window`` (rad/s): median and max."""
    w = _samples(window)
    (s1, l1), (s0, l0) = _moduli(series, w), _moduli(full, w)
    ds, dl = np.abs(np.log10(s1 / s0)), np.abs(np.log10(l1 / l0))
    return {"storage_median": float(np.median(ds)), "storage_max": float(ds.max()),
            "loss_median": float(np.median(dl)), "loss_max": float(dl.max())}


def _kernel(kind, x, tau):
    """Response of unit arms (times ``tau``) at ``x`` and its derivative with respect to
    ln tau, and whether the long-term modulus adds: storage and loss at angular frequency x,
    relaxation E(t) at time x."""
    if kind == "relaxation":
        z = x[:, None] / tau[None, :]
        p = np.exp(-z)
        return p, z * p, True
    ps, pl, dps, dpl = _arms(x, tau)
    return (ps, dps, True) if kind == "storage" else (pl, dpl, False)


def fit_terms(full: Series, n: int, window, margin: float = MARGIN_DECADES, target=None,
              robust: float = ROBUST, weights=(1.0, 1.0), max_iter: int = 100, times=None,
              long_term: bool = True) -> Series:
    """The ``n``-term series (plus a long-term modulus E0) closest in log modulus to
    ``target``: the DMA points under the material's shift law, (omega, storage, loss) (reduced
    rad/s, Pa) or ('time', t, E) (reduced s, Pa); without it ``full``'s storage and loss over
    ``window`` = (omega_min, omega_max) (rad/s, reduced). Relaxation times stay within
    [1/omega_max, 1/omega_min] widened by ``margin`` decades (module docstring). ``robust``:
    scale (decades) of the Cauchy loss on the data's residuals (0: least squares), as the
    calibration's (a few inconsistent points do not bend the series); ``weights``: of the
    storage and loss residuals. ``times``: the ``n`` starting relaxation times (s), default
    log-spaced from 1/omega_max to 1/omega_min. ``long_term`` False: E0 = 0 (a liquid: no
    equilibrium modulus), not fitted."""
    if not (isinstance(n, int) and n >= 1):
        raise ValueError(f"n (terms) must be an integer >= 1, got {n!r}")
    if times is not None and not (np.shape(times) == (n,) and np.all(np.asarray(times, float) > 0)):
        raise ValueError(f"times must be {n} positive relaxation times (s), got {times!r}")
    lo, hi = _window(window)
    if target is None:
        w = _samples((lo, hi))
        st, ls = _moduli(full, w)
        parts = [("storage", w, st, 1.0), ("loss", w, ls, 1.0)]
    elif isinstance(target[0], str):          # ("time", t, E)
        parts = [("relaxation", np.asarray(target[1], float), np.asarray(target[2], float), 1.0)]
    else:
        w, st, ls = (np.asarray(v, float) for v in target)
        parts = [("storage", w, st, weights[0]), ("loss", w, ls, weights[1])]
    scale = float(max(np.max(p[2]) for p in parts))
    lt_lo, lt_hi = -math.log(hi) - margin * LN10, -math.log(lo) + margin * LN10
    ltau = (np.log(np.asarray(times, float)) if times is not None else
            np.linspace(-math.log(hi), -math.log(lo), n) if n > 1 else np.array([-0.5 * math.log(lo * hi)]))
    # start: non-negative moduli at these times (relative residuals)
    rows = []
    for kind, x, y, _ in parts:
        k, _, e0 = _kernel(kind, x, np.exp(ltau))
        rows.append(np.hstack([np.full((len(x), 1), float(e0)), k]) / y[:, None])
    A = np.vstack(rows)
    x0, _ = optim.nnls(A, np.ones(A.shape[0]))
    x = np.concatenate([np.log(np.maximum(x0, 1e-9 * scale) / scale), ltau])
    pen = 10.0

    def resid_jac(x):
        E0, Ek, lt = float(np.exp(x[0])), np.exp(x[1:n + 1]), x[n + 1:]
        rs, Js = [], []
        for kind, xs, y, wt in parts:
            k, dk, e0 = _kernel(kind, xs, np.exp(lt))
            model = k @ Ek + (E0 if e0 else 0.0)
            c = wt / (LN10 * model)
            rs.append(wt * np.log10(model * scale / y))
            Js.append(np.hstack([(c * E0 * e0)[:, None], c[:, None] * k * Ek, c[:, None] * dk * Ek]))
        r, J = np.concatenate(rs), np.vstack(Js)
        if robust:
            r, dr = _cauchy(r, robust)
            J = J * dr[:, None]
        above, below = lt > lt_hi, lt < lt_lo
        bound = pen * (np.where(above, lt - lt_hi, 0.0) + np.where(below, lt_lo - lt, 0.0))
        Jb = np.hstack([np.zeros((n, n + 1)), np.diag(pen * (above.astype(float) - below.astype(float)))])
        return np.concatenate([r, bound]), np.vstack([J, Jb]), None

    if not long_term:           # E0 = exp(-inf) = 0, held: the other parameters are fitted
        full_x = resid_jac

        def resid_jac(y):
            r, J, _ = full_x(np.concatenate([[-np.inf], y]))
            return r, J[:, 1:], None
        x = x[1:]
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):    # a wild trial step: its
        x, *_ = optim.levenberg_marquardt_host(resid_jac, x, max_iter=max_iter, ftol=1e-6)   # cost is inf, rejected
    if not long_term:
        x = np.concatenate([[-np.inf], x])
    order = np.argsort(x[n + 1:])
    return Series(float(math.exp(x[0]) * scale), np.exp(x[1:n + 1])[order] * scale, np.exp(x[n + 1:])[order])


def ripple(spacing):
    """Ripple of a Maxwell sum whose relaxation times are ``spacing`` decades apart (array or
    float): (relative amplitude of E'', amplitude of the ripple's slope d log10 E'' / d log10
    omega). Each term's loss is a Debye peak 1/(2 cosh u) in u = ln(omega tau); the first
    Fourier harmonic of the sum of peaks a period P = spacing ln 10 apart is 2 sech(pi^2 / P)
    of the mean (a flat spectrum): 5.5 % at 1 decade, 1.9 % at 0.8, 23 % at 1.5."""
    h = np.asarray(spacing, float)
    amp = 2.0 / np.cosh(np.pi ** 2 / (h * LN10))
    return amp, amp / LN10 * (2.0 * np.pi / h)


_SPACINGS = np.linspace(0.2, 4.0, 400)          # decades: the spacings placement() chooses from


def placement(full: Series, window, n: int, margin: float = MARGIN_DECADES) -> np.ndarray:
    """``n`` relaxation times (s, increasing) placed where ``full``'s loss modulus needs them.

    A ripple makes local extrema only where the curve's own log-log slope s = d log10 E'' /
    d log10 omega is smaller than the ripple's slope (:func:`ripple`). The local spacing is
    the largest h (0.2 to 4 decades) whose ripple slope is below |s| of ``full`` there: dense
    near the loss peak and on flat plateaus, coarse where E'' is steep. The times are the
    ``n`` quantiles of that density (1/h) over ``window`` (rad/s, reduced) widened by
    ``margin`` decades each side (tau = 1/omega)."""
    if not (isinstance(n, int) and n >= 1):
        raise ValueError(f"n (terms) must be an integer >= 1, got {n!r}")
    lo, hi = (math.log10(v) for v in _window(window))
    x = np.linspace(lo - margin, hi + margin, max(200, int(100 * (hi - lo + 2 * margin))))
    _, pl, _, _ = _arms(10.0 ** x, np.asarray(full.times, float))
    slope = np.abs(np.gradient(np.log10(pl @ np.asarray(full.moduli, float)), x))
    ok = ripple(_SPACINGS)[1][None, :] < slope[:, None]
    density = 1.0 / np.where(ok, _SPACINGS[None, :], _SPACINGS[0]).max(axis=1)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(x))])
    return np.sort(10.0 ** -np.interp((np.arange(n) + 0.5) / n, cum / cum[-1], x))


def placed_terms(full: Series, n: int, window, margin: float = MARGIN_DECADES, long_term: bool = True) -> Series:
    """``n`` terms at :func:`placement`'s times, moduli (and E0) by non-negative least squares
    on ``full``'s storage and loss over ``window`` (rad/s; relative residuals at
    ``2 * SAMPLES_PER_DECADE`` frequencies a decade). Fitted to the smooth full series rather
    than to the scattered points, so the series keeps its smoothness (a fit to the points
    moves times and moduli to chase scatter and leaves bumps). ``long_term`` False: E0 = 0."""
    tau = placement(full, window, n, margin)
    w = _samples(window, 2 * SAMPLES_PER_DECADE)
    st, ls = _moduli(full, w)
    ps, pl, _, _ = _arms(w, tau)
    A = np.vstack([np.hstack([np.ones((len(w), 1)), ps]) / st[:, None],
                   np.hstack([np.zeros((len(w), 1)), pl]) / ls[:, None]])
    if not long_term:
        A = A[:, 1:]
    x, _ = optim.nnls(A, np.ones(A.shape[0]))
    return Series(float(x[0]), x[1:], tau) if long_term else Series(0.0, x, tau)


def _turns(y):
    """The alternating local extrema of the sampled curve ``y`` (its first and last samples
    included as ends), as an array of values: the zig-zag the swings are measured on."""
    y = np.asarray(y, float)
    d = np.sign(np.diff(y))
    keep = np.flatnonzero(d != 0)
    if keep.size == 0:
        return y[:1]
    d = d[keep]
    idx = keep[1:][d[1:] != d[:-1]]            # a sample where the slope changes sign
    return np.concatenate([y[:1], y[idx], y[-1:]])


def _significant(turns, h):
    """Local extrema of a zig-zag whose swing exceeds ``h``: a turn counts once the curve has
    moved back from it by more than ``h`` (the usual zig-zag filter with threshold h)."""
    count, hi, lo, trend = 0, turns[0], turns[0], 0
    for v in turns[1:]:
        if trend == 0:
            hi, lo = max(hi, v), min(lo, v)
            trend = 1 if v - lo > h else -1 if hi - v > h else 0
            hi, lo = (v, v) if trend else (hi, lo)
        elif trend > 0:
            if v > hi:
                hi = v
            elif hi - v > h:          # a maximum confirmed
                count, trend, lo = count + 1, -1, v
        else:
            if v < lo:
                lo = v
            elif v - lo > h:          # a minimum confirmed
                count, trend, hi = count + 1, 1, v
    return count


def _log_loss(series: Series, window, per_decade=100):
    lo, hi = (math.log10(v) for v in window)
    w = 10.0 ** np.linspace(lo, hi, max(int(per_decade * (hi - lo)) + 1, 400))
    return np.log10(_moduli(series, w)[1])


def ripple_of(series: Series, full: Series, window) -> float:
    """Ripple of ``series``' loss modulus over ``window`` (rad/s), decades of log10 E'': the
    largest swing h at which the series has more local extrema with swings of h or more than
    ``full`` has with swings of h / ``SAME`` or more (:func:`_significant`; an extremum the
    full fit has, its swing changed by the fewer terms, is not an extra one), i.e. the largest
    swing among the extrema the full fit does not have; 0 for a series with no extra extremum. The full fit's own extrema (the
    glass transition's loss peak, or its own ripple of a few 1e-6 decades) are not ripple."""
    a, b = _turns(_log_loss(series, window)), _turns(_log_loss(full, window))
    cands = np.unique(np.concatenate([np.abs(np.diff(a)), np.abs(np.diff(b))]))
    for h in cands[::-1]:                 # descending: the first swing that brings an extra extremum
        if h < ROUNDOFF:
            break
        below = h * (1.0 - 1e-9)          # swings of h itself count
        if _significant(a, below) > _significant(b, below / SAME):
            return float(h)
    return 0.0


def scatter(errors: dict) -> float:
    """Scatter of the data about the full fit (decades) from its errors on them: the median
    |log10(E''_fit / E''_measured)| (``loss_median``), for relaxation data the one of E(t)."""
    for k in ("loss_median", "relaxation_median"):
        if k in errors:
            return float(errors[k])
    raise ValueError(f"errors carry no loss_median or relaxation_median to measure the scatter: {sorted(errors)}")


def choose(full: Series, window, errors_of=None, reference=None, target=None, max_terms: int | None = None,
           tolerance: float = TOLERANCE, long_term: bool = True) -> Choice:
    """The fewest terms that hold ``full``'s accuracy and are smooth within the data's
    scatter (module docstring).

    ``errors_of(series) -> dict`` gives a series' errors on the DMA data (keys
    ``storage_median``, ``loss_median`` or ``relaxation_median``); without it, ``reference``
    (the full fit's recorded errors on the data, same keys) bounds the deviation from the
    full fit over ``window`` (rad/s) and gives the scatter. ``target``: the DMA points for
    the free-time candidate (:func:`fit_terms`). ``max_terms``: a cap on the count (default:
    ``full``'s own count). ``long_term`` False: every series has E0 = 0 (a liquid)."""
    if errors_of is None and not reference:
        raise ValueError("choose needs the DMA data (errors_of) or the full fit's recorded errors (reference)")
    if max_terms is not None and not (isinstance(max_terms, int) and max_terms >= 1):
        raise ValueError(f"max_terms must be an integer >= 1, got {max_terms!r}")
    if errors_of is not None:
        basis, ref = "data", errors_of(full)
        keys = [k for k in ("storage_median", "loss_median", "relaxation_median") if k in ref]
        limit = {k: tolerance * ref[k] for k in keys}
        measure = errors_of
    else:
        basis, ref = "full fit", dict(reference)
        keys = [k for k in ("storage_median", "loss_median") if k in ref] or ["storage_median"]
        if "relaxation_median" in ref:       # relaxation data: E(t) bounds both moduli's deviation
            ref.update(storage_median=ref["relaxation_median"], loss_median=ref["relaxation_median"])
            keys = ["storage_median", "loss_median"]
        limit = {k: (tolerance - 1.0) * ref[k] for k in keys}
        measure = lambda s: deviation(s, full, window)  # noqa: E731
    noise = scatter(ref)
    cap = int(max_terms) if max_terms is not None else max(len(full.times), 1)
    fits = {}

    def run(n):
        """(series, errors, ripple, worst error / limit) of the better candidate at n terms:
        smooth and accurate first, then accurate, then the smaller error."""
        if n not in fits:
            cands = [placed_terms(full, n, window, long_term=long_term)]
            if n <= FREE_MAX_TERMS:
                cands.append(fit_terms(full, n, window, target=target, long_term=long_term,
                                       **(DATA_FIT if target is not None else {})))
            rows = []
            for s in cands:
                e = measure(s)
                rows.append((s, e, ripple_of(s, full, window), max(e[k] / limit[k] for k in keys)))
            fits[n] = min(rows, key=lambda r: (not (r[3] <= 1.0 and r[2] < noise), r[3] > 1.0, r[3]))
        return fits[n]

    def smallest(ok):
        """The smallest n <= cap with ok(n), or None: doubling from 1 up to the first n with
        ok(n), then bisection below it (accuracy and smoothness grow with n nearly
        monotonically, but not beyond: least squares on many close times picks a sparse subset
        of them and ripples again, so the search never starts from the cap)."""
        hi = 1
        while not ok(hi):
            if hi >= cap:
                return None
            hi = min(2 * hi, cap)
        lo = hi // 2
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (lo, mid) if ok(mid) else (mid, hi)
        return hi

    accurate = lambda n: run(n)[3] <= 1.0  # noqa: E731
    smooth = lambda n: accurate(n) and run(n)[2] < noise  # noqa: E731
    n = smallest(smooth)
    met = n is not None
    if not met:
        n = smallest(accurate) or cap
    s, e, rip, _ = run(n)
    tried = tuple((k, {q: v[1][q] for q in keys}, v[2]) for k, v in sorted(fits.items()))
    return Choice(s, met, accurate(n), e, ref, loss_extrema(s, *window), basis, tried, rip, noise)
