"""Export a fitted material to finite-element codes: Abaqus, ANSYS, LS-DYNA and COMSOL.

A vjax material is one relaxation modulus, tensile E(t) = E0 + sum_k E_k exp(-t/tau_k) (or
shear G(t) when the JSON says ``"modulus": "G"``), with a shift law log10 a_T(T). FEM codes
want an isotropic split into a shear and a bulk part (docs/theory.md, Eq. 1.43-1.44 for the
Prony series):

* shear: G(t) = E(t) / (2 (1 + nu)), i.e. G_inf = E0 / (2 (1 + nu)), G_k = E_k / (2 (1 + nu)),
  same relaxation times tau_k (for a shear material the series is taken as it is);
* bulk: an elastic bulk modulus K, either given (``bulk_modulus``) or from the instantaneous
  tensile modulus and nu: K = E_g / (3 (1 - 2 nu)), E_g = E0 + sum_k E_k (for a shear
  material K = 2 G_g (1 + nu) / (3 (1 - 2 nu))). It must be finite: FEM elements reject
  nu = 0.5 (K infinite; the stiffness matrix is singular without a hybrid/mixed formulation),
  so nu < 0.5 or K must be given. With K from nu, uniaxial relaxation equals E(t) at t = 0
  exactly and within 1 - 9 K G(t) / ((3 K + G(t)) E(t)) later (small when K >> G).

Shift law: WLF log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref) or Arrhenius
ln a_T = (Ea / R) (1/T - 1/T_ref) (T in K), a_T > 1 below T_ref: relaxation times at T are
a_T tau_k. A table of shift factors has no FEM equivalent: :func:`load` refuses it and names
the closed-form alternative the material JSON carries, if any (``shift_alternatives``).

Formats (what each file holds, and the manual pages followed):

* **Abaqus** (``.inp`` include; Abaqus Keywords Reference *ELASTIC, *VISCOELASTIC, *TRS and
  Analysis User's Guide "Time domain viscoelasticity", abaqus-docs.mit.edu/2017/English/
  SIMACAEKEYRefMap/simakey-r-trs.htm and SIMACAEMATRefMap/simamat-c-timevisco.htm):
  ``*ELASTIC, MODULI=INSTANTANEOUS`` with the instantaneous E_g and nu_g of (G_g, K);
  ``*VISCOELASTIC, TIME=PRONY`` lines g_i, k_i, tau_i with g_i = G_i / G_g (normalized by
  the instantaneous shear modulus) and k_i = 0 (elastic bulk); ``*TRS, DEFINITION=WLF``
  theta_0, C1, C2 with Abaqus' log10 A = -C1 (theta - theta_0) / (C2 + theta - theta_0),
  reduced time d xi = dt / A: A is a_T, so C1, C2 keep vjax' (positive) signs; or
  ``*TRS, DEFINITION=ARRHENIUS`` theta_0, E0 (activation energy) with R and absolute zero
  from ``*PHYSICAL CONSTANTS`` (written as a comment: it is model data). A commented
  ``*HYPERELASTIC, NEO HOOKE`` alternative gives C10 = G_g / 2, D1 = 2 / K.
* **ANSYS** (APDL commands; Command Reference TB, TBDATA, MP, TOFFST, Material Reference
  "Viscoelasticity" / "Shift functions", ANSYS 18.2 help Hlp_C_TB.html): ``MP,EX`` and
  ``MP,NUXY`` instantaneous, ``TB,PRONY,mat,1,n,SHEAR`` with TBDATA pairs a_i, tau_i,
  a_i = G_i / G_g (relative moduli; no BULK table: the bulk response is elastic);
  ``TB,SHIFT,mat,1,3,WLF`` with TBDATA Tr, C1, C2, or ``TB,SHIFT,mat,1,3,TN``
  (Tool-Narayanaswamy without fictive temperatures is Arrhenius) with Tr, H/R = Ea/R (K), 0,
  and ``TOFFST,273.15`` when temperatures are in C.
* **LS-DYNA** (Keyword User's Manual vol. II, *MAT_GENERAL_VISCOELASTIC = *MAT_076):
  long-format cards (``+`` after the keyword, 20-character fields so that 13 significant
  digits fit): MID, RO, BULK, PCF, EF, TREF, A, B / LCID, NT, BSTART, TRAMP, ... / one card
  per term GI, BETAI = 1 / tau_i, KI, BETAKI; the long-term G_inf is a term with BETAI = 0;
  BULK = K; TREF, A = C1, B = C2 (WLF only: MAT_076 has no Arrhenius, refused). RO is 0 in
  the file: set the density. Older LS-DYNA versions read at most 6 term cards.
* **COMSOL** (Structural Mechanics User's Guide, Viscoelasticity node, generalized Maxwell,
  doc.comsol.com/5.4/doc/com.comsol.help.sme/sme_ug_solid.07.13.html): a parameter file for
  Parameters > Load from File (``name value[unit] "description"``: T_ref, C1, C2 or Q,
  G_inf (long-term shear modulus), K, G_i, tau_i) and a branch file for the Viscoelasticity
  table's Load from File (three space-separated columns: branch number, shear modulus,
  relaxation time). COMSOL's shift functions: WLF as above, Arrhenius
  a_T = exp((Q/R)(1/T - 1/T_ref)).

Units: ``"SI"`` (Pa, s, J/mol) or ``"mm-N-s-MPa"`` (MPa, s, mJ/mol); temperatures in K
(``temperature="K"``, the default: LS-DYNA wants TREF > 0, Arrhenius laws want absolute
temperature) or C. Numbers are written with 15 significant digits (13 on LS-DYNA cards).
"""
from __future__ import annotations

import dataclasses
import json
import math
import os

import numpy as np

from .files import write_atomic

__all__ = ["FEMMaterial", "FORMATS", "UNITS", "load", "split", "export", "render", "parse_formats", "check_terms"]

FORMATS = ("abaqus", "ansys", "lsdyna", "comsol")
UNITS = {"SI": (1.0, "Pa", "J/mol"), "mm-N-s-MPa": (1e-6, "MPa", "mJ/mol")}   # Pa -> unit, names
GAS_CONSTANT = 8.314462618     # J/(mol K), as vjax.material (not imported: keeps this module JAX-free)
KELVIN = 273.15
SUFFIX = {"abaqus": "_abaqus.inp", "ansys": "_ansys.mac", "lsdyna": "_lsdyna.k",
          "comsol": ("_comsol_parameters.txt", "_comsol_branches.txt")}


@dataclasses.dataclass(frozen=True)
class FEMMaterial:
    """Shear/bulk split of a Prony material, SI units, temperatures in C.

    G_inf: long-term shear modulus (Pa); G: branch shear moduli (Pa); tau: relaxation times
    (s); K: elastic bulk modulus (Pa); law: 'WLF' or 'Arrhenius' with ``shift`` = {C1, C2}
    or {Ea (J/mol)}; T_ref (C).
    """

    G_inf: float
    G: np.ndarray
    tau: np.ndarray
    K: float
    law: str
    shift: dict
    T_ref: float
    source: str = ""

    @property
    def G_g(self) -> float:
        """Instantaneous (glassy) shear modulus G_inf + sum G_i (Pa)."""
        return float(self.G_inf + self.G.sum())

    @property
    def E_g(self) -> float:
        """Instantaneous tensile modulus 9 K G_g / (3 K + G_g) (Pa)."""
        return 9.0 * self.K * self.G_g / (3.0 * self.K + self.G_g)

    @property
    def nu_g(self) -> float:
        """Instantaneous Poisson ratio (3 K - 2 G_g) / (2 (3 K + G_g))."""
        return (3.0 * self.K - 2.0 * self.G_g) / (2.0 * (3.0 * self.K + self.G_g))


def _alternatives(d: dict) -> dict:
    """Closed-form shift laws carried next to a table law, as {law: shift dict}; tolerant of
    where and how the fit stored them (``shift_alternatives``/``closed_form`` at the top or
    under ``fit``, a dict keyed by law or a list of records with ``law``)."""
    found = {}
    for holder in (d, d.get("fit") or {}):
        for key in ("shift_alternatives", "closed_form", "shift_closed_form"):
            rec = holder.get(key) if isinstance(holder, dict) else None
            if isinstance(rec, dict) and "law" in rec:
                rec = [rec]
            elif isinstance(rec, dict):
                rec = [dict(v, law=k) for k, v in rec.items() if isinstance(v, dict)]
            for r in rec or []:
                if isinstance(r, dict) and r.get("law") in ("WLF", "Arrhenius"):
                    found.setdefault(r["law"], r)
    return found


def _describe(law, s) -> str:
    if law == "WLF":
        return f"WLF (C1 = {float(s['C1']):.5g}, C2 = {float(s['C2']):.5g} K, T_ref = {float(s.get('T_ref', math.nan)):g} C)"
    return f"Arrhenius (Ea = {float(s['Ea']):.5g} J/mol, T_ref = {float(s.get('T_ref', math.nan)):g} C)"


def _positive(name, v, where):
    v = float(v)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{where}: {name} must be a finite number > 0, got {v!r}")
    return v


def split(d: dict, nu=None, bulk_modulus=None, shift_law=None, where="material") -> FEMMaterial:
    """The :class:`FEMMaterial` of a material JSON object ``d`` (schema of
    :mod:`fitting.io`).

    Args:
      nu: Poisson ratio for the split, -1 < nu < 0.5 (default: the material's own nu, which
        is refused when it is 0.5).
      bulk_modulus: elastic bulk modulus K (Pa) instead of the one from nu; nu then only
        converts E to G.
      shift_law: None (the material's law) or 'WLF'/'Arrhenius' to export the closed-form
        alternative the JSON carries next to a table law.
    """
    if not isinstance(d, dict) or d.get("kind") != "prony":
        raise ValueError(f"{where}: not a vjax Prony material (kind must be 'prony')")
    E0 = _positive("E0", d.get("E0", math.nan), where)
    Ek = np.asarray(d.get("moduli", []), float)
    tau = np.asarray(d.get("times", []), float)
    if Ek.ndim != 1 or Ek.shape != tau.shape or not (np.all(Ek > 0) and np.all(tau > 0)
                                                     and np.all(np.isfinite(Ek)) and np.all(np.isfinite(tau))):
        raise ValueError(f"{where}: moduli and times must be lists of equal length of finite numbers > 0")
    nu_given = nu is not None
    if nu is None:
        nu = float(d.get("nu", 0.5))      # with a given K, the material's nu (0.5 allowed) only turns E into G
    nu = float(nu)
    if bulk_modulus is not None and not -1.0 < nu <= 0.5:
        raise ValueError(f"nu must be a Poisson ratio -1 < nu <= 0.5, got {nu:g}")
    if bulk_modulus is None and not -1.0 < nu < 0.5:
        raise ValueError(
            f"nu must be a Poisson ratio -1 < nu < 0.5 for an FEM export, got {nu:g}"
            + ("" if nu_given else " (the material's own)") + ": nu = 0.5 means an infinite bulk modulus, "
            "which FEM elements reject (singular stiffness unless hybrid/mixed); give --nu 0.49 (e.g.) "
            "or --bulk-modulus K")
    modulus = d.get("modulus", "E")
    if modulus not in ("E", "G"):
        raise ValueError(f"{where}: modulus must be 'E' or 'G', got {modulus!r}")
    to_shear = 1.0 / (2.0 * (1.0 + nu)) if modulus == "E" else 1.0
    G_inf, G = E0 * to_shear, Ek * to_shear
    G_g = G_inf + G.sum()
    if bulk_modulus is not None:
        K = _positive("bulk modulus", bulk_modulus, "--bulk-modulus")
    else:
        K = 2.0 * G_g * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu))
    s = d.get("shift") or {}
    law = s.get("law")
    if shift_law is not None and shift_law != law:
        alts = _alternatives(d)
        if shift_law not in alts:
            raise ValueError(f"{where}: the material carries no {shift_law} alternative to its {law} shift law")
        s = dict(alts[shift_law])
        s.setdefault("T_ref", d["shift"]["T_ref"])
        if float(s["T_ref"]) != float(d["shift"]["T_ref"]):
            raise ValueError(f"{where}: the {shift_law} alternative refers to T_ref = {s['T_ref']} C, the Prony "
                             f"series to {d['shift']['T_ref']} C")
        law = shift_law
    if law == "table":
        alts = _alternatives(d)
        hint = ("; the fit also carries " + " and ".join(_describe(k, v) for k, v in alts.items())
                + ": export one with --shift-law " + "|".join(alts)
                + " (an approximation of the table), or refit with vjax-fit --law WLF") if alts else \
            "; refit with vjax-fit --law WLF (or Arrhenius) to get closed-form constants"
        raise ValueError(f"{where}: the shift law is a table of shift factors, which Abaqus, ANSYS, LS-DYNA and "
                         f"COMSOL cannot take as WLF or Arrhenius constants{hint}")
    if law == "WLF":
        shift = {"C1": _positive("C1", s.get("C1", math.nan), where), "C2": _positive("C2", s.get("C2", math.nan), where)}
    elif law == "Arrhenius":
        shift = {"Ea": _positive("Ea", s.get("Ea", math.nan), where)}
    else:
        raise ValueError(f"{where}: unknown shift law {law!r} (WLF, Arrhenius or table)")
    T_ref = float(s.get("T_ref", math.nan))
    if not math.isfinite(T_ref):
        raise ValueError(f"{where}: shift law without a finite T_ref")
    return FEMMaterial(float(G_inf), G, tau, float(K), law, shift, T_ref, source=where)


def load(path, nu=None, bulk_modulus=None, shift_law=None) -> FEMMaterial:
    """Read a material JSON file (:mod:`fitting.io` schema) and :func:`split` it."""
    path = os.fspath(path)
    with open(path, encoding="utf-8") as fh:
        try:
            d = json.load(fh)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}, line {e.lineno}: invalid JSON ({e.msg})") from None
    return split(d, nu=nu, bulk_modulus=bulk_modulus, shift_law=shift_law, where=path)


# ---- rendering ----------------------------------------------------------------------------
def _num(v) -> str:
    return f"{float(v):.15g}"


class _Units:
    def __init__(self, units, temperature):
        if units not in UNITS:
            raise ValueError(f"units must be one of {list(UNITS)}, got {units!r}")
        if temperature not in ("K", "C"):
            raise ValueError(f"temperature must be 'K' or 'C', got {temperature!r}")
        self.scale, self.stress, self.energy = UNITS[units]
        self.name, self.T_unit = units, temperature
        self.energy_scale = 1.0 if units == "SI" else 1e3        # J -> mJ (N mm)

    def p(self, v):             # a modulus in the output unit
        return float(v) * self.scale

    def T(self, T_c):           # a temperature in the output unit
        return float(T_c) + (KELVIN if self.T_unit == "K" else 0.0)

    def header(self, m: FEMMaterial, comment: str) -> str:
        law = _describe(m.law, dict(m.shift, T_ref=m.T_ref))
        return "\n".join(comment + " " + s for s in (
            f"vjax-export: {os.path.basename(m.source) or 'material'}, {len(m.G)} Prony terms, shift law {law}",
            f"units: stress {self.stress}, time s, temperature {self.T_unit}"
            + (", energy " + self.energy if m.law == "Arrhenius" else ""),
            f"shear G(t) = G_inf + sum G_i exp(-t/tau_i): G_inf = {_num(self.p(m.G_inf))}, G_g = {_num(self.p(m.G_g))}; "
            f"elastic bulk K = {_num(self.p(m.K))}"))


def _abaqus(m: FEMMaterial, u: _Units, name: str) -> str:
    g = m.G / m.G_g
    lines = [u.header(m, "**"), f"*MATERIAL, NAME={name}", "*ELASTIC, MODULI=INSTANTANEOUS",
             f"{_num(u.p(m.E_g))}, {_num(m.nu_g)}",
             "** for large strain replace *ELASTIC by (same *VISCOELASTIC below):",
             "** *HYPERELASTIC, NEO HOOKE, MODULI=INSTANTANEOUS",
             f"** {_num(u.p(m.G_g) / 2)}, {_num(2.0 / u.p(m.K))}",
             "*VISCOELASTIC, TIME=PRONY"]
    lines += [f"{_num(gi)}, 0., {_num(ti)}" for gi, ti in zip(g, m.tau)]
    if m.law == "WLF":
        lines += ["*TRS, DEFINITION=WLF", f"{_num(u.T(m.T_ref))}, {_num(m.shift['C1'])}, {_num(m.shift['C2'])}"]
    else:
        zero = 0.0 if u.T_unit == "K" else -KELVIN
        lines += ["** model data (outside *MATERIAL):",
                  f"** *PHYSICAL CONSTANTS, ABSOLUTE ZERO={_num(zero)}, "
                  f"UNIVERSAL GAS CONSTANT={_num(GAS_CONSTANT * u.energy_scale)}",
                  "*TRS, DEFINITION=ARRHENIUS", f"{_num(u.T(m.T_ref))}, {_num(m.shift['Ea'] * u.energy_scale)}"]
    return "\n".join(lines) + "\n"


def _ansys(m: FEMMaterial, u: _Units, mat_id: int = 1) -> str:
    a = m.G / m.G_g
    lines = [u.header(m, "!"), f"MP,EX,{mat_id},{_num(u.p(m.E_g))}", f"MP,NUXY,{mat_id},{_num(m.nu_g)}",
             f"TB,PRONY,{mat_id},1,{len(a)},SHEAR"]
    pairs = [v for ai, ti in zip(a, m.tau) for v in (ai, ti)]
    for i in range(0, len(pairs), 6):
        lines.append(f"TBDATA,{i + 1}," + ",".join(_num(v) for v in pairs[i:i + 6]))
    if u.T_unit == "C":
        lines.append(f"TOFFST,{_num(KELVIN)}")
    if m.law == "WLF":
        lines += [f"TB,SHIFT,{mat_id},1,3,WLF", f"TBDATA,1,{_num(u.T(m.T_ref))},{_num(m.shift['C1'])},{_num(m.shift['C2'])}"]
    else:
        lines += [f"TB,SHIFT,{mat_id},1,3,TN",
                  f"TBDATA,1,{_num(u.T(m.T_ref))},{_num(m.shift['Ea'] / GAS_CONSTANT)},0"]
    return "\n".join(lines) + "\n"


def _card(values, width=20) -> str:
    out = []
    for v in values:
        s = "" if v is None else (str(v) if isinstance(v, int) else f"{float(v):.13g}")
        if len(s) > width:
            s = f"{float(v):.{width - 8}e}"
        out.append(s.rjust(width))
    return "".join(out)


def _lsdyna(m: FEMMaterial, u: _Units, mat_id: int = 1) -> str:
    if m.law != "WLF":
        raise ValueError("LS-DYNA *MAT_GENERAL_VISCOELASTIC has only the WLF shift (TREF, A, B): "
                         f"the material's law is {m.law}; refit with vjax-fit --law WLF")
    if u.T_unit == "K" and u.T(m.T_ref) <= 0 or u.T_unit == "C" and m.T_ref <= 0:
        raise ValueError(f"LS-DYNA wants TREF > 0: use temperatures in K (T_ref = {m.T_ref:g} C)")
    lines = ["*KEYWORD", u.header(m, "$"), "*MAT_GENERAL_VISCOELASTIC +",
             "$ MID, RO (set the density), BULK, PCF, EF, TREF, A, B",
             _card([mat_id, 0.0, u.p(m.K), 0.0, 0.0, u.T(m.T_ref), m.shift["C1"], m.shift["C2"]]),
             "$ LCID, NT, BSTART, TRAMP, LCIDK, NTK, BSTARTK, TRAMPK",
             _card([0, 0, 0.0, 0.0, 0, 0, 0.0, 0.0]),
             "$ GI, BETAI = 1/tau_i, KI, BETAKI; the first term (BETAI = 0) is the long-term modulus"]
    lines.append(_card([u.p(m.G_inf), 0.0, 0.0, 0.0]))
    lines += [_card([u.p(gi), 1.0 / ti, 0.0, 0.0]) for gi, ti in zip(m.G, m.tau)]
    lines.append("*END")
    return "\n".join(lines) + "\n"


def _comsol(m: FEMMaterial, u: _Units):
    T = f"[{u.T_unit if u.T_unit == 'K' else 'degC'}]"
    P = f"[{u.stress}]"
    lines = [u.header(m, "//"), f'T_ref {_num(u.T(m.T_ref))}{T} "reference temperature of the shift function"']
    if m.law == "WLF":
        lines += [f'C1 {_num(m.shift["C1"])} "WLF constant C1 (log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref))"',
                  f'C2 {_num(m.shift["C2"])}[K] "WLF constant C2"']
    else:
        lines += [f'Q {_num(m.shift["Ea"] * u.energy_scale)}[{u.energy}] '
                  '"Arrhenius activation energy (a_T = exp(Q/R (1/T - 1/T_ref)))"']
    lines += [f'K_bulk {_num(u.p(m.K))}{P} "bulk modulus"', f'G_inf {_num(u.p(m.G_inf))}{P} "long-term shear modulus"']
    for i, (gi, ti) in enumerate(zip(m.G, m.tau), 1):
        lines += [f'G_{i} {_num(u.p(gi))}{P} "branch {i} shear modulus"', f'tau_{i} {_num(ti)}[s] "branch {i} relaxation time"']
    params = "\n".join(lines) + "\n"
    branches = "".join(f"{i} {_num(u.p(gi))} {_num(ti)}\n" for i, (gi, ti) in enumerate(zip(m.G, m.tau), 1))
    return params, branches


def render(m: FEMMaterial, fmt: str, units: str = "SI", temperature: str = "K", name: str = "VJAX"):
    """The text of one export (for ``comsol``: a (parameters, branches) pair)."""
    u = _Units(units, temperature)
    if fmt == "abaqus":
        return _abaqus(m, u, name)
    if fmt == "ansys":
        return _ansys(m, u)
    if fmt == "lsdyna":
        return _lsdyna(m, u)
    if fmt == "comsol":
        return _comsol(m, u)
    raise ValueError(f"unknown export format {fmt!r}; known: {', '.join(FORMATS)}")


def parse_formats(text) -> list:
    """'abaqus,ansys' -> ['abaqus', 'ansys'] (checked; 'all' means every format)."""
    names = [s.strip().lower() for s in (text.split(",") if isinstance(text, str) else text) if s.strip()]
    if names == ["all"]:
        return list(FORMATS)
    bad = [n for n in names if n not in FORMATS]
    if bad or not names:
        raise ValueError(f"unknown export format(s) {bad or text!r}; choose from {', '.join(FORMATS)}")
    return list(dict.fromkeys(names))


def check_terms(m: FEMMaterial, max_terms) -> None:
    """Refuse a material with more than ``max_terms`` Prony terms: dropping or merging terms
    after the fit loses accuracy that a refit with the cap keeps."""
    if max_terms is not None and len(m.G) > int(max_terms):
        raise ValueError(f"the material has {len(m.G)} Prony terms, more than --max-terms {int(max_terms)}; "
                         f"removing terms after the fit is not accurate: refit with vjax-fit --max-terms {int(max_terms)}")


def export(m: FEMMaterial, formats, out_dir, stem, units="SI", temperature="K", max_terms=None) -> list:
    """Write the files of ``formats`` (names of :data:`FORMATS`) as ``<out_dir>/<stem>_<code>...``
    atomically; every file is rendered before the first is written, so a refused format
    leaves nothing behind. Returns the paths."""
    check_terms(m, max_terms)
    if not os.path.isdir(out_dir):
        raise ValueError(f"output directory {out_dir!r} does not exist")
    texts = []
    for fmt in parse_formats(formats):
        text = render(m, fmt, units, temperature, name=stem.upper().replace(" ", "_") or "VJAX")
        suffixes = SUFFIX[fmt] if isinstance(SUFFIX[fmt], tuple) else (SUFFIX[fmt],)
        parts = text if isinstance(text, tuple) else (text,)
        texts += [(os.path.join(out_dir, stem + s), t) for s, t in zip(suffixes, parts)]
    return [os.fspath(write_atomic(p, t)) for p, t in texts]

