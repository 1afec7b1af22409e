"""Twin experiment: boundary friction mu_b and roughness sigma, with the material, from a
Stribeck curve (fitting.torque with a rough journal model; issue 43, item 5).

1. **Truth.** The liner material of :mod:`experiments.studies.torque_twin` (10-term Prony +
   WLF from the pyvisco DMA data, Poisson's ratio 0.4) in a finite journal bearing, R = 25 mm,
   c = 50 um, L = 50 mm, a 3 mm liner turning on a fixed rigid shaft (the torque on the shaft),
   no groove, ISO VG 32 oil (:func:`fitting.torque.oil_viscosity` (32, 5.4)); the bore (liner)
   rough, the shaft smooth (Vr = -1): sigma = 1 um,
   mu_b = 0.1, E' of steel and a 3 GPa polymer held fixed, eta_s beta sigma = 0.05,
   sigma/beta = 0.005; 16 x 4 film cells (``N``, ``M``).
2. **Data.** Torque against speed from 0.2 to 2000 rpm (boundary -> mixed -> full film) at
   (40 C, 2 kN) and (70 C, 1 kN), times (1 + 0.05 N(0, 1)) (seed 11), scatter 5 %.
3. **Start.** The moduli and WLF constants off by 20-50 % (torque_twin's draw), mu_b = 0.15,
   sigma = 0.6 um.
4. **Fits** (:func:`fitting.torque.fit_torque`, extras mu_b and sigma): (a) torque alone;
   (b) torque + DMA consistency (w_dma = 0.1).
5. **Report.** Parameter errors, Gauss-Newton sd, identifiability of the torque Jacobian at the
   truth (singular values, which parameters the Stribeck curve alone fixes to < 10 %), chi^2,
   the asperity share along the curve.

Outputs in ``OUT`` (``torque_mixed_twin_*``: data CSV, params CSV, summary markdown, torque and
loss figures). Run: ``python -m experiments.studies.torque_mixed_twin OUT [--quick]``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from experiments import _common

L = 0.05
SIGMA, MU_B = 1e-6, 0.1
CONDITIONS = [(40.0, 2000.0 / L), (70.0, 1000.0 / L)]     # (T in C, load in N/m)
# film cells: coarse, so that two fits of ~35 Jacobians of 18 mixed-regime solves each run in
# minutes on two cores; truth and fit share the grid, so its discretization error cancels
N, M = 16, 4


def roughness(sigma=SIGMA, mu_b=MU_B):
    """The rough bore (the liner), smooth shaft (Vr = -1: the shear flow's sign follows the
    sliding speed of the shaft relative to the bore, whichever turns): composite sigma (m), E'
    of a steel shaft in a 3 GPa polymer (held)."""
    import vjax
    return vjax.Roughness.from_surfaces(0.0, sigma, 210e9, 0.3, 3e9, 0.4, mu_b=mu_b)


def identifiability_lines(ident, title):
    lines = [f"**{title}**", "",
             "singular values: " + " ".join(f"{s:.3g}" for s in ident["singular_values"]), "",
             "fixed individually to < 10 %: " + (", ".join(ident["identifiable"]) or "none"), "",
             "not identified individually: " + (", ".join(ident["not_identifiable"]) or "none"), "",
             f"combinations fixed to < 10 % ({len(ident['identified_directions'])}):", ""]
    lines += [f"- s = {d['singular_value']:.3g}: {d['direction']}" for d in ident["identified_directions"]]
    lines += ["", "weakest directions:", ""]
    lines += [f"- s = {d['singular_value']:.3g}: {d['direction']}" for d in ident["weakest"]]
    return lines + [""]


def run_fits(data, start_mat, start_shift, model, dma_table, extras0, steps, polish):
    from fitting import torque as ft
    results = {}
    for label, w in (("torque only", 0.0), ("torque + DMA", 0.1)):
        print(f"fit: {label} (w_dma = {w})", flush=True)
        results[label] = ft.fit_torque(data, start_mat, start_shift, model, dma_table=dma_table if w else None,
                                       w_dma=w, extras=extras0, steps=steps, lr=0.05, lr_end=0.005,
                                       polish=polish, every=5)
    return results


def param_rows(results, x_true, ident_true):
    rows = []
    for label, fit in results.items():
        for name, before, after, sd, truth, e0, e1 in fit.table(truth=x_true):
            rows.append([label, name, truth, before, after, e0, e1, sd, ident_true["sd"][name]])
    header = ["fit", "param", "truth", "start", "fitted", "err_start", "err_fitted", "sd_rel_GN_fit",
              "sd_rel_torque_at_truth"]
    return header, rows


def markdown_table(header, rows):
    fmt = lambda v: f"{v:.4g}" if isinstance(v, float) else str(v)     # noqa: E731
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(fmt(v) for v in r) + " |" for r in rows]
    return out


def main(out_dir, quick=False):
    _common.enable_x64()
    out = _common.setup(out_dir)
    import jax
    import jax.numpy as jnp
    from fitting.calibration import plots
    from fitting import torque as ft
    from vjax import Material
    from experiments.studies.torque_twin import JOURNAL_NU, perturbation, rig_data, twin_material

    t_all = time.perf_counter()
    stem = "torque_mixed_twin"
    mat, shift, dma_table = twin_material(quick)
    true_mat = Material.prony(mat.E0, mat.moduli, mat.times, JOURNAL_NU)
    model = ft.journal_model(length=L, thickness=3e-3, viscosity=ft.oil_viscosity(32.0, 5.4),
                             n=N, m=M, roughness=roughness(), supply_angle=None)
    speeds = np.geomspace(0.2, 2000.0, 5 if quick else 9)
    rpm = np.concatenate([speeds for _ in CONDITIONS])
    T = np.concatenate([np.full(len(speeds), c[0]) for c in CONDITIONS])
    load = np.concatenate([np.full(len(speeds), c[1]) for c in CONDITIONS])
    truth_extras = {"mu_b": MU_B, "sigma": SIGMA}

    # the truth's torques and asperity shares (the share from the scene itself)
    import vjax
    t0 = time.perf_counter()
    f_model = jax.jit(lambda m, s, a, b, c, e: ft.evaluate(model, m, s, a, b, c, e))
    tq_true, ok = (np.asarray(v) for v in f_model(true_mat, shift, rpm, T, load, truth_extras))
    print(f"true torques: {time.perf_counter() - t0:.1f} s, converged {bool(ok.all())}", flush=True)
    eta = ft.oil_viscosity(32.0, 5.4)
    opt = vjax.FiniteJournalOptions(n=N, m=M)
    share = []
    for a, b, c in zip(rpm, T, load):
        r = vjax.journal_bearing(0.025, 5e-5, eta(b), c * L, length=L, housing=vjax.liner(true_mat.with_shift(shift), 3e-3),
                                 temperature=b, omega_housing=a * np.pi / 30, options=opt,
                                 throw=False, roughness=roughness(), supply_angle=None)
        share.append(float(r.asperity_share))
    share = np.asarray(share)

    data = rig_data(out / f"{stem}_data.csv", model.scene, rpm, T, load, tq_true, 0.05, 11)
    sigma = data.scatter

    P = ft.Params.of(true_mat, shift, extras=("mu_b", "sigma"))
    x_true = P.pack(true_mat, shift, truth_extras)
    nm = P.n_material
    start_mat, start_shift = P.physical(x_true[:nm] + perturbation(nm))       # torque_twin's draw for the material
    extras0 = {"mu_b": 0.15, "sigma": 0.6e-6}

    jac_t, _ = ft.residual_jacobian(P, model, data)
    J_true = np.asarray(jac_t(jnp.asarray(x_true))[0])
    ident_true = ft.identifiability(J_true, P.names())

    results = run_fits(data, start_mat, start_shift, model, dma_table, extras0,
                       steps=3 if quick else 10, polish=5 if quick else 25)
    header, rows = param_rows(results, x_true, ident_true)
    _common.write_csv(out / f"{stem}_params.csv", header, rows,
                      comments=["units: Pa (E0, E_k), C (C2), m (sigma); errors relative to the truth",
                                "sd_rel_GN_fit: Gauss-Newton sd of the log-parameter at the fit (its terms)",
                                "sd_rel_torque_at_truth: from the torque Jacobian alone at the truth"])
    chi = lambda tq: float(np.mean(((tq - data.torque) / sigma) ** 2))     # noqa: E731
    summary = [[label, chi(f.torque0), chi(f.torque), f.iterations, round(f.wall_time, 1), f.converged,
                f.extras["mu_b"] / MU_B - 1, f.extras["sigma"] / SIGMA - 1] for label, f in results.items()]
    sheader = ["fit", "chi2_start", "chi2_fitted", "iterations", "wall_s", "converged", "err_mu_b", "err_sigma"]
    _common.print_table(sheader, summary, title="mixed-lubrication twin")
    _common.print_table(header, rows, title="parameters")

    # what the torque fixes: sd of mu_b and sigma from the torque alone at the truth, and with E0 or
    # the whole material known (the columns of J dropped)
    names = P.names()
    iE = [names.index("mu_b"), names.index("sigma")]
    sd_known = ft.identifiability(J_true[:, iE], ["mu_b", "sigma"])["sd"]
    lines = ["# Mixed-lubrication twin: mu_b and sigma from a Stribeck curve", "",
             f"scene: {model.scene}", "",
             f"{len(data)} points, {speeds[0]:g}-{speeds[-1]:g} rpm at {CONDITIONS}; 5 % noise; truth chi2 "
             f"{chi(tq_true):.3f}; asperity share along the curves: " + ", ".join(f"{s:.3f}" for s in share), "",
             "truth: mu_b = 0.1, sigma = 1 um; start: mu_b = 0.15, sigma = 0.6 um, material 20-50 % off", ""]
    lines += markdown_table(sheader, summary) + [""] + markdown_table(header, rows) + [""]
    lines += identifiability_lines(ident_true, "torque Jacobian at the truth (all parameters free)")
    lines += [f"with the material known: sd(log mu_b) = {sd_known['mu_b']:.3g}, sd(log sigma) = "
              f"{sd_known['sigma']:.3g}", ""]
    for label, f in results.items():
        lines += identifiability_lines(f.ident, f"torque Jacobian at the {label} optimum")
    lines.append(f"total wall time {time.perf_counter() - t_all:.0f} s")
    text = "\n".join(lines)
    _common.atomic_write_text(out / f"{stem}_summary.md", text + "\n")
    print(text)
    plots.torque_fit(data, results, sigma, out / f"{stem}_torque.png", truth=tq_true)
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for label, f in results.items():
        h = np.asarray(f.history)
        ax.semilogy(h[:, 0], h[:, 1], label=label)
    ax.axhline(chi(tq_true), color="k", lw=0.8, ls=":", label="truth")
    ax.set_xlabel("iteration (Adam, then Levenberg-Marquardt)")
    ax.set_ylabel("loss")
    ax.legend()
    _common.save_figure(fig, out / f"{stem}_loss.png")
    return {"results": results, "ident_true": ident_true, "x_true": x_true, "share": share, "summary": summary}


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", help="output directory")
    ap.add_argument("--quick", action="store_true", help="5 speeds, few iterations")
    a = ap.parse_args()
    _common.enable_x64()
    main(a.out, quick=a.quick)
