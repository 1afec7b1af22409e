"""Calibration plots (fitting.calibration.plots): each writes a PNG, draws what it claims (checked on
synthetic data lying exactly on the model) and refuses bad input with a clear message."""
import types

import numpy as np
import pytest

from fitting.measurements import dma
from fitting.calibration import figures, master, plots
from vjax.material import Material, WLF

MAT = Material.prony(2e6, np.array([8e8, 2e8, 5e7, 1e7]), np.array([1e-6, 1e-4, 1e-2, 1.0]), 0.5)
LAW = WLF(9.0, 110.0, 30.0)
FREQS = np.array([0.1, 1.0, 10.0, 100.0])
TEMPS = np.arange(-10.0, 71.0, 10.0)


@pytest.fixture(scope="module")
def data():
    """DMA sweeps computed from MAT and LAW (exact model data)."""
    T, f = np.meshgrid(TEMPS, FREQS, indexing="ij")
    E = np.asarray(MAT.modulus(2 * np.pi * f.ravel() * 10.0 ** np.asarray(LAW.log10_aT(T.ravel()))))
    table = dma.from_arrays(T.ravel(), f.ravel(), E.real, E.imag)
    shifts = master.ShiftTable.make(TEMPS, np.asarray(LAW.log10_aT(TEMPS)), 30.0)
    return table, shifts


def _is_png(path):
    with open(path, "rb") as fh:
        return fh.read(8) == b"\x89PNG\r\n\x1a\n"


def test_save_all_writes_every_plot(tmp_path, data):
    table, shifts = data
    paths = figures.save_all(str(tmp_path), "m", table, MAT, LAW, shifts)
    assert [p.rsplit("_", 1)[1] for p in paths] == ["master.png", "shift.png", "residuals.png", "spectrum.png",
                                                    "tsweep.png", "vgp.png"]
    assert all(_is_png(p) for p in paths)


def test_worker_processes_draw_the_same_files_and_raise_the_same_errors(tmp_path, data, monkeypatch):
    """Figures drawn by the forked workers (what vjax-fit does) are byte for byte those drawn
    in this process, and a plot's error (bad input) reaches the caller as itself."""
    table, shifts = data
    here = figures.save_all(str(tmp_path), "here", table, MAT, LAW, shifts)
    monkeypatch.setattr(figures, "_context", figures._context)     # restored after the test
    # the suite's workers are pinned to a core each (conftest.py): the path is what is tested here
    monkeypatch.setattr(figures, "_cores", lambda: 2)
    if not figures.start_workers():
        pytest.skip("no fork server on this machine")
    there = figures.save_all(str(tmp_path), "there", table, MAT, LAW, shifts)
    for a, b in zip(here, there):
        with open(a, "rb") as fa, open(b, "rb") as fb:
            assert fa.read() == fb.read(), b
    bad = master.ShiftTable(TEMPS, np.full(TEMPS.shape, np.nan), 30.0)     # past make's checks
    with pytest.raises(ValueError, match="data_shift must hold finite"):
        figures.save_all(str(tmp_path), "bad", table, MAT, LAW, bad)


def test_temperature_sweep_passes_through_the_data(data):
    """The fit lines at 1 and 10 Hz, read off the figure at the measured temperatures, equal
    the (exact) data: the sweep is rebuilt with a_T in the right direction."""
    table, _ = data
    fig = plots.temperature_sweep(table, MAT, LAW, frequencies=(1.0, 10.0))
    for j, f in enumerate((1.0, 10.0)):
        m = table.f == f
        for ax, y in zip(fig.axes, (table.storage[m], table.loss[m], table.loss[m] / table.storage[m])):
            line = ax.get_lines()[2 * j]
            assert line.get_label() == f"fit, {f:g} Hz"
            x, v = line.get_xdata(), line.get_ydata()
            np.testing.assert_allclose(np.exp(np.interp(table.T[m], x, np.log(v))), y, rtol=2e-3)
        assert len(fig.axes[0].get_lines()[2 * j + 1].get_xdata()) == len(TEMPS)   # data at that frequency


def test_van_gurp_palmen_curve_through_the_data(data):
    table, _ = data
    fig = plots.van_gurp_palmen(table, MAT, LAW)
    line = fig.axes[0].get_lines()[0]
    mag, delta = line.get_xdata(), line.get_ydata()
    o = np.argsort(mag)
    d_data = np.degrees(np.arctan2(table.loss, table.storage))
    np.testing.assert_allclose(np.interp(np.hypot(table.storage, table.loss), mag[o], delta[o]), d_data, atol=0.05)


def test_shift_plot_names_the_material_law(data):
    _, shifts = data
    fig = plots.shift_factors(shifts, LAW)
    labels = [l.get_label() for l in fig.axes[0].get_lines()]
    assert any(l.startswith("WLF") and "the material's law" in l for l in labels)
    assert any(l.startswith("Arrhenius") and "fitted to the table" in l for l in labels)
    assert "the material uses: WLF" in fig.axes[0].get_title()
    fig = plots.shift_factors(shifts, shifts)        # a table law: both closed forms fitted
    labels = [l.get_label() for l in fig.axes[0].get_lines()]
    assert sum("fitted to the table" in l for l in labels) == 2 and "table (the material's law)" in labels


def test_bad_input_is_refused(data):
    table, _ = data
    for bad in ((), (-1.0,), (float("nan"),), [[1.0, 2.0]]):
        with pytest.raises(ValueError, match="frequencies must be"):
            plots.temperature_sweep(table, MAT, LAW, frequencies=bad)
    empty = table.subset(np.zeros(len(table), bool))
    for fn in (plots.temperature_sweep, plots.van_gurp_palmen):
        with pytest.raises(ValueError, match="no points"):
            fn(empty, MAT, LAW)
    with pytest.raises(ValueError, match="finite per-sweep shift factors"):
        plots.shift_factors(types.SimpleNamespace(T=[], values=[], T_ref=30.0), LAW)
    with pytest.raises(ValueError, match="undefined over the data's temperatures"):
        plots.temperature_sweep(table, MAT, WLF(9.0, 5.0, 100.0))     # asymptote above every T
