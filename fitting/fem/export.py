"""Export a fitted material to finite-element codes: Abaqus, ANSYS, LS-DYNA and COMSOL.

A vjax material is one relaxation modulus, tensile E(t) = E0 + sum_k E_k exp(-t/tau_k) (or
shear G(t) when the JSON says ``"modulus": "G"``), with a shift law log10 a_T(T), a_T > 1
below T_ref (relaxation times at T are a_T tau_k). FEM codes want an isotropic split:

* shear: G(t) = E(t) / (2 (1 + nu)) (:func:`fitting.shared.evaluate.tensile_over_shear`), same
  relaxation times; for a shear material the series is taken as it is;
* bulk: an elastic bulk modulus K, given (``bulk_modulus``) or K = E_g / (3 (1 - 2 nu)) from
  the instantaneous tensile modulus E_g = E0 + sum E_k. It must be finite (nu < 0.5): FEM
  elements reject an infinite K.

Each code's documented formulas, and how vjax' (G_inf, G_i, tau_i, K, C1, C2 / Ea, T_ref)
fill its fields (docs/fem_export.md derives and cites them; :func:`evaluate_card` applies
them to a written file):

============ ======================================================= ============================================
code         relaxation function and shift, as documented           fields written
============ ======================================================= ============================================
Abaqus       g_R(t) = 1 - sum g_i (1 - exp(-t/tau_i)), G = G_0 g_R;  ``*ELASTIC, MODULI=INSTANTANEOUS`` E_g, nu_g;
             reduced time d xi = dt / A, WLF                         ``*VISCOELASTIC, TIME=PRONY`` g_i = G_i/G_g,
             log10 A = -C1 (th - th0)/(C2 + th - th0); Arrhenius     k_i = 0, tau_i; ``*TRS`` th0, C1, C2 (A = a_T)
             ln A = (E0/R)(1/(th - thZ) - 1/(th0 - thZ))             or th0, Ea with *PHYSICAL CONSTANTS R, thZ
                                                                     (the model's R: the header states the one assumed)
ANSYS        G(t) = G_0 (a_inf + sum a_i exp(-t/tau_i)),             ``MP,EX/NUXY`` instantaneous; ``TB,PRONY,,,n,
             a_inf = 1 - sum a_i; WLF log10 A as Abaqus; TN          SHEAR`` a_i = G_i/G_g, tau_i; ``TB,SHIFT`` WLF
             (Tool-Narayanaswamy, no fictive temperature)            Tr, C1, C2 or TN Tr, H/R = Ea/R;
             ln A = H/R (1/T - 1/Tr), T absolute via TOFFST          ``TOFFST,273.15`` with temperatures in C
LS-DYNA      G(t) = sum_i GI exp(-BETAI t) (the long-term modulus    ``*MAT_GENERAL_VISCOELASTIC``: RO, BULK = K,
             is a term with BETAI = 0); reduced time t' = int Phi dt TREF = T_ref, A = -C1 ln 10, B = C2 (WLF) or
             Phi = exp(-A (T - TREF)/(B + T - TREF)) (WLF),          A = Ea/R, B = 0 (Arrhenius, T in K); cards
             Phi = exp(-A (1/T - 1/TREF)) when B = 0 (Arrhenius)     GI, BETAI = 1/tau_i (G_inf: BETAI = 0)
COMSOL       G(t) = G_inf + sum G_m exp(-t/tau_m); WLF               parameter file (T_ref, C1, C2 or Q, K, G_inf,
             log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref),           G_i, tau_i, rho with units) and branch file
             Arrhenius a_T = exp((Q/R)(1/T - 1/T_ref))               (branch, G_i [Pa], tau_i [s], always SI)
============ ======================================================= ============================================

LS-DYNA's Phi multiplies the time step (t' = int Phi dt) where Abaqus divides by A: Phi =
1/a_T. With its documented Phi = exp(-A (T - TREF)/(B + T - TREF)) and vjax' ln a_T =
-C1 ln(10) (T - T_ref)/(C2 + T - T_ref), the constants are A = -C1 ln 10 (a negative number;
writing A = C1 would shift by ln instead of log10 and in the wrong direction) and B = C2.
Its keyword reads at most six GI/BETAI cards, G_inf included (:data:`CARD_LIMIT`).

Where each convention comes from, and what was checked (docs/fem_export.md has the detail):
LS-DYNA Keyword User's Manual, vol. II, ``*MAT_GENERAL_VISCOELASTIC`` (``*MAT_076``), card 1
and remarks: the layout (MID RO BULK PCF EF TREF A B / LCID NT BSTART TRAMP LCIDK NTK BSTARTK
TRAMPK / up to six GI BETAI KI BETAKI) and the meaning of TREF, A, B are confirmed by
OpenRadioss's keyword file ``hm_cfg_files/config/CFG/Keyword971/MAT/mat_076.cfg`` and by Ansys'
PyDyna keyword classes (github.com/ansys/pydyna, ``MatGeneralViscoelastic``: A "Coefficient
for the Arrhenius and the Williams-Landau-Ferry shift function", B "Coefficient for
Williams-Landau-Ferry shift function", TREF "must be greater than zero", "Define up to six
cards"); the shift formulas Phi = exp(-A (T - TREF)/(B + T - TREF)) (WLF) and
Phi = exp(-A (1/T - 1/TREF)) (B = 0), time multiplied by Phi, were found only as a second-hand
quote of the R16 manual's remarks (a third-party card writer's source), not on a manual page:
check a written card with the check values in its header on the solver. ANSYS Mechanical APDL
Command Reference ``TB`` (TB,SHIFT, TBOPT = WLF: Tr, C1, C2) and Material Reference "Shift
Functions": the WLF field order is confirmed by pyvisco's ANSYS card
``tests/data/E1_WLF.USER_MPL``; the base 10 of its logarithm and the two TN constants (Tr, H/R)
are not confirmed by quoted text.

Term counts: by default the series written is compact (:mod:`fitting.calibration.compact`): the fewest
terms whose medians on the DMA data stay within 1.5x of the full fit's and whose loss-modulus
ripple (the largest swing of an extremum the full fit does not have) stays below the data's
scatter about the full fit (its median |log10(E''_fit/E''_measured)|); ``max_terms`` caps the
count and the note says what the cap costs. ``window`` (reduced times at T_ref, s: the user's
working window) is the main lever for fewer terms: the series is then chosen over it. A code
with a card limit (LS-DYNA: six cards) gets the best series of that many terms over the window,
a refit, never a truncation; without ``window`` it is refused when the refit cannot hold the
data's window within twice the full fit's error, and the message names the widest window it
does hold (:func:`widest_window`). Every header states the count, the window, the ripple and
the accuracy. A liquid (the fit's E0 below 0.1 % of its storage modulus at the data's lowest
frequency: :func:`fitting.calibration.compact.is_liquid`) is written with G_inf = 0, and the header says
so. ``isothermal`` writes every card at one temperature (times a_T(T) tau_i, no shift fields).
Beside each LS-DYNA and ANSYS card (not isothermal) a one-element verification deck is written
(:func:`verification_plan`): the element at a step shear strain at T_ref and a hotter
temperature, with the stresses the card's material predicts, so the solver confirms the
shift's sign and base. The temperature scale has no default (``temperature='K'`` or ``'C'``,
also in the file names); the density (``density``, kg/m^3) is written where each code wants
it and LS-DYNA's RO is refused without it. Units: ``"SI"`` (Pa, s, kg/m^3, J/mol) or
``"mm-N-s-MPa"`` (MPa, s, t/mm^3, mJ/mol). Every header names the source DMA files, the fit's
accuracy and the vjax version. Files are rendered before the first is written, then written
as a set (all to temporaries, renamed at the end: :func:`fitting.shared.files.write_all_atomic`): a
refusal or an I/O error leaves nothing behind.
"""
from __future__ import annotations

import dataclasses
import json
import math
import os
import re

import numpy as np

from fitting.calibration import compact
from fitting.shared import evaluate
from fitting.shared.evaluate import tensile_over_shear
from fitting.shared import files

__all__ = ["ExportRefused", "FEMMaterial", "Card", "FORMATS", "UNITS", "CARD_LIMIT", "load", "split", "prepare", "export",
           "render", "parse_formats", "lsdyna_shift", "abaqus_name", "evaluate_card", "file_name", "data_points",
           "deck_name", "isothermal_card", "verification_plan", "widest_window", "STRAIN"]

FORMATS = ("abaqus", "ansys", "lsdyna", "comsol")
# output unit system -> (Pa -> stress unit, stress name, energy name, kg/m^3 -> density unit, density name)
UNITS = {"SI": (1.0, "Pa", "J/mol", 1.0, "kg/m^3"), "mm-N-s-MPa": (1e-6, "MPa", "mJ/mol", 1e-12, "t/mm^3")}
TEMPERATURES = {"K": "K", "C": "degC"}         # --temperature -> the tag in file names
CARD_LIMIT = {"lsdyna": 6}     # GI/BETAI cards the keyword reads, the long-term modulus included
GAS_CONSTANT = 8.314462618     # J/(mol K), as vjax.materials.GAS_CONSTANT (not imported: keeps this module JAX-free)
KELVIN = 273.15
LN10 = math.log(10.0)
MIN_POINTS = 10                # DMA points inside a --window to measure a compact series on (else: the full fit)
EXTENSION = {"abaqus": ".inp", "ansys": ".mac", "lsdyna": ".k", "comsol": ("_parameters.txt", "_branches.txt")}


@dataclasses.dataclass(frozen=True)
class FEMMaterial:
    """Shear/bulk split of a Prony material, SI units, temperatures in C.

    G_inf: long-term shear modulus (Pa); G: branch shear moduli (Pa); tau: relaxation times
    (s); K: elastic bulk modulus (Pa); law: 'WLF' or 'Arrhenius' with ``shift`` = {C1, C2}
    or {Ea (J/mol)}; T_ref (C). Provenance: ``source`` (material JSON), ``files`` (DMA
    files of the fit), ``errors`` (the fit's errors on them, median |log10(model/measured)|),
    ``window`` (reduced angular frequencies of the data at T_ref, rad/s, or None),
    ``to_data`` (factor from this shear series to the data's modulus), ``domain``
    ('frequency' or 'time' data), ``note`` (how the series was obtained: its count, window,
    ripple and accuracy), ``liquid`` (why G_inf = 0, when the data show no equilibrium modulus;
    empty for a solid), ``iso_T`` (C: an isothermal card at that temperature, relaxation
    times a_T(iso_T) tau_i and no shift law; None: the card at T_ref with its shift law)."""

    G_inf: float
    G: np.ndarray
    tau: np.ndarray
    K: float
    law: str
    shift: dict
    T_ref: float
    source: str = ""
    files: tuple = ()
    errors: dict = dataclasses.field(default_factory=dict)
    window: tuple | None = None
    to_data: float = 1.0
    domain: str = "frequency"
    note: str = ""
    liquid: str = ""
    iso_T: float | None = None
    nu: float | None = None         # the ratio E was split with into G and K (None: K was given)

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

    @property
    def series(self) -> compact.Series:
        """The shear series as a :class:`fitting.calibration.compact.Series` (Pa, s)."""
        return compact.Series(float(self.G_inf), np.asarray(self.G, float), np.asarray(self.tau, float))

    def with_series(self, s: compact.Series, note: str) -> "FEMMaterial":
        """This material with another shear series (bulk modulus and shift law kept)."""
        return dataclasses.replace(self, G_inf=float(s.E0), G=np.asarray(s.moduli, float),
                                   tau=np.asarray(s.times, float), note=note)

    def log10_aT(self, T) -> np.ndarray:
        """log10 a_T at temperatures ``T`` (C), vjax' convention (a_T > 1 below T_ref)."""
        T = np.asarray(T, float)
        if self.law == "WLF":
            d = T - self.T_ref
            return -self.shift["C1"] * d / (self.shift["C2"] + d)
        return self.shift["Ea"] / (GAS_CONSTANT * LN10) * (1.0 / (T + KELVIN) - 1.0 / (self.T_ref + KELVIN))


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
    :mod:`fitting.calibration.io`).

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
    E0 = float(d.get("E0", math.nan))
    if not (math.isfinite(E0) and E0 >= 0):
        raise ValueError(f"{where}: E0 must be a finite number >= 0 (0: a liquid), got {d.get('E0')!r}")
    Ek = np.asarray(d.get("moduli", []), float)
    tau = np.asarray(d.get("times", []), float)
    if Ek.ndim != 1 or Ek.shape != tau.shape or not (np.all(Ek > 0) and np.all(tau > 0)
                                                     and np.all(np.isfinite(Ek)) and np.all(np.isfinite(tau))):
        raise ValueError(f"{where}: moduli and times must be lists of equal length of finite numbers > 0")
    nu_given = nu is not None
    nu_material = float(d.get("nu", 0.5))
    nu = nu_material if nu is None else float(nu)   # with a given K, nu (0.5 allowed) only turns E into G
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
    to_shear = 1.0 / tensile_over_shear(nu) if modulus == "E" else 1.0
    G_inf, G = E0 * to_shear, Ek * to_shear
    G_g = G_inf + G.sum()
    if bulk_modulus is not None:
        K = _positive("bulk modulus", bulk_modulus, "--bulk-modulus")
    else:
        K = G_g * tensile_over_shear(nu) / (3.0 * (1.0 - 2.0 * nu))
    s = d.get("shift") or {}
    law = s.get("law")
    fit = d.get("fit") if isinstance(d.get("fit"), dict) else {}
    errors = dict(fit.get("errors") or {})
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
        errors = dict(s.get("errors") or {})
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
    # the data's modulus: the series' own, unless shear data were turned into E at the fit
    to_data = 1.0 / to_shear
    if modulus == "E" and fit.get("data_kind") == "G":
        to_data /= tensile_over_shear(nu_material)
    files = tuple(str(f) for f in (fit.get("files") or fit.get("inputs") or ()))
    window = fit.get("window_rad_s")
    window = (float(window[0]), float(window[1])) if window and len(window) == 2 else None
    # no equilibrium modulus where the data could see one: written as G_inf = 0 (a liquid)
    w_min = window[0] if window else 10.0 / float(tau.max())
    liquid = ""
    if compact.is_liquid(compact.Series(G_inf, G, tau), w_min):
        liquid = (f"E_inf = 0: no equilibrium modulus (a liquid): the fit's E0 = {E0:.3g} Pa is below "
                  f"{compact.LIQUID:.1%} of its storage modulus at the data's lowest reduced frequency "
                  f"({w_min:.3g} rad/s), so the data show none; G_inf = 0 is written")
        G_inf = 0.0
    return FEMMaterial(float(G_inf), G, tau, float(K), law, shift, T_ref, source=where, files=files,
                       errors={k: float(v) for k, v in errors.items() if isinstance(v, (int, float))},
                       window=window, to_data=to_data, domain=str(fit.get("domain", "frequency")),
                       note=f"{len(G)} terms: the full fit", liquid=liquid,
                       nu=None if bulk_modulus is not None else nu)


def load(path, nu=None, bulk_modulus=None, shift_law=None) -> FEMMaterial:
    """Read a material JSON file (:mod:`fitting.calibration.io` schema) and :func:`split` it. DMA file
    names recorded relative to the JSON's folder are resolved there."""
    path = os.fspath(path)
    with open(path, encoding="utf-8") as fh:
        try:
            d = json.load(fh)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}, line {e.lineno}: invalid JSON ({e.msg})") from None
    m = split(d, nu=nu, bulk_modulus=bulk_modulus, shift_law=shift_law, where=path)
    here = os.path.dirname(os.path.abspath(path))
    files = tuple(f if os.path.isabs(f) or os.path.exists(f) else os.path.join(here, f) for f in m.files)
    return dataclasses.replace(m, files=files)


# ---- the series written: compact by default, refit to a code's card limit ----------------
def data_points(m: FEMMaterial, window=None):
    """(target points, errors_of, their reduced window) from the DMA files the fit names, or
    None when they are not all readable (or fewer than ``MIN_POINTS`` fall inside ``window``).
    ``target``: reduced omega (rad/s), storage, loss of the points in this series' own
    modulus; ``errors_of(series)``: the series' errors on the points. ``window``: (omega_min,
    omega_max) rad/s reduced: only the points inside it."""
    if not m.files or not all(os.path.exists(f) for f in m.files):
        return None
    from fitting.measurements import dma, relaxation
    try:
        if relaxation.is_relaxation(list(m.files)):
            table = relaxation.read(list(m.files))
            rate = 1.0 / table.t
        else:
            table = dma.read(list(m.files))
            rate = table.omega
    except (ValueError, OSError):
        return None
    wr = rate * 10.0 ** m.log10_aT(table.T)
    keep = np.ones(len(wr), bool) if window is None else (wr >= window[0]) & (wr <= window[1])
    if keep.sum() < MIN_POINTS:
        return None
    wr = wr[keep]
    if table.domain == "time":
        E = table.modulus[keep]
        target = ("time", 1.0 / wr, E / m.to_data)

        def errors_of(s):
            r = np.abs(np.log10(evaluate.relaxation(s.scaled(m.to_data), 1.0 / wr) / E))
            return {"relaxation_median": float(np.median(r)), "relaxation_p90": float(np.percentile(r, 90))}
    else:
        st, ls = table.storage[keep], table.loss[keep]
        target = (wr, st / m.to_data, ls / m.to_data)

        def errors_of(s):
            return evaluate.errors_at(s.scaled(m.to_data), wr, st, ls)
    return target, errors_of, (float(wr.min()), float(wr.max()))


def _window(m: FEMMaterial, data):
    """The data's reduced window (rad/s): recorded in the JSON, else from the data, else from
    the relaxation times (the smooth fit's grid spans the data plus a decade each side)."""
    if m.window:
        return m.window, "the data's (recorded with the fit)"
    if data is not None:
        return data[2], "the data's"
    return (10.0 / float(m.tau.max()), 0.1 / float(m.tau.min())), "the relaxation times' less a decade each side"


def _pct(v) -> str:
    return f"{(10 ** v - 1) * 100:.1f}%"


def _times(w) -> str:
    """A reduced window (rad/s) as reduced times at T_ref: '1e-03..1e+05 s at T_ref'."""
    return f"{1.0 / w[1]:.3g}..{1.0 / w[0]:.3g} s at T_ref"


def _medians(ref: dict) -> dict:
    """The full fit's median errors per modulus (storage, loss); relaxation data: E(t) for both."""
    if "relaxation_median" in ref:
        return {"storage_median": ref["relaxation_median"], "loss_median": ref["relaxation_median"]}
    return {k: ref[k] for k in ("storage_median", "loss_median") if k in ref}


def widest_window(full: compact.Series, n: int, window, reference: dict, long_term: bool = True, points=None):
    """The widest window of whole decades of reduced time (s at T_ref) inside ``window``
    (rad/s) over which ``n`` terms (:func:`fitting.calibration.compact.fit_terms`) stay within twice the
    full fit's error: their median deviation from ``full`` there at most the full fit's median
    error on the data (``reference``), storage and loss (relaxation data: E(t), as measured).
    With ``points(w)`` (the DMA points inside a window w, as :func:`data_points`, or None)
    a window holding at least ``MIN_POINTS`` of them is judged as the refusal is: the refit's
    medians on those points at most twice the full fit's on them. Returns (t_min, t_max) or
    None.
    Widths are bisected; at each, windows are tried from the middle of the data outwards."""
    lim = _medians(reference)
    lo, hi = math.floor(-math.log10(window[1])), math.ceil(-math.log10(window[0]))
    relaxation = "relaxation_median" in reference       # relaxation data: judged on E(t), as measured

    def holds(a, b):
        w = (10.0 ** -b, 10.0 ** -a)
        s = compact.fit_terms(full, n, w, long_term=long_term)
        inside = points(w) if points is not None else None
        if inside is not None:
            got, ref = _medians(inside[1](s)), _medians(inside[1](full))
            return all(got[k] <= 2.0 * v for k, v in ref.items())
        if relaxation:
            t = np.logspace(a, b, 10 * (b - a) + 1)
            return float(np.median(np.abs(np.log10(evaluate.relaxation(s, t) / evaluate.relaxation(full, t))))) \
                <= reference["relaxation_median"]
        d = compact.deviation(s, full, w)
        return all(d[k] <= v for k, v in lim.items())

    def at(width):
        starts = sorted(range(lo, hi - width + 1), key=lambda a: abs(a + width / 2 - (lo + hi) / 2))
        return next(((a, a + width) for a in starts if holds(a, a + width)), None)

    best, wlo, whi = None, 1, hi - lo
    while wlo <= whi:                     # the largest width that holds somewhere
        mid = (wlo + whi) // 2
        got = at(mid)
        if got:
            best, wlo = got, mid + 1
        else:
            whi = mid - 1
    return None if best is None else (10.0 ** best[0], 10.0 ** best[1])


def prepare(m: FEMMaterial, terms="compact", max_terms=None, window=None, limit=None, messages=None) -> FEMMaterial:
    """The series to write; its ``note`` states the count, the window, the ripple and the
    accuracy. ``terms``: 'compact' (default; :func:`fitting.calibration.compact.choose`: the fewest terms
    within 1.5x of the full fit's medians whose loss-modulus ripple stays below the data's
    scatter, at most ``max_terms`` if given, the note saying what the cap costs) or 'full' (all
    terms, refused above ``max_terms``). ``window`` = (t_min, t_max) (s, reduced time at
    T_ref): the user's working window, the main lever for fewer terms: the compact series is
    chosen over it (accuracy on the DMA points inside it, ripple over it).
    ``limit``: the code's card limit (:data:`CARD_LIMIT`, G_inf included): a series with more
    terms is refit to ``limit - 1`` decaying terms over ``window`` = (t_min, t_max) (s,
    reduced time at T_ref). Without ``window`` the data's window is used, and refused when
    the refit there misses the data by more than twice the full fit's error: the message
    names the widest window that ``limit - 1`` terms do hold (:func:`widest_window`).
    ``messages``: a list that gets one line per decision."""
    if terms not in ("compact", "full"):
        raise ValueError(f"terms must be 'compact' or 'full', got {terms!r}")
    if max_terms is not None and not (isinstance(max_terms, int) and max_terms >= 1):
        raise ValueError(f"max_terms must be an integer >= 1, got {max_terms!r}")
    say = messages.append if messages is not None else (lambda s: None)
    if window is not None:
        t_min, t_max = (float(v) for v in window)
        if not (0 < t_min < t_max and math.isfinite(t_max)):
            raise ValueError(f"--window must be t_min,t_max with 0 < t_min < t_max (s), got {window!r}")
        w_user = (1.0 / t_max, 1.0 / t_min)
    data = data_points(m) if terms == "compact" or limit else None
    wdata, wsource = _window(m, data)
    long_term = not m.liquid
    ref = data[1](m.series) if data is not None else dict(m.errors)
    noise = compact.scatter(ref) if _medians(ref) else None
    noise_txt = (f"the data's scatter {noise:.4f} decades ({_pct(noise)}: the full fit's median "
                 f"|log10(E''_fit/E''_measured)|" + ("" if data is not None else ", as recorded") + ")"
                 if noise is not None else "the data's scatter (not recorded)")
    out = m
    if terms == "full":
        if max_terms is not None and len(m.G) > max_terms:
            raise ValueError(f"the material has {len(m.G)} Prony terms, more than --max-terms {max_terms}; drop "
                             f"--full-spectrum to write a compact refit of at most {max_terms} terms")
        out = dataclasses.replace(m, note=f"{len(m.G)} terms: the full fit, over {_times(wdata)} ({wsource} "
                                          f"window); ripple: none (the fit is the reference); accuracy: the full "
                                          f"fit's (above)")
    else:
        cap = min(max_terms, len(m.G)) if max_terms else None
        if data is None and not m.errors and (max_terms is None or len(m.G) <= max_terms):
            say(f"{len(m.G)} terms kept as fitted (no DMA data or recorded errors to check a refit against)")
            return m if not limit else prepare(m, "full", None, window, limit, messages)
        # over the user's working window: the DMA points inside it, or the full fit there
        wc, wcsource, dc = wdata, f"{wsource} window", data
        if window is not None:
            wc, wcsource = w_user, "the window given"
            dc = data_points(m, w_user) if data is not None else None
        if dc is not None:
            c = compact.choose(m.series, wc, errors_of=dc[1], target=dc[0], max_terms=cap, long_term=long_term)
        elif m.errors:
            c = compact.choose(m.series, wc, reference=m.errors, max_terms=cap, long_term=long_term)
        else:
            raise ValueError(f"{m.source}: neither the DMA files nor the fit's errors are available, so the compact "
                             "series cannot be checked against the fit's accuracy; give --full-spectrum, or keep "
                             "the DMA files named in the JSON")
        keys = [k for k in ("storage_median", "loss_median", "relaxation_median") if k in c.errors and k in c.reference]
        acc = ", ".join(f"{k.split('_')[0]} {c.errors[k]:.4f} ({_pct(c.errors[k])}) vs {c.reference[k]:.4f}"
                        for k in keys)
        what = ("median |log10(model/measured)| on the DMA data" if c.basis == "data"
                else "median deviation from the full fit over the data window")
        noise_c = noise_txt if window is None or c.scatter == noise else (
            f"the data's scatter {c.scatter:.4f} decades ({_pct(c.scatter)}: the full fit's median "
            f"|log10(E''_fit/E''_measured)| inside the window)")
        rip = f"ripple {c.ripple:.4f} decades ({_pct(c.ripple)}) vs {noise_c}"
        verdict = (f"holds the full fit's accuracy within {compact.TOLERANCE:g}x and its ripple is below the scatter"
                   if c.met else
                   f"holds the full fit's accuracy within {compact.TOLERANCE:g}x but its ripple is NOT below the "
                   f"scatter: that is what --max-terms {max_terms} costs (drop it for the smooth default)"
                   if c.accurate else f"does NOT hold the full fit's accuracy within {compact.TOLERANCE:g}x (the "
                   f"best of at most {cap or len(m.G)} terms" + (f": that is what --max-terms {max_terms} costs"
                                                                 if max_terms else "") + ")")
        note = (f"compact: {len(c.series.times)} of {len(m.G)} terms over {_times(wc)} ({wcsource}); "
                f"{rip}; accuracy ({what}" + (" inside the window" if window is not None else "") + f"): {acc}; it "
                f"{verdict}")
        out = m.with_series(c.series, note)
        say(note)
    if limit and len(out.G) > limit - 1:
        if window is None:
            w, wtxt = wdata, f"{wsource} window"
        else:
            w, wtxt = w_user, f"the window {t_min:g} to {t_max:g} s"
        s = compact.fit_terms(m.series, limit - 1, w, long_term=long_term)
        dev = compact.deviation(s, m.series, w)
        rip = compact.ripple_of(s, m.series, w)
        e = data[1](s) if data is not None and window is None else None   # (a narrower window leaves points out)
        lim = _medians(ref)
        if window is None and lim:
            if e is not None:
                got = _medians(e)
                holds = all(got[k] <= 2.0 * v for k, v in lim.items())
                how = "on the DMA data: " + ", ".join(f"{k.split('_')[0]} median {got[k]:.4f} against the full "
                                                      f"fit's {v:.4f}" for k, v in lim.items())
            else:
                holds = all(dev[k] <= v for k, v in lim.items())
                how = "deviation from the full fit: " + ", ".join(f"{k.split('_')[0]} median {dev[k]:.4f} against "
                                                                  f"the full fit's error {v:.4f}" for k, v in lim.items())
            if not holds:
                best = widest_window(m.series, limit - 1, w, ref, long_term,
                                     points=(lambda ww: data_points(m, ww)) if data is not None else None)
                dec = [f"1e{round(math.log10(t))}" for t in best] if best else None
                where = (f"the widest window {limit} cards do hold is {dec[0]}..{dec[1]} s at T_ref: give --window "
                         f"{dec[0]},{dec[1]} (the reduced times the analysis will see), "
                         if best else f"no window of a decade or more is held by {limit} cards; ")
                raise ValueError(
                    f"no card written for a code limited to {limit} term cards ({limit - 1} terms + G_inf): over the "
                    f"data's window ({_times(w)}, {math.log10(w[1] / w[0]):.0f} decades) its best {limit - 1} terms "
                    f"miss by more than twice the full fit's error ({how}); {where}or use a code without a term limit")
        note = (f"refit to {limit - 1} terms + G_inf ({limit} cards, the keyword's limit) over {wtxt}: "
                f"{_times(w)} (reduced angular frequency {w[0]:.3g} to {w[1]:.3g} rad/s); ripple {rip:.4f} decades "
                f"({_pct(rip)}) vs {noise_txt}; accuracy, deviation from the full fit there: storage median "
                f"{dev['storage_median']:.4f} ({_pct(dev['storage_median'])}), max {dev['storage_max']:.4f}; loss "
                f"median {dev['loss_median']:.4f} ({_pct(dev['loss_median'])}), max {dev['loss_max']:.4f} decades")
        if e is not None:
            note += "; on the DMA data " + ", ".join(f"{k.split('_')[0]} median {e[k]:.4f}" for k in
                                                    ("storage_median", "loss_median", "relaxation_median") if k in e)
        out = m.with_series(s, note)
        say(note)
    return out


def isothermal_card(m: FEMMaterial, T) -> FEMMaterial:
    """``m`` at the one temperature ``T`` (C): relaxation times a_T(T) tau_i, no shift law
    (every code reads it the same way; what a single-temperature analysis needs)."""
    T = float(T)
    la = float(m.log10_aT(T))
    if not math.isfinite(la):
        raise ValueError(f"--isothermal {T:g} C: the shift law has no finite a_T there (log10 a_T = {la})")
    return dataclasses.replace(m, tau=np.asarray(m.tau, float) * 10.0 ** la, iso_T=T,
                               note=m.note + f"; isothermal at {T:g} C: relaxation times a_T tau_i with log10 a_T "
                                             f"= {la:.6g}")


# ---- rendering ----------------------------------------------------------------------------
def _num(v) -> str:
    return f"{float(v):.15g}"


def _version() -> str:
    try:
        from importlib.metadata import version
        return version("vjax")
    except Exception:       # not installed (a source checkout on sys.path)
        return "unknown (not installed)"


class _Units:
    def __init__(self, units, temperature, density):
        if units not in UNITS:
            raise ValueError(f"units must be one of {list(UNITS)}, got {units!r}")
        if temperature not in TEMPERATURES:
            raise ValueError("the temperature scale of the cards has no default: give temperature 'K' or 'C' "
                             f"(--temperature K or --temperature C), got {temperature!r}")
        if density is not None and not (math.isfinite(float(density)) and float(density) > 0):
            raise ValueError(f"--density must be a finite number > 0 (kg/m^3), got {density!r}")
        self.scale, self.stress, self.energy, self.rho_scale, self.rho_unit = UNITS[units]
        self.name, self.T_unit = units, temperature
        self.energy_scale = 1.0 if units == "SI" else 1e3        # J -> mJ (N mm)
        self.density = None if density is None else float(density)

    def p(self, v):             # a modulus in the output unit
        return float(v) * self.scale

    def rho(self):              # the density in the output unit
        return self.density * self.rho_scale

    def T(self, T_c):           # a temperature in the output unit
        return float(T_c) + (KELVIN if self.T_unit == "K" else 0.0)

    def header(self, m: FEMMaterial, comment: str, code: str, fields: str) -> str:
        law = _describe(m.law, dict(m.shift, T_ref=m.T_ref))
        err = ", ".join(f"{k.split('_')[0]} {v:.4f} ({_pct(v)})" for k, v in m.errors.items()
                        if k in ("storage_median", "loss_median", "relaxation_median"))
        rho = (f"density {self.density:g} kg/m^3 = {_num(self.rho())} {self.rho_unit}" if self.density is not None
               else "no density given (vjax-export --density, kg/m^3): add it for dynamic analyses")
        lines = [
            f"vjax {_version()} export for {code} of {m.source or 'a material'}",
            "source DMA data: " + (", ".join(m.files) if m.files else "not recorded in the material JSON"),
            "full fit's accuracy on the DMA data, median |log10(model/measured)|: " + (err or "not recorded"),
            f"series written: {len(m.G)} Prony terms; {m.note}",
            f"units: stress {self.stress}, time s, temperature {self.T_unit}, density {self.rho_unit}"
            + (f", energy {self.energy}" if m.law == "Arrhenius" else "") + f"; {rho}",
            f"shift law {law}; vjax: log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref), a_T > 1 below T_ref"
            if m.law == "WLF" else f"shift law {law}; vjax: ln a_T = Ea/R (1/T - 1/T_ref), T in K"]
        if m.iso_T is not None:
            lines[-1] = "the fit's " + lines[-1] + " (it set the times below; it is NOT in this card)"
        if m.iso_T is None:
            lines.append("check (e.g. the one-element verification deck written beside this card): " + ", ".join(
                f"log10 a_T at {self.T(T):g} {self.T_unit} = {float(m.log10_aT(T)):.6g}" for T in (m.T_ref - 20, m.T_ref + 20)
                if m.law != "WLF" or m.shift["C2"] > 20))
        else:
            lines.append(f"ISOTHERMAL card at T = {self.T(m.iso_T):g} {self.T_unit}: relaxation times a_T(T) tau_i "
                         f"(log10 a_T = {float(m.log10_aT(m.iso_T)):.6g}), no shift fields: valid at this temperature "
                         "only")
        if m.liquid:
            lines.append(m.liquid + " (a code that wants sum g_i < 1 needs a small G_inf instead)")
        lines += [
            f"shear G(t) = G_inf + sum G_i exp(-t/tau_i): G_inf = {_num(self.p(m.G_inf))}, "
            f"G_g = {_num(self.p(m.G_g))}; elastic bulk K = {_num(self.p(m.K))}",
            _poisson(m), fields]
        return "\n".join(comment + " " + s for s in lines)


def _poisson(m: FEMMaterial) -> str:
    """The header line that says which Poisson's ratio the card's elastic fields hold, and why
    it is not the one the material was split with when it differs."""
    line = f"Poisson's ratio in the elastic fields: instantaneous nu_g = (3K - 2G_g)/(2(3K + G_g)) = {m.nu_g:.4f}"
    if m.nu is None:
        return line + " (K as given)"
    if abs(m.nu_g - m.nu) <= 5e-4:
        return line + f", the nu = {m.nu:g} the material was split with"
    return (line + f", not the nu = {m.nu:g} the material was split with: K = E_g / (3 (1 - 2 nu)) holds the full "
            "fit's glassy modulus and G_g is this series' (a refit over a window, or G_inf = 0 for a liquid, "
            "changes it); the card's shear and bulk responses are the ones stated here")


def abaqus_name(name: str) -> str:
    """``name`` as an Abaqus label: letters, digits and underscores only, starting with a
    letter (``M_`` prefixed otherwise), at most 80 characters: '2024_EPDM' -> 'M_2024_EPDM'."""
    name = re.sub(r"[^A-Za-z0-9_]", "_", str(name)) or "VJAX"
    return (name if name[0].isalpha() else "M_" + name)[:80]


def _abaqus(m: FEMMaterial, u: _Units, name: str) -> str:
    g = m.G / m.G_g
    fields = ("*VISCOELASTIC g_i = G_i/G_g, k_i = 0, tau_i; " + (
        "no *TRS (isothermal)" if m.iso_T is not None else
        "*TRS th0, C1, C2 (log10 A = a_T)" if m.law == "WLF" else "*TRS th0, Ea (ln A = ln a_T)"))
    lines = [u.header(m, "**", "Abaqus", fields)]
    if m.law == "Arrhenius" and m.iso_T is None:
        lines += ["** Arrhenius: Abaqus takes R and absolute zero from *PHYSICAL CONSTANTS (model data, one per model).",
                  f"** This card assumes the universal gas constant R = {_num(GAS_CONSTANT * u.energy_scale)} "
                  f"{u.energy.replace('/mol', '/(mol K)')} (units {u.name}) and ABSOLUTE ZERO = "
                  f"{_num(0.0 if u.T_unit == 'K' else -KELVIN)}; a model with another R shifts by the wrong factor."]
    lines.append(f"*MATERIAL, NAME={abaqus_name(name)}")
    if u.density is not None:
        lines += ["*DENSITY", _num(u.rho())]
    lines += ["*ELASTIC, MODULI=INSTANTANEOUS", f"{_num(u.p(m.E_g))}, {_num(m.nu_g)}",
              "** for large strain replace *ELASTIC by (same *VISCOELASTIC below):",
              "** *HYPERELASTIC, NEO HOOKE, MODULI=INSTANTANEOUS",
              f"** {_num(u.p(m.G_g) / 2)}, {_num(2.0 / u.p(m.K))}",
              "*VISCOELASTIC, TIME=PRONY"]
    lines += [f"{_num(gi)}, 0., {_num(ti)}" for gi, ti in zip(g, m.tau)]
    if m.iso_T is not None:
        pass                         # isothermal: no *TRS
    elif m.law == "WLF":
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
    fields = "TB,PRONY SHEAR a_i = G_i/G_g, tau_i; " + ("no TB,SHIFT (isothermal)" if m.iso_T is not None else
                                                          "TB,SHIFT WLF Tr, C1, C2" if m.law == "WLF"
                                                          else "TB,SHIFT TN Tr, H/R = Ea/R")
    lines = [u.header(m, "!", "ANSYS", fields), f"MP,EX,{mat_id},{_num(u.p(m.E_g))}", f"MP,NUXY,{mat_id},{_num(m.nu_g)}"]
    if u.density is not None:
        lines.append(f"MP,DENS,{mat_id},{_num(u.rho())}")
    lines.append(f"TB,PRONY,{mat_id},1,{len(a)},SHEAR")
    pairs = [v for ai, ti in zip(a, m.tau) for v in (ai, ti)]
    for i in range(0, len(pairs), 6):
        lines.append(f"TBDATA,{i + 1}," + ",".join(_num(v) for v in pairs[i:i + 6]))
    if m.iso_T is not None:
        return "\n".join(lines) + "\n"
    if u.T_unit == "C":
        lines.append(f"TOFFST,{_num(KELVIN)}")
    if m.law == "WLF":
        lines += [f"TB,SHIFT,{mat_id},1,3,WLF", f"TBDATA,1,{_num(u.T(m.T_ref))},{_num(m.shift['C1'])},{_num(m.shift['C2'])}"]
    else:
        lines += [f"TB,SHIFT,{mat_id},1,2,TN",
                  f"TBDATA,1,{_num(u.T(m.T_ref))},{_num(m.shift['Ea'] / GAS_CONSTANT)}"]
    return "\n".join(lines) + "\n"


def _card(values, width=20) -> str:
    out = []
    for v in values:
        s = "" if v is None else (str(v) if isinstance(v, int) else f"{float(v):.13g}")
        if len(s) > width:
            s = f"{float(v):.{width - 8}e}"
        out.append(s.rjust(width))
    return "".join(out)


def lsdyna_shift(m: FEMMaterial, T_unit: str):
    """(TREF, A, B) of ``*MAT_GENERAL_VISCOELASTIC`` for ``m``'s shift law, temperatures in
    ``T_unit`` ('K' or 'C'). LS-DYNA's reduced time is t' = int Phi dt with Phi = 1/a_T:
    WLF Phi = exp(-A (T - TREF)/(B + T - TREF)), so A = -C1 ln 10 and B = C2; Arrhenius
    (B = 0) Phi = exp(-A (1/T - 1/TREF)) with absolute T, so A = Ea/R (K) and TREF in K."""
    if m.law == "WLF":
        TREF = m.T_ref + (KELVIN if T_unit == "K" else 0.0)
        if TREF <= 0:
            raise ValueError(f"LS-DYNA wants TREF > 0: T_ref = {m.T_ref:g} C; use --temperature K")
        return TREF, -m.shift["C1"] * LN10, m.shift["C2"]
    if T_unit != "K":
        raise ValueError("LS-DYNA's Arrhenius shift (B = 0) uses absolute temperatures: use --temperature K")
    return m.T_ref + KELVIN, m.shift["Ea"] / GAS_CONSTANT, 0.0


def _lsdyna(m: FEMMaterial, u: _Units, mat_id: int = 1) -> str:
    if u.density is None:
        raise ValueError("LS-DYNA needs the density (RO of *MAT_GENERAL_VISCOELASTIC; a deck with RO = 0 does not "
                         "run): add --density RHO in kg/m^3")
    if len(m.G) + 1 > CARD_LIMIT["lsdyna"]:
        raise ValueError(f"LS-DYNA reads at most {CARD_LIMIT['lsdyna']} GI/BETAI cards, G_inf included; the series "
                         f"has {len(m.G)} terms + G_inf (export prepares a refit of {CARD_LIMIT['lsdyna'] - 1})")
    if m.iso_T is not None:          # A = B = 0: Phi = 1 at every temperature
        TREF, A, B = u.T(m.iso_T), 0.0, 0.0
        if TREF <= 0:
            raise ValueError(f"LS-DYNA wants TREF > 0: --isothermal {TREF:g} C; use --temperature K")
        shift = "isothermal: A = B = 0, so Phi = 1 (no shift); TREF = the card's temperature"
    else:
        TREF, A, B = lsdyna_shift(m, u.T_unit)
        shift = ("A = -C1 ln 10 is negative on purpose (Phi = exp(-A (T-TREF)/(B+T-TREF)) = 1/a_T), B = C2"
                 if m.law == "WLF"
                 else "B = 0: Phi = exp(-A (1/T - 1/TREF)) = 1/a_T, T in K: A = Ea/R, TREF in K")
    lines = ["*KEYWORD", u.header(m, "$", "LS-DYNA", "reduced time t' = int Phi dt, " + shift),
             "*MAT_GENERAL_VISCOELASTIC +",
             "$ MID, RO, BULK, PCF, EF, TREF, A, B",
             _card([mat_id, u.rho(), u.p(m.K), 0.0, 0.0, TREF, A, B]),
             "$ LCID, NT, BSTART, TRAMP, LCIDK, NTK, BSTARTK, TRAMPK",
             _card([0, 0, 0.0, 0.0, 0, 0, 0.0, 0.0]),
             "$ GI, BETAI = 1/tau_i, KI, BETAKI; the first card (BETAI = 0) is the long-term modulus G_inf"]
    lines.append(_card([u.p(m.G_inf), 0.0, 0.0, 0.0]))
    lines += [_card([u.p(gi), 1.0 / ti, 0.0, 0.0]) for gi, ti in zip(m.G, m.tau)]
    lines.append("*END")
    return "\n".join(lines) + "\n"


def _comsol(m: FEMMaterial, u: _Units):
    T = f"[{'K' if u.T_unit == 'K' else 'degC'}]"
    P = f"[{u.stress}]"
    fields = "parameters with their units in brackets; branch file: branch, G_i [Pa], tau_i [s] (always SI)"
    head = u.header(m, "%", "COMSOL", fields)
    if m.iso_T is not None:
        lines = [head, f'T_iso {_num(u.T(m.iso_T))}{T} "the one temperature of this isothermal card (no shift function)"']
    else:
        lines = [head, f'T_ref {_num(u.T(m.T_ref))}{T} "reference temperature of the shift function"']
    if m.iso_T is not None:
        pass
    elif m.law == "WLF":
        lines += [f'C1 {_num(m.shift["C1"])} "WLF constant C1 (log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref))"',
                  f'C2 {_num(m.shift["C2"])}[K] "WLF constant C2"']
    else:
        lines += [f'Q {_num(m.shift["Ea"] * u.energy_scale)}[{u.energy}] '
                  '"Arrhenius activation energy (a_T = exp(Q/R (1/T - 1/T_ref)))"']
    lines += [f'K_bulk {_num(u.p(m.K))}{P} "bulk modulus"', f'G_inf {_num(u.p(m.G_inf))}{P} "long-term shear modulus"']
    if u.density is not None:
        lines.append(f'rho {_num(u.rho())}[{u.rho_unit}] "density"')
    for i, (gi, ti) in enumerate(zip(m.G, m.tau), 1):
        lines += [f'G_{i} {_num(u.p(gi))}{P} "branch {i} shear modulus"', f'tau_{i} {_num(ti)}[s] "branch {i} relaxation time"']
    params = "\n".join(lines) + "\n"
    # the branch table's Load from File takes no units: COMSOL reads the numbers in the model's
    # unit system (normally SI), so this file is in Pa and s whatever ``units`` says
    si = _Units("SI", u.T_unit, u.density)
    branches = (si.header(m, "%", "COMSOL", fields) + "\n% columns: branch number, shear modulus G_i [Pa], relaxation "
                "time tau_i [s]: always Pa and s, whatever --units (COMSOL's Load from File reads no units, it takes "
                "the numbers in the model's unit system); at T_ref, shift law and bulk modulus in the parameter file\n"
                + "".join(f"{i} {_num(gi)} {_num(ti)}\n" for i, (gi, ti) in enumerate(zip(m.G, m.tau), 1)))
    return params, branches


# ---- verification decks: one element at a step strain, at T_ref and one other temperature --
STRAIN = 0.01          # engineering shear strain of the verification decks' step
RAMP = 1e-2            # the step's rise time, as a share of the first expected time (curves start 100 rises in)


def verification_plan(m: FEMMaterial):
    """What the verification decks run and expect, for the card of ``m`` (T_ref, shift law):
    temperatures (T_ref, T2) in C, T2 the whole degree above T_ref nearest to log10 a_T = -2
    (relaxation 100 times faster, inside the same time axis); the shear strain ``STRAIN`` held
    after a linear rise of ``t_rise`` (s); and ``times`` (s, 5 a decade from 100 rises to 10
    times the longest a_T tau_i): the expected shear stress at T is STRAIN G(t / a_T(T)) (Pa),
    the ideal step response, which the ramp approaches within 0.5 % from 100 rise times on.
    Returns a dict with T, aT, t_rise, t_end, times, stress (2 x len(times), Pa)."""
    if m.iso_T is not None:
        raise ValueError("verification decks check the shift law: an isothermal card has none")
    if m.law == "WLF":
        C1, C2 = m.shift["C1"], m.shift["C2"]
        d = 2.0 * C2 / (C1 - 2.0) if C1 > 2.0 else 20.0
    else:
        Tk = m.T_ref + KELVIN
        d = 1.0 / (1.0 / Tk - 2.0 * LN10 * GAS_CONSTANT / m.shift["Ea"]) - Tk if m.shift["Ea"] > 2 * LN10 * GAS_CONSTANT * Tk else 20.0
    T2 = m.T_ref + max(1.0, float(round(d)))
    T = (m.T_ref, T2)
    aT = tuple(10.0 ** float(m.log10_aT(t)) for t in T)
    t_lo = 0.1 * float(np.min(m.tau)) * min(aT)
    t_end = 10.0 * float(np.max(m.tau)) * max(aT)
    n = int(math.ceil(5 * math.log10(t_end / t_lo))) + 1
    times = np.logspace(math.log10(t_lo), math.log10(t_end), n)
    G = m.series
    stress = np.array([STRAIN * (G.E0 + np.exp(-np.outer(times / a, 1.0 / G.times)) @ G.moduli) for a in aT])
    return {"T": T, "aT": aT, "t_rise": RAMP * t_lo, "t_end": t_end, "times": times, "stress": stress}


# one unit cube per temperature: nodes 1-4 at z = 0, 5-8 at z = 1 (the second cube 10 further
# in node numbers and 2 in x); simple shear u_x = gamma z, all other motion held: sigma_xz = G gamma
_CUBE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]


def _nodes(k):
    return [(10 * k + i + 1, x + 2.0 * k, y, z) for i, (x, y, z) in enumerate(_CUBE)]


def _lsdyna_deck(m: FEMMaterial, u: _Units, card: str) -> str:
    p = verification_plan(m)
    T = [u.T(t) for t in p["T"]]
    tr, te = p["t_rise"], p["t_end"]
    g = lambda *v: ", ".join(_num(x) if not isinstance(x, int) else str(x) for x in v)  # noqa: E731
    lines = ["*KEYWORD",
             f"$ vjax {_version()}: one-element verification of {card} (LS-DYNA *MAT_GENERAL_VISCOELASTIC)",
             f"$ Two unit cubes (one solid element each), each held at one temperature: element 1 at T_ref = {T[0]:g}"
             f" {u.T_unit}, element 2 at {T[1]:g} {u.T_unit} (log10 a_T = {math.log10(p['aT'][1]):.6g} by the fit).",
             f"$ Simple shear u_x = {STRAIN:g} z, raised linearly over {tr:.6g} s and held to {te:.6g} s; all other "
             "motion held, so sigma_zx = G(t/a_T) * gamma.",
             "$ Expected sigma_zx (curves 101: element 1, 102: element 2; stress in the card's unit, time s) is",
             "$ the fitted material's: STRAIN * G(t / a_T(T)). Compare with the elements' zx stress (elout): a",
             "$ curve 102 that relaxes 100 times SLOWER than 101 instead of faster means the sign of A is read",
             "$ the other way; a factor ln 10 off in the shift means the base. Run implicit (static) as written.",
             "*TITLE", f"vjax verification of {card}",
             "*INCLUDE", card,
             "*CONTROL_TERMINATION", "$ ENDTIM", g(te),
             "*CONTROL_IMPLICIT_GENERAL", "$ IMFLAG, DT0", g(1, tr / 10),
             "*CONTROL_IMPLICIT_AUTO", "$ IAUTO, ITEOPT, ITEWIN, DTMIN, DTMAX (< 0: curve 2, about t/10)",
             g(1, 11, 5, tr / 1000, -2),
             "*DATABASE_ELOUT", "$ DT, BINARY, LCUR (curve 3: an output about every t/20)", g(te / 20, 1, 3),
             "*DATABASE_HISTORY_SOLID", "$ element ids", g(1, 2),
             "*SECTION_SOLID", "$ SECID, ELFORM (1: constant stress)", g(1, 1),
             "*PART", "vjax verification element", "$ PID, SECID, MID (the card's MID)", g(1, 1, 1),
             "*NODE", "$ NID, X, Y, Z"]
    lines += [g(n, float(x), float(y), float(z)) for k in (0, 1) for n, x, y, z in _nodes(k)]
    lines += ["*ELEMENT_SOLID", "$ EID, PID, N1..N8"]
    lines += [g(k + 1, 1, *[n for n, *_ in _nodes(k)]) for k in (0, 1)]
    lines += ["*LOAD_THERMAL_CONSTANT_NODE", "$ NID, T, TE"]
    lines += [g(n, T[k], 0.0) for k in (0, 1) for n, *_ in _nodes(k)]
    lines += ["*BOUNDARY_SPC_NODE", "$ NID, CID, DOFX, DOFY, DOFZ, DOFRX, DOFRY, DOFRZ"]
    lines += [g(n, 0, int(z == 0), 1, 1, 0, 0, 0) for k in (0, 1) for n, x, y, z in _nodes(k)]
    lines += ["*BOUNDARY_PRESCRIBED_MOTION_NODE", "$ NID, DOF, VAD (2: displacement), LCID, SF (= gamma at z = 1)"]
    lines += [g(n, 1, 2, 1, STRAIN) for k in (0, 1) for n, x, y, z in _nodes(k) if z == 1]
    curve = lambda lcid, title, pts: (["*DEFINE_CURVE_TITLE", title, "$ LCID, SIDR, SFA, SFO", g(lcid, 0, 1.0, 1.0)]  # noqa: E731
                                      + [g(a, o) for a, o in pts])
    lines += curve(1, "step: linear rise, then held", [(0.0, 0.0), (tr, 1.0), (te, 1.0)])
    lines += curve(2, "largest implicit time step (s) against time", [(0.0, tr / 10), (te, te / 10)])
    lines += curve(3, "output interval (s) against time", [(0.0, tr / 10), (te, te / 20)])
    for k in (0, 1):
        lines += curve(101 + k, f"expected sigma_zx ({u.stress}) of element {k + 1} at {T[k]:g} {u.T_unit}",
                       [(t, u.p(sv)) for t, sv in zip(p["times"], p["stress"][k])])
    lines.append("*END")
    return "\n".join(lines) + "\n"


def _ansys_deck(m: FEMMaterial, u: _Units, card: str) -> str:
    p = verification_plan(m)
    T = [u.T(t) for t in p["T"]]
    tr, te = p["t_rise"], p["t_end"]
    stem = os.path.splitext(card)[0]
    # load steps: the rise (10 substeps), then one a decade to t_end (5 substeps each)
    ends = [tr] + [10.0 ** k for k in range(math.floor(math.log10(tr)) + 1, math.ceil(math.log10(te)))] + [te]
    lines = [f"! vjax {_version()}: one-element verification of {card} (ANSYS Mechanical APDL)",
             f"! Two unit cubes (SOLID185, one element each): element 1 at T_ref = {T[0]:g} {u.T_unit}, element 2 at "
             f"{T[1]:g} {u.T_unit} (log10 a_T = {math.log10(p['aT'][1]):.6g} by the fit).",
             f"! Simple shear UX = {STRAIN:g} z, raised over {tr:.6g} s and held to {te:.6g} s, all other motion held: "
             "SXZ = G(t/a_T) * gamma.",
             f"! The computed SXZ of both elements is written by *VWRITE to {stem}_verify_computed.txt (time, element",
             "! 1, element 2); compare with the EXPECTED table below (the fitted material's STRAIN * G(t / a_T(T)),",
             f"! stress in {u.stress}). Element 2 relaxing 100 times SLOWER than element 1 instead of faster means",
             "! the shift is read the other way; a factor ln 10 off means its base.",
             "FINISH", "/CLEAR,NOSTART", "/PREP7", f"/INPUT,'{stem}','{os.path.splitext(card)[1][1:]}'",
             "ET,1,SOLID185", "MAT,1", "TYPE,1"]
    lines += [f"N,{n},{_num(x)},{_num(y)},{_num(z)}" for k in (0, 1) for n, x, y, z in _nodes(k)]
    lines += ["E," + ",".join(str(n) for n, *_ in _nodes(k)) for k in (0, 1)]
    lines += [f"BF,{n},TEMP,{_num(T[k])}" for k in (0, 1) for n, *_ in _nodes(k)]
    lines += ["FINISH", "/SOLU", "ANTYPE,STATIC", "NLGEOM,OFF", "AUTOTS,OFF", "OUTRES,ALL,ALL"]
    lines += [f"D,{n},UY,0" for k in (0, 1) for n, *_ in _nodes(k)]
    lines += [f"D,{n},UZ,0" for k in (0, 1) for n, *_ in _nodes(k)]
    lines += [f"D,{n},UX,{_num(STRAIN * z)}" for k in (0, 1) for n, x, y, z in _nodes(k)]
    nsets = 0
    for i, t in enumerate(ends):
        sub = 10 if i == 0 else 5
        nsets += sub
        lines += [f"TIME,{_num(t)}", f"NSUBST,{sub},{sub},{sub}", "KBC,0" if i == 0 else "KBC,1", "SOLVE"]
    lines += ["FINISH", "/POST26", "NUMVAR,10", "ESOL,2,1,5,S,XZ,SXZ_1", "ESOL,3,2,15,S,XZ,SXZ_2",
              f"*DIM,RES,ARRAY,{nsets},3", "VGET,RES(1,1),1", "VGET,RES(1,2),2", "VGET,RES(1,3),3",
              f"*CFOPEN,{stem}_verify_computed,txt", "*VWRITE,RES(1,1),RES(1,2),RES(1,3)", "(3E20.10)",
              "*CFCLOS", "FINISH",
              f"! EXPECTED: time (s), SXZ of element 1 at {T[0]:g} {u.T_unit}, SXZ of element 2 at {T[1]:g} "
              f"{u.T_unit} ({u.stress})"]
    lines += [f"! {t:.10e} {u.p(a):.10e} {u.p(b):.10e}" for t, a, b in zip(p["times"], *p["stress"])]
    return "\n".join(lines) + "\n"


DECKS = {"lsdyna": _lsdyna_deck, "ansys": _ansys_deck}


def render(m: FEMMaterial, fmt: str, units: str = "SI", temperature: str | None = None, name: str = "VJAX",
           density=None):
    """The text of one export (for ``comsol``: a (parameters, branches) pair) of the series
    ``m`` as it is (:func:`prepare` chooses the terms). ``temperature`` ('K' or 'C') is
    required; ``density`` in kg/m^3 (required by LS-DYNA)."""
    u = _Units(units, temperature, density)
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


def file_name(stem: str, fmt: str, temperature: str, isothermal=None) -> tuple:
    """The file names of one format: ``<stem>_<code>_<K|degC><extension>`` (COMSOL: the
    parameter and the branch file); an isothermal card adds ``_iso<T>`` (T in the file's
    scale)."""
    ext = EXTENSION[fmt] if isinstance(EXTENSION[fmt], tuple) else (EXTENSION[fmt],)
    iso = "" if isothermal is None else f"_iso{float(isothermal):g}"
    return tuple(f"{stem}_{fmt}_{TEMPERATURES[temperature]}{iso}{e}" for e in ext)


def deck_name(stem: str, fmt: str, temperature: str) -> str:
    """The verification deck written beside a card: ``<stem>_<code>_<K|degC>_verify<ext>``."""
    return f"{stem}_{fmt}_{TEMPERATURES[temperature]}_verify{EXTENSION[fmt]}"


class ExportRefused(ValueError):
    """Some codes of an export were refused: ``refused`` maps each to its reason; ``written``
    lists the files of the others (written whole)."""

    def __init__(self, refused: dict, written: list):
        self.refused, self.written = refused, written
        super().__init__("; ".join(f"{code}: {why}" for code, why in refused.items()))


def export(m: FEMMaterial, formats, out_dir, stem, units="SI", temperature=None, max_terms=None, *, density=None,
           terms="compact", window=None, messages=None, isothermal=None) -> list:
    """Write the files of ``formats`` (names of :data:`FORMATS`) as
    ``<out_dir>/<stem>_<code>_<K|degC>...`` atomically; returns the paths. A code's files are
    all rendered before any is written, so a refused code leaves nothing of its own behind; the
    other codes are written all the same, and :class:`ExportRefused` then names each refused
    code with its reason (``written``: the files of the others).

    ``temperature``: 'K' or 'C', required (the scale of every temperature in the files).
    ``density``: kg/m^3 (LS-DYNA refuses without it). ``terms``, ``max_terms``, ``window``
    ((t_min, t_max) s at T_ref, for codes with a card limit): see :func:`prepare`.
    ``isothermal``: a temperature in the files' scale: every card at that one temperature
    (relaxation times a_T tau_i, no shift fields; :func:`isothermal`), named ``..._iso<T>``.
    Otherwise LS-DYNA and ANSYS also get a one-element verification deck beside the card
    (:func:`deck_name`; :func:`verification_plan`).
    ``messages``: a list that gets the choices made (term counts, refits, accuracy)."""
    u = _Units(units, temperature, density)          # refuse a missing scale before any fitting
    if not os.path.isdir(out_dir):
        raise ValueError(f"output directory {out_dir!r} does not exist")
    fmts = parse_formats(formats)
    T_iso = None
    if isothermal is not None:
        T_iso = float(isothermal) - (KELVIN if temperature == "K" else 0.0)
        if not math.isfinite(T_iso) or T_iso <= -KELVIN:
            raise ValueError(f"--isothermal must be a temperature above absolute zero, got {isothermal!r} "
                             f"({temperature})")
    texts, base, refused = [], None, {}
    for fmt in fmts:
        try:
            if fmt in CARD_LIMIT:       # the full series if it fits, else its refit to the limit
                series = prepare(m, "full", None, window, CARD_LIMIT[fmt], messages)
            else:
                base = base or prepare(m, terms, max_terms, window, messages=messages)
                series = base
            if T_iso is not None:
                series = isothermal_card(series, T_iso)
            text = render(series, fmt, u.name, temperature, name=stem.upper().replace(" ", "_") or "VJAX",
                          density=density)
            parts = text if isinstance(text, tuple) else (text,)
            names = file_name(stem, fmt, temperature, isothermal)
            own = [(os.path.join(out_dir, n), t) for n, t in zip(names, parts)]
            if fmt in DECKS and T_iso is None:
                own.append((os.path.join(out_dir, deck_name(stem, fmt, temperature)), DECKS[fmt](series, u, names[0])))
        except ValueError as e:
            refused[fmt] = str(e)
            continue
        texts += own
    written = [os.fspath(p) for p in files.write_all_atomic(texts)] if texts else []
    if refused:
        raise ExportRefused(refused, written)
    return written


# ---- reading a card back: each code's documented formula -----------------------------------
@dataclasses.dataclass(frozen=True)
class Card:
    """A card evaluated by its code's formula (:func:`evaluate_card`): ``code``, ``terms``,
    ``K`` (Pa), ``G(t)`` (Pa, t in s at T_ref), ``log10_aT(T)`` (T in C) and
    ``temperature`` (the file's scale)."""

    code: str
    terms: int
    K: float
    G: object
    log10_aT: object
    temperature: str


def _header_units(text, path):
    m = re.search(r"units: stress (\w+), time s, temperature (K|C)", text)
    if not m:
        raise ValueError(f"{path}: no 'units: stress ..., temperature ...' header line: cannot tell the units")
    return {"Pa": 1.0, "MPa": 1e6}[m.group(1)], m.group(2)


def evaluate_card(path) -> Card:
    """G(t), K and log10 a_T(T) of a card written by :func:`export` (and perhaps edited since),
    by its code's documented formula (module docstring): a round trip for checking a card.
    The code is told by the file name; units and temperature scale by the header line
    ``units: ...`` (the LS-DYNA and Abaqus keywords carry none)."""
    path = os.fspath(path)
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    to_pa, T_unit = _header_units(text, path)
    Tfile = (lambda Tc: np.asarray(Tc, float) + (KELVIN if T_unit == "K" else 0.0))
    name = os.path.basename(path)
    prony = lambda g_inf, g, tau: (lambda t: g_inf + np.sum(  # noqa: E731
        g * np.exp(-np.asarray(t, float)[..., None] / tau), axis=-1))
    if name.endswith(".inp"):
        blocks, key, consts = {}, None, {}
        for line in (l.strip() for l in text.splitlines()):
            if re.match(r"(\*\*\s*)?\*PHYSICAL\s*CONSTANTS", line, re.I):     # as written, or un-commented
                consts = {re.sub(r"\s+", " ", k.strip().upper()): float(v)
                          for k, v in re.findall(r"([A-Za-z ]+)=\s*([-+0-9.eE]+)", line.split(",", 1)[-1])}
            elif line.startswith("*") and not line.startswith("**"):
                key = line.upper().replace(" ", "")
                blocks[key] = []
            elif line and not line.startswith("**"):
                blocks[key].append([float(v) for v in line.split(",") if v.strip()])
        (E, nu), = blocks["*ELASTIC,MODULI=INSTANTANEOUS"]
        G0, K = E / tensile_over_shear(nu) * to_pa, E / (3 * (1 - 2 * nu)) * to_pa
        g, _, tau = np.array(blocks["*VISCOELASTIC,TIME=PRONY"]).T
        G = prony(G0 * (1 - g.sum()), G0 * g, tau)
        if not any(k.startswith("*TRS") for k in blocks):        # isothermal: no shift
            la = lambda T: np.zeros_like(np.asarray(T, float))  # noqa: E731
        elif "*TRS,DEFINITION=WLF" in blocks:
            (th0, C1, C2), = blocks["*TRS,DEFINITION=WLF"]
            la = lambda T: -C1 * (Tfile(T) - th0) / (C2 + Tfile(T) - th0)  # noqa: E731
        else:
            (th0, E0), = blocks["*TRS,DEFINITION=ARRHENIUS"]
            if not {"ABSOLUTE ZERO", "UNIVERSAL GAS CONSTANT"} <= set(consts):
                raise ValueError(f"{path}: Arrhenius *TRS needs *PHYSICAL CONSTANTS, ABSOLUTE ZERO=..., "
                                 "UNIVERSAL GAS CONSTANT=...")
            z, R = consts["ABSOLUTE ZERO"], consts["UNIVERSAL GAS CONSTANT"]
            la = lambda T: E0 / R * (1 / (Tfile(T) - z) - 1 / (th0 - z)) / LN10  # noqa: E731
        return Card("abaqus", len(tau), K, G, la, T_unit)
    if name.endswith(".mac"):
        mp, tables, cur, toff = {}, {}, None, 0.0
        for line in text.splitlines():
            f = [v.strip() for v in line.split("!")[0].split(",")]
            cmd = f[0].upper()
            if cmd == "MP":
                mp[f[1].upper()] = float(f[3])
            elif cmd == "TB":
                cur = (f[1].upper(), f[5].upper())
                tables[cur] = {}
            elif cmd == "TBDATA":
                tables[cur].update({int(f[1]) + i: float(v) for i, v in enumerate(f[2:])})
            elif cmd == "TOFFST":
                toff = float(f[1])
        E, nu = mp["EX"], mp["NUXY"]
        G0, K = E / tensile_over_shear(nu) * to_pa, E / (3 * (1 - 2 * nu)) * to_pa
        v = np.array([tables[("PRONY", "SHEAR")][i] for i in sorted(tables[("PRONY", "SHEAR")])])
        a, tau = v[0::2], v[1::2]
        G = prony(G0 * (1 - a.sum()), G0 * a, tau)
        if not any(k[0] == "SHIFT" for k in tables):              # isothermal: no shift
            la = lambda T: np.zeros_like(np.asarray(T, float))  # noqa: E731
        elif ("SHIFT", "WLF") in tables:
            s = tables[("SHIFT", "WLF")]
            la = lambda T: -s[2] * (Tfile(T) - s[1]) / (s[3] + Tfile(T) - s[1])  # noqa: E731
        else:
            s = tables[("SHIFT", "TN")]
            la = lambda T: s[2] * (1 / (Tfile(T) + toff) - 1 / (s[1] + toff)) / LN10  # noqa: E731
        return Card("ansys", len(tau), K, G, la, T_unit)
    if name.endswith(".k"):
        lines = text.splitlines()
        i = next(j for j, l in enumerate(lines) if l.upper().startswith("*MAT_GENERAL_VISCOELASTIC"))
        width = 20 if lines[i].rstrip().endswith("+") else 10
        cards = []
        for l in lines[i + 1:]:
            if l.startswith("*"):
                break
            if not l.startswith("$") and l.strip():
                cards.append([float(l[j:j + width]) if l[j:j + width].strip() else 0.0 for j in range(0, len(l), width)])
        K, TREF, A, B = cards[0][2] * to_pa, cards[0][5], cards[0][6], cards[0][7]
        terms = np.array([c + [0.0] * (4 - len(c)) for c in cards[2:]])
        G = lambda t: to_pa * np.sum(terms[:, 0] * np.exp(-np.asarray(t, float)[..., None] * terms[:, 1]), axis=-1)  # noqa: E731
        if B != 0:     # log10 a_T = -ln Phi / ln 10
            la = lambda T: A * (Tfile(T) - TREF) / (B + Tfile(T) - TREF) / LN10  # noqa: E731
        else:
            la = lambda T: A * (1 / Tfile(T) - 1 / TREF) / LN10  # noqa: E731
        return Card("lsdyna", int(np.count_nonzero(terms[:, 1])), K, G, la, T_unit)
    if name.endswith("_parameters.txt"):
        p, units = {}, {"": 1.0, "Pa": 1.0, "MPa": 1e6, "s": 1.0, "K": 1.0, "J/mol": 1.0, "mJ/mol": 1e-3,
                        "kg/m^3": 1.0, "t/mm^3": 1e12}
        for line in text.splitlines():
            q = re.match(r'^(\w+) ([-+0-9.eE]+)(?:\[([^\]]*)\])? "', line)
            if q:
                v, un = float(q.group(2)), q.group(3) or ""
                if un != "degC" and un not in units:
                    raise ValueError(f"{path}: unit {un!r} of {q.group(1)} is not one vjax-export writes "
                                     f"({', '.join(u for u in units if u)} or degC): cannot evaluate the card")
                p[q.group(1)] = v + KELVIN if un == "degC" else v * units[un]
        n = sum(1 for k in p if re.fullmatch(r"G_\d+", k))
        g = np.array([p[f"G_{i}"] for i in range(1, n + 1)])
        tau = np.array([p[f"tau_{i}"] for i in range(1, n + 1)])
        Tk = lambda T: np.asarray(T, float) + KELVIN  # noqa: E731
        if "C1" not in p and "Q" not in p:                        # isothermal: no shift
            la = lambda T: np.zeros_like(np.asarray(T, float))  # noqa: E731
        elif "C1" in p:
            la = lambda T: -p["C1"] * (Tk(T) - p["T_ref"]) / (p["C2"] + Tk(T) - p["T_ref"])  # noqa: E731
        else:
            la = lambda T: p["Q"] / GAS_CONSTANT * (1 / Tk(T) - 1 / p["T_ref"]) / LN10  # noqa: E731
        return Card("comsol", n, p["K_bulk"], prony(p["G_inf"], g, tau), la, T_unit)
    raise ValueError(f"{path}: not a card of vjax-export (expected .inp, .mac, .k or _parameters.txt)")
