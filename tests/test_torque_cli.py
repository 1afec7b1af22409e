"""vjax-fit-torque: a small pin-joint fit end to end, and its failures on bad input."""
import json

import jax
import numpy as np
import pytest

from fitting.calibration import io
from fitting import torque as ft
from fitting.cli.torque import main
from vjax import Arrhenius, Material, WLF

TRUE = Material.prony(1e6, [3e6, 4e6, 2e6], [1e-4, 1e-3, 1e-2], 0.5)
SHIFT = WLF(8.0, 100.0, 25.0)
GEOMETRY = ["--scene", "pin", "--R", "0.01", "--radial-clearance", "1e-4", "--n", "32"]


@pytest.fixture
def files(tmp_path):
    model = ft.pin_model(R=0.01, radial_clearance=1e-4, n=32)
    rpm = np.tile([30.0, 100.0, 300.0], 2)
    T = np.repeat([30.0, 50.0], 3)
    load = np.full(6, 1e3)
    tq, ok = jax.vmap(lambda a, b, c: model(TRUE, SHIFT, a, b, c))(rpm, T, load)
    assert bool(np.all(ok))
    data = tmp_path / "torque.csv"
    ft.write_torque_csv(data, ft.TorqueData(rpm, T, load, np.asarray(tq), 0.02 * np.abs(np.asarray(tq))))
    start = tmp_path / "start.json"
    io.save_material(start, Material.prony(1.3e6, [2.2e6, 5.2e6, 1.5e6], [1e-4, 1e-3, 1e-2], 0.5),
                     WLF(10.0, 80.0, 25.0))
    return data, start


def test_fit_writes_material_table_and_plots(files, tmp_path, capsys):
    data, start = files
    out = tmp_path / "refined.json"
    code = main([str(data), "--material", str(start), "--out", str(out), "--steps", "30", "--polish", "10",
                 *GEOMETRY])
    assert code == 0, capsys.readouterr().err
    text = capsys.readouterr().out
    chi0, chi1 = (float(v) for v in text.split("chi2 per point ")[1].split(" (")[0].split(" -> "))
    assert chi1 < 1e-2 * chi0                              # noise-free data: the fit closes the gap
    mat, shift, _ = io.load_material(out)
    assert isinstance(shift, WLF) and mat.moduli.shape == (3,)
    assert set(json.loads(out.read_text())["uncertainty"]["sd_rel"]) == {"E0", "E_1", "E_2", "E_3", "C1", "C2"}
    params = (tmp_path / "refined_params.csv").read_text().splitlines()
    assert params[2] == "param,start,fitted,sd_rel,torque_identifies" and len(params) == 3 + 6
    for name in ("refined_torque.png", "refined_moduli.png"):
        assert (tmp_path / name).stat().st_size > 10_000
    assert not list(tmp_path.glob(".*.tmp")) and not list(tmp_path.glob(".*.png"))


def test_bad_inputs_fail_cleanly(files, tmp_path, capsys):
    data, start = files
    out = tmp_path / "r.json"
    assert main([str(data), "--material", str(start), "--out", str(tmp_path / "r.txt")]) == 2
    assert "--out must name a .json file" in capsys.readouterr().err
    assert main([str(tmp_path / "missing.csv"), "--material", str(start), "--out", str(out), *GEOMETRY]) == 1
    assert "missing.csv" in capsys.readouterr().err
    arr = tmp_path / "arrhenius.json"
    io.save_material(arr, TRUE, Arrhenius(1e5, 25.0))
    assert main([str(data), "--material", str(arr), "--out", str(out), *GEOMETRY]) == 1
    assert "WLF" in capsys.readouterr().err
    for bad in (["--steps", "-1"], ["--lr", "0"], ["--rel-scatter", "0"], ["--n", "8"], ["--w-dma", "-1"],
                ["--radial-clearance=-0.01"], ["--oil", "32"], ["--oil", "5.4,32"], ["--oil", "32,x"],
                ["--oil", "32,5.4", "--viscosity", "0.03"]):
        assert main([str(data), "--material", str(start), "--out", str(out), *GEOMETRY, *bad]) == 2, bad
        assert bad[0].split("=")[0] in capsys.readouterr().err
    assert not out.exists()


def test_shear_start_material_is_converted_to_tensile(files, tmp_path, capsys):
    """A vjax-fit --shear JSON (G moduli) starts the fit at E = 2 (1 + nu) G, and the result is E."""
    data, _ = files
    start = tmp_path / "shear.json"
    f = 2 * (1 + 0.5)
    io.save_material(start, Material.prony(1.3e6 / f, [2.2e6 / f, 5.2e6 / f, 1.5e6 / f], [1e-4, 1e-3, 1e-2], 0.5),
                     WLF(10.0, 80.0, 25.0), modulus="G")
    out = tmp_path / "refined.json"
    code = main([str(data), "--material", str(start), "--out", str(out), "--steps", "30", "--polish", "10",
                 "--no-plots", *GEOMETRY])
    assert code == 0, capsys.readouterr().err
    mat, _, modulus = io.load_material(out)
    assert modulus == "E"
    np.testing.assert_allclose(float(mat.E0), float(TRUE.E0), rtol=0.05)


def test_command_line_tools_print_no_float32_warning():
    import subprocess
    import sys
    for module in ("fitting.cli.fit", "fitting.cli.torque"):
        r = subprocess.run([sys.executable, "-m", module, "--help"], capture_output=True, text=True, timeout=120,
                           env={**__import__("os").environ, "JAX_ENABLE_X64": "0"})
        assert r.returncode == 0 and "usage" in r.stdout, r.stderr
        assert "float32" not in r.stderr, (module, r.stderr)


def test_written_files_are_readable_by_others(tmp_path):
    """Atomic writes give the mode of a newly created file (0666 less the umask), not
    tempfile's 0600."""
    import os
    import stat
    old = os.umask(0o022)
    try:
        path = tmp_path / "m.json"
        io.save_material(path, TRUE, WLF(8.86, 101.6, 25.0))
        assert stat.S_IMODE(path.stat().st_mode) == 0o644
    finally:
        os.umask(old)
