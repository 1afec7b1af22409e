"""FEM export on every shipped data set: term counts, accuracy, and pyvisco at its own counts.

For each data set (pyvisco's Eplexor .xls raw export and user CSV at T_ref = 25 C, its
relaxation example, DMA-analysis-suite T0..T105 at 70 C): vjax-fit's calibration (WLF,
nu = 0.45), then what ``vjax-export`` writes by default:

* the compact series for Abaqus, ANSYS and COMSOL (:func:`fitting.fem.export.prepare`), the
  default (smooth) and capped at 20 terms (``--max-terms 20``): terms, median
  |log10(model/measured)| of storage and loss on the raw points against the full smooth
  fit's, loss-modulus extrema over the data's reduced range;
* LS-DYNA's six cards (5 terms + G_inf) over the data's window: deviation from the full fit.

Then, where ``import pyvisco`` works (``pip install pyvisco``; it is in the ``experiments``
extra), pyvisco's default pipeline on the same frequency data in the same run (its own
master curve and term count N, :func:`experiments.studies.dma_fit.run_pyvisco`), and vjax at N terms:
the compact refit (:func:`fitting.calibration.compact.fit_terms` to the DMA points) of the table-law fit
(one shift factor per temperature, as pyvisco's) and of the WLF fit, and ``vjax-fit
--max-terms N`` (WLF, end to end). Each scored with its own shift factors on the raw points. Writes ``<out_dir>/fem_export.md``.

    python -m experiments.studies.fem_export [out_dir]
"""
from __future__ import annotations

import os
import sys
import time

import jax

jax.config.update("jax_enable_x64", True)

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))   # the repository root
from fitting import calibrate  # noqa: E402
from fitting.calibration import compact
from fitting.measurements import dma
from fitting.shared import evaluate
from fitting.fem import export
from fitting.fem.export import CARD_LIMIT  # noqa: E402

HERE = os.path.dirname(dma.default_data("pyvisco"))
DATASETS = [("pyvisco Eplexor raw (.xls)", [os.path.join(HERE, "freq_Eplexor_raw.xls")], 25.0),
            ("pyvisco user raw (.csv)", [dma.default_data("pyvisco")], 25.0),
            ("pyvisco relaxation E(t)", [os.path.join(HERE, "time_user_raw.csv")], 25.0),
            ("dmasuite E 0-105 C", [dma.default_data("dmasuite")], 70.0)]
NU = 0.45


def _fit(paths, T_ref, out_dir, stem, max_terms=None):
    mat, shift, rep = calibrate(paths, T_ref, law="WLF", nu=NU, max_terms=max_terms)
    path = os.path.join(out_dir, stem + ".json")
    rep.save(path, mat, shift, "E", files=[os.path.abspath(p) for p in paths])
    return path, rep


def main(out_dir="experiments/out"):
    os.makedirs(out_dir, exist_ok=True)
    rows, pv_rows = [], []
    for i, (name, paths, T_ref) in enumerate(DATASETS):
        t0 = time.perf_counter()
        path, rep = _fit(paths, T_ref, out_dir, f"fem_{i}")
        m = export.load(path, nu=NU)
        notes = []
        t1 = time.perf_counter()
        c = export.prepare(m, "compact", messages=notes)
        t_compact = time.perf_counter() - t1
        c20 = export.prepare(m, "compact", 20)
        data = export.data_points(m)
        window = data[2]
        # six cards over the data's whole window, asked for explicitly (without --window the
        # export refuses it: docs/fem_export.md, python -m experiments.studies.fem_cards)
        ls = export.prepare(m, "full", None, (1.0 / window[1], 1.0 / window[0]), CARD_LIMIT["lsdyna"], notes)
        e_full = data[1](m.series)
        dev = compact.deviation(ls.series, m.series, window)
        keys = [k for k in ("storage_median", "loss_median", "relaxation_median") if k in e_full]
        for tag, cc in (("", c), (" (--max-terms 20)", c20)):
            e_cc = data[1](cc.series)
            rows.append((name + tag, len(m.G), len(cc.G), {k: (e_full[k], e_cc[k]) for k in keys},
                         rep.errors["loss_extrema"], compact.loss_extrema(cc.series, *window),
                         np.log10(window[1] / window[0]), dev, t_compact))
        print(f"[{name}] fit {time.perf_counter() - t0:.1f} s; " + " | ".join(notes))
        if rep.domain != "frequency":
            continue
        from experiments.studies.dma_fit import run_pyvisco
        table = dma.read(paths)
        pv = run_pyvisco(table, T_ref, out_dir)
        if pv is None:
            print(f"[{name}] pyvisco not installed: comparison skipped")
            continue
        N = pv["terms"]
        s_n = compact.fit_terms(m.series, N, window, target=data[0], **compact.DATA_FIT)
        e_n = data[1](s_n)
        _, rep_n = _fit(paths, T_ref, out_dir, f"fem_{i}_n{N}", max_terms=max(N, 3))
        # the same kind of shift as pyvisco's (one factor per temperature): the table-law fit, compacted
        mat_t, law_t, _ = calibrate(paths, T_ref, law="table", nu=NU)
        wr_t = table.omega * 10.0 ** evaluate.log10_aT(law_t, table.T)
        full_t = compact.Series(float(mat_t.E0), np.asarray(mat_t.moduli), np.asarray(mat_t.times))
        s_t = compact.fit_terms(full_t, N, (wr_t.min(), wr_t.max()), target=(wr_t, table.storage, table.loss),
                                **compact.DATA_FIT)
        e_t = evaluate.errors_at(s_t, wr_t, table.storage, table.loss)
        pv_rows.append((name, N, pv, e_n, rep_n.errors, rep_n.terms, e_t))
    lines = ["# FEM export: term counts and accuracy per data set (WLF, nu = 0.45)", "",
             "median \\|log10(model/measured)\\| on the raw points, full smooth fit -> compact series",
             "", "| data set | full terms | compact terms | storage | loss | E(t) | loss extrema full / compact "
             "| window (decades) | LS-DYNA 6 cards: median deviation from full fit, storage / loss | compact time |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for name, nf, nc, e, xf, xc, dec, dev, tc in rows:
        cell = lambda k: f"{e[k][0]:.4f} -> {e[k][1]:.4f} ({e[k][1] / e[k][0]:.2f}x)" if k in e else ""  # noqa: E731
        lines.append(f"| {name} | {nf} | {nc} | {cell('storage_median')} | {cell('loss_median')} | "
                     f"{cell('relaxation_median')} | {xf} / {xc} | {dec:.1f} | "
                     f"{dev['storage_median']:.3f} / {dev['loss_median']:.3f} | {tc:.2f} s |")
    if pv_rows:
        lines += ["", "## pyvisco at its own term count N (same data, same run; each with its own shift factors)", "",
                  "| data set | N | pyvisco (its shift table) storage / loss | vjax compact at N, table shift "
                  "| vjax compact at N, WLF | vjax-fit --max-terms N, WLF |", "|---|---|---|---|---|---|"]
        for name, N, pv, e_n, e_fit, nfit, e_t in pv_rows:
            lines.append(f"| {name} | {N} | {pv['storage_median']:.4f} / {pv['loss_median']:.4f} | "
                         f"{e_t['storage_median']:.4f} / {e_t['loss_median']:.4f} | "
                         f"{e_n['storage_median']:.4f} / {e_n['loss_median']:.4f} | "
                         f"{e_fit['storage_median']:.4f} / {e_fit['loss_median']:.4f} ({nfit} terms) |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "fem_export.md"), "w") as fh:
        fh.write(text)
    print(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
