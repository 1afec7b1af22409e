"""``vjax-fit-torque DATA.csv --material start.json --out refined.json``: refine a material
against measured bearing friction torque.

DATA.csv: torque-versus-speed curves (format in :mod:`fitting.torque`). The start material
(a ``vjax-fit`` JSON: Prony series with a WLF shift law, or with another law and the WLF
alternative ``vjax-fit`` fits next to it, which is then used; shear moduli are converted to
E = 2 (1 + nu) G, as are shear DMA files) is refined by gradients through
the bearing solves (:func:`fitting.torque.fit_torque`: Adam, then Levenberg-Marquardt),
optionally with the misfit to DMA files as a second term so it stays consistent with them.
Progress (iteration, loss, gradient norm) goes to stderr. Writes the refined material JSON
(with the Gauss-Newton standard deviations of the log-parameters), ``<stem>_params.csv``
(every parameter before/after with its uncertainty and whether the torque alone identifies
it), ``<stem>_torque.png`` and ``<stem>_moduli.png`` (before/after). Exit codes: 0 success,
1 bad input or a fit whose bearing solves did not converge (nothing written), 2 bad command
line. Every file goes through a temporary file and ``os.replace``.

Self-heating: ``--heat-transfer HA`` runs every scene at the effective temperature its own
dissipation sets (the CSV's temperature is then the ambient and oil supply temperature; hA in
W/K for a journal bearing, W/(m K) per unit length for pin and roller), ``--fit-heat-transfer``
fits log hA with the material. Mixed lubrication (journal): ``--roughness SIGMA
--asperity-modulus E_PRIME [--mu-b MU]`` for a rough bore; ``--fit-friction`` fits mu_b and
sigma with the material. The fitted values go to the JSON's ``fit`` record and the params CSV.

Example (the roller twin's data)::

    vjax-fit-torque experiments/out/torque_twin_roller_data.csv \\
        --material experiments/out/torque_twin_roller_truth.json --out refined.json
"""
from __future__ import annotations

import argparse
import os
import sys

from fitting.shared import jax_cache
from fitting.cli.fit import output_json
from fitting.cli.interrupt import exits_on_interrupt


def _parser():
    p = argparse.ArgumentParser(prog="vjax-fit-torque", description=__doc__.splitlines()[0])
    p.add_argument("data", help="torque CSV: speed_rpm, temperature_C, load_N_per_m, torque_Nm_per_m[, scatter]")
    p.add_argument("--material", required=True, help="start material JSON (Prony + WLF), e.g. from vjax-fit")
    p.add_argument("--out", required=True, help="output material JSON path")
    p.add_argument("--scene", choices=["roller", "pin", "journal"], default="roller",
                   help="roller: needle roller bearing, torque on the fixed outer ring; pin: pin in a plate; "
                        "journal: finite journal bearing with a liner of the material (load and torque per unit "
                        "length: the rig's totals over --length)")
    g = p.add_argument_group("roller bearing geometry (m)")
    g.add_argument("--R-outer", type=float, default=6e-3, help="outer raceway radius (default 6e-3)")
    g.add_argument("--R-inner", type=float, default=4e-3, help="inner raceway radius (default 4e-3)")
    g.add_argument("--roller-diameter", type=float, default=2e-3, help="roller diameter (default 2e-3)")
    g.add_argument("--rollers", type=int, default=9, help="number of rollers (default 9)")
    g.add_argument("--diametral-clearance", type=float, default=None,
                   help="diametral clearance (default from the radii); a preload is negative: --diametral-clearance=-5e-6")
    g = p.add_argument_group("pin joint and journal bearing geometry (m)")
    g.add_argument("--R", type=float, default=None, help="hole (bore) radius (default 0.01 pin, 0.025 journal)")
    g.add_argument("--radial-clearance", type=float, default=None,
                   help="radial clearance hole radius - pin radius (default 1e-4 pin, 5e-5 journal)")
    g = p.add_argument_group("journal bearing (--scene journal)")
    g.add_argument("--length", type=float, default=0.05, help="axial length L (m, default 0.05)")
    g.add_argument("--thickness", type=float, default=0.01, help="liner thickness (m, default 0.01)")
    g.add_argument("--viscosity", type=float, default=None,
                   help="lubricant viscosity (Pa s), held fixed (default: water's, by temperature)")
    g.add_argument("--oil", default=None, metavar="NU40,NU100[,DENSITY]",
                   help="a mineral oil instead, by temperature: its kinematic viscosities at 40 and 100 C (cSt) "
                        "and density (kg/m^3, default 860), Walther's equation (e.g. ISO VG 32: --oil 32,5.4)")
    g.add_argument("--turning", choices=["liner", "shaft"], default="liner",
                   help="the side turning at speed_rpm (default liner: the lined housing on a fixed shaft; "
                        "shaft: the torque then identifies E0 only)")
    g.add_argument("--m", type=int, default=8, help="axial film cells (even, default 8)")
    g.add_argument("--roughness", type=float, default=None, metavar="SIGMA",
                   help="mixed lubrication: the composite rms roughness sigma (m) of a rough bore and smooth shaft "
                        "(Patir-Cheng, Greenwood-Tripp; the torque then follows the Stribeck curve); needs "
                        "--asperity-modulus")
    g.add_argument("--mu-b", type=float, default=0.1, help="boundary friction coefficient with --roughness (default 0.1)")
    g.add_argument("--asperity-modulus", type=float, default=None, metavar="E_PRIME",
                   help="the asperities' composite modulus E' (Pa), 1/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2, with --roughness")
    g.add_argument("--fit-friction", action="store_true",
                   help="also fit mu_b and sigma (log), starting from --mu-b and --roughness")
    g = p.add_argument_group("self-heating (every scene)")
    g.add_argument("--heat-transfer", type=float, default=None, metavar="HA",
                   help="the rig's heat transfer coefficient times area to the CSV's temperature, which becomes the "
                        "ambient (and oil supply) temperature: the scene runs at the effective temperature its own "
                        "dissipation sets (W/K for --scene journal, where the side leakage of --oil or the default "
                        "water also carries heat, not of a fixed --viscosity; W/(m K) per unit length for pin and "
                        "roller); inf: isothermal")
    g.add_argument("--fit-heat-transfer", action="store_true",
                   help="also fit log hA, starting from --heat-transfer")
    p.add_argument("--n", type=int, default=None,
                   help="elements per ring (default 256 roller, 128 pin), film cells round a journal (default 32)")
    p.add_argument("--dma", nargs="+", default=None, metavar="FILE", help="DMA files for the consistency term")
    p.add_argument("--w-dma", type=float, default=0.1, help="weight of the DMA term with --dma (default 0.1)")
    p.add_argument("--rel-scatter", type=float, default=0.05,
                   help="torque scatter relative to the torque when the CSV has none (default 0.05)")
    p.add_argument("--steps", type=int, default=200, help="Adam iterations (default 200)")
    p.add_argument("--lr", type=float, default=0.05, help="Adam learning rate, log units (default 0.05)")
    p.add_argument("--polish", type=int, default=20, help="Levenberg-Marquardt iterations after Adam (default 20)")
    p.add_argument("--fit-times", action="store_true", help="also refine the relaxation times")
    p.add_argument("--no-plots", action="store_true")
    jax_cache.add_argument(p)
    return p


def _model(args):
    from fitting import torque as ft
    hA = args.heat_transfer
    if args.scene == "journal":
        viscosity = args.viscosity or (ft.oil_viscosity(*_oil(args.oil)) if args.oil else ft.water_viscosity)
        rough = None
        if args.roughness is not None:
            import vjax
            rough = vjax.Roughness(args.roughness, args.asperity_modulus, mu_b=args.mu_b)
        return ft.journal_model(args.R or 0.025, args.radial_clearance or 5e-5, args.length, args.thickness,
                                viscosity, args.turning, n=args.n or 32, m=args.m, roughness=rough, heat_transfer=hA)
    if args.scene == "roller":
        return ft.roller_model(args.R_outer, args.R_inner, args.roller_diameter, args.rollers,
                               n=args.n or 256, diametral_clearance=args.diametral_clearance, heat_transfer=hA)
    return ft.pin_model(args.R or 0.01, args.radial_clearance or 1e-4, n=args.n or 128, heat_transfer=hA)


def _extras(args):
    """Start values of the scene parameters fitted with the material."""
    extras = {}
    if args.fit_friction:
        extras.update(mu_b=args.mu_b, sigma=args.roughness)
    if args.fit_heat_transfer:
        extras["hA"] = args.heat_transfer
    return extras


def _oil(text):
    """--oil's numbers (nu40, nu100[, density]); ValueError if they are not 2 or 3 numbers."""
    values = [float(v) for v in text.split(",")]
    if len(values) not in (2, 3):
        raise ValueError
    return values


def _check_args(args):
    """The first problem with the numeric arguments, or None."""
    if args.oil is not None:
        if args.viscosity is not None:
            return "--oil and --viscosity both give the lubricant's viscosity: give one"
        try:
            values = _oil(args.oil)
        except ValueError:
            return f"--oil must be NU40,NU100[,DENSITY] (cSt, cSt, kg/m^3), got {args.oil!r}"
        if not all(0 < v < float("inf") for v in values) or not values[1] < values[0]:
            return f"--oil: NU40 > NU100 > 0 and DENSITY > 0, finite, got {args.oil!r}"
    if args.heat_transfer is not None:
        if not args.heat_transfer > 0:        # NaN fails too
            return f"--heat-transfer must be a number hA > 0 (W/K, or W/(m K) per unit length; inf: isothermal), " \
                   f"got {args.heat_transfer}"
        if args.fit_heat_transfer and args.heat_transfer == float("inf"):
            return "--fit-heat-transfer needs a finite --heat-transfer to start from (log hA is fitted), got inf"
    elif args.fit_heat_transfer:
        return "--fit-heat-transfer needs --heat-transfer HA, the start value (W/K, or W/(m K) per unit length)"
    if args.roughness is not None or args.fit_friction:
        if args.scene != "journal":
            return "--roughness and --fit-friction are for --scene journal (mixed lubrication of the film)"
        if args.roughness is None:
            return "--fit-friction needs --roughness SIGMA, the start value (m)"
        if args.asperity_modulus is None:
            return "--roughness needs --asperity-modulus E_PRIME (Pa), the asperities' composite modulus"
        for name in ("roughness", "asperity_modulus"):
            v = getattr(args, name)
            if not (v > 0 and v < float("inf")):
                return f"--{name.replace('_', '-')} must be a finite number > 0, got {v}"
        if not (args.mu_b > 0 and args.mu_b < float("inf")):
            return f"--mu-b must be a finite number > 0, got {args.mu_b}"
    for name in ("steps", "polish"):
        if getattr(args, name) < 0:
            return f"--{name} must be >= 0, got {getattr(args, name)}"
    for name in ("lr", "rel_scatter", "R_outer", "R_inner", "roller_diameter", "R", "radial_clearance", "length",
                 "thickness", "viscosity"):
        v = getattr(args, name)
        if v is None:
            continue
        if not (v > 0 and v < float("inf")):
            return f"--{name.replace('_', '-')} must be a finite number > 0, got {v}"
    if not args.w_dma >= 0:
        return f"--w-dma must be >= 0, got {args.w_dma}"
    if args.n is not None and (args.n < 16 or (args.scene == "journal" and args.n % 2)):
        return f"--n must be an integer >= 16 (even for a journal), got {args.n}"
    if args.m < 2 or args.m % 2:
        return f"--m must be an even integer >= 2, got {args.m}"
    if args.rollers < 2:
        return f"--rollers must be >= 2, got {args.rollers}"
    return None


def _tensile(material, modulus, table):
    """E = 2 (1 + nu) G for a shear start material and a shear DMA table: the bearing scenes
    and the DMA term work with E."""
    import dataclasses
    from fitting.calibration.pipeline import convert_modulus
    from fitting.shared.evaluate import tensile_over_shear
    f = tensile_over_shear(material.nu)
    if modulus == "G":
        material = convert_modulus(material, f)
    if table is not None and table.kind == "G":
        table = dataclasses.replace(table, storage=table.storage * f, loss=table.loss * f, kind="E")
    return material, table


@exits_on_interrupt("vjax-fit-torque")
def main(argv=None) -> int:
    """Console entry point; returns the exit code (also when called from Python)."""
    args = _parser().parse_args(argv)
    problem = _check_args(args)
    if problem:
        print(f"vjax-fit-torque: error: {problem}", file=sys.stderr)
        return 2
    out, code = output_json("vjax-fit-torque", args.out)
    if code:
        return code
    import jax
    jax.config.update("jax_enable_x64", True)
    jax_cache.enable(args.no_cache)
    import numpy as np
    from vjax import WLF

    from fitting.calibration import io
    from fitting import torque as ft

    written = []
    try:
        data = ft.read_torque_csv(args.data)
        material, shift, modulus = io.load_material(args.material)
        if not isinstance(shift, WLF):     # e.g. vjax-fit's table law: refine its fitted WLF alternative
            shift = io.closed_form_shift(args.material, "WLF")
            print(f"vjax-fit-torque: the start material's shift law is not WLF; refining the WLF law fitted with "
                  f"it (C1 = {float(shift.C1):.5g}, C2 = {float(shift.C2):.5g} K)", file=sys.stderr)
        table = None
        if args.dma:
            from fitting.measurements import dma
            table = dma.read(args.dma)
        material, table = _tensile(material, modulus, table)
        model = _model(args)
        fit = ft.fit_torque(data, material, shift, model, dma_table=table, w_dma=args.w_dma if table else 0.0,
                            rel_scatter=args.rel_scatter, fit_times=args.fit_times, extras=_extras(args),
                            steps=args.steps, lr=args.lr, polish=args.polish)
        if not fit.converged:
            raise ValueError(f"some bearing solves did not converge at the fitted material ({model.scene}); "
                             "nothing written. Check the geometry, loads and start material; a smaller --lr "
                             "or a finer --n may help")
        stem = os.path.splitext(out)[0]
        rows = [[name, before, after, s, "yes" if fit.ident["sd"][name] < 0.1 else "no"]
                for name, before, after, s in fit.table()]
        if not args.no_plots:
            from fitting.calibration import plots
            sigma = data.sigma(args.rel_scatter)
            written.append(plots.torque_fit(data, {"fit": fit}, sigma, stem + "_torque.png"))
            written.append(plots.moduli([(material, "start", "k:"), (fit.material, "fitted", "C2-")],
                                        stem + "_moduli.png"))
        lines = ["# parameters before/after; sd_rel: Gauss-Newton standard deviation of the log-parameter",
                 "# torque_identifies: determined to < 10% by the torque alone (singular values of its Jacobian)",
                 "param,start,fitted,sd_rel,torque_identifies"]
        lines += [f"{n},{b:.10g},{a:.10g},{s:.4g},{i}" for n, b, a, s, i in rows]
        io.atomic_write(stem + "_params.csv", "\n".join(lines) + "\n")
        written.append(stem + "_params.csv")
        # the material last: it exists only if everything else was written
        sd = {n: float(s) for n, s in zip(fit.names, fit.sd)}
        io.save_material(out, fit.material, fit.shift, uncertainty={"sd_rel": sd},
                         fit={"scene": model.scene, "data": os.path.abspath(args.data), "loss": fit.loss,
                              "loss_start": fit.loss0, "iterations": fit.iterations, **fit.extras})
        written.insert(0, out)
    except (ValueError, OSError, np.linalg.LinAlgError) as e:
        for path in written:          # no partial set of outputs
            if os.path.exists(path):
                os.unlink(path)
        print(f"vjax-fit-torque: error: {e}", file=sys.stderr)
        return 1
    chi0 = float(np.mean(((fit.torque0 - data.torque) / data.sigma(args.rel_scatter)) ** 2))
    chi1 = float(np.mean(((fit.torque - data.torque) / data.sigma(args.rel_scatter)) ** 2))
    print(f"{model.scene}: {len(data)} torque points, chi2 per point {chi0:.4g} -> {chi1:.4g} "
          f"({fit.iterations} iterations, {fit.wall_time:.1f} s)")
    print(f"{'param':>8s} {'start':>12s} {'fitted':>12s} {'sd_rel':>9s}  torque identifies")
    for n, b, a, s, i in rows:
        print(f"{n:>8s} {b:12.5g} {a:12.5g} {s:9.3g}  {i}")
    print("wrote " + ", ".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
