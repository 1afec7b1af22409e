"""The dry scenes at their effective temperature (level 1; docs/theory.md §19): the pin in its
hole and the needle roller bearing, each polymer ring at the bulk temperature its own
hysteresis sets against ``hA`` (per unit axial length; no oil; :mod:`.balance`)."""
from __future__ import annotations

import jax.numpy as jnp

from ..._core import checks
from ..pin import pin_in_hole
from ..roller import roller_bearing
from .balance import HeatTransfer, default_tol, removal, report, result_at, solve_balance


def _dry(what, scene_fn, power_fn, heat, params, tol, max_iter, throw):
    """A dry scene ``scene_fn(T, params)`` at the bulk temperature its hysteresis ``power_fn(scene) ->
    (P_housing, P_shaft)`` (W/m) sets against ``heat.hA`` (no oil)."""
    checks.instance("heat", heat, HeatTransfer, "a vjax.HeatTransfer")

    def balance(T, p):
        s = scene_fn(T, p)
        P_B, P_J = power_fn(s)
        P = P_B + P_J
        T_star, heat_oil, convected = removal(p["heat"], T, p["heat"].ambient, 0.0, P)
        return dict(T_star=T_star, valid=s.converged, scene=s, P=P, P_B=P_B, P_J=P_J, heat_oil=heat_oil,
                    convected=convected)

    T, b, stats = solve_balance(balance, dict(params, heat=heat), False, default_tol(heat.ambient, tol), max_iter)
    out = result_at(T, T, b, stats, None, heat)
    report(what, out, heat.T_limit, throw)
    return out


def thermal_pin(housing, R, radial_clearance, load, heat: HeatTransfer, *, shift=None, omega_shaft=0.0,
                omega_housing=0.0, options=None, throw=True, tol=None, max_iter=60, **scene_arguments):
    """:func:`vjax.pin_in_hole` with the housing at the bulk temperature T (C) its own
    hysteresis sets: P(T) = -Omega torque (W/m, Omega the patch speed) = ``heat.hA`` (T -
    T_ambient) (hA in W/(m K), per unit axial length; no oil). The housing's material is
    evaluated at T through its own shift law (``shift``: the 0.2 form, deprecated). Returns a :class:`~vjax.ThermalResult` (``scene``: a
    :class:`~vjax.PinResult`); runaway and failures as :func:`vjax.thermal_journal_bearing`."""
    kw = dict(scene_arguments, **({} if options is None else dict(options=options)))

    def scene(T, p):
        return pin_in_hole(p["housing"], p["R"], p["c"], p["load"], omega_shaft=p["wJ"], omega_housing=p["wB"],
                           temperature=T, shift=p["shift"], throw=False, **kw)

    params = dict(housing=housing, R=R, c=radial_clearance, load=load, wJ=omega_shaft, wB=omega_housing, shift=shift)
    return _dry("thermal_pin", scene, lambda s: (-s.patch_speed * s.torque, 0.0 * s.torque), heat, params, tol,
                max_iter, throw)


def thermal_roller(housing, shaft, R_outer, R_inner, roller_diameter, n_rollers, load, heat: HeatTransfer, *,
                   shift=None, omega_shaft=0.0, omega_housing=0.0, options=None, throw=True, tol=None, max_iter=60,
                   **scene_arguments):
    """:func:`vjax.roller_bearing` with both rings at the bulk temperature T (C) their
    hysteresis sets: P = Omega_O T_O + Omega_I T_I (W/m, Omega the patch speeds relative to
    each ring, T each ring's torque about its own centre: the inner ring's centre is shifted
    by ``ring_shift`` along the load) = ``heat.hA`` (T - T_ambient) (W/(m K)). Returns a
    :class:`~vjax.ThermalResult` (``scene``: a :class:`~vjax.RollerResult`)."""
    kw = dict(scene_arguments, **({} if options is None else dict(options=options)))
    load_angle = kw.get("load_angle", 0.0)

    def hysteresis(s):
        # the inner ring's torque about its own centre, ring_shift along the load from the bearing's
        cx, cy = s.ring_shift * jnp.cos(load_angle), s.ring_shift * jnp.sin(load_angle)
        inner = s.torque_shaft - (cx * s.force_shaft[1] - cy * s.force_shaft[0])
        return s.patch_speed[0] * s.torque, s.patch_speed[1] * inner

    def scene(T, p):
        return roller_bearing(p["housing"], p["shaft"], p["RO"], p["RI"], p["D"], n_rollers, p["load"],
                              omega_shaft=p["wJ"], omega_housing=p["wB"], temperature=T, shift=p["shift"],
                              throw=False, **kw)

    params = dict(housing=housing, shaft=shaft, RO=R_outer, RI=R_inner, D=roller_diameter, load=load,
                  wJ=omega_shaft, wB=omega_housing, shift=shift)
    return _dry("thermal_roller", scene, hysteresis, heat, params, tol, max_iter, throw)
