"""How many Prony terms does a smooth loss modulus take? (issue 26)

For each shipped data set (the WLF fits of :mod:`experiments.studies.fem_export`): the decades of the
data's reduced window over which the full smooth fit's log-log loss slope is below 0.07 (where
a Maxwell sum 1 decade apart, ripple slope 0.15, adds extrema), then for n = 20 .. 60 the
series :func:`fitting.calibration.compact.placed_terms` (times placed by the ripple rule, moduli by NNLS on
the full fit) and, at 20, :func:`fitting.calibration.compact.fit_terms` to the DMA points (free times):
loss-modulus extrema over the window and storage / loss medians on the DMA points against the
full fit's. Printed: the fewest n with at most max(3, the full fit's) extrema and both medians
within 1.5x.

    python -m experiments.studies.compact_ripple [out_dir]
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))   # the repository root
from fitting.calibration import compact  # noqa: E402
from fitting.shared import evaluate
from fitting.fem import export


def main(out_dir="experiments/out"):
    import jax
    jax.config.update("jax_enable_x64", True)
    from experiments.studies.fem_export import DATASETS, NU, _fit
    os.makedirs(out_dir, exist_ok=True)
    for i, (name, paths, T_ref) in enumerate(DATASETS):
        path, _ = _fit(paths, T_ref, out_dir, f"ripple_{i}")
        m = export.load(path, nu=NU)
        targets, errors_of, (lo, hi) = export.data_points(m)
        ref = errors_of(m.series)
        keys = [k for k in ("storage_median", "loss_median", "relaxation_median") if k in ref]
        x = np.linspace(math.log10(lo), math.log10(hi), 4000)
        slope = np.gradient(np.log10(evaluate.loss(m.series, 10.0 ** x)), x)
        limit = max(3, evaluate.loss_extrema(m.series, lo, hi))
        print(f"{name}: {math.log10(hi / lo):.1f} decades, |loss slope| < 0.07 over "
              f"{np.mean(np.abs(slope) < 0.07) * math.log10(hi / lo):.1f}; extrema limit {limit}")

        def row(kind, s):
            e, ext = errors_of(s), evaluate.loss_extrema(s, lo, hi)
            ok = ext <= limit and all(e[k] <= 1.5 * ref[k] for k in keys)
            print(f"  {kind:7s} n = {len(s.times)}: {ext} extrema; "
                  + ", ".join(f"{k.split('_')[0]} {e[k] / ref[k]:.2f}x" for k in keys))
            return ok
        row("free", compact.fit_terms(m.series, 20, (lo, hi), target=targets, **compact.DATA_FIT))
        for n in range(20, 61):
            if row("placed", compact.placed_terms(m.series, n, (lo, hi))) or n == 60:
                break


if __name__ == "__main__":
    main(*sys.argv[1:])
