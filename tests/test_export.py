"""FEM exports (fitting.export, vjax-export, vjax-fit --export): every file is read back by an
independent parser written here from each code's documented formulas, and the rebuilt shear
relaxation modulus, bulk modulus and shift function are compared with the fitted material
(vjax.Material.relaxation, the vjax shift law) to 1e-9 relative."""
import json
import math
import os
import re

import numpy as np
import pytest

from fitting import export, export_cli
from fitting import cli as fit_cli
from fitting.dma import default_data
from vjax.material import Arrhenius, Material, WLF

R = 8.314462618
TOL = 1e-9
UNIT_SCALE = {"SI": 1.0, "mm-N-s-MPa": 1e6}        # output stress unit -> Pa


# ---- independent readers: each returns G(t) [Pa], K [Pa], log10 a_T(T in C) ---------------
def _floats(line):
    return [float(v) for v in line.replace(",", " ").split()]


def read_abaqus(path, to_pa):
    """*ELASTIC instantaneous E, nu; *VISCOELASTIC g_i, k_i, tau_i with
    g_R(t) = 1 - sum g_i (1 - exp(-t/tau_i)); *TRS WLF log10 A = -C1 (th - th0)/(C2 + th - th0)
    or ARRHENIUS ln A = (E0/R)(1/(th - thZ) - 1/(th0 - thZ))."""
    blocks, key, consts = {}, None, {}
    for raw in open(path).read().splitlines():
        line = raw.strip()
        if line.startswith("** *PHYSICAL CONSTANTS"):
            consts = {k.strip().upper(): float(v) for k, v in re.findall(r"([A-Z ]+)=([-+0-9.eE]+)", line[3:])}
            continue
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            key = line.upper().replace(" ", "")
            blocks[key] = []
        else:
            blocks[key].append(_floats(line))
    (E, nu), = blocks["*ELASTIC,MODULI=INSTANTANEOUS"]
    G0, K0 = E / (2 * (1 + nu)) * to_pa, E / (3 * (1 - 2 * nu)) * to_pa
    gkt = np.array(blocks["*VISCOELASTIC,TIME=PRONY"])
    g, k, tau = gkt.T
    assert np.all(k == 0)
    G = lambda t: G0 * (1 - np.sum(g * (1 - np.exp(-np.asarray(t)[:, None] / tau)), axis=1))
    if "*TRS,DEFINITION=WLF" in blocks:
        (th0, C1, C2), = blocks["*TRS,DEFINITION=WLF"]
        return G, K0, lambda Tc, th0=th0, C1=C1, C2=C2: _wlf(Tc, th0, C1, C2, path)
    (th0, E0), = blocks["*TRS,DEFINITION=ARRHENIUS"]
    thZ, Rg = consts["ABSOLUTE ZERO"], consts["UNIVERSAL GAS CONSTANT"]
    return G, K0, lambda Tc: (E0 / Rg) * (1 / (_in_file_T(Tc, path) - thZ) - 1 / (th0 - thZ)) / math.log(10)


def _in_file_T(Tc, path):
    """Temperatures of the test (C) in the file's unit (its header says which)."""
    unit = re.search(r"temperature (K|C)", open(path).read()).group(1)
    return np.asarray(Tc) + (273.15 if unit == "K" else 0.0)


def _wlf(Tc, Tr, C1, C2, path):
    d = _in_file_T(Tc, path) - Tr
    return -C1 * d / (C2 + d)


def read_ansys(path, to_pa):
    """MP,EX/NUXY instantaneous; TB,PRONY SHEAR pairs a_i, tau_i with
    G(t) = G0 (a_inf + sum a_i exp(-t/tau_i)), a_inf = 1 - sum a_i; TB,SHIFT WLF (Tr, C1, C2)
    or TN (Tr, H/R, nf = 0: ln a_T = H/R (1/T - 1/Tr), absolute T = T + TOFFST)."""
    mp, tables, cur, toff = {}, {}, None, 0.0
    for raw in open(path).read().splitlines():
        f = [s.strip() for s in raw.split("!")[0].split(",")]
        if not f[0]:
            continue
        cmd = f[0].upper()
        if cmd == "MP":
            mp[f[1].upper()] = float(f[3])
        elif cmd == "TB":
            cur = (f[1].upper(), f[5].upper())
            tables[cur] = {}
        elif cmd == "TBDATA":
            for i, v in enumerate(f[2:]):
                tables[cur][int(f[1]) + i] = float(v)
        elif cmd == "TOFFST":
            toff = float(f[1])
    E, nu = mp["EX"], mp["NUXY"]
    G0, K0 = E / (2 * (1 + nu)) * to_pa, E / (3 * (1 - 2 * nu)) * to_pa
    p = tables[("PRONY", "SHEAR")]
    vals = np.array([p[i] for i in sorted(p)])
    a, tau = vals[0::2], vals[1::2]
    G = lambda t: G0 * (1 - a.sum() + np.sum(a * np.exp(-np.asarray(t)[:, None] / tau), axis=1))
    if ("SHIFT", "WLF") in tables:
        s = tables[("SHIFT", "WLF")]
        return G, K0, lambda Tc: _wlf(Tc, s[1], s[2], s[3], path)
    s = tables[("SHIFT", "TN")]
    assert s[3] == 0
    return G, K0, lambda Tc: s[2] * (1 / (_in_file_T(Tc, path) + toff) - 1 / (s[1] + toff)) / math.log(10)


def read_lsdyna(path, to_pa):
    """*MAT_GENERAL_VISCOELASTIC long format (20-character fields): card 1 MID, RO, BULK, PCF,
    EF, TREF, A, B; card 2 LCID...; then GI, BETAI, KI, BETAKI per term:
    G(t) = sum GI exp(-BETAI t); log10 a_T = -A (T - TREF) / (B + T - TREF)."""
    lines = open(path).read().splitlines()
    i = next(j for j, l in enumerate(lines) if l.startswith("*MAT_GENERAL_VISCOELASTIC"))
    assert lines[i].rstrip().endswith("+")
    cards = []
    for l in lines[i + 1:]:
        if l.startswith("*"):
            break
        if l.startswith("$"):
            continue
        cards.append([float(l[j:j + 20]) if l[j:j + 20].strip() else 0.0 for j in range(0, len(l), 20)])
    c1, c2, terms = cards[0], cards[1], np.array(cards[2:])
    K, TREF, A, B = c1[2] * to_pa, c1[5], c1[6], c1[7]
    assert c2[0] == 0 and np.all(terms[:, 2] == 0)
    G = lambda t: to_pa * np.sum(terms[:, 0] * np.exp(-np.asarray(t)[:, None] * terms[:, 1]), axis=1)
    return G, K, lambda Tc: _wlf(Tc, TREF, A, B, path)


_COMSOL_UNITS = {"Pa": 1.0, "MPa": 1e6, "s": 1.0, "K": 1.0, "J/mol": 1.0, "mJ/mol": 1e-3, "": 1.0}


def read_comsol(path_params, path_branches, to_pa):
    """name value[unit] "description" lines (units converted to SI here, temperatures to K)
    and the branch file (number, G_i, tau_i). G(t) = G_inf + sum G_i exp(-t/tau_i); WLF
    log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref) or Arrhenius ln a_T = Q/R (1/T - 1/T_ref)."""
    p = {}
    for line in open(path_params).read().splitlines():
        m = re.match(r'^(\w+) ([-+0-9.eE]+)(?:\[([^\]]*)\])? "', line)
        if m:
            v, u = float(m.group(2)), m.group(3) or ""
            p[m.group(1)] = v + 273.15 if u == "degC" else v * _COMSOL_UNITS[u]
    n = sum(1 for k in p if k.startswith("G_") and k != "G_inf")
    Gi = np.array([p[f"G_{i}"] for i in range(1, n + 1)])
    tau = np.array([p[f"tau_{i}"] for i in range(1, n + 1)])
    br = np.loadtxt(path_branches, ndmin=2)
    np.testing.assert_array_equal(br[:, 0], np.arange(1, n + 1))
    scale = 1e6 if "[MPa]" in open(path_params).read() else 1.0
    np.testing.assert_allclose(br[:, 1] * scale, Gi, rtol=1e-14)
    np.testing.assert_allclose(br[:, 2], tau, rtol=1e-14)
    G = lambda t: p["G_inf"] + np.sum(Gi * np.exp(-np.asarray(t)[:, None] / tau), axis=1)
    Tk = lambda Tc: np.asarray(Tc) + 273.15
    if "C1" in p:
        return G, p["K_bulk"], lambda Tc: -p["C1"] * (Tk(Tc) - p["T_ref"]) / (p["C2"] + Tk(Tc) - p["T_ref"])
    return G, p["K_bulk"], lambda Tc: p["Q"] / R * (1 / Tk(Tc) - 1 / p["T_ref"]) / math.log(10)


def read_back(fmt, out_dir, stem, units):
    to_pa = UNIT_SCALE[units]
    base = os.path.join(out_dir, stem)
    if fmt == "abaqus":
        return read_abaqus(base + "_abaqus.inp", to_pa)
    if fmt == "ansys":
        return read_ansys(base + "_ansys.mac", to_pa)
    if fmt == "lsdyna":
        return read_lsdyna(base + "_lsdyna.k", to_pa)
    return read_comsol(base + "_comsol_parameters.txt", base + "_comsol_branches.txt", to_pa)


# ---- the fitted material, in vjax' own terms ---------------------------------------------
def _reference(d, nu, K=None):
    """(G(t), K, log10 a_T(T)) of the material JSON ``d`` through vjax' Material and shift laws."""
    mat = Material.prony(d["E0"], np.array(d["moduli"]), np.array(d["times"]), 0.3)
    s = d["shift"]
    law = WLF(s["C1"], s["C2"], s["T_ref"]) if s["law"] == "WLF" else Arrhenius(s["Ea"], s["T_ref"])
    f = 1 / (2 * (1 + nu)) if d.get("modulus", "E") == "E" else 1.0
    G = lambda t: np.asarray(mat.relaxation(np.asarray(t))) * f
    Kref = K if K is not None else float(mat.Einf) * f * 2 * (1 + nu) / (3 * (1 - 2 * nu))
    return G, Kref, lambda T: np.asarray(law.log10_aT(np.asarray(T)))


def _check(d, fmt, out_dir, stem, units, nu, K=None):
    G, Kb, la = read_back(fmt, out_dir, stem, units)
    Gr, Kr, lar = _reference(d, nu, K)
    tau = np.array(d["times"])
    t = np.concatenate([[0.0], np.logspace(np.log10(tau.min()) - 2, np.log10(tau.max()) + 2, 200)])
    np.testing.assert_allclose(G(t), Gr(t), rtol=TOL, err_msg=f"{fmt} {units}: shear relaxation modulus")
    assert abs(Kb / Kr - 1) < TOL, (fmt, units, Kb, Kr)
    s = d["shift"]
    lo = s["T_ref"] - 0.8 * s["C2"] if s["law"] == "WLF" else -60.0
    T = np.linspace(max(lo, -100.0), s["T_ref"] + 120, 57)
    np.testing.assert_allclose(la(T), lar(T), rtol=TOL, atol=TOL * np.max(np.abs(lar(T))),
                               err_msg=f"{fmt} {units}: log10 a_T")


WLF_MAT = {"kind": "prony", "E0": 1.5e6, "moduli": [3.1e8, 1.2e8, 2.5e7, 4.4e6, 9.0e5],
           "times": [2e-7, 3.3e-5, 1.7e-3, 0.21, 47.0], "nu": 0.5, "modulus": "E",
           "shift": {"law": "WLF", "C1": 12.3, "C2": 141.7, "T_ref": 25.0}}
ARR_MAT = dict(WLF_MAT, shift={"law": "Arrhenius", "Ea": 2.31e5, "T_ref": -10.0})


def _write(tmp_path, d, name="mat"):
    p = tmp_path / f"{name}.json"
    p.write_text(json.dumps(d))
    return str(p)


@pytest.mark.parametrize("units", ["SI", "mm-N-s-MPa"])
@pytest.mark.parametrize("temperature", ["K", "C"])
@pytest.mark.parametrize("d", [WLF_MAT, ARR_MAT], ids=["WLF", "Arrhenius"])
def test_every_format_reads_back(tmp_path, d, units, temperature):
    path = _write(tmp_path, d)
    fmts = [f for f in export.FORMATS if not (f == "lsdyna" and d["shift"]["law"] != "WLF")]
    assert export_cli.main([path, "--format", ",".join(fmts), "--nu", "0.42", "--units", units,
                            "--temperature", temperature]) == 0
    for fmt in fmts:
        _check(d, fmt, str(tmp_path), "mat", units, nu=0.42)


def test_bulk_modulus_and_shear_material(tmp_path):
    d = dict(WLF_MAT, modulus="G", nu=0.5)
    path = _write(tmp_path, d)
    assert export_cli.main([path, "--format", "all", "--bulk-modulus", "2.5e9", "--units", "mm-N-s-MPa"]) == 0
    for fmt in export.FORMATS:
        _check(d, fmt, str(tmp_path), "mat", "mm-N-s-MPa", nu=0.3, K=2.5e9)   # G material: nu unused


def test_incompressible_refused_with_reason(tmp_path, capsys):
    path = _write(tmp_path, WLF_MAT)      # nu = 0.5 in the file
    assert export_cli.main([path, "--format", "abaqus"]) == 1
    err = capsys.readouterr().err
    assert "infinite bulk modulus" in err and "--bulk-modulus" in err
    assert export_cli.main([path, "--format", "abaqus", "--nu", "0.5"]) == 2
    assert export_cli.main([path, "--format", "nastran", "--nu", "0.4"]) == 2
    assert "unknown export format" in capsys.readouterr().err
    assert not [p for p in os.listdir(tmp_path) if not p.endswith(".json")]


def test_table_law_names_the_alternative(tmp_path, capsys):
    alt = {"law": "WLF", "C1": 9.5, "C2": 120.0, "T_ref": 25.0, "rms_to_table": 0.08}
    d = dict(WLF_MAT, nu=0.45, shift={"law": "table", "T": [0.0, 25.0, 60.0], "log10_aT": [2.1, 0.0, -2.5],
                                      "T_ref": 25.0}, shift_alternatives=[alt])
    path = _write(tmp_path, d)
    assert export_cli.main([path, "--format", "ansys"]) == 1
    err = capsys.readouterr().err
    assert "table" in err and "C1 = 9.5" in err and "--shift-law WLF" in err
    assert export_cli.main([path, "--format", "ansys", "--shift-law", "WLF"]) == 0
    _check(dict(d, shift=alt), "ansys", str(tmp_path), "mat", "SI", nu=0.45)
    shifted = _write(tmp_path, dict(d, shift_alternatives=[dict(alt, T_ref=30.0)]), "shifted")
    assert export_cli.main([shifted, "--format", "ansys", "--shift-law", "WLF"]) == 1
    assert "refers to T_ref = 30.0 C" in capsys.readouterr().err
    bare = _write(tmp_path, dict(d, shift_alternatives=None), "bare")
    assert export_cli.main([bare, "--format", "ansys"]) == 1
    assert "refit with vjax-fit --law WLF" in capsys.readouterr().err


def test_refusals_write_nothing(tmp_path, capsys):
    path = _write(tmp_path, dict(ARR_MAT, nu=0.4))
    assert export_cli.main([path, "--format", "abaqus,lsdyna"]) == 1      # MAT_076: WLF only
    assert "only the WLF shift" in capsys.readouterr().err
    assert export_cli.main([path, "--format", "abaqus", "--max-terms", "3"]) == 1
    assert "refit with vjax-fit --max-terms 3" in capsys.readouterr().err
    assert sorted(os.listdir(tmp_path)) == ["mat.json"]
    assert export_cli.main([path, "--format", "abaqus", "--out-dir", str(tmp_path / "missing")]) == 1


@pytest.fixture(scope="module")
def shipped_fit(tmp_path_factory):
    """vjax-fit on the shipped pyvisco example (its Eplexor .xls export) with --export all (WLF, nu = 0.45)."""
    out = tmp_path_factory.mktemp("shipped") / "pyvisco.json"
    code = fit_cli.main([os.path.join(os.path.dirname(default_data("pyvisco")), "freq_Eplexor_raw.xls"), "--tref", "25", "--law", "WLF", "--out", str(out), "--nu", "0.45",
                         "--export", "all", "--no-plots", "--no-cache"])
    assert code == 0
    return out


def test_shipped_example_exports_read_back(shipped_fit, tmp_path):
    d = json.loads(shipped_fit.read_text())
    assert len(d["times"]) > 10
    for fmt in export.FORMATS:
        _check(d, fmt, str(shipped_fit.parent), "pyvisco", "SI", nu=0.45)
    assert export_cli.main([str(shipped_fit), "--format", "all", "--units", "mm-N-s-MPa", "--out-dir", str(tmp_path),
                            "--nu", "0.45"]) == 0
    for fmt in export.FORMATS:
        _check(d, fmt, str(tmp_path), "pyvisco", "mm-N-s-MPa", nu=0.45)


def test_fit_cli_table_law_keeps_the_fit_and_explains(tmp_path, capsys):
    out = tmp_path / "m.json"
    table = os.path.join(os.path.dirname(default_data("pyvisco")), "freq_user_raw.csv")
    code = fit_cli.main([table, "--tref", "25", "--law", "table", "--out", str(out), "--nu", "0.45",
                         "--export", "abaqus", "--no-plots"])
    assert code == 1 and out.exists() and not (tmp_path / "m_abaqus.inp").exists()
    cap = capsys.readouterr()
    assert "wrote " + str(out) in cap.out and "no FEM export" in cap.err and "table of shift factors" in cap.err


def test_fit_cli_checks_export_options_first(tmp_path, capsys):
    out = str(tmp_path / "m.json")
    assert fit_cli.main([default_data("pyvisco"), "--tref", "25", "--out", out, "--export", "abaqus"]) == 2
    assert "infinite bulk modulus" in capsys.readouterr().err
    assert not os.path.exists(out)
