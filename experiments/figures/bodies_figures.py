"""Bodies of finite thickness against the thesis's infinite plane (bushings, liners).

    PYTHONPATH=. python -m experiments.figures.bodies_figures [out_dir] [--quick]

1. The thesis's test bearing as built (Section 2.3.3): a polymer bushing of 12 mm bore and
   16 mm outside diameter (a 2 mm wall) pressed into a rigid steel holder, 9 rigid needles of
   2 mm on a rigid 8 mm shaft, 50 N and 100 N on the 7.8 mm needle length, 30 and 50 C. The
   polymer is the main job's calibration of the shipped DMA data (Prony series and shift law),
   used as it is. Friction torque, loaded rollers and the largest roller load versus shaft
   speed, for the bushing (``vjax.liner``) and for the thesis's model of the outer ring (a
   hole in an infinite plane, with log reference lengths 1 m and R_O): the plane's answer
   moves with that arbitrary length, the bushing has none.
2. A pin in a thin bushing against the Winkler foundation it must approach
   (``vjax.reference.winkler_pin``).
3. A water-lubricated journal bearing with a thin rubber liner bonded to a rigid shell
   (R = 50 mm, radial clearance 150 um, liner 5 mm, rubber SLS E0 = 5 MPa, Einf = 50 MPa,
   tau = 1 ms, nu = 0.49; water 1 mPa s; 3e4 N/m, i.e. 0.3 MPa on the projected area;
   stationary shell, shaft 5..500 rad/s) against the same bearing with an infinite-plane
   rubber bore: minimum film, effective eccentricity, friction torque, viscoelastic share.

Writes ``bodies_test_bearing.png/.csv``, ``bodies_water_journal.png/.csv``,
``bodies_summary.txt``.
"""
from __future__ import annotations

import sys
from pathlib import Path

from experiments import _common

_common.enable_x64()

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

import vjax  # noqa: E402
from vjax import reference  # noqa: E402

RO, RI, D, Z, WALL, NEEDLE_LENGTH = 6e-3, 4e-3, 2e-3, 9, 2e-3, 7.8e-3
LOADS_N, TEMPS = (50.0, 100.0), (30.0, 50.0)
RUBBER = vjax.Material.sls(5e6, 50e6, 1e-3, 0.49)
JR, JC, WATER, JLOAD, LINER = 0.05, 1.5e-4, 1e-3, 3e4, 5e-3


def _material(out):
    """The main job's calibrated polymer, or a fresh calibration of the shipped DMA data."""
    from fitting import calibrate, load_material
    from fitting.measurements import dma
    path = Path(out).parent / "calibration" / "material.json"
    if path.exists():
        material, shift, _ = load_material(path)
        return material, shift, str(path)
    material, shift, _ = calibrate(dma.default_data("pyvisco"), 25.0, out, stem="material", max_iter=60)
    return material, shift, "fitting.calibrate(pyvisco data, T_ref = 25 C)"


def test_bearing(out, material, shift, quick):
    n = 256 if quick else 1024
    rpm = np.geomspace(1.0, 3000.0, 5 if quick else 14)
    material = material.with_shift(shift)      # moved by each row's temperature
    models = {"bushing (liner, 2 mm)": vjax.liner(material, WALL),
              "infinite plane, l = 1 m": vjax.hole(material, 1.0),
              "infinite plane, l = R_O": vjax.hole(material, RO)}
    rows, res = [], {}
    for name, body in models.items():
        for F in LOADS_N:
            for T in TEMPS:
                prev, out_rows = None, []
                for N in rpm:
                    r = vjax.roller_bearing(body, None, RO, RI, D, Z, F / NEEDLE_LENGTH, omega_shaft=N * np.pi / 30,
                                            temperature=T, initial=prev,
                                            options=vjax.RollerOptions(n=n), throw=False)
                    prev = r if bool(r.converged) else None
                    loads = np.asarray(r.roller_loads)[0]       # numpy: indexing a jax array compiles
                    out_rows.append((float(r.torque), int(np.sum(loads > 1e-9 * loads.max())),
                                     float(loads.max() * Z / (F / NEEDLE_LENGTH)), bool(r.converged)))
                    rows.append([name, F, T, float(N), *out_rows[-1]])
                res[(name, F, T)] = np.array(out_rows, dtype=float)
    _common.write_csv(out / "bodies_test_bearing.csv",
                      ["outer_ring", "load_N", "T_C", "rpm", "torque_Nm_per_m", "loaded_rollers", "Qmax_Z_over_F",
                       "converged"], rows,
                      comments=[f"R_O = {RO} m, R_I = {RI} m, Z = {Z}, D = {D} m, rigid shaft; n = {n}; loads per "
                                f"{NEEDLE_LENGTH} m needle length"])
    fig, axes = plt.subplots(2, len(LOADS_N) * len(TEMPS), figsize=(14, 6.5), sharex=True, constrained_layout=True)
    for j, (F, T) in enumerate((F, T) for F in LOADS_N for T in TEMPS):
        for name, style in zip(models, ("k-", "C0--", "C1:")):
            v = res[(name, F, T)]
            axes[0, j].loglog(rpm, np.abs(v[:, 0]), style, label=name)
            axes[1, j].semilogx(rpm, v[:, 1], style, label=name)
        axes[0, j].set_title(f"{F:g} N on {NEEDLE_LENGTH * 1e3:g} mm, {T:g} C", fontsize=9)
        axes[1, j].set_xlabel("shaft speed (rpm)")
        axes[1, j].yaxis.set_major_locator(MaxNLocator(integer=True))     # a count of rollers
    axes[0, 0].set_ylabel(r"friction torque $C_t$ (N m/m)")
    axes[1, 0].set_ylabel("loaded rollers")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(f"Thesis test bearing: bore {2 * RO * 1e3:g} mm, 2 mm polymer bushing in a rigid holder (or an "
                 f"infinite plane), {Z} rigid needles of {D * 1e3:g} mm, rigid shaft; calibrated polymer", fontsize=9)
    _common.save_figure(fig, out / "bodies_test_bearing.png")
    return res, rpm, n


def winkler(out):
    m, t, c, F, R = vjax.Material.elastic(1e8, 0.3), 1e-4, 1e-4, 2e4, 0.08
    r = vjax.pin_in_hole(vjax.liner(m, t), R, c, F, options=vjax.PinOptions(n=2048))
    alpha, _, p = reference.winkler_pin(F, R, c, reference.oedometric_stiffness(1e8, 0.3, t))
    return float(r.contact_angle), float(alpha), float(np.asarray(r.pressure).max()), float(p(0.0))


GIVE_UP = 3   # a water-journal sweep whose first GIVE_UP speeds all fail stops (each failure: ~1 s of CPU)


def water_journal(out, quick):
    n = 128 if quick else 256
    speeds = np.geomspace(5.0, 500.0, 4 if quick else 10)
    bodies = {"rubber liner 5 mm": vjax.liner(RUBBER, LINER), "infinite rubber plane": RUBBER}
    rows, res = [], {}
    for name, body in bodies.items():
        prev, vals = None, []
        for w in speeds:
            if len(vals) >= GIVE_UP and not any(v[4] > 0 for v in vals):
                vals.append((np.nan,) * 4 + (-1,))        # not tried: the sweep has failed from its start
                continue
            s = vjax.journal_bearing(JR, JC, WATER, JLOAD, housing=body, omega_shaft=w, initial=prev,
                                     options=vjax.JournalOptions(n=n), throw=False)
            ok = bool(s.converged)
            prev = s if ok else None
            share = 100 * float(s.torque_viscoelastic) / float(s.torque) if ok else np.nan
            vals.append((float(s.min_film) / JC if ok else np.nan, float(s.eccentricity_effective) if ok else np.nan,
                         float(s.torque) if ok else np.nan, share, int(ok)))
            rows.append([name, float(w), *vals[-1]])
        res[name] = np.array(vals, dtype=float)
    _common.write_csv(out / "bodies_water_journal.csv", ["bore", "omega_shaft_rad_s", "hmin_over_c", "eps_eff",
                                                          "torque_Nm_per_m", "viscoelastic_share_pct", "converged"],
                      rows, comments=[f"R = {JR} m, c = {JC} m, water {WATER} Pa s, load {JLOAD} N/m, n = {n}; rubber "
                                      "SLS E0 5 MPa, Einf 50 MPa, tau 1 ms, nu 0.49; stationary shell"])
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), constrained_layout=True)
    failed = [name for name in bodies if not np.isfinite(res[name][:, 0]).any()]
    for name, style in zip(bodies, ("k-o", "C1--s")):
        if name in failed:       # in the legend only what is drawn; the title names the rest
            continue
        v = res[name]
        axes[0].semilogx(speeds, v[:, 0], style, label=name)
        axes[1].semilogx(speeds, v[:, 1], style, label=name)
        axes[2].loglog(speeds, v[:, 2], style, label=name)
    for ax, lab in zip(axes, (r"$h_{min}/c$", r"$\epsilon_{eff}$", "friction torque on the shell (N m/m)")):
        ax.set(xlabel=r"shaft speed $\omega_J$ (rad/s)", ylabel=lab)
    axes[0].legend(fontsize=8)
    note = "missing points: no converged solution" + (f"; {' and '.join(failed)}: none at the speeds tried, not drawn"
                                                      if failed else "")
    fig.suptitle(f"Water-lubricated journal bearing: R = {JR * 1e3:g} mm, c = {JC * 1e6:g} um, rubber liner "
                 f"{LINER * 1e3:g} mm in a rigid shell vs an infinite rubber bore, {JLOAD:g} N/m\n{note}",
                 fontsize=9)
    _common.save_figure(fig, out / "bodies_water_journal.png")
    return res, speeds, n


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    material, shift, source = _material(out)
    lines = [f"bodies_figures: polymer from {source}: E0 = {float(material.E0):.4g} Pa, "
             f"Einf = {float(material.Einf):.4g} Pa, {material.times.shape[0]} Prony terms, nu = {float(material.nu)}"]
    tb, rpm, n = test_bearing(out, material, shift, quick)
    header = ["outer ring", "load N", "T C", "C_t at 10 rpm (N m/m)", "C_t at 1000 rpm", "loaded rollers", "max Q Z/F"]
    i10, i1000 = (int(np.argmin(np.abs(np.log(rpm / x)))) for x in (10.0, 1000.0))
    table = [[name, F, T, v[i10, 0], v[i1000, 0], f"{int(v[:, 1].min())}-{int(v[:, 1].max())}", float(v[:, 2].max())]
             for (name, F, T), v in tb.items()]
    lines += [f"Thesis test bearing (n = {n}, {len(rpm)} speeds {rpm[0]:g}..{rpm[-1]:g} rpm)",
              _common.format_table(header, table)]
    plane = [tb[(name, 50.0, 30.0)][:, 0] for name in ("infinite plane, l = 1 m", "infinite plane, l = R_O")]
    ref_spread = float(np.max(np.abs(plane[0] / plane[1] - 1)))
    bushing = tb[("bushing (liner, 2 mm)", 50.0, 30.0)][:, 0]
    lines.append(f"the infinite-plane torque moves by up to {100 * ref_spread:.1f}% between l = 1 m and l = R_O; "
                 f"the bushing has no such length; bushing / plane (l = 1 m) torque: "
                 f"{np.min(bushing / plane[0]):.3g}..{np.max(bushing / plane[0]):.3g}")
    a_num, a_w, p_num, p_w = winkler(out)
    lines.append(f"pin in a 0.1 mm bushing (E = 100 MPa, nu = 0.3): contact half-angle {a_num:.4f} rad, Winkler "
                 f"{a_w:.4f}; peak pressure {p_num:.4g} Pa, Winkler {p_w:.4g}")
    wj, speeds, nj = water_journal(out, quick)
    lines.append(f"Water-lubricated journal bearing (n = {nj}):")
    for name, v in wj.items():
        ok, tried = v[:, 4] > 0, int(np.sum(v[:, 4] >= 0))
        lines.append(f"  {name}: converged at {int(ok.sum())} of {len(speeds)} speeds; h_min/c "
                     f"{np.nanmin(v[:, 0]):.3g}..{np.nanmax(v[:, 0]):.3g}; eps_eff {np.nanmin(v[:, 1]):.3g}.."
                     f"{np.nanmax(v[:, 1]):.3g}; viscoelastic share {np.nanmax(np.abs(v[:, 3])):.2g}%"
                     if ok.any() else f"  {name}: no converged solution at the {tried} speeds tried (the lowest "
                                      f"{tried} of {len(speeds)}: the sweep stops when its first {GIVE_UP} all fail)")
    lines.append("  the shell is stationary and the load steady: the pressure pattern does not move relative to "
                 "the rubber, which therefore dissipates nothing (share 0). The infinite rubber plane deforms by "
                 "many clearances (its effective eccentricity is the first Fourier mode of the film over c); the "
                 "bonded 5 mm liner is far stiffer (its constrained modulus over its thickness)")
    text = "\n".join(lines) + "\n"
    _common.atomic_write_text(out / "bodies_summary.txt", text)
    print(text)
    failures = sum(int(np.sum(v[:, 3] == 0)) for (name, F, T), v in tb.items() if name.startswith("bushing"))
    checks = (
        _common.Check("bushing test bearing: solves that did not converge", failures, 0, 0, "solver report", "max"),
        _common.Check("pin in a thin bushing: contact half-angle over Winkler's", a_num / a_w, 1.0, 0.02,
                      "vjax.reference.winkler_pin (thin-layer limit)"),
        _common.Check("water journal with a rubber liner: speeds without a converged solution",
                      int(np.sum(wj["rubber liner 5 mm"][:, 4] == 0)), 0, 0, "solver report", "max"),
    )
    figures = (("bodies_test_bearing.png", "Thesis test bearing as built (2 mm bushing in a rigid holder) vs the "
                                           "infinite plane (l = 1 m, R_O): torque and loaded rollers vs speed"),
               ("bodies_water_journal.png", "Water-lubricated journal bearing: rubber liner vs infinite rubber bore"))
    about = ("Bodies of finite thickness: the thesis's test bearing with its real 2 mm bushing, a pin in a thin "
             "bushing against the Winkler limit, and a water-lubricated rubber-lined journal bearing, each side by "
             "side with the infinite-plane model.")
    return _common.StageReport(text, about, checks, figures)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
