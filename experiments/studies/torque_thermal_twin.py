"""Twin experiment: the material from friction torques measured with self-heating
(fitting.torque with a heat transfer; issue 40, item 5).

1. **Truth.** The pin-joint twin of :mod:`experiments.studies.torque_twin` (rigid pin R' = 9.9
   mm in a 10 mm hole of the pyvisco-calibrated 10-term Prony + WLF polymer, n = 128 per ring)
   heated by its own hysteresis (:func:`vjax.thermal_pin`): -Omega torque = hA (T_eff - T_amb)
   with hA per unit axial length (W/(m K)) the largest isothermal power over ``HEAT_RISE`` = 8 K
   (the feedback of the softening polymer heats the hottest point further; the summary lists
   every point's T_eff - T_amb).
2. **Data.** A rig: three speeds (100, 400, 1600 rpm) x three loads (F/(E0 R) = 0.5, 1, 2 %)
   at ambient 40 C and at 70 C (18 points); the CSV's T is the ambient temperature; torque x
   (1 + 0.03 N(0, 1)) (seed 5), scatter 3 %.
3. **Start.** Moduli and WLF constants off by 20-50 % (torque_twin's draw).
4. **Fits** (torque alone; then the same with the DMA consistency term, w_dma = 0.1):
   - isothermal: the scene at the CSV's T (what the rig's data get today);
   - thermal, hA known: the heat balance with the rig's hA;
   - thermal, hA fitted: log hA a parameter, started at twice the truth.
5. **Report.** The effective temperatures of the truth, parameter errors, the error of the
   dynamic modulus |E*| over the band the rig probes (rms of log(|E*_fit| / |E*_true|) over
   1-1e4 rad/s at 40-100 C), chi^2 and the torque misfit against the truth.

``--scene journal``: the same with torque_twin's oil-lubricated journal bearing (R = 25 mm,
c = 50 um, L = 50 mm, a 3 mm liner of the polymer at Poisson's ratio 0.4 turning on a fixed
shaft, ISO VG 32 oil with c_p = 2000 J/(kg K), 16 x 4 film cells) at 700, 1500, 3000 rpm x 1,
2.5, 5 kN with the supply at 40 C and x 0.4, 1, 2 kN at 70 C, heat carried by the side leakage and by hA = 2 W/K
(:func:`vjax.thermal_journal_bearing`, ISO 7902's balance).

Outputs in ``OUT`` (``torque_thermal_twin_<scene>_*``: data CSV, params CSV, summary markdown,
torque and moduli figures). Run:
``python -m experiments.studies.torque_thermal_twin OUT [--quick] [--scene pin|journal]``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from experiments import _common

HEAT_RISE = 8.0                   # K: the isothermal estimate of the hottest point's rise (feedback adds to it)
SPEEDS = (100.0, 400.0, 1600.0)   # rpm
LOADS = (0.5e-2, 1e-2, 2e-2)      # F / (E0 R)
AMBIENT = (40.0, 70.0)            # C
R, C = 0.01, 1e-4                 # hole radius, radial clearance (m)
JOURNAL_L, JOURNAL_HA = 0.05, 2.0    # journal scene: length (m), housing heat transfer (W/K)


def modulus_error(mat, true_mat, shift, true_shift):
    """rms of ln(|E*_fit| / |E*_true|) over omega = 1..1e4 rad/s at 40, 70 and 100 C (the band
    the rig probes, its self-heating included)."""
    import jax.numpy as jnp
    w = jnp.logspace(0, 4, 17)
    errs = []
    for T in (40.0, 70.0, 100.0):
        a = jnp.abs(mat.with_shift(shift).at_temperature(T).modulus(w))
        b = jnp.abs(true_mat.with_shift(true_shift).at_temperature(T).modulus(w))
        errs.append(np.asarray(jnp.log(a / b)))
    return float(np.sqrt(np.mean(np.concatenate(errs) ** 2)))


def _pin(true_mat, true_shift, quick):
    """(isothermal model, thermal model, grid, hA, T_eff of the truth at each point, hA unit)."""
    import jax.numpy as jnp
    import vjax
    from fitting import torque as ft
    n = 64 if quick else 128
    E0 = float(true_mat.E0)
    grid = [(s, T, f * E0 * R) for T in AMBIENT for f in LOADS for s in SPEEDS]
    rpm = np.array([g[0] for g in grid])
    iso = ft.pin_model(n=n)
    # the rig's hA: the largest isothermal power over HEAT_RISE
    tq_iso, _ = ft.evaluate(iso, true_mat, true_shift, *(jnp.asarray(v) for v in zip(*grid)))
    P_iso = np.asarray(tq_iso) * rpm * np.pi / 30 * (R - C) / C     # Omega torque, Omega the patch speed
    hA = float(f"{P_iso.max() / HEAT_RISE:.2g}")
    T_eff = [float(vjax.thermal_pin(true_mat.with_shift(true_shift), R, C, c,
                                    vjax.HeatTransfer(T_supply=b, hA=hA, oil_flow=False), omega_shaft=a * np.pi / 30,
                                    options=vjax.PinOptions(n=n)).temperature) for a, b, c in grid]
    return iso, ft.pin_model(n=n, heat_transfer=hA), grid, hA, np.asarray(T_eff), "W/(m K)"


def _journal(true_mat, true_shift, quick):
    """The oil-lubricated journal bearing of torque_twin's journal scene (its liner at Poisson's
    ratio 0.4, turning; ISO VG 32 with c_p = 2000 J/(kg K)) on 16 x 4 cells, 700-3000 rpm x 1,
    2.5, 5 kN at supply 40 and 70 C, hA = JOURNAL_HA W/K to the supply temperature."""
    import vjax
    from fitting import torque as ft
    oil = ft.oil_viscosity(32.0, 5.4)
    kw = dict(length=JOURNAL_L, thickness=3e-3, viscosity=oil, n=16, m=4)
    # the thinner hot oil carries 0.4 times the load (as torque_twin's journal scene)
    grid = [(s, T, F * (1.0 if T < 50 else 0.4) / JOURNAL_L) for T in AMBIENT for F in (1000.0, 2500.0, 5000.0)
            for s in (700.0, 1500.0, 3000.0)]
    opt = vjax.FiniteJournalOptions(n=16, m=4)
    T_eff = [float(vjax.thermal_journal_bearing(
        0.025, 5e-5, oil.lubricant, c * JOURNAL_L, vjax.HeatTransfer(T_supply=b, hA=JOURNAL_HA), length=JOURNAL_L,
        housing=vjax.liner(true_mat.with_shift(true_shift), 3e-3), omega_housing=a * np.pi / 30, options=opt).temperature)
        for a, b, c in grid]
    return (ft.journal_model(**kw), ft.journal_model(heat_transfer=JOURNAL_HA, **kw), grid, JOURNAL_HA,
            np.asarray(T_eff), "W/K")


def main(out_dir, quick=False, scene="pin"):
    _common.enable_x64()
    out = _common.setup(out_dir)
    import jax
    import jax.numpy as jnp
    from fitting.calibration import plots
    from fitting import torque as ft
    from vjax import Material
    from experiments.studies.torque_mixed_twin import identifiability_lines, markdown_table
    from experiments.studies.torque_twin import JOURNAL_NU, perturbation, rig_data, twin_material

    t_all = time.perf_counter()
    stem = f"torque_thermal_twin_{scene}"
    true_mat, true_shift, dma_table = twin_material(quick)
    if scene == "journal":
        true_mat = Material.prony(true_mat.E0, true_mat.moduli, true_mat.times, JOURNAL_NU)
    iso, thermal, grid, hA, T_eff, unit = (_journal if scene == "journal" else _pin)(true_mat, true_shift, quick)
    rpm, T, load = (np.array(v) for v in zip(*grid))
    pts = tuple(jnp.asarray(a) for a in (rpm, T, load))
    t0 = time.perf_counter()
    tq_true, ok = (np.asarray(v) for v in jax.jit(lambda m, s: ft.evaluate(thermal, m, s, *pts))(true_mat, true_shift))
    print(f"hA = {hA:g} {unit}; true torques {time.perf_counter() - t0:.1f} s, converged {bool(ok.all())}; "
          f"T_eff - T_amb: {np.round(T_eff - T, 2)}", flush=True)

    csv_path = out / f"{stem}_data.csv"
    data = rig_data(csv_path, thermal.scene, rpm, T, load, tq_true, 0.03, 5, ["T: the ambient temperature"])
    sigma = data.scatter

    P = ft.Params.of(true_mat, true_shift)
    x_true = P.pack(true_mat, true_shift)
    start_mat, start_shift = P.physical(x_true + perturbation(x_true.size))

    steps, polish = (20, 10) if quick else (150, 30)
    cases = [("isothermal", iso, None), ("thermal, hA known", thermal, None),
             ("thermal, hA fitted", thermal, {"hA": 2 * hA})]
    results = {}
    for w in (0.0, 0.1):
        for label, model, extras in cases:
            key = label + (" + DMA" if w else "")
            print(f"fit: {key}", flush=True)
            results[key] = ft.fit_torque(data, start_mat, start_shift, model, dma_table=dma_table if w else None,
                                         w_dma=w, extras=extras, steps=steps, lr=0.05, lr_end=0.002,
                                         polish=polish, every=25)

    chi = lambda tq: float(np.mean(((tq - data.torque) / sigma) ** 2))     # noqa: E731
    rms_rel = lambda tq, sel=slice(None): float(np.sqrt(np.mean((tq / tq_true - 1.0)[sel] ** 2)))     # noqa: E731
    hot = T_eff - T > 1.0          # the points the heating moves by more than 1 K
    nm = P.n_material
    summary, rows = [], []
    for key, f in results.items():
        mod_err = modulus_error(f.material, true_mat, f.shift, true_shift)
        lerr = f.x[:nm] - x_true
        summary.append([key, chi(f.torque), rms_rel(f.torque), rms_rel(f.torque, hot), rms_rel(f.torque, ~hot),
                        float(np.max(np.abs(f.torque / tq_true - 1))),
                        mod_err, float(np.exp(lerr[0]) - 1), float(np.exp(lerr[nm - 2]) - 1),
                        float(np.exp(lerr[nm - 1]) - 1), f.extras.get("hA", float("nan")) / hA - 1,
                        f.iterations, round(f.wall_time, 1), f.converged])
        for name, before, after, sd, truth, e0, e1 in f.table(truth=np.concatenate([x_true, [np.log(hA)]])
                                                              [:len(f.x)]):
            rows.append([key, name, truth, before, after, e0, e1, sd])
    sheader = ["fit", "chi2", "rms_rel_torque_vs_truth", "rms_rel_hot", "rms_rel_cool", "max_rel_torque_vs_truth",
               "rms_ln_modulus_err",
               "err_E0", "err_C1", "err_C2", "err_hA", "iterations", "wall_s", "converged"]
    header = ["fit", "param", "truth", "start", "fitted", "err_start", "err_fitted", "sd_rel_GN"]
    _common.write_csv(out / f"{stem}_params.csv", header, rows,
                      comments=[f"scene: {thermal.scene}", "errors relative to the truth"])
    _common.write_csv(out / f"{stem}_summary.csv", sheader, summary,
                      comments=["chi2 per point (3 % scatter); torque misfit relative to the noise-free truth "
                                "(all points; hot: heated by > 1 K; cool: the others)",
                                "rms_ln_modulus_err: |E*| over 1-1e4 rad/s at 40, 70, 100 C"])
    _common.print_table(sheader, summary, title="thermal twin")
    start_mod = modulus_error(start_mat, true_mat, start_shift, true_shift)
    lines = ["# Thermal twin: the material from self-heated torques", "",
             f"scene: {thermal.scene}", "",
             f"{len(data)} points: " + ", ".join(f"({a:g} rpm, {b:g} C, {c:.3g} N/m)" for a, b, c in grid)
             + f"; 3 % noise; truth chi2 {chi(tq_true):.3f}; hA = {hA:g} {unit}", "",
             "self-heating of the truth, T_eff - T_amb (K): " + ", ".join(f"{d:.1f}" for d in T_eff - T)
             + f" ({int(hot.sum())} points heated by > 1 K: 'hot')", "",
             f"start: rms ln|E*| error {start_mod:.3f}, chi2 {chi(results['isothermal'].torque0):.3g}", ""]
    lines += markdown_table(sheader, summary) + [""]
    lines += identifiability_lines(results["thermal, hA fitted"].ident, "torque Jacobian at the thermal, hA-fitted optimum")
    lines.append(f"total wall time {time.perf_counter() - t_all:.0f} s")
    text = "\n".join(lines)
    _common.atomic_write_text(out / f"{stem}_summary.md", text + "\n")
    print(text)
    show = {k: results[k] for k in ("isothermal", "thermal, hA known", "thermal, hA fitted")}
    plots.torque_fit(data, show, sigma, out / f"{stem}_torque.png", truth=tq_true)
    plots.moduli([(true_mat, "truth", "k-"), (start_mat, "start", "k:"),
                  (results["isothermal"].material, "isothermal fit", "C1--"),
                  (results["thermal, hA fitted"].material, "thermal fit (hA fitted)", "C2-.")],
                 out / f"{stem}_moduli.png")
    return {"results": results, "summary": summary, "hA": hA, "T_eff": T_eff, "x_true": x_true}


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", help="output directory")
    ap.add_argument("--quick", action="store_true", help="n = 64, few iterations")
    ap.add_argument("--scene", choices=("pin", "journal"), default="pin")
    a = ap.parse_args()
    main(a.out, quick=a.quick, scene=a.scene)
