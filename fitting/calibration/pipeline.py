"""One-call calibration: DMA files -> Prony material + shift law (+ JSON and plots).

:func:`calibrate` chains the steps of :mod:`fitting.measurements.dma` (or :mod:`fitting.measurements.relaxation`),
:mod:`fitting.calibration.master`, :mod:`fitting.calibration.spectrum` and :mod:`fitting.calibration.prony`:

1. read the files: frequency sweeps, or relaxation curves E(t) (detected from the header);
2. shift factors per sweep from the overlap of the storage (or E(t)) curves, or the user's table;
3. method 'smooth' (default, :func:`fitting.calibration.spectrum.smooth_fit`): relaxation times fixed on a
   grid at 3 per decade, a second-difference penalty on ln E_k whose weight generalized
   cross-validation chooses, refined end to end on the raw data with the per-sweep table;
   method 'free': NNLS starts at several densities refined with free times
   (:func:`fitting.calibration.prony.refine`), the number of terms by BIC after refinement;
4. both weight storage 5:1 over loss and use a Cauchy loss of scale 0.03 decades (constants
   below);
5. WLF and Arrhenius are always fitted as well, starting from the refined table, end to end;
6. with ``law="auto"`` the candidate with the lowest BIC on the raw data wins (a table costs
   one parameter per sweep, WLF two); the others are reported as alternatives;
7. shear data are converted to tensile with E = 2 (1 + nu) G when ``tensile=True``.
"""
from __future__ import annotations

import dataclasses
import math
import os
import time

import numpy as np

from vjax import checks
from vjax import Material

from fitting.calibration import compact
from fitting.measurements import dma
from fitting.shared import evaluate
from fitting.calibration import io
from fitting.calibration import master, prony
from fitting.measurements import relaxation
from fitting.calibration import spectrum
from fitting.shared.evaluate import tensile_over_shear

__all__ = ["calibrate", "Report"]

# refinement settings (see :func:`fitting.calibration.prony.refine` and :func:`fitting.calibration.spectrum.smooth_fit`):
# storage counts five times as much as loss (the smoother, better-superposing half of DMA data),
# Cauchy loss with scale 0.03 decades (7%: a few inconsistent points, typically loss near the
# glassy plateau, do not bend the fit); method 'free' keeps the relaxation times within the
# data range (E0 stays physical)
WEIGHTS = (5.0, 1.0)
ROBUST = 0.03
FTOL = 1e-5
SCREEN_FTOL = 3e-5     # the term-count candidates; the chosen one is finished at FTOL
TAU_MARGIN = 0.0
CLOSED_FORM = ("WLF", "Arrhenius")


@dataclasses.dataclass
class Report:
    """What a calibration did. Errors are |log10(pred/meas)| on the raw unshifted points
    (median and 90th percentile; storage and loss separately, or the relaxation modulus).

    ``alternatives``: the closed-form shift laws not chosen, each fitted end to end, as
    {law: {constants, 'sigma', 'errors', 'bic', 'delta_log10_aT_vs_table': {'rms', 'max'}}}
    (the material JSON carries it as ``shift_alternatives``). ``smoothing``: the penalty of
    method 'smooth' (criterion, weight, effective parameters, loss-modulus extrema)."""

    terms: int
    law: str
    shift_params: dict
    uncertainty: dict
    errors: dict
    candidates: list
    n_points: int
    n_sets: int
    kind: str
    T_ref: float
    wall_time: float
    iterations: int
    converged: bool
    dropped: int
    data_shift: object = None
    criterion: tuple = ()
    outputs: list = dataclasses.field(default_factory=list)
    method: str = "smooth"
    domain: str = "frequency"
    alternatives: dict = dataclasses.field(default_factory=dict)
    smoothing: dict | None = None
    laws: dict = dataclasses.field(default_factory=dict)
    window: tuple | None = None

    def _law_line(self, law, params, sigma) -> str:
        return f"{law}  " + "  ".join(
            f"{k}={v:.5g}" + (f" +- {sigma[k]:.2g}" if isinstance(sigma.get(k), float) else "")
            for k, v in params.items() if k in ("C1", "C2", "Ea", "T_ref"))

    def table(self) -> str:
        """A plain-text summary table."""
        e = self.errors
        pct = lambda v: f"{(10 ** v - 1) * 100:.1f}%"
        what = "E(t)" if self.domain == "time" else f"{self.kind}' and {self.kind}''"
        how = (f"smooth spectrum, GCV weight {self.smoothing['lam']:.3g}" if self.smoothing else
               "free times, count by BIC") + f", loss modulus with {e['loss_extrema']} extrema over the data"
        lines = [
            f"data            {self.n_points} points, {self.n_sets} temperatures, {what}"
            + (f", {self.dropped} dropped" if self.dropped else ""),
            f"T_ref           {self.T_ref:g} C",
            "shift law       " + (self._law_line(self.law, self.shift_params, self.uncertainty)
                                  if self.law != "table" else f"table of {self.n_sets} factors"),
        ]
        for law, alt in self.alternatives.items():
            d = alt["delta_log10_aT_vs_table"]
            lines.append(f"  alternative   {self._law_line(law, alt, alt['sigma'])}  (rms {d['rms']:.3f}, "
                         f"max {d['max']:.3f} decades from the table; raw-data rms {alt['errors']['rms']:.4f})")
        lines += [
            f"Prony terms     {self.terms}  ({how}; {self.iterations} iterations, "
            f"{'converged' if self.converged else 'NOT converged'})",
            "error |log10(pred/meas)|   median      p90"]
        for part in ("relaxation",) if self.domain == "time" else ("storage", "loss"):
            lines.append(f"  {part:<24s} {e[part + '_median']:.4f} ({pct(e[part + '_median'])})  "
                         f"{e[part + '_p90']:.4f} ({pct(e[part + '_p90'])})")
        lines += ["candidates      " + "; ".join(f"{c['law']}: BIC {c['bic']:.1f}, rms {c['rms']:.4f}"
                                               for c in self.candidates),
                  f"time            {self.wall_time:.2f} s"]
        return "\n".join(lines)

    def save(self, path, material, shift, modulus, **fit_extra) -> None:
        """Write the material JSON (:mod:`fitting.calibration.io`) with this report's errors, the shift-law
        alternatives (``shift_alternatives``) and the smoothing in it, atomically."""
        fit = {"errors": self.errors, "terms": self.terms, "law": self.law, "method": self.method,
               "data_kind": self.kind, "domain": self.domain, "points": self.n_points, **fit_extra}
        if self.smoothing:
            fit["smoothing"] = self.smoothing
        if self.window:
            fit["window_rad_s"] = list(self.window)     # reduced rates of the data at T_ref (fitting.fem.export)
        io.save_material(path, material, shift, modulus=modulus, uncertainty=self.uncertainty, fit=fit,
                         shift_alternatives=self.alternatives)


def convert_modulus(material: Material, factor) -> Material:
    """The Prony material with every modulus multiplied by ``factor`` (e.g.
    :func:`tensile_over_shear` for G -> E, its inverse for E -> G); times and nu kept."""
    return Material.prony(float(material.E0) * factor, np.asarray(material.moduli) * factor,
                          np.asarray(material.times), material.nu)


def _free_fits(table, start, nu, densities, max_iter):
    """The earlier method: free relaxation times, the number of terms by BIC after refinement
    (few terms, but the loss modulus may ring). Returns ({law: PronyFit}, criterion)."""
    wr = table.omega * 10.0 ** evaluate.log10_aT(start, table.T)
    # one NNLS start per density, each refined end-to-end (table law); the number of terms is
    # chosen by BIC after the refinement (not on the linear master-curve fit, whose times are
    # frozen on a grid and which therefore asks for more terms)
    starts = [(d,) + prony.fit_master(wr, table.storage, table.loss, density=d) for d in sorted(densities)]
    # one padded size for all candidates: a single compilation per law
    opts = dict(max_iter=max_iter, weights=WEIGHTS, robust=ROBUST, ftol=FTOL, tau_margin=TAU_MARGIN,
                pad_terms=prony.pad_size(max(len(s[2]) for s in starts)))
    # BIC of the unweighted log residuals (the weighted one would let the down-weighted loss
    # go unresolved and pick too few terms); the shift parameters are common to all candidates.
    # Densities in increasing order; stop once the BIC has risen twice in a row.
    n_obs = 2 * len(table)

    def bic(f):
        return n_obs * math.log(prony.raw_errors(f.material, f.shift, table)["rms"] ** 2) \
            + (2 * f.terms + 1) * math.log(n_obs)
    crit, f_tab, best, worse = [], None, math.inf, 0
    for d, E0, Ek, tau in starts:
        m0 = Material.prony(max(E0, 1e-6 * float(table.storage.min())), Ek, tau, nu)
        f = prony.refine(table, m0, start, **dict(opts, ftol=SCREEN_FTOL))
        b = bic(f)
        crit.append((d, f.terms, b, f.rms))
        if b < best:
            f_tab, best, worse = f, b, 0
        else:
            worse += 1
            if worse >= 2:
                break
    # the candidates were screened with a looser tolerance: finish the chosen one
    fits = {"table": prony.refine(table, f_tab.material, f_tab.shift, **opts)}
    for name in CLOSED_FORM:
        guess, _ = master.fit_law(fits["table"].shift, name)
        fits[name] = prony.refine(table, fits["table"].material, guess, **opts)
    return fits, tuple(crit)


def _smooth_fits(table, start, nu, per_decade, max_terms):
    """Smooth spectrum (:mod:`fitting.calibration.spectrum`): the penalty weight chosen by GCV with the
    per-sweep table, then WLF and Arrhenius refined end to end with that weight from the table
    fit. Returns ({law: PronyFit}, info of the table fit).

    A term cap that would make the grid coarser than one time per decade cannot give a smooth
    loss modulus (each arm's loss peak is about a decade wide, so sparse arms show as bumps);
    frequency data then get ``max_terms`` free relaxation times (:func:`_few_terms`)."""
    data = spectrum.SmoothData.from_table(table)
    opts = dict(per_decade=per_decade, weights=WEIGHTS, robust=ROBUST, nu=nu)
    few = data.domain == "frequency" and max_terms is not None
    # relaxation curves: the per-sweep factors stay those of the overlap (see smooth_fit)
    fit_shift = data.domain == "frequency"
    f_tab, info = spectrum.smooth_fit(data, start, fit_shift=fit_shift, max_terms=None if few else max_terms, **opts)
    g = info["grid"]
    if few and len(g) > max_terms and (g[-1] - g[0]) / (max_terms - 1) <= 1.0:     # a dense capped grid
        few = False
        f_tab, info = spectrum.smooth_fit(data, start, fit_shift=fit_shift, max_terms=max_terms, **opts)
    few = few and len(g) > max_terms
    fits = {"table": f_tab}
    for name in CLOSED_FORM:
        guess, _ = master.fit_law(f_tab.shift, name)
        fits[name], _ = spectrum.smooth_fit(data, guess, lam=info["lam"], start=f_tab, grid=info["grid"], **opts)
    if few:
        fits = {k: _few_terms(table, f, max_terms) for k, f in fits.items()}
        info = dict(info, free_times=True)
    return fits, info


E0_FLOOR = 1e-12     # relative to the glassy modulus: the start of a liquid's log E0 (_few_terms)


def _few_terms(table, fit, n):
    """``n`` terms with free relaxation times from the smooth ``fit``: :func:`fitting.calibration.compact.fit_terms`
    to the points under the fit's law (times within the data's reduced-time window plus
    ``compact.MARGIN_DECADES``), refined end to end with the law (:func:`fitting.calibration.prony.refine`,
    same window). Two starts, times log-spaced from edge to edge of the window and at the
    centres of n equal cells of it; the lower cost is kept (the refinement has local minima,
    some 20 % apart in loss error)."""
    wr = table.omega * 10.0 ** evaluate.log10_aT(fit.shift, table.T)
    m = fit.material
    full = compact.Series(float(m.E0), np.asarray(m.moduli), np.asarray(m.times))
    lo, hi = -math.log10(wr.max()), -math.log10(wr.min())
    liquid = compact.is_liquid(full, float(wr.min()))     # no equilibrium modulus: E0 held near 0
    best = None
    for times in (None, 10.0 ** (lo + (hi - lo) * (np.arange(n) + 0.5) / n)):
        s = compact.fit_terms(full, n, (wr.min(), wr.max()), target=(wr, table.storage, table.loss), times=times,
                              long_term=not liquid, **compact.DATA_FIT)
        # a liquid's E0 is 0 here (no equilibrium modulus); vjax.Material wants E0 > 0 and the
        # refinement works in log E0: it holds E0 at a floor far below the data instead
        E0 = max(s.E0, E0_FLOOR * float(np.sum(s.moduli)))
        f = prony.refine(table, Material.prony(E0, s.moduli, s.times, m.nu), fit.shift, max_iter=300,
                         weights=WEIGHTS, robust=ROBUST, ftol=FTOL, tau_margin=compact.MARGIN_DECADES,
                         fix_E0=liquid)
        best = f if best is None or f.rms < best.rms else best
    return best


def _law_distance(law, table_law, temperatures) -> dict:
    """rms and max |log10 a_T(law) - log10 a_T(table)| over the measured temperatures (decades)."""
    d = evaluate.log10_aT(law, temperatures) - evaluate.log10_aT(table_law, temperatures)
    return {"rms": float(np.sqrt(np.mean(d ** 2))), "max": float(np.max(np.abs(d)))}


def calibrate(paths, T_ref, out_dir=None, *, law="auto", nu=0.5, kind=None, tensile=True, shifts=None,
              drop_nonpositive=False, method="smooth", per_decade=3.0, max_terms=None,
              densities=(0.5, 0.75, 1.0, 1.25, 1.5), max_iter=300, plots_=True, stem="material"):
    """Calibrate a Prony material and shift law from DMA frequency sweeps or relaxation data.

    Args:
      paths: DMA file(s)/directory(ies), see :func:`fitting.measurements.dma.read`, or relaxation-modulus
        files (:mod:`fitting.measurements.relaxation`, detected from the content).
      T_ref: reference temperature (C); need not be a measured one.
      out_dir: if given, writes ``<stem>.json`` and the plots there (atomically).
      law: 'WLF', 'Arrhenius', 'table' or 'auto' (lowest BIC of the three). WLF and Arrhenius
        are always fitted; the ones not chosen are reported as alternatives.
      nu: Poisson's ratio stored in the material (and used for G -> E).
      kind: override 'E'/'G' from the files. tensile: convert shear data to E.
      shifts: user shift factors (a :class:`fitting.calibration.master.ShiftTable` or a CSV path with
        T [C], log10 a_T); used as the start instead of the data overlap.
      method: 'smooth' (relaxation times on a fixed grid at ``per_decade``, smoothness penalty
        chosen by GCV: a loss modulus without ringing, :mod:`fitting.calibration.spectrum`) or 'free'
        (free relaxation times, their number by BIC: fewer terms; frequency data only).
      max_terms: cap on the number of Prony terms ('smooth': the grid gets coarser; where that
        would leave less than one time per decade, frequency data get ``max_terms`` free times
        fitted to the points from the uncapped smooth fit and refined end to end).
      densities: relaxation times per decade tried by the BIC of method 'free'.
    Returns ``(Material, shift, Report)``; the material's moduli are in Pa (tensile E unless
    the data are shear and ``tensile=False``), times in s, at T_ref.
    """
    t0 = time.perf_counter()
    if law not in ("auto", "WLF", "Arrhenius", "table"):
        raise ValueError(f"law must be 'auto', 'WLF', 'Arrhenius' or 'table', got {law!r}")
    if method not in ("smooth", "free"):
        raise ValueError(f"method must be 'smooth' or 'free', got {method!r}")
    if max_terms is not None and not (isinstance(max_terms, int) and max_terms >= 3):
        raise ValueError(f"max_terms must be an integer >= 3, got {max_terms!r}")
    if method == "free" and max_terms is not None:
        raise ValueError("max_terms applies to method 'smooth' (method 'free' chooses its terms by BIC)")
    if not (isinstance(T_ref, (int, float)) and math.isfinite(T_ref)):
        raise ValueError(f"T_ref must be a finite temperature in C, got {T_ref!r}")
    checks.poisson("nu", nu)    # before reading and fitting, not when the material is built
    if relaxation.is_relaxation(paths):
        table = relaxation.read(paths, kind=kind, drop_nonpositive=drop_nonpositive)
        if method == "free":
            raise ValueError("method 'free' fits frequency sweeps; relaxation data use method 'smooth'")
    else:
        table = dma.read(paths, kind=kind, drop_nonpositive=drop_nonpositive)
    if shifts is None:
        # pair shifts from the storage modulus alone (as pyvisco does): in the glassy range the
        # loss often follows a secondary relaxation that does not superpose with the same a_T,
        # and would pin the cold sweeps together; the refinement below uses both moduli
        start = master.shift_factors(table.as_rate_table() if table.domain == "time" else table, float(T_ref),
                                     loss_weight=0.0)
    else:
        start = shifts if isinstance(shifts, master.ShiftTable) else master.read_shift_file(shifts)
        start = master.ShiftTable.make(np.asarray(start.T), np.asarray(start.values), float(T_ref))
        missing = [t for t in table.temperatures if not np.any(np.isclose(np.asarray(start.T), t, atol=0.51))]
        if missing:
            raise ValueError(f"user shift factors lack the measured temperatures {missing} C")
        if table.n_sets < 2 and law != "table":
            raise ValueError("a shift law needs sweeps at two or more temperatures")
    if method == "smooth":
        fits, info = _smooth_fits(table, start, nu, per_decade, max_terms)
        crit = tuple(info["gcv"])
        smoothing = {"criterion": "GCV", "lam": info["lam"], "per_decade": per_decade,
                     "effective_parameters": info["edf"], "free_times": info.get("free_times", False)}
    else:
        fits, crit = _free_fits(table, start, nu, densities, max_iter)
        smoothing = None
    chosen = law if law != "auto" else min(fits, key=lambda k: fits[k].bic)
    fit = fits[chosen]
    mat, shift = fit.material, fit.shift
    errors = table.errors(mat, shift)
    rate = table.omega if table.domain == "frequency" else 1.0 / table.t
    wr = rate * 10.0 ** evaluate.log10_aT(shift, table.T)
    errors["loss_extrema"] = spectrum.loss_extrema(mat, float(wr.min()), float(wr.max()))
    alternatives = {}
    for name in CLOSED_FORM:
        if name != chosen:
            f = fits[name]
            alternatives[name] = dict(io.shift_to_dict(f.shift), sigma=dict(_law_sigma(f.sigma)),
                                      errors=table.errors(f.material, f.shift), bic=f.bic,
                                      delta_log10_aT_vs_table=_law_distance(f.shift, fits["table"].shift,
                                                                            table.temperatures))
    sigma = dict(fit.sigma)
    out_kind = table.kind
    if table.kind == "G" and tensile:
        f = tensile_over_shear(nu)
        mat = convert_modulus(mat, f)
        sigma = {k: (v * f if k == "E0" else [x * f for x in v] if k == "moduli" else v) for k, v in sigma.items()}
        out_kind = "E"
    shift_params = io.shift_to_dict(shift)
    shift_params.pop("law")
    report = Report(terms=fit.terms, law=chosen, shift_params=shift_params, uncertainty=sigma, errors=errors,
                    candidates=[{"law": k, "bic": v.bic, "rms": v.rms, "terms": v.terms} for k, v in fits.items()],
                    n_points=len(table), n_sets=table.n_sets, kind=table.kind, T_ref=float(T_ref),
                    wall_time=0.0, iterations=fit.iterations, converged=fit.converged, dropped=table.dropped,
                    data_shift=fits["table"].shift, criterion=crit, method=method, domain=table.domain,
                    alternatives=alternatives, smoothing=smoothing,
                    laws={k: fits[k].shift for k in CLOSED_FORM}, window=(float(wr.min()), float(wr.max())))
    if out_dir is not None:
        os.makedirs(out_dir, exist_ok=True)
        jpath = os.path.join(out_dir, f"{stem}.json")
        report.save(jpath, mat, shift, out_kind, files=list(table.files))
        report.outputs.append(jpath)
        if plots_:
            from fitting.calibration import figures
            # plots show the data in their own modulus, hence the fitted (unconverted) material
            report.outputs += figures.save_all(out_dir, stem, table, fit.material, shift, fits["table"].shift,
                                               report.laws)
    report.wall_time = time.perf_counter() - t0
    return mat, shift, report


def _law_sigma(sigma):
    return {k: v for k, v in sigma.items() if k in ("C1", "C2", "Ea")}
