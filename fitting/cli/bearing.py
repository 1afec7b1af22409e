"""``vjax-bearing CASE.toml``: a bearing analysed from a file.

CASE.toml describes the scene (a finite or infinitely long journal bearing, a needle roller
bearing, a pin joint), its geometry, lubricant, bodies and materials (a ``material.json`` from
``vjax-fit`` or Prony/SLS numbers inline) and the operating points (lists or ranges of speed,
load and temperature); every key is in docs/bearing_files.md, and dimensional values are
strings with their unit ("50 mm", "3000 rpm", "40 C"). The whole file is checked before any
computation: bad input is refused naming the file, the key and what is expected, and nothing
is written.

Writes, into OUT/<case name>/ (OUT: --out, default the current directory): ``points.csv`` (one
row per operating point, SI), ``coefficients.csv`` (journal bearings: K and C per point and
whirl frequency in ROSS's bearing-table columns), PNG figures and ``report.md``. The folder is
built under a temporary name and renamed into place at the end (an earlier run's folder is
replaced only then). Points run as a warm-started sweep with a progress bar on stderr; a point
that fails is reported in its row with the solver's reason and the others go on.

Exit status: 0 every point converged, 1 some did not (results written), 2 bad input (nothing
written), 130 interrupted (Ctrl-C).

Example::

    vjax-bearing examples/journal_lined.toml --out results
    vjax-bearing examples/pin_joint.toml --set grid.n=256 --set 'operating.speed=["10 rad/s"]'
"""
from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from fitting.shared import files, jax_cache
from fitting.cli.interrupt import exits_on_interrupt


def _parser():
    p = argparse.ArgumentParser(prog="vjax-bearing", description=__doc__.splitlines()[0].replace("``", ""),
                                epilog="Units accepted (values are strings such as \"50 mm\"):\n" + _units(),
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", help="the case file (TOML; docs/bearing_files.md)")
    p.add_argument("--out", default=".", help="where the case's folder is written (default: the current directory)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a key of the case with a TOML value, e.g. grid.n=64 or "
                        "'operating.load=\"2 kN\"' (repeatable; echoed in the report)")
    p.add_argument("--check", action="store_true", help="check the case file and stop (writes nothing)")
    p.add_argument("--quiet", action="store_true", help="no progress bar and no table on stdout")
    jax_cache.add_argument(p)
    return p


def _units():
    from fitting.bearing.case_units import UNITS
    return "\n".join(f"  {d}: {', '.join(u)}" for d, u in UNITS.items())


def _replace_folder(tmp: Path, target: Path):
    """Put the finished folder ``tmp`` at ``target``: an earlier folder is moved aside first
    and removed after the rename, so ``target`` is always either the old or the new run."""
    old = None
    if target.exists():
        old = Path(tempfile.mkdtemp(prefix=f".{target.name}.old.", dir=target.parent))
        os.replace(target, old / target.name)
    try:
        os.replace(tmp, target)
    except BaseException:
        if old is not None:
            os.replace(old / target.name, target)
        raise
    finally:
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)


@exits_on_interrupt("vjax-bearing")
def main(argv=None) -> int:
    """Console entry point; returns the exit status (also when called from Python)."""
    args = _parser().parse_args(argv)
    overrides = []
    for s in args.set:
        if "=" not in s:
            print(f"vjax-bearing: error: --set {s!r}: expected KEY=VALUE", file=sys.stderr)
            return 2
        k, v = s.split("=", 1)
        overrides.append((k.strip(), v.strip()))
    import jax
    jax.config.update("jax_enable_x64", True)
    from fitting.bearing.case import CaseError, load_case
    try:
        case = load_case(args.case, overrides)
        out = Path(args.out)
        if out.exists() and not out.is_dir():
            raise CaseError(args.case, None, f"--out {out} is a file, not a folder")
        target = out / case.name
        if target.exists() and not target.is_dir():
            raise CaseError(args.case, "case.name", f"{target} exists and is a file, not a folder")
        if not args.check:
            _check_writable(out, args.case)
    except CaseError as e:
        print(f"vjax-bearing: error: {e}", file=sys.stderr)
        return 2
    if args.check:
        print(f"vjax-bearing: {args.case}: OK ({case.scene}, {len(case.points)} operating points)")
        return 0
    jax_cache.enable(args.no_cache)
    from fitting.bearing import output as bearing_output
    from fitting.bearing import run as bearing_run
    import vjax

    t0 = time.perf_counter()
    points = bearing_run.run_case(case, progress=not args.quiet)
    _remove_stale(out, case.name)
    tmp = Path(tempfile.mkdtemp(prefix=f".{case.name}.{os.getpid()}.", dir=out))
    try:
        written = bearing_output.write_outputs(case, points, tmp, time.perf_counter() - t0,
                                             getattr(vjax, "__version__", "0.1.0"))
        os.chmod(tmp, 0o777 & ~files.umask())    # mkdtemp makes it 0700
        _replace_folder(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    failed = sum(not p.row["converged"] for p in points)
    if not args.quiet:
        print(bearing_output.summary_table(case, points))
    print(f"vjax-bearing: wrote {target}/ ({', '.join(written)}); {len(points) - failed} of {len(points)} points "
          f"converged", file=sys.stderr)
    return 1 if failed else 0


def _check_writable(out: Path, case_path):
    """Before any work: ``--out`` can be made and written to (a folder is written whole, so the
    sweep's results would otherwise be lost at its end)."""
    from fitting.bearing.case import CaseError
    try:
        out.mkdir(parents=True, exist_ok=True)
        Path(tempfile.mkdtemp(prefix=".vjax-bearing-check.", dir=out)).rmdir()
    except OSError as e:
        raise CaseError(case_path, None, f"--out {out}: cannot write there ({e.strerror})") from None


def _remove_stale(out: Path, name: str):
    """The temporary folders ``.<name>.<pid>.*`` a killed run of this case left in ``out`` (its
    process no longer running); a concurrent run's own folder is left alone."""
    for folder in out.glob(f".{name}.*.*"):
        pid = folder.name[len(name) + 2:].split(".")[0]
        if folder.is_dir() and pid.isdigit() and not _running(int(pid)):
            shutil.rmtree(folder, ignore_errors=True)


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:     # another user's process
        pass
    return True


if __name__ == "__main__":
    sys.exit(main())
