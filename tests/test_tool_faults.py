"""The command-line tools under faults and hostile input (issue 52): Ctrl-C, a killed run's
leftovers, an output folder that cannot be written, files that are not UTF-8 text, a byte-order
mark, and arguments checked before any work."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from fitting.cli import bearing as bearing_cli
from fitting.cli import export as export_cli
from fitting.torque import TorqueFormatError, read_torque_csv

ROOT = Path(__file__).resolve().parents[1]
PIN = (ROOT / "examples" / "pin_joint.toml").read_text()


def _bearing(capsys, *argv):
    code = bearing_cli.main([str(a) for a in argv] + ["--no-cache"])
    out = capsys.readouterr()
    return code, out.err


def test_ctrl_c_ends_a_run_with_one_line_and_status_130(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(ROOT), VJAX_NO_CACHE="1")
    p = subprocess.Popen([sys.executable, "-m", "fitting.cli.bearing", str(ROOT / "examples" / "pin_joint.toml"),
                          "--out", str(tmp_path)], cwd=tmp_path, env=env, stderr=subprocess.PIPE, text=True)
    first = p.stderr.readline()           # the sweep has started: its progress
    assert first, "the tool printed nothing"
    p.send_signal(signal.SIGINT)
    err = first + p.stderr.read()
    assert p.wait(timeout=60) == 130, err
    assert "interrupted" in err and "Traceback" not in err, err
    assert list(tmp_path.iterdir()) == []          # nothing written, no temporary folder left


def test_a_killed_runs_folder_is_removed_by_the_next_run(tmp_path, capsys):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f".pin_joint.{dead.pid}.x1"
    live = tmp_path / f".pin_joint.{os.getpid()}.x2"      # a concurrent run's: left alone
    for folder in (stale, live):
        folder.mkdir()
        (folder / "points.csv").write_text("half")
    case = tmp_path / "pin.toml"
    case.write_text(PIN.replace("points = 9", "points = 2").replace("n = 512", "n = 128"))
    code, err = _bearing(capsys, case, "--out", tmp_path, "--quiet")
    assert code == 0, err
    assert not stale.exists() and live.exists() and (tmp_path / "pin_joint" / "points.csv").exists()


def test_an_output_folder_that_cannot_be_made_is_refused_before_the_sweep(tmp_path, capsys):
    (tmp_path / "a_file").write_text("")
    t0 = time.perf_counter()
    code, err = _bearing(capsys, ROOT / "examples" / "pin_joint.toml", "--out", tmp_path / "a_file" / "sub")
    assert code == 2 and "--out" in err and "cannot write there" in err, err
    assert time.perf_counter() - t0 < 20      # refused before the nine solves, not after them


@pytest.mark.parametrize("content", [PIN.encode("utf-16"), bytes(range(256))], ids=["utf-16", "binary"])
def test_a_case_file_that_is_not_utf8_is_refused_naming_it(tmp_path, capsys, content):
    case = tmp_path / "case.toml"
    case.write_bytes(content)
    code, err = _bearing(capsys, case, "--out", tmp_path / "out")
    assert code == 2 and "case.toml" in err and "not a UTF-8 text file" in err, err
    assert "Traceback" not in err and not (tmp_path / "out").exists()


def test_a_case_file_with_a_byte_order_mark_is_read(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_bytes(PIN.encode("utf-8-sig"))
    code, err = _bearing(capsys, case, "--check")
    assert code == 0, err


def test_torque_csv_with_a_byte_order_mark_is_read_and_utf16_is_refused(tmp_path):
    text = "speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n100,40,1000,0.01\n200,40,1000,0.012\n"
    bom = tmp_path / "bom.csv"
    bom.write_bytes(text.encode("utf-8-sig"))    # as spreadsheets write "CSV UTF-8"
    data = read_torque_csv(bom)
    assert list(map(float, data.rpm)) == [100.0, 200.0]
    utf16 = tmp_path / "utf16.csv"
    utf16.write_bytes(text.encode("utf-16"))
    with pytest.raises(TorqueFormatError, match="not a UTF-8 text file"):
        read_torque_csv(utf16)


@pytest.mark.parametrize("args, words", [
    (["--stem", "../escape"], "--stem must be a file name"),
    (["--stem", "sub/escape"], "--stem must be a file name"),
    (["--isothermal", "nan"], "--isothermal must be a finite temperature"),
])
def test_export_arguments_refused_before_any_work(tmp_path, capsys, args, words):
    code = export_cli.main([str(tmp_path / "material.json"), "--format", "abaqus", "--nu", "0.45",
                            "--temperature", "C", "--out-dir", str(tmp_path / "out"), *args])
    err = capsys.readouterr().err
    assert code == 2 and words in err, err
    assert not (tmp_path / "out").exists() and not (tmp_path.parent / "escape_abaqus_degC.inp").exists()


def test_a_film_past_laminar_is_flagged_in_points_and_report(tmp_path, capsys):
    """The issue's journal at 1e6 rpm (constant viscosity): Re = rho omega R c / eta far above
    Taylor's 41.3 sqrt(R/c); 1000 rpm is laminar. The Reynolds number is the textbook's."""
    import csv
    case = tmp_path / "fast.toml"
    case.write_text('[case]\nscene = "long_journal"\nname = "fast"\n[geometry]\nbore_radius = "25 mm"\n'
                    'radial_clearance = "50 um"\nlength = "50 mm"\n[lubricant]\nviscosity = "0.01 Pa s"\n'
                    '[operating]\nspeed = ["1000 rpm", "1000000 rpm"]\nload = "2 kN"\n[grid]\nn = 64\n')
    code, err = _bearing(capsys, case, "--out", tmp_path / "out", "--quiet")
    rows = list(csv.DictReader(open(tmp_path / "out" / "fast" / "points.csv")))
    slow, fast = rows
    assert float(slow["reynolds_number"]) == pytest.approx(860 * 1000 * 2 * 3.141592653589793 / 60 * 0.025 * 5e-5 / 0.01)
    assert slow["validity"] == "" and "Taylor" not in slow["validity"]
    assert "laminar limit" in fast["validity"]
    limit = 41.3 * (0.025 / 5e-5) ** 0.5
    assert f"{limit:.3g}" in fast["validity"]
    report = (tmp_path / "out" / "fast" / "report.md").read_text()
    assert "outside the model's validity" in report and f"- point {fast['point']}:" in report
