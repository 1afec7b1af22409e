"""The calibration figures of fitting.calibration.plots (what vjax-fit and the main job's calibration stage
draw) pass the layout checker of experiments/figures/layout.py, as saved: on exact model data
(fast) and on the calibration of the shipped pyvisco DMA data (slow)."""
import types

import numpy as np
import pytest

from experiments.figures import layout
from fitting.measurements import dma
from fitting.calibration import figures
from fitting.shared import files
from fitting.calibration import master, plots
from fitting.measurements import relaxation
from vjax.material import WLF, Material

MAT = Material.prony(2e6, np.array([8e8, 2e8, 5e7, 1e7]), np.array([1e-6, 1e-4, 1e-2, 1.0]), 0.5)
LAW = WLF(9.0, 110.0, 30.0)
TEMPS = np.arange(-10.0, 71.0, 10.0)


@pytest.fixture
def checked(monkeypatch):
    """fitting.shared.files.save_figure through the layout checker: {path: problems} of every figure saved."""
    found = {}

    def save(fig, path, dpi=150, **savefig_kw):
        data, found[str(path)] = layout.render(fig, str(path).rsplit(".", 1)[-1], dpi=dpi, **savefig_kw)
        return files.write_atomic(path, data)

    monkeypatch.setattr(files, "save_figure", save)
    return found


def _table():
    T, f = np.meshgrid(TEMPS, np.array([0.1, 1.0, 10.0, 100.0]), indexing="ij")
    E = np.asarray(MAT.modulus(2 * np.pi * f.ravel() * 10.0 ** np.asarray(LAW.log10_aT(T.ravel()))))
    return dma.from_arrays(T.ravel(), f.ravel(), E.real, E.imag)


def test_calibration_and_torque_figures_pass_the_layout_rules(tmp_path, checked):
    table = _table()
    shifts = master.ShiftTable.make(TEMPS, np.asarray(LAW.log10_aT(TEMPS)), 30.0)
    paths = figures.save_all(str(tmp_path), "m", table, MAT, LAW, shifts)      # in this process: no workers started
    t = np.tile(np.logspace(-2, 2, 9), len(TEMPS))
    T = np.repeat(TEMPS, 9)
    E = np.asarray(MAT.relaxation(t / 10.0 ** np.asarray(LAW.log10_aT(T))))
    rtable = relaxation.RelaxationTable(T=T, t=t, modulus=E, set=np.repeat(np.arange(len(TEMPS)), 9), kind="E")
    paths.append(plots.relaxation_curve(rtable, MAT, LAW, str(tmp_path / "r_master.png")))
    rpm = np.tile(np.geomspace(1.0, 3000.0, 6), 4)
    data = types.SimpleNamespace(T=np.repeat([30.0, 30.0, 50.0, 50.0], 6), load=np.tile(np.repeat([50.0, 100.0], 6), 2),
                                 rpm=rpm, torque=1e-2 * rpm ** 0.3)
    fit = types.SimpleNamespace(torque0=1.2 * data.torque, torque=data.torque)
    paths.append(plots.torque_fit(data, {"gradient": fit, "random search": fit}, 0.05 * data.torque,
                                  str(tmp_path / "t_torque.png"), truth=data.torque))
    paths.append(plots.moduli([(MAT, "start", "k:"), (MAT, "fitted", "C0-")], str(tmp_path / "t_moduli.png"),
                              bands=((1e-2, 1e2),)))
    assert sorted(checked) == sorted(map(str, paths)) and len(paths) == 9
    assert {p: v for p, v in checked.items() if v} == {}


@pytest.mark.slow     # ~10 s: the shipped data's calibration compiles its fit
def test_the_shipped_calibration_figures_pass_the_layout_rules(tmp_path, checked):
    from fitting import calibrate
    calibrate(dma.default_data("pyvisco"), 25.0, str(tmp_path), stem="material", max_iter=60)
    assert len(checked) == 6
    assert {p: v for p, v in checked.items() if v} == {}
