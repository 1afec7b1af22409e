"""``vjax-export material.json --format abaqus,ansys,lsdyna,comsol``: write a fitted material
(from ``vjax-fit`` or ``vjax-fit-torque``) for finite-element codes.

The shear relaxation modulus G(t) = E(t) / (2 (1 + nu)) and an elastic bulk modulus K (from
``--nu`` < 0.5 or ``--bulk-modulus``) are written in each code's own normalization, with the
WLF or Arrhenius shift law (see :mod:`fitting.export`). Files: ``<stem>_abaqus.inp``,
``<stem>_ansys.mac``, ``<stem>_lsdyna.k``, ``<stem>_comsol_parameters.txt`` and
``<stem>_comsol_branches.txt`` in ``--out-dir`` (default: next to the JSON). Exit codes: 0
success, 1 a material that cannot be exported (message on stderr, nothing written), 2 bad
command line. Files are written atomically. This tool does not use JAX (nothing to compile).

Example::

    vjax-export material.json --format abaqus,ansys --nu 0.45 --units mm-N-s-MPa
"""
from __future__ import annotations

import argparse
import os
import sys


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
    g.add_argument("--temperature", choices=["K", "C"], default="K",
                   help="temperature unit in the files (default K)")


def check_arguments(args, fit: bool = False):
    """The first problem with the export options, or None."""
    from .export import parse_formats
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
    return None


def _parser():
    p = argparse.ArgumentParser(prog="vjax-export",
                                description="Write a fitted material JSON for finite-element codes (Abaqus, ANSYS, "
                                            "LS-DYNA, COMSOL): shear Prony series, bulk modulus, shift law.",
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="Example: vjax-export material.json --format abaqus,ansys --nu 0.45")
    p.add_argument("material", help="material JSON (vjax-fit output)")
    p.add_argument("--format", required=True, help="comma-separated: abaqus, ansys, lsdyna, comsol (or all)")
    p.add_argument("--out-dir", default=None, help="output directory (default: the JSON's)")
    p.add_argument("--stem", default=None, help="file name stem (default: the JSON's)")
    p.add_argument("--max-terms", type=int, default=None,
                   help="refuse materials with more Prony terms (refit with vjax-fit --max-terms instead)")
    p.add_argument("--shift-law", choices=["WLF", "Arrhenius"], default=None,
                   help="export this closed-form alternative stored next to a table shift law")
    add_arguments(p)
    return p


def main(argv=None) -> int:
    """Console entry point; returns the exit code."""
    p = _parser()
    args = p.parse_args(argv)
    problem = check_arguments(args)
    if problem:
        p.print_usage(sys.stderr)
        print(f"vjax-export: error: {problem}", file=sys.stderr)
        return 2
    from . import export
    out_dir = os.path.abspath(args.out_dir or os.path.dirname(os.path.abspath(args.material)))
    stem = args.stem or os.path.splitext(os.path.basename(args.material))[0]
    try:
        m = export.load(args.material, nu=args.nu, bulk_modulus=args.bulk_modulus, shift_law=args.shift_law)
        written = export.export(m, args.format, out_dir, stem, units=args.units, temperature=args.temperature,
                                max_terms=args.max_terms)
    except (ValueError, OSError) as e:
        print(f"vjax-export: error: {e}", file=sys.stderr)
        return 1
    print(f"{len(m.G)} Prony terms, G_g = {m.G_g:.6g} Pa, G_inf = {m.G_inf:.6g} Pa, K = {m.K:.6g} Pa, "
          f"shift law {m.law}")
    print("wrote " + ", ".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
