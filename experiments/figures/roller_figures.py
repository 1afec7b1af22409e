"""Needle roller bearing (thesis Section 2.3): Figs. 2.14-2.21 with both memory models, and a
torque-versus-shaft-speed curve at two temperatures (after Figs. 2.24-2.29).

Run::

    PYTHONPATH=. python -m experiments.figures.roller_figures [out_dir] [--quick]

**Thesis case** (Section 2.3.2): R_O = 6 mm, R_I = 4 mm, D = 2 mm, Z = 9, zero clearance,
outer ring fixed, both rings SLS E0 = 1 MPa, Einf = 10 MPa, tau = 0.01 s, nu = 0.5,
F~ = F/(E0 R_O) = 6.5e-3 along x (roller 1 on the load line), ref_length = 1 m. The shaft
turns at omega_I > 0 and omega~ = |omega_O,c| tau = omega_c tau (omega_c the cage speed).
Each speed sweep is one jitted ``lax.scan`` from rest over 60 speeds (20 with --quick; the
snapshots' among them) with continuation (``roller_bearing(initial=previous)``), one per memory
model and load.

- Fig. 2.14 (``roller_fig2_14.png``): for rollers 1, 2, 3, 8, 9 (the load zone) the total
  deflection delta_j/R_O, the ring displacements at the roller u_j^O/R_O and u_j^I/R_O, the gap
  g_j/R_O and the load F_j/(E0 R_O) versus omega~; solid "periodic", dashed "thesis".
- Fig. 2.15 (``roller_fig2_15.png``): angle of the net force on the outer ring.
- Figs. 2.16-2.20 (``roller_fig2_16_20.png``): at omega~ = 0, 0.004, 0.2, 1.4, 1e3, the rings'
  deformed contours magnified K = 10 with the roller circles and the net force, and the
  pressure p/E0 on each roller of the load zone against the angle from the roller centre,
  inner and outer ring, both memory models.
- Fig. 2.21 (``roller_fig2_21.png``): C~ = |C_t|/(F R_O) (outer ring), tan(friction angle)
  and R*/R_O versus omega~ for F~ = 3e-3, 6.5e-3, 1.3e-2, both memory models.
- Torque versus shaft speed (``roller_torque_temperature.png``): steel shaft (rigid inner
  ring), polymer bushing (outer ring) of a documented 4-term Prony material with a WLF
  shift (the fitting issue's calibrated PTFE/PA6 materials are not in the package yet: the
  shipped ``dmasuite`` fit has E0 = 3e-3 Pa, i.e. no rubbery plateau, which a load-controlled
  dry contact cannot use), F = 50 N over a 7.8 mm needle, T = 30 and 50 C.

CSV files hold every plotted number; ``roller_figures.txt`` the printed summary (balance
errors, Stribeck ratio, the speed ranges where rollers 3 and 8 carry nothing).
"""
from __future__ import annotations

import sys
import time

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402
from vjax.operator import grid, memory_revolutions  # noqa: E402

RO, RI, D, Z = 6e-3, 4e-3, 2e-3, 9
E0, EINF, TAU, NU = 1e6, 1e7, 0.01, 0.5
F_TILDE = 6.5e-3
LOADS = (3e-3, 6.5e-3, 1.3e-2)
MEMORIES = ("periodic", "thesis")
STYLE = {"periodic": "-", "thesis": "--"}
SNAPS = (0.0, 0.004, 0.2, 1.4, 1e3)
ZONE = (0, 1, 2, 7, 8)          # rollers 1, 2, 3, 8, 9
SLS = vjax.Material.sls(E0, EINF, TAU, NU)


def _py(x):
    return x.item() if isinstance(x, np.generic) else x


def _write_csv(path, header, rows, comments=()):
    return _common.write_csv(path, header, [[_py(x) for x in r] for r in rows], comments=comments)


CASE = (f"R_O = {RO * 1e3:g} mm, R_I = {RI * 1e3:g} mm, Z = {Z} rollers of D = {D * 1e3:g} mm, zero clearance, "
        f"SLS rings (E0 = {E0 / 1e6:g} MPa, Einf = {EINF / 1e6:g} MPa, tau = {TAU} s, nu = {NU}), "
        r"$\tilde F$" + f" = {F_TILDE}")


def shaft_speed(w_tilde, tau=TAU):
    """omega_I giving omega_c tau = w_tilde with the outer ring fixed (omega_c = omega_I R_I/(R_I+R_O))."""
    return w_tilde / tau * (RI + RO) / RI


def _record(r, load):
    theta, alpha = grid(r.pressure.shape[-1])
    Fx = RI * 2 * alpha * jnp.sum(r.pressure_shaft * jnp.cos(theta))
    return dict(loads=r.roller_loads[0], loads_inner=r.roller_loads[1], deflection=r.deflection,
                u_outer=r.u_at_rollers[0], u_inner=r.u_at_rollers[1], gaps=r.gaps,
                force_angle=r.force_angle, friction_angle=r.friction_angle,
                torque=jnp.stack([r.torque, r.torque_shaft]),       # (housing, shaft)
                friction_radius=r.friction_radius, force=r.force, ring_shift=r.ring_shift,
                load_error=jnp.abs(Fx - load) / load,
                roller_error=jnp.max(jnp.abs(r.roller_loads[0] - r.roller_loads[1])) / load,
                iterations=r.iterations, residual=r.residual, converged=r.converged)


def make_sweep(n, outer_only=False):
    """Jitted continuation sweep ``f(material, load, shaft_speeds, memory) -> (dict of arrays,
    RollerResult)``, the results stacked along the speeds, ``memory`` the number of revolutions
    (inf: periodic; traced): one compiled program for both memory models, and for the snapshots
    of Figs. 2.16-2.20 (points of such a sweep)."""
    def solve(mat, load, w, memory, initial=None):
        shaft = None if outer_only else mat
        return vjax.roller_bearing(mat, shaft, RO, RI, D, Z, load, omega_shaft=w, memory=memory,
                                   options=vjax.RollerOptions(n=n), initial=initial, throw=False)

    @jax.jit
    def sweep(mat, load, ws, memory):
        # the first point from a result of NaNs: a cold start (vjax.roller_bearing) in the same
        # solve as the warm ones, so that the program holds one copy of it
        cold = jax.tree_util.tree_map(
            lambda a: jnp.full(a.shape, jnp.nan if jnp.issubdtype(a.dtype, jnp.floating) else 0, a.dtype),
            jax.eval_shape(lambda: solve(mat, load, ws[0], memory)))

        def step(prev, w):
            r = solve(mat, load, w, memory, initial=prev)
            return r, (_record(r, load), r)

        return jax.lax.scan(step, cold, ws)[1]

    return lambda mat, load, ws, memory="periodic": sweep(mat, load, ws, memory_revolutions(memory))


def _zero_ranges(w, loads, idx):
    """Speed intervals (first, last omega~) where all rollers ``idx`` carry nothing."""
    off = np.all(loads[:, idx] == 0, axis=1)
    out, start = [], None
    for i, o in enumerate(off):
        if o and start is None:
            start = i
        if (not o or i == len(off) - 1) and start is not None:
            end = i if o else i - 1
            out.append((float(w[start]), float(w[end])))
            start = None
    return out


def fig_2_14(w, res, out):
    fig, axes = plt.subplots(len(ZONE), 1, figsize=(8, 2.4 * len(ZONE)), sharex=True, constrained_layout=True)
    for ax, j in zip(axes, ZONE):
        ax2 = ax.twinx()
        for mem in MEMORIES:
            s = res[mem]
            ls = STYLE[mem]
            ax.semilogx(w, s["deflection"][:, j] / RO, "k" + ls, lw=1.2, label=r"$\delta_j/R_O$" if mem == "periodic" else None)
            ax.semilogx(w, s["u_outer"][:, j] / RO, "C0" + ls, label=r"$u_j^O/R_O$" if mem == "periodic" else None)
            ax.semilogx(w, s["u_inner"][:, j] / RO, "C2" + ls, label=r"$u_j^I/R_O$" if mem == "periodic" else None)
            ax.semilogx(w, s["gaps"][:, j] / RO, "C1" + ls, label=r"$g_j/R_O$" if mem == "periodic" else None)
            ax2.semilogx(w, s["loads"][:, j] / (E0 * RO), "C3" + ls, label=r"$F_{r,j}/(E_0R_O)$" if mem == "periodic" else None)
        ax.set_ylabel(f"roller {j + 1}")
        ax2.set_ylabel(r"$\tilde F_{r,j}$", color="C3")
    h1, l1 = axes[0].get_legend_handles_labels()
    h2, l2 = axes[0].get_figure().axes[len(ZONE)].get_legend_handles_labels()
    axes[0].legend(h1 + h2, l1 + l2, fontsize=7, ncol=5, loc="upper left")
    axes[-1].set_xlabel(r"$\tilde\omega = \omega_c\tau$   (solid: periodic memory, dashed: thesis kernel)")
    fig.suptitle(r"Fig. 2.14: rollers of the load zone, $\tilde F = 6.5\cdot10^{-3}$")
    _common.save_figure(fig, out / "roller_fig2_14.png")


def fig_2_15(w, res, out):
    fig, ax = plt.subplots(figsize=(6, 3.5), constrained_layout=True)
    for mem in MEMORIES:
        ax.semilogx(w, np.degrees(res[mem]["force_angle"]), "k" + STYLE[mem], label=mem)
    ax.set_xlabel(r"$\tilde\omega$")
    ax.set_ylabel(r"$\theta_F$ of $F^O_{tot}$ (deg)")
    ax.legend()
    ax.set_title("Fig. 2.15: angle of the net force on the outer ring")
    _common.save_figure(fig, out / "roller_fig2_15.png")


def fig_2_16_20(snaps, out):
    fig, axes = plt.subplots(len(SNAPS), 3, figsize=(13, 3.2 * len(SNAPS)), constrained_layout=True)
    K = 10.0
    for row, wt in enumerate(SNAPS):
        ax = axes[row, 0]
        r = snaps[("periodic", wt)]
        th = np.asarray(r.theta)
        C = np.array([float(r.ring_shift), 0.0])
        for u, R, sgn, c in ((r.displacement, RO, 1, (0, 0)), (r.displacement_shaft, RI, -1, C)):
            u = np.asarray(u)
            rr = R + sgn * K * u
            ax.plot(c[0] / RO + R / RO * np.cos(th), c[1] / RO + R / RO * np.sin(th), "k:", lw=0.6)
            ax.plot(c[0] / RO + rr / RO * np.cos(th), c[1] / RO + rr / RO * np.sin(th), "k-", lw=1)
        rho = RO - D / 2 + np.asarray(r.penetration_outer)
        for j, psi in enumerate(np.asarray(r.roller_angles)):
            col = "g" if bool(r.active[j]) else "0.6"
            circ = plt.Circle((rho[j] * np.cos(psi) / RO, rho[j] * np.sin(psi) / RO), D / 2 / RO, fill=False, color=col)
            ax.add_patch(circ)
            ax.text(0.75 * np.cos(psi), 0.75 * np.sin(psi), str(j + 1), fontsize=7, ha="center", va="center")
        F = np.asarray(r.force) / float(np.hypot(*r.force))
        ax.arrow(0, 0, 0.5 * F[0], 0.5 * F[1], color="r", width=0.01)
        ax.set_aspect("equal")
        ax.set_title(rf"$\tilde\omega$ = {wt:g}: contours x{K:g} (periodic), green = loaded", fontsize=9)
        for col, k, name in ((1, 1, "inner"), (2, 0, "outer")):
            ax = axes[row, col]
            for mem in MEMORIES:
                s = snaps[(mem, wt)]
                th = np.asarray(s.theta)
                p = np.asarray((s.pressure, s.pressure_shaft)[k]) / E0
                for ci, j in enumerate(ZONE):
                    psi = float(s.roller_angles[j])
                    if k == 1:   # the inner ring's angles are about its own centre
                        psi = float(np.arctan2(np.sin(psi) * (RO - D / 2), np.cos(psi) * (RO - D / 2) - float(s.ring_shift)))
                    dth = (th - psi + np.pi) % (2 * np.pi) - np.pi
                    sel = np.abs(dth) < 0.12
                    order = np.argsort(dth[sel])
                    ax.plot(np.degrees(dth[sel][order]), p[sel][order], f"C{ci}" + STYLE[mem], lw=1,
                            label=f"roller {j + 1}" if mem == "periodic" else None)
            ax.set_title(f"{name} ring pressure (solid periodic, dashed thesis)", fontsize=9)
            ax.set_xlabel(r"$\theta - \psi_j$ (deg)")
            ax.set_ylabel(r"$p/E_0$")
        axes[row, 1].legend(fontsize=7)
    fig.suptitle(r"Figs. 2.16-2.20: $\tilde F = 6.5\cdot10^{-3}$")
    _common.save_figure(fig, out / "roller_fig2_16_20.png")


def fig_2_21(w, torque_res, out):
    fig, axes = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
    for li, Ft in enumerate(LOADS):
        for mem in MEMORIES:
            s = torque_res[(mem, Ft)]
            load = Ft * E0 * RO
            lab = rf"$\tilde F$={Ft:g}, {mem}"
            axes[0].loglog(w, np.abs(s["torque"][:, 0]) / (load * RO), f"C{li}" + STYLE[mem], label=lab)
            axes[1].loglog(w, np.tan(s["friction_angle"]), f"C{li}" + STYLE[mem], label=lab)
            axes[2].loglog(w, s["friction_radius"] / RO, f"C{li}" + STYLE[mem], label=lab)
    for ax, yl in zip(axes, (r"$\tilde C = |C_t|/(F R_O)$", r"$\tan\varphi^*$", r"$R^*/R_O$")):
        ax.set_xlabel(r"$\tilde\omega$")
        ax.set_ylabel(yl)
        ax.set_ylim(bottom=1e-6)
    axes[0].legend(fontsize=8)
    fig.suptitle("Fig. 2.21: outer ring, three loads, both memory models")
    _common.save_figure(fig, out / "roller_fig2_21.png")


# A documented polymer bushing for the temperature curves: 4-term Prony (relaxation times
# one decade apart, 1 ms..1 s at 20 C), rubbery 0.1 GPa, glassy 1.5 GPa (PTFE-like
# magnitudes), WLF C1 = 8.86, C2 = 101.6 K referred to T_ref = 20 C (log10 a_T = -0.79 at
# 30 C and -2.02 at 50 C). Not a fit to data: a stand-in until the fitted materials land.
POLY = vjax.Material.prony(1e8, [3e8, 4e8, 4e8, 3e8], [1e-3, 1e-2, 1e-1, 1.0], 0.46)
WLF = vjax.WLF(8.86, 101.6, 20.0)
NEEDLE_LENGTH = 7.8e-3


def main(out_dir="experiments/out", quick=False):
    out = _common.setup(out_dir)
    n = 512 if quick else 1024
    # log-spaced speeds with Figs. 2.16-2.20's snapshots among them; every sweep starts from rest,
    # whose point is the first snapshot (and the elastic check) and is left out of the curves
    w = np.union1d(np.logspace(-4, 4, (20 if quick else 60) - len(SNAPS) + 1), SNAPS[1:])
    speeds = jnp.asarray(shaft_speed(np.concatenate([[0.0], w])))
    lines = [f"roller_figures: thesis case, n = {n} elements per ring, {w.size} speeds omega~ = 1e-4..1e4 "
             f"(among them {', '.join(f'{x:g}' for x in SNAPS[1:])}) after rest"]
    t0 = time.perf_counter()
    sweep = make_sweep(n)
    torque_res, snaps, failures = {}, {}, 0
    for mem in MEMORIES:
        for Ft in (LOADS if not quick else (F_TILDE,)):
            load = Ft * E0 * RO
            t = time.perf_counter()
            rec, full = jax.device_get(sweep(SLS, load, speeds, mem))
            s = torque_res[(mem, Ft)] = {k: np.asarray(v)[1:] for k, v in rec.items()}
            failures += int(np.sum(~np.asarray(rec["converged"])))        # the point at rest too
            if Ft == F_TILDE:
                for wt in SNAPS:
                    i = 0 if wt == 0.0 else 1 + int(np.flatnonzero(w == wt)[0])
                    snaps[(mem, wt)] = jax.tree_util.tree_map(lambda a, i=i: a[i], full)
            lines.append(f"  sweep {mem:8s} F~={Ft:g}: {time.perf_counter() - t:6.1f} s, all converged: "
                         f"{bool(np.all(s['converged']))}, Newton iterations {int(np.min(s['iterations']))}-"
                         f"{int(np.max(s['iterations']))}, max load-balance error "
                         f"{float(np.max(s['load_error'])):.1e}, max |F_O - F_I|/F {float(np.max(s['roller_error'])):.1e}")
    res = {mem: torque_res[(mem, F_TILDE)] for mem in MEMORIES}

    # rollers 3 and 8 out of contact
    for mem in MEMORIES:
        rng = _zero_ranges(w, res[mem]["loads"], [2, 7])
        lines.append(f"  {mem}: rollers 3 and 8 carry nothing for omega~ in "
                     + (", ".join(f"[{a:.3g}, {b:.3g}]" for a, b in rng) or "none of the grid"))
        i_peak = int(np.argmax(np.abs(res[mem]["torque"][:, 0])))
        lines.append(f"  {mem}: peak C~ = {np.abs(res[mem]['torque'][i_peak, 0]) / (F_TILDE * E0 * RO * RO):.3e} "
                     f"at omega~ = {w[i_peak]:.3g}; max |force angle| = "
                     f"{np.degrees(np.max(np.abs(res[mem]['force_angle']))):.2f} deg")
    # elastic limits and Stribeck
    for mem in MEMORIES:
        for i in (0, -1):
            L = res[mem]["loads"][i]
            asym = np.max(np.abs(L - L[(-np.arange(Z)) % Z])) / L.max()
            lines.append(f"  {mem} omega~={w[i]:g}: load asymmetry {asym:.1e}, C~ = "
                         f"{abs(res[mem]['torque'][i, 0]) / (F_TILDE * E0 * RO * RO):.1e}, Q_max Z/F = "
                         f"{L.max() * Z / (F_TILDE * E0 * RO):.4f}")
    for mem in MEMORIES:
        lines.append(f"  snapshots {mem}: all converged {all(bool(snaps[(mem, wt)].converged) for wt in SNAPS)}")
    # The elastic check: the SLS rings at rest are elastic rings of modulus E0 (their operator at zero
    # speed is the relaxed one), the snapshot at omega~ = 0
    r_el = snaps[("periodic", 0.0)]
    Q = np.asarray(r_el.roller_loads[0])
    c = np.maximum(np.cos(np.asarray(r_el.roller_angles)), 0)
    ratio = Q.max() * Z / (F_TILDE * E0 * RO)
    lines.append(f"  Stribeck/Harris (elastic E0 rings, zero clearance): Q_max Z / F_r = {ratio:.4f}; Harris line "
                 f"contact 4.08 (J_r = 0.2453); discrete Z = 9 with Q ~ delta^(10/9): "
                 f"{Z / np.sum(c ** (1 + 1 / 0.9)):.4f}; with Q ~ delta: {Z / np.sum(c ** 2):.4f}. Q_j/Q_max = "
                 + ", ".join(f"{q:.4f}" for q in Q[[0, 1, 2]] / Q.max())
                 + f" (Stribeck 10/9: {', '.join(f'{x:.4f}' for x in c[[0, 1, 2]] ** (1 / 0.9))})")

    # snapshots for Figs. 2.16-2.20
    fig_2_14(w, res, out)
    fig_2_15(w, res, out)
    fig_2_16_20(snaps, out)
    if not quick:
        fig_2_21(w, torque_res, out)

    # CSVs
    rows = []
    for mem in MEMORIES:
        s = res[mem]
        for i, wt in enumerate(w):
            for j in range(Z):
                rows.append([mem, float(wt), j + 1, float(s["deflection"][i, j] / RO), float(s["u_outer"][i, j] / RO),
                             float(s["u_inner"][i, j] / RO), float(s["gaps"][i, j] / RO),
                             float(s["loads"][i, j] / (E0 * RO)), float(np.degrees(s["force_angle"][i]))])
    _write_csv(out / "roller_sweep.csv", ["memory", "omega_tilde", "roller", "delta_over_RO", "uO_over_RO",
                                          "uI_over_RO", "gap_over_RO", "F_over_E0RO", "force_angle_outer_deg"], rows,
               comments=[f"thesis case, F~ = {F_TILDE}, n = {n}; Figs. 2.14-2.15"])
    rows = []
    for (mem, Ft), s in torque_res.items():
        load = Ft * E0 * RO
        for i, wt in enumerate(w):
            rows.append([mem, Ft, float(wt), float(s["torque"][i, 0] / (load * RO)), float(s["torque"][i, 1] / (load * RO)),
                         float(np.tan(s["friction_angle"][i])), float(s["friction_radius"][i] / RO)])
    _write_csv(out / "roller_torque.csv", ["memory", "F_tilde", "omega_tilde", "C_outer_over_FRO", "C_inner_over_FRO",
                                           "tan_friction_angle_outer", "friction_radius_over_RO"], rows,
               comments=["Fig. 2.21; torques on each ring about O (Eq. 2.40), signed"])
    rows = []
    for (mem, wt), s in snaps.items():
        for ring, pressure, displacement in (("outer", s.pressure, s.displacement),
                                             ("inner", s.pressure_shaft, s.displacement_shaft)):
            for th, p, u in zip(np.asarray(s.theta), np.asarray(pressure), np.asarray(displacement)):
                rows.append([mem, wt, ring, float(th), float(p / E0), float(u / RO)])
    _write_csv(out / "roller_rings.csv", ["memory", "omega_tilde", "ring", "theta", "p_over_E0", "u_over_RO"], rows,
               comments=["Figs. 2.16-2.20; inner-ring angles about the inner ring's centre"])

    # torque versus shaft speed at two temperatures (after Figs. 2.24-2.29)
    rpm = np.logspace(0, 4, 12 if quick else 30)
    load = 50.0 / NEEDLE_LENGTH
    sweep_T = make_sweep(n, outer_only=True)
    rows, fig = [], plt.figure(figsize=(6, 4), constrained_layout=True)
    for T in (30.0, 50.0):
        mat = POLY.at_temperature(WLF, T)
        s = jax.device_get(sweep_T(mat, load, jnp.asarray(rpm * 2 * np.pi / 60))[0])
        Ct = np.abs(np.asarray(s["torque"][:, 0]))          # N m/m
        lines.append(f"  bushing T = {T:g} C: all converged {bool(np.all(s['converged']))}, torque per unit length "
                     f"{Ct.min():.3e}..{Ct.max():.3e} N m/m over {rpm[0]:g}..{rpm[-1]:g} rpm (x {NEEDLE_LENGTH} m "
                     f"needle length: {Ct.min() * NEEDLE_LENGTH:.3e}..{Ct.max() * NEEDLE_LENGTH:.3e} N m)")
        plt.loglog(rpm, Ct, label=f"T = {T:g} C")
        rows += [[T, float(N), float(c)] for N, c in zip(rpm, Ct)]
    plt.xlabel("shaft speed N (rpm)")
    plt.ylabel(r"viscoelastic friction torque $C_t$ (N m/m)")
    plt.title(f"Rigid shaft, 4-term Prony bushing, {50.0 / NEEDLE_LENGTH:.0f} N/m (50 N on a 7.8 mm needle set), "
              "$R_O$ = 6 mm, $Z$ = 9", fontsize=8)
    plt.legend()
    _common.save_figure(fig, out / "roller_torque_temperature.png")
    _write_csv(out / "roller_torque_temperature.csv", ["T_C", "rpm", "torque_Nm_per_m"], rows,
               comments=["4-term Prony bushing (E0 = 0.1 GPa, Einf = 1.5 GPa, tau 1e-3..1 s at 20 C, nu = 0.46), "
                         "WLF C1 = 8.86, C2 = 101.6, T_ref = 20 C; rigid inner ring; Z = 9, R_O = 6 mm, R_I = 4 mm"])
    lines.append(f"  total {time.perf_counter() - t0:.1f} s")
    text = "\n".join(lines)
    print(text)
    _common.atomic_write_text(out / "roller_figures.txt", text + "\n")
    i14 = int(np.argmin(np.abs(np.log(w / 1.4))))
    checks = [
        _common.Check("all sweep points converged (count of failures)",
                      failures, 0, 0,
                      "solver report", "max"),
        _common.Check("load balance: max abs(F_x(inner ring) - F) / F over every sweep",
                      max(float(np.max(s["load_error"])) for s in torque_res.values()), 1e-9, 0,
                      "Eq. 2.38 equilibrium", "max"),
        _common.Check("elastic rings: Q_max Z / F_r", ratio, 4.08, 0.03 * 4.08,
                      "Stribeck/Harris line contact 4.08 (3%)"),
        _common.Check(f"rollers 3 and 8 at omega~ = {w[i14]:.3g}, periodic memory: their load (N/m)",
                      float(np.max(res["periodic"]["loads"][i14, [2, 7]])), 0.0, 0, "thesis Fig. 2.14: no contact",
                      "max"),
    ]
    figures = (
        ("roller_fig2_14.png", f"Fig. 2.14: deflection and ring displacements at the rollers versus omega~; {CASE}"),
        ("roller_fig2_15.png", "Fig. 2.15: angle of the net force on the outer ring versus omega~"),
        ("roller_fig2_16_20.png", "Figs. 2.16-2.20: deformed rings (magnified 10x) and ring pressures at five speeds"),
        ("roller_fig2_21.png", "Fig. 2.21: friction torque, friction angle and radius versus omega~ at three loads"),
        ("roller_torque_temperature.png", "Friction torque per unit length (N m/m) versus shaft speed at 30 and "
                                          "50 C: rigid shaft, 4-term Prony bushing with a WLF shift, 50 N on 7.8 mm"),
    )
    about = ("The needle roller bearing of thesis Section 2.3 (9 rigid rollers between two viscoelastic rings) "
             "over eight decades of speed with both memory models: load sharing, contact loss of rollers 3 "
             "and 8, friction torque; and a polymer bushing at two temperatures.")
    return _common.StageReport(text, about, tuple(checks), figures)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "experiments/out", quick="--quick" in sys.argv)
