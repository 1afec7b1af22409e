"""``vjax-fit INPUT... --tref T --out material.json``: calibrate a material from DMA files.

Frequency sweeps or relaxation curves (detected from the content). By default the Prony
spectrum is smooth (``--method smooth``: fixed log-spaced times, penalty chosen by GCV) and
WLF and Arrhenius are fitted next to the chosen law (``shift_alternatives`` in the JSON, which
``vjax-fit-torque`` and ``vjax-export --shift-law`` use); ``--max-terms N`` caps the terms.

Prints a summary table (terms, errors, shift parameters, time), writes the material JSON
atomically and the plots next to it (``<out stem>_master.png`` etc.). Exit codes: 0 success,
1 bad data or failed fit (message on stderr), 2 bad command line. An existing output is
never left half-written: every file goes through a temporary file and ``os.replace``.
``--export abaqus,ansys,lsdyna,comsol`` also writes the material for FEM codes (see
``vjax-export``, :mod:`fitting.fem.export`; needs ``--nu`` < 0.5 or ``--bulk-modulus``; its
``--window``, ``--isothermal`` and verification decks as there). A liquid (a melt: no
equilibrium modulus) fits with ``--max-terms`` too: E0 is held at a floor far below the data,
and the FEM cards write E_inf = 0.
Compiled functions are kept in a persistent cache (:mod:`fitting.shared.jax_cache`; ``--no-cache``).
"""
from __future__ import annotations

import argparse
import gc
import os
import sys

from fitting.cli import export as export_cli
from fitting.shared import jax_cache
from fitting.cli.interrupt import exits_on_interrupt


def _parser():
    p = argparse.ArgumentParser(prog="vjax-fit", description=__doc__.splitlines()[0])
    p.add_argument("inputs", nargs="+", metavar="INPUT", help="DMA files or directories")
    p.add_argument("--tref", type=float, required=True, help="reference temperature (C)")
    p.add_argument("--out", required=True, help="output material JSON path")
    p.add_argument("--law", default="auto", choices=["auto", "WLF", "Arrhenius", "table"],
                   help="shift law (auto: lowest BIC of table, WLF and Arrhenius; the others are fitted too and "
                        "written as shift_alternatives)")
    p.add_argument("--method", default="smooth", choices=["smooth", "free"],
                   help="smooth: relaxation times on a fixed grid, smoothness penalty chosen by GCV (a loss modulus "
                        "without ringing; default); free: free relaxation times, their number by BIC (fewer terms)")
    p.add_argument("--max-terms", type=int, default=None, metavar="N",
                   help="at most N Prony terms (smooth method; Abaqus users often keep <= 13). For the FEM "
                        "cards' count see --export's --window (fewer terms over a working window)")
    p.add_argument("--nu", type=float, default=0.5, help="Poisson's ratio (default 0.5)")
    p.add_argument("--kind", choices=["E", "G"], help="override tensile/shear from the files")
    p.add_argument("--shear", action="store_true", help="keep shear moduli (no G -> E conversion)")
    p.add_argument("--shifts", help="CSV of user shift factors: T [C], log10 a_T")
    p.add_argument("--drop-nonpositive", action="store_true", help="drop points with modulus <= 0")
    p.add_argument("--no-plots", action="store_true")
    p.add_argument("--export", default=None, metavar="FORMATS",
                   help="also write the material for FEM codes: abaqus,ansys,lsdyna,comsol (see vjax-export; "
                        "needs --nu < 0.5 or --bulk-modulus)")
    export_cli.add_arguments(p, fit=True)
    jax_cache.add_argument(p)
    return p


def output_json(prog, path):
    """(absolute path, None) for a usable ``--out`` material path, else (path, exit code)
    after printing why: 2 if it does not name a .json file, 1 if its folder is missing."""
    out = os.path.abspath(path)
    if not out.lower().endswith(".json"):
        print(f"{prog}: error: --out must name a .json file, got {path!r}", file=sys.stderr)
        return out, 2
    if not os.path.isdir(os.path.dirname(out)):
        print(f"{prog}: error: output directory {os.path.dirname(out)!r} does not exist", file=sys.stderr)
        return out, 1
    return out, None


def _export(args, out) -> list:
    """Write the FEM files of ``--export`` next to the material JSON ``out``."""
    from fitting.fem import export
    m = export.load(out, nu=args.nu, bulk_modulus=args.bulk_modulus)
    stem = os.path.splitext(os.path.basename(out))[0]
    return export_cli.run(m, args.export, os.path.dirname(out), stem, args,
                          max_terms=None)


@exits_on_interrupt("vjax-fit")
def main(argv=None) -> int:
    """Console entry point; returns the exit code (also when called from Python)."""
    p = _parser()
    args = p.parse_args(argv)
    problem = export_cli.check_arguments(args, fit=True) if args.export else None
    if args.max_terms is not None and args.max_terms < 3:
        problem = f"--max-terms must be an integer >= 3, got {args.max_terms}"
    elif args.max_terms is not None and args.method == "free":
        problem = "--max-terms applies to --method smooth"
    if problem:
        p.print_usage(sys.stderr)
        print(f"vjax-fit: error: {problem}", file=sys.stderr)
        return 2
    out, code = output_json("vjax-fit", args.out)
    if code:
        return code
    # the fit's numpy linear algebra works on matrices of a few hundred rows, where OpenBLAS's
    # threads only contend with XLA's (seconds lost on a busy two-core machine); this takes
    # effect when numpy is not loaded yet, i.e. from the command line
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    if not args.no_plots:
        from fitting.calibration import figures
        figures.start_workers()     # matplotlib's import in a fork server, on another core
    import jax
    jax.config.update("jax_enable_x64", True)
    jax_cache.enable(args.no_cache)
    from fitting.calibration.pipeline import calibrate
    # everything loaded so far (JAX, vjax, numpy) lives as long as the process:
    # exempt it from the cyclic garbage collector, whose full collections, triggered by the
    # many objects that tracing allocates, would walk it again and again (about
    # 0.3 s of a cached call)
    gc.freeze()

    try:
        mat, shift, rep = calibrate(args.inputs, args.tref, None, law=args.law, nu=args.nu, kind=args.kind,
                                    tensile=not args.shear, shifts=args.shifts,
                                    drop_nonpositive=args.drop_nonpositive, method=args.method,
                                    max_terms=args.max_terms)
        kind = "E" if (rep.kind == "E" or not args.shear) else "G"
        rep.save(out, mat, shift, kind, inputs=[os.path.abspath(p) for p in args.inputs])
        written = [out]
        if not args.no_plots:
            from fitting.measurements import dma, relaxation
            reader = relaxation if rep.domain == "time" else dma
            table = reader.read(args.inputs, kind=args.kind, drop_nonpositive=args.drop_nonpositive)
            stem = os.path.splitext(out)[0]
            fit_mat = mat
            if rep.kind == "G" and kind == "E":  # plot against the data's own modulus
                from fitting.calibration.pipeline import convert_modulus
                from fitting.shared.evaluate import tensile_over_shear
                fit_mat = convert_modulus(mat, 1.0 / tensile_over_shear(args.nu))
            written += figures.save_all(os.path.dirname(stem), os.path.basename(stem), table, fit_mat, shift,
                                        rep.data_shift, rep.laws)
    except (ValueError, OSError) as e:
        print(f"vjax-fit: error: {e}", file=sys.stderr)
        return 1
    print(rep.table())
    export_errors = []
    if args.export:
        from fitting.fem.export import ExportRefused
        try:
            written += _export(args, out)
        except ExportRefused as e:              # the fit and the other codes are written
            written += e.written
            export_errors = [f"{code} not written: {why}" for code, why in e.refused.items()]
        except (ValueError, OSError) as e:     # the fit is written: say so, then why the export is not
            export_errors = [f"no FEM export: {e}"]
    print("wrote " + ", ".join(written))
    for why in export_errors:
        print(f"vjax-fit: error: {why}", file=sys.stderr)
    return 1 if export_errors else 0


if __name__ == "__main__":
    sys.exit(main())
