"""DMA calibration on the shipped data sets, side by side with pyvisco when it is installed.

For each data set (pyvisco freq_user_raw.csv at T_ref = 25 C; DMA-analysis-suite T0..T105 at
T_ref = 70 C; a TRIOS export at 20 C when ``VJAX_TRIOS_SAMPLE`` names one) this runs
:func:`fitting.calibrate` three ways (the smooth spectrum, the default; the earlier free-time
fit, ``method='free'``; the smooth fit capped at 13 terms) and, if ``import pyvisco`` works, pyvisco's
default pipeline (load.user_raw, master.get_aT, master.get_curve, prony.discretize,
prony.fit(opt=True), opt.nprony) in the same process. Both are scored on the **raw unshifted**
points with each tool's own shift factors: median and 90th percentile of
|log10(predicted/measured)| for storage and loss separately, number of terms, wall time
(steady state, after one warm-up calibration that compiles the JIT kernels; the plots are
drawn outside the timed region, as pyvisco's timed pipeline draws none), the number of local
extrema of the fitted loss modulus over the data's reduced frequencies (ringing), and the WLF
and Arrhenius constants with their one-sigma errors. The relaxation example
(time_user_raw.csv) is fitted by vjax alone.

Writes ``<out_dir>/dma_fit.csv``, ``dma_fit.md`` and the calibration plots. pyvisco is not a
dependency: without it the pyvisco rows are skipped.

    python experiments/studies/dma_fit.py            # or: main(out_dir=..., quick=True)
"""
from __future__ import annotations

import contextlib
import csv
import io as _io
import os
import sys
import time
import warnings

import jax

jax.config.update("jax_enable_x64", True)

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))   # the repository root
from fitting import calibrate  # noqa: E402
from fitting.measurements import dma
from fitting.calibration import figures

DATASETS = [("pyvisco_freq_user_raw", lambda: dma.default_data("pyvisco"), 25.0, {}),
            ("dmasuite_E_0to105C", lambda: dma.default_data("dmasuite"), 70.0, {})]
# a TA TRIOS export that is not shipped (redistribution not cleared): included when the
# environment variable points at a copy (rheojax examples/data/temperature_sweep/polymers/
# frequency_sweep_tts.txt); shear, 20 temperatures -40..150 C, non-positive points dropped
if os.path.isfile(os.environ.get("VJAX_TRIOS_SAMPLE", "")):
    DATASETS.append(("trios_3M468MP", lambda: os.environ["VJAX_TRIOS_SAMPLE"], 20.0, {"drop_nonpositive": True}))
RELAXATION = ("pyvisco_time_user_raw", lambda: os.path.join(os.path.dirname(dma.default_data("pyvisco")),
                                                          "time_user_raw.csv"), 25.0)
CAP = 13   # the term cap Abaqus users often keep


def _score(pred_s, pred_l, meas_s, meas_l):
    rs, rl = np.abs(np.log10(pred_s / meas_s)), np.abs(np.log10(pred_l / meas_l))
    return {"storage_median": float(np.median(rs)), "storage_p90": float(np.percentile(rs, 90)),
            "loss_median": float(np.median(rl)), "loss_p90": float(np.percentile(rl, 90))}


def _pyvisco_csv(table, path):
    """pyvisco's user_raw format (f [Hz], E_stor/E_loss [MPa], T [C], Set) from a DMATable."""
    with open(path, "w") as fh:
        fh.write(f"f,{table.kind}_stor,{table.kind}_loss,T,Set\nHz,MPa,MPa,C,-\n")
        for f, s, l, T, k in zip(table.f, table.storage, table.loss, table.T, table.set):
            fh.write(f"{f:.8g},{s / 1e6:.10g},{l / 1e6:.10g},{T:.6g},{k}\n")


def run_pyvisco(table, T_ref, work):
    """pyvisco's default frequency-domain pipeline; returns a result dict or None."""
    try:
        from pyvisco import load, master, opt, prony
    except Exception:  # not installed (or broken): skip gracefully
        return None
    path = os.path.join(work, "pyvisco_input.csv")
    _pyvisco_csv(table, path)
    warnings.filterwarnings("ignore")
    t0 = time.perf_counter()
    m = table.kind
    df_raw, arr_RefT, units = load.user_raw(load.file(path), "freq", m)
    # pyvisco needs T_ref among its rounded set temperatures: take the nearest one
    RefT = float(arr_RefT.iloc[int(np.argmin(np.abs(arr_RefT.values - T_ref)))])
    with contextlib.redirect_stdout(_io.StringIO()):
        df_aT, _ = master.get_aT(df_raw, RefT)
        df_master = master.smooth(master.get_curve(df_raw, df_aT, RefT), 1)
        df_dis = prony.discretize(df_master, "round")
        pr, _ = prony.fit(df_dis, df_master, opt=True)
        dict_prony, N, _ = opt.nprony(df_master, pr, opt=1.5)
    wall = time.perf_counter() - t0
    p = dict_prony[N]
    E_inst, a, tau = p["E_0"], p["df_terms"]["alpha_i"].values, p["df_terms"]["tau_i"].values
    logaT = df_raw["T_round"].map(dict(zip(df_aT["T"], df_aT["log_aT"]))).values
    w = 2 * np.pi * df_raw["f_set"].values * 10 ** logaT
    A = w[:, None] * tau
    st = E_inst * (1 - a.sum()) + (E_inst * a * A ** 2 / (1 + A ** 2)).sum(1)
    lo = (E_inst * a * A / (1 + A ** 2)).sum(1)
    res = _score(st, lo, df_raw[f"{m}_stor"].values, df_raw[f"{m}_loss"].values)
    from fitting.calibration.spectrum import count_extrema
    ww = np.logspace(np.log10(w.min()), np.log10(w.max()), 4096)[:, None] * tau
    res["loss_extrema"] = count_extrema((E_inst * a * ww / (1 + ww ** 2)).sum(1))
    res.update(tool="pyvisco", terms=int(N), wall_time=wall, T_ref=RefT, law="table (pyvisco aT)",
               E_rubbery_MPa=float(E_inst * (1 - a.sum())))
    return res


def _law_text(rep, law):
    """'C1 = .. +- .., C2 = .. +- ..' or 'Ea = .. +- .. kJ/mol' of the WLF/Arrhenius fit."""
    if rep.law == law:
        p, sig = rep.shift_params, rep.uncertainty
    elif law in rep.alternatives:
        p, sig = rep.alternatives[law], rep.alternatives[law]["sigma"]
    else:
        return ""
    if law == "WLF":
        return f"C1 = {p['C1']:.4g} +- {sig.get('C1', float('nan')):.2g}, C2 = {p['C2']:.4g} +- {sig.get('C2', float('nan')):.2g} K"
    return f"Ea = {p['Ea'] / 1e3:.4g} +- {sig.get('Ea', float('nan')) / 1e3:.2g} kJ/mol"


def _vjax_row(name, tool, rep, wall, T_ref):
    e = rep.errors
    alt = rep.alternatives
    best = min(alt.items(), key=lambda kv: kv[1]["delta_log10_aT_vs_table"]["rms"], default=(None, None))
    return dict(dataset=name, tool=tool, terms=rep.terms, loss_extrema=e["loss_extrema"], wall_time=wall, T_ref=T_ref,
                law=rep.law, WLF=_law_text(rep, "WLF"), Arrhenius=_law_text(rep, "Arrhenius"),
                closed_form_vs_table=(f"{best[0]}: rms {best[1]['delta_log10_aT_vs_table']['rms']:.3f} dec"
                                      if rep.law == "table" and best[0] else ""),
                **{k: e[k] for k in ("storage_median", "storage_p90", "loss_median", "loss_p90") if k in e})


def main(out_dir="experiments/out", quick=False):
    """Every data set (``quick``: the first only): vjax's smooth fit (default), the earlier
    free-time fit, a 13-term capped fit, and pyvisco; plus vjax on the relaxation example.
    Writes CSV + markdown + PNGs, returns the rows."""
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for name, get_path, T_ref, kw in DATASETS[:1] if quick else DATASETS:
        path = get_path()
        table = dma.read(path, **kw)
        # calibrate once to compile (JIT), then time a second run: steady-state cost
        if not quick:
            calibrate(path, T_ref, **kw)
        # timed: reading, shifting, fitting and the material JSON; the plots are written after
        # the clock stops (pyvisco's timed pipeline draws none either)
        t0 = time.perf_counter()
        # tensile=False: a shear data set keeps its G (plots and errors in the data's own modulus)
        mat, shift, rep = calibrate(path, T_ref, os.path.join(out_dir, name), stem=name, plots_=False, tensile=False,
                                    **kw)
        wall = time.perf_counter() - t0
        figures.save_all(os.path.join(out_dir, name), name, table, mat, shift, rep.data_shift, rep.laws)
        rows.append(_vjax_row(name, "vjax smooth (default)", rep, wall, T_ref))
        print(f"[{name}] vjax smooth: {rep.terms} terms, {wall:.2f} s\n{rep.table()}", flush=True)
        for tool, opts in (("vjax free times (before)", dict(method="free")),
                           (f"vjax smooth, max {CAP} terms", dict(max_terms=CAP))):
            if quick:
                continue
            t0 = time.perf_counter()
            _, _, r = calibrate(path, T_ref, **opts, **kw)
            rows.append(_vjax_row(name, tool, r, time.perf_counter() - t0, T_ref))
            print(f"[{name}] {tool}: {r.terms} terms, loss-modulus extrema {r.errors['loss_extrema']}", flush=True)
        pv = run_pyvisco(table, T_ref, out_dir)
        if pv is not None:
            pv["dataset"] = name
            rows.append(pv)
            print(f"[{name}] pyvisco: {pv['terms']} terms, {pv['wall_time']:.2f} s, loss-modulus extrema "
                  f"{pv['loss_extrema']}, storage median {pv['storage_median']:.4f}, loss median {pv['loss_median']:.4f}")
        else:
            print(f"[{name}] pyvisco not installed: comparison skipped")
    if not quick:
        name, get_path, T_ref = RELAXATION
        t0 = time.perf_counter()
        mat, shift, rep = calibrate(get_path(), T_ref, os.path.join(out_dir, name), stem=name)
        row = _vjax_row(name, "vjax smooth (relaxation data)", rep, time.perf_counter() - t0, T_ref)
        row.update(storage_median=rep.errors["relaxation_median"], storage_p90=rep.errors["relaxation_p90"])
        rows.append(row)
        print(f"[{name}] vjax smooth on E(t) (errors in the storage columns):\n{rep.table()}")
    cols = ["dataset", "tool", "terms", "loss_extrema", "storage_median", "storage_p90", "loss_median", "loss_p90",
            "wall_time", "T_ref", "law", "WLF", "Arrhenius", "closed_form_vs_table"]
    # written atomically (temporary file + os.replace): a crash never leaves half a report
    from experiments import _common
    fh = _io.StringIO()
    w = csv.DictWriter(fh, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: r.get(k) for k in cols})
    _common.atomic_write_text(os.path.join(out_dir, "dma_fit.csv"), fh.getvalue())
    md = ("Errors |log10(pred/meas)| on the raw points; loss_extrema: local extrema of the fitted E'' over the "
          "data's reduced frequencies; relaxation data: errors of E(t) in the storage columns.\n\n")
    md += "| " + " | ".join(cols) + " |\n|" + "---|" * len(cols) + "\n"
    for r in rows:
        md += "| " + " | ".join(f"{r.get(k):.4g}" if isinstance(r.get(k), float) else str(r.get(k, ""))
                                for k in cols) + " |\n"
    _common.atomic_write_text(os.path.join(out_dir, "dma_fit.md"), md)
    print(md)
    return rows


if __name__ == "__main__":
    main()
