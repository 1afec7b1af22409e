"""fitting.torque with self-heating: the thermal models at hA = inf are the isothermal ones, the
torque's derivative w.r.t. log hA matches central differences, a fit on noise-free self-heated
torques recovers the material and hA, and vjax-fit-torque's --heat-transfer is checked."""
import jax.numpy as jnp
import numpy as np
import pytest

from fitting.calibration import io
from fitting import torque as ft
from fitting.cli.torque import main
from vjax import WLF, Material

TRUE = Material.prony(1e6, [3e6, 4e6], [1e-4, 1e-2], 0.5)
SHIFT = WLF(8.0, 100.0, 25.0)
HA = 20.0        # W/(m K): heats the pin's plate by 0.3-8 K at these points
# three speeds x three loads at two ambient temperatures
GRID = [(s, T, F) for T in (30.0, 50.0) for F in (500.0, 1000.0, 2000.0) for s in (30.0, 100.0, 300.0)]
RPM, T, LOAD = (jnp.asarray(v) for v in zip(*GRID))


def _torques(model, material=TRUE, shift=SHIFT, extras=None):
    tq, ok = ft.evaluate(model, material, shift, RPM, T, LOAD, extras)
    assert bool(np.all(np.asarray(ok)))
    return np.asarray(tq)


def test_infinite_heat_transfer_is_the_isothermal_model():
    """hA = inf holds the plate at the data's T: the same torques as the isothermal pin model to
    round-off; a finite hA heats it and the torques differ (the comparison can fail)."""
    iso = _torques(ft.pin_model(n=32))
    np.testing.assert_allclose(_torques(ft.pin_model(n=32, heat_transfer=float("inf"))), iso, rtol=1e-12)
    hot = _torques(ft.pin_model(n=32, heat_transfer=HA))
    assert np.max(np.abs(hot / iso - 1)) > 0.02


@pytest.mark.slow
def test_roller_infinite_heat_transfer_is_the_isothermal_model():
    """The same for the roller model (both rings heated by their hysteresis)."""
    pts = (jnp.array([100.0, 1000.0]), jnp.array([30.0, 50.0]), jnp.array([240.0, 240.0]))
    iso = np.asarray(ft.evaluate(ft.roller_model(n=64), TRUE, SHIFT, *pts)[0])
    inf = np.asarray(ft.evaluate(ft.roller_model(n=64, heat_transfer=float("inf")), TRUE, SHIFT, *pts)[0])
    hot = np.asarray(ft.evaluate(ft.roller_model(n=64, heat_transfer=0.5), TRUE, SHIFT, *pts)[0])
    np.testing.assert_allclose(inf, iso, rtol=1e-12)
    assert np.max(np.abs(hot / iso - 1)) > 0.02


@pytest.mark.slow
def test_journal_infinite_heat_transfer_is_the_isothermal_model():
    """The same for the journal model (ISO 7902's balance with hA = inf: the film and the liner
    at the supply temperature), one point of a water-lubricated bearing with a turning liner."""
    iso = ft.journal_model(length=0.05, n=16, m=4)
    th = ft.journal_model(length=0.05, n=16, m=4, heat_transfer=float("inf"))
    mat = Material.prony(1e6, [8e6, 6e6], [0.03, 1.0], 0.5)
    a = iso(mat, SHIFT, 200.0, 40.0, 400.0)
    b = th(mat, SHIFT, 200.0, 40.0, 400.0)
    assert bool(a[1]) and bool(b[1])
    np.testing.assert_allclose(float(b[0]), float(a[0]), rtol=1e-10)


@pytest.mark.slow      # hA = inf against the isothermal model stays fast
def test_heat_transfer_derivative_and_noise_free_fit_recover_the_truth():
    """d torque / d log hA from the implicit derivatives of the thermal balance against central
    differences; then a fit with log hA free, started 20-50 % off in every parameter, lands on
    the truth (material and hA) from noise-free self-heated torques."""
    model = ft.pin_model(n=32, heat_transfer=HA)
    tq = _torques(model)
    n = len(GRID)
    data = ft.TorqueData(*(np.asarray(a) for a in (RPM, T, LOAD)), tq, 0.01 * tq)
    P = ft.Params.of(TRUE, SHIFT, extras=("hA",))
    x = P.pack(TRUE, SHIFT, {"hA": HA})
    unit = ft.TorqueData(data.rpm, data.T, data.load, tq, np.ones(n))
    jac, _ = ft.residual_jacobian(P, model, unit)
    J = np.asarray(jac(jnp.asarray(x))[0])[:, -1]
    h = 1e-5
    e = np.zeros_like(x)
    e[-1] = h
    fd = (np.asarray(jac(jnp.asarray(x + e))[1][2]) - np.asarray(jac(jnp.asarray(x - e))[1][2])) / (2 * h)
    np.testing.assert_allclose(J, fd, rtol=1e-6, atol=1e-8 * np.max(np.abs(fd)))
    assert np.max(np.abs(J) / tq) > 0.01      # the heating matters: hA is in the data

    start_mat, start_shift = P.physical(x[:-1] + np.log([1.3, 0.7, 1.4, 0.8, 1.2]))
    fit = ft.fit_torque(data, start_mat, start_shift, model, extras={"hA": 1.5 * HA}, steps=60, polish=40,
                        progress=False)
    assert fit.converged
    np.testing.assert_allclose(np.exp(fit.x), np.exp(x), rtol=1e-4)
    np.testing.assert_allclose(fit.extras["hA"], HA, rtol=1e-4)


@pytest.fixture
def files(tmp_path):
    tq = _torques(ft.pin_model(n=32, heat_transfer=HA))
    data = tmp_path / "torque.csv"
    ft.write_torque_csv(data, ft.TorqueData(*(np.asarray(a) for a in (RPM, T, LOAD)), tq, 0.02 * tq))
    start = tmp_path / "start.json"
    io.save_material(start, Material.prony(1.2e6, [2.5e6, 4.5e6], [1e-4, 1e-2], 0.5), WLF(9.0, 90.0, 25.0))
    return data, start


GEOMETRY = ["--scene", "pin", "--R", "0.01", "--radial-clearance", "1e-4", "--n", "32"]


def test_cli_heat_transfer_is_validated(files, tmp_path, capsys):
    data, start = files
    out = tmp_path / "r.json"
    for bad, named in ((["--heat-transfer", "0"], "--heat-transfer"), (["--heat-transfer=-5"], "--heat-transfer"),
                       (["--heat-transfer", "nan"], "--heat-transfer"), (["--heat-transfer", "x"], "--heat-transfer"),
                       (["--fit-heat-transfer"], "--fit-heat-transfer"),
                       (["--heat-transfer", "inf", "--fit-heat-transfer"], "--fit-heat-transfer"),
                       (["--roughness", "1e-6"], "--roughness"),
                       (["--fit-friction"], "--fit-friction")):
        with_args = [str(data), "--material", str(start), "--out", str(out), *GEOMETRY, *bad]
        try:
            code = main(with_args)
        except SystemExit as e:          # argparse's own refusal (not a number)
            code = e.code
        assert code == 2, bad
        assert named in capsys.readouterr().err, bad
    assert not out.exists()


@pytest.mark.slow      # the CLI option checks stay fast
def test_cli_fits_heat_transfer(files, tmp_path, capsys):
    """--heat-transfer with --fit-heat-transfer: runs, writes hA into the JSON's fit record and
    the params CSV, and brings the torque to the noise."""
    import json
    data, start = files
    out = tmp_path / "refined.json"
    code = main([str(data), "--material", str(start), "--out", str(out), "--steps", "30", "--polish", "20",
                 "--no-plots", "--heat-transfer", str(2 * HA), "--fit-heat-transfer", *GEOMETRY])
    assert code == 0, capsys.readouterr().err
    record = json.loads(out.read_text())
    fit = next(v for k, v in record.items() if isinstance(v, dict) and "hA" in v)
    assert abs(fit["hA"] / HA - 1) < 0.05
    assert fit["loss"] < 1.0
    assert "hA," in (tmp_path / "refined_params.csv").read_text()
