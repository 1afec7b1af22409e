"""Refine a Prony material and its WLF shift against measured bearing friction torque.

Data: torque-versus-speed curves of a bearing, as a CSV (:func:`read_torque_csv`)::

    # comment lines start with '#'
    speed_rpm, temperature_C, load_N_per_m, torque_Nm_per_m[, scatter_Nm_per_m]

``speed_rpm`` is the shaft (inner ring or pin) speed in rev/min, > 0; ``temperature_C`` in
C; ``load_N_per_m`` the radial load per unit axial length (N/m), > 0; ``torque_Nm_per_m``
the friction torque per unit length (N m/m); the optional ``scatter`` column is the
standard deviation of each torque (same unit, > 0). Columns are matched by name
(case-insensitive, units in the name optional: ``rpm``, ``speed``, ``T``, ``temperature``,
``load``, ``F``, ``torque``, ``scatter``, ``sigma``, ``std``).

Model: a bearing scene evaluated at each point with the material at the point's
temperature (:meth:`vjax.Material.at_temperature`): :func:`roller_model` (needle roller
bearing, torque on the fixed outer ring), :func:`pin_model` (a polymer pin joint: rigid
pin turning in a viscoelastic plate) or :func:`journal_model` (a finite lubricated journal
bearing with a liner of the material; the CSV's load and torque are then the rig's totals
divided by the bearing's length). The scenes carry implicit derivatives, so the
gradient of the torque with respect to the material is one linear solve per solve at the
converged state, not a differentiation through iterations.

Parameters (:class:`Params`): log E0, log E_k, optionally log tau_k, log C1, log C2, and
optionally scene parameters (``extras``): mixed lubrication's boundary friction coefficient
mu_b and composite rms roughness sigma (a :func:`journal_model` with ``roughness=``, torque
along a Stribeck curve through lift-off), or the rig's heat transfer hA (a model with
``heat_transfer=``: the scene at the effective temperature its own dissipation sets, the
data's T the supply/ambient temperature). The fit works on the logarithms: positivity is
automatic and a step means the same relative change for a 1e9 Pa modulus and a C1 of 20.

Objective (dimensionless, a chi^2 per torque point)::

    loss = (1/N_t) [ sum_i ((T_model,i - T_i) / s_i)^2 + w_dma sum_j (r_j / s_dma)^2 ]

with r_j the log10 residuals of the storage and loss moduli on raw DMA points (the material
stays consistent with its DMA; ``w_dma = 0`` fits the torque only), s_i the torque scatter
(or ``rel_scatter`` times the torque when the file has none) and s_dma the DMA scatter in
decades.

Optimizer: optax Adam on the log-parameters, then a Levenberg-Marquardt polish. Why Adam:
the parameters span 10+ decades in value and their torque sensitivities span several more
(a relaxation time far outside the tested frequencies has almost none); Adam's
per-parameter step normalization makes the step a relative change of roughly the learning
rate for every parameter, whatever its scale, and it is robust far from the optimum, where
a Gauss-Newton model of a nearly singular J^T J (exactly what the torque data give, see the
identifiability report) is poor. Near the optimum Adam crawls along the valley; a few
Marquardt-scaled Levenberg-Marquardt steps on the same Jacobian then reach the noise floor
(noise-free pin data in the tests: loss 0.70 after 40 Adam steps, 6e-26 after 20 more LM
steps). optax rather than jaxopt: jaxopt is unmaintained. The Jacobian (forward mode through the
implicit derivatives, one compiled function that returns residuals and Jacobian together)
gives both the gradient 2 J^T r / N_t and, at the end, the Gauss-Newton covariance
(J^T J)^-1 and the singular values that say which parameters the torque cannot identify.
"""
from __future__ import annotations

import csv
import dataclasses
import math
import sys
import time

import jax
import jax.numpy as jnp
import numpy as np

import vjax
from vjax import Material, WLF

from . import optim

__all__ = ["TorqueData", "TorqueFormatError", "read_torque_csv", "write_torque_csv", "roller_model", "pin_model",
           "journal_model", "water_viscosity", "evaluate",
           "Params", "TorqueFit", "fit_torque", "residual_jacobian", "identifiability", "gauss_newton_cov",
           "gradient_check"]


# ---- data ------------------------------------------------------------------------------
class TorqueFormatError(ValueError):
    """A torque CSV that cannot be used; the message names the file, the line and the problem."""

    def __init__(self, path, line, problem):
        where = f"{path}" + (f", line {line}" if line else "")
        super().__init__(f"{where}: {problem}")


@dataclasses.dataclass(frozen=True)
class TorqueData:
    """Torque points: rpm (rev/min), T (C), load (N/m), torque (N m/m), scatter (N m/m or None)."""

    rpm: np.ndarray
    T: np.ndarray
    load: np.ndarray
    torque: np.ndarray
    scatter: np.ndarray | None = None
    source: str = "arrays"

    def __len__(self) -> int:
        return len(self.rpm)

    @property
    def omega(self):
        """Shaft angular speed (rad/s)."""
        return self.rpm * (2 * math.pi / 60.0)

    def sigma(self, rel_scatter=0.05):
        """Per-point standard deviation: the scatter column, else rel_scatter * |torque|."""
        if self.scatter is not None:
            return self.scatter
        return rel_scatter * np.maximum(np.abs(self.torque), 1e-300)

    def conditions(self):
        """Distinct (T, load) pairs, in order of appearance."""
        seen = []
        for t, f in zip(self.T, self.load):
            if (t, f) not in seen:
                seen.append((t, f))
        return seen


_ALIASES = {
    "rpm": ("speed_rpm", "rpm", "speed", "shaft_speed", "n_rpm", "shaft_speed_rpm"),
    "T": ("temperature_c", "temperature", "t", "t_c", "temp", "temp_c"),
    "load": ("load_n_per_m", "load", "f", "force", "load_n/m", "f_n_per_m"),
    "torque": ("torque_nm_per_m", "torque", "c_t", "torque_n_m_per_m", "torque_nm/m"),
    "scatter": ("scatter_nm_per_m", "scatter", "sigma", "std", "torque_std", "scatter_n_m_per_m"),
}


def _canon(name: str):
    key = name.strip().lower().replace(" ", "_").replace("[", "_").replace("]", "").replace("(", "_") \
        .replace(")", "").strip("_")
    while "__" in key:
        key = key.replace("__", "_")
    for canon, names in _ALIASES.items():
        if key in names:
            return canon
    return None


def read_torque_csv(path) -> TorqueData:
    """Read a torque CSV (module docstring); raises :class:`TorqueFormatError` naming the
    file and line for: an empty file, missing or duplicated columns, non-numeric or
    non-finite values, speed or load <= 0, scatter <= 0, or a curve with a repeated speed."""
    path = str(path)
    try:
        with open(path, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except OSError as e:
        raise TorqueFormatError(path, None, f"cannot read ({e.strerror})") from None
    body = [(i + 1, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    if not body:
        raise TorqueFormatError(path, None, "no header and no data (empty file or only comments)")
    hline, header = body[0]
    names = [h.strip() for h in next(csv.reader([header]))]
    cols = {}
    for j, h in enumerate(names):
        c = _canon(h)
        if c is None:
            continue
        if c in cols:
            raise TorqueFormatError(path, hline, f"two columns mean {c!r}: {names[cols[c]]!r} and {h!r}")
        cols[c] = j
    missing = [c for c in ("rpm", "T", "load", "torque") if c not in cols]
    if missing:
        want = {"rpm": "speed_rpm", "T": "temperature_C", "load": "load_N_per_m", "torque": "torque_Nm_per_m"}
        raise TorqueFormatError(path, hline, f"missing column(s) {[want[m] for m in missing]}; found {names}")
    rows = {c: [] for c in cols}
    for lineno, ln in body[1:]:
        toks = [t.strip() for t in next(csv.reader([ln]))]
        if len(toks) < len(names):
            raise TorqueFormatError(path, lineno, f"expected {len(names)} values, got {len(toks)}")
        for c, j in cols.items():
            try:
                v = float(toks[j])
            except ValueError:
                raise TorqueFormatError(path, lineno, f"{names[j]!r} is not a number: {toks[j]!r}") from None
            if not math.isfinite(v):
                raise TorqueFormatError(path, lineno, f"{names[j]!r} is not finite: {toks[j]!r}")
            if c in ("rpm", "load", "scatter") and v <= 0:
                raise TorqueFormatError(path, lineno, f"{names[j]!r} must be > 0, got {v!r}")
            rows[c].append(v)
    if not rows["rpm"]:
        raise TorqueFormatError(path, None, "header but no data rows")
    a = {c: np.asarray(v, float) for c, v in rows.items()}
    for t, f in {(t, f) for t, f in zip(a["T"], a["load"])}:
        sel = (a["T"] == t) & (a["load"] == f)
        s = a["rpm"][sel]
        if len(np.unique(s)) != len(s):
            raise TorqueFormatError(path, None, f"repeated speed in the curve at T={t:g} C, load={f:g} N/m")
    return TorqueData(a["rpm"], a["T"], a["load"], a["torque"], a.get("scatter"), source=path)


def write_torque_csv(path, data: TorqueData, comments=()) -> None:
    """Write ``data`` in the format :func:`read_torque_csv` reads (atomically)."""
    from .io import atomic_write
    lines = [f"# {c}" for c in comments]
    head = ["speed_rpm", "temperature_C", "load_N_per_m", "torque_Nm_per_m"]
    if data.scatter is not None:
        head.append("scatter_Nm_per_m")
    lines.append(",".join(head))
    for i in range(len(data)):
        vals = [data.rpm[i], data.T[i], data.load[i], data.torque[i]]
        if data.scatter is not None:
            vals.append(data.scatter[i])
        lines.append(",".join(repr(float(v)) for v in vals))
    atomic_write(path, "\n".join(lines) + "\n")


# ---- bearing models --------------------------------------------------------------------
def roller_model(R_outer=6e-3, R_inner=4e-3, roller_diameter=2e-3, n_rollers=9, n=256, memory="periodic",
                 diametral_clearance=None, heat_transfer=None):
    """Needle roller bearing (:func:`vjax.roller_bearing`), both rings of the fitted material,
    outer ring fixed, shaft (inner ring) at the given rpm; returns the friction torque on the
    outer ring (N m/m, positive). Signature ``model(material, shift, rpm, T, load[, hA=])``.

    ``heat_transfer``: None (isothermal: the rings at the data's T) or hA (W/(m K), per unit
    axial length, > 0; inf is the isothermal limit): the rings at the bulk temperature their own
    hysteresis sets (:func:`vjax.thermal_roller`), cooled by hA to the data's T (then the
    ambient temperature). The model's keyword ``hA`` overrides it (fitting log hA)."""
    options = vjax.RollerOptions(n=n)
    _check_heat(heat_transfer)

    def model(material, shift, rpm, T, load, hA=None):
        kw = dict(omega_shaft=rpm * (2 * jnp.pi / 60.0), diametral_clearance=diametral_clearance, memory=memory,
                  options=options, throw=False)
        material = _with_law(material, shift)
        hA = heat_transfer if hA is None else hA
        if hA is None:
            r = vjax.roller_bearing(material, material, R_outer, R_inner, roller_diameter, n_rollers, load,
                                    temperature=T, **kw)
            return r.torque, r.converged
        t = vjax.thermal_roller(material, material, R_outer, R_inner, roller_diameter, n_rollers, load,
                                vjax.HeatTransfer(T_supply=T, hA=hA, oil_flow=False), **kw)
        return t.scene.torque, t.converged & t.scene.converged
    model.extras = () if heat_transfer is None else ("hA",)
    model.scene = (f"roller_bearing(R_O={R_outer}, R_I={R_inner}, D={roller_diameter}, Z={n_rollers}, n={n}, "
                   f"memory={memory!r}, diametral_clearance={diametral_clearance}"
                   + _heat_text(heat_transfer, "W/(m K)") + ")")
    return model


def _with_law(material, shift):
    """The fitted material with the fitted shift law as its own (the scenes' one material
    state): the data's temperature T then moves it."""
    return material if shift is None else material.with_shift(shift)


def _check_heat(hA):
    if hA is not None and not (isinstance(hA, (int, float)) and hA > 0):
        raise ValueError(f"heat_transfer must be None (isothermal) or a number hA > 0 (inf: the isothermal "
                         f"limit), got {hA!r}")


def _heat_text(hA, unit):
    return "" if hA is None else f", heat: hA={hA:g} {unit} to the data's T"


def pin_model(R=0.01, radial_clearance=1e-4, n=128, memory="periodic", heat_transfer=None):
    """Polymer pin joint (:func:`vjax.pin_in_hole`): rigid pin of radius R - radial_clearance
    turning at the given rpm in a hole of radius R in a plate of the fitted material; returns
    the friction torque (N m/m, positive). Signature ``model(material, shift, rpm, T, load[, hA=])``.

    ``heat_transfer``: None (isothermal at the data's T) or hA (W/(m K), per unit axial length,
    > 0; inf: the isothermal limit): the plate at the bulk temperature its hysteresis sets
    (:func:`vjax.thermal_pin`: -Omega torque = hA (T_eff - T)), the data's T the ambient
    temperature. The model's keyword ``hA`` overrides it (fitting log hA)."""
    options = vjax.PinOptions(n=n)
    _check_heat(heat_transfer)

    def model(material, shift, rpm, T, load, hA=None):
        kw = dict(omega_shaft=rpm * (2 * jnp.pi / 60.0), memory=memory, options=options, throw=False)
        material = _with_law(material, shift)
        hA = heat_transfer if hA is None else hA
        if hA is None:
            r = vjax.pin_in_hole(material, R, radial_clearance, load, temperature=T, **kw)
            return r.torque, r.converged
        t = vjax.thermal_pin(material, R, radial_clearance, load, vjax.HeatTransfer(T_supply=T, hA=hA, oil_flow=False),
                             **kw)
        return t.scene.torque, t.converged & t.scene.converged
    model.extras = () if heat_transfer is None else ("hA",)
    model.scene = (f"pin_in_hole(R={R}, radial_clearance={radial_clearance}, n={n}, memory={memory!r}"
                   + _heat_text(heat_transfer, "W/(m K)") + ")")
    return model


def water_viscosity(T):
    """Dynamic viscosity of water (Pa s) at ``T`` (C), Vogel's equation
    eta = 2.414e-5 * 10^(247.8 / (T + 273.15 - 140)) (1.00e-3 at 20 C, 0.65e-3 at 40 C,
    0.40e-3 at 70 C; within 1 % of IAPWS's from 10 to 100 C): :meth:`Lubricant.water
    <vjax.Lubricant.water>`'s viscosity."""
    from vjax import Lubricant
    return Lubricant.water().viscosity(T)


def oil_viscosity(nu40, nu100, density=860.0, specific_heat=2000.0):
    """The dynamic viscosity (Pa s) of a mineral oil as a function of the temperature T (C):
    Walther's equation (ASTM D341), log10 log10(nu + 0.7) linear in log10 T (K), through the
    oil's kinematic viscosities ``nu40`` and ``nu100`` (cSt = mm^2/s) at 40 and 100 C (its data
    sheet's), times its ``density`` (kg/m^3, held constant). An ISO VG 32 oil of viscosity
    index about 100: ``oil_viscosity(32, 5.4)``, 0.0275 Pa s at 40 C and 0.0096 at 70 C.
    Traceable in T (jit, grad). The function delegates to (and carries as ``.lubricant``) a
    :meth:`Lubricant.walther <vjax.Lubricant.walther>`, with the oil's
    ``specific_heat`` (J/(kg K), default 2000, a mineral oil's) for the thermal balance."""
    from vjax import checks
    from vjax import Lubricant
    for name, v in (("nu40", nu40), ("nu100", nu100), ("density", density), ("specific_heat", specific_heat)):
        checks.positive(name, v)
    if not nu100 < nu40:
        raise ValueError(f"nu100 must be below nu40 (an oil thins when heated), got nu40={nu40}, nu100={nu100}")
    lubricant = Lubricant.walther(nu40, nu100, 40.0, 100.0, rho=density, c_p=specific_heat)

    def viscosity(T):
        return lubricant.viscosity(T)
    viscosity.__name__ = f"oil_viscosity({nu40:g}, {nu100:g}, {density:g})"
    viscosity.lubricant = lubricant
    return viscosity


_TURNING = ("liner", "shaft")


def journal_model(R=0.025, radial_clearance=5e-5, length=0.05, thickness=0.01, viscosity=water_viscosity,
                  turning="liner", n=32, m=8, memory="periodic", roughness=None, heat_transfer=None,
                  supply_angle=math.pi):
    """Finite journal bearing with a liner of the fitted material (:func:`vjax.journal_bearing`
    with ``length=``, housing :func:`vjax.liner`): bore radius ``R``, ``radial_clearance``,
    axial ``length``, liner ``thickness`` (m) bonded in a rigid housing, rigid shaft, axial
    groove at ambient pressure at ``supply_angle`` from the load (default opposite it; None: no
    groove), Reynolds cavitation, ``n`` x ``m`` film cells.

    Units: the CSV (and so ``load`` and the returned torque) are per unit axial length, as for
    the other scenes: a rig's total load (N) and total friction torque (N m) divided by
    ``length``. The model multiplies the load by ``length`` for the bearing and divides the
    bearing's total torque by it.

    ``viscosity``: the lubricant's viscosity (Pa s), a number (held fixed), a function of the
    temperature (C) (default :func:`water_viscosity`: a water-lubricated bearing; an oil's:
    :func:`oil_viscosity`) or a :class:`vjax.Lubricant`.

    ``turning``: which side turns at the given rpm; the friction torque returned is the one on
    the stationary side (what a torque arm on it measures), positive in the sense of rotation.
    "liner" (default): the lined housing turns on a fixed shaft (a lined wheel, roller or pulley
    on an axle); the film's pressure, fixed in space, travels round the liner, which answers with
    its modulus at the passing frequencies (the Prony terms and the shift law). "shaft": the shaft
    turns in a fixed lined housing; the liner then carries a pressure field at rest, its steady
    response is the relaxed one (E0 alone), and the torque carries no information about the
    Prony terms or the shift law (their torque derivatives are exactly zero) - use it to fit E0
    only.

    ``roughness``: a :class:`vjax.Roughness` (mixed lubrication: Patir-Cheng flow factors,
    Greenwood-Tripp asperities, boundary friction ``mu_b``; its ``Vr`` is -1 for a rough bore
    (the liner) and a smooth shaft whichever side turns): the torque follows the Stribeck curve
    through lift-off. The model's keywords ``mu_b`` and ``sigma`` (m) replace
    the roughness's (fitting them; E', eta_s beta sigma and sigma/beta stay as given).

    ``heat_transfer``: None (isothermal: film and liner at the data's T) or hA (W/K, > 0; inf:
    the isothermal limit): the bearing at its effective temperature
    (:func:`vjax.thermal_journal_bearing`, ISO 7902's balance): the data's T is then the supply
    (and ambient) temperature, the heat leaves with the side leakage (when the lubricant has a
    density and specific heat: :func:`oil_viscosity`, :meth:`vjax.Lubricant.water`) and through
    hA. The model's keyword ``hA`` overrides it (fitting log hA). With ``roughness`` too, the
    asperities' boundary friction heats the bearing as well.

    Signature ``model(material, shift, rpm, T, load, **extras)``, ``model.extras`` the names
    of the keywords it takes ("mu_b", "sigma" with a roughness; "hA" with a heat transfer)."""
    from vjax import checks
    for name, v in (("R", R), ("radial_clearance", radial_clearance), ("length", length),
                    ("thickness", thickness)):
        checks.positive(name, v)
    if not radial_clearance < R:
        raise ValueError(f"radial_clearance must be < R, got {radial_clearance} >= {R}")
    checks.one_of("turning", turning, _TURNING)
    if not callable(viscosity):
        checks.positive("viscosity", viscosity)
    if roughness is not None and not isinstance(roughness, vjax.Roughness):
        raise ValueError(f"roughness must be a vjax.Roughness or None, got {type(roughness).__name__}")
    _check_heat(heat_transfer)
    lubricant = _lubricant(viscosity) if heat_transfer is not None else None
    eta = viscosity if callable(viscosity) else (lambda T, v=float(viscosity): v)
    options = vjax.FiniteJournalOptions(n=n, m=m)

    def model(material, shift, rpm, T, load, mu_b=None, sigma=None, hA=None):
        w = rpm * (2 * jnp.pi / 60.0)
        speeds = dict(omega_housing=w) if turning == "liner" else dict(omega_shaft=w)
        kw = dict(length=length, housing=vjax.liner(_with_law(material, shift), thickness), memory=memory,
                  options=options, throw=False, supply_angle=supply_angle, **speeds)
        hA = heat_transfer if hA is None else hA
        rough = roughness
        if rough is not None and (mu_b is not None or sigma is not None):
            rough = dataclasses.replace(rough, **({} if mu_b is None else dict(mu_b=mu_b)),
                                        **({} if sigma is None else dict(sigma=sigma)))
        if hA is not None:
            heat = vjax.HeatTransfer(T_supply=T, hA=hA, oil_flow=lubricant.c_p is not None)
            t = vjax.thermal_journal_bearing(R, radial_clearance, lubricant, load * length, heat, roughness=rough, **kw)
            r, ok = t.scene, t.converged & t.scene.converged
        else:
            r = vjax.journal_bearing(R, radial_clearance, eta(T), load * length, temperature=T, roughness=rough, **kw)
            ok = r.converged
        # the stationary side: the shaft when the liner turns, the housing when the shaft does
        tq = r.torque_shaft if turning == "liner" else r.torque
        return tq / length, ok
    model.sequential = True       # the soft liner's solve falls back on continuation: no vmap over points
    model.extras = (("mu_b", "sigma") if roughness is not None else ()) + (("hA",) if heat_transfer is not None else ())
    visc = getattr(viscosity, "__name__", None) if callable(viscosity) else viscosity
    if isinstance(viscosity, vjax.Lubricant):
        visc = viscosity.name or viscosity.law
    rough_text = "" if roughness is None else (f", roughness: sigma={float(roughness.sigma):.4g} m, "
                                               f"mu_b={float(roughness.mu_b):.4g}, E'={float(roughness.E):.4g} Pa")
    model.scene = (f"journal_bearing(R={R}, radial_clearance={radial_clearance}, length={length}, liner "
                   f"thickness={thickness}, viscosity={visc}, turning={turning!r}, n={n}, m={m}, memory={memory!r}"
                   f"{rough_text}{_heat_text(heat_transfer, 'W/K')})")
    return model


def _lubricant(viscosity):
    """The :class:`vjax.Lubricant` behind ``viscosity`` for the thermal balance: itself, an
    :func:`oil_viscosity`'s, water's for :func:`water_viscosity`, a constant one for a number
    (no heat carried by the oil then: hA alone)."""
    from vjax import Lubricant
    if isinstance(viscosity, Lubricant):
        return viscosity
    if getattr(viscosity, "lubricant", None) is not None:
        return viscosity.lubricant
    if viscosity is water_viscosity:
        return Lubricant.water()
    if callable(viscosity):
        return Lubricant.from_function(viscosity)
    return Lubricant.constant(float(viscosity))


# ---- parameters ------------------------------------------------------------------------
# the scene parameters a model may take as keywords, fitted on their logarithms: mixed
# lubrication's boundary friction coefficient and composite rms roughness (m); the rig's heat
# transfer coefficient times area (W/K for the journal, W/(m K) for the pin and roller)
EXTRAS = ("mu_b", "sigma", "hA")


@dataclasses.dataclass(frozen=True)
class Params:
    """Log-parametrization of a Prony material + WLF shift, and of scene parameters.

    x = [log E0, log E_1..E_K, (log tau_1..tau_K if fit_times), log C1, log C2, log extras...];
    T_ref and nu are fixed; ``extras`` names scene parameters of :data:`EXTRAS` fitted with the
    material ("mu_b", "sigma" of a rough journal model; "hA" of a thermal model), passed to the
    model as keywords. :meth:`unpack` builds the material and shift from x inside jit (no
    checks), :meth:`unpack_extras` the keywords.
    """

    K: int
    fit_times: bool
    times: np.ndarray
    nu: float
    T_ref: float
    extras: tuple = ()

    @classmethod
    def of(cls, material: Material, shift: WLF, fit_times: bool = False, extras=()):
        if not isinstance(shift, WLF):
            raise ValueError(f"torque fitting refines a WLF shift law, got {type(shift).__name__}")
        extras = tuple(extras)
        for e in extras:
            if e not in EXTRAS:
                raise ValueError(f"extras: {e!r} is not a fittable scene parameter; choose from {EXTRAS}")
        if len(set(extras)) != len(extras):
            raise ValueError(f"extras: a name repeated in {extras}")
        return cls(int(material.moduli.shape[0]), bool(fit_times), np.asarray(material.times, float),
                   float(material.nu), float(shift.T_ref), extras)

    @property
    def n_material(self):
        """Number of material and shift log-parameters (the extras follow them in x)."""
        return 1 + self.K * (2 if self.fit_times else 1) + 2

    def names(self):
        K = self.K
        n = ["E0"] + [f"E_{k + 1}" for k in range(K)]
        if self.fit_times:
            n += [f"tau_{k + 1}" for k in range(K)]
        return n + ["C1", "C2"] + list(self.extras)

    def pack(self, material: Material, shift: WLF, extras=None) -> np.ndarray:
        """x from the material, shift and a dict of the extras' values (> 0)."""
        parts = [[float(material.E0)], np.asarray(material.moduli, float)]
        if self.fit_times:
            parts.append(np.asarray(material.times, float))
        parts.append([float(shift.C1), float(shift.C2)])
        extras = extras or {}
        missing = [e for e in self.extras if e not in extras]
        if missing:
            raise ValueError(f"extras: no start value for {missing}")
        for e in self.extras:
            if not (float(extras[e]) > 0 and math.isfinite(float(extras[e]))):
                raise ValueError(f"extras: {e} must be a finite number > 0 to be fitted on its logarithm, "
                                 f"got {extras[e]!r}")
        parts.append([float(extras[e]) for e in self.extras])
        return np.log(np.concatenate([np.ravel(p) for p in parts]))

    def unpack(self, x):
        K, n = self.K, self.n_material
        v = jnp.exp(x)
        tau = v[1 + K:1 + 2 * K] if self.fit_times else jnp.asarray(self.times)
        mat = Material(v[0], v[1:1 + K], tau, jnp.asarray(self.nu, v.dtype))
        return mat, WLF(v[n - 2], v[n - 1], jnp.asarray(self.T_ref, v.dtype))

    def unpack_extras(self, x):
        """The extras' values (dict name -> value) from x (traceable)."""
        v = jnp.exp(x[self.n_material:])
        return {e: v[i] for i, e in enumerate(self.extras)}

    def physical(self, x):
        """(Material, WLF) with concrete, checked values."""
        v = np.exp(np.asarray(x, float))
        K, n = self.K, self.n_material
        tau = v[1 + K:1 + 2 * K] if self.fit_times else self.times
        return (Material.prony(v[0], v[1:1 + K], tau, self.nu),
                WLF(float(v[n - 2]), float(v[n - 1]), self.T_ref))

    def physical_extras(self, x):
        """The extras' values (dict name -> float)."""
        return {e: float(v) for e, v in zip(self.extras, np.exp(np.asarray(x, float)[self.n_material:]))}


# ---- objective -------------------------------------------------------------------------
def evaluate(model, material, shift, rpm, T, load, extras=None):
    """(torque, converged) of ``model`` at the points (arrays rpm, T, load), with the scene
    keywords ``extras`` (dict, e.g. mu_b, sigma, hA; the same at every point): batched by vmap,
    or one point after the other when ``model.sequential`` (the journal: its solve's fallbacks,
    restarts and continuation, are branches, which vmap turns into selects that run every
    branch for every point)."""
    extras = extras or {}
    # jax arrays: a numpy array closed over by a jitted caller and vmapped into the thermal
    # scenes' implicit root fails as a non-canonical constant
    rpm, T, load = (jnp.asarray(a) for a in (rpm, T, load))
    point = lambda a, b, c: model(material, shift, a, b, c, **extras)     # noqa: E731
    if getattr(model, "sequential", False):
        return jax.lax.map(lambda p: point(*p), (rpm, T, load))
    return jax.vmap(point)(rpm, T, load)


def _residual_fn(params: Params, model, data: TorqueData, rel_scatter, dma_table, w_dma, s_dma):
    unknown = [e for e in params.extras if e not in getattr(model, "extras", ())]
    if unknown:
        raise ValueError(f"extras: the model ({getattr(model, 'scene', model)}) takes no {unknown}; it takes "
                         f"{list(getattr(model, 'extras', ())) or 'none'} (a roughness= gives mu_b and sigma, a "
                         f"heat_transfer= gives hA)")
    rpm, T, load = (jnp.asarray(a) for a in (data.rpm, data.T, data.load))
    meas = jnp.asarray(data.torque)
    sig = jnp.asarray(data.sigma(rel_scatter))
    if dma_table is not None and w_dma > 0:
        from .prony import log_residual
    else:
        dma_table = None

    def residuals(x):
        mat, shift = params.unpack(x)
        tq, ok = evaluate(model, mat, shift, rpm, T, load, params.unpack_extras(x))
        r_t = (tq - meas) / sig
        if dma_table is not None:
            r_d = math.sqrt(w_dma) * log_residual(mat, shift, dma_table) / s_dma
            r = jnp.concatenate([r_t, r_d])
        else:
            r = r_t
        return r, (r_t, tq, ok)

    return residuals


def residual_jacobian(params: Params, model, data: TorqueData, rel_scatter=0.05, dma_table=None, w_dma=0.0,
                      s_dma=0.02):
    """Compiled ``x -> (J, (r, r_torque, torque_model, converged))``: the stacked weighted
    residuals r (torque, then sqrt(w_dma) DMA) and their Jacobian J = dr/dx (forward mode)."""
    res = _residual_fn(params, model, data, rel_scatter, dma_table, w_dma, s_dma)

    def with_aux(x):
        r, aux = res(x)
        return r, (r,) + aux

    return jax.jit(jax.jacfwd(with_aux, has_aux=True)), jax.jit(lambda x: res(x)[0])


def gauss_newton_cov(J, rcond=1e-8):
    """Gauss-Newton covariance (J^T J)^-1 of the log-parameters from the Jacobian of
    noise-scaled residuals, by SVD: directions with s < rcond s_max are dropped, and a
    parameter with more than 1% of its weight in dropped directions gets sd = inf (it is not
    determined; a plain pseudo-inverse would report a misleadingly small sd). Returns
    (cov, sd)."""
    cov, sd, resolved = optim.covariance(J, rcond)
    return cov, np.where(resolved < 0.99, np.inf, sd)


def identifiability(J_torque, names, threshold=0.1, rcond=1e-10):
    """Which log-parameters the torque data identify, from the Jacobian of the noise-scaled
    torque residuals (rows: points, columns: log-parameters).

    Returns a dict: ``singular_values`` (descending), ``sd`` (Gauss-Newton standard deviation
    of each log-parameter from the torque alone, sqrt diag pinv(J^T J); a relative error),
    ``identifiable`` (sd < ``threshold``, i.e. determined to better than ~10%),
    ``identified_directions`` (singular directions with 1/s < threshold, i.e. combinations
    of parameters the data fix to better than ~10%, with their three largest components)
    with ``identified_basis`` their unit vectors (rows), and ``weakest`` (the three least
    determined directions).
    """
    J = np.asarray(J_torque, float)
    _, s, Vt = np.linalg.svd(J, full_matrices=False)
    _, sd, resolved = optim.covariance(J, rcond)
    # a parameter with no projection on the retained directions is not identified at all
    sd = np.where(resolved < 0.5, np.inf, sd)
    def describe(i):
        v = Vt[i]
        top = np.argsort(-np.abs(v))[:3]
        return {"singular_value": float(s[i]), "direction": {names[j]: round(float(v[j]), 3) for j in top}}

    # a direction v (unit, in log-parameters) is determined to sd 1/s: identified if 1/s < threshold
    strong = [describe(i) for i in range(len(s)) if s[i] > 1.0 / threshold]
    basis = Vt[s > 1.0 / threshold]
    weak = [describe(i) for i in np.argsort(s)[: min(3, len(s))]]
    return {"singular_values": s.tolist(), "sd": dict(zip(names, sd.tolist())),
            "identifiable": [n for n, d in zip(names, sd) if d < threshold],
            "not_identifiable": [n for n, d in zip(names, sd) if not d < threshold],
            "identified_directions": strong, "identified_basis": basis.tolist(), "weakest": weak}


@dataclasses.dataclass
class TorqueFit:
    """Result of :func:`fit_torque`.

    material, shift: refined (checked) material and WLF law. x0, x: log-parameters before
    and after; names: their names. history: per iteration (iteration, loss, grad norm,
    seconds). iterations, wall_time (s), compile_time (s). loss0, loss. torque0, torque:
    model torque at the data points before/after. converged: all scene solves converged at
    the final point. cov: Gauss-Newton covariance of x (torque + DMA terms). sd: its
    standard deviations (relative errors of the parameters). ident: :func:`identifiability`
    of the torque term alone at the final point. extras: the fitted scene parameters (dict,
    e.g. mu_b, sigma in m, hA in W/K).
    """

    material: Material
    shift: WLF
    params: Params
    names: list
    x0: np.ndarray
    x: np.ndarray
    history: list
    iterations: int
    wall_time: float
    compile_time: float
    loss0: float
    loss: float
    torque0: np.ndarray
    torque: np.ndarray
    converged: bool
    cov: np.ndarray
    sd: np.ndarray
    ident: dict
    extras: dict = dataclasses.field(default_factory=dict)

    def table(self, truth=None):
        """Rows (name, before, after, sd_rel, [truth, err_before, err_after]) with values in
        SI units and relative errors."""
        v0, v1 = np.exp(self.x0), np.exp(self.x)
        rows = []
        for i, n in enumerate(self.names):
            row = [n, float(v0[i]), float(v1[i]), float(self.sd[i])]
            if truth is not None:
                t = float(np.exp(truth[i]))
                row += [t, float(v0[i] / t - 1.0), float(v1[i] / t - 1.0)]
            rows.append(row)
        return rows


def fit_torque(data: TorqueData, material: Material, shift: WLF, model, *, dma_table=None, w_dma=1.0,
               s_dma=0.02, rel_scatter=0.05, fit_times=False, extras=None, steps=100, lr=0.05, lr_end=0.005,
               gtol=1e-6, polish=20, progress=True, every=5, log=None) -> TorqueFit:
    """Refine ``material`` and its WLF ``shift`` against the torque ``data`` (see module docs).

    Args:
      data: :class:`TorqueData`. material, shift: the start (a Prony material, WLF law).
      model: ``model(material, shift, rpm, T, load) -> (torque, converged)``, e.g.
        :func:`roller_model` or :func:`pin_model`.
      dma_table: optional :class:`fitting.dma.DMATable` for the consistency term, weight
        ``w_dma``, scatter ``s_dma`` (decades of log10 modulus).
      rel_scatter: torque scatter relative to the torque when the data have none.
      fit_times: also refine the relaxation times (the torque rarely identifies them).
      extras: scene parameters fitted with the material, a dict of start values (> 0) by name
        (:data:`EXTRAS`: ``mu_b`` and ``sigma`` (m) of a journal model with a roughness, ``hA``
        of a model with a heat transfer); None or {}: the material alone.
      steps, lr, lr_end: Adam iterations and a cosine-decayed learning rate (log units).
      gtol: stop when the gradient norm falls below it.
      polish: at most this many Levenberg-Marquardt iterations after Adam (0: none).
      progress: print (iteration, loss, gradient norm) every ``every`` iterations to
        ``log`` (stderr).
    """
    import optax

    log = log or sys.stderr
    extras = dict(extras or {})
    params = Params.of(material, shift, fit_times, tuple(extras))
    names = params.names()
    x0 = params.pack(material, shift, extras)
    jac_fn, _ = residual_jacobian(params, model, data, rel_scatter, dma_table, w_dma, s_dma)
    Nt = len(data)
    t0 = time.perf_counter()
    J, aux = jac_fn(jnp.asarray(x0))
    jax.block_until_ready(J)
    compile_time = time.perf_counter() - t0
    r, r_t, tq0, ok = aux
    loss0 = float(jnp.sum(r ** 2) / Nt)
    sched = optax.cosine_decay_schedule(lr, max(steps, 1), alpha=lr_end / lr)
    opt = optax.adam(sched)
    x = jnp.asarray(x0)
    state = opt.init(x)
    history = []
    t_start = time.perf_counter()

    def loss_grad(J, aux):
        r = aux[0]
        return float(jnp.sum(r ** 2) / Nt), 2.0 * (J.T @ r) / Nt

    def usable(loss, aux):           # finite, and every bearing solve converged
        return np.isfinite(loss) and bool(np.all(np.asarray(aux[3])))

    if not usable(loss0, aux):
        raise ValueError(f"the bearing solves do not converge at the start material ({getattr(model, 'scene', '')})"
                         "; check the geometry, loads and material")
    best = (loss0, x, J, aux)
    for it in range(steps + 1):
        loss, g = loss_grad(J, aux)
        gn = float(jnp.linalg.norm(g))
        history.append((it, loss, gn, time.perf_counter() - t_start))
        if usable(loss, aux) and loss < best[0]:
            best = (loss, x, J, aux)
        if progress and (it % every == 0 or it == steps):
            print(f"  iter {it:4d}  loss {loss:.6g}  |grad| {gn:.3e}  {time.perf_counter() - t_start:7.1f} s",
                  file=log, flush=True)
        if it == steps or not np.isfinite(loss) or gn < gtol:
            break
        upd, state = opt.update(g, state, x)
        x = optax.apply_updates(x, upd)
        J, aux = jac_fn(x)
    loss, x, J, aux = best
    # Levenberg-Marquardt from Adam's best point, on the Jacobian Adam already uses: Adam
    # crawls once the loss is a narrow valley; Gauss-Newton steps reach the noise floor.
    # The steps and damping of fitting.optim's Levenberg-Marquardt, driven from here
    # (fitting.optim.levenberg_marquardt_host: each trial is a set of bearing solves,
    # reported, and kept only if they all converged).
    lm_log = []

    def resid_jac(x_try):
        J_try, aux_try = jac_fn(jnp.asarray(x_try))
        return np.asarray(aux_try[0], float), np.asarray(J_try, float), (J_try, aux_try)

    def accepted(k, cost, x_new, extra):
        loss_new, g_new = loss_grad(*extra)
        lm_log.append((it + k, loss_new, float(jnp.linalg.norm(g_new)), time.perf_counter() - t_start))
        if progress:
            print(f"  LM   {it + k:4d}  loss {loss_new:.6g}  {time.perf_counter() - t_start:7.1f} s",
                  file=log, flush=True)

    if polish > 0 and float(jnp.linalg.norm(2.0 * (J.T @ aux[0]) / Nt)) >= gtol:
        xl, _, _, (J, aux), _, k, _ = optim.levenberg_marquardt_host(
            resid_jac, np.asarray(x), max_iter=polish, ftol=1e-6, floor=1e-4, on_accept=accepted,
            usable=lambda extra: usable(loss_grad(*extra)[0], extra[1]),
            start=(np.asarray(aux[0], float), np.asarray(J, float), (J, aux)))   # Adam's best: no solve again
        x, loss, it = jnp.asarray(xl), float(jnp.sum(aux[0] ** 2) / Nt), it + k
        history += lm_log
    r, r_t, tq, ok = aux
    if progress:
        print(f"  best  loss {loss:.6g} (start {loss0:.6g}) after {it} iterations, "
              f"{time.perf_counter() - t_start:.1f} s", file=log, flush=True)
    wall = time.perf_counter() - t0
    Jn = np.asarray(J, float)
    cov, sd = gauss_newton_cov(Jn)
    ident = identifiability(Jn[:Nt], names)
    mat, sh = params.physical(np.asarray(x))
    return TorqueFit(mat, sh, params, names, np.asarray(x0), np.asarray(x), history, it, wall, compile_time,
                     loss0, loss, np.asarray(tq0), np.asarray(tq), bool(np.all(np.asarray(ok))), cov, sd, ident,
                     params.physical_extras(np.asarray(x)))


def gradient_check(params: Params, model, data: TorqueData, x, *, rel_scatter=0.05, dma_table=None, w_dma=0.0,
                   s_dma=0.02, h=1e-4, coords=None, seed=0):
    """Loss gradient (from the implicit-derivative Jacobian) versus central finite
    differences of the loss, for a few coordinates and one random direction.
    Returns rows (what, analytic, finite difference, relative error)."""
    jac_fn, val_fn = residual_jacobian(params, model, data, rel_scatter, dma_table, w_dma, s_dma)
    Nt = len(data)
    x = jnp.asarray(x)
    J, aux = jac_fn(x)
    g = 2.0 * (J.T @ aux[0]) / Nt
    loss = lambda y: float(jnp.sum(val_fn(y) ** 2) / Nt)
    names = params.names()
    coords = list(range(len(names))) if coords is None else coords
    dirs = [(names[i], np.eye(len(names))[i]) for i in coords]
    v = np.random.default_rng(seed).normal(size=len(names))
    dirs.append(("random direction", v / np.linalg.norm(v)))
    rows = []
    for what, d in dirs:
        d = jnp.asarray(d)
        fd = (loss(x + h * d) - loss(x - h * d)) / (2 * h)
        an = float(g @ d)
        rows.append((what, an, fd, abs(an - fd) / max(abs(fd), abs(an), 1e-300)))
    return rows
