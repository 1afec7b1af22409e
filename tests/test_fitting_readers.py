"""Readers of fitting.dma on every shipped format and on broken files."""
import os

import numpy as np
import pytest

from fitting import dma, master

TRIOS = os.path.join(os.path.dirname(__file__), "..", "..", "shared", "data", "dma", "rheojax_TA_3M468MP_tts",
                     "frequency_sweep_tts.txt")


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


@pytest.mark.skipif(not os.path.exists(TRIOS), reason="TRIOS sample (not redistributable) is absent")
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
