"""Readers of fitting.measurements.dma on every shipped format and on broken files."""
import os

import numpy as np
import pytest

from fitting.measurements import dma
from fitting.calibration import master

# a TA Instruments TRIOS export whose redistribution is not cleared: not shipped; point
# VJAX_TRIOS_SAMPLE at a copy (e.g. rheojax's examples/data/temperature_sweep/polymers/
# frequency_sweep_tts.txt) to run the tests that read it
TRIOS = os.environ.get("VJAX_TRIOS_SAMPLE", "")


def test_pyvisco_csv():
    t = dma.read(dma.default_data("pyvisco"))
    assert t.kind == "E" and len(t) == 210 and t.n_sets == 21
    # first data row of the file: 0.1 Hz, 8097.175545 MPa, 93.07449045 MPa, -49.9612 C
    i = np.flatnonzero(t.source == t.source[0])[0]
    assert t.f[i] == pytest.approx(0.1) and t.omega[i] == pytest.approx(0.2 * np.pi)
    assert t.storage[i] == pytest.approx(8097.175545e6) and t.loss[i] == pytest.approx(93.07449045e6)
    assert t.T_measured[i] == pytest.approx(-49.9612)
    assert t.temperatures[0] == pytest.approx(-49.9, abs=0.1) and t.temperatures[-1] == pytest.approx(100, abs=0.1)
    assert t.source[i].endswith("freq_user_raw.csv:3")


def test_whitespace_export_one_file_per_temperature():
    t = dma.read(dma.default_data("dmasuite"))
    assert t.kind == "E" and t.n_sets == 22 and len(t) == 22 * 60
    assert list(t.temperatures) == list(np.arange(0.0, 106.0, 5.0))  # from the file names
    m = t.T == 0.0
    # T0.txt line 3: f 9.99999e-02 Hz, E' 2.93911e+03 MPa, E" 5.45177e+01 MPa, Ts -5.91320e-01 C
    assert t.f[m][0] == pytest.approx(0.0999999) and t.storage[m][0] == pytest.approx(2.93911e9)
    assert t.loss[m][0] == pytest.approx(5.45177e7) and t.T_measured[m][0] == pytest.approx(-0.59132)


@pytest.mark.skipif(not os.path.isfile(TRIOS), reason="VJAX_TRIOS_SAMPLE (a TRIOS export, not shipped) is not set")
def test_trios_export():
    with pytest.raises(dma.DMAFormatError, match=r"line 538: non-positive modulus"):
        dma.read(TRIOS)
    t = dma.read(TRIOS, drop_nonpositive=True)
    assert t.kind == "G" and t.n_sets == 20 and t.dropped == 1 and len(t) == 20 * 17 - 1
    assert t.temperatures[0] == -40 and t.temperatures[-1] == 150
    m = t.T == 150
    # first point of the 150 C step: 0.628318548 rad/s (0.1 Hz)
    assert t.omega[m].min() == pytest.approx(0.628318548202515, rel=1e-6)


def _write(path, text, encoding="utf-8"):
    path.write_text(text, encoding=encoding)
    return str(path)


def _tidy_rows(T, f, Es, El):
    return "".join(f"{a},{b},{c},{d}\n" for a, b, c, d in zip(T, f, Es, El))


def test_tidy_csv_units_in_headers(tmp_path):
    T = [20] * 3 + [40] * 3
    w = [1.0, 10.0, 100.0] * 2
    p = _write(tmp_path / "tidy.csv", "T [C],omega [rad/s],G' [kPa],G'' (kPa)\n" + _tidy_rows(T, w, [1, 2, 3, 4, 5, 6],
                                                                                                  [7, 8, 9, 1, 2, 3]))
    t = dma.read(p)
    assert t.kind == "G" and t.n_sets == 2
    assert t.f[0] == pytest.approx(1 / (2 * np.pi)) and t.storage[0] == 1e3 and t.loss[-1] == 3e3
    # Kelvin and Hz
    p = _write(tmp_path / "tidyK.csv", "T [K],f [Hz],E' [GPa],E'' [GPa]\n" + _tidy_rows([300, 300], [1, 2], [1, 1], [1, 1]))
    t = dma.read(p)
    assert t.T_measured[0] == pytest.approx(26.85) and t.T[0] == pytest.approx(26.9) and t.storage[0] == 1e9 and t.kind == "E"


def test_one_file_per_temperature_names(tmp_path):
    for T in (-20, 0, 35.5):
        _write(tmp_path / f"sweep_{T}C.csv", "f [Hz],E' [MPa],E'' [MPa]\n1,10,1\n10,20,2\n")
    t = dma.read(str(tmp_path))
    assert list(t.temperatures) == [-20, 0, 35.5]
    assert dma.temperature_from_filename("T85.txt") == 85 and dma.temperature_from_filename("T-20.csv") == -20
    assert dma.temperature_from_filename("data.csv") is None


BROKEN = {
    "missing_column.csv": ("f [Hz],E' [MPa],T [C]\n1,2,3\n", r"line 1: missing column\(s\): loss modulus"),
    "missing_unit.csv": ("f [Hz],E',E'' [MPa],T [C]\n1,2,3,4\n", r"line 1: column \"E'\" has no unit"),
    "unknown_unit.csv": ("f [Hz],E' [bar],E'' [MPa],T [C]\n1,2,3,4\n", r"unknown modulus unit 'bar'"),
    "unknown_freq.csv": ("f [rpm],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n", r"unknown frequency unit 'rpm'"),
    "nan.csv": ("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,nan,3,4\n", r"line 3: storage modulus is NaN"),
    "text.csv": ("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,abc,3,4\n", r"line 3: not a number: 'abc'"),
    "short.csv": ("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,3,4\n", r"line 3: expected 4 values, found 3"),
    "negative.csv": ("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,3,-4,4\n", r"line 3: non-positive modulus"),
    "duplicate.csv": ("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n1,3,4,4\n", r"line 3: duplicated point"),
    "nonmono.csv": ("f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n3,3,4,4\n2,3,4,4\n",
                    r"line 4: frequency not monotonic"),
    "noT.csv": ("f [Hz],E' [MPa],E'' [MPa]\n1,2,3\n", r"no temperature"),
    "empty.csv": ("", r"file is empty"),
    "nounits.txt": ("f E' E''\n1 2 3\n", r"line 2: missing unit row"),
    "mixed.csv": ("f [Hz],E' [MPa],G'' [MPa],T [C]\n1,2,3,4\n", r"mix tensile \(E\) and shear \(G\)"),
}


@pytest.mark.parametrize("name", sorted(BROKEN))
def test_broken_files_name_file_line_problem(tmp_path, name):
    text, pattern = BROKEN[name]
    p = _write(tmp_path / name, text)
    with pytest.raises(ValueError, match=pattern) as e:
        dma.read(p)
    assert name in str(e.value)


def test_drop_nonpositive_counts(tmp_path):
    p = _write(tmp_path / "neg.csv", "f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,3,-4,4\n3,0,4,4\n4,5,6,4\n")
    t = dma.read(p, drop_nonpositive=True)
    assert len(t) == 2 and t.dropped == 2 and "2 non-positive points dropped" in t.summary()


def test_missing_file_and_single_temperature(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        dma.read(str(tmp_path / "nope.csv"))
    p = _write(tmp_path / "one.csv", "f [Hz],E' [MPa],E'' [MPa],T [C]\n1,2,3,4\n2,3,4,4\n")
    with pytest.raises(ValueError, match="two or more temperatures"):
        master.shift_factors(dma.read(p), 4.0)


def test_pyvisco_header_with_shear_and_latin1(tmp_path):
    p = _write(tmp_path / "g.csv", "f,G_stor,G_loss,T,Set\nHz,GPa,GPa,°C,-\n1,1,0.1,20,0\n2,1.1,0.1,20,0\n"
                                   "1,0.5,0.1,40,1\n2,0.6,0.1,40,1\n", encoding="latin-1")
    t = dma.read(p)
    assert t.kind == "G" and t.n_sets == 2 and t.storage[0] == 1e9


# ---- Netzsch Eplexor .xls exports (fitting.measurements.eplexor) ------------------------------------------
PV = os.path.dirname(dma.default_data("pyvisco"))


def test_eplexor_raw_xls_equals_the_csv_export():
    """freq_Eplexor_raw.xls and freq_user_raw.csv hold the same experiment: same table to the
    CSV's rounding (10 significant digits)."""
    x = dma.read(os.path.join(PV, "freq_Eplexor_raw.xls"))
    c = dma.read(dma.default_data("pyvisco"))
    assert x.kind == c.kind == "E" and len(x) == len(c) == 210 and x.n_sets == c.n_sets == 21
    for k in ("T", "set"):
        np.testing.assert_array_equal(getattr(x, k), getattr(c, k))
    for k in ("f", "T_measured", "storage", "loss"):
        np.testing.assert_allclose(getattr(x, k), getattr(c, k), rtol=1e-9, err_msg=k)
    assert x.source[0].endswith("freq_Eplexor_raw.xls:3")


@pytest.mark.parametrize("name, kind, T_ref, C1, C2, n_sets",
                         [("freq_Eplexor_master.xls", "E", 25.0, 13.50, 141.19, 21),
                          ("freq_Eplexor_master_shear.xls", "G", -30.0, 727.24, 2299.50, 19)])
def test_eplexor_master_xls_rebuilds_the_sweeps(name, kind, T_ref, C1, C2, n_sets):
    """A master-curve file becomes sweeps again: each on the measured grid 0.1..100 Hz (3 per
    decade, from the file's Data header), at a shift-list temperature; shifting them back with
    the shift list gives the file's reduced frequencies."""
    import xlrd
    from fitting.measurements import eplexor
    path = os.path.join(PV, name)
    t = dma.read(path)
    assert t.kind == kind and t.n_sets == n_sets
    grid = np.linspace(-1, 2, 10)
    lf = np.log10(t.f)
    assert np.max(np.min(np.abs(lf[:, None] - grid), axis=1)) < 1e-6
    T, a, Tr, wlf = eplexor.shift_list(path)
    assert Tr == T_ref and wlf == {"C1": C1, "C2": C2}
    assert set(np.round(t.T_measured, 6)) <= set(np.round(T, 6))
    shift = dict(zip(np.round(T, 6), a))
    reduced = t.f * 10.0 ** np.array([shift[v] for v in np.round(t.T_measured, 6)])
    sheet = xlrd.open_workbook(path).sheet_by_name("Exported Data")
    f_file = np.array(sheet.col_values(sheet.row_values(0).index("f"))[2:], float)
    np.testing.assert_allclose(np.sort(reduced), np.sort(f_file), rtol=1e-12)
    for s in range(t.n_sets):                    # a sweep: one temperature, increasing frequency
        m = t.set == s
        assert len(set(t.T[m])) == 1 and np.all(np.diff(t.f[m]) > 0)


def test_other_binary_files_are_refused_clearly(tmp_path, monkeypatch):
    blob = tmp_path / "sweep.xlsx"
    blob.write_bytes(b"PK\x03\x04" + bytes(range(256)) * 4)
    with pytest.raises(dma.DMAFormatError, match="binary file.*save it as CSV"):
        dma.read(str(blob))
    png = tmp_path / "T20.dat"
    png.write_bytes(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR")
    with pytest.raises(dma.DMAFormatError, match="T20.dat: binary file"):
        dma.read(str(png))
    bad = tmp_path / "broken.xls"
    bad.write_bytes(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + b"\0" * 600)
    with pytest.raises(dma.DMAFormatError, match="broken.xls: not a readable Excel .xls file"):
        dma.read(str(bad))
    monkeypatch.setitem(__import__("sys").modules, "xlrd", None)
    with pytest.raises(dma.DMAFormatError, match="pip install xlrd"):
        dma.read(os.path.join(PV, "freq_Eplexor_raw.xls"))
