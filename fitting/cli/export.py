"""``vjax-export material.json --format abaqus,ansys,lsdyna,comsol``: write a fitted material
(from ``vjax-fit`` or ``vjax-fit-torque``) for finite-element codes.

The shear relaxation modulus G(t) = E(t) / (2 (1 + nu)) and an elastic bulk modulus K (from
``--nu`` < 0.5 or ``--bulk-modulus``) are written in each code's own normalization, with the
WLF or Arrhenius shift law (see :mod:`fitting.fem.export`). The series is compact by default: the
fewest terms whose medians on the DMA data named in the JSON stay within 1.5x of the full
fit's and whose loss-modulus ripple stays below the data's scatter about the full fit
(:mod:`fitting.calibration.compact`; ``--max-terms N`` caps the count and the output says what that
costs); ``--full-spectrum`` writes every term. Every card's header states its term count,
window, ripple and accuracy. ``--window T_MIN,T_MAX`` (reduced times at T_ref, s) is the
working window of the analysis and the main lever for fewer terms: LS-DYNA gets the best 5
terms + G_inf (its six cards) over it; without it LS-DYNA is refused when six cards cannot hold
the data's window within twice the full fit's error, and the message names the widest window
they do hold. ``--isothermal T`` writes every card at one temperature (times a_T(T) tau_i, no
shift fields). Beside the LS-DYNA and ANSYS cards a one-element verification deck is written
(``<stem>_<code>_<K|degC>_verify.k|.mac``): the element at a step shear strain at T_ref and a
hotter temperature, with the stresses the fitted material predicts.
``--temperature K|C`` is required (it is in the file names too); ``--density`` (kg/m^3) is
written for every code and required for LS-DYNA. Files: ``<stem>_<code>_<K|degC>.inp|.mac|.k``
and ``<stem>_comsol_<K|degC>_parameters.txt`` / ``_branches.txt`` in ``--out-dir`` (default:
next to the JSON). Exit codes: 0 success, 1 a material that cannot be exported (message on
stderr, nothing written), 2 bad command line. Files are written atomically.

Example (the analysis sees reduced times 0.1 ms to 100 s at T_ref: 6 terms on the shipped
pyvisco example, against 30 over its 27 decades without ``--window``)::

    vjax-export material.json --format abaqus,lsdyna --nu 0.45 --temperature C --density 1200 --window 1e-4,1e2
"""
from __future__ import annotations

import argparse
import math
import os
import sys

from fitting.cli.interrupt import exits_on_interrupt


def add_arguments(p, fit: bool = False) -> None:
    """The export options, shared by ``vjax-export`` and ``vjax-fit --export``; ``fit``: the
    caller already has --nu (the material's Poisson ratio, then also used for the split)."""
    g = p.add_argument_group("finite-element export")
    if not fit:
        g.add_argument("--nu", type=float, default=None,
                       help="Poisson ratio of the shear/bulk split, < 0.5 (default: the material's own)")
    g.add_argument("--bulk-modulus", type=float, default=None, metavar="K",
                   help="elastic bulk modulus in Pa instead of the one from --nu")
    g.add_argument("--units", choices=["SI", "mm-N-s-MPa"], default="SI",
                   help="SI (Pa, s, J/mol) or mm-N-s-MPa (MPa, s, mJ/mol); default SI")
    g.add_argument("--temperature", choices=["K", "C"], default=None,
                   help="temperature scale of the files, K or C (required: no default; also in the file names)")
    g.add_argument("--density", type=float, default=None, metavar="RHO",
                   help="density in kg/m^3, written where each code wants it (required for LS-DYNA)")
    g.add_argument("--full-spectrum", action="store_true",
                   help="write every Prony term of the fit instead of the compact series")
    g.add_argument("--window", default=None, metavar="T_MIN,T_MAX",
                   help="your working window: the reduced times (s, at T_ref) the analysis will see, the main lever "
                        "for fewer terms: every card's series is chosen over it (LS-DYNA's six cards refit over it). "
                        "Without it LS-DYNA is refused when "
                        "six cards cannot hold the data's whole window, and the message names the widest window they "
                        "do hold. Example: --window 1e-4,1e2 gives 6 terms on the shipped pyvisco example, against 30 over its "
                        "27 decades (docs/fem_export.md)")
    g.add_argument("--isothermal", type=float, default=None, metavar="T",
                   help="write every card at the one temperature T (in the --temperature scale): relaxation times "
                        "a_T(T) tau_i, no shift fields (unambiguous in every code; what most single-temperature "
                        "analyses need). Without it, LS-DYNA and ANSYS also get a one-element verification deck")


def check_arguments(args, fit: bool = False):
    """The first problem with the export options, or None."""
    from fitting.fem.export import parse_formats
    try:
        parse_formats(args.export if fit else args.format)
    except ValueError as e:
        return str(e)
    if args.bulk_modulus is not None and not (0 < args.bulk_modulus < float("inf")):
        return f"--bulk-modulus must be a finite number > 0 (Pa), got {args.bulk_modulus}"
    if not fit and args.nu is not None and args.bulk_modulus is not None:
        return "give --nu or --bulk-modulus, not both"
    nu = args.nu
    if nu is not None and args.bulk_modulus is None and not (-1 < nu < 0.5):
        return (f"--nu must be < 0.5 for an FEM export, got {nu:g}: nu = 0.5 is an infinite bulk modulus, which "
                "FEM elements reject; give --nu 0.49 (e.g.) or --bulk-modulus K")
    if not fit and args.max_terms is not None and args.max_terms < 1:
        return f"--max-terms must be >= 1, got {args.max_terms}"
    if args.temperature is None:
        return ("the temperature scale of the cards has no default: add --temperature K or --temperature C "
                "(every temperature in the files is in it)")
    if args.density is not None and not (0 < args.density < float("inf")):
        return f"--density must be a finite number > 0 (kg/m^3), got {args.density}"
    if args.isothermal is not None and not math.isfinite(args.isothermal):
        return f"--isothermal must be a finite temperature (in the --temperature scale), got {args.isothermal}"
    stem = getattr(args, "stem", None)
    if stem is not None and (not stem or os.path.basename(stem) != stem or stem in (".", "..")):
        return f"--stem must be a file name without a folder (the files go in --out-dir), got {stem!r}"
    try:
        parse_window(args.window)
    except ValueError as e:
        return str(e)
    return None


def parse_window(text):
    """'1e-6,1e3' -> (1e-6, 1e3) (s), or None."""
    if text is None:
        return None
    try:
        lo, hi = (float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(f"--window must be T_MIN,T_MAX in s, e.g. 1e-6,1e3; got {text!r}") from None
    if not (0 < lo < hi < float("inf")):
        raise ValueError(f"--window must be T_MIN,T_MAX with 0 < T_MIN < T_MAX (s), got {text!r}")
    return lo, hi


def run(m, formats, out_dir, stem, args, max_terms=None) -> list:
    """Export ``m`` with the options of :func:`add_arguments`, printing the choices made."""
    from fitting.fem import export
    notes = []
    try:
        written = export.export(m, formats, out_dir, stem, units=args.units, temperature=args.temperature,
                                max_terms=max_terms, density=args.density,
                                terms="full" if args.full_spectrum else "compact", window=parse_window(args.window),
                                messages=notes, isothermal=args.isothermal)
    finally:
        for n in notes:
            print(n)
    return written


def _parser():
    p = argparse.ArgumentParser(prog="vjax-export",
                                description="Write a fitted material JSON for finite-element codes (Abaqus, ANSYS, "
                                            "LS-DYNA, COMSOL): shear Prony series, bulk modulus, shift law.",
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="Example: vjax-export material.json --format abaqus,ansys --nu 0.45 --temperature C "
                                       "--window 1e-4,1e2 (the analysis sees reduced times 0.1 ms..100 s at T_ref: "
                                       "6 terms on the shipped pyvisco example, 30 without --window)")
    p.add_argument("material", help="material JSON (vjax-fit output)")
    p.add_argument("--format", required=True, help="comma-separated: abaqus, ansys, lsdyna, comsol (or all)")
    p.add_argument("--out-dir", default=None, help="output directory (default: the JSON's)")
    p.add_argument("--stem", default=None, help="file name stem (default: the JSON's)")
    p.add_argument("--max-terms", type=int, default=None,
                   help="at most this many Prony terms. Default: the fewest within 1.5x of the full fit's medians "
                        "whose loss-modulus ripple stays below the data's scatter about the fit; a smaller cap says "
                        "what it costs (ripple above the scatter, or accuracy) in the output and the card. With "
                        "--full-spectrum a material with more terms is refused")
    p.add_argument("--shift-law", choices=["WLF", "Arrhenius"], default=None,
                   help="export this closed-form alternative stored next to a table shift law")
    add_arguments(p)
    return p


@exits_on_interrupt("vjax-export")
def main(argv=None) -> int:
    """Console entry point; returns the exit code."""
    p = _parser()
    args = p.parse_args(argv)
    problem = check_arguments(args)
    if problem:
        p.print_usage(sys.stderr)
        print(f"vjax-export: error: {problem}", file=sys.stderr)
        return 2
    from fitting.fem import export
    out_dir = os.path.abspath(args.out_dir or os.path.dirname(os.path.abspath(args.material)))
    stem = args.stem or os.path.splitext(os.path.basename(args.material))[0]
    try:
        m = export.load(args.material, nu=args.nu, bulk_modulus=args.bulk_modulus, shift_law=args.shift_law)
        written = run(m, args.format, out_dir, stem, args, max_terms=args.max_terms)
    except export.ExportRefused as e:      # the other codes are written
        if e.written:
            print("wrote " + ", ".join(e.written))
        for code, why in e.refused.items():
            print(f"vjax-export: error: {code} not written: {why}", file=sys.stderr)
        return 1
    except (ValueError, OSError) as e:
        print(f"vjax-export: error: {e}", file=sys.stderr)
        return 1
    print(f"fit: {len(m.G)} Prony terms, G_g = {m.G_g:.6g} Pa, G_inf = {m.G_inf:.6g} Pa, K = {m.K:.6g} Pa, "
          f"shift law {m.law}")
    print("wrote " + ", ".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
