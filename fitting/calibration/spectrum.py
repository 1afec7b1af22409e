"""Smooth relaxation spectra: a Prony fit on a fixed log-spaced grid of relaxation times with
a smoothness penalty chosen by generalized cross-validation (docs/theory.md, fitting section).

Model. Frequency data (DMA sweeps): E*(omega) = E0 + sum_k E_k i omega tau_k / (1 + i omega tau_k);
relaxation data: E(t) = E0 + sum_k E_k exp(-t / tau_k); in both, omega and t are reduced,
a_T omega and t / a_T, with log10 a_T from a shift law. The relaxation times sit on a grid
log-spaced at ``per_decade`` (>= 2) over the reduced range of the data widened by ``margin``
decades each side; they do not move (free times let neighbouring arms trade modulus, which is
what makes a Prony spectrum ring).

Penalized least squares. The unknowns x = (ln E0, ln E_1..ln E_K, shift-law parameters)
minimize

    S(x; lam) = sum_i r_i(x)^2 + lam sum_k (ln E_{k-1} - 2 ln E_k + ln E_{k+1})^2,

r_i the log10 residuals of storage and loss (or of E(t)) on the raw unshifted points. The
penalty is on the second difference of the log spectrum: a smooth, positive spectrum (the
moduli are positive by construction) whose shape the data fix and whose wiggles they do not.
Levenberg-Marquardt with JAX Jacobians solves it (:mod:`fitting.shared.optim`).

Choice of lam: generalized cross-validation (Craven and Wahba 1979; Golub, Heath and Wahba
1979) on the problem linearized at the solution,

    GCV(lam) = n RSS(lam) / (n - tr H(lam))^2,   H = J (J^T J + lam D^T D)^+ J^T,

with J the Jacobian of the n data residuals and D the second-difference operator on the log
moduli; tr H is the effective number of parameters. lam runs down a log grid from 1e3 (each
solve warm-started from the previous one, stopping two steps past the minimum) and the
minimum of GCV is kept. Residuals of DMA
data are correlated (the model error of a master curve is smooth), and GCV then tends to
under-smooth; so the chosen lam is the GCV minimum unless its loss modulus has more than
``max_extrema`` local extrema over the data range (one loss peak plus a secondary relaxation
at most give three), in which case it is the smallest lam on the grid above it that has at
most ``max_extrema``.
"""
from __future__ import annotations

import dataclasses
import functools
import math

import jax
import jax.numpy as jnp
import numpy as np

from vjax import Material

from fitting.shared import evaluate
from fitting.shared import jax_cache, optim
from fitting.shared.evaluate import count_extrema, loss_extrema
from fitting.measurements.dma import set_temperatures
from fitting.calibration.prony import COV_RCOND, LN10, PronyFit, cauchy_residual, law_eval, law_spec

__all__ = ["count_extrema", "loss_extrema", "SmoothData", "smooth_fit", "LAMBDAS"]

LAMBDAS = tuple(10.0 ** np.arange(3.0, -6.01, -1.0))


@dataclasses.dataclass(frozen=True)
class SmoothData:
    """Raw points for :func:`smooth_fit`, either domain.

    ``x``: angular frequency omega (rad/s) for ``domain='frequency'``, time t (s) for
    ``'time'``; ``y1``: storage (or relaxation) modulus, ``y2``: loss modulus (ignored for
    time data) (Pa); ``T`` nominal temperature (C) and ``set`` sweep index per point."""

    x: np.ndarray
    y1: np.ndarray
    y2: np.ndarray
    T: np.ndarray
    set: np.ndarray
    domain: str = "frequency"

    @classmethod
    def from_table(cls, table) -> "SmoothData":
        """From a :class:`fitting.measurements.dma.DMATable` (frequency) or :class:`fitting.measurements.dma.RelaxationTable`."""
        if getattr(table, "domain", "frequency") == "time":
            return cls(table.t, table.modulus, table.modulus, table.T, table.set, "time")
        return cls(table.omega, table.storage, table.loss, table.T, table.set, "frequency")

    @property
    def temperatures(self):
        return set_temperatures(self.T, self.set)

    def log_rate(self):
        """ln of omega (frequency) or of 1/t (time): the variable a shift adds ln a_T to."""
        return np.log(self.x) if self.domain == "frequency" else -np.log(self.x)


def _bucket(n, base=64):
    """Padded size for ``n`` rows: the next power-of-two multiple of ``base`` - repeated fits of
    files of similar size reuse one compilation."""
    size = base
    while size < n:
        size *= 2
    return size


def _kernel(domain, z):
    """Arm responses at z = omega tau (frequency) or tau / t (time) and their derivatives with
    respect to ln z: (phi1, phi2, dphi1, dphi2); for time data phi2 = phi1."""
    if domain == "frequency":
        den = 1 + z * z
        p1, p2 = z * z / den, z / den
        return p1, p2, 2 * p1 / den, p2 * (1 - z * z) / den
    p1 = jnp.exp(-1.0 / z)
    return p1, p1, p1 / z, p1 / z


def _resid_jac(x, on, data, domain, K, robust):
    """Residuals (log10 storage and loss or E(t), then the smoothness rows) and their analytic
    Jacobian with respect to x = (ln E0, ln E_k (K), law parameters)."""
    u, setid, y1, y2, w1, w2, Ts, T_ref, c2min, ltau, kind, sq_lam = data
    E0 = jnp.exp(x[0])
    lE = x[1:K + 1]
    Ek = jnp.exp(lE) * on
    plaw = x[K + 1:]
    L, JL = law_eval(kind, plaw, Ts, T_ref, c2min)
    JL = LN10 * JL[setid]      # d ln z / d law
    z = jnp.exp((u + LN10 * L[setid])[:, None] + ltau[None, :])
    p1, p2, d1, d2 = _kernel(domain, z)
    m1 = E0 + p1 @ Ek
    m2 = p2 @ Ek + (E0 if domain == "time" else 0.0)    # time data: w2 = 0, m2 only stays > 0
    c1, c2 = w1 / (LN10 * m1), w2 / (LN10 * m2)
    J1 = jnp.concatenate([(c1 * E0)[:, None], c1[:, None] * p1 * Ek, (c1 * (d1 @ Ek))[:, None] * JL], axis=1)
    J2 = jnp.concatenate([jnp.zeros_like(c2)[:, None], c2[:, None] * p2 * Ek, (c2 * (d2 @ Ek))[:, None] * JL], axis=1)
    r = jnp.concatenate([w1 * (jnp.log10(m1) - y1), w2 * (jnp.log10(m2) - y2)])
    J = jnp.concatenate([J1, J2], axis=0)
    if np.isfinite(robust):
        r, dr = jax.jvp(lambda v: cauchy_residual(v, robust), (r,), (jnp.ones_like(r),))
        J = J * dr[:, None]
    # smoothness: second differences of ln E_k among active arms (rows touching padding are off)
    rows_on = on[:-2] * on[1:-1] * on[2:]
    D = (jnp.eye(K - 2, K) - 2 * jnp.eye(K - 2, K, 1) + jnp.eye(K - 2, K, 2)) * (sq_lam * rows_on)[:, None]
    Jp = jnp.concatenate([jnp.zeros((K - 2, 1)), D, jnp.zeros((K - 2, plaw.shape[0]))], axis=1)
    return jnp.concatenate([r, D @ lE]), jnp.concatenate([J, Jp], axis=0)


@functools.partial(jax.jit, static_argnames=("domain", "K", "max_iter", "robust"))
def _solve(x0, active, data, *, domain, K, max_iter, ftol, robust):
    # the shift law's kind is data (a traced index): the table, WLF and Arrhenius fits of a
    # calibration share one compilation
    on = active[1:K + 1]
    sol = optim.levenberg_marquardt(None, x0, max_iter=max_iter, ftol=ftol, active=active,
                                     resid_jac=lambda x: _resid_jac(x, on, data, domain, K, robust))
    return tuple(jax.tree.leaves(sol))     # arrays only, for jax_cache.call (LMSolution(*leaves))


def _grid(lo, hi, per_decade, max_terms):
    """log10 tau grid over [lo, hi] (decades) at ``per_decade``, at most ``max_terms`` points."""
    K = max(int(math.ceil((hi - lo) * per_decade)) + 1, 3)
    if max_terms is not None:
        K = min(K, int(max_terms))
    return np.linspace(lo, hi, K)


def smooth_fit(data: SmoothData, shift, *, per_decade: float = 3.0, margin: float = 1.0,
               max_terms: int | None = None, lam=None, lambdas=LAMBDAS, max_extrema: int = 3,
               weights=(1.0, 1.0), robust: float = math.inf, start=None, grid=None, fit_shift: bool = True,
               max_iter: int = 400, ftol: float = 1e-9, nu: float = 0.5):
    """Smooth-spectrum Prony fit of ``data`` with the shift law ``shift`` refined end to end.

    Args:
      data: :class:`SmoothData`. shift: starting law (WLF, Arrhenius or ShiftTable; its type
        is kept, its parameters are fitted).
      per_decade: relaxation times per decade (>= 2 for a smooth loss modulus);
        ``max_terms`` caps the number (the grid then gets coarser, the penalty stays).
      margin: decades added to each end of the data's reduced range.
      lam: penalty weight; None chooses it on ``lambdas`` by GCV (module docstring).
      weights: of the storage and loss residuals; robust: scale (decades) of a Cauchy loss
        (inf: least squares). start: a :class:`PronyFit` to warm-start from (its spectrum
        interpolated onto the grid); grid: log10 relaxation times to use instead of the
        default grid (e.g. the one of an earlier fit). fit_shift: False holds the shift law
        fixed (a table of relaxation curves: a sweep on a plateau carries no information on
        its own shift, and a free factor would drift along it).
    Returns ``(PronyFit, info)``; the fit's relaxation times are the grid (their sigma 0).
    info: 'lam' (chosen weight), 'grid' (log10 tau), 'edf' (effective parameters tr H),
    'extrema' (of E'' over the data), 'gcv': rows (lam, GCV, edf, rms, extrema, LM iterations,
    converged) of every weight tried.
    """
    if data.domain not in ("frequency", "time"):
        raise ValueError(f"domain must be 'frequency' or 'time', got {data.domain!r}")
    if max_terms is not None and int(max_terms) < 3:
        raise ValueError(f"max_terms must be >= 3, got {max_terms!r}")
    Tsets = data.temperatures
    T_ref = float(shift.T_ref)
    kind, p_law0, physical, sig, c2min = law_spec(shift, Tsets, T_ref, float(Tsets.min()))
    u = data.log_rate()
    scale = float(np.median(data.y1))
    ur = u + LN10 * evaluate.log10_aT(shift, data.T)     # ln reduced rate
    if grid is None:
        grid = _grid(-ur.max() / LN10 - margin, -ur.min() / LN10 + margin, per_decade, max_terms)
    grid = np.asarray(grid, float)
    K = len(grid)
    Kp = K if K % 8 == 0 else K + 8 - K % 8
    nlp = max(len(Tsets), 2)
    n = len(data.x)
    npad = _bucket(n)
    pad = lambda a, v=0.0: np.concatenate([np.asarray(a, float), np.full(npad - n, v)])  # noqa: E731
    two = 1.0 if data.domain == "frequency" else 0.0
    ltau = np.concatenate([grid, np.full(Kp - K, grid[-1])]) * LN10
    # numpy arrays and Python scalars go to the jitted solver as they are: jnp.asarray would
    # compile a transfer per shape in every process
    base = (pad(u), np.concatenate([data.set, np.zeros(npad - n, int)]),
            pad(np.log10(data.y1 / scale)), pad(np.log10(data.y2 / scale)),
            pad(np.full(n, weights[0])), pad(np.full(n, weights[1] * two)),
            np.asarray(Tsets, float), float(T_ref), float(c2min), ltau, int(kind))
    # start: the log-linear interpolation of the data's storage (relaxation) modulus drop
    if start is None:
        E0 = max(float(np.min(data.y1)) * 0.9, 1e-6 * scale)
        drop = max(float(np.max(data.y1)) - E0, 1e-3 * scale)
        lE = np.full(K, math.log(drop / K / scale))
    else:
        E0 = float(start.material.E0)
        lE = np.interp(grid, np.log10(np.asarray(start.material.times)),
                       np.log(np.asarray(start.material.moduli) / scale))
    plaw = np.zeros(nlp)
    plaw[:len(p_law0)] = p_law0
    x = np.concatenate([[math.log(E0 / scale)], lE, np.zeros(Kp - K), plaw])
    active = np.concatenate([[1.0], np.arange(Kp) < K, (np.arange(nlp) < len(p_law0)) & fit_shift]).astype(float)
    on = np.flatnonzero(active > 0)
    n_res = 2 * npad
    live = np.concatenate([np.arange(n), npad + np.arange(n)]) if two else np.arange(n)
    D = np.zeros((K - 2, len(on)))
    for i in range(K - 2):
        D[i, 1 + i:4 + i] = (1.0, -2.0, 1.0)

    def run(lam_, x0):
        sol = optim.LMSolution(*jax_cache.call(_solve, (x0, active, base + (math.sqrt(lam_),)),
                                                domain=data.domain, K=Kp, max_iter=int(max_iter),
                                                ftol=float(ftol), robust=float(robust)))
        xs = np.asarray(sol.x)
        J = np.asarray(sol.jacobian)[:n_res][live][:, on]
        r = np.asarray(sol.residual)[:n_res][live]
        JtJ = J.T @ J
        edf = float(np.trace(np.linalg.solve(JtJ + lam_ * D.T @ D + 1e-12 * np.eye(len(on)) * np.trace(JtJ), JtJ)))
        rss = float(np.sum(r ** 2))
        m = len(live)
        mat = _material(xs, K, scale, grid, nu)
        # extrema over the reduced range of the data under the fitted law
        wr = np.exp(u + LN10 * evaluate.log10_aT(physical(xs[Kp + 1:Kp + 1 + len(p_law0)]), data.T))
        return xs, sol, dict(lam=lam_, gcv=m * rss / max(m - edf, 1.0) ** 2, edf=edf, rms=math.sqrt(rss / m),
                             extrema=loss_extrema(mat, wr.min(), wr.max()),
                             x=xs, iterations=int(sol.iterations), converged=bool(sol.converged), J=J, r=r)

    table = []
    if lam is not None:
        x, sol, best = run(float(lam), x)
        table.append(best)
    else:
        rises = 0
        for lam_ in lambdas:     # large to small, warm-started; stop two steps past the minimum
            x, sol, row = run(lam_, x)
            table.append(row)
            rises = rises + 1 if row["gcv"] > min(r["gcv"] for r in table) else 0
            if rises == 2:
                break
        ok = [row for row in table if row["extrema"] <= max_extrema]
        gmin = min(table, key=lambda row: row["gcv"])
        if gmin["extrema"] <= max_extrema or not ok:
            best = gmin
        else:   # smallest lam above the GCV minimum whose loss modulus has few extrema
            best = min((row for row in ok if row["lam"] > gmin["lam"]), key=lambda row: row["lam"],
                       default=max(ok, key=lambda row: row["lam"]))
    xs = best["x"]
    mat = _material(xs, K, scale, grid, nu)
    law = physical(xs[Kp + 1:Kp + 1 + len(p_law0)])
    J, r = best["J"], best["r"]
    m = len(live)
    p_eff = best["edf"]
    s2 = float(np.sum(r ** 2)) / max(m - p_eff, 1.0)
    cov = s2 * optim.covariance(np.vstack([J, math.sqrt(best["lam"]) * D]), COV_RCOND)[0]
    sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    sigma = {"E0": float(mat.E0) * sd[0], "moduli": list(np.asarray(mat.moduli) * sd[1:K + 1]), "times": [0.0] * K}
    if fit_shift:
        sigma.update(sig(xs[Kp + 1:Kp + 1 + len(p_law0)], cov[K + 1:, K + 1:]))
    bic = m * math.log(float(np.sum(r ** 2)) / m) + p_eff * math.log(m)
    fit = PronyFit(mat, law, sigma, best["rms"], m, bic, best["iterations"], best["converged"])
    info = dict(lam=best["lam"], grid=grid, edf=p_eff, extrema=best["extrema"],
                gcv=[tuple(row[k] for k in ("lam", "gcv", "edf", "rms", "extrema", "iterations", "converged"))
                     for row in table])
    return fit, info


def _material(x, K, scale, grid, nu):
    """The Prony material of the parameter vector; an E0 that underflowed (the data still
    relax at their lowest reduced frequency) is floored at 1e-12 of the glassy modulus."""
    Ek = np.exp(x[1:K + 1]) * scale
    E0 = max(float(np.exp(x[0]) * scale), 1e-12 * float(Ek.sum()))
    return Material.prony(E0, Ek, 10.0 ** np.asarray(grid), nu)
