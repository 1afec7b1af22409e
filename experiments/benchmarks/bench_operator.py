"""Benchmark of the FFT ring operator (issue 2): apply, build the symbol, dense baseline.

Run::

    PYTHONPATH=. python -m experiments.benchmarks.bench_operator [out_dir] [--quick]

For N = 2^8 ... 2^16 elements (hole kernel, R = 0.08 m, omega = 100 rad/s) it times, on the
default JAX device, in float64:

- ``apply``: one operator application u = op(sigma) (one rfft + one irfft), jitted;
- ``symbol``: building the Fourier symbol, ``ring_operator("hole", material, R, N, omega,
  memory=...).symbol`` jitted with the material and omega as traced arguments, for memory
  "periodic" and "thesis" (the latter includes the creep-spectrum bisection);
- ``dense``: the baseline, a jitted dense matrix-vector product M @ sigma with the N x N
  matrix ``op.dense()`` precomputed (N <= 2^12; O(N^2) time and memory), and the largest
  relative difference between the FFT and dense results.

Each time is the median of warm calls ending in ``block_until_ready`` (see
:func:`experiments._common.time_fn`); the first call (trace + compile + one run) is reported
separately as ``*_first_s``. Small-N times include JAX's Python dispatch overhead (about 7 us
here) and a fixed cost of XLA's CPU FFT call (about 40 us per rfft/irfft pair on this
machine): that is what a caller sees per call.

Material (:func:`prony30`): 30-term Prony series, E0 = 1 MPa, tau_k log-spaced from
1e-8 s to 1e6 s, E_k proportional to tau_k**-0.3 with sum E_k = 999 MPa, nu = 0.5.

Outputs (in ``out_dir``): ``bench_operator.csv``, ``bench_operator.png``,
``bench_operator.txt`` (the printed table).
"""
from __future__ import annotations

import os
import platform
import sys

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

R = 0.08          # m
OMEGA = 100.0     # rad/s
KIND = "hole"


def prony30():
    """The 30-term Prony material of the module docstring."""
    times = np.logspace(-8, 6, 30)
    w = times ** -0.3
    return vjax.Material.prony(1e6, (1e9 - 1e6) * w / w.sum(), times, 0.5)


@jax.jit
def _apply(op, sigma):
    return op(sigma)


@jax.jit
def _dense(op):
    return op.dense()


@jax.jit
def _matvec(M, sigma):
    return M @ sigma


def _symbol_fn(n, memory):
    """Jitted (material, omega) -> symbol for a fixed static N and memory model."""
    return jax.jit(lambda mat, omega: vjax.ring_operator(KIND, mat, R, n, omega=omega, memory=memory).symbol)


def run(exponents, repeats, dense_max, material=None):
    """Time everything for N = 2**e, e in ``exponents``; returns (header, rows)."""
    material = prony30() if material is None else material
    omega = jnp.asarray(OMEGA)
    rng = np.random.default_rng(0)
    header = ["N", "apply_median_s", "apply_first_s", "symbol_periodic_median_s", "symbol_periodic_first_s",
              "symbol_thesis_median_s", "symbol_thesis_first_s", "dense_matvec_median_s",
              "dense_matvec_first_s", "fft_vs_dense_max_rel_diff"]
    rows = []
    for e in exponents:
        n = 2 ** e
        sigma = jnp.asarray(rng.random(n))
        # Symbols first: the jitted builder also gives the operator (an eager ring_operator
        # call would compile op by op, slower than everything timed here).
        sym = []
        for memory in ("periodic", "thesis"):
            fn = _symbol_fn(n, memory)
            sym += _common.time_fn(fn, material, omega, repeats=max(3, repeats // 3))[::-1]
            if memory == "periodic":
                op = vjax.RingOperator(fn(material, omega), n)
        row = [n, *_common.time_fn(_apply, op, sigma, repeats=repeats)[::-1], *sym]
        if n <= dense_max:
            M = jax.block_until_ready(_dense(op))
            first, med = _common.time_fn(_matvec, M, sigma, repeats=max(3, repeats // 3))
            u_fft, u_dense = np.asarray(_apply(op, sigma)), np.asarray(_matvec(M, sigma))
            diff = float(np.max(np.abs(u_fft - u_dense)) / np.max(np.abs(u_dense)))
            row += [med, first, diff]
            del M
        else:
            row += [float("nan")] * 3
        rows.append(row)
    return header, rows


def plot(header, rows, path, dpi, note):
    a = np.array(rows, dtype=float)
    col = {h: a[:, i] for i, h in enumerate(header)}
    N = col["N"]
    fig, ax = plt.subplots(figsize=(9, 6.5), layout="constrained")
    series = [("apply_median_s", "apply op(sigma): rfft + irfft", "o-", "tab:blue"),
              ("symbol_periodic_median_s", 'build symbol, memory="periodic"', "s-", "tab:orange"),
              ("symbol_thesis_median_s", 'build symbol, memory="thesis"', "^-", "tab:green"),
              ("dense_matvec_median_s", "baseline: dense M @ sigma", "D-", "tab:red")]
    for key, label, fmt, c in series:
        ok = np.isfinite(col[key])
        ax.loglog(N[ok], col[key][ok], fmt, color=c, label=f"{label} (warm median)")
        first = key.replace("median", "first")
        ax.loglog(N[ok], col[first][ok], ":", marker=fmt[0], mfc="none", color=c, alpha=0.7,
                  label="dotted, open markers: first call of the same colour (trace + compile + run)"
                  if key == series[0][0] else None)
    # Reference slopes anchored at the largest N of the FFT apply and the dense baseline.
    ref = col["apply_median_s"][-1] * N * np.log2(N) / (N[-1] * np.log2(N[-1]))
    ax.loglog(N, ref, "k--", lw=0.8, label=r"$\propto N \log N$")
    ok = np.isfinite(col["dense_matvec_median_s"])
    if ok.any():
        k = np.flatnonzero(ok)[-1]
        ax.loglog(N[ok], col["dense_matvec_median_s"][k] * (N[ok] / N[k]) ** 2, "k-.", lw=0.8,
                  label=r"$\propto N^2$")
    ax.set_xscale("log", base=2)
    ax.set_xlabel("N (elements on the ring)")
    ax.set_ylabel("time per call (s)")
    ax.set_title("vjax.ring_operator: FFT application vs dense baseline (issue 2 benchmark, Eq. 2.18)\n"
                 f"30-term Prony, hole kernel, float64; dotted: first call. {note}", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return _common.save_figure(fig, path, dpi=dpi)


def main(out_dir="experiments/out", quick=False):
    """Run the benchmark, print the table, write CSV/PNG/TXT into ``out_dir``; return the rows."""
    out = _common.setup(out_dir)
    print(f"device: {_common.device_note()}", flush=True)
    if quick:
        exponents, repeats, dense_max, dpi = (8, 10), 9, 2 ** 10, 70
    else:
        exponents, repeats, dense_max, dpi = tuple(range(8, 17)), 201, 2 ** 12, 150
    dev = jax.devices()[0]
    note = (f"jax {jax.__version__}, {dev.platform} ({dev.device_kind}), {os.cpu_count()} CPUs, "
            f"{platform.machine()}, repeats {repeats}, load avg {os.getloadavg()[0]:.1f} at start")
    header, rows = run(exponents, repeats, dense_max)
    comments = [f"vjax ring_operator benchmark: kind={KIND}, R={R} m, omega={OMEGA} rad/s, "
                "30-term Prony E0=1e6 Pa, tau 1e-8..1e6 s, sum E_k=999e6 Pa, nu=0.5",
                "*_median_s: median of warm calls with block_until_ready; *_first_s: first call "
                "(trace + compile + one run); dense: jitted M @ sigma with M precomputed (N <= "
                f"{dense_max}); {note}"]
    csv_path = _common.write_csv(out / "bench_operator.csv", header, rows, comments=comments)
    short = ["N", "apply_us", "apply_1st_ms", "sym_per_us", "sym_per_1st_ms", "sym_thes_us",
             "sym_thes_1st_ms", "dense_us", "dense_1st_ms", "fft/dense_diff"]
    scaled = [[r[0], 1e6 * r[1], 1e3 * r[2], 1e6 * r[3], 1e3 * r[4], 1e6 * r[5], 1e3 * r[6],
               1e6 * r[7], 1e3 * r[8], r[9]] for r in rows]
    text = _common.print_table(short, scaled, title=f"bench_operator ({'quick' if quick else 'full'}): "
                               f"median warm time per call (us) and first call (ms); {note}")
    png = plot(header, rows, out / "bench_operator.png", dpi, note)
    txt = _common.atomic_write_text(out / "bench_operator.txt", text + "\n")
    print(f"written: {csv_path}, {png}, {txt}")
    return rows


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(out_dir=args[0] if args else "experiments/out", quick="--quick" in sys.argv)
