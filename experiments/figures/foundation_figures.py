"""Foundation figures (issue 2): thesis Figs. 2.3 / A.4 and A.6, and material curves.

Run::

    PYTHONPATH=. python -m experiments.figures.foundation_figures [out_dir] [--quick]

**Deformed rings (Figs. 2.3, A.4, A.6).** A unit pressure (1 Pa) acts on one element,
centred at theta = 0, of a ring of radius R = 0.08 m cut into N = 400 elements (element
half-angle alpha = pi/400 = 7.85e-3 rad), the values of the caption of Fig. 2.3. The
pressure pattern rotates relative to the body at omega = omega~/tau, omega~ in
{0, 0.1, 1, 10, 1000}. Material (captions of Figs. 2.3, A.4, A.6): standard linear solid,
E0 = 1 MPa, Einf = 10 MPa, relaxation time tau = 0.01 s, nu = 0.5. Log-R reference length
1 m, as the thesis.

- Figs. 2.3 and A.4 show the same case: a hole in an infinite plane ("hole" kernel, A.45).
  The body is outside the ring, so u (positive into the body) pushes the contour outwards.
- Fig. A.6: cylinder under two diametrically opposite loads ("diametral" kernel, A.69): the
  same unit pressure acts on the element at theta = pi too. The body is inside, so u pushes
  the contour inwards. Captions A.4/A.6 give no radius: the Fig. 2.3 values are used.

The deformed contour is drawn at radius (R +- K u)/R with the magnification K = 1e7 of
Fig. 2.3, over the dashed undeformed circle. Each figure has one row per memory model of
:func:`vjax.ring_operator`: "periodic" (exact steady state) and "thesis" (Eq. 2.14/2.16,
one revolution of memory). omega > 0 moves the pattern towards +theta (counter-clockwise):
the leading edge is at theta > 0, the trailing edge at theta < 0.

**Materials.** Storage and loss moduli, tan delta (Eq. 1.43-1.44) and the relaxation and
creep (retardation, Eq. 2.3-2.4) spectra of the SLS above and of a synthetic 12-term
Prony series (:data:`PRONY12`): E0 = 1 MPa, tau_k = 1e-8 ... 1e3 s (one per decade),
E_k proportional to tau_k**-0.3 with sum E_k = 999 MPa (Einf = 1 GPa), nu = 0.5.

Outputs (in ``out_dir``): ``fig2_3_A4_hole.png``, ``figA6_diametral.png``,
``ring_profiles_u_theta.png``, ``material_curves.png``, ``ring_profiles.csv``,
``material_curves.csv``, ``material_spectra.csv``, ``foundation_summary.txt``.
"""
from __future__ import annotations

import functools
import sys

from experiments import _common

_common.enable_x64()

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vjax  # noqa: E402

R = 0.08                      # m, Fig. 2.3
N = 400                       # elements: alpha = pi/400 = 7.85e-3 rad, Fig. 2.3
MAGNIFICATION = 1e7           # K of Fig. 2.3
OMEGA_TILDES = (0.0, 0.1, 1.0, 10.0, 1000.0)
MEMORIES = ("periodic", "thesis")
SLS = vjax.Material.sls(E0=1e6, Einf=1e7, tau=0.01, nu=0.5)
TAU = 0.01
# Body side of each kernel: +1 if "into the body" is outwards (hole), -1 if inwards.
OUTWARD = {"hole": +1.0, "diametral": -1.0}
FIGURES = {"hole": ("fig2_3_A4_hole.png", "Figs. 2.3 / A.4: hole in an infinite plane (kernel A.45)"),
           "diametral": ("figA6_diametral.png",
                         "Fig. A.6: cylinder under diametral loads at 0 and $\\pi$ (kernel A.69)")}


def prony12():
    """Synthetic 12-term Prony series documented in the module docstring."""
    times = 10.0 ** np.arange(-8, 4)
    w = times ** -0.3
    return vjax.Material.prony(1e6, (1e9 - 1e6) * w / w.sum(), times, 0.5)


PRONY12 = prony12()


@functools.lru_cache(maxsize=None)
def _profiles_fn(kind, n, memory):
    """Jitted (material, omegas) -> u of shape (len(omegas), n) under 1 Pa on element 0."""
    sigma = jnp.zeros(n).at[0].set(1.0)

    def one(material, omega):
        return vjax.ring_operator(kind, material, R, n, omega=omega, memory=memory)(sigma)

    return jax.jit(jax.vmap(one, in_axes=(None, 0)))


def ring_profiles(kind, n=N, omega_tildes=OMEGA_TILDES, memories=MEMORIES, material=SLS, tau=TAU):
    """u(theta_i) (m) under 1 Pa on element 0, for every (memory, omega~): dict of arrays."""
    out = {}
    for mem in memories:
        u = np.asarray(_profiles_fn(kind, n, mem)(material, jnp.asarray(omega_tildes) / tau))
        out.update({(mem, wt): u[i] for i, wt in enumerate(omega_tildes)})
    return out


def signed_theta(n):
    """Element centres in [-pi, pi) (rad), in grid order."""
    th = 2 * np.pi * np.arange(n) / n          # = vjax.grid(n)[0], in numpy
    return np.where(th >= np.pi, th - 2 * np.pi, th)


def asymmetry(u, near_deg=5.0):
    """Trailing- versus leading-edge displacement of a profile ``u`` on the grid.

    Returns a dict: ``peak_deg`` (angle of the largest u within 90 deg of the load),
    ``near_deg`` (grid angle nearest to ``near_deg``), ``u_trail`` and ``u_lead`` (u at
    -/+ that angle, m), ``max_diff`` (max over theta in (0, pi) of u(-theta) - u(theta), m;
    > 0 means the trailing side is higher) and ``max_diff_deg`` (where).
    """
    n = u.size
    th = signed_theta(n)
    near = np.abs(th) < np.pi / 2
    k_peak = np.flatnonzero(near)[np.argmax(u[near])]
    mirror = u[(-np.arange(n)) % n]          # u(-theta_i)
    d = mirror - u
    half = np.arange(1, n // 2)              # theta_i in (0, pi)
    k = half[np.argmax(d[half])]
    k_near = max(1, int(round(np.radians(near_deg) * n / (2 * np.pi))))
    return dict(peak_deg=float(np.degrees(th[k_peak])), near_deg=float(np.degrees(th[k_near])),
                u_trail=float(u[-k_near]), u_lead=float(u[k_near]),
                max_diff=float(d[k]), max_diff_deg=float(np.degrees(th[k])))


def plot_ring_figure(kind, profiles, n, path, dpi):
    """One row per memory model, one column per omega~: deformed contour over the dashed circle."""
    th = signed_theta(n)
    order = np.argsort(th)
    th_s = np.append(th[order], th[order][0] + 2 * np.pi)
    fine = np.linspace(0, 2 * np.pi, 721)
    mems = sorted({m for m, _ in profiles}, key=MEMORIES.index)
    wts = sorted({w for _, w in profiles})
    fig, axes = plt.subplots(len(mems), len(wts), figsize=(max(3.3 * len(wts), 11.0), 4.0 * len(mems) + 1.3),
                             squeeze=False, layout="constrained")
    s = OUTWARD[kind]
    lim = 1.1 + max(0.0, s * MAGNIFICATION * max(float(np.max(s * u)) for u in profiles.values()) / R)
    loads = [0.0] if kind == "hole" else [0.0, np.pi]
    for i, mem in enumerate(mems):
        for j, wt in enumerate(wts):
            ax = axes[i, j]
            u = profiles[mem, wt]
            u_s = np.append(u[order], u[order][0])
            r = 1.0 + s * MAGNIFICATION * u_s / R
            ax.plot(np.cos(fine), np.sin(fine), "k--", lw=0.9, label="undeformed")
            ax.plot(r * np.cos(th_s), r * np.sin(th_s), "k-", lw=1.4, label=f"deformed, K = {MAGNIFICATION:.0e}")
            for t0 in loads:  # loaded element(s), and the direction the pattern moves (+theta)
                seg = np.linspace(t0 - np.pi / n, t0 + np.pi / n, 5)
                ax.plot(np.cos(seg), np.sin(seg), color="tab:red", lw=5, solid_capstyle="butt")
                if wt > 0:
                    a0, a1 = t0 + 0.35, t0 + 0.75
                    rr = 0.75
                    ax.annotate("", xy=(rr * np.cos(a1), rr * np.sin(a1)),
                                xytext=(rr * np.cos(a0), rr * np.sin(a0)),
                                arrowprops=dict(arrowstyle="->", color="tab:red",
                                                connectionstyle="arc3,rad=0.2"))
            ax.set_aspect("equal")
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
            ax.set_title(f"$\\tilde\\omega = \\omega\\tau$ = {wt:g}\nmemory = \"{mem}\"", fontsize=10)
            ax.set_xlabel(r"$\tilde x = x/R$")
            if j == 0:
                ax.set_ylabel(r"$\tilde y = y/R$")
            ax.grid(alpha=0.3)
            if i == 0 and j == 0:
                ax.legend(loc="lower left", fontsize=9)
    name, title = FIGURES[kind]
    fig.suptitle(
        f"{title}: deformed profile under a unit pressure (1 Pa) on one element (red), magnified "
        f"K = {MAGNIFICATION:.0e}\nSLS $E_0$ = 1 MPa, $E_\\infty$ = 10 MPa, $\\tau$ = 0.01 s, "
        f"$\\nu$ = 0.5; R = {R} m, N = {n} ($\\alpha$ = {np.pi / n:.3g} rad).\nRed arrow: pattern "
        r"moves towards $+\theta$ ($\omega > 0$); trailing edge at $\theta < 0$."
        "\nRows: memory model \"periodic\" (exact steady state) and \"thesis\" "
        "(Eq. 2.14/2.16, one revolution).", fontsize=10)
    return _common.save_figure(fig, path, dpi=dpi)


def plot_profiles_u_theta(all_profiles, n, path, dpi):
    """u(theta) near the load (Cartesian): rows kernel, columns memory model."""
    th = signed_theta(n)
    order = np.argsort(th)
    kinds = list(all_profiles)
    fig, axes = plt.subplots(len(kinds), 2, figsize=(12, 4.2 * len(kinds)), squeeze=False, sharex=True,
                             layout="constrained")
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(OMEGA_TILDES)))
    for i, kind in enumerate(kinds):
        for j, mem in enumerate(MEMORIES):
            ax = axes[i, j]
            for c, wt in zip(colors, OMEGA_TILDES):
                if (mem, wt) in all_profiles[kind]:
                    u = all_profiles[kind][mem, wt]
                    ax.plot(np.degrees(th[order]), 1e9 * u[order], "-", color=c, lw=1.3,
                            label=f"$\\tilde\\omega$ = {wt:g}")
            ax.set_xlim(-40, 40)
            ax.axvspan(-180 / n, 180 / n, color="tab:red", alpha=0.25, lw=0)
            ax.set_title(f"{FIGURES[kind][1].split(':')[0]} ({kind}), memory = \"{mem}\"", fontsize=10)
            ax.set_ylabel("u (nm), positive into the body")
            ax.grid(alpha=0.3)
            ax.text(0.02, 0.95, "trailing edge", transform=ax.transAxes, va="top", fontsize=9)
            ax.text(0.98, 0.95, "leading edge", transform=ax.transAxes, va="top", ha="right", fontsize=9)
            if i == len(kinds) - 1:
                ax.set_xlabel(r"$\theta$ (deg); pattern moves towards $+\theta$")
            if i == 0 and j == 0:
                ax.legend(fontsize=9, loc="center right")
    fig.suptitle("Radial displacement u($\\theta$) under 1 Pa on one element (shaded), SLS "
                 "$E_0$ = 1 MPa, $E_\\infty$ = 10 MPa, $\\tau$ = 0.01 s, $\\nu$ = 0.5, "
                 f"R = {R} m, N = {n}  (Eq. 2.18)", fontsize=10)
    return _common.save_figure(fig, path, dpi=dpi)


@jax.jit
def _material_arrays(material, omega):
    """E*(omega), the creep spectrum and the creep-form compliance, in one compiled call."""
    spec = material.creep_spectrum()
    return material.modulus(omega), spec, spec.compliance(omega)


def material_data(omega):
    """Curves and spectra of the two materials: (curves dict, spectra dict, creep-form errors)."""
    curves, spectra, errs = {}, {}, {}
    for name, mat in (("SLS", SLS), ("Prony12", PRONY12)):
        Estar, spec, J_creep = _material_arrays(mat, jnp.asarray(omega))
        Estar, J_creep = np.asarray(Estar), np.asarray(J_creep)
        rel = np.abs(J_creep * Estar - 1.0)        # |J_creep - 1/E*| / |1/E*|
        curves[name] = dict(storage=Estar.real, loss=Estar.imag, tan_delta=Estar.imag / Estar.real,
                            creep_rel_err=rel)
        spectra[name] = dict(tau=np.asarray(mat.times), E=np.asarray(mat.moduli),
                             lam=np.asarray(spec.retardation_times), C=np.asarray(spec.C),
                             J0=float(spec.J0), E0=float(mat.E0), Einf=float(mat.Einf))
        errs[name] = float(rel.max())
    return curves, spectra, errs


def plot_materials(omega, curves, spectra, path, dpi):
    fig, ax = plt.subplots(2, 2, figsize=(12, 9), layout="constrained")
    styles = {"SLS": "tab:blue", "Prony12": "tab:orange"}
    labels = {"SLS": "SLS ($E_0$ = 1 MPa, $E_\\infty$ = 10 MPa, $\\tau$ = 0.01 s)",
              "Prony12": "12-term Prony ($E_0$ = 1 MPa, $E_\\infty$ = 1 GPa)"}
    for name, c in curves.items():
        col = styles[name]
        ax[0, 0].loglog(omega, c["storage"], "-", color=col, label=f"$E'$ {name}")
        ax[0, 0].loglog(omega, c["loss"], "--", color=col, label=f"$E''$ {name}")
        ax[0, 1].loglog(omega, c["tan_delta"], "-", color=col, label=labels[name])
        sp = spectra[name]
        ax[1, 0].loglog(sp["tau"], sp["E"], "o-", color=col, label=f"{name}: $E_k$ at $\\tau_k$")
        ax[1, 1].loglog(sp["lam"], sp["C"], "s-", color=col,
                        label=f"{name}: $C_k$ at $\\lambda_k$ ($J_0$ = 1/$E_\\infty$ = {sp['J0']:.3g} 1/Pa)")
    ax[0, 0].set(xlabel=r"$\omega$ (rad/s)", ylabel="modulus (Pa)",
                 title="(a) storage $E'$ (solid) and loss $E''$ (dashed) moduli, Eq. 1.43-1.44")
    ax[0, 1].set(xlabel=r"$\omega$ (rad/s)", ylabel=r"$\tan\delta = E''/E'$ (-)", title=r"(b) loss factor $\tan\delta$")
    ax[1, 0].set(xlabel=r"relaxation time $\tau_k$ (s)", ylabel="arm modulus $E_k$ (Pa)",
                 title="(c) relaxation spectrum (Prony arms, Eq. 1.44)")
    ax[1, 1].set(xlabel=r"retardation time $\lambda_k$ (s)", ylabel="creep compliance $C_k$ (1/Pa)",
                 title="(d) creep (retardation) spectrum, Eq. 2.3-2.4")
    for a in ax.flat:
        a.grid(alpha=0.3, which="both")
    for a, loc in zip(ax.flat, ("upper left", "lower center", "upper right", "lower right")):
        a.legend(fontsize=9, loc=loc)
    fig.suptitle(r"Material laws: $E^*(\omega) = E_0 + \sum_k E_k\, i\omega\tau_k/(1+i\omega\tau_k)$;  "
                 r"$1/E^* = J_0 + \sum_k C_k/(1+i\omega\lambda_k)$", fontsize=11)
    return _common.save_figure(fig, path, dpi=dpi)


def main(out_dir="experiments/out", quick=False):
    """Write the figures, CSVs and summary into ``out_dir``; return the summary text."""
    out = _common.setup(out_dir)
    n = 128 if quick else N
    dpi = 60 if quick else 150
    written = []

    # ---- deformed rings ---------------------------------------------------------
    wts = (0.0, 0.1, 1000.0) if quick else OMEGA_TILDES   # quick: fewer panels to draw
    profiles = {kind: ring_profiles(kind, n, omega_tildes=wts) for kind in FIGURES}
    for kind in FIGURES:
        written.append(plot_ring_figure(kind, profiles[kind], n, out / FIGURES[kind][0], dpi))
    written.append(plot_profiles_u_theta(profiles, n, out / "ring_profiles_u_theta.png", dpi))
    th = np.asarray(vjax.grid(n)[0])
    rows = []
    for kind in FIGURES:
        s = OUTWARD[kind]
        for (mem, wt), u in profiles[kind].items():
            r = 1.0 + s * MAGNIFICATION * u / R
            rows += [(kind, mem, wt, float(t), float(ui), float(ri * np.cos(t)), float(ri * np.sin(t)))
                     for t, ui, ri in zip(th, u, r)]
    written.append(_common.write_csv(
        out / "ring_profiles.csv",
        ["kind", "memory", "omega_tilde", "theta_rad", "u_m", "x_tilde", "y_tilde"], rows,
        comments=[f"u: radial displacement (m, positive into the body) under 1 Pa on the element at theta=0 "
                  f"(and at pi for 'diametral'); R={R} m, N={n}, SLS E0=1e6 Pa, Einf=1e7 Pa, tau=0.01 s, nu=0.5",
                  f"x_tilde, y_tilde: deformed contour (R + sign*K*u)/R at angle theta, K={MAGNIFICATION:g}, "
                  "sign +1 hole (body outside), -1 diametral (body inside)"]))

    # ---- materials --------------------------------------------------------------
    omega = np.logspace(-6, 11, 120 if quick else 681)
    curves, spectra, errs = material_data(omega)
    written.append(plot_materials(omega, curves, spectra, out / "material_curves.png", dpi))
    written.append(_common.write_csv(
        out / "material_curves.csv",
        ["material", "omega_rad_s", "storage_Pa", "loss_Pa", "tan_delta", "creep_form_rel_err"],
        [(name, float(w), float(c["storage"][i]), float(c["loss"][i]), float(c["tan_delta"][i]),
          float(c["creep_rel_err"][i])) for name, c in curves.items() for i, w in enumerate(omega)],
        comments=["creep_form_rel_err = |J0 + sum C_k/(1 + i omega lambda_k) - 1/E*| / |1/E*|"]))
    written.append(_common.write_csv(
        out / "material_spectra.csv",
        ["material", "k", "tau_k_s", "E_k_Pa", "lambda_k_s", "C_k_per_Pa", "E0_Pa", "Einf_Pa", "J0_per_Pa"],
        [(name, k, float(sp["tau"][k]), float(sp["E"][k]), float(sp["lam"][k]), float(sp["C"][k]),
          sp["E0"], sp["Einf"], sp["J0"])
         for name, sp in spectra.items() for k in range(sp["tau"].size)],
        comments=["tau_k sorted as given; lambda_k sorted ascending (they pair by order: tau_k < lambda_k)"]))

    # ---- summary ----------------------------------------------------------------
    table = []
    for kind in FIGURES:
        for (mem, wt), u in profiles[kind].items():
            a = asymmetry(u)
            table.append((kind, mem, wt, 1e9 * float(u.max()), a["peak_deg"], 1e9 * a["u_trail"],
                          1e9 * a["u_lead"], a["u_trail"] / a["u_lead"], 1e9 * a["max_diff"],
                          # symmetric profile: the angle of a round-off difference means nothing
                          a["max_diff_deg"] if a["max_diff"] > 1e-9 * float(u.max()) else float("nan"),
                          1e9 * float(u.mean())))
    near = asymmetry(profiles["hole"][MEMORIES[0], OMEGA_TILDES[0]])["near_deg"]
    header = ["kind", "memory", "omega~", "u_peak_nm", "peak_deg", f"u(-{near:.2g}deg)_nm",
              f"u(+{near:.2g}deg)_nm", "trail/lead", "max_diff_nm", "at_deg", "u_mean_nm"]
    lines = [f"foundation_figures: {'quick' if quick else 'full'} run, N = {n}, R = {R} m, "
             f"unit pressure 1 Pa on one element, SLS E0=1 MPa Einf=10 MPa tau=0.01 s nu=0.5",
             "u_peak: largest displacement (at the loaded element); u(-/+th): trailing / leading "
             "side; max_diff: max over th of u(-th) - u(th) (> 0: trailing side higher), at_deg: "
             "where; u_mean: mode n = 0",
             _common.format_table(header, table), "",
             "creep-spectrum check, max abs(J_creep / J* - 1) over omega 1e-6..1e11 rad/s: "
             + ", ".join(f"{k} {v:.2e}" for k, v in errs.items()),
             "Prony12 retardation times lambda_k (s): "
             + " ".join(f"{x:.3g}" for x in spectra["Prony12"]["lam"]),
             "SLS retardation time (s): " + " ".join(f"{x:.4g}" for x in spectra["SLS"]["lam"])
             + " (expected (Einf/E0) tau = 0.1)"]
    summary_path = out / "foundation_summary.txt"
    written.append(summary_path)
    lines += ["", "written:"] + [f"  {p}" for p in written]
    text = "\n".join(lines) + "\n"
    _common.atomic_write_text(summary_path, text)
    print(text, end="")
    lam_sls = float(np.max(spectra["SLS"]["lam"]))
    hole = {(mem, wt): asymmetry(u) for (mem, wt), u in profiles["hole"].items()}
    checks = [
        _common.Check("creep spectrum: max abs(J_creep / J* - 1) over omega 1e-6..1e11 rad/s", max(errs.values()), 1e-8,
                      0, "the complex compliance 1/E*", "max"),
        _common.Check("SLS retardation time (s)", lam_sls, 0.1, 1e-12, "(Einf/E0) tau = 0.1 s (Eq. 1.41)"),
        _common.Check("moving load on a hole: smallest trailing/leading displacement ratio",
                      min(a["u_trail"] / a["u_lead"] for (mem, wt), a in hole.items() if 0 < wt < 1e3), 1.0, 0,
                      "viscoelastic lag: the trailing side is higher (Fig. 2.3)", "min"),
    ]
    figures = (
        ("fig2_3_A4_hole.png", f"Fig. 2.3 / A.4: displacement of a hole (R = {R} m) under 1 Pa on one element, "
                               "SLS E0 = 1 MPa, Einf = 10 MPa, tau = 0.01 s, at several speeds, both memory models"),
        ("figA6_diametral.png", "Fig. A.6: cylinder under diametral forces"),
        ("ring_profiles_u_theta.png", "Displacement profiles of hole and cylinder versus angle"),
        ("material_curves.png", "Storage and loss moduli, tan delta, creep spectra of the test materials"),
    )
    about = ("The building blocks: material laws and their creep spectra, and the ring operators "
             "(Green's functions of a hole and a cylinder) under a moving unit pressure.")
    return _common.StageReport(text, about, tuple(checks), figures)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(out_dir=args[0] if args else "experiments/out", quick="--quick" in sys.argv)
