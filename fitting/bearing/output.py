"""What ``vjax-bearing`` writes: points.csv, coefficients.csv, PNG figures and report.md.

Everything is written into a directory the caller gives (the CLI's temporary folder, renamed
over the case's folder at the end). The coefficients' column layout is ROSS's bearing table
(``kxx, kxy, kyx, kyy`` N/m, ``cxx, cxy, cyx, cyy`` N s/m, ``frequency`` rad/s), documented in
docs/bearing_files.md; no cell of that file holds "rpm", "lb" or "inches", words that make
ROSS's table reader convert units.
"""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

__all__ = ["COEFFICIENT_COLUMNS", "coefficient_rows", "write_outputs", "summary_table"]

_K = ["kxx", "kxy", "kyx", "kyy"]
_C = ["cxx", "cxy", "cyx", "cyy"]
COEFFICIENT_COLUMNS = (["point", "temperature_C", "load_N", "speed", "frequency", "whirl_ratio"] + _K + _C
                       + [k + "_bar" for k in _K] + [k + "_bar" for k in _C])


def coefficient_rows(case, points) -> list:
    """One row per converged journal point and whirl ratio: K (N/m) and C (N s/m), the
    bearing's totals (a long bearing's per-length values times geometry.length), and their
    dimensionless forms K c / W and C c omega / W (W the load, omega the turning body's speed)."""
    rows, c = [], case.geometry["c"]
    scale = 1.0 if case.scene == "finite_journal" else case.length
    for p in points:
        co = p.coefficients
        if co is None or p.reason:
            continue
        W = p.load if case.scene == "finite_journal" else p.load * case.length
        K, C = np.asarray(co.stiffness) * scale, np.asarray(co.damping) * scale
        for j, (ratio, whirl) in enumerate(zip(case.whirl_ratios, np.asarray(co.whirl))):
            k, d = K[j].ravel(), C[j].ravel()       # [xx, xy, yx, yy]
            rows.append([p.index, p.temperature, W, p.speed, float(whirl), ratio, *map(float, k), *map(float, d),
                         *(float(x) * c / W for x in k), *(float(x) * c * p.speed / W for x in d)])
    return rows


def _csv(header, rows) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow(["" if v is None else repr(v) if isinstance(v, float) else v for v in r])
    return buf.getvalue()


def _fmt(v, spec):
    return "" if v is None else format(v, spec) if isinstance(v, (int, float)) and not isinstance(v, bool) else str(v)


def summary_table(case, points) -> str:
    """The points as a Markdown table (the report's, and what the CLI prints)."""
    row0 = points[0].row
    load_key = next(k for k in row0 if k.startswith("load_"))
    torque_key = next(k for k in row0 if k.startswith("friction_torque_"))
    cols = [("speed_rpm", "rpm", ".4g")]
    if case.temperatures != (None,):
        cols.append(("temperature_C", "T (C)", ".4g"))
    cols.append((load_key, f"load ({load_key[5:].replace('_per_', '/')})", ".4g"))
    if case.journal:
        cols += [("eccentricity", "eps", ".3f"), ("attitude_deg", "attitude (deg)", ".1f"),
                 ("min_film_m", "h_min (um)", ".3g"), ("max_pressure_Pa", "p_max (MPa)", ".3g")]
    elif case.scene == "pin":
        cols += [("contact_angle_deg", "contact angle (deg)", ".1f"), ("max_pressure_Pa", "p_max (MPa)", ".3g")]
    else:
        cols += [("max_pressure_Pa", "p_max (MPa)", ".3g")]
    unit = torque_key[len("friction_torque_"):].replace("Nm", "N m").replace("_per_", "/")
    cols += [(torque_key, f"friction torque ({unit})", ".4g"), ("friction_coefficient", "mu", ".4f")]
    if case.journal:
        cols.append(("viscoelastic_share", "visco share", ".3f"))
    scale = {"min_film_m": 1e6, "max_pressure_Pa": 1e-6}
    lines = ["| " + " | ".join(h for _, h, _ in cols) + " | status |", "|" + "---|" * (len(cols) + 1)]
    for p in points:
        cells = []
        for k, _, spec in cols:
            v = p.row.get(k)
            cells.append(_fmt(v * scale.get(k, 1.0) if isinstance(v, float) else v, spec))
        lines.append("| " + " | ".join(cells) + f" | {'ok' if p.row['converged'] else 'FAILED'} |")
    return "\n".join(lines)


def _sweeps(case, points):
    """Points grouped by (temperature, load), each a speed sweep, with a legend label."""
    out = {}
    for p in points:
        out.setdefault((p.temperature, p.load), []).append(p)
    unit = "N" if case.scene == "finite_journal" or case.length else "N/m"
    for (T, W), ps in out.items():
        Wout = W if case.scene == "finite_journal" else W * (case.length or 1.0)
        yield (f"{Wout:.4g} {unit}" + (f", {T:g} C" if T is not None else "")), ps


def _figures(case, points, folder: Path) -> list:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    made = []
    row0 = points[0].row
    tkey = next(k for k in row0 if k.startswith("friction_torque_"))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for label, ps in _sweeps(case, points):
        ok = [p for p in ps if p.row["converged"]]
        rpm = [p.row["speed_rpm"] for p in ok]
        a1.plot(rpm, [p.row[tkey] for p in ok], "o-", label=label)
        a2.plot(rpm, [p.row["friction_coefficient"] for p in ok], "o-", label=label)
        bad = [p for p in ps if not p.row["converged"]]
        if bad:
            a1.plot([p.row["speed_rpm"] for p in bad], [0.0] * len(bad), "rx")
    for a in (a1, a2):
        a.set_xscale("log" if case.speeds.max() / case.speeds.min() > 10 else "linear")
        a.set_xlabel("speed (rpm)")
        a.grid(True, alpha=0.3)
    a1.set_ylabel(tkey.replace("friction_torque_", "friction torque (").replace("Nm", "N m").replace("_per_", "/") + ")")
    a2.set_ylabel("friction coefficient")
    a1.legend(fontsize=7)
    anyfail = any(not p.row["converged"] for p in points)
    fig.suptitle(f"{case.title}: friction against speed" + (" (x: failed point)" if anyfail else ""), fontsize=9)
    fig.savefig(folder / "torque_friction.png", dpi=120)
    plt.close(fig)
    made.append(("torque_friction.png", "Friction torque and friction coefficient against speed, one line per load"
                 + (" and temperature" if case.temperatures != (None,) else "") + "."))
    if case.journal:
        fig, ax = plt.subplots(figsize=(4.6, 4.6), constrained_layout=True)
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(np.cos(t), np.sin(t), "k-", lw=0.8)
        for label, ps in _sweeps(case, points):
            ok = [p for p in ps if p.row["converged"]]
            e = np.array([p.row["eccentricity"] for p in ok])
            a = np.radians([p.row["attitude_deg"] for p in ok])
            ax.plot(e * np.sin(a), -e * np.cos(a), "o-", label=label)    # load downward, attitude from it
        ax.annotate("load", xy=(0, -0.25), xytext=(0, 0.05), arrowprops=dict(arrowstyle="->"), ha="center")
        ax.set_aspect("equal")
        ax.set_xlim(-1.1, 1.1)
        ax.set_ylim(-1.1, 1.1)
        ax.set_xlabel("x / c (load frame)")
        ax.set_ylabel("y / c")
        ax.legend(fontsize=7, loc="upper right")
        ax.set_title("journal centre locus (speed rising along each line)", fontsize=9)
        fig.savefig(folder / "eccentricity_locus.png", dpi=120)
        plt.close(fig)
        made.append(("eccentricity_locus.png", "The journal centre's locus in the clearance circle (load downward), "
                     "one line per load, speed rising along it."))
    if case.scene == "finite_journal":
        ok = [p for p in points if p.row["converged"]]
        if ok:
            p = max(ok, key=lambda q: q.row["max_pressure_Pa"])
            r = p.result
            th, z = np.degrees(np.asarray(r.theta)), np.asarray(r.z) * 1e3
            fig, axs = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)
            for ax, data, lab in ((axs[0], np.asarray(r.film) / case.geometry["c"], "film h / c"),
                                  (axs[1], np.asarray(r.pressure) / 1e6, "pressure (MPa)")):
                im = ax.pcolormesh(th, z, data.T, shading="nearest")
                fig.colorbar(im, ax=ax, label=lab)
                ax.set_xlabel("angle from the load (deg)")
                ax.set_ylabel("axial position z (mm)")
            fig.suptitle(f"point {p.index}: {p.row['speed_rpm']:.4g} rpm, load {p.load:.4g} N"
                         + (f", {p.temperature:g} C" if p.temperature is not None else "")
                         + " (the highest peak pressure of the run)", fontsize=9)
            fig.savefig(folder / "film_pressure.png", dpi=120)
            plt.close(fig)
            made.append(("film_pressure.png", f"Film thickness and pressure over the land at point {p.index}, the "
                         "highest peak pressure of the run."))
    return made


def _inputs(case) -> list:
    g, lines = case.geometry, []
    names = {"R": "bore / hole radius", "c": "radial clearance", "length": "axial length", "R_outer": "outer raceway radius",
             "R_inner": "inner raceway radius", "D": "roller diameter", "Z": "rollers",
             "clearance": "diametral clearance", "supply_angle": "groove angle from the load (rad)"}
    for k, v in g.items():
        if v is not None:
            unit = "" if k in ("Z", "supply_angle") else " m"
            lines.append(f"| {names.get(k, k)} | {v:.6g}{unit} |")
    for side, b in (("housing", case.housing), ("shaft", case.shaft)):
        if b.kind == "rigid":
            lines.append(f"| {side} | rigid |")
            continue
        m = b.material
        desc = (f"{b.kind}" + (f", thickness {b.thickness:.4g} m" if b.thickness else f", ref_length {b.ref_length:g} m")
                + f"; Prony E0 = {float(m.E0):.4g} Pa, {np.asarray(m.moduli).size} terms, glassy "
                f"{float(m.E0) + float(np.sum(np.asarray(m.moduli))):.4g} Pa, nu = {float(m.nu):g}; "
                f"shift: {type(b.shift).__name__ if b.shift is not None else 'none'}; from {b.source}")
        lines.append(f"| {side} | {desc} |")
    lines.append(f"| lubricant | {case.lubricant} |")
    lines.append(f"| turning | the {case.turning} (counter-clockwise), the other body fixed |")
    lines.append(f"| load angle | {math.degrees(case.load_angle):g} deg |")
    lines.append(f"| grid | n = {case.n}" + (f", m = {case.m}" if case.m else "") + " |")
    if case.journal:
        lines.append(f"| cavitation | {case.cavitation} |")
        lines.append(f"| whirl ratios | {', '.join(f'{r:g}' for r in case.whirl_ratios)} |")
    if not case.scene == "finite_journal":
        lines.append(f"| memory | {case.memory} |")
    return lines


def write_outputs(case, points, folder, seconds: float, version: str) -> list:
    """Write every output of ``case`` into ``folder``; returns the file names."""
    folder = Path(folder)
    header = list(points[0].row)
    files = {"points.csv": _csv(header, [[p.row[k] for k in header] for p in points])}
    if case.journal:
        files["coefficients.csv"] = _csv(COEFFICIENT_COLUMNS, coefficient_rows(case, points))
    for name, text in files.items():
        (folder / name).write_text(text, encoding="utf-8")
    figures = _figures(case, points, folder)
    failed = [p for p in points if not p.row["converged"]]
    rep = [f"# {case.title}", "",
           f"`vjax-bearing {Path(case.file).name}`" + "".join(f" --set {k}={v}" for k, v in case.overrides)
           + f": scene `{case.scene}`, {len(points)} operating points, {len(points) - len(failed)} converged, "
           f"{seconds:.1f} s (vjax {version}).", "",
           "## Inputs", "", "| input | value (SI) |", "|---|---|", *_inputs(case), "",
           "The case file as read:", "", "```toml", case.text.rstrip(), "```", "",
           "## Operating points", "", summary_table(case, points), "",
           "Every column, in SI, is in `points.csv` (docs/bearing_files.md defines each)."]
    if failed:
        rep += ["", "### Points that did not converge", ""]
        rep += [f"- point {p.index}: {p.row['reason']}" for p in failed]
    outside = [p for p in points if p.row.get("validity")]
    if outside:
        rep += ["", "### Points outside the model's validity", ""]
        rep += [f"- point {p.index}: {p.row['validity']}" for p in outside]
    if case.journal:
        rep += ["", "## Dynamic coefficients", "",
                f"`coefficients.csv`: K (N/m) and C (N s/m) of every converged point at whirl ratios "
                f"{', '.join(f'{r:g}' for r in case.whirl_ratios)} (whirl frequency over the turning body's speed), "
                "in the absolute frame (x right, y up; dF = -(K dx + C dx/dt) on the journal), with their "
                "dimensionless forms K c / W and C c omega / W. The columns are those of ROSS's bearing tables "
                "(`kxx` ... `cyy`, `frequency` in rad/s); docs/bearing_files.md says how to read them into "
                "`ross.BearingElement`."]
        if case.scene == "long_journal":
            rep += ["", "The long-bearing theory's per-length values are multiplied by geometry.length: they "
                    "overstate a real bearing's load capacity and stiffness at moderate L/D (several times at L/D = 1)."]
    rep += ["", "## Figures", ""] + [f"![{n}]({n})\n\n{what}\n" for n, what in figures]
    rep += ["## Definitions", "",
            "- friction torque: on the stationary body, positive when it is dragged along (a torque arm on it); "
            + ("friction coefficient: the journal's friction force over the load (Raimondi and Boyd's f)."
               if case.journal else "friction coefficient: friction torque / (load x radius), the bore radius"
               + (" (the inner raceway radius for a roller bearing)" if case.scene == "roller" else "") + "."),
            "- viscoelastic share: the bodies' hysteresis power over the power put in (1 for a dry contact, "
            "whose friction is all hysteresis; 0 for a body that sees a steady load, e.g. a liner in a fixed "
            "housing under a turning shaft)."]
    (folder / "report.md").write_text("\n".join(rep) + "\n", encoding="utf-8")
    return sorted(list(files) + [n for n, _ in figures] + ["report.md"])
