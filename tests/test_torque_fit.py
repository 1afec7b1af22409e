"""fitting.torque: CSV reader errors, loss gradient vs finite differences, a tiny recovery."""
import numpy as np
import pytest

from fitting import torque as ft
from vjax import Material, WLF

GOOD = "# a comment\nspeed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m,scatter_Nm_per_m\n" \
       "100,40,1000,0.5,0.02\n200,40,1000,0.4,0.02\n100,60,1000,0.3,0.01\n"


def _write(tmp_path, text, name="t.csv"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_reader_roundtrip(tmp_path):
    d = ft.read_torque_csv(_write(tmp_path, GOOD))
    assert len(d) == 3 and d.scatter is not None
    np.testing.assert_allclose(d.omega, d.rpm * 2 * np.pi / 60)
    assert d.conditions() == [(40.0, 1000.0), (60.0, 1000.0)]
    ft.write_torque_csv(tmp_path / "w.csv", d, comments=["x"])
    e = ft.read_torque_csv(tmp_path / "w.csv")
    for k in ("rpm", "T", "load", "torque", "scatter"):
        np.testing.assert_array_equal(getattr(d, k), getattr(e, k))
    # aliases, units in brackets, no scatter column: sigma falls back to 5%
    f = ft.read_torque_csv(_write(tmp_path, "RPM, T [C], F, Torque\n10,20,5,2\n", "a.csv"))
    assert f.scatter is None and f.sigma()[0] == pytest.approx(0.1)


@pytest.mark.parametrize("text,match", [
    ("", "empty file"),
    ("# only a comment\n", "empty file"),
    ("speed_rpm,temperature_C,torque_Nm_per_m\n1,2,3\n", r"missing column\(s\) \['load_N_per_m'\]"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n", "no data rows"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n100,40,abc,1\n", "line 2.*not a number"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n100,40,1000,nan\n", "not finite"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n-5,40,1000,1\n", "must be > 0"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n5,40,0,1\n", "must be > 0"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m,sigma\n5,40,1,1,0\n", "must be > 0"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n5,40,1\n", "expected 4 values"),
    ("rpm,speed,temperature_C,load_N_per_m,torque_Nm_per_m\n5,5,40,1,1\n", "two columns"),
    ("speed_rpm,temperature_C,load_N_per_m,torque_Nm_per_m\n5,40,1,1\n5,40,1,2\n", "repeated speed"),
])
def test_reader_errors(tmp_path, text, match):
    with pytest.raises(ft.TorqueFormatError, match=match):
        ft.read_torque_csv(_write(tmp_path, text))


def test_reader_missing_file(tmp_path):
    with pytest.raises(ft.TorqueFormatError, match="cannot read"):
        ft.read_torque_csv(tmp_path / "nope.csv")


def test_params_roundtrip_and_wlf_only():
    m = Material.prony(1e6, [2e6, 3e6], [1e-3, 1e-1], 0.5)
    sh = WLF(10.0, 100.0, 25.0)
    P = ft.Params.of(m, sh, fit_times=True)
    x = P.pack(m, sh)
    assert P.names() == ["E0", "E_1", "E_2", "tau_1", "tau_2", "C1", "C2"]
    m2, sh2 = P.physical(x)
    np.testing.assert_allclose(np.asarray(m2.moduli), [2e6, 3e6])
    np.testing.assert_allclose(np.asarray(m2.times), [1e-3, 1e-1])
    assert float(sh2.C2) == pytest.approx(100.0)
    from vjax import Arrhenius
    with pytest.raises(ValueError, match="WLF"):
        ft.Params.of(m, Arrhenius(1e5, 25.0))


# a small pin-joint problem shared by the next two tests (compiled once per residual function)
TRUE = Material.prony(1e6, [3e6, 4e6, 2e6], [1e-4, 1e-3, 1e-2], 0.5)
SHIFT = WLF(8.0, 100.0, 25.0)
MODEL = ft.pin_model(R=0.01, radial_clearance=1e-4, n=32)


def _data():
    import jax
    rpm = np.tile([30.0, 100.0, 300.0], 2)
    T = np.repeat([30.0, 50.0], 3)
    load = np.full(6, 1e-2 * 1e6 * 0.01)
    tq, ok = jax.vmap(lambda a, b, c: MODEL(TRUE, SHIFT, a, b, c))(rpm, T, load)
    assert bool(np.all(ok))
    return ft.TorqueData(rpm, T, load, np.asarray(tq))


def test_gradient_matches_finite_differences():
    data = _data()
    P = ft.Params.of(TRUE, SHIFT, fit_times=True)
    x = P.pack(TRUE, SHIFT) + np.linspace(-0.2, 0.2, len(P.names()))
    rows = ft.gradient_check(P, MODEL, data, x, h=1e-5)
    for what, an, fd, rel in rows:
        assert np.isfinite(an)
        assert rel < 1e-5, (what, an, fd)


def test_tiny_recovery():
    data = _data()
    start = Material.prony(1.3e6, [2.2e6, 5.2e6, 1.5e6], [1e-4, 1e-3, 1e-2], 0.5)
    sh0 = WLF(10.0, 80.0, 25.0)
    fit = ft.fit_torque(data, start, sh0, MODEL, steps=150, lr=0.05, lr_end=0.005, progress=False)
    assert fit.converged
    assert fit.loss < 0.02 * fit.loss0
    # the combinations the torque identifies move toward the truth
    P = fit.params
    xt = P.pack(TRUE, SHIFT)
    V = np.asarray(fit.ident["identified_basis"]).reshape(-1, len(fit.names))
    assert len(V) >= 1
    assert np.linalg.norm(V @ (fit.x - xt)) < 0.5 * np.linalg.norm(V @ (fit.x0 - xt))
    rows = fit.table(truth=xt)
    assert [r[0] for r in rows] == fit.names and len(rows[0]) == 7


def test_levenberg_marquardt_polish_beats_adam_alone():
    """Noise-free data: after the same Adam steps the LM polish drives the loss far lower
    (Adam alone crawls along the valley), and never raises it."""
    data = _data()
    start = Material.prony(1.3e6, [2.2e6, 5.2e6, 1.5e6], [1e-4, 1e-3, 1e-2], 0.5)
    sh0 = WLF(10.0, 80.0, 25.0)
    kw = dict(steps=40, lr=0.05, lr_end=0.005, progress=False)
    adam = ft.fit_torque(data, start, sh0, MODEL, polish=0, **kw)
    both = ft.fit_torque(data, start, sh0, MODEL, polish=20, **kw)
    assert both.converged and adam.converged
    assert both.loss < 1e-2 * adam.loss
    losses = [h[1] for h in both.history[len(adam.history):]]      # the LM rows: accepted steps only
    assert losses and all(b < a for a, b in zip([adam.loss] + losses, losses))
