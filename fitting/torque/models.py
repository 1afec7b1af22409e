"""The bearing models a torque fit evaluates: :func:`roller_model`, :func:`pin_model`,
:func:`journal_model` (vjax scenes at each data point), and the lubricants they take."""
from __future__ import annotations

import dataclasses
import math

import jax.numpy as jnp

import vjax


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
