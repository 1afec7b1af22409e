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
   (:func:`fitting.calibrate` instead refines one candidate per density and compares the
   BIC after refinement.)
3. :func:`refine` - all parameters (log E0, log E_k, log tau_k and the shift-law parameters:
   C1, C2 for WLF, Ea for Arrhenius, or one log10 a_T per sweep for a table) minimize the
   log residual on the **raw unshifted** data by Levenberg-Marquardt with JAX Jacobians
   (:mod:`fitting.shared.optim`). Positivity holds by construction (log parameters; WLF C2 is kept
   above the asymptote, C2 > T_ref - min T). The relaxation times are held within the
   reduced-frequency range of the data plus ``tau_margin`` decades by a penalty residual (an
   arm relaxing below the data would stand in for E0). The Jacobian is analytic and the
   parameter vector is padded to a fixed number of terms, so one compilation serves all
   refinements of a data set; storage/loss weights and a Cauchy loss are options.
4. Uncertainties: covariance s^2 (J^T J)^+ at the optimum, s^2 = RSS/(n - p), mapped from
   the log parameters to the physical ones by the delta method (one standard deviation).
"""
from __future__ import annotations

import dataclasses
import functools
import math

import jax
import jax.numpy as jnp
import numpy as np

from vjax import Arrhenius, Material, WLF
from vjax.materials import GAS_CONSTANT, KELVIN

from fitting.shared import optim
from fitting.shared import evaluate
from fitting.shared.evaluate import raw_errors
from fitting.measurements.dma import DMATable
from fitting.calibration.master import ShiftTable, segment

__all__ = ["PronyFit", "fit_master", "choose_terms", "refine", "raw_errors", "log_residual"]

LN10 = math.log(10.0)
COV_RCOND = math.sqrt(1e-13)    # singular values kept in the fits' covariances (eigenvalues of J^T J: 1e-13)


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
        z, _ = optim.nnls(Aw / colnorm, y * wts)
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
_WLF, _ARR, _TAB = 0, 1, 2


def law_spec(shift, T_sets, T_ref, T_min):
    """(kind, initial unconstrained params, params -> physical law, params, cov -> sigma, c2min)."""
    if isinstance(shift, WLF):
        c2min = max(0.0, T_ref - T_min) + 1e-6
        c2 = max(float(shift.C2) - c2min, 1e-3)
        p0 = np.array([math.log(float(shift.C1)), math.log(c2)])

        def physical(p):
            return WLF(float(np.exp(p[0])), float(c2min + np.exp(p[1])), float(T_ref))

        def sig(p, cov):
            return {"C1": float(np.exp(p[0]) * math.sqrt(max(cov[0, 0], 0))),
                    "C2": float(np.exp(p[1]) * math.sqrt(max(cov[1, 1], 0)))}
        return _WLF, p0, physical, sig, c2min
    if isinstance(shift, Arrhenius):
        p0 = np.array([math.log(float(shift.Ea))])

        def physical(p):
            return Arrhenius(float(np.exp(p[0])), float(T_ref))

        def sig(p, cov):
            return {"Ea": float(np.exp(p[0]) * math.sqrt(max(cov[0, 0], 0)))}
        return _ARR, p0, physical, sig, 0.0
    if isinstance(shift, ShiftTable):
        p0 = evaluate.log10_aT(shift, T_sets)
        Tsn = np.asarray(T_sets, float)

        def physical(p):
            return ShiftTable.make(Tsn, np.asarray(p), T_ref)

        def sig(p, cov):
            return {"log10_aT": [float(math.sqrt(max(c, 0))) for c in np.diag(cov)]}
        return _TAB, p0, physical, sig, 0.0
    raise TypeError(f"unknown shift law {type(shift).__name__}")


def law_eval(kind, p, Ts, T_ref, c2min):
    """log10 a_T per set and its Jacobian with respect to the unconstrained law parameters
    ``p`` (padded vector): ``(L (sets,), dL/dp (sets, len(p)))``, the derivatives written out
    (forward-mode differentiation through a switch of three laws was half of the fit's
    tracing time). ``Ts``: the sets' temperatures, increasing. ``kind`` (_WLF, _ARR or _TAB)
    may be traced: then one compiled function serves all three laws."""
    n, m = Ts.shape[0], p.shape[0]

    def wlf(p):
        C1, e1 = jnp.exp(p[0]), jnp.exp(p[1])
        dT = Ts - T_ref
        L = -C1 * dT / (c2min + e1 + dT)
        dL_dp1 = C1 * dT * e1 / (c2min + e1 + dT) ** 2
        return L, jnp.zeros((n, m)).at[:, 0].set(L).at[:, 1].set(dL_dp1)

    def arrhenius(p):
        g = (1.0 / (Ts + KELVIN) - 1.0 / (T_ref + KELVIN)) / (GAS_CONSTANT * LN10)
        L = jnp.exp(p[0]) * g
        return L, jnp.zeros((n, m)).at[:, 0].set(L)

    def table(p):
        # gauge: log10 a_T(T_ref) = 0 on the table's interpolant, i.e. L = q - w.q with the
        # weights w of T_ref on its segment
        if n == 1:
            return jnp.zeros(1), jnp.zeros((1, m))
        i, t = segment(Ts, T_ref)
        w = jnp.zeros(m).at[i - 1].add(1.0 - t).at[i].add(t)
        return p[:n] - w @ p, jnp.eye(n, m) - w[None, :]
    branches = {_WLF: wlf, _ARR: arrhenius, _TAB: table}
    if isinstance(kind, int):
        return branches[kind](p)
    return jax.lax.switch(kind, [branches[k] for k in (_WLF, _ARR, _TAB)], p)


def _resid_jac(x, on, data, kind, K, robust):
    """Residual (weighted log10 storage and loss, then the time-bound penalty) and its
    analytic Jacobian with respect to the padded parameter vector (O(N K) work, not the
    O(N K P) of forward-mode differentiation)."""
    w, setid, ls, ll, Ts, T_ref, c2min, wts, lt_lo, lt_hi, pen = data
    nl = x.shape[0] - 2 * K - 1
    E0 = jnp.exp(x[0])
    Ek = jnp.exp(x[1:K + 1]) * on
    lt = x[K + 1:2 * K + 1]
    plaw = x[2 * K + 1:]
    L, JL = law_eval(kind, plaw, Ts, T_ref, c2min)      # JL: (sets, nl)
    u = jnp.log(w) + LN10 * L[setid]
    wt = jnp.exp(u[:, None] + lt[None, :])
    den = 1.0 + wt * wt
    ps = wt * wt / den
    pl = wt / den
    st = E0 + ps @ Ek
    lo = pl @ Ek
    dps = 2.0 * ps / den                      # d phi_s / d ln(omega tau)
    dpl = pl * (1.0 - wt * wt) / den          # d phi_l / d ln(omega tau)
    cs = wts[0] / (LN10 * st)
    cl = wts[1] / (LN10 * lo)
    Js_b = cs[:, None] * dps * Ek[None, :]
    Jl_b = cl[:, None] * dpl * Ek[None, :]
    Js_u = jnp.sum(Js_b, axis=1)
    Jl_u = jnp.sum(Jl_b, axis=1)
    Jlaw = LN10 * JL[setid]
    n = w.shape[0]
    Js = jnp.concatenate([(cs * E0)[:, None], cs[:, None] * ps * Ek[None, :], Js_b, Js_u[:, None] * Jlaw], axis=1)
    Jl = jnp.concatenate([jnp.zeros((n, 1)), cl[:, None] * pl * Ek[None, :], Jl_b, Jl_u[:, None] * Jlaw], axis=1)
    r = jnp.concatenate([wts[0] * (jnp.log10(st) - ls), wts[1] * (jnp.log10(lo) - ll)])
    J = jnp.concatenate([Js, Jl], axis=0)
    if np.isfinite(robust):
        rr, dr = jax.jvp(lambda v: cauchy_residual(v, robust), (r,), (jnp.ones_like(r),))
        r, J = rr, J * dr[:, None]
    # soft bounds: relaxation times stay within the reduced-frequency range of the data
    # plus a margin (an arm relaxing far below the data is indistinguishable from E0)
    hi, lo_ = lt > lt_hi, lt < lt_lo
    bound = pen * on * (jnp.where(hi, lt - lt_hi, 0.0) + jnp.where(lo_, lt_lo - lt, 0.0))
    Jb = jnp.concatenate([jnp.zeros((K, K + 1)), jnp.diag(pen * on * (hi.astype(x.dtype) - lo_.astype(x.dtype))),
                          jnp.zeros((K, nl))], axis=1)
    return jnp.concatenate([r, bound]), jnp.concatenate([J, Jb], axis=0)


@functools.partial(jax.jit, static_argnames=("kind", "K", "max_iter", "robust"))
def _solve(x0, active, data, *, kind, K, max_iter, robust, ftol):
    """Levenberg-Marquardt on the padded parameter vector [log E0, log E_k (K), log tau_k (K),
    law (padded)]; inactive entries (``active`` = 0) carry no modulus and do not move. The
    shapes (K, padded law size, points) are the only things that trigger a compilation."""
    on = active[1:K + 1]
    return optim.levenberg_marquardt(None, x0, max_iter=max_iter, ftol=ftol, active=active,
                                      resid_jac=lambda x: _resid_jac(x, on, data, kind, K, robust))


def log_residual(material: Material, shift, table: DMATable):
    """log10(model/measured) for storage then loss on the raw points of ``table`` (length 2N)."""
    return _log_residual(material, shift, *(jnp.asarray(a) for a in (table.T, table.omega, table.storage, table.loss)))


@jax.jit
def _log_residual(material, shift, T, omega, storage, loss):
    E = material.modulus(omega * 10.0 ** shift.log10_aT(T))
    return jnp.concatenate([jnp.log10(E.real / storage), jnp.log10(E.imag / loss)])


def cauchy_residual(r, c):
    """Residual transform whose sum of squares is the Cauchy loss sum c^2 ln(1 + (r/c)^2);
    c = inf leaves r unchanged. Double-where keeps the gradient finite at r = 0."""
    if not np.isfinite(c):
        return r
    small = jnp.abs(r) < 1e-8 * c
    rs = jnp.where(small, 1.0, r)
    out = jnp.sign(rs) * c * jnp.sqrt(jnp.log1p((rs / c) ** 2))
    return jnp.where(small, r, out)


def pad_size(n, step=8):
    return max(step, -(-n // step) * step)


def refine(table: DMATable, material: Material, shift, max_iter: int = 300, robust: float = math.inf,
           weights=(1.0, 1.0), ftol: float = 1e-7, tau_margin: float = 1.0, pad_terms: int | None = None,
           prune: float = 0.0, fix_E0: bool = False) -> PronyFit:
    """End-to-end Levenberg-Marquardt refinement of E0, moduli, times and the shift law
    against the raw unshifted data (see the module docstring). Returns a :class:`PronyFit`
    with uncertainties from the Jacobian at the optimum.

    ``ftol``: stop when a step lowers the cost by less than this fraction. ``tau_margin``:
    decades by which the relaxation times may leave the reduced-frequency range of the data
    (soft bound, a penalty residual) so that the longest arm cannot stand in for E0.
    ``pad_terms``: pad the parameter vector to this many terms (default: the next multiple of
    8) so that refinements of similar size share one compilation. ``prune``: after the
    refinement, terms whose modulus is below ``prune`` x (E0 + sum E_k) are removed and the
    rest refined again (0 disables). ``fix_E0``: hold E0 at its start (at least 1e-4 of the
    smallest measured storage modulus): a liquid, whose data show no equilibrium modulus."""
    T_sets = table.temperatures
    T_ref = float(shift.T_ref)
    kind, p_law0, physical, sig, c2min = law_spec(shift, T_sets, T_ref, float(T_sets.min()))
    scale = float(np.median(table.storage))
    K = int(material.moduli.shape[0])
    Kp = max(pad_terms or pad_size(K), K)
    nl = len(p_law0)
    nlp = max(len(T_sets), 2)
    E0 = max(float(material.E0), 1e-4 * float(np.min(table.storage)))
    lEk = np.zeros(Kp)
    lEk[:K] = np.log(np.asarray(material.moduli) / scale)
    ltau = np.zeros(Kp)
    ltau[:K] = np.log(np.asarray(material.times))
    plaw = np.zeros(nlp)
    plaw[:nl] = p_law0
    x0 = np.concatenate([[math.log(E0 / scale)], lEk, ltau, plaw])
    active = np.concatenate([[0.0 if fix_E0 else 1.0], np.arange(Kp) < K, np.arange(Kp) < K, np.arange(nlp) < nl]).astype(float)
    # reduced-frequency range of the data under the starting shift law
    wr = np.asarray(table.omega) * 10.0 ** evaluate.log10_aT(shift, table.T)
    lt_lo = -math.log(wr.max()) - tau_margin * LN10
    lt_hi = -math.log(wr.min()) + tau_margin * LN10
    # start inside the bounds: a start outside pays a penalty that can outweigh the (robust,
    # hence nearly flat for large errors) data cost, and the first steps then give up the fit
    # to remove it (a 20-term grid with a decade of margin collapsed to 2 terms, 18 decades off)
    x0[Kp + 1:Kp + K + 1] = np.clip(x0[Kp + 1:Kp + K + 1], lt_lo, lt_hi)
    data = (jnp.asarray(table.omega), jnp.asarray(table.set), jnp.log10(jnp.asarray(table.storage) / scale),
            jnp.log10(jnp.asarray(table.loss) / scale), jnp.asarray(T_sets, float), jnp.asarray(T_ref),
            jnp.asarray(c2min), jnp.asarray(weights, float), jnp.asarray(lt_lo), jnp.asarray(lt_hi),
            jnp.asarray(10.0))
    sol = _solve(jnp.asarray(x0), jnp.asarray(active), data, kind=kind, K=Kp, max_iter=int(max_iter),
                 robust=float(robust), ftol=float(ftol))
    xa = np.asarray(sol.x)
    iters, conv = int(sol.iterations), bool(sol.converged)
    if prune > 0:
        Ek_all = np.exp(xa[1:K + 1]) * scale
        small = Ek_all < prune * (np.exp(xa[0]) * scale + Ek_all.sum())
        if small.any() and (~small).sum() >= 1:
            act2 = active.copy()
            act2[1:K + 1][small] = 0.0
            act2[Kp + 1:Kp + K + 1][small] = 0.0
            sol = _solve(jnp.asarray(xa), jnp.asarray(act2), data, kind=kind, K=Kp, max_iter=int(max_iter),
                         robust=float(robust), ftol=float(ftol))
            xa = np.asarray(sol.x)
            iters += int(sol.iterations)
            conv = bool(sol.converged)
            active = act2
    n = 2 * len(table)
    on = np.flatnonzero(active > 0)
    if fix_E0:          # E0 held: kept in x (x[0] is log E0 below), with no say in the covariance
        on = np.concatenate([[0], on])
    r = np.asarray(sol.residual)[:n]
    J = np.asarray(sol.jacobian)[:n][:, on]
    if fix_E0:
        J[:, 0] = 0.0
    x = xa[on]
    p = len(x) - int(fix_E0)
    Kk = int(active[1:Kp + 1].sum())
    rss = float(np.sum(r ** 2))
    s2 = rss / max(n - p, 1)
    cov = s2 * optim.covariance(J, COV_RCOND)[0]
    E0, Ek, tau = np.exp(x[0]) * scale, np.exp(x[1:Kk + 1]) * scale, np.exp(x[Kk + 1:2 * Kk + 1])
    order = np.argsort(tau)
    sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    sigma = {"E0": float(E0 * sd[0]), "moduli": list(Ek[order] * sd[1:Kk + 1][order]),
             "times": list(tau[order] * sd[Kk + 1:2 * Kk + 1][order])}
    sigma.update(sig(x[2 * Kk + 1:], cov[2 * Kk + 1:, 2 * Kk + 1:]))
    # terms whose modulus underflowed carry no information: drop them (moduli must be > 0)
    keep = Ek[order] > 1e-12 * (E0 + Ek.sum())
    # a relaxation time that underflowed to 0 (log tau driven out of the data range) is an
    # arm that never relaxes into the data: E_k i w tau/(1 + i w tau) -> 0, drop it too
    keep &= tau[order] > 0
    sigma["moduli"] = [v for v, k in zip(sigma["moduli"], keep) if k]
    sigma["times"] = [v for v, k in zip(sigma["times"], keep) if k]
    E0 = max(E0, 1e-12 * float(Ek.sum()))
    # two arms that converged onto the same relaxation time (e.g. both held at the bound) are
    # one arm: merge them (moduli add, their uncertainties in quadrature)
    Ekk, tk = list(Ek[order][keep]), list(tau[order][keep])
    sm, st = sigma["moduli"], sigma["times"]
    i = 1
    while i < len(tk):
        if tk[i] <= tk[i - 1] * (1.0 + 1e-9):
            Ekk[i - 1] += Ekk.pop(i)
            tk.pop(i)
            sm[i - 1] = math.hypot(sm[i - 1], sm.pop(i))
            st[i - 1] = max(st[i - 1], st.pop(i))
        else:
            i += 1
    mat = Material.prony(float(E0), np.asarray(Ekk), np.asarray(tk), material.nu)
    bic = n * math.log(rss / n) + p * math.log(n)
    return PronyFit(mat, physical(x[2 * Kk + 1:]), sigma, math.sqrt(rss / n), n, bic, iters, conv)
