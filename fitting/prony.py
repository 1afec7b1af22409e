"""Prony-series fit of DMA data: linear NNLS start, information criterion, end-to-end refinement.

Model (generalized Maxwell, :class:`vjax.Material`): at temperature T and angular frequency
omega (rad/s),

    E*(omega, T) = E0 + sum_k E_k i w tau_k / (1 + i w tau_k),   w = a_T(T) omega,

with E0 >= 0 the rubbery modulus (a free parameter, not forced to zero), E_k > 0 (Pa) and
tau_k (s) the relaxation times, log10 a_T from a shift law (WLF, Arrhenius or a table).
Every residual is a difference of log10 moduli, storage and loss together with equal weight:

    r = [log10 E'_model - log10 E'_meas ;  log10 E''_model - log10 E''_meas].

Steps:

1. :func:`fit_master` - for relaxation times log-spaced over the shifted data range at a
   density of ``d`` per decade, the moduli (E0, E_k) >= 0 solve a non-negative least-squares
   problem in the relative residual (model - meas)/meas ~ ln(10) * log10 residual, re-weighted
   twice by the model (so the weights approach the log residual). Terms with E_k = 0 are
   dropped: non-negative by construction.
2. The density (hence the number of terms) is chosen by the **Bayesian information
   criterion** BIC = n ln(RSS/n) + p ln(n) on the log10 residuals of the master curve, with
   n = 2 x points and p = 2 K + 1 (each kept term carries a modulus and a time, plus E0).
3. :func:`refine` - all parameters (log E0, log E_k, log tau_k and the shift-law parameters:
   C1, C2 for WLF, Ea for Arrhenius, or one log10 a_T per sweep for a table) minimize the
   log residual on the **raw unshifted** data by Levenberg-Marquardt with JAX Jacobians
   (:mod:`fitting._optim`). Positivity holds by construction (log parameters; WLF C2 is kept
   above the asymptote, C2 > T_ref - min T).
4. Uncertainties: covariance s^2 (J^T J)^+ at the optimum, s^2 = RSS/(n - p), mapped from
   the log parameters to the physical ones by the delta method (one standard deviation).
"""
from __future__ import annotations

import dataclasses
import math

import jax
import jax.numpy as jnp
import numpy as np

from vjax.material import GAS_CONSTANT, KELVIN, Arrhenius, Material, WLF

from . import _optim
from .dma import DMATable
from .master import ShiftTable

__all__ = ["PronyFit", "fit_master", "choose_terms", "refine", "raw_errors", "log_residual"]

LN10 = math.log(10.0)


@dataclasses.dataclass(frozen=True)
class PronyFit:
    """A fitted Prony series and its diagnostics.

    Attributes:
      material: the fitted :class:`vjax.Material` (moduli in Pa, times in s, at T_ref).
      shift: the shift law (:class:`vjax.WLF`, :class:`vjax.Arrhenius` or :class:`ShiftTable`).
      sigma: one-standard-deviation uncertainties, dict with 'E0', 'moduli', 'times' and the
        shift-law parameters ('C1', 'C2' / 'Ea' / 'log10_aT'); empty before refinement.
      rms: root-mean-square log10 residual over storage and loss.
      n_obs: number of residuals (2 x points). bic: information criterion value.
      iterations, converged: of the refinement (0, True for the linear fit).
      criterion: list of (density per decade, terms, BIC) tried by :func:`choose_terms`.
    """

    material: Material
    shift: object
    sigma: dict
    rms: float
    n_obs: int
    bic: float
    iterations: int = 0
    converged: bool = True
    criterion: tuple = ()

    @property
    def terms(self) -> int:
        return int(self.material.moduli.shape[0])


def _phi(omega_r, tau):
    wt = omega_r[:, None] * tau[None, :]
    return wt ** 2 / (1 + wt ** 2), wt / (1 + wt ** 2)


def fit_master(omega_r, storage, loss, density=1.0, pad=0.5, reweight=2):
    """NNLS Prony fit of a master curve at fixed log-spaced relaxation times.

    Args:
      omega_r: reduced angular frequency a_T omega (rad/s); storage, loss (Pa).
      density: relaxation times per decade; they span [1/max omega_r, 1/min omega_r]
        widened by ``pad`` decades each side.
    Returns ``(E0, moduli, times)`` with zero-modulus terms removed (Pa, Pa, s).
    """
    w, s, l = (np.asarray(a, float) for a in (omega_r, storage, loss))
    lo, hi = -np.log10(w.max()) - pad, -np.log10(w.min()) + pad
    K = max(int(round((hi - lo) * density)) + 1, 2)
    tau = np.logspace(lo, hi, K)
    ps, pl = _phi(w, tau)
    A = np.block([[np.ones((len(w), 1)), ps], [np.zeros((len(w), 1)), pl]])
    y = np.concatenate([s, l])
    scale = np.median(s)
    wts = 1.0 / y
    x = np.zeros(K + 1)
    for _ in range(reweight + 1):
        Aw = A * wts[:, None]
        colnorm = np.linalg.norm(Aw, axis=0) + 1e-300
        z, _ = _optim.nnls(Aw / colnorm, y * wts)
        x = z / colnorm
        model = A @ x
        wts = 1.0 / np.sqrt(y * np.maximum(model, 1e-6 * y))
    E0, Ek = x[0], x[1:]
    keep = Ek > 1e-9 * scale
    return float(E0), Ek[keep], tau[keep]


def _log_res_master(E0, Ek, tau, w, s, l):
    ps, pl = _phi(w, tau)
    ms = E0 + ps @ Ek
    ml = pl @ Ek
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.concatenate([np.log10(np.maximum(ms, 1e-300) / s), np.log10(np.maximum(ml, 1e-300) / l)])
    return r


def choose_terms(omega_r, storage, loss, densities=(0.5, 0.75, 1.0, 1.25, 1.5, 2.0), pad=0.5):
    """Fit :func:`fit_master` for each density (times per decade) and keep the lowest BIC.

    Returns ``((E0, moduli, times), table)`` where table lists (density, terms, BIC, rms)."""
    n = 2 * len(omega_r)
    best, rows = None, []
    for d in densities:
        E0, Ek, tau = fit_master(omega_r, storage, loss, density=d, pad=pad)
        r = _log_res_master(E0, Ek, tau, np.asarray(omega_r), np.asarray(storage), np.asarray(loss))
        rss = float(np.sum(r ** 2))
        p = 2 * len(Ek) + 1
        bic = n * math.log(rss / n) + p * math.log(n)
        rows.append((d, len(Ek), bic, math.sqrt(rss / n)))
        if best is None or bic < best[0]:
            best = (bic, (E0, Ek, tau))
    return best[1], tuple(rows)


# ---- end-to-end refinement ----------------------------------------------------------------
def _law_spec(shift, T_sets, T_ref, T_min):
    """(name, initial unconstrained params, function params -> log10 a_T per set)."""
    Ts = jnp.asarray(T_sets)
    if isinstance(shift, WLF):
        c2min = max(0.0, T_ref - T_min) + 1e-6
        c2 = max(float(shift.C2) - c2min, 1e-3)
        p0 = np.array([math.log(float(shift.C1)), math.log(c2)])

        def law(p):
            C1, C2 = jnp.exp(p[0]), c2min + jnp.exp(p[1])
            dT = Ts - T_ref
            return -C1 * dT / (C2 + dT)

        def physical(p):
            return WLF(float(np.exp(p[0])), float(c2min + np.exp(p[1])), float(T_ref))

        def sig(p, cov):
            return {"C1": float(np.exp(p[0]) * math.sqrt(max(cov[0, 0], 0))),
                    "C2": float(np.exp(p[1]) * math.sqrt(max(cov[1, 1], 0)))}
        return p0, law, physical, sig
    if isinstance(shift, Arrhenius):
        p0 = np.array([math.log(float(shift.Ea))])
        g = (1.0 / (Ts + KELVIN) - 1.0 / (T_ref + KELVIN)) / (GAS_CONSTANT * LN10)

        def law(p):
            return jnp.exp(p[0]) * g

        def physical(p):
            return Arrhenius(float(np.exp(p[0])), float(T_ref))

        def sig(p, cov):
            return {"Ea": float(np.exp(p[0]) * math.sqrt(max(cov[0, 0], 0)))}
        return p0, law, physical, sig
    if isinstance(shift, ShiftTable):
        p0 = np.asarray(shift.log10_aT(np.asarray(T_sets)), float)
        Tsn = np.asarray(T_sets, float)

        def law(p):
            # gauge: log10 a_T(T_ref) = 0 on the linear interpolant of the table
            return p - ShiftTable(Ts, p, jnp.asarray(T_ref)).log10_aT(T_ref)

        def physical(p):
            return ShiftTable.make(Tsn, np.asarray(p), T_ref)

        def sig(p, cov):
            return {"log10_aT": [float(math.sqrt(max(c, 0))) for c in np.diag(cov)]}
        return p0, law, physical, sig
    raise TypeError(f"unknown shift law {type(shift).__name__}")


def log_residual(material: Material, shift, table: DMATable):
    """log10(model/measured) for storage then loss on the raw points of ``table`` (length 2N)."""
    aT = 10.0 ** shift.log10_aT(jnp.asarray(table.T))
    E = material.modulus(jnp.asarray(table.omega) * aT)
    return jnp.concatenate([jnp.log10(E.real / table.storage), jnp.log10(E.imag / table.loss)])


def raw_errors(material: Material, shift, table: DMATable) -> dict:
    """Errors on the raw unshifted points: median and 90th percentile of |log10(pred/meas)|
    for storage and loss separately, plus rms of all log10 residuals."""
    r = np.asarray(log_residual(material, shift, table))
    n = len(table)
    rs, rl = np.abs(r[:n]), np.abs(r[n:])
    return {"storage_median": float(np.median(rs)), "storage_p90": float(np.percentile(rs, 90)),
            "loss_median": float(np.median(rl)), "loss_p90": float(np.percentile(rl, 90)),
            "rms": float(np.sqrt(np.mean(r ** 2)))}


def _robust(r, c):
    """Residual transform whose sum of squares is the Cauchy loss sum c^2 ln(1 + (r/c)^2);
    c = inf leaves r unchanged. Double-where keeps the gradient finite at r = 0."""
    if not np.isfinite(c):
        return r
    small = jnp.abs(r) < 1e-8 * c
    rs = jnp.where(small, 1.0, r)
    out = jnp.sign(rs) * c * jnp.sqrt(jnp.log1p((rs / c) ** 2))
    return jnp.where(small, r, out)


def refine(table: DMATable, material: Material, shift, max_iter: int = 300, robust: float = math.inf,
           weights=(1.0, 1.0)) -> PronyFit:
    """End-to-end Levenberg-Marquardt refinement of E0, moduli, times and the shift law
    against the raw unshifted data (see the module docstring). Returns a :class:`PronyFit`
    with uncertainties from the Jacobian at the optimum."""
    T_sets = table.temperatures
    T_ref = float(shift.T_ref)
    p_law0, law, physical, sig = _law_spec(shift, T_sets, T_ref, float(T_sets.min()))
    scale = float(np.median(table.storage))
    K = int(material.moduli.shape[0])
    E0 = max(float(material.E0), 1e-4 * float(np.min(table.storage)))
    x0 = np.concatenate([[math.log(E0 / scale)], np.log(np.asarray(material.moduli) / scale),
                         np.log(np.asarray(material.times)), p_law0])
    nl = len(p_law0)
    setid = jnp.asarray(table.set)
    w = jnp.asarray(table.omega)
    ls, ll = jnp.log10(jnp.asarray(table.storage)), jnp.log10(jnp.asarray(table.loss))

    def resid(x):
        E0 = jnp.exp(x[0])
        Ek = jnp.exp(x[1:K + 1])
        tau = jnp.exp(x[K + 1:2 * K + 1])
        L = law(x[2 * K + 1:])[setid]
        wr = w * 10.0 ** L
        wt = wr[:, None] * tau[None, :]
        den = 1.0 + wt * wt
        st = E0 + jnp.sum(Ek * wt * wt / den, axis=1)
        lo = jnp.sum(Ek * wt / den, axis=1)
        r = jnp.concatenate([weights[0] * (jnp.log10(st) - (ls - math.log10(scale))),
                             weights[1] * (jnp.log10(lo) - (ll - math.log10(scale)))])
        return _robust(r, robust)

    sol = jax.jit(lambda x: _optim.levenberg_marquardt(lambda y: resid(y), x, max_iter=max_iter))(jnp.asarray(x0))
    x = np.asarray(sol.x)
    r = np.asarray(sol.residual)
    J = np.asarray(sol.jacobian)
    n, p = len(r), len(x)
    rss = float(np.sum(r ** 2))
    s2 = rss / max(n - p, 1)
    cov = s2 * np.linalg.pinv(J.T @ J, rcond=1e-13)
    E0, Ek, tau = np.exp(x[0]) * scale, np.exp(x[1:K + 1]) * scale, np.exp(x[K + 1:2 * K + 1])
    order = np.argsort(tau)
    sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    sigma = {"E0": float(E0 * sd[0]), "moduli": list(Ek[order] * sd[1:K + 1][order]),
             "times": list(tau[order] * sd[K + 1:2 * K + 1][order])}
    sigma.update(sig(x[2 * K + 1:], cov[2 * K + 1:, 2 * K + 1:]))
    # terms whose modulus underflowed carry no information: drop them (moduli must be > 0)
    keep = Ek[order] > 1e-12 * (E0 + Ek.sum())
    # a relaxation time that underflowed to 0 (log tau driven out of the data range) is an
    # arm that never relaxes into the data: E_k i w tau/(1 + i w tau) -> 0, drop it too
    keep &= tau[order] > 0
    sigma["moduli"] = [v for v, k in zip(sigma["moduli"], keep) if k]
    sigma["times"] = [v for v, k in zip(sigma["times"], keep) if k]
    E0 = max(E0, 1e-12 * float(Ek.sum()))
    mat = Material.prony(float(E0), Ek[order][keep], tau[order][keep], material.nu)
    bic = n * math.log(rss / n) + p * math.log(n)
    return PronyFit(mat, physical(x[2 * K + 1:]), sigma, math.sqrt(rss / n), n, bic,
                    int(sol.iterations), bool(sol.converged))
