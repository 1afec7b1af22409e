"""A bearing case file (TOML) for ``vjax-bearing``: schema, validation, units.

:func:`load_case` reads and checks the whole file before any computation and returns a
:class:`Case` in SI; anything wrong raises :class:`CaseError` naming the file, the key and what
is expected (unknown keys, missing units, non-positive sizes, a clearance not below the radius,
a material file that does not load). The schema, with every key, is in docs/bearing_files.md;
values with a dimension are strings with their unit (:mod:`fitting.bearing.case_units`).
"""
from __future__ import annotations

import dataclasses
import math
import os
import tomllib
from pathlib import Path

import numpy as np

from fitting.bearing.case_table import REQUIRED, CaseError, Table, positive_quantity, sweep

__all__ = ["Case", "Body", "CaseError", "load_case", "SCENES"]

SCENES = ("finite_journal", "long_journal", "roller", "pin")
# the library's own defaults (vjax.FiniteJournalOptions, JournalOptions, RollerOptions,
# PinOptions; tests/test_bearing_cli.py keeps them equal): one default, stated once
_DEFAULT_N = {"finite_journal": 64, "long_journal": 256, "roller": 1024, "pin": 1024}
_DEFAULT_M = 16
_BODY_KINDS = {"housing": ("rigid", "hole", "liner", "half_plane"), "shaft": ("rigid", "disc", "sleeve", "half_plane")}


@dataclasses.dataclass(frozen=True)
class Body:
    """A bearing body: ``kind`` (rigid, hole, liner, half_plane, disc, sleeve), its
    ``material`` (vjax.Material or None), ``shift`` law (or None), ``thickness`` (m; liner and
    sleeve) and ``ref_length`` (m; hole, disc, half-plane), ``source`` (where the material came
    from), ``temperature`` (C: the body's own, whatever the operating temperature; None: the
    operating temperature's)."""

    kind: str
    material: object = None
    shift: object = None
    thickness: float | None = None
    ref_length: float = 1.0
    source: str = ""
    temperature: float | None = None


@dataclasses.dataclass(frozen=True)
class Case:
    """A validated case, SI throughout (temperatures in C). ``loads`` are in N for a finite
    journal bearing and in N/m (per unit axial length) for the plane scenes; ``points`` is the
    sweep, (temperature, load, speed) with the speed innermost (warm starts along it)."""

    file: str
    text: str
    name: str
    title: str
    scene: str
    geometry: dict
    housing: Body
    shaft: Body
    viscosity: object              # callable T -> Pa s, or None (dry scenes)
    lubricant: str
    speeds: np.ndarray
    loads: np.ndarray
    temperatures: tuple
    turning: str
    load_angle: float
    memory: str
    cavitation: str
    n: int
    m: int | None
    whirl_ratios: tuple
    overrides: tuple = ()
    density: float | None = None   # the lubricant's (kg/m^3): the film's Reynolds number
    oil_temperature: float | None = None   # C: the oil's own, whatever the operating temperature

    def eta(self, T) -> float:
        """The lubricant's viscosity (Pa s) at the operating temperature ``T`` (C): at the oil's
        own temperature where the case gives one. None only where no temperature is given, which
        only a constant viscosity allows: any T gives it."""
        T = self.oil_temperature if self.oil_temperature is not None else T
        return float(self.viscosity(0.0 if T is None else T))

    @property
    def journal(self):
        return self.scene.endswith("journal")

    @property
    def length(self):
        return self.geometry.get("length")

    @property
    def points(self):
        return [(T, W, w) for T in self.temperatures for W in self.loads for w in self.speeds]


def _material(t: Table, base: Path):
    """A material: a string (a material.json of vjax-fit, relative to the case file) or an
    inline table (model = sls | prony | elastic, optional shift). Returns (Material, shift, source)."""
    import vjax
    v = t.raw("material")
    if isinstance(v, str):
        from fitting.calibration.io import load_material
        path = (base / v).resolve()
        try:
            mat, shift, modulus = load_material(path)
        except (OSError, ValueError) as e:
            raise t.error("material", f"the material file does not load: {e}") from None
        if modulus != "E":
            raise t.error("material", f"{path} holds a shear modulus (G); the bearings take tensile moduli (E)")
        return mat, shift, f"{v} ({path})"
    m = Table(v, t.path("material"), t.file)
    model = m.choice("model", ("sls", "prony", "elastic"))
    nu = m.number("nu", lo=-1.0, hi=0.5)
    try:
        if model == "elastic":
            mat = vjax.Material.elastic(m.quantity("E", "modulus"), nu)
        elif model == "sls":
            mat = vjax.Material.sls(m.quantity("E0", "modulus"), m.quantity("Einf", "modulus"),
                                    m.quantity("tau", "time"), nu)
        else:
            moduli, times = (m.raw(k) for k in ("moduli", "times"))
            if not isinstance(moduli, list) or not isinstance(times, list) or len(moduli) != len(times) or not moduli:
                raise m.error("moduli", "moduli and times must be lists of the same, non-zero length")
            mods = [positive_quantity(m, "moduli", x, "modulus") for x in moduli]
            tims = [positive_quantity(m, "times", x, "time") for x in times]
            mat = vjax.Material.prony(m.quantity("E0", "modulus"), np.array(mods), np.array(tims), nu)
    except ValueError as e:
        if isinstance(e, CaseError):
            raise
        raise t.error("material", f"{model}: {e}") from None
    shift = None
    s = m.table("shift", None)
    if s is not None:
        law = s.choice("law", ("WLF", "Arrhenius"))
        T_ref = s.quantity("T_ref", "temperature", positive=False)
        shift = (vjax.WLF(s.number("C1"), s.quantity("C2", "temperature difference"), T_ref) if law == "WLF"
                 else vjax.Arrhenius(s.quantity("Ea", "molar energy"), T_ref))
        s.close()
    m.close()
    return mat, shift, f"inline {model}"


def _body(root: Table, side: str, scene: str, base: Path) -> Body:
    t = root.table(side, None)
    if t is None:
        return Body("rigid")
    kinds = _BODY_KINDS[side]
    if scene == "pin" and side == "housing":
        kinds = ("hole", "liner")
    if scene == "roller":
        kinds = ("rigid", "hole", "liner") if side == "housing" else ("rigid", "disc", "sleeve")
    kind = t.choice("body", kinds)
    if kind == "rigid":
        t.close()
        return Body("rigid")
    mat, shift, source = _material(t, base)
    thickness = t.quantity("thickness", "length") if kind in ("liner", "sleeve") else None
    ref = t.quantity("ref_length", "length", "1 m") if kind in ("hole", "disc", "half_plane") else 1.0
    temperature = t.quantity("temperature", "temperature", None, positive=False)
    if temperature is not None and shift is None:
        raise t.error("temperature", "moves nothing: the material has no shift law (give it one, or remove "
                                     "the body's temperature)")
    t.close()
    return Body(kind, mat, shift, thickness, ref, source, temperature)


def _geometry(t: Table, scene: str) -> dict:
    g = {}
    if scene in ("finite_journal", "long_journal", "pin"):
        g["R"] = t.quantity("bore_radius" if scene != "pin" else "hole_radius", "length")
        g["c"] = t.quantity("radial_clearance", "length")
        if not g["c"] < g["R"]:
            raise t.error("radial_clearance", f"must be below the radius ({g['R']} m), got {g['c']} m")
        g["length"] = t.quantity("length", "length", None if scene != "finite_journal" else REQUIRED)
        if scene == "finite_journal":
            g["supply_angle"] = t.quantity("supply_angle", "angle", "180 deg", positive=False)
    else:
        g["R_outer"] = t.quantity("outer_radius", "length")
        g["R_inner"] = t.quantity("inner_radius", "length")
        g["D"] = t.quantity("roller_diameter", "length")
        g["Z"] = t.number("rollers", lo=3, integer=True)
        g["clearance"] = t.quantity("diametral_clearance", "length", None, positive=False)
        g["length"] = t.quantity("length", "length", None)
        if not g["R_inner"] < g["R_outer"]:
            raise t.error("inner_radius", f"must be below outer_radius, got {g['R_inner']} >= {g['R_outer']} m")
    t.close()
    return g


def _lubricant(root: Table, scene: str):
    t = root.table("lubricant", None if not scene.endswith("journal") else REQUIRED)
    if not scene.endswith("journal"):
        if t is not None:
            raise root.error("lubricant", f"a {scene} is dry: remove the [lubricant] table")
        return None, "none (dry contact)", None, None
    from vjax import Lubricant
    law = t.choice("law", ("constant", "oil", "water"), "constant")
    if law == "constant":
        eta = t.quantity("viscosity", "viscosity")
        rho = t.quantity("density", "density", "860 kg/m3")
        lubricant, what = Lubricant.constant(eta, rho=rho), f"isoviscous, {eta:g} Pa s, density {rho:g} kg/m3"
    elif law == "water":
        lubricant, what = Lubricant.water(), "water (Vogel's equation)"
        rho = float(lubricant.rho)
    else:
        nu40 = t.quantity("nu40", "kinematic viscosity")
        nu100 = t.quantity("nu100", "kinematic viscosity")
        rho = t.quantity("density", "density", "860 kg/m3")
        if not nu100 < nu40:
            raise t.error("nu100", f"must be below nu40 (an oil thins when heated), got nu40={nu40:g} cSt, "
                                   f"nu100={nu100:g} cSt")
        lubricant = Lubricant.walther(nu40, nu100, 40.0, 100.0, rho=rho)
        what = f"oil, Walther (ASTM D341) through nu40 = {nu40:g} cSt, nu100 = {nu100:g} cSt, density {rho:g} kg/m3"
    oil_T = t.quantity("temperature", "temperature", None, positive=False)
    if oil_T is not None and law == "constant":
        raise t.error("temperature", "moves nothing: a constant viscosity has no temperature (give law = \"oil\" "
                                     "or \"water\", or remove it)")
    t.close()
    return lubricant.viscosity, what, rho, oil_T     # Pa s at T (C); kg/m^3; C


def load_case(path, overrides=()) -> Case:
    """Read and validate the case file ``path``; ``overrides`` are (dotted key, TOML value
    text) pairs applied first (the CLI's ``--set``). Raises :class:`CaseError`."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")     # -sig: an editor's byte-order mark
    except OSError as e:
        raise CaseError(path, None, f"cannot read the case file ({e.strerror})") from None
    except UnicodeDecodeError:
        raise CaseError(path, None, "not a UTF-8 text file (TOML is UTF-8: a file saved as UTF-16, or a "
                                    "binary file?)") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise CaseError(path, None, f"not valid TOML: {e}") from None
    for key, value in overrides:
        try:
            v = tomllib.loads(f"v = {value}")["v"]
        except tomllib.TOMLDecodeError:
            raise CaseError(path, key, f"--set value {value!r} is not a TOML value (quote strings: '\"50 mm\"')") from None
        d, parts = data, key.split(".")
        for p in parts[:-1]:
            d = d.setdefault(p, {})
            if not isinstance(d, dict):
                raise CaseError(path, key, "--set: not a table")
        d[parts[-1]] = v
    root = Table(data, "", path)
    case_t = root.table("case")
    scene = case_t.choice("scene", SCENES)
    name = case_t.raw("name", path.stem)
    if not isinstance(name, str) or not name or any(ch in name for ch in "/\\") or name.startswith("."):
        raise case_t.error("name", f"expected a folder name (no slashes, not starting with '.'), got {name!r}")
    title = case_t.raw("title", name)
    memory = case_t.choice("memory", ("periodic", "thesis"), "periodic")
    cavitation = case_t.choice("cavitation", ("reynolds", "jfo", "half_sommerfeld", "sommerfeld"), "reynolds")
    case_t.close()
    geometry = _geometry(root.table("geometry"), scene)
    viscosity, lubricant, density, oil_temperature = _lubricant(root, scene)
    housing = _body(root, "housing", scene, path.parent)
    shaft = _body(root, "shaft", scene, path.parent) if scene != "pin" else Body("rigid")
    if scene == "pin" and "shaft" in data:
        raise root.error("shaft", "a pin joint's pin is rigid: remove the [shaft] table")
    if scene == "roller" and housing.kind == "rigid" and shaft.kind == "rigid":
        raise root.error("housing", "a roller bearing needs at least one deformable ring (housing or shaft)")

    op = root.table("operating")
    speeds, _ = sweep(op, "speed", "angular speed")
    if np.any(speeds <= 0):
        raise op.error("speed", "speeds must be > 0 (the turning body and its sense: 'turning')")
    loads, load_dim = sweep(op, "load", None, load=True)
    if np.any(loads <= 0):
        raise op.error("load", "loads must be > 0 (the direction: 'load_angle')")
    length = geometry.get("length")
    if scene == "finite_journal" and load_dim == "force per length":
        loads = loads * length
    elif scene != "finite_journal" and load_dim == "force":
        if length is None:
            raise op.error("load", f"a force (N) on a {scene} needs geometry.length (the axial length) to give "
                                   "the load per length; or give the load per length, e.g. \"6500 N/m\"")
        loads = loads / length
    temps = sweep(op, "temperature", "temperature", None)
    temperatures = tuple(float(x) for x in temps[0]) if temps is not None else (None,)
    turning = op.choice("turning", ("shaft", "housing"), "shaft")
    load_angle = op.quantity("load_angle", "angle", "-90 deg", positive=False)
    op.close()
    needs_T = [b for b in (housing, shaft) if b.shift is not None and b.temperature is None]
    if temperatures == (None,) and (needs_T or (lubricant.startswith(("oil", "water")) and oil_temperature is None)):
        raise root.error("operating.temperature", "required: the lubricant's viscosity law or a material's shift "
                         "law needs it (e.g. temperature = \"40 C\"; or give that body or the lubricant its own)")
    for side, b in (("housing", housing), ("shaft", shaft)):
        own = (b.temperature,) if b.temperature is not None else temperatures
        for T in own if b.shift is not None else ():
            try:                                 # a shift law's own range (a fitted table's)
                times = np.asarray(b.material.with_shift(b.shift).at_temperature(T).times)
                why = "" if np.all(np.isfinite(times) & (times > 0)) else ": relaxation times not finite"
            except ValueError as e:
                why = f": {e}"
            if why:
                key = f"{side}.temperature" if b.temperature is not None else "operating.temperature"
                raise root.error(key, f"{T:g} C is outside the {side} material's shift law{why}")

    g = root.table("grid", None) or Table({}, "grid", path)
    n = g.number("n", _DEFAULT_N[scene], lo=8, integer=True)
    m = g.number("m", _DEFAULT_M, lo=2, integer=True) if scene == "finite_journal" else None
    g.close()
    whirl = (1.0,)
    co = root.table("coefficients", None)
    if co is not None:
        if not scene.endswith("journal"):
            raise root.error("coefficients", "dynamic coefficients are for journal bearings only")
        w = co.raw("whirl_ratio", [1.0])
        w = w if isinstance(w, list) else [w]
        if not w or any(isinstance(x, bool) or not isinstance(x, (int, float)) or x < 0 for x in w):
            raise co.error("whirl_ratio", f"expected non-negative numbers (whirl / shaft speed), got {w!r}")
        whirl = tuple(float(x) for x in w)
        co.close()
    if scene == "long_journal" and length is None:
        raise root.error("geometry.length", "required for a long journal bearing: coefficients.csv holds the "
                         "bearing's totals (N/m, N s/m), the long bearing's per-length values times it")
    root.close()
    case = Case(os.fspath(path), text, name, title, scene, geometry, housing, shaft, viscosity, lubricant,
                np.asarray(speeds, float), np.asarray(loads, float), temperatures, turning, load_angle, memory,
                cavitation, n, m, whirl, tuple(overrides), density, oil_temperature)
    for T in temperatures if case.journal else ():
        eta = case.eta(T)
        if not (math.isfinite(eta) and eta > 0):
            key = "lubricant.temperature" if oil_temperature is not None else "operating.temperature"
            raise root.error(key, f"the lubricant's viscosity at {T if oil_temperature is None else oil_temperature} C is {eta!r}")
    return case

