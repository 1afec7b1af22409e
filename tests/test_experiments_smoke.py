"""Smoke test of the experiment scripts: quick runs write their files with finite numbers."""
import csv
import math
import sys
from pathlib import Path

import pytest

try:
    import experiments  # noqa: F401  (top-level folder, not installed: needs the repo root on sys.path)
except ImportError:  # plain `pytest` puts tests/ on sys.path, `python -m pytest` the working dir
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from experiments import _common  # noqa: E402
from experiments.benchmarks import bench_operator  # noqa: E402
from experiments.figures import foundation_figures, journal_bores, journal_dynamics  # noqa: E402


def _numeric_cells(path):
    """All cells of a '#'-commented CSV that parse as floats (header excluded)."""
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    assert len(rows) > 1, f"{path} has no data rows"
    values = []
    for row in rows[1:]:
        for cell in row:
            try:
                values.append(float(cell))
            except ValueError:
                pass
    return rows[0], values


def test_foundation_figures_quick(tmp_path):
    report = foundation_figures.main(out_dir=tmp_path, quick=True)
    assert "trail/lead" in report.text
    assert report.checks and all(c.passed for c in report.checks), [c for c in report.checks if not c.passed]
    for name, _ in report.figures:
        assert (tmp_path / name).exists(), name
    for name in ("fig2_3_A4_hole.png", "figA6_diametral.png", "ring_profiles_u_theta.png",
                 "material_curves.png"):
        assert (tmp_path / name).stat().st_size > 10_000
    for name in ("ring_profiles.csv", "material_curves.csv", "material_spectra.csv"):
        _, values = _numeric_cells(tmp_path / name)
        assert values and all(math.isfinite(v) for v in values), name
    assert (tmp_path / "foundation_summary.txt").read_text() == report.text
    assert not list(tmp_path.glob(".*.tmp")), "temporary files left behind"


def test_bench_operator_quick(tmp_path):
    rows = bench_operator.main(out_dir=tmp_path, quick=True)
    assert (tmp_path / "bench_operator.png").stat().st_size > 10_000
    header, values = _numeric_cells(tmp_path / "bench_operator.csv")
    assert header[0] == "N" and len(rows) >= 2
    finite = [v for v in values if not math.isnan(v)]
    assert finite and all(math.isfinite(v) and v >= 0 for v in finite)
    for r in rows:  # every timing of the FFT path is there, and the FFT matches the dense product
        assert all(math.isfinite(x) and x > 0 for x in r[1:7])
        if not math.isnan(r[9]):
            assert r[9] < 1e-10


def test_common_helpers(tmp_path):
    p = _common.write_csv(tmp_path / "sub" / "t.csv", ["a", "b"], [(1, 0.1), ("x", float("nan"))],
                          comments=["units: none"])
    assert p.read_text() == "# units: none\na,b\n1,0.1\nx,nan\n"
    import time
    first, median = _common.time_fn(lambda x: time.sleep(x), 0.02, repeats=3)   # it measures wall time
    assert 0.02 <= median < 1.0 and 0.02 <= first < 1.0
    assert "-" in _common.format_table(["h"], [[float("nan")]])


@pytest.mark.slow
def test_roller_design_quick(tmp_path):
    """The gradient-vs-random-search design script runs end to end (one material, Z = 10,
    n = 128) and both methods use the same number of solver calls."""
    pytest.importorskip("scipy")
    from experiments.studies import design
    result = design.main(out_dir=tmp_path, quick=True, only="roller")
    gradient, random = result["roller"]
    assert gradient[1] == random[1] >= 2
    header, values = _numeric_cells(tmp_path / "design_roller_history.csv")
    assert header[:3] == ["method", "material", "Z"] and all(math.isfinite(v) for v in values)
    assert (tmp_path / "design_roller.png").stat().st_size > 10_000
    assert "roller bearing design" in (tmp_path / "design_summary_roller.txt").read_text()


@pytest.mark.slow
def test_torque_twin_quick(tmp_path):
    """The twin experiment writes its data, tables, refined material and plots, and both fits
    lower the torque misfit."""
    from experiments.studies import torque_twin
    res = torque_twin.main(out_dir=tmp_path, quick=True, scene="pin", steps=10)   # the pin compiles 2x faster
    for row in res["summary"]:
        assert row[2] < row[1]                     # chi2 fitted < chi2 start
    assert all(r[3] < 1e-5 for r in res["gradient_check"])
    for suffix in ("data.csv", "params.csv", "summary.csv", "refined.json", "truth.json", "torque.png",
                   "moduli.png", "loss.png", "summary.txt"):
        assert (tmp_path / f"torque_twin_pin_{suffix}").exists(), suffix


@pytest.mark.slow
def test_bodies_figures_quick(tmp_path):
    from experiments.figures import bodies_figures
    report = bodies_figures.main(out_dir=tmp_path / "bodies", quick=True)
    assert all(c.passed for c in report.checks), [c for c in report.checks if not c.passed]
    for name, _ in report.figures:
        assert (tmp_path / "bodies" / name).stat().st_size > 10_000
    _, values = _numeric_cells(tmp_path / "bodies" / "bodies_test_bearing.csv")
    assert values and all(math.isfinite(v) for v in values)



@pytest.mark.slow
def test_journal_dynamics_quick(tmp_path):
    report = journal_dynamics.main(out_dir=tmp_path, quick=True)
    assert report.checks and all(c.passed for c in report.checks), [c for c in report.checks if not c.passed]
    assert (tmp_path / "dynamics_coefficients.png").stat().st_size > 10_000
    header, values = _numeric_cells(tmp_path / "dynamics_liner.csv")
    assert header[:4] == ["speed", "frequency", "kxx", "kxy"] and all(math.isfinite(v) for v in values)
    assert not list(tmp_path.glob(".*.tmp")), "temporary files left behind"


@pytest.mark.slow
def test_journal_bores_quick(tmp_path):
    report = journal_bores.stage(out_dir=tmp_path, quick=True)
    assert report.checks and all(c.passed for c in report.checks), [c for c in report.checks if not c.passed]
    assert (tmp_path / "journal_bores.png").stat().st_size > 10_000
    header, values = _numeric_cells(tmp_path / "journal_bores.csv")
    assert "iterations" in header and all(math.isfinite(v) for v in values)
