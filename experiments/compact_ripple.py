"""Can 20 Prony terms give a loss modulus with at most 3 local extrema over the data? (issue 26)

For each shipped data set (the WLF fits of :mod:`experiments.fem_export`): the smooth fit's
log-loss slope s(x) and curvature s'(x) over the data's reduced window (x = log10 omega), and
relaxation times placed by the ripple model of a Maxwell sum: terms h decades apart leave a
relative ripple 2 sech(pi^2 / (h ln 10)) in E'', whose slope (amplitude a1(h)) and slope
derivative (a2(h)) must not beat the true ones, (s/a1)^2 + (s'/a2)^2 > 1; the local spacing is
the largest h that satisfies it (dense where log E'' is flat, coarse where it is steep), the
times are its N quantiles, the moduli non-negative least squares on the full fit's storage and
loss. Printed: the term count the model asks for, and the fewest N (adaptive and uniform
grids) whose series has at most max(3, the full fit's) extrema with storage and loss medians
on the DMA points within 1.5x of the full fit's.

    python -m experiments.compact_ripple [out_dir]
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fitting import compact, evaluate, export, optim  # noqa: E402

LN10 = math.log(10.0)
H = np.linspace(0.15, 3.0, 800)                              # spacings tried, decades
A1 = 2.0 / np.cosh(np.pi ** 2 / (H * LN10)) / LN10 * (2 * np.pi / H)
A2 = A1 * (2 * np.pi / H)


def spacing(s, sp):
    ok = (s[:, None] / A1) ** 2 + (sp[:, None] / A2) ** 2 > 1.0
    return np.where(ok, H, 0.0).max(axis=1).clip(H[0])


def nnls_series(full, log10_w, window):
    w = np.logspace(math.log10(window[0]), math.log10(window[1]), 400)
    tau = np.sort(10.0 ** -np.asarray(log10_w))
    z = w[:, None] * tau
    ps, pl = z * z / (1 + z * z), z / (1 + z * z)
    st, ls = evaluate.modulus(full, w).real, evaluate.loss(full, w)
    A = np.vstack([np.hstack([np.ones((len(w), 1)), ps]) / st[:, None],
                   np.hstack([np.zeros((len(w), 1)), pl]) / ls[:, None]])
    x, _ = optim.nnls(A, np.ones(A.shape[0]))
    return compact.Series(float(x[0]), x[1:], tau)


def main(out_dir="experiments/out"):
    import jax
    jax.config.update("jax_enable_x64", True)
    from experiments.fem_export import DATASETS, NU, _fit
    os.makedirs(out_dir, exist_ok=True)
    for i, (name, paths, T_ref) in enumerate(DATASETS):
        path, _ = _fit(paths, T_ref, out_dir, f"ripple_{i}")
        m = export.load(path, nu=NU)
        targets, errors_of, (lo, hi) = export.data_points(m)
        ref = errors_of(m.series)
        keys = [k for k in ("storage_median", "loss_median", "relaxation_median") if k in ref]
        x = np.linspace(math.log10(lo) - 0.5, math.log10(hi) + 0.5, int(50 * (math.log10(hi / lo) + 1)))
        s = np.gradient(np.log10(evaluate.loss(m.series, 10.0 ** x)), x)
        rho = 1.0 / spacing(s, np.gradient(s, x))
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (rho[1:] + rho[:-1]) * np.diff(x))])
        limit = max(3, evaluate.loss_extrema(m.series, lo, hi))
        print(f"{name}: {math.log10(hi / lo):.1f} decades, ripple model asks for {cum[-1]:.0f} terms")
        for kind in ("adaptive", "uniform"):
            for N in range(20, 81, 2):
                g = (np.interp((np.arange(N) + 0.5) / N, cum / cum[-1], x) if kind == "adaptive"
                     else np.linspace(x[0], x[-1], N))
                ser = nnls_series(m.series, g, (lo, hi))
                e, ext = errors_of(ser), evaluate.loss_extrema(ser, lo, hi)
                if N == 20 or (ext <= limit and all(e[k] <= 1.5 * ref[k] for k in keys)):
                    print(f"  {kind:8s} N = {N}: {ext} extrema (limit {limit}); "
                          + ", ".join(f"{k.split('_')[0]} {e[k] / ref[k]:.2f}x" for k in keys))
                if ext <= limit and all(e[k] <= 1.5 * ref[k] for k in keys):
                    break


if __name__ == "__main__":
    main(*sys.argv[1:])
