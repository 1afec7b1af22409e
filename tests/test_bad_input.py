"""Bad input to every public function: a ValueError naming the argument, raised early.

Each case gives one wrong argument (shape, NaN/inf, a non-positive physical quantity,
inconsistent geometry, an unknown option or unit) and checks that the error message names
it, and that it comes before any long computation (a few seconds at most: argument checks
run before the solvers, at worst after tracing). The CLI returns exit code 1 (bad data) or
2 (bad command line) with a message on stderr. Output files are written atomically: when a
write fails no partial file is left and an existing file is unchanged.
"""
import math
import os
import time

import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import Arrhenius, ContactOptions, Material, WLF
from experiments import _common
from fitting import calibrate
from fitting.measurements import dma
from fitting.calibration import io
from fitting.calibration import master
from fitting.cli.fit import main as cli

NAN, INF = float("nan"), float("inf")
M = Material.sls(1e6, 1e7, 0.01, 0.5)
E = Material.elastic(1e6, 0.3)
PIN_LOAD = 3.5e-2 * 1e6 * 0.08
ROLLER_LOAD = 6.5e-3 * 1e6 * 6e-3
LIMIT_S = 10.0   # an argument error must come before any solve (generous on a loaded 2-core CPU)


def _op(n=64):
    return vjax.ring_operator("hole", E, 0.05, n)


def _d(q, args):
    return args


def _d_load(q, args):
    return args + q[0]


def _force(sigma, u, args):
    return jnp.sum(sigma)[None]


D64 = jnp.where(jnp.arange(64) < 3, 1e-6, -1e-6)


def _pin(**kw):
    a = dict(housing=M, R=0.08, radial_clearance=0.005, load=PIN_LOAD, options=vjax.PinOptions(n=64))
    a.update(kw)
    return vjax.pin_in_hole(a.pop("housing"), a.pop("R"), a.pop("radial_clearance"), a.pop("load"), **a)


def _journal(**kw):
    a = dict(R=0.05, radial_clearance=5e-5, viscosity=0.01, load=2e4, omega_shaft=100.0,
             options=vjax.JournalOptions(n=64))
    a.update(kw)
    return vjax.journal_bearing(a.pop("R"), a.pop("radial_clearance"), a.pop("viscosity"), a.pop("load"), **a)


def _roller(**kw):
    a = dict(housing=M, shaft=M, R_outer=6e-3, R_inner=4e-3, roller_diameter=2e-3, n_rollers=9, load=ROLLER_LOAD,
             options=vjax.RollerOptions(n=64))
    a.update(kw)
    return vjax.roller_bearing(a.pop("housing"), a.pop("shaft"), a.pop("R_outer"), a.pop("R_inner"),
                               a.pop("roller_diameter"), a.pop("n_rollers"), a.pop("load"), **a)


# (id, call, regex the message must match: it names the argument and the problem)
CASES = [
    # ---- materials
    ("elastic-E-nan", lambda: Material.elastic(NAN, 0.3), r"E must be finite"),
    ("elastic-E-zero", lambda: Material.elastic(0.0, 0.3), r"E must be > 0"),
    ("elastic-E-negative", lambda: Material.elastic(-1e6, 0.3), r"E must be > 0"),
    ("elastic-E-shape", lambda: Material.elastic(np.ones((2, 2)), 0.3), r"E must be a scalar"),
    ("elastic-E-string", lambda: Material.elastic("1e6", 0.3), r"E must be a number"),
    ("elastic-nu-above-half", lambda: Material.elastic(1e6, 0.6), r"nu .*\(-1, 0.5\]"),
    ("elastic-nu-minus-one", lambda: Material.elastic(1e6, -1.0), r"nu .*\(-1, 0.5\]"),
    ("sls-Einf-below-E0", lambda: Material.sls(1e6, 5e5, 0.01, 0.5), r"Einf must be > E0"),
    ("sls-Einf-equal-E0", lambda: Material.sls(1e6, 1e6, 0.01, 0.5), r"Einf must be > E0"),
    ("sls-Einf-inf", lambda: Material.sls(1e6, INF, 0.01, 0.5), r"Einf must be finite"),
    ("sls-tau-zero", lambda: Material.sls(1e6, 1e7, 0.0, 0.5), r"tau must be > 0"),
    ("sls-tau-nan", lambda: Material.sls(1e6, 1e7, NAN, 0.5), r"tau must be finite"),
    ("sls-nu-nan", lambda: Material.sls(1e6, 1e7, 0.01, NAN), r"nu must be finite"),
    ("sls-E0-shape", lambda: Material.sls(np.ones(3) * 1e6, 1e7, 0.01, 0.5), r"E0 must be a scalar"),
    ("prony-moduli-negative", lambda: Material.prony(1e6, [1e6, -1e5], [1e-3, 1e-1], 0.5), r"moduli must be > 0"),
    ("prony-times-zero", lambda: Material.prony(1e6, [1e6, 1e5], [0.0, 1e-1], 0.5), r"times must be > 0"),
    ("prony-times-inf", lambda: Material.prony(1e6, [1e6, 1e5], [1e-3, INF], 0.5), r"times must be finite"),
    ("prony-length-mismatch", lambda: Material.prony(1e6, [1e6, 1e5], [1e-3], 0.5), r"moduli and times .*equal length"),
    ("prony-2d", lambda: Material.prony(1e6, np.ones((2, 2)), np.ones((2, 2)), 0.5), r"1-D"),
    ("prony-repeated-times", lambda: Material.prony(1e6, [1e6, 1e5], [1e-3, 1e-3], 0.5), r"times must be distinct"),
    ("prony-E0-shape", lambda: Material.prony(np.ones(3), [1.0, 2.0], [1.0, 2.0], 0.5), r"E0 must be a scalar"),
    ("prony-nu-shape", lambda: Material.prony(1e6, [1.0, 2.0], [1.0, 2.0], [0.3, 0.3]), r"nu must be a scalar"),
    # ---- shift laws
    ("WLF-C1-nan", lambda: WLF(NAN, 100.0, 25.0), r"C1 must be finite"),
    ("WLF-C2-zero", lambda: WLF(8.0, 0.0, 25.0), r"C2 must be > 0"),
    ("WLF-Tref-inf", lambda: WLF(8.0, 100.0, INF), r"T_ref must be finite"),
    ("WLF-T-nan", lambda: WLF(8.0, 100.0, 25.0).log10_aT(NAN), r"T must be finite"),
    ("WLF-below-asymptote", lambda: WLF(8.0, 100.0, 25.0).log10_aT(-80.0), r"asymptote"),
    ("Arrhenius-Ea-negative", lambda: Arrhenius(-1.0, 25.0), r"Ea must be > 0"),
    ("Arrhenius-Tref-below-zero-K", lambda: Arrhenius(1e5, -300.0), r"T_ref must be above absolute zero"),
    ("Arrhenius-T-below-zero-K", lambda: Arrhenius(1e5, 25.0).log10_aT(-300.0), r"T must be above absolute zero"),
    ("at_temperature-shift-string", lambda: M.at_temperature("WLF", 30.0), r"shift must be a shift law"),
    ("at_temperature-T-nan", lambda: M.at_temperature(WLF(8.0, 100.0, 25.0), NAN), r"T must be finite"),
    # ---- ring operator
    ("ring-kind", lambda: vjax.ring_operator("plate", M, 0.1, 64), r"kind must be one of"),
    ("ring-n-small", lambda: vjax.ring_operator("hole", M, 0.1, 3), r"n \(number of elements\)"),
    ("ring-n-float", lambda: vjax.ring_operator("hole", M, 0.1, 64.0), r"n \(number of elements\)"),
    ("ring-R-negative", lambda: vjax.ring_operator("hole", M, -0.1, 64), r"R must be > 0"),
    ("ring-R-shape", lambda: vjax.ring_operator("hole", M, np.array([0.1, 0.2]), 64), r"R must be a scalar"),
    ("ring-omega-nan", lambda: vjax.ring_operator("hole", M, 0.1, 64, omega=NAN), r"omega must be finite"),
    ("ring-memory-unknown", lambda: vjax.ring_operator("hole", M, 0.1, 64, memory="forever"), r"memory must be"),
    ("ring-memory-zero", lambda: vjax.ring_operator("hole", M, 0.1, 64, memory=0), r"memory .* > 0"),
    ("ring-memory-nan", lambda: vjax.ring_operator("hole", M, 0.1, 64, memory=NAN), r"memory .* > 0"),
    ("ring-material-none", lambda: vjax.ring_operator("hole", None, 0.1, 64), r"material must be a vjax.Material"),
    ("ring-ref-length-zero", lambda: vjax.ring_operator("hole", M, 0.1, 64, ref_length=0.0), r"ref_length must be > 0"),
    # ---- contact solve and its options
    ("contact-op", lambda: vjax.solve_contact("op", _d, D64), r"op must be a vjax.RingOperator"),
    ("contact-interference-not-callable", lambda: vjax.solve_contact(_op(), 3.0, D64), r"interference must be a function"),
    ("contact-interference-shape", lambda: vjax.solve_contact(_op(), _d, jnp.ones(10)), r"interference\(q, args\) must return shape \(64,\)"),
    ("contact-interference-nan", lambda: vjax.solve_contact(_op(), _d, D64.at[0].set(jnp.nan)), r"interference\(q0, args\) must be finite"),
    ("contact-F-nan", lambda: vjax.solve_contact(_op(), _d_load, D64, q0=jnp.zeros(1), force=_force, F=NAN), r"F must be finite"),
    ("contact-F-shape", lambda: vjax.solve_contact(_op(), _d_load, D64, q0=jnp.zeros(1), force=_force, F=[1.0, 2.0]), r"F of shape \(1,\)"),
    ("contact-force-missing", lambda: vjax.solve_contact(_op(), _d_load, D64, q0=jnp.zeros(1), F=1.0), r"force"),
    ("contact-q0-nan", lambda: vjax.solve_contact(_op(), _d_load, D64, q0=jnp.array([NAN]), force=_force, F=1.0), r"q0 must be finite"),
    ("contact-sigma_init-shape", lambda: vjax.solve_contact(_op(), _d, D64, sigma_init=jnp.ones(5)), r"sigma_init must have shape \(64,\)"),
    ("contact-sigma_init-inf", lambda: vjax.solve_contact(_op(), _d, D64, sigma_init=jnp.full(64, jnp.inf)), r"sigma_init must be finite"),
    ("contact-options-dict", lambda: vjax.solve_contact(_op(), _d, D64, options={"tol": 1e-8}), r"options must be a vjax.ContactOptions"),
    ("options-tol-negative", lambda: ContactOptions(tol=-1.0), r"tol must be a finite number > 0"),
    ("options-tol-nan", lambda: ContactOptions(tol=NAN), r"tol must be a finite number > 0"),
    ("options-krylov_tol-zero", lambda: ContactOptions(krylov_tol=0.0), r"krylov_tol must be a finite number > 0"),
    ("options-max_iter-zero", lambda: ContactOptions(max_iter=0), r"max_iter must be an integer >= 1"),
    ("options-krylov-float", lambda: ContactOptions(krylov=10.5), r"krylov must be an integer >= 1"),
    ("options-krylov_method", lambda: ContactOptions(krylov_method="cg"), r"krylov_method must be one of"),
    ("options-window", lambda: ContactOptions(window="yes"), r"window must be True or False"),
    # ---- bodies
    ("hole-ref-length", lambda: vjax.hole(M, ref_length=-1.0), r"ref_length must be > 0"),
    ("hole-material", lambda: vjax.hole("rubber"), r"material must be a vjax.Material"),
    # ---- pin in hole
    ("pin-larger-than-hole", lambda: _pin(radial_clearance=0.09), r"radial_clearance must be smaller than the bore radius R"),
    ("pin-equal-to-hole", lambda: _pin(radial_clearance=0.08), r"radial_clearance must be smaller"),
    ("pin-R-zero", lambda: _pin(R=0.0), r"R must be > 0"),
    ("pin-clearance-negative", lambda: _pin(radial_clearance=-0.005), r"radial_clearance must be > 0"),
    ("pin-load-zero", lambda: _pin(load=0.0), r"load must be > 0"),
    ("pin-load-nan", lambda: _pin(load=NAN), r"load must be finite"),
    ("pin-load-shape", lambda: _pin(load=np.array([PIN_LOAD, PIN_LOAD])), r"load must be a scalar"),
    ("pin-R-shape", lambda: _pin(R=np.array([0.08, 0.09])), r"R must be a scalar"),
    ("pin-omega-inf", lambda: _pin(omega_shaft=INF), r"omega_shaft must be finite"),
    ("pin-n-small", lambda: vjax.PinOptions(n=3), r"n must be an integer >= 16"),
    ("pin-n-float", lambda: vjax.PinOptions(n=64.0), r"n must be an integer >= 16"),
    ("pin-housing-none", lambda: _pin(housing=None), r"housing must be a deformable body"),
    ("pin-housing-disc", lambda: _pin(housing=vjax.disc(M)), r"housing must be one of the bodies hole"),
    ("pin-memory", lambda: _pin(memory="x"), r"memory must be one of"),
    ("pin-options", lambda: _pin(options=None), r"options must be a vjax.PinOptions"),
    ("pin-initial", lambda: _pin(initial="x"), r"initial must be a PinResult"),
    ("pin-temperature-nan", lambda: _pin(temperature=NAN, shift=WLF(8.0, 100.0, 25.0)), r"temperature must be finite"),
    # ---- journal bearing
    ("journal-R-nan", lambda: _journal(R=NAN), r"R must be finite"),
    ("journal-long-no-groove", lambda: _journal(supply_angle=None), r"supply_angle: the infinitely long.*length="),
    ("journal-clearance-above-R", lambda: _journal(radial_clearance=0.06), r"radial_clearance must be < R"),
    ("journal-clearance-zero", lambda: _journal(radial_clearance=0.0), r"radial_clearance must be > 0"),
    ("journal-viscosity-zero", lambda: _journal(viscosity=0.0), r"viscosity must be > 0"),
    ("journal-omega-inf", lambda: _journal(omega_shaft=INF), r"omega_shaft must be finite"),
    ("journal-zero-entrainment", lambda: _journal(omega_shaft=0.0), r"zero entrainment speed"),
    ("journal-load-shape", lambda: _journal(load=[1.0, 2.0, 3.0]), r"load must be a magnitude or a vector"),
    ("journal-load-nan", lambda: _journal(load=[NAN, 1.0]), r"load must be finite"),
    ("journal-load-zero-vector", lambda: _journal(load=[0.0, 0.0]), r"load must be a non-zero vector"),
    ("journal-load-negative", lambda: _journal(load=-2e4), r"load must be > 0"),
    ("journal-R-shape", lambda: _journal(R=np.array([0.05, 0.06])), r"R must be a scalar"),
    ("journal-n-odd", lambda: vjax.JournalOptions(n=63), r"n must be even"),
    ("journal-housing-disc", lambda: _journal(housing=vjax.disc(M)), r"housing must be one of the bodies hole, liner, half_plane"),
    ("journal-cavitation", lambda: _journal(cavitation="none"), r"cavitation must be one of"),
    ("journal-strategy", lambda: vjax.JournalOptions(strategy="x"), r"strategy must be one of"),
    ("journal-housing-type", lambda: _journal(housing="steel"), r"housing must be a vjax body"),
    ("journal-memory", lambda: _journal(memory=-1), r"memory .* > 0"),
    ("journal-supply-negative", lambda: _journal(supply_pressure=-1.0), r"supply_pressure must be >= 0"),
    ("journal-tol-negative", lambda: vjax.JournalOptions(tol=-1.0), r"tol must be a finite number > 0"),
    ("journal-tol-nan", lambda: vjax.JournalOptions(tol=NAN), r"tol must be a finite number > 0"),
    ("journal-initial-type", lambda: _journal(initial="x"), r"initial must be a JournalResult"),
    ("journal-stages-zero", lambda: vjax.JournalOptions(stages=0), r"stages must be an integer >= 1"),
    ("journal-max_iter-zero", lambda: vjax.JournalOptions(max_iter=0), r"max_iter must be an integer >= 1"),
    ("journal-options", lambda: _journal(options=vjax.PinOptions()), r"options must be a vjax.JournalOptions"),
    ("tilt-coefficients-whirl-shape", lambda: vjax.journal_finite.tilt_coefficients(
        0.05, 5e-5, 0.01, 100.0, 0.1, whirl=[[1.0]], omega_shaft=100.0), r"whirl must be a number or a 1-D array"),
    ("tilt-coefficients-whirl-nan", lambda: vjax.journal_finite.tilt_coefficients(
        0.05, 5e-5, 0.01, 100.0, 0.1, whirl=[NAN], omega_shaft=100.0), r"whirl must be finite"),
    # ---- roller bearing
    ("roller-too-many-rollers", lambda: _roller(n_rollers=40), r"n_rollers=40 rollers .* do not fit"),
    ("roller-clearance-below-minus-D", lambda: _roller(diametral_clearance=-3e-3), r"diametral_clearance must exceed -roller_diameter"),
    ("roller-clearance-nan", lambda: _roller(diametral_clearance=NAN), r"diametral_clearance must be finite"),
    ("roller-clearance-exceeds-D", lambda: _roller(roller_diameter=0.9e-3), r"roller_diameter=.* less than half the radial space"),
    ("roller-inner-larger-than-outer", lambda: _roller(R_outer=4e-3, R_inner=6e-3), r"R_inner must be smaller than R_outer"),
    ("roller-load-zero", lambda: _roller(load=0.0), r"load must be > 0"),
    ("roller-load-nan", lambda: _roller(load=NAN), r"load must be finite"),
    ("roller-one-roller", lambda: _roller(n_rollers=1), r"n_rollers must be an integer >= 2"),
    ("roller-n_rollers-float", lambda: _roller(n_rollers=9.0), r"n_rollers must be an integer"),
    ("roller-both-rigid", lambda: _roller(housing=None, shaft=None), r"housing and shaft cannot both be None"),
    ("roller-housing-type", lambda: _roller(housing="steel"), r"housing must be a vjax body"),
    ("roller-memory", lambda: _roller(memory="y"), r"memory must be one of"),
    ("roller-temperature-without-shift", lambda: _roller(temperature=30.0), r"temperature= moves no body"),
    ("roller-shift-type", lambda: _roller(temperature=30.0, shift="WLF"), r"shift must be a shift law"),
    ("roller-n-small", lambda: vjax.RollerOptions(n=8), r"n must be an integer >= 16"),
    ("roller-omega-nan", lambda: _roller(omega_shaft=NAN), r"omega_shaft must be finite"),
    ("roller-R-negative", lambda: _roller(R_inner=-4e-3), r"R_inner must be > 0"),
    ("roller-tol-negative", lambda: vjax.RollerOptions(tol=-1.0), r"tol must be a finite number > 0"),
    ("roller-max_iter-zero", lambda: vjax.RollerOptions(max_iter=0), r"max_iter must be an integer >= 1"),
    ("roller-load-shape", lambda: _roller(load=np.array([ROLLER_LOAD, ROLLER_LOAD])), r"load must be a scalar"),
    ("roller-options", lambda: _roller(options=None), r"options must be a vjax.RollerOptions"),
    ("roller-initial", lambda: _roller(initial="x"), r"initial must be a RollerResult"),
    # ---- fitting
    ("dma-kind", lambda: dma.read(dma.default_data(), kind="X"), r"kind must be 'E' or 'G'"),
    ("dma-from_arrays-nan", lambda: dma.from_arrays([20.0], [1.0], [NAN], [1.0]), r"storage must be finite"),
    ("dma-from_arrays-negative", lambda: dma.from_arrays([20.0], [1.0], [-1.0], [1.0]), r"must be > 0"),
    ("dma-default-data-name", lambda: dma.default_data("nope"), r"unknown data set"),
    ("calibrate-law", lambda: calibrate(dma.default_data(), 25.0, law="VFT"), r"law must be"),
    ("calibrate-T_ref-nan", lambda: calibrate(dma.default_data(), NAN), r"T_ref must be a finite temperature"),
    ("calibrate-nu", lambda: calibrate(dma.default_data(), 25.0, nu=0.7), r"nu .*\(-1, 0.5\]"),
    ("shift-law-unknown", lambda: master.fit_law(master.ShiftTable.make([0.0, 10.0], [0.0, -1.0], 0.0), "VFT"),
     r"shift law must be"),
    ("shift-table-nan", lambda: master.ShiftTable.make([0.0, 10.0], [0.0, NAN], 0.0), r"finite"),
]

CASES += [
]


@pytest.mark.parametrize("call, pattern", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_argument_raises_value_error_naming_it(call, pattern):
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=pattern):
        call()
    assert time.perf_counter() - t0 < LIMIT_S



# ---------------------------------------------------------------------- DMA files
def _w(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return str(p)


HDR = "T [C],f [Hz],E' [MPa],E'' [MPa]\n"
BAD_FILES = [
    ("empty", "", r"file is empty"),
    ("unknown-modulus-unit", "T [C],f [Hz],E' [bar],E'' [bar]\n20,1,1,1\n", r"unknown modulus unit 'bar'"),
    ("unknown-frequency-unit", "T [C],f [rpm],E' [MPa],E'' [MPa]\n20,1,1,1\n", r"unknown frequency unit 'rpm'"),
    ("unknown-temperature-unit", "T [F],f [Hz],E' [MPa],E'' [MPa]\n20,1,1,1\n", r"unknown temperature unit 'F'"),
    ("missing-unit", "T [C],f,E' [MPa],E'' [MPa]\n20,1,1,1\n", r"has no unit"),
    ("nan-modulus", HDR + "20,1,nan,1\n20,2,1,1\n", r"line 2: storage modulus is NaN"),
    ("negative-modulus", HDR + "20,1,-1,1\n20,2,1,1\n", r"line 2: non-positive modulus"),
    ("zero-frequency", HDR + "20,0,1,1\n20,2,1,1\n", r"line 2: frequency must be > 0"),
    ("missing-column", "T [C],f [Hz],E' [MPa]\n20,1,1\n", r"missing column\(s\): loss modulus"),
    ("non-monotonic-frequency", HDR + "20,1,1,1\n20,3,1,1\n20,2,1,1\n", r"line 4: frequency not monotonic"),
    ("duplicated-point", HDR + "20,1,1,1\n20,1,1,1\n", r"duplicated point"),
    ("wrong-row-length", HDR + "20,1,1\n", r"line 2: expected 4 values, found 3"),
    ("not-a-number", HDR + "20,1,abc,1\n", r"line 2: not a number: 'abc'"),
]


@pytest.mark.parametrize("text, pattern", [c[1:] for c in BAD_FILES], ids=[c[0] for c in BAD_FILES])
def test_bad_dma_file(tmp_path, text, pattern):
    path = _w(tmp_path, "bad.csv", text)
    with pytest.raises(dma.DMAFormatError, match=pattern) as info:
        dma.read(path)
    assert "bad.csv" in str(info.value)          # names the file
    assert isinstance(info.value, ValueError)


def test_missing_file_and_single_temperature(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        dma.read(str(tmp_path / "nope.csv"))
    one = _w(tmp_path, "one.csv", HDR + "20,1,1,1\n20,2,2,1\n20,3,3,1\n")
    with pytest.raises(ValueError, match="two or more temperatures"):
        calibrate(one, 20.0)


def test_bad_material_json(tmp_path):
    with pytest.raises(ValueError, match="missing key 'moduli'"):
        io.load_material(_w(tmp_path, "m.json", '{"kind": "prony"}'))
    with pytest.raises(ValueError, match="invalid JSON"):
        io.load_material(_w(tmp_path, "b.json", '{"kind": '))
    bad = ('{"kind": "prony", "E0": 1e6, "moduli": [-1.0], "times": [1.0], "nu": 0.5, '
           '"shift": {"law": "WLF", "C1": 8, "C2": 100, "T_ref": 25}}')
    with pytest.raises(ValueError, match="moduli must be > 0"):
        io.load_material(_w(tmp_path, "neg.json", bad))
    law = bad.replace("-1.0", "1.0").replace('"WLF"', '"VFT"')
    with pytest.raises(ValueError, match="unknown shift law 'VFT'"):
        io.load_material(_w(tmp_path, "law.json", law))


# ---------------------------------------------------------------------- CLI
def _cli(args, capsys):
    try:
        code = cli(args)
    except SystemExit as e:        # argparse: bad command line
        code = e.code
    return code, capsys.readouterr().err


def test_cli_exit_codes(tmp_path, capsys):
    data = dma.default_data()
    out = str(tmp_path / "m.json")
    code, err = _cli(["--tref", "25", "--out", out], capsys)
    assert code == 2 and "INPUT" in err
    code, err = _cli([data, "--out", out], capsys)
    assert code == 2 and "--tref" in err
    code, err = _cli([data, "--tref", "25", "--out", out, "--law", "VFT"], capsys)
    assert code == 2 and "--law" in err
    code, err = _cli([data, "--tref", "25", "--out", out, "--kind", "X"], capsys)
    assert code == 2 and "--kind" in err
    code, err = _cli([data, "--tref", "abc", "--out", out], capsys)
    assert code == 2 and "--tref" in err
    code, err = _cli([data, "--tref", "25", "--out", str(tmp_path / "m.txt")], capsys)
    assert code == 2 and "--out must name a .json file" in err
    code, err = _cli([data, "--tref", "25", "--out", str(tmp_path / "nodir" / "m.json")], capsys)
    assert code == 1 and "does not exist" in err
    code, err = _cli([data, "--tref", "nan", "--out", out], capsys)
    assert code == 1 and "T_ref must be a finite temperature" in err
    neg = _w(tmp_path, "neg.csv", HDR + "20,1,-1,1\n20,2,1,1\n")
    code, err = _cli([neg, "--tref", "25", "--out", out], capsys)
    assert code == 1 and "neg.csv, line 2: non-positive modulus" in err
    code, err = _cli([data, "--tref", "25", "--nu", "0.9", "--out", out], capsys)
    assert code == 1 and "nu (Poisson's ratio)" in err
    assert not os.path.exists(out)            # nothing written on failure
    assert os.listdir(tmp_path) == ["neg.csv"]


# ---------------------------------------------------------------------- atomic writes
def _listing(d):
    return sorted(os.listdir(d))


def test_atomic_writes_leave_no_partial_file(tmp_path, monkeypatch):
    target = tmp_path / "table.csv"
    target.write_text("old\n")

    def rows():
        yield [1.0, 2.0]
        raise RuntimeError("generator failed half-way")

    with pytest.raises(RuntimeError):
        _common.write_csv(target, ["a", "b"], rows())
    assert target.read_text() == "old\n" and _listing(tmp_path) == ["table.csv"]

    # a failure during the write itself (disk full, killed between write and rename)
    def boom(fd):
        raise OSError("disk full")

    monkeypatch.setattr(os, "fsync", boom)
    with pytest.raises(OSError):
        _common.atomic_write_text(target, "new content\n")
    with pytest.raises(OSError):
        _common.write_csv(tmp_path / "fresh.csv", ["a"], [[1.0]])
    with pytest.raises(OSError):
        io.save_material(tmp_path / "m.json", M, WLF(8.0, 100.0, 25.0))
    assert target.read_text() == "old\n" and _listing(tmp_path) == ["table.csv"]
    monkeypatch.undo()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = plt.figure()
    with pytest.raises(ValueError):
        _common.save_figure(fig, tmp_path / "fig.nosuchformat")
    plt.close(fig)
    assert _listing(tmp_path) == ["table.csv"]

    # and a successful write replaces the file as a whole, with the usual permissions
    _common.write_csv(target, ["a"], [[1.5]], comments=["unit: m"])
    assert target.read_text() == "# unit: m\na\n1.5\n"
    assert oct(os.stat(target).st_mode & 0o777) == "0o644"
    io.save_material(tmp_path / "m.json", M, WLF(8.0, 100.0, 25.0))
    mat, shift, kind = io.load_material(tmp_path / "m.json")
    assert math.isclose(float(mat.Einf), 1e7) and kind == "E"
    assert _listing(tmp_path) == ["m.json", "table.csv"]
