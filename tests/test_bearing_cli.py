"""vjax-bearing (fitting.cli.bearing): refusals of bad input, the coefficients file read back by
an independent reader of its documented layout (docs/bearing_files.md) against vjax called
directly, a failed point reported while the others go on, and one shipped example end to end."""
import csv
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from fitting.cli import bearing as bearing_cli
from fitting.bearing.case_units import parse

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

# a long journal bearing with a soft viscoelastic bore; 2e4 N/m is beyond the solver (the bore
# would deform the film by ~200 clearances), 200 N/m converges at both speeds
LONG = """
[case]
scene = "long_journal"
name = "long_soft"

[geometry]
bore_radius = "50 mm"
radial_clearance = "50 um"
length = "0.1 m"

[lubricant]
viscosity = "0.01 Pa s"

[housing]
body = "hole"
material = { model = "sls", E0 = "1 MPa", Einf = "10 MPa", tau = "10 ms", nu = 0.45 }

[operating]
speed = ["10 rad/s", "1000 rad/s"]
load = ["200 N/m", "20000 N/m"]

[grid]
n = 64

[coefficients]
whirl_ratio = [0.0, 0.5, 1.0]
"""

JOURNAL = """
[case]
scene = "finite_journal"
name = "lined"

[geometry]
bore_radius = "25 mm"
radial_clearance = "50 um"
length = "50 mm"

[lubricant]
law = "oil"
nu40 = "32 cSt"
nu100 = "5.4 cSt"

[housing]
body = "liner"
thickness = "2 mm"
material = "liner.json"

[operating]
speed = ["1000 rpm"]
load = ["1 kN"]
temperature = "50 C"
"""


def _write(tmp_path, text, name="case.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _run(capsys, *argv):
    code = bearing_cli.main([str(a) for a in argv] + ["--no-cache"])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_units():
    assert parse("50 mm", "length") == pytest.approx(0.05)
    assert parse("3000 rpm", "angular speed") == pytest.approx(100 * math.pi)
    assert parse("313.15 K", "temperature") == pytest.approx(40.0)
    assert parse("32cSt", "kinematic viscosity") == 32.0


@pytest.mark.parametrize("edit, key, words", [
    (("bore_radius = \"25 mm\"", "bore_radios = \"25 mm\""), "geometry.bore_radios", "unknown key"),
    (("radial_clearance = \"50 um\"", "radial_clearance = 0.00005"), "geometry.radial_clearance", "missing unit"),
    (("radial_clearance = \"50 um\"", "radial_clearance = \"-50 um\""), "geometry.radial_clearance", "> 0"),
    (("radial_clearance = \"50 um\"", "radial_clearance = \"30 mm\""), "geometry.radial_clearance", "below the radius"),
    (("radial_clearance = \"50 um\"", "radial_clearance = \"50 furlong\""), "geometry.radial_clearance", "unknown unit"),
    (("material = \"liner.json\"", "material = \"missing.json\""), "housing.material", "does not load"),
    (("material = \"liner.json\"", "material = \"broken.json\""), "housing.material", "does not load"),
    (("temperature = \"50 C\"\n", ""), "operating.temperature", "required"),
    (("scene = \"finite_journal\"", "scene = \"thrust\""), "case.scene", "expected one of"),
    (("[operating]", "[operating]\nspeed_max = \"1 rpm\""), "operating.speed_max", "unknown key"),
    (("load = [\"1 kN\"]", "load = [\"1 kN\", \"2 Pa\"]"), "operating.load", "unknown unit"),
    (("load = [\"1 kN\"]", "load = [\"-1 kN\"]"), "operating.load", "> 0"),
    (("thickness = \"2 mm\"", "thickness = \"2\""), "housing.thickness", "missing unit"),
])
def test_bad_input_refused_naming_the_key_and_nothing_written(tmp_path, capsys, edit, key, words):
    shutil.copy(EXAMPLES / "polymer_liner.json", tmp_path / "liner.json")
    (tmp_path / "broken.json").write_text('{"kind": "prony", "E0": 1e6, "moduli": [1e6], "nu": 0.4}')
    assert edit[0] in JOURNAL
    case = _write(tmp_path, JOURNAL.replace(edit[0], edit[1]))
    before = sorted(p.name for p in tmp_path.rglob("*"))
    out = tmp_path / "results"
    code, _, err = _run(capsys, case, "--out", out)
    assert code == 2
    assert str(case) in err and f"{key}:" in err and words in err, err
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.rglob("*")) == before     # no file, no temporary folder


def test_bad_set_value_refused(tmp_path, capsys):
    shutil.copy(EXAMPLES / "polymer_liner.json", tmp_path / "liner.json")
    case = _write(tmp_path, JOURNAL)
    code, _, err = _run(capsys, case, "--out", tmp_path / "r", "--set", "grid.n=many")
    assert code == 2 and "grid.n" in err and not (tmp_path / "r").exists()
    code, _, err = _run(capsys, case, "--out", tmp_path / "r", "--set", "grid.n=4")
    assert code == 2 and "grid.n" in err and not (tmp_path / "r").exists()


def test_inline_material_refused_naming_the_key(tmp_path, capsys):
    code, _, err = _run(capsys, EXAMPLES / "pin_joint.toml", "--out", tmp_path / "r",
                        "--set", 'housing.material.Einf="0.5 MPa"')       # below E0 = 1 MPa
    assert code == 2 and "housing.material:" in err and "Einf" in err and not (tmp_path / "r").exists()
    code, _, err = _run(capsys, EXAMPLES / "pin_joint.toml", "--out", tmp_path / "r", "--set", "housing.material.nu=0.7")
    assert code == 2 and "housing.material.nu:" in err and not (tmp_path / "r").exists()


def _read_coefficients(path):
    """An independent reader of docs/bearing_files.md's layout: one header line, then per row
    kxx, kxy, kyx, kyy (N/m), cxx, cxy, cyx, cyy (N s/m), frequency (whirl, rad/s), speed (rad/s)."""
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    K = np.array([[[float(r["kxx"]), float(r["kxy"])], [float(r["kyx"]), float(r["kyy"])]] for r in rows])
    C = np.array([[[float(r["cxx"]), float(r["cxy"])], [float(r["cyx"]), float(r["cyy"])]] for r in rows])
    return rows, K, C


def test_long_journal_coefficients_and_failed_points(tmp_path, capsys):
    import vjax
    case = _write(tmp_path, LONG)
    code, table, err = _run(capsys, case, "--out", tmp_path)
    folder = tmp_path / "long_soft"
    assert code == 1, err                                   # some points failed: status 1, results written
    with open(folder / "points.csv", newline="") as fh:
        points = list(csv.DictReader(fh))
    assert [p["converged"] for p in points] == ["True", "True", "False", "False"]
    for p in points[2:]:                                     # the solver's reason, and no numbers
        assert "did not converge" in p["reason"] and "clearances" in p["reason"] and p["eccentricity"] == ""
    assert table.count("FAILED") == 2 and "did not converge" in (folder / "report.md").read_text()

    rows, K, C = _read_coefficients(folder / "coefficients.csv")
    assert len(rows) == 2 * 3                                # the converged points x the whirl ratios
    L, c = 0.1, 5e-5
    body = vjax.hole(vjax.Material.sls(1e6, 1e7, 0.01, 0.45))
    for i, w in enumerate((10.0, 1000.0)):
        whirl = np.array([0.0, 0.5, 1.0]) * w
        co = vjax.journal_coefficients(0.05, c, 0.01, 200.0, whirl, housing=body, omega_shaft=w,
                                       options=vjax.JournalOptions(n=64))
        mine = slice(3 * i, 3 * i + 3)
        assert [float(r["frequency"]) for r in rows[mine]] == pytest.approx(whirl)
        assert [float(r["speed"]) for r in rows[mine]] == pytest.approx([w] * 3)
        # the file holds the bearing's totals: the long bearing's per-length K, C times L
        np.testing.assert_allclose(K[mine], np.asarray(co.stiffness) * L, rtol=1e-6, atol=1e-9 * abs(K[mine]).max())
        np.testing.assert_allclose(C[mine], np.asarray(co.damping) * L, rtol=1e-6, atol=1e-9 * abs(C[mine]).max())
        W = 200.0 * L
        for r, k, d in zip(rows[mine], K[mine], C[mine]):
            assert float(r["kxy_bar"]) == pytest.approx(k[0, 1] * c / W, rel=1e-12)
            assert float(r["cyy_bar"]) == pytest.approx(d[1, 1] * c * w / W, rel=1e-12)
    # the viscoelastic bore answers at its own frequency: K depends on the whirl
    assert abs(K[0, 1, 1] - K[2, 1, 1]) > 1e-3 * abs(K[0]).max()
    # ROSS's table reader converts units when a cell says rpm, lb or inches: none may
    text = (folder / "coefficients.csv").read_text().lower()
    assert not any(word in text for word in ("rpm", "lb", "inches"))


def test_pin_example_end_to_end(tmp_path, capsys):
    import vjax
    speeds = ["0.1 rad/s", "10 rad/s"]
    code, table, err = _run(capsys, EXAMPLES / "pin_joint.toml", "--out", tmp_path, "--set", "grid.n=256",
                            "--set", "operating.speed=" + str(speeds).replace("'", '"'))
    folder = tmp_path / "pin_joint"
    assert code == 0, err
    assert sorted(p.name for p in folder.iterdir()) == ["points.csv", "report.md", "torque_friction.png"]
    assert [p for p in tmp_path.iterdir() if p.name.startswith(".")] == []     # no temporary left
    report = (folder / "report.md").read_text()
    assert "hole_radius = \"80 mm\"" in report and "--set grid.n=256" in report and "![torque_friction.png]" in report
    with open(folder / "points.csv", newline="") as fh:
        points = list(csv.DictReader(fh))
    assert len(points) == 2 and "| ok |" in table
    m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)
    for p, w in zip(points, (0.1, 10.0)):
        r = vjax.pin_in_hole(m, 0.08, 0.005, 2800.0, omega_shaft=w, load_angle=0.0, options=vjax.PinOptions(n=256))
        assert float(p["torque_housing_Nm_per_m"]) == pytest.approx(float(r.torque), rel=1e-8)
        assert float(p["friction_coefficient"]) == pytest.approx(float(r.torque) / (2800.0 * 0.08), rel=1e-8)
    # a second run replaces the folder whole
    (folder / "stale.txt").write_text("x")
    assert _run(capsys, EXAMPLES / "pin_joint.toml", "--out", tmp_path, "--set", "grid.n=256",
                "--set", 'operating.speed="1 rad/s"', "--quiet")[0] == 0
    assert not (folder / "stale.txt").exists()


def test_finite_journal_coefficients_read_back(tmp_path, capsys):
    """The finite bearing's path: rigid, isoviscous, 16 x 4 cells, two speeds (the second warm-started)."""
    import vjax
    text = JOURNAL.replace('law = "oil"\nnu40 = "32 cSt"\nnu100 = "5.4 cSt"', 'viscosity = "20 mPa s"') \
                  .replace('body = "liner"\nthickness = "2 mm"\nmaterial = "liner.json"', 'body = "rigid"') \
                  .replace('speed = ["1000 rpm"]', 'speed = ["1000 rpm", "3000 rpm"]') \
                  .replace('temperature = "50 C"\n', "") + '\n[grid]\nn = 16\nm = 4\n'
    code, _, err = _run(capsys, _write(tmp_path, text), "--out", tmp_path)
    assert code == 0, err
    rows, K, C = _read_coefficients(tmp_path / "lined" / "coefficients.csv")
    assert len(rows) == 2
    opt = vjax.FiniteJournalOptions(n=16, m=4)
    for i, w in enumerate((1000 * math.pi / 30, 3000 * math.pi / 30)):
        co = vjax.journal_coefficients(0.025, 5e-5, 0.02, 1000.0, np.array([w]), omega_shaft=w, length=0.05,
                                       options=opt)
        assert float(rows[i]["frequency"]) == pytest.approx(w)
        np.testing.assert_allclose(K[i], np.asarray(co.stiffness)[0], rtol=1e-6, atol=1e-9 * abs(K[i]).max())
        np.testing.assert_allclose(C[i], np.asarray(co.damping)[0], rtol=1e-6, atol=1e-9 * abs(C[i]).max())
    assert (tmp_path / "lined" / "film_pressure.png").exists() and (tmp_path / "lined" / "eccentricity_locus.png").exists()


def test_viscoelastic_share_against_the_dissipations(tmp_path, capsys):
    """A viscoelastic bore turning under a fixed load: its share of the power (from torques, in
    points.csv) equals its hysteresis over all the dissipation vjax reports (the power balance)."""
    import vjax
    text = LONG.replace('speed = ["10 rad/s", "1000 rad/s"]', 'speed = "100 rad/s"\nturning = "housing"') \
               .replace('load = ["200 N/m", "20000 N/m"]', 'load = "200 N/m"')
    code, _, err = _run(capsys, _write(tmp_path, text), "--out", tmp_path, "--quiet")
    assert code == 0, err
    with open(tmp_path / "long_soft" / "points.csv", newline="") as fh:
        (row,) = list(csv.DictReader(fh))
    r = vjax.journal_bearing(0.05, 5e-5, 0.01, 200.0, housing=vjax.hole(vjax.Material.sls(1e6, 1e7, 0.01, 0.45)),
                             omega_housing=100.0, options=vjax.JournalOptions(n=64))
    total = float(r.dissipation_fluid + r.dissipation_housing + r.dissipation_shaft)
    share = float(row["viscoelastic_share"])
    assert 1e-5 < share < 1
    assert share == pytest.approx(float(r.dissipation_housing) / total, rel=1e-6)


def test_default_grids_are_the_librarys():
    # one default, stated once: a case file without [grid] solves on the scene's own default
    import vjax
    from fitting.bearing import case
    assert case._DEFAULT_N == {"finite_journal": vjax.FiniteJournalOptions().n, "long_journal": vjax.JournalOptions().n,
                               "roller": vjax.RollerOptions().n, "pin": vjax.PinOptions().n}
    assert case._DEFAULT_M == vjax.FiniteJournalOptions().m


# Raimondi and Boyd (ASLE Trans. 1, 1958), L/D = 1, Reynolds conditions, the film from its
# maximum: (eps, S, attitude deg, (R/c) f), as tests/test_journal_finite.py's table
RAIMONDI_BOYD_LD1 = [(0.4, 0.264, 63.10, 5.79), (0.6, 0.121, 50.58, 3.22)]


@pytest.mark.parametrize("eps, S, phi, f", RAIMONDI_BOYD_LD1)
def test_friction_coefficient_is_raimondi_and_boyds(tmp_path, capsys, eps, S, phi, f):
    """A rigid bearing written from docs/bearing_files.md alone, on the default grid: the tool's
    friction coefficient is the journal's, (R/c) f within 4 % of the table; the housing's
    torque over W R is not: it is short by the load's moment arm e sin(phi)."""
    R, c, L, eta, N = 0.02, 4e-5, 0.04, 0.03, 50.0
    W = (R / c) ** 2 * eta * N * 2 * R * L / S
    case = f"""
[case]
scene = "finite_journal"
name = "rb"

[geometry]
bore_radius = "{R * 1e3} mm"
radial_clearance = "{c * 1e6} um"
length = "{L * 1e3} mm"
supply_angle = "{180 + phi} deg"

[lubricant]
viscosity = "{eta} Pa s"

[operating]
speed = "{N * 60} rpm"
load = "{W} N"
"""
    path = tmp_path / "rb.toml"
    path.write_text(case)
    code, _, err = _run(capsys, path, "--out", tmp_path / "out")
    assert code == 0, err
    (row,) = list(csv.DictReader(open(tmp_path / "out" / "rb" / "points.csv")))
    assert float(row["eccentricity"]) == pytest.approx(eps, abs=0.01)
    assert float(row["friction_coefficient"]) * R / c == pytest.approx(f, rel=0.04)
    # the housing's torque is the journal's less the load's moment arm W e sin(phi) (the moment
    # balance of the film): the two agree only when e sin(phi) << f R
    housing = float(row["friction_torque_Nm"]) / (W * R) * R / c
    arm = float(row["eccentricity"]) * math.sin(math.radians(float(row["attitude_deg"])))
    assert housing == pytest.approx(float(row["friction_coefficient"]) * R / c - arm, rel=0.01)


assert JOURNAL.endswith('temperature = "50 C"\n')
TWO_TEMPERATURES = (JOURNAL.removesuffix('temperature = "50 C"\n') + 'temperature = "40 C"\n') \
    .replace('material = "liner.json"\n', 'material = "liner.json"\ntemperature = "60 C"\n\n'
             '[shaft]\nbody = "sleeve"\nthickness = "2 mm"\nmaterial = "liner.json"\n') \
    .replace('nu100 = "5.4 cSt"\n', 'nu100 = "5.4 cSt"\ntemperature = "50 C"\n') + '\n[grid]\nn = 16\nm = 4\n'


def test_two_bodies_at_two_temperatures_and_the_oil_at_a_third(tmp_path, capsys):
    """The housing's liner at its own 60 C, the shaft's sleeve at the operating 40 C, the oil at
    its own 50 C: each body's relaxation times are its material's at its temperature
    (Material.at_temperature), the viscosity the oil's at 50 C; the case runs (issue 51)."""
    import numpy as np
    import vjax
    from fitting.bearing import run
    from fitting.bearing.case import load_case
    from fitting.calibration.io import load_material
    shutil.copy(EXAMPLES / "polymer_liner.json", tmp_path / "liner.json")
    path = _write(tmp_path, TWO_TEMPERATURES)
    case = load_case(path)
    assert case.temperatures == (40.0,) and case.housing.temperature == 60.0 and case.oil_temperature == 50.0
    material, law, _ = load_material(tmp_path / "liner.json")
    scene = run._Scene(case, 40.0)
    for body, T in ((scene.housing, 60.0), (scene.shaft, 40.0)):
        expected = material.with_shift(law).at_temperature(T).times
        np.testing.assert_allclose(np.asarray(body.material.times), np.asarray(expected), rtol=1e-12)
    oil = vjax.Lubricant.walther(32.0, 5.4, 40.0, 100.0, rho=860.0)
    assert case.eta(40.0) == pytest.approx(float(oil.viscosity(50.0)), rel=1e-12)
    code, _, err = _run(capsys, path, "--out", tmp_path / "out", "--quiet")
    assert code == 0, err


@pytest.mark.parametrize("edit, key", [
    (('[lubricant]\nlaw = "oil"', '[lubricant]\nlaw = "constant"\nviscosity = "0.01 Pa s"'), "lubricant.temperature"),
    (('material = "liner.json"\ntemperature = "60 C"',
      'material = { model = "sls", E0 = "1 MPa", Einf = "10 MPa", tau = "10 ms", nu = 0.45 }\ntemperature = "60 C"'),
     "housing.temperature"),
])
def test_a_temperature_that_moves_nothing_is_refused(tmp_path, capsys, edit, key):
    shutil.copy(EXAMPLES / "polymer_liner.json", tmp_path / "liner.json")
    text = TWO_TEMPERATURES.replace(edit[0], edit[1])
    if key == "lubricant.temperature":
        text = text.replace('nu40 = "32 cSt"\nnu100 = "5.4 cSt"\n', "")
    assert text != TWO_TEMPERATURES
    code, _, err = _run(capsys, _write(tmp_path, text), "--out", tmp_path / "out")
    assert code == 2 and f"{key}:" in err and "moves nothing" in err, err
