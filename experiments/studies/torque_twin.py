"""Twin experiment: recover a material from bearing friction torque (fitting.torque).

1. **Truth.** A 10-term Prony series + WLF law (T_ref = 25 C) calibrated from the shipped
   pyvisco DMA data between 10 and 100 C (data-overlap shift factors, WLF fit, NNLS Prony at
   0.5 terms per decade, end-to-end refinement: :func:`twin_material`). The full 21-term
   calibration with a tabulated shift law has no WLF constants to refine, and a direct WLF
   calibration of all 21 temperatures (-50..100 C) does not converge (C2 = 840 C), so the
   twin uses the operating range of a bearing.
2. **Data.** Torque versus shaft speed (100-3000 rpm, 6 speeds) at 40 and 70 C and two
   loads, from the scene with the true material, times (1 + 0.05 N(0, 1)) noise; written to
   a CSV and read back with :func:`fitting.torque.read_torque_csv`.
3. **Start.** Every modulus (E0, E_k) and both WLF constants off by 20-50% (random sign and
   size, fixed seed); relaxation times kept (the torque cannot resolve them, see the
   Jacobian).
4. **Fits** (Adam on log-parameters, :func:`fitting.torque.fit_torque`): (a) torque only;
   (b) torque + DMA consistency term (the same DMA points, weight w_dma).
5. **Report.** Torque misfit (chi^2 per point; 1 = within the noise) and parameter errors
   before/after, iterations, wall time, gradient check of the loss versus central finite
   differences, Gauss-Newton uncertainties and the identifiability analysis (singular
   values of the torque Jacobian).

Scene: ``--scene roller`` (default: needle roller bearing of the thesis geometry, R_O = 6
mm, R_I = 4 mm, 9 rollers, both rings of the fitted material, outer ring fixed, F~ =
F/(E0 R_O) = 4e-3 and 8e-3, n = 256 per ring) or ``--scene pin`` (a polymer pin joint,
rigid pin R' = 9.9 mm in a 10 mm hole of the fitted material, F~ = 1e-2 and 2e-2, n = 128)
or ``--scene journal`` (:func:`fitting.torque.journal_model`: an oil-lubricated finite journal
bearing, R = 25 mm, c = 50 um, L = 50 mm, a 3 mm liner of the fitted polymer (Poisson's ratio
JOURNAL_NU = 0.4, a thermoplastic's) turning on a fixed rigid shaft, an ISO VG 32 mineral oil
(:func:`fitting.torque.oil_viscosity` (32, 5.4): 0.0275 Pa s at 40 C, 0.0096 at 70 C),
n x m = 32 x 8 film cells; 700-3000 rpm, 2.5 and 5 kN at 40 C, 1 and 2 kN at 70 C (5e4-1e5
and 2e4-4e4 N/m in the CSV): eccentricities 0.37-0.92, minimum films 0.08-0.63 c,
the liner's deformation up to 0.16 c, which lowers the torque 2-8 % below the rigid bearing's,
its hysteresis at most 1 % of it; the quick run skips the gradient check, which
tests/test_torque_journal.py makes). Outputs are ``torque_twin_<scene>_*`` (csv, png, json, txt).

Run: ``python -m experiments.studies.torque_twin [--quick] [--scene pin|roller|journal]``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from experiments import _common

T_REF = 25.0


def twin_material(quick: bool = False, data: str = "pyvisco", density: float = 0.5):
    """The true material: Prony + WLF fitted to a shipped DMA data set (``data``: "pyvisco"
    or "dmasuite") at 10-100 C with ``density`` terms per decade (pyvisco, 0.5: 10 terms).
    Returns (Material, WLF, DMATable used)."""
    from fitting.measurements import dma
    from fitting.calibration import master, prony
    from vjax import Material

    tab = dma.read(dma.default_data(data))
    sub = tab.subset((tab.T >= 10.0) & (tab.T <= 100.0))
    wlf, _ = master.fit_law(master.shift_factors(sub, T_REF), "WLF")
    wr = sub.omega * 10.0 ** np.asarray(wlf.log10_aT(sub.T))
    E0, Ek, tau = prony.fit_master(wr, sub.storage, sub.loss, density=density)
    fit = prony.refine(sub, Material.prony(E0, Ek, tau, 0.5), wlf, max_iter=60 if quick else 200)
    return fit.material, fit.shift, sub


# journal scene: the liner's Poisson's ratio (a thermoplastic's; the calibration's 0.5 is a
# rubber's: a 10 mm rubber liner in 3D bulges into the clearance at the land's ends)
JOURNAL_NU = 0.4


def rig_data(path, scene, rpm, T, load, true_torque, scatter, seed, comments=()):
    """Synthetic rig data, as a rig's CSV would give them: the true torques times
    (1 + ``scatter`` N(0, 1)) (random seed ``seed``), each with ``scatter`` of the true torque as
    its scatter, written to ``path`` and read back. ``scene``: the model's description."""
    from fitting import torque as ft
    rng = np.random.default_rng(seed)
    noisy = true_torque * (1.0 + scatter * rng.normal(size=true_torque.shape))
    ft.write_torque_csv(path, ft.TorqueData(rpm, T, load, noisy, scatter * np.abs(true_torque)),
                        comments=[f"twin experiment: {scene}", *comments,
                                  f"true torque x (1 + {scatter:g} N(0,1)), seed {seed}"])
    return ft.read_torque_csv(path)


def perturbation(size, seed=3):
    """Log factors of a start off by 20-50 % with random signs, one per parameter."""
    rng = np.random.default_rng(seed)
    return np.log(1.0 + rng.choice([-1.0, 1.0], size=size) * rng.uniform(0.2, 0.5, size=size))


def _scene(name, quick):
    """(model, load per unit length of each (T, load) condition after the first two, speeds
    (rpm), (lowest, highest) patch speed per shaft speed)."""
    from fitting import torque as ft
    if name == "journal":
        # oil films 0.08-0.6 c thick at the minimum: every solve converges at the truth, at the
        # start and with the moduli doubled (halved, the heaviest slowest point does not)
        L = 0.05
        return (ft.journal_model(length=L, thickness=3e-3, viscosity=ft.oil_viscosity(32.0, 5.4)), None,
                np.geomspace(700.0, 3000.0, 4 if quick else 6), (1.0, 1.0),
                [(40.0, 2500.0 / L), (70.0, 1000.0 / L), (40.0, 5000.0 / L), (70.0, 2000.0 / L)])
    speeds = np.geomspace(100.0, 3000.0, 4 if quick else 6)
    if name == "roller":   # relative to the outer ring R_I/(R_I+R_O), to the inner R_O/(R_I+R_O)
        model, R_scale, patch, F = ft.roller_model(n=128 if quick else 256), 6e-3, (0.4, 0.6), 4e-3
    else:
        model, R_scale, patch, F = ft.pin_model(n=64 if quick else 128), 0.01, (0.0099 / (0.01 - 0.0099),) * 2, 1e-2
    return model, F * R_scale, speeds, patch, None


def main(out_dir="experiments/out", quick: bool = False, scene: str = "roller", steps=None) -> dict:
    out = _common.setup(out_dir)
    import jax
    import matplotlib.pyplot as plt
    from fitting.calibration import io as fio
    from fitting.calibration import plots
    from fitting import torque as ft

    t_all = time.perf_counter()
    stem = f"torque_twin_{scene}"
    true_mat, true_shift, dma_table = twin_material(quick)
    if scene == "journal":      # a thermoplastic liner: the same moduli, a compressible one
        from vjax import Material
        true_mat = Material.prony(true_mat.E0, true_mat.moduli, true_mat.times, JOURNAL_NU)
    K = int(true_mat.moduli.shape[0])
    print(f"truth: {K}-term Prony, E0 = {float(true_mat.E0):.4g} Pa, WLF C1 = {float(true_shift.C1):.4g}, "
          f"C2 = {float(true_shift.C2):.4g} C, T_ref = {T_REF} C", flush=True)
    fio.save_material(out / f"{stem}_truth.json", true_mat, true_shift)

    model, F1, speeds, patch, conds = _scene(scene, quick)
    if conds is None:
        F1 *= float(true_mat.E0)                          # F~ = F/(E0 R)
        conds = [(40.0, F1), (70.0, F1), (40.0, 2 * F1), (70.0, 2 * F1)]
    rpm = np.concatenate([speeds for _ in conds])
    T = np.concatenate([np.full(len(speeds), c[0]) for c in conds])
    load = np.concatenate([np.full(len(speeds), c[1]) for c in conds])
    f_model = jax.jit(lambda m, s, a, b, c: ft.evaluate(model, m, s, a, b, c))
    t0 = time.perf_counter()
    tq_true, ok = f_model(true_mat, true_shift, rpm, T, load)
    print(f"true torques: {time.perf_counter() - t0:.1f} s (compile + {len(rpm)} solves), converged "
          f"{bool(np.all(ok))}", flush=True)
    tq_true = np.asarray(tq_true)
    csv_path = out / f"{stem}_data.csv"
    data = rig_data(csv_path, model.scene, rpm, T, load, tq_true, 0.05, 7)
    sigma = data.scatter

    # perturbed start: moduli and WLF constants off by 20-50%, random sign
    P = ft.Params.of(true_mat, true_shift)
    x_true = P.pack(true_mat, true_shift)
    start_mat, start_shift = P.physical(x_true + perturbation(x_true.size))

    # gradient check of the loss (torque + DMA) at the start; the quick journal leaves it to
    # tests/test_torque_journal.py (two more compilations of the journal solve, 2 min)
    gc_rows = [] if (quick and scene == "journal") else ft.gradient_check(P, model, data, P.pack(start_mat, start_shift), dma_table=dma_table, w_dma=0.1,
                                coords=[0, K // 2, K + 1, K + 2])
    _common.print_table(["direction", "analytic", "finite diff", "rel err"], gc_rows,
                        title="gradient check of the loss (log-parameters, h = 1e-4)")

    # identifiability at the truth: which combinations the torque data fix (sd < 10%)
    jac_t, _ = ft.residual_jacobian(P, model, data)
    J_true = np.asarray(jac_t(jax.numpy.asarray(x_true))[0])
    ident_true = ft.identifiability(J_true, P.names())

    steps = steps or (25 if quick else 400)
    results = {}
    for label, w in (("torque only", 0.0), ("torque + DMA", 0.1)):
        print(f"fit: {label} (w_dma = {w}), {steps} Adam steps", flush=True)
        fit = ft.fit_torque(data, start_mat, start_shift, model, dma_table=dma_table if w else None, w_dma=w,
                            steps=steps, lr=0.05, lr_end=0.002, every=10)
        results[label] = fit

    # ---- tables ----
    names = P.names()
    rows = []
    for label, fit in results.items():
        for name, before, after, sd, truth, e0, e1 in fit.table(truth=x_true):
            ident = "yes" if fit.ident["sd"][name] < 0.1 else "no"
            rows.append([label, name, truth, before, after, sd, e0, e1, ident])
    header = ["fit", "param", "truth", "start", "fitted", "sd_rel_GN", "err_start", "err_fitted", "torque_identifies"]
    _common.write_csv(out / f"{stem}_params.csv", header, rows,
                      comments=["units: Pa for E0/E_k, C1 dimensionless, C2 in C; errors relative to the truth",
                                "sd_rel_GN: Gauss-Newton standard deviation of the log-parameter (torque + DMA terms "
                                "of that fit)", "torque_identifies: sd from the torque Jacobian alone < 10%"])
    _common.print_table(header, rows, title="parameter changes")

    def rms_log_err(x):
        return float(np.sqrt(np.mean((np.asarray(x) - x_true) ** 2)))

    summary_rows = []
    for label, fit in results.items():
        chi0 = float(np.mean(((fit.torque0 - data.torque) / sigma) ** 2))
        chi1 = float(np.mean(((fit.torque - data.torque) / sigma) ** 2))
        rel_true = float(np.sqrt(np.mean((fit.torque / tq_true - 1) ** 2)))
        rel_true0 = float(np.sqrt(np.mean((fit.torque0 / tq_true - 1) ** 2)))
        # errors in the parameter combinations the torque identifies (torque Jacobian at the truth)
        V = np.asarray(ident_true["identified_basis"]).reshape(-1, len(names))
        proj = lambda x: float(np.sqrt(np.mean((V @ (np.asarray(x) - x_true)) ** 2))) if len(V) else float("nan")
        summary_rows.append([label, chi0, chi1, rel_true0, rel_true, rms_log_err(fit.x0), rms_log_err(fit.x),
                             proj(fit.x0), proj(fit.x),
                             fit.iterations, fit.wall_time, fit.compile_time, fit.converged])
    chi_true = float(np.mean(((tq_true - data.torque) / sigma) ** 2))
    sheader = ["fit", "chi2_start", "chi2_fitted", "rms_rel_vs_true_start", "rms_rel_vs_true_fitted",
               "rms_log_param_err_start", "rms_log_param_err_fitted", "identified_combo_err_start",
               "identified_combo_err_fitted",
               "iterations", "wall_s", "first_eval_s", "converged"]
    _common.write_csv(out / f"{stem}_summary.csv", sheader, summary_rows,
                      comments=[f"chi2 per point of the noisy data; the true material gives {chi_true:.3f}",
                                "param errors: rms of log(fitted/true) (all parameters; and projected on the "
                                f"{len(ident_true['identified_basis'])} directions the torque identifies at the truth)",
                                f"scene: {model.scene}"])
    stext = _common.print_table(sheader, summary_rows, title="twin experiment")

    # ---- refined material JSON (the torque + DMA fit) ----
    best = results["torque + DMA"]
    unc = {n: float(s) for n, s in zip(names, best.sd)}
    fio.save_material(out / f"{stem}_refined.json", best.material, best.shift, uncertainty={"sd_rel": unc},
                      fit={"scene": model.scene, "loss": best.loss, "iterations": best.iterations})

    # ---- plots ----
    plots.torque_fit(data, results, sigma, out / f"{stem}_torque.png", truth=tq_true)
    # reduced frequencies that the torque data probe (patch speed x modes 1..10, shifted to 25 C)
    bands = []
    for Tc in (40.0, 70.0):
        aT = 10 ** float(true_shift.log10_aT(Tc))
        bands.append((aT * speeds.min() * 2 * np.pi / 60 * patch[0], aT * speeds.max() * 2 * np.pi / 60 * patch[1] * 10))
    plots.moduli([(true_mat, "truth", "k-"), (start_mat, "start", "k:"),
                  (results["torque only"].material, "torque only", "C1--"), (best.material, "torque + DMA", "C2-.")],
                 out / f"{stem}_moduli.png", bands=bands)

    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for label, fit in results.items():
        h = np.asarray(fit.history)
        ax.semilogy(h[:, 0], h[:, 1], label=label)
    ax.axhline(chi_true, color="k", lw=0.8, ls=":", label="true material (torque part)")
    ax.set_xlabel("iteration (Adam, then Levenberg-Marquardt)")
    ax.set_ylabel("loss")
    ax.legend()
    _common.save_figure(fig, out / f"{stem}_loss.png")

    # ---- identifiability ----
    # d ln T / d ln p at the truth from the noise-scaled Jacobian (sigma = 5% of the true torque)
    sens = 0.05 * J_true * np.sign(tq_true)[:, None]
    rng_of = lambda v: f"{np.min(v):+.3g} .. {np.max(v):+.3g} (median {np.median(v):+.3g})"
    lines = [stext, "", f"scene: {model.scene}; data: {len(data)} points, 5% noise; truth chi2 {chi_true:.3f}",
             f"torque sensitivity at the truth over the points: d ln T / d ln E0 {rng_of(sens[:, 0])}; "
             f"d ln T / d ln (all moduli) {rng_of(sens[:, :K + 1].sum(axis=1))}; d ln T / d ln C1 "
             f"{rng_of(sens[:, -2])}",
             "gradient check (loss at the start, torque + DMA w=0.1):"]
    lines += [f"  {r[0]:>16s}: analytic {r[1]: .6e}  FD {r[2]: .6e}  rel err {r[3]:.2e}" for r in gc_rows]
    for label, idf in [("truth", ident_true)] + [(k + " optimum", v.ident) for k, v in results.items()]:
        lines += ["", f"identifiability from the torque Jacobian at the {label}:",
                  "  singular values: " + " ".join(f"{s:.3g}" for s in idf["singular_values"]),
                  "  parameters fixed individually to < 10% by the torque: " + (", ".join(idf["identifiable"]) or "none"),
                  "  not identified individually: " + ", ".join(idf["not_identifiable"]),
                  f"  combinations fixed to < 10% ({len(idf['identified_directions'])}):"]
        lines += [f"    s={d['singular_value']:.3g}: {d['direction']}" for d in idf["identified_directions"]]
        lines += ["  weakest directions:"] + [f"    s={d['singular_value']:.3g}: {d['direction']}"
                                              for d in idf["weakest"]]
    lines.append(f"total wall time {time.perf_counter() - t_all:.1f} s")
    text = "\n".join(lines)
    print("\n".join(lines[1:]))
    _common.atomic_write_text(out / f"{stem}_summary.txt", text + "\n")
    return {"summary": summary_rows, "gradient_check": gc_rows, "results": results, "truth": x_true,
            "chi_true": chi_true}


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--scene", choices=("roller", "pin", "journal"), default="roller")
    ap.add_argument("--steps", type=int, default=None)
    ap.add_argument("--out", default="experiments/out")
    a = ap.parse_args()
    main(a.out, quick=a.quick, scene=a.scene, steps=a.steps)
