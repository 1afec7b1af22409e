"""FEM exports (fitting.export, vjax-export, vjax-fit --export): every file is read back by an
independent parser written here from each code's documented formulas (not from
fitting/export.py), and the rebuilt shear relaxation modulus, bulk modulus, density and shift
function are compared with the fitted material (vjax.Material.relaxation and vjax's shift
laws) to 1e-10. The documented formulas (docs/fem_export.md cites the manuals):

* Abaqus: G(t) = G_0 (1 - sum g_i (1 - exp(-t/tau_i))); reduced time d xi = dt / A,
  log10 A = -C1 (th - th0)/(C2 + th - th0) or ln A = (E0/R)(1/(th - thZ) - 1/(th0 - thZ)).
* ANSYS: G(t) = G_0 (1 - sum a_i + sum a_i exp(-t/tau_i)); WLF as Abaqus; TN (no fictive
  temperature) ln A = H/R (1/T - 1/Tr), absolute temperatures T + TOFFST.
* LS-DYNA *MAT_GENERAL_VISCOELASTIC: G(t) = sum GI exp(-BETAI t); reduced time t' = int Phi dt
  with Phi = exp(-A (T - TREF)/(B + T - TREF)), or Phi = exp(-A (1/T - 1/TREF)) when B = 0;
  a shift factor a_T stretches times, so a_T = 1/Phi.
* COMSOL: G(t) = G_inf + sum G_m exp(-t/tau_m); WLF log10 a_T as above; Arrhenius
  a_T = exp(Q/R (1/T - 1/T_ref)).
"""
import json
import math
import os
import re
from importlib.metadata import version

import numpy as np
import pytest

from fitting import dma, export, export_cli
from fitting import cli as fit_cli
from fitting.dma import default_data
from vjax.material import Arrhenius, Material, WLF

R = 8.314462618
TOL = 1e-10
UNIT_SCALE = {"SI": (1.0, 1.0), "mm-N-s-MPa": (1e6, 1e12)}        # output unit -> (Pa, kg/m^3)
TAG = {"K": "K", "C": "degC"}
SHIPPED = os.path.join(os.path.dirname(default_data("pyvisco")), "freq_Eplexor_raw.xls")


# ---- independent readers: each returns (terms (G_inf, G_i, tau_i) in Pa and s, K [Pa],
# ---- density [kg/m^3] or None, log10 a_T(T in C)) ------------------------------------------
def _in_file_T(Tc, T_unit):
    """Temperatures of the test (C) in the scale the test asked the exporter for (not the
    one the file's header claims: a card in the wrong scale must fail)."""
    return np.asarray(Tc, float) + (273.15 if T_unit == "K" else 0.0)


def _wlf(Tc, Tr, C1, C2, T_unit):
    d = _in_file_T(Tc, T_unit) - Tr
    return -C1 * d / (C2 + d)


def read_abaqus(path, to_pa, to_rho, T_unit):
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
            blocks[key].append([float(v) for v in line.replace(",", " ").split()])
    (E, nu), = blocks["*ELASTIC,MODULI=INSTANTANEOUS"]
    G0, K0 = E / (2 * (1 + nu)) * to_pa, E / (3 * (1 - 2 * nu)) * to_pa
    g, k, tau = np.array(blocks["*VISCOELASTIC,TIME=PRONY"]).T
    assert np.all(k == 0)
    rho = blocks["*DENSITY"][0][0] * to_rho if "*DENSITY" in blocks else None
    terms = (G0 * (1 - g.sum()), G0 * g, tau)
    if "*TRS,DEFINITION=WLF" in blocks:
        (th0, C1, C2), = blocks["*TRS,DEFINITION=WLF"]
        return terms, K0, rho, lambda Tc: _wlf(Tc, th0, C1, C2, T_unit)
    (th0, E0), = blocks["*TRS,DEFINITION=ARRHENIUS"]
    thZ, Rg = consts["ABSOLUTE ZERO"], consts["UNIVERSAL GAS CONSTANT"]
    return terms, K0, rho, lambda Tc: (E0 / Rg) * (1 / (_in_file_T(Tc, T_unit) - thZ) - 1 / (th0 - thZ)) / math.log(10)


def read_ansys(path, to_pa, to_rho, T_unit):
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
    rho = mp["DENS"] * to_rho if "DENS" in mp else None
    terms = (G0 * (1 - a.sum()), G0 * a, tau)
    if ("SHIFT", "WLF") in tables:
        s = tables[("SHIFT", "WLF")]
        return terms, K0, rho, lambda Tc: _wlf(Tc, s[1], s[2], s[3], T_unit)
    s = tables[("SHIFT", "TN")]
    assert sorted(s) == [1, 2]            # TN takes Tr and H/R only (no fictive-temperature weight)
    return terms, K0, rho, lambda Tc: s[2] * (1 / (_in_file_T(Tc, T_unit) + toff) - 1 / (s[1] + toff)) / math.log(10)


def read_lsdyna(path, to_pa, to_rho, T_unit):
    lines = open(path).read().splitlines()
    i = next(j for j, l in enumerate(lines) if l.startswith("*MAT_GENERAL_VISCOELASTIC"))
    assert lines[i].rstrip().endswith("+")            # long format: 20-character fields
    cards = []
    for l in lines[i + 1:]:
        if l.startswith("*"):
            break
        if not l.startswith("$"):
            cards.append([float(l[j:j + 20]) if l[j:j + 20].strip() else 0.0 for j in range(0, len(l), 20)])
    c1, c2, t = cards[0], cards[1], np.array(cards[2:])
    assert len(t) <= 6, "LS-DYNA reads at most six GI/BETAI cards"
    rho, K, TREF, A, B = c1[1] * to_rho, c1[2] * to_pa, c1[5], c1[6], c1[7]
    assert c2[0] == 0 and np.all(t[:, 2] == 0) and TREF > 0
    long_term = t[:, 1] == 0
    terms = (to_pa * t[long_term, 0].sum(), to_pa * t[~long_term, 0], 1.0 / t[~long_term, 1])

    def log10_aT(Tc):
        T = _in_file_T(Tc, T_unit)
        ln_phi = -A * (T - TREF) / (B + T - TREF) if B != 0 else -A * (1 / T - 1 / TREF)
        return -ln_phi / math.log(10)            # a_T = 1/Phi
    return terms, K, rho, log10_aT


_COMSOL_UNITS = {"Pa": 1.0, "MPa": 1e6, "s": 1.0, "K": 1.0, "J/mol": 1.0, "mJ/mol": 1e-3, "": 1.0,
                 "kg/m^3": 1.0, "t/mm^3": 1e12}


def read_comsol(path_params, path_branches, to_pa, to_rho, T_unit=None):
    """T_unit unused: every COMSOL temperature carries its unit in brackets. The branch file
    is in Pa and s whatever the units (COMSOL reads it in the model's units, normally SI)."""
    p = {}
    text = open(path_params).read()
    assert "//" not in text and text.startswith("%")
    for line in text.splitlines():
        m = re.match(r'^(\w+) ([-+0-9.eE]+)(?:\[([^\]]*)\])? "', line)
        if m:
            v, u = float(m.group(2)), m.group(3) or ""
            p[m.group(1)] = v + 273.15 if u == "degC" else v * _COMSOL_UNITS[u]
    n = sum(1 for k in p if re.fullmatch(r"G_\d+", k))
    Gi = np.array([p[f"G_{i}"] for i in range(1, n + 1)])
    tau = np.array([p[f"tau_{i}"] for i in range(1, n + 1)])
    br = np.loadtxt(path_branches, ndmin=2, comments="%")
    assert open(path_branches).read().startswith("%")
    np.testing.assert_array_equal(br[:, 0], np.arange(1, n + 1))
    np.testing.assert_allclose(br[:, 1], Gi, rtol=1e-14)
    np.testing.assert_allclose(br[:, 2], tau, rtol=1e-14)
    Tk = lambda Tc: np.asarray(Tc) + 273.15
    if "C1" in p:
        la = lambda Tc: -p["C1"] * (Tk(Tc) - p["T_ref"]) / (p["C2"] + Tk(Tc) - p["T_ref"])
    else:
        la = lambda Tc: p["Q"] / R * (1 / Tk(Tc) - 1 / p["T_ref"]) / math.log(10)
    return (p["G_inf"], Gi, tau), p["K_bulk"], p.get("rho"), la


def card_paths(fmt, out_dir, stem, temperature):
    base = os.path.join(out_dir, f"{stem}_{fmt}_{TAG[temperature]}")
    return ((base + "_parameters.txt", base + "_branches.txt") if fmt == "comsol"
            else (base + {"abaqus": ".inp", "ansys": ".mac", "lsdyna": ".k"}[fmt],))


def read_back(fmt, out_dir, stem, units, temperature):
    reader = {"abaqus": read_abaqus, "ansys": read_ansys, "lsdyna": read_lsdyna, "comsol": read_comsol}[fmt]
    return reader(*card_paths(fmt, out_dir, stem, temperature), *UNIT_SCALE[units], temperature)


def prony_G(terms):
    G_inf, G, tau = terms
    return lambda t: G_inf + np.sum(G * np.exp(-np.asarray(t, float)[:, None] / tau), axis=1)


# ---- the fitted material, in vjax's own terms ---------------------------------------------
def _reference(d, nu, K=None, law=None):
    """(G(t), K, log10 a_T(T)) of the material JSON ``d`` through vjax's Material and shift laws."""
    mat = Material.prony(d["E0"], np.array(d["moduli"]), np.array(d["times"]), 0.3)
    s = law or d["shift"]
    law = WLF(s["C1"], s["C2"], s["T_ref"]) if s["law"] == "WLF" else Arrhenius(s["Ea"], s["T_ref"])
    f = 1 / (2 * (1 + nu)) if d.get("modulus", "E") == "E" else 1.0
    G = lambda t: np.asarray(mat.relaxation(np.asarray(t))) * f
    Kref = K if K is not None else float(mat.Einf) * f * 2 * (1 + nu) / (3 * (1 - 2 * nu))
    return G, Kref, lambda T: np.asarray(law.log10_aT(np.asarray(T)))


def _check(d, fmt, out_dir, stem, units, nu, temperature, K=None, rho=None, law=None, T=None):
    terms, Kb, rho_b, la = read_back(fmt, out_dir, stem, units, temperature)
    Gr, Kr, lar = _reference(d, nu, K, law)
    tau = np.array(d["times"])
    t = np.concatenate([[0.0], np.logspace(np.log10(tau.min()) - 2, np.log10(tau.max()) + 2, 200)])
    np.testing.assert_allclose(prony_G(terms)(t), Gr(t), rtol=TOL, err_msg=f"{fmt} {units}: shear relaxation modulus")
    assert abs(Kb / Kr - 1) < TOL, (fmt, units, Kb, Kr)
    if rho is not None:
        assert abs(rho_b / rho - 1) < TOL, (fmt, units, rho_b, rho)
    s = law or d["shift"]
    if T is None:
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
    # LS-DYNA's Arrhenius form takes absolute temperatures only
    fmts = [f for f in export.FORMATS if not (f == "lsdyna" and d["shift"]["law"] != "WLF" and temperature == "C")]
    assert export_cli.main([path, "--format", ",".join(fmts), "--nu", "0.42", "--units", units, "--full-spectrum",
                            "--temperature", temperature, "--density", "1150"]) == 0
    for fmt in fmts:
        _check(d, fmt, str(tmp_path), "mat", units, 0.42, temperature, rho=1150.0)


_WLF_STD = dict(WLF_MAT, shift=dict(WLF_MAT["shift"], C1=17.4, C2=51.6))
_WRONG_A = {  # what a convention error would write into A, for each law
    "A=C1": (_WLF_STD, lambda m: m.shift["C1"]),
    "A=+C1ln10": (_WLF_STD, lambda m: m.shift["C1"] * math.log(10)),
    "Arrhenius A=Ea/(R ln10)": (ARR_MAT, lambda m: m.shift["Ea"] / (R * math.log(10))),
    "Arrhenius A=-Ea/R": (ARR_MAT, lambda m: -m.shift["Ea"] / R),
}


@pytest.mark.parametrize("case", list(_WRONG_A))
def test_lsdyna_check_fails_when_A_is_wrong(tmp_path, monkeypatch, case):
    """The LS-DYNA check can fail: with the base-10 constant A = C1 written (the old card),
    the documented Phi puts log10 a_T 10 decades off at -20 C; a sign error alone (A = +C1 ln
    10) is caught too, and so are an Arrhenius A in base 10 or of the wrong sign. The header
    says why a WLF A is negative."""
    d, wrong = _WRONG_A[case]
    path = _write(tmp_path, d)
    args = [path, "--format", "lsdyna", "--nu", "0.42", "--temperature", "K", "--density", "1150", "--full-spectrum"]
    assert export_cli.main(args) == 0
    _check(d, "lsdyna", str(tmp_path), "mat", "SI", 0.42, "K", T=[-20.0, 25.0, 80.0])
    text = open(card_paths("lsdyna", str(tmp_path), "mat", "K")[0]).read()
    if d["shift"]["law"] == "WLF":
        assert "A = -C1 ln 10 is negative on purpose (Phi = exp(-A (T-TREF)/(B+T-TREF)) = 1/a_T)" in text
    assert re.search(r"check .*log10 a_T at \S+ K = ", text)
    B = d["shift"]["C2"] if d["shift"]["law"] == "WLF" else 0.0
    monkeypatch.setattr(export, "lsdyna_shift", lambda m, T_unit: (m.T_ref + 273.15, wrong(m), B))
    assert export_cli.main(args) == 0
    with pytest.raises(AssertionError, match="log10 a_T"):
        _check(d, "lsdyna", str(tmp_path), "mat", "SI", 0.42, "K", T=[-20.0, 25.0, 80.0])


def test_comsol_branch_file_is_in_pa_whatever_the_units(tmp_path):
    """COMSOL's Load from File reads the branch table without units, in the model's unit
    system (normally SI): with --units mm-N-s-MPa the branch moduli are still the fitted G_i
    in Pa (the parameter file, with bracketed units, is in MPa), and its header says so."""
    path = _write(tmp_path, dict(WLF_MAT, nu=0.4))
    assert export_cli.main([path, "--format", "comsol", "--units", "mm-N-s-MPa", "--temperature", "K",
                            "--full-spectrum"]) == 0
    params, branches = card_paths("comsol", str(tmp_path), "mat", "K")
    G = np.array(WLF_MAT["moduli"]) / (2 * 1.4)
    br = np.loadtxt(branches, ndmin=2, comments="%")
    np.testing.assert_allclose(br[:, 1], G, rtol=1e-14)
    np.testing.assert_allclose(br[:, 2], WLF_MAT["times"], rtol=1e-14)
    head = open(branches).read()
    assert "shear modulus G_i [Pa]" in head and "always Pa and s" in head and "[MPa]" not in head
    G1 = float(re.search(r'^G_1 ([-+0-9.eE]+)\[MPa\] ', open(params).read(), re.M).group(1))
    assert abs(G1 / (G[0] * 1e-6) - 1) < 1e-14


def test_evaluate_card_refuses_unknown_comsol_units(tmp_path):
    path = _write(tmp_path, dict(WLF_MAT, nu=0.4))
    assert export_cli.main([path, "--format", "comsol", "--temperature", "C", "--full-spectrum"]) == 0
    params = card_paths("comsol", str(tmp_path), "mat", "C")[0]
    text = open(params).read()
    assert export.evaluate_card(params).terms == 5
    open(params, "w").write(text.replace('[Pa] "long-term', '[kPa] "long-term'))     # an edit COMSOL would take
    with pytest.raises(ValueError, match=re.escape(os.path.basename(params)) + r": unit 'kPa' of G_inf"):
        export.evaluate_card(params)


@pytest.mark.parametrize("units, R_text", [("SI", r"8\.31446\d* J/\(mol K\)"), ("mm-N-s-MPa", r"8314\.46\d* mJ/\(mol K\)")])
def test_abaqus_arrhenius_states_R_and_reads_physical_constants(tmp_path, units, R_text):
    """Abaqus' Arrhenius shift uses the model's R (*PHYSICAL CONSTANTS): the header says which
    R the card assumes, and evaluate_card reads the keyword also once the user un-comments it."""
    path = _write(tmp_path, dict(ARR_MAT, nu=0.4))
    assert export_cli.main([path, "--format", "abaqus", "--units", units, "--temperature", "C",
                            "--full-spectrum"]) == 0
    inp = card_paths("abaqus", str(tmp_path), "mat", "C")[0]
    text = open(inp).read()
    assert re.search(r"^\*\* This card assumes the universal gas constant R = " + R_text + r" \(units " + units
                     + r"\) and ABSOLUTE ZERO = -273\.15;", text, re.M)
    T = np.array([-40.0, -10.0, 30.0])
    before = export.evaluate_card(inp).log10_aT(T)
    open(inp, "w").write(text.replace("** *PHYSICAL CONSTANTS", "*PHYSICAL CONSTANTS"))
    np.testing.assert_allclose(export.evaluate_card(inp).log10_aT(T), before, rtol=1e-14)
    np.testing.assert_allclose(before, Arrhenius(ARR_MAT["shift"]["Ea"], -10.0).log10_aT(T), rtol=1e-10, atol=1e-12)


def test_abaqus_material_name_starts_with_a_letter(tmp_path):
    path = _write(tmp_path, dict(WLF_MAT, nu=0.4), "2024_EPDM")
    assert export_cli.main([path, "--format", "abaqus", "--temperature", "K", "--full-spectrum"]) == 0
    text = open(card_paths("abaqus", str(tmp_path), "2024_EPDM", "K")[0]).read()
    assert "*MATERIAL, NAME=M_2024_EPDM\n" in text
    assert export_cli.main([path, "--format", "abaqus", "--temperature", "K", "--full-spectrum",
                            "--stem", "epdm v2.1"]) == 0
    assert "*MATERIAL, NAME=EPDM_V2_1\n" in open(card_paths("abaqus", str(tmp_path), "epdm v2.1", "K")[0]).read()


def test_file_set_is_atomic(tmp_path, monkeypatch):
    """An I/O error on the second file of an export leaves no file at all (no first card, no
    temporary)."""
    from fitting import files
    path = _write(tmp_path, dict(WLF_MAT, nu=0.4))
    real, calls = files.write_temporary, []

    def failing(p, data):
        calls.append(p)
        if len(calls) == 2:
            raise OSError(28, "No space left on device")
        return real(p, data)
    monkeypatch.setattr(files, "write_temporary", failing)
    with pytest.raises(OSError, match="No space left"):
        export.export(export.load(path), "abaqus,ansys", str(tmp_path), "mat", temperature="K", terms="full")
    assert len(calls) == 2 and os.listdir(tmp_path) == ["mat.json"]


def test_bulk_modulus_and_shear_material(tmp_path):
    d = dict(WLF_MAT, modulus="G", nu=0.5)
    path = _write(tmp_path, d)
    assert export_cli.main([path, "--format", "all", "--bulk-modulus", "2.5e9", "--units", "mm-N-s-MPa",
                            "--temperature", "K", "--density", "900", "--full-spectrum"]) == 0
    for fmt in export.FORMATS:
        _check(d, fmt, str(tmp_path), "mat", "mm-N-s-MPa", 0.3, "K", K=2.5e9, rho=900.0)   # G material: nu unused


def test_evaluate_card_round_trip(tmp_path):
    """fitting.export.evaluate_card gives back what the independent readers read, and follows
    an edited card."""
    path = _write(tmp_path, WLF_MAT)
    assert export_cli.main([path, "--format", "all", "--nu", "0.4", "--temperature", "C", "--density", "1000",
                            "--units", "mm-N-s-MPa", "--full-spectrum"]) == 0
    t, T = np.logspace(-9, 4, 40), np.array([-20.0, 25.0, 80.0])
    for fmt in export.FORMATS:
        terms, K, _, la = read_back(fmt, str(tmp_path), "mat", "mm-N-s-MPa", "C")
        card = export.evaluate_card(card_paths(fmt, str(tmp_path), "mat", "C")[0])
        assert card.code == fmt and card.terms == 5 and card.temperature == "C"
        np.testing.assert_allclose(card.G(t), prony_G(terms)(t), rtol=1e-12)
        np.testing.assert_allclose(card.log10_aT(T), la(T), rtol=1e-12, atol=1e-12)
        assert abs(card.K / K - 1) < 1e-12
    ansys = card_paths("ansys", str(tmp_path), "mat", "C")[0]
    text = open(ansys).read()
    open(ansys, "w").write(text.replace(",12.3,", ",10,"))         # an engineer edits C1
    assert abs(export.evaluate_card(ansys).log10_aT([-20.0])[0] - 10 * 45 / (141.7 - 45)) < 1e-12


def test_incompressible_refused_with_reason(tmp_path, capsys):
    path = _write(tmp_path, WLF_MAT)      # nu = 0.5 in the file
    assert export_cli.main([path, "--format", "abaqus", "--temperature", "K"]) == 1
    err = capsys.readouterr().err
    assert "infinite bulk modulus" in err and "--bulk-modulus" in err
    assert export_cli.main([path, "--format", "abaqus", "--nu", "0.5", "--temperature", "K"]) == 2
    assert export_cli.main([path, "--format", "nastran", "--nu", "0.4", "--temperature", "K"]) == 2
    assert "unknown export format" in capsys.readouterr().err
    assert not [p for p in os.listdir(tmp_path) if not p.endswith(".json")]


def test_table_law_names_the_alternative(tmp_path, capsys):
    alt = {"law": "WLF", "C1": 9.5, "C2": 120.0, "T_ref": 25.0, "rms_to_table": 0.08}
    d = dict(WLF_MAT, nu=0.45, shift={"law": "table", "T": [0.0, 25.0, 60.0], "log10_aT": [2.1, 0.0, -2.5],
                                      "T_ref": 25.0}, shift_alternatives=[alt])
    path = _write(tmp_path, d)
    opts = ["--temperature", "K", "--full-spectrum"]
    assert export_cli.main([path, "--format", "ansys"] + opts) == 1
    err = capsys.readouterr().err
    assert "table" in err and "C1 = 9.5" in err and "--shift-law WLF" in err
    assert export_cli.main([path, "--format", "ansys", "--shift-law", "WLF"] + opts) == 0
    _check(dict(d, shift=alt), "ansys", str(tmp_path), "mat", "SI", 0.45, "K")
    shifted = _write(tmp_path, dict(d, shift_alternatives=[dict(alt, T_ref=30.0)]), "shifted")
    assert export_cli.main([shifted, "--format", "ansys", "--shift-law", "WLF"] + opts) == 1
    assert "refers to T_ref = 30.0 C" in capsys.readouterr().err
    bare = _write(tmp_path, dict(d, shift_alternatives=None), "bare")
    assert export_cli.main([bare, "--format", "ansys"] + opts) == 1
    assert "refit with vjax-fit --law WLF" in capsys.readouterr().err


def test_refusals_say_what_to_add_and_write_nothing(tmp_path, capsys):
    path = _write(tmp_path, dict(WLF_MAT, nu=0.4))
    # no temperature scale: refused before anything is fitted or written, in the CLI and the API
    assert export_cli.main([path, "--format", "abaqus"]) == 2
    assert "add --temperature K or --temperature C" in capsys.readouterr().err
    with pytest.raises(ValueError, match="temperature 'K' or 'C'"):
        export.export(export.load(path), "abaqus", str(tmp_path), "mat")
    # LS-DYNA without a density: nothing written, not even the Abaqus file rendered before it
    assert export_cli.main([path, "--format", "abaqus,lsdyna", "--temperature", "K", "--full-spectrum"]) == 1
    assert "add --density" in capsys.readouterr().err
    arr = _write(tmp_path, dict(ARR_MAT, nu=0.4), "arr")
    assert export_cli.main([arr, "--format", "abaqus,lsdyna", "--temperature", "C", "--density", "1000",
                            "--full-spectrum"]) == 1
    assert "absolute temperatures: use --temperature K" in capsys.readouterr().err
    assert export_cli.main([path, "--format", "abaqus", "--max-terms", "3", "--full-spectrum",
                            "--temperature", "K"]) == 1
    assert "drop --full-spectrum" in capsys.readouterr().err
    assert sorted(os.listdir(tmp_path)) == ["arr.json", "mat.json"]
    assert export_cli.main([path, "--format", "abaqus", "--out-dir", str(tmp_path / "missing"),
                            "--temperature", "K"]) == 1


# ---- fitted materials: the shipped example ---------------------------------------------------
def _data_errors(terms, nu, d, table):
    """Median |log10(model/measured)| of storage and loss of a shear series read from a card,
    as the data's tensile modulus, under the JSON's WLF law (numpy, written here)."""
    G_inf, G, tau = terms
    s = d["shift"]
    wr = table.omega * 10.0 ** (-s["C1"] * (table.T - s["T_ref"]) / (s["C2"] + table.T - s["T_ref"]))
    iwt = 1j * wr[:, None] * tau
    E = 2 * (1 + nu) * (G_inf + np.sum(G * iwt / (1 + iwt), axis=1))
    return (float(np.median(np.abs(np.log10(E.real / table.storage)))),
            float(np.median(np.abs(np.log10(E.imag / table.loss))))), wr


@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    """vjax-fit on the shipped pyvisco example (its Eplexor .xls export), WLF, nu = 0.45, with
    the default FEM export of every code (compact series; LS-DYNA's six cards)."""
    out = tmp_path_factory.mktemp("shipped") / "pyvisco.json"
    code = fit_cli.main([SHIPPED, "--tref", "25", "--law", "WLF", "--out", str(out), "--nu", "0.45",
                         "--export", "all", "--temperature", "C", "--density", "1200", "--no-plots", "--no-cache"])
    assert code == 0
    return out, json.loads(out.read_text()), dma.read([SHIPPED])


def _loss_turns(terms, wr):
    """Local extrema of the loss modulus of (G_inf, G_i, tau_i) over the reduced window of the
    points wr (rad/s), on 8192 log-spaced frequencies."""
    w = np.logspace(np.log10(wr.min()), np.log10(wr.max()), 8192)
    z = w[:, None] * terms[2]
    return int(np.sum(np.diff(np.sign(np.diff((z / (1 + z * z)) @ terms[1]))) != 0))


def test_shipped_compact_series_keeps_the_fit_accuracy(shipped, tmp_path):
    """The default cards carry fewer terms than the fit, as accurate within 1.5x on the DMA
    points and smooth (loss modulus with at most 3 local extrema over the data, counted
    here); capped at 20 terms (--max-terms 20) they stay within 1.5x but ripple, and the
    card says so. Times stay within the data's reduced-time window plus half a decade."""
    out, d, table = shipped
    assert len(d["times"]) > 50
    (full_s, full_l), wr = _data_errors((d["E0"] / 2.9, np.array(d["moduli"]) / 2.9, np.array(d["times"])),
                                        0.45, d, table)
    assert export_cli.main([str(out), "--format", "abaqus", "--nu", "0.45", "--temperature", "C", "--density",
                            "1200", "--max-terms", "20", "--out-dir", str(tmp_path)]) == 0
    cards = [(fmt, str(out.parent)) for fmt in ("abaqus", "ansys", "comsol")] + [("abaqus", str(tmp_path))]
    for fmt, folder in cards:
        terms, _, rho, _ = read_back(fmt, folder, "pyvisco", "SI", "C")
        capped = folder == str(tmp_path)
        assert len(terms[1]) <= (20 if capped else len(d["times"]) // 2) and rho == 1200.0, fmt
        (es, el), _ = _data_errors(terms, 0.45, d, table)
        assert es <= 1.5 * full_s and el <= 1.5 * full_l, (fmt, es, full_s, el, full_l)
        assert (_loss_turns(terms, wr) > 3) == capped, (fmt, folder, _loss_turns(terms, wr))
        # relaxation times within the data's reduced-time window plus half a decade
        assert terms[2].min() >= 10 ** -0.5 / wr.max() and terms[2].max() <= 10 ** 0.5 / wr.min(), fmt
    assert "is NOT smooth" in open(card_paths("abaqus", str(tmp_path), "pyvisco", "C")[0]).read()
    head = open(card_paths("abaqus", str(out.parent), "pyvisco", "C")[0]).read()
    assert SHIPPED in head and f"vjax {version('vjax')}" in head
    assert f"storage {d['fit']['errors']['storage_median']:.4f}" in head
    assert "temperature C" in head and "density 1200 kg/m^3" in head


@pytest.mark.parametrize("law", ["WLF", "Arrhenius"])
def test_shipped_fit_every_code_by_its_formula(shipped, tmp_path, law):
    """The fitted material itself (--full-spectrum; Arrhenius: the fit's alternative), every
    code: G(t) over the data's times and log10 a_T at three temperatures to 1e-10. LS-DYNA
    gets its six-card refit, so there only the shift law is compared."""
    out, d, _ = shipped
    shift = d["shift"] if law == "WLF" else dict(d["shift_alternatives"]["Arrhenius"], law="Arrhenius")
    assert export_cli.main([str(out), "--format", "all", "--nu", "0.45", "--temperature", "K", "--density", "1200",
                            "--shift-law", law, "--full-spectrum", "--out-dir", str(tmp_path)]) == 0
    T = [-20.0, 25.0, 80.0]
    for fmt in ("abaqus", "ansys", "comsol"):
        _check(d, fmt, str(tmp_path), "pyvisco", "SI", 0.45, "K", rho=1200.0, law=shift, T=T)
    _, _, rho, la = read_back("lsdyna", str(tmp_path), "pyvisco", "SI", "K")
    lar = _reference(d, 0.45, law=shift)[2]
    np.testing.assert_allclose(la(T), lar(T), rtol=TOL, atol=TOL)
    assert rho == 1200.0


def test_shipped_lsdyna_six_cards_and_stated_accuracy(shipped, tmp_path):
    """LS-DYNA gets the best 5 terms + G_inf over a window; the deviation from the full fit
    its header states is the one measured here, and a narrower --window holds the fit better."""
    out, d, _ = shipped
    full = lambda t: (d["E0"] + np.sum(np.array(d["moduli"]) * np.exp(-np.asarray(t)[:, None] / d["times"]),
                                       axis=1)) / 2.9
    stated = []
    for folder, window in ((str(out.parent), None), (str(tmp_path), "1e-4,1e2")):
        if window:
            assert export_cli.main([str(out), "--format", "lsdyna", "--nu", "0.45", "--temperature", "C",
                                    "--density", "1200", "--window", window, "--out-dir", folder]) == 0
        terms, _, rho, la = read_back("lsdyna", folder, "pyvisco", "SI", "C")
        assert len(terms[1]) == 5 and rho == 1200.0
        Gr, _, lar = _reference(d, 0.45)
        np.testing.assert_allclose(la([-20.0, 25.0, 80.0]), lar([-20.0, 25.0, 80.0]), rtol=TOL, atol=TOL)
        text = open(card_paths("lsdyna", folder, "pyvisco", "C")[0]).read()
        lo, hi = (float(v) for v in re.search(r"reduced angular frequency (\S+) to (\S+) rad/s", text).groups())
        w = np.logspace(np.log10(lo), np.log10(hi), 400)
        G_inf, G, tau = terms
        iwt = 1j * w[:, None] * tau
        card = G_inf + np.sum(G * iwt / (1 + iwt), axis=1)
        iwt = 1j * w[:, None] * np.array(d["times"])
        ref = (d["E0"] + np.sum(np.array(d["moduli"]) * iwt / (1 + iwt), axis=1)) / 2.9
        dev = np.median(np.abs(np.log10(card.real / ref.real)))
        said = float(re.search(r"storage median ([0-9.]+)", text).group(1))
        assert abs(said - dev) < 0.003, (said, dev)       # the header's 4 decimals, another sampling
        stated.append(dev)
        if window:
            t = np.logspace(-4, 2, 50)
            assert np.max(np.abs(np.log10(prony_G(terms)(t) / full(t)))) < 0.05
    assert stated[1] < stated[0] / 3


def test_compact_without_the_data_uses_the_recorded_errors(shipped, tmp_path, capsys):
    """DMA files moved away: the compact series is held to the fit's recorded errors (its
    deviation from the full fit), and the output says which basis and whether it held."""
    _, d, table = shipped
    path = _write(tmp_path, dict(d, fit=dict(d["fit"], inputs=[str(tmp_path / "moved.xls")])), "moved")
    assert export_cli.main([path, "--format", "ansys", "--nu", "0.45", "--temperature", "K"]) == 0
    out = capsys.readouterr().out
    assert "median deviation from the full fit over the data window" in out
    terms, *_ = read_back("ansys", str(tmp_path), "moved", "SI", "K")
    assert len(terms[1]) < len(d["times"])
    text = open(card_paths("ansys", str(tmp_path), "moved", "K")[0]).read()
    assert "source DMA data: " + str(tmp_path / "moved.xls") in text
    assert ("holds the full fit's accuracy" in text) != ("does NOT hold" in text)


def test_fit_cli_table_law_keeps_the_fit_and_explains(tmp_path, capsys):
    out = tmp_path / "m.json"
    table = os.path.join(os.path.dirname(default_data("pyvisco")), "freq_user_raw.csv")
    code = fit_cli.main([table, "--tref", "25", "--law", "table", "--out", str(out), "--nu", "0.45",
                         "--export", "abaqus", "--temperature", "K", "--no-plots"])
    assert code == 1 and out.exists() and not list(tmp_path.glob("m_abaqus*"))
    cap = capsys.readouterr()
    assert "wrote " + str(out) in cap.out and "no FEM export" in cap.err and "table of shift factors" in cap.err


def test_fit_cli_checks_export_options_first(tmp_path, capsys):
    out = str(tmp_path / "m.json")
    assert fit_cli.main([default_data("pyvisco"), "--tref", "25", "--out", out, "--export", "abaqus",
                         "--temperature", "K"]) == 2
    assert "infinite bulk modulus" in capsys.readouterr().err
    assert fit_cli.main([default_data("pyvisco"), "--tref", "25", "--out", out, "--export", "abaqus",
                         "--nu", "0.45"]) == 2
    assert "--temperature" in capsys.readouterr().err
    assert not os.path.exists(out)
