"""One-call calibration: DMA files -> Prony material + shift law (+ JSON and plots).

:func:`calibrate` chains the steps of :mod:`fitting.dma`, :mod:`fitting.master` and
:mod:`fitting.prony`:

1. read the files (:func:`fitting.dma.read`);
2. shift factors per sweep from the overlap of the storage curves (or the user's table);
3. Prony starts on the master curve (NNLS, one per density of relaxation times), each refined
   end-to-end on the raw data with a per-sweep shift table; the number of terms is the
   candidate with the lowest BIC after refinement;
4. (the refinement weights storage 3:1 over loss, uses a Cauchy loss of scale 0.03 decades and
   keeps the relaxation times within half a decade of the data, see the constants below);
5. WLF and/or Arrhenius fitted to the refined table and refined end-to-end again;
6. with ``law="auto"`` the candidate with the lowest BIC on the raw data wins (a table costs
   one parameter per sweep, WLF two);
7. shear data are converted to tensile with E = 2 (1 + nu) G when ``tensile=True``.
"""
from __future__ import annotations

import dataclasses
import math
import os
import time

import numpy as np

from vjax import _checks
from vjax.material import Material

from . import dma, io, master, plots, prony

__all__ = ["calibrate", "Report"]

# refinement settings (see :func:`fitting.prony.refine`): storage counts three times as much as
# loss (the smoother, better-superposing half of DMA data), Cauchy loss with scale 0.03 decades
# (7%: a few inconsistent points, typically loss near the glassy plateau, do not bend the
# fit), relaxation times within half a decade of the data range (E0 stays physical)
WEIGHTS = (5.0, 1.0)
ROBUST = 0.03
FTOL = 1e-5
SCREEN_FTOL = 3e-5     # the term-count candidates; the chosen one is finished at FTOL
TAU_MARGIN = 0.0


@dataclasses.dataclass
class Report:
    """What a calibration did. Errors are |log10(pred/meas)| on the raw unshifted points
    (median and 90th percentile, storage and loss separately)."""

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

    def table(self) -> str:
        """A plain-text summary table."""
        e = self.errors
        pct = lambda v: f"{(10 ** v - 1) * 100:.1f}%"
        lines = [
            f"data            {self.n_points} points, {self.n_sets} temperatures, {self.kind}' and {self.kind}''"
            + (f", {self.dropped} dropped" if self.dropped else ""),
            f"T_ref           {self.T_ref:g} C",
            f"shift law       {self.law}  " + "  ".join(
                f"{k}={v:.5g}" + (f" +- {self.uncertainty[k]:.2g}" if isinstance(self.uncertainty.get(k), float) else "")
                for k, v in self.shift_params.items() if not isinstance(v, list)),
            f"Prony terms     {self.terms}  (BIC after refinement on raw data; {self.iterations} iterations, "
            f"{'converged' if self.converged else 'NOT converged'})",
            "error |log10(pred/meas)|   median      p90",
            f"  storage                  {e['storage_median']:.4f} ({pct(e['storage_median'])})  "
            f"{e['storage_p90']:.4f} ({pct(e['storage_p90'])})",
            f"  loss                     {e['loss_median']:.4f} ({pct(e['loss_median'])})  "
            f"{e['loss_p90']:.4f} ({pct(e['loss_p90'])})",
            "candidates      " + "; ".join(f"{c['law']}: BIC {c['bic']:.1f}, rms {c['rms']:.4f}" for c in self.candidates),
            f"time            {self.wall_time:.2f} s",
        ]
        return "\n".join(lines)


def tensile_over_shear(nu) -> float:
    """E / G = 2 (1 + nu) for an isotropic material with constant Poisson ratio ``nu``."""
    return 2.0 * (1.0 + float(nu))


def convert_modulus(material: Material, factor) -> Material:
    """The Prony material with every modulus multiplied by ``factor`` (e.g.
    :func:`tensile_over_shear` for G -> E, its inverse for E -> G); times and nu kept."""
    return Material.prony(float(material.E0) * factor, np.asarray(material.moduli) * factor,
                          np.asarray(material.times), material.nu)


def calibrate(paths, T_ref, out_dir=None, *, law="auto", nu=0.5, kind=None, tensile=True, shifts=None,
              drop_nonpositive=False, densities=(0.5, 0.75, 1.0, 1.25, 1.5), max_iter=300, plots_=True,
              stem="material"):
    """Calibrate a Prony material and shift law from DMA frequency sweeps.

    Args:
      paths: DMA file(s)/directory(ies), see :func:`fitting.dma.read`.
      T_ref: reference temperature (C); need not be a measured one.
      out_dir: if given, writes ``<stem>.json`` and the plots there (atomically).
      law: 'WLF', 'Arrhenius', 'table' or 'auto' (lowest BIC among WLF and table).
      nu: Poisson's ratio stored in the material (and used for G -> E).
      kind: override 'E'/'G' from the files. tensile: convert shear data to E.
      shifts: user shift factors (a :class:`fitting.master.ShiftTable` or a CSV path with
        T [C], log10 a_T); used as the start instead of the data overlap.
      densities: Prony relaxation times per decade tried by the BIC.
    Returns ``(Material, shift, Report)``; the material's moduli are in Pa (tensile E unless
    the data are shear and ``tensile=False``), times in s, at T_ref.
    """
    t0 = time.perf_counter()
    if law not in ("auto", "WLF", "Arrhenius", "table"):
        raise ValueError(f"law must be 'auto', 'WLF', 'Arrhenius' or 'table', got {law!r}")
    if not (isinstance(T_ref, (int, float)) and math.isfinite(T_ref)):
        raise ValueError(f"T_ref must be a finite temperature in C, got {T_ref!r}")
    _checks.poisson("nu", nu)    # before reading and fitting, not when the material is built
    table = dma.read(paths, kind=kind, drop_nonpositive=drop_nonpositive)
    if shifts is None:
        # pair shifts from the storage modulus alone (as pyvisco does): in the glassy range the
        # loss often follows a secondary relaxation that does not superpose with the same a_T,
        # and would pin the cold sweeps together; the refinement below uses both moduli
        start = master.shift_factors(table, float(T_ref), loss_weight=0.0)
    else:
        start = shifts if isinstance(shifts, master.ShiftTable) else master.read_shift_file(shifts)
        start = master.ShiftTable.make(np.asarray(start.T), np.asarray(start.values), float(T_ref))
        missing = [t for t in table.temperatures if not np.any(np.isclose(np.asarray(start.T), t, atol=0.51))]
        if missing:
            raise ValueError(f"user shift factors lack the measured temperatures {missing} C")
        if table.n_sets < 2 and law != "table":
            raise ValueError("a shift law needs sweeps at two or more temperatures")
    wr = table.omega * 10.0 ** np.asarray(start.log10_aT(table.T))
    # one NNLS start per density, each refined end-to-end (table law); the number of terms is
    # chosen by BIC after the refinement (not on the linear master-curve fit, whose times are
    # frozen on a grid and which therefore asks for more terms)
    starts = [(d,) + prony.fit_master(wr, table.storage, table.loss, density=d) for d in sorted(densities)]
    # one padded size for all candidates: a single compilation per law
    opts = dict(max_iter=max_iter, weights=WEIGHTS, robust=ROBUST, ftol=FTOL, tau_margin=TAU_MARGIN,
                pad_terms=prony._pad_size(max(len(s[2]) for s in starts)))
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
    crit = tuple(crit)
    # the candidates were screened with a looser tolerance: finish the chosen one
    f_tab = prony.refine(table, f_tab.material, f_tab.shift, **opts)

    fits = {"table": f_tab}
    todo = {"auto": ["WLF"], "WLF": ["WLF"], "Arrhenius": ["Arrhenius"], "table": []}[law]
    for name in todo:
        guess, _ = master.fit_law(f_tab.shift, name)
        fits[name] = prony.refine(table, f_tab.material, guess, **opts)
    chosen = law if law != "auto" else min(fits, key=lambda k: fits[k].bic)
    fit = fits[chosen]
    mat, shift = fit.material, fit.shift
    errors = prony.raw_errors(mat, shift, table)
    sigma = dict(fit.sigma)
    out_kind = table.kind
    if table.kind == "G" and tensile:
        f = tensile_over_shear(nu)
        mat = convert_modulus(mat, f)
        sigma = {k: (v * f if k == "E0" else [x * f for x in v] if k == "moduli" else v) for k, v in sigma.items()}
        out_kind = "E"
    shift_params = io._shift_to_dict(shift)
    shift_params.pop("law")
    report = Report(terms=fit.terms, law=chosen, shift_params=shift_params, uncertainty=sigma, errors=errors,
                    candidates=[{"law": k, "bic": v.bic, "rms": v.rms, "terms": v.terms} for k, v in fits.items()],
                    n_points=len(table), n_sets=table.n_sets, kind=table.kind, T_ref=float(T_ref),
                    wall_time=0.0, iterations=fit.iterations, converged=fit.converged, dropped=table.dropped,
                    data_shift=f_tab.shift, criterion=crit)
    if out_dir is not None:
        os.makedirs(out_dir, exist_ok=True)
        jpath = os.path.join(out_dir, f"{stem}.json")
        io.save_material(jpath, mat, shift, modulus=out_kind, uncertainty=sigma,
                         fit={"errors": errors, "terms": fit.terms, "law": chosen, "data_kind": table.kind,
                              "files": list(table.files), "points": len(table)})
        report.outputs.append(jpath)
        if plots_:
            # plots show the data in their own modulus, hence the fitted (unconverted) material
            report.outputs += plots.save_all(out_dir, stem, table, fit.material, shift, f_tab.shift)
    report.wall_time = time.perf_counter() - t0
    return mat, shift, report
