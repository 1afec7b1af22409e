"""Round trip of a synthetic material, shift factors, NNLS, material JSON and the CLI."""
import json
import os

import numpy as np
import pytest

from vjax import Arrhenius, Material, WLF
from fitting import calibrate
from fitting.shared import optim
from fitting.cli import fit as cli
from fitting.measurements import dma
from fitting.calibration import io
from fitting.calibration import master, prony, spectrum

TRUE_WLF = WLF(10.0, 120.0, 30.0)


def _truth():
    tau = np.logspace(-7, 5, 20)
    Ek = 1e8 * np.exp(-0.5 * ((np.log10(tau) + 1.0) / 3.0) ** 2) + 2e6
    return Material.prony(1e6, Ek, tau, 0.5)


def _synthetic(tmp_path, noise=0.02, seed=0):
    mat = _truth()
    T = np.repeat(np.arange(-10.0, 71.0, 10.0), 13)
    f = np.tile(np.logspace(-1, 2, 13), 9)
    E = np.asarray(mat.modulus(2 * np.pi * f * 10 ** np.asarray(TRUE_WLF.log10_aT(T))))
    rng = np.random.default_rng(seed)
    s = E.real * np.exp(noise * rng.standard_normal(T.size))
    l = E.imag * np.exp(noise * rng.standard_normal(T.size))
    p = tmp_path / "synthetic.csv"
    with open(p, "w") as fh:
        fh.write("T [C],f [Hz],E' [Pa],E'' [Pa]\n")
        for row in zip(T, f, s, l):
            fh.write(",".join(f"{v:.10g}" for v in row) + "\n")
    return str(p), mat, T, f


def test_round_trip_synthetic_20_terms_wlf(tmp_path):
    path, truth, T, f = _synthetic(tmp_path)
    mat, shift, rep = calibrate(path, 30.0, law="WLF")
    assert isinstance(shift, WLF) and rep.converged
    # C1, C2 within three reported standard deviations of the truth
    for k in ("C1", "C2"):
        assert abs(float(getattr(shift, k)) - float(getattr(TRUE_WLF, k))) < 3 * rep.uncertainty[k], (k, shift, rep.uncertainty)
        assert rep.uncertainty[k] < 0.1 * float(getattr(TRUE_WLF, k))
    # curves within the noise: model vs noise-free truth at the measured points, and the
    # data residual at the noise level (2% = 0.0087 decades rms)
    w = 2 * np.pi * f * 10 ** np.asarray(TRUE_WLF.log10_aT(T))
    w_fit = 2 * np.pi * f * 10 ** np.asarray(shift.log10_aT(T))
    Et, Ef = np.asarray(truth.modulus(w)), np.asarray(mat.modulus(w_fit))
    dev = np.concatenate([np.log10(Ef.real / Et.real), np.log10(Ef.imag / Et.imag)])
    noise = np.log10(np.e) * 0.02
    assert np.sqrt(np.mean(dev ** 2)) < noise
    assert np.max(np.abs(dev)) < 4 * noise
    assert 0.8 * noise < rep.errors["rms"] < 1.2 * noise
    # the smooth spectrum: one loss peak (plus at most a valley and a second peak) over the data
    # range (the 20-arm truth itself, 1.6 arms per decade, ripples: it shows 3)
    assert rep.errors["loss_extrema"] == spectrum.loss_extrema(mat, w_fit.min(), w_fit.max()) <= 3


def test_shift_factors_recover_wlf_from_noisy_data(tmp_path):
    path, _, _, _ = _synthetic(tmp_path, noise=0.02, seed=1)
    t = dma.read(path)
    st = master.shift_factors(t, 30.0)
    true = np.asarray(TRUE_WLF.log10_aT(t.temperatures))
    assert np.max(np.abs(np.asarray(st.values) - true)) < 0.15
    # an unmeasured reference temperature shifts the table by log10 a_T(T_ref) (to the
    # accuracy of the linear interpolation between 30 and 40 C)
    st2 = master.shift_factors(t, 35.0)
    assert np.allclose(np.asarray(st2.values) - np.asarray(st.values), -float(st.log10_aT(35.0)), atol=1e-9)
    wlf, rms = master.fit_wlf(st.T, st.values, 30.0)
    assert rms < 0.1 and abs(float(wlf.C1) - 10) < 2.5


def test_wlf_and_arrhenius_fits_exact():
    T = np.linspace(-20, 80, 11)
    w, rms = master.fit_wlf(T, np.asarray(TRUE_WLF.log10_aT(T)), 30.0)
    assert float(w.C1) == pytest.approx(10.0, rel=1e-5) and float(w.C2) == pytest.approx(120.0, rel=1e-5)
    a = Arrhenius(1.5e5, 30.0)
    r, rms = master.fit_arrhenius(T, np.asarray(a.log10_aT(T)), 30.0)
    assert float(r.Ea) == pytest.approx(1.5e5, rel=1e-10) and rms < 1e-10


def test_nnls_matches_known_solution():
    rng = np.random.default_rng(3)
    A = rng.random((200, 12))
    x_true = np.where(rng.random(12) < 0.5, 0.0, rng.random(12))
    x, res = optim.nnls(A, A @ x_true)
    assert np.allclose(x, x_true, atol=1e-9) and res < 1e-9
    # an active constraint: the unconstrained optimum is negative
    x, _ = optim.nnls(np.eye(2), np.array([1.0, -1.0]))
    assert np.allclose(x, [1.0, 0.0])


def test_prony_master_fit_recovers_curve():
    mat = _truth()
    w = np.logspace(-3, 7, 60)
    E = np.asarray(mat.modulus(w))
    (E0, Ek, tau), crit = prony.choose_terms(w, E.real, E.imag)
    assert np.all(Ek > 0) and E0 >= 0 and len(crit) == 6
    fit = Material.prony(max(E0, 1.0), Ek, tau, 0.5)
    Ef = np.asarray(fit.modulus(w))
    assert np.max(np.abs(np.log10(Ef.real / E.real))) < 0.01
    assert np.max(np.abs(np.log10(Ef.imag / E.imag))) < 0.02


@pytest.mark.parametrize("shift", [WLF(8.86, 101.6, 25.0), Arrhenius(2.0e5, 25.0),
                                   master.ShiftTable.make([0.0, 25.0, 50.0], [3.0, 0.0, -2.5], 25.0)])
def test_json_round_trip(tmp_path, shift):
    mat = _truth()
    p = tmp_path / "m.json"
    io.save_material(p, mat, shift, modulus="E", uncertainty={"C1": 0.1})
    d = json.loads(p.read_text())
    assert d["kind"] == "prony" and d["modulus"] == "E" and d["shift"]["T_ref"] == 25.0
    assert set(d) >= {"E0", "moduli", "times", "nu", "shift"}
    m2, s2, kind = io.load_material(p)
    assert kind == "E" and type(s2) is type(shift)
    np.testing.assert_allclose(np.asarray(m2.moduli), np.asarray(mat.moduli), rtol=1e-15)
    np.testing.assert_allclose(np.asarray(m2.times), np.asarray(mat.times), rtol=1e-15)
    assert float(m2.E0) == float(mat.E0) and float(m2.nu) == 0.5
    T = np.array([0.0, 10.0, 40.0])
    np.testing.assert_allclose(np.asarray(s2.log10_aT(T)), np.asarray(shift.log10_aT(T)), rtol=1e-14)
    assert os.listdir(tmp_path) == ["m.json"]  # no temporary files left
    if isinstance(shift, WLF):
        assert d["shift"] == {"law": "WLF", "C1": 8.86, "C2": 101.6, "T_ref": 25.0}


def test_json_errors(tmp_path):
    p = tmp_path / "bad.json"
    p.write_text('{"kind": "prony", "E0": 1.0')
    with pytest.raises(ValueError, match="bad.json, line 1: invalid JSON"):
        io.load_material(p)
    p.write_text(json.dumps({"kind": "prony", "E0": 1.0, "moduli": [1.0], "times": [1.0], "nu": 0.5,
                             "shift": {"law": "VFT", "T_ref": 0}}))
    with pytest.raises(ValueError, match="unknown shift law 'VFT'"):
        io.load_material(p)
    p.write_text(json.dumps({"kind": "prony", "E0": 1.0, "moduli": [-1.0], "times": [1.0], "nu": 0.5,
                             "shift": {"law": "WLF", "C1": 1, "C2": 1, "T_ref": 0}}))
    with pytest.raises(ValueError, match="moduli must be > 0"):
        io.load_material(p)


def test_cli_success_and_failures(tmp_path, capsys):
    path, _, _, _ = _synthetic(tmp_path)
    out = tmp_path / "mat.json"
    assert cli.main([path, "--tref", "30", "--out", str(out), "--law", "WLF"]) == 0
    text = capsys.readouterr().out
    assert "Prony terms" in text and "storage" in text and "C1=" in text
    m, s, kind = io.load_material(out)
    assert isinstance(s, WLF) and kind == "E"
    for suffix in ("master", "shift", "residuals", "spectrum"):
        assert (tmp_path / f"mat_{suffix}.png").stat().st_size > 1000
    # failure: bad file -> exit 1, message on stderr, existing output untouched, no temp files
    before = out.read_bytes()
    bad = tmp_path / "bad.csv"
    bad.write_text("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,nan,4\n")
    assert cli.main([str(bad), "--tref", "30", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "bad.csv, line 2: loss modulus is NaN" in err
    assert out.read_bytes() == before
    assert not [n for n in os.listdir(tmp_path) if n.endswith(".tmp")]
    # failure: single temperature, and a missing output directory
    one = tmp_path / "one.csv"
    one.write_text("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,3,4,4\n")
    assert cli.main([str(one), "--tref", "4", "--out", str(tmp_path / "x.json")]) == 1
    assert "two or more temperatures" in capsys.readouterr().err and not (tmp_path / "x.json").exists()
    assert cli.main([path, "--tref", "30", "--out", str(tmp_path / "no" / "x.json")]) == 1
    # usage error: argparse exits with 2
    with pytest.raises(SystemExit) as e:
        cli.main([path, "--out", str(out)])
    assert e.value.code == 2
