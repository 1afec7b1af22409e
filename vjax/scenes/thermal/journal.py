"""The journal bearing at its effective temperature (level 1; docs/theory.md §19): the film's
friction power (:func:`vjax.films.shear.film_power`, the Couette part striated in the cavity)
and the bodies' hysteresis carried off by the side leakage and ``hA`` (:mod:`.balance`)."""
from __future__ import annotations

import math

import jax

from ..._core import checks, scene as _scene
from ...films.shear import film_power
from ...materials.lubricant import as_lubricant
from ..journal.bearing import journal_bearing
from .balance import HeatTransfer, ThermalResult, default_tol, removal, report, result_at, solve_balance

# the balance's film power, compiled once per bearing geometry: called eagerly, its scan would be
# traced and compiled again at every scene solve of the root search
_film_power = jax.jit(film_power, static_argnums=(8, 9, 10))


def thermal_journal_bearing(R, radial_clearance, lubricant, load, heat: HeatTransfer, *, length=None, housing=None,
                            shaft=None, shift=None, omega_shaft=0.0, omega_housing=0.0, supply_angle=math.pi,
                            supply_width=1.0, cavitation="reynolds", roughness=None, options=None, throw=True,
                            tol=None, max_iter=60, **scene_arguments) -> ThermalResult:
    """A finite journal bearing (:func:`vjax.journal_bearing` with ``length=``) at its effective
    temperature T_eff (C), ISO 7902's global balance (docs/theory.md, "Thermal balance (level 1)"):
    the film isoviscous at eta(T_eff) of the :class:`~vjax.Lubricant` ``lubricant``, the bodies
    (``housing``, ``shaft``) at T_eff through ``shift`` (their materials' WLF/Arrhenius law;
    None: temperature-independent), the heat -- film shear (:func:`vjax.films.shear.film_power`)
    and the bodies' hysteresis -- carried off by the side leakage, T_out = T_in + P_oil / (rho
    c_p Q), T_eff = (T_in + T_out) / 2 (no carry-over), and by ``heat.hA`` to ``heat.T_ambient``.

    With ``roughness`` (mixed lubrication) the power is the scene's own ``power_loss``: Patir and
    Cheng's viscous shear over the whole land and the asperities' friction mu_b p_a times the
    sliding speed.

    Without ``length`` the infinitely long bearing, per unit length: no side leakage, so the heat
    leaves through ``heat.hA`` (W/(m K)) alone (``HeatTransfer(oil_flow=False)``), and its power
    is -(omega_B torque + omega_J torque_shaft), the scene's torques (the cavity's film sheared
    as full, as they count it; with ``roughness`` the asperities' friction too).

    ``heat``: :class:`HeatTransfer`. ``tol`` (K): of |T - T*(T)| (None: ~1e-10 K in float64).
    ``max_iter``: scene solves. Other arguments as :func:`vjax.journal_bearing` (``throw``
    raises :class:`~vjax.ConvergenceError` on a failed balance or thermal runaway). Returns
    a :class:`ThermalResult`, its ``scene`` a :class:`~vjax.FiniteJournalResult`."""
    lubricant = as_lubricant(lubricant, "lubricant")
    checks.instance("heat", heat, HeatTransfer, "a vjax.HeatTransfer")
    for name in ("temperature", "viscosity", "initial"):
        if name in scene_arguments:
            raise ValueError(f"{name}: not an argument of thermal_journal_bearing (the temperature is solved for; "
                             f"the viscosity is the lubricant's at it)")
    if length is None and heat.oil_flow:
        raise ValueError("heat: an infinitely long bearing (no length=) has no side leakage to carry heat: "
                         "HeatTransfer(oil_flow=False, hA=...) with hA per unit length (W/(m K)), or give length=")
    if heat.oil_flow:
        lubricant.require("rho", "c_p")
    v = checks.values("omega_shaft", 0.5 * (omega_housing * R + omega_shaft * (R - radial_clearance)))
    if v is not None and not v > 0:
        raise ValueError("omega_shaft, omega_housing: the thermal balance is built for a positive entrainment speed "
                         "(omega_housing R + omega_shaft R_J > 0); turn the bearing the other way round")
    # the bodies follow T_eff when their materials carry shift laws (or through the 0.2 shift=)
    deformable = (housing is not None or shaft is not None) and (
        shift is not None or _scene.responds(housing) or _scene.responds(shaft))
    params = dict(R=R, c=radial_clearance, load=load, L=length, wJ=omega_shaft, wB=omega_housing, oil=lubricant,
                  heat=heat, housing=housing, shaft=shaft, shift=shift, rough=roughness)
    static_angle = None if supply_angle is None else float(supply_angle)
    static_width = float(supply_width)

    def balance(T, p):
        eta = p["oil"].viscosity(T)
        at = dict(temperature=T, shift=p["shift"]) if deformable else {}
        finite = {} if p["L"] is None else dict(length=p["L"], supply_width=supply_width)
        s = journal_bearing(p["R"], p["c"], eta, p["load"], housing=p["housing"], shaft=p["shaft"],
                            omega_shaft=p["wJ"], omega_housing=p["wB"], supply_angle=supply_angle, roughness=p["rough"],
                            cavitation=cavitation, options=options, throw=False, **finite, **at, **scene_arguments)
        P_B, P_J = -p["wB"] * s.torque_viscoelastic, -p["wJ"] * s.torque_viscoelastic_shaft
        if p["L"] is None:
            P = -(p["wB"] * s.torque + p["wJ"] * s.torque_shaft)
            P_film = P - P_B - P_J
        elif p["rough"] is not None:
            # mixed lubrication: the scene's own dissipation, Patir and Cheng's shear over the land and
            # the asperities' friction mu_b p_a times the sliding speed
            P_film = s.power_loss
            P = P_film + P_B + P_J
        else:
            P_film, _ = _film_power(s.pressure, s.film, s.z, p["R"], p["c"], eta, p["wJ"], p["wB"], static_angle,
                                    static_width, cavitation, s.film_fraction)
            P = P_film + P_B + P_J
        h = p["heat"]
        G_oil = 2 * p["oil"].density(T) * p["oil"].c_p * s.side_leakage if h.oil_flow else 0.0
        T_star, heat_oil, convected = removal(h, T, h.T_supply, G_oil, P)
        return dict(T_star=T_star, valid=s.converged, scene=s, P=P, P_film=P_film, P_B=P_B, P_J=P_J, eta=eta,
                    heat_oil=heat_oil, convected=convected, Q=0.0 if p["L"] is None else s.side_leakage)

    T, b, stats = solve_balance(balance, params, heat.oil_flow, default_tol(heat.T_supply, tol), max_iter)
    T_out = 2 * T - heat.T_supply if heat.oil_flow else T
    out = result_at(T, T_out, b, stats, lubricant.T_max, heat)
    report("thermal_journal_bearing", out, heat.T_limit, throw)
    return out
