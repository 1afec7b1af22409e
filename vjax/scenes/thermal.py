"""Level 1 thermal scenes: each scene at the effective temperature its own dissipation sets.

A scene dissipates a power P(T) that depends on the temperature T at which its oil and its
bodies are evaluated (the lubricant's viscosity law, each body's material through its shift
law). The power leaves with the oil and through housing and shaft (docs/theory.md, "Thermal
balance (level 1)"):

    P(T) = rho c_p Q (T_out - T_in) + hA (T - T_amb),       T_out = 2 T - T_in (journal bearing)

The effective temperature T is the root of r(T) = T - T*(T), with

    T*(T) = T_amb + (P(T) + G(T) (T_in - T_amb)) / (G(T) + hA),     G = 2 rho c_p Q,

the temperature the balance would give if the mechanics were frozen at T (plain successive
substitution iterates T <- T*(T), which diverges where |dT*/dT| > 1: ISO 7902's heavily
loaded fast bearings). The root is bracketed and found by secant steps safeguarded by
bisection (:func:`_root`); each residual is a full solve of the scene at T. Derivatives are
implicit (:func:`vjax._core.solve.implicit_root`): dT = dr/dparams / (dr/dT), never through
the iterations; jit, vmap and grad go through. Outside jit the iterations run in Python over
the scene's own compiled solve (no new compilation); under a trace, in a ``lax.while_loop``.

No root below ``HeatTransfer.T_limit`` (the generated heat outgrowing the removed heat, or no
removal at all) is thermal runaway: :class:`~vjax.ConvergenceError` naming it and the
temperatures reached, or with ``throw=False`` the result code :data:`RUNAWAY`.
"""
from __future__ import annotations

import dataclasses
import math

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks, scene as _scene, solve as _solve
from .._core.solve import ConvergenceError
from ..films import film2d
from ..materials.lubricant import as_lubricant
from .journal.bearing import journal_bearing
from .pin import pin_in_hole
from .roller import roller_bearing

RUNAWAY = len(_solve.MESSAGES)       # result code: no steady state below T_limit
MESSAGES = _solve.MESSAGES + ("found no steady state (thermal runaway)",)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class HeatTransfer:
    """How a scene's heat leaves it (level 1: one effective temperature per scene).

    ``T_supply`` (C): the oil's supply temperature (journal bearing). ``hA``: convection and
    conduction through housing and shaft to ``T_ambient`` (C; None: ``T_supply``), a heat-
    transfer coefficient times its area, W/K for a finite bearing, W/(m K) for the per-unit-
    length pin and roller scenes; ``jnp.inf`` holds the scene at T_ambient (isothermal).
    ``oil_flow`` (static): the side leakage carries heat, rho c_p Q (T_out - T_in) (the
    lubricant must have rho and c_p). ``T_limit`` (C): the top of the search; no steady state
    below it is thermal runaway. ``T_max_body`` (C): the bodies' materials' stated maximum
    temperature (a datasheet's), or None; the result flags a body above it."""

    T_supply: jax.Array = 40.0
    hA: jax.Array = 0.0
    T_ambient: jax.Array | None = None
    T_limit: jax.Array = 250.0
    T_max_body: jax.Array | None = None
    oil_flow: bool = dataclasses.field(default=True, metadata=dict(static=True))

    def __post_init__(self):
        checks.finite("T_supply", self.T_supply)
        checks.finite("T_limit", self.T_limit)
        if checks.is_concrete(self.hA):       # inf allowed: the isothermal limit
            if not (np.all(np.asarray(self.hA) >= 0)):
                raise ValueError(f"hA must be >= 0 (W/K; inf: isothermal), got {self.hA!r}")
        for name in ("T_ambient", "T_max_body"):
            if getattr(self, name) is not None:
                checks.finite(name, getattr(self, name))

    @property
    def ambient(self):
        return self.T_supply if self.T_ambient is None else self.T_ambient


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class ThermalResult(_scene.SceneResult):
    """A scene at its effective temperature (W for a finite bearing, W/m per unit length).

    Temperatures (C): ``temperature`` the effective temperature (the film's T_eff in a journal
    bearing, where the bodies sit too; the polymer ring's bulk temperature in a dry scene),
    ``outlet_temperature`` T_out = 2 T_eff - T_in of the oil (T_eff without oil flow),
    ``body_temperature`` the bodies'. Power: ``power_film`` the film's shear (U times the
    journal's shear, the Couette part striated in the cavity), ``power_housing`` and
    ``power_shaft`` the bodies' hysteresis (-omega times each viscoelastic torque, the dry
    scenes' patch speeds), ``power`` their sum. Heat: ``heat_oil`` rho c_p Q (T_out - T_in),
    ``heat_convected`` hA (T - T_amb); ``power = heat_oil + heat_convected`` at the root.
    ``side_leakage`` Q (m^3/s), ``viscosity`` eta(T_eff) (Pa s; NaN for dry scenes).
    Flags: ``film_overheated`` T_eff above the lubricant's T_max, ``body_overheated`` above
    ``HeatTransfer.T_max_body``. ``scene``: the scene's own result at T. Convergence of the
    thermal root: ``iterations`` (scene solves), ``residual`` |T - T*(T)| (K), ``result``
    (:data:`RUNAWAY` for thermal runaway)."""

    temperature: jax.Array
    outlet_temperature: jax.Array
    body_temperature: jax.Array
    power: jax.Array
    power_film: jax.Array
    power_housing: jax.Array
    power_shaft: jax.Array
    heat_oil: jax.Array
    heat_convected: jax.Array
    side_leakage: jax.Array
    viscosity: jax.Array
    film_overheated: jax.Array
    body_overheated: jax.Array
    scene: object
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array

    def _describe(self, sep):
        parts = [f"{f.name}={np.asarray(getattr(self, f.name)).item():.6g}" for f in dataclasses.fields(self)
                 if f.name not in ("scene", "result") and checks.is_concrete(getattr(self, f.name))
                 and np.shape(getattr(self, f.name)) == ()]
        if checks.is_concrete(self.result) and np.shape(self.result) == ():
            parts.append(f"status: {MESSAGES[int(self.result)]}")
        return sep.join(parts)


# ---- the scalar root ---------------------------------------------------------------------------
def _root(target, lo, T_limit, tol, max_iter):
    """Root of r(T) = T - target(T) on [lo, T_limit], r(lo) <= 0 by construction; ``target(T)
    -> (T*, valid)``. Secant steps from the last two points, kept inside the bracket (bisection
    otherwise); above the last point while no positive r is known (each step at least doubling
    the distance from lo), up to T_limit. Returns (T, Stats)."""
    f = jnp.result_type(float)
    lo, T_limit = jnp.asarray(lo, f), jnp.asarray(T_limit, f)

    def r_at(T):
        Ts, valid = target(T)
        return T - Ts, valid & ~jnp.isnan(Ts)

    r0, v0 = r_at(lo)
    done0 = v0 & (r0 >= -tol)
    x1 = jnp.clip(lo - r0, lo, T_limit)
    x1 = jnp.where(jnp.isfinite(x1), x1, T_limit)
    res0 = jnp.where(done0, _solve.SUCCESS, jnp.where(v0, _solve.MAX_ITERATIONS, _solve.INNER_FAILED))
    # carry: k, a, b, b_known, (xp, rp) last point, x candidate, T found, |r|, result
    carry = (jnp.asarray(1), lo, T_limit, jnp.asarray(False), lo, r0, x1, lo, jnp.abs(r0), res0)

    def cond(c):
        return (c[-1] == _solve.MAX_ITERATIONS) & (c[0] < max_iter)

    def body(c):
        k, a, b, known, xp, rp, x, _, _, _ = c
        r, valid = r_at(x)
        ok = valid & jnp.isfinite(r)
        up = ok & (r < 0)
        a = jnp.where(up, x, a)
        b, known = jnp.where(up, b, x), known | ~up
        success = ok & (jnp.abs(r) <= tol) | ok & known & (b - a <= tol)
        runaway = up & (x >= T_limit)
        s = x - r * (x - xp) / (r - rp)
        s = jnp.where(ok & jnp.isfinite(rp) & jnp.isfinite(s), s, jnp.nan)
        inside = (s > a) & (s < b)
        bracketed = jnp.where(inside, s, 0.5 * (a + b))
        # no positive r yet: the secant's point if it lies ahead, else at least twice as far from lo
        ahead = jnp.minimum(jnp.where(s > x, s, x + 2.0 * (x - lo) + 1.0), T_limit)
        nxt = jnp.where(known, bracketed, ahead)
        result = jnp.where(success, _solve.SUCCESS, jnp.where(runaway, RUNAWAY, _solve.MAX_ITERATIONS))
        xp, rp = jnp.where(ok, x, xp), jnp.where(ok, r, rp)
        return (k + 1, a, b, known, xp, rp, nxt, x, jnp.where(ok, jnp.abs(r), jnp.inf), result)

    if checks.is_concrete((lo, T_limit, r0)):
        while bool(cond(carry)):
            carry = body(carry)
    else:
        carry = jax.lax.while_loop(cond, body, carry)
    k, *_, T, res, result = carry
    T = jnp.where(done0, lo, T)
    res = jnp.where(done0, jnp.abs(r0), res)
    return T, _solve.Stats(k, res, result)


def _default_tol(T_ref, tol):
    if tol is not None:
        return tol
    eps = float(jnp.finfo(jnp.result_type(float)).eps)
    T_ref = checks.values("T_supply", T_ref)
    T_K = 373.15 if T_ref is None else 273.15 + abs(float(np.max(T_ref)))      # traced: a 100 C scale
    return (1e3 if eps < 1e-10 else 30.0) * eps * T_K


def _message(what, T, P, removed, T_limit, stats):
    T, P, removed, result = (np.ravel(np.asarray(a)) for a in (T, P, removed, stats.result))
    bad = np.flatnonzero(result != _solve.SUCCESS)
    if bad.size == 0:
        return None
    i = bad[0]
    where = f" at {bad.size} of {result.size} points (first: flat index {i})" if result.size > 1 else ""
    if result[i] == RUNAWAY:
        return (f"{what}: thermal runaway{where}: the heat generated grows faster with temperature than the heat "
                f"removed, and no steady state exists up to T_limit = {float(np.ravel(T_limit)[0]):.6g} C; reached "
                f"T = {T[i]:.6g} C generating {P[i]:.6g} W against {removed[i]:.6g} W removed (more cooling: a "
                f"larger hA or oil flow; or a higher HeatTransfer.T_limit if the material holds there)")
    return (f"{what}: the thermal balance did not converge{where}: {MESSAGES[int(result[i])]} after "
            f"{int(np.ravel(np.asarray(stats.iterations))[i])} scene solves, |T - T*| = "
            f"{float(np.ravel(np.asarray(stats.residual))[i]):.3e} K at T = {T[i]:.6g} C")


def _report(what, out: ThermalResult, T_limit, throw):
    if not throw:
        return
    args = (out.temperature, out.power, out.heat_oil + out.heat_convected, T_limit, out.result, out.iterations,
            out.residual)

    def raise_(T, P, removed, T_limit, result, iterations, residual):
        message = _message(what, T, P, removed, T_limit, _solve.Stats(iterations, residual, result))
        if message is not None:
            raise ConvergenceError(message, out if checks.is_concrete(out.result) else None)

    if checks.is_concrete(args):
        raise_(*args)
    else:
        jax.lax.cond(jnp.any(out.result != _solve.SUCCESS),
                     lambda a: jax.debug.callback(raise_, *a), lambda a: None, args)


def _solve_balance(balance, params, oil_in: bool, tol, max_iter):
    """The effective temperature of ``balance(T, params) -> dict`` (T_star, valid, ...),
    differentiated implicitly; then the balance at it. ``params["heat"]``: the HeatTransfer;
    ``oil_in``: the oil's supply temperature bounds the root from below too."""
    def solver(p):
        h = p["heat"]
        lo = jnp.minimum(h.T_supply, h.ambient) if oil_in else h.ambient
        T, stats = _root(lambda T: (lambda b: (b["T_star"], b["valid"]))(balance(T, p)), lo, h.T_limit, tol,
                         max_iter)
        return jnp.atleast_1d(T), stats

    def residual(x, aux, p):
        return jnp.atleast_1d(x[0] - balance(x[0], p)["T_star"])

    x, stats = _solve.implicit_root(solver, residual)(params)
    return x[0], balance(x[0], params), stats


def _removal(heat, T, T_in, G_oil, P):
    """T* and the heat flows at T for the power P and the oil's conductance G_oil = 2 rho c_p Q."""
    hA, T_amb = heat.hA, heat.ambient
    G = G_oil + hA
    T_star = T_amb + jnp.where(G > 0, (P + G_oil * (T_in - T_amb)) / jnp.where(G > 0, G, 1.0), jnp.inf)
    T_star = jnp.where(jnp.isinf(hA), T_amb, T_star)
    heat_oil = G_oil * (T - T_in)
    convected = jnp.where(jnp.isinf(hA), P - heat_oil, hA * (T - T_amb))
    return T_star, heat_oil, convected


# ---- the journal bearing -------------------------------------------------------------------------
def striated_fraction(p, h, z, R, eta, v, full):
    """Liquid fraction of each theta face (n, m + 1) of a Reynolds film: 1 where the upstream
    node is full (pressurized, a groove's or the film outside the cavity), h_r / h_face in the
    cavity, h_r = q_x / v the flux (m^2/s) through the last full face upstream on the same
    axial line (the finite-volume flux into the cavity; the striated film carries it on at
    the surfaces' mean speed v > 0). ``full`` (n, m + 1): bool, or a weight in [0, 1] (a node
    partly full: its flux and the cavity's blended, a continuous switch). End lines take their
    inner neighbours' fractions (the cavity reaches the edge)."""
    n = p.shape[0]
    f = film2d.fluxes(p, h, R, z, eta, v)
    hx, hr_face = f["hx"], f["qx"] / v
    full = jnp.asarray(full, hx.dtype)

    def step(carry, xs):
        full_i, q_i = xs
        carry = full_i * q_i + (1.0 - full_i) * carry
        return carry, carry

    twice = lambda a: jnp.concatenate([a, a], axis=0)    # noqa: E731  (twice round: every line's wrap)
    _, hr = jax.lax.scan(step, hx[0], (twice(full), twice(hr_face)))
    frac = full + (1.0 - full) * hr[n:] / hx
    return frac.at[:, 0].set(frac[:, 1]).at[:, -1].set(frac[:, -2]), f


def film_power(scene, R, radial_clearance, eta, omega_shaft, omega_housing, supply_angle, supply_width,
               cavitation="reynolds"):
    """Friction power (W) of a finite bearing's film: U times the integral of the journal's
    shear tau_J = -h/2 dp/dx + phi eta (U_B - U_J)/h over the land (both surfaces' shear and
    speeds when the housing turns), on the theta faces as the scene's torques, with the
    Couette part scaled by the liquid fraction phi (:func:`striated_fraction` under Reynolds
    conditions; the upwind node's film fraction for "jfo"). Returns (P, phi)."""
    p, h, z = scene.pressure, scene.film, scene.z
    n = p.shape[0]
    RJ = R - radial_clearance
    v = 0.5 * (omega_housing * R + omega_shaft * RJ)
    dU = omega_housing * R - omega_shaft * RJ
    if cavitation == "jfo":
        frac, f = film2d.upwind(scene.film_fraction, v), film2d.fluxes(p, h, R, z, eta, v)
    else:
        dth = 2 * math.pi / n
        full = p > jnp.sqrt(jnp.finfo(p.dtype).eps) * jnp.max(p)
        if supply_angle is not None:
            g = int(round(float(supply_angle) % (2 * math.pi) / dth)) % n
            s = np.asarray(film2d.unit_nodes(p.shape[1] - 1))
            full = full.at[g].set(full[g] | jnp.asarray(np.abs(s) <= float(supply_width) * (1 + 1e-12)))
        frac, f = striated_fraction(p, h, z, R, eta, v, full)
    wz = film2d.node_widths(z)
    arc = R * 2 * math.pi / n
    poiseuille = jnp.sum((-0.5 * f["hx"] * f["dpdx"]) @ wz)
    couette = jnp.sum((frac * eta * dU / f["hx"]) @ wz)
    T_J = RJ * arc * (poiseuille + couette)
    T_B = R * arc * (poiseuille - couette)
    return -(omega_housing * T_B + omega_shaft * T_J), frac


# the balance's film power, compiled once per bearing geometry: called eagerly, its scan would be
# traced and compiled again at every scene solve of the root search
_film_power = jax.jit(film_power, static_argnums=(6, 7, 8))


def thermal_journal_bearing(R, radial_clearance, lubricant, load, heat: HeatTransfer, *, length=None, housing=None,
                            shaft=None, shift=None, omega_shaft=0.0, omega_housing=0.0, supply_angle=math.pi,
                            supply_width=1.0, cavitation="reynolds", roughness=None, options=None, throw=True,
                            tol=None, max_iter=60, **scene_arguments) -> ThermalResult:
    """A finite journal bearing (:func:`vjax.journal_bearing` with ``length=``) at its effective
    temperature T_eff (C), ISO 7902's global balance (docs/theory.md, "Thermal balance (level 1)"):
    the film isoviscous at eta(T_eff) of the :class:`~vjax.Lubricant` ``lubricant``, the bodies
    (``housing``, ``shaft``) at T_eff through ``shift`` (their materials' WLF/Arrhenius law;
    None: temperature-independent), the heat -- film shear (:func:`film_power`) and the bodies'
    hysteresis -- carried off by the side leakage, T_out = T_in + P_oil / (rho c_p Q), T_eff =
    (T_in + T_out) / 2 (no carry-over), and by ``heat.hA`` to ``heat.T_ambient``.

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
    deformable = housing is not None or shaft is not None
    params = dict(R=R, c=radial_clearance, load=load, L=length, wJ=omega_shaft, wB=omega_housing, oil=lubricant,
                  heat=heat, housing=housing, shaft=shaft, shift=shift, rough=roughness)
    static_angle = None if supply_angle is None else float(supply_angle)
    static_width = float(supply_width)

    def balance(T, p):
        eta = p["oil"].viscosity(T)
        at = dict(temperature=T, shift=p["shift"]) if deformable and p["shift"] is not None else {}
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
            P_film, _ = _film_power(s, p["R"], p["c"], eta, p["wJ"], p["wB"], static_angle, static_width, cavitation)
            P = P_film + P_B + P_J
        h = p["heat"]
        G_oil = 2 * p["oil"].density(T) * p["oil"].c_p * s.side_leakage if h.oil_flow else 0.0
        T_star, heat_oil, convected = _removal(h, T, h.T_supply, G_oil, P)
        return dict(T_star=T_star, valid=s.converged, scene=s, P=P, P_film=P_film, P_B=P_B, P_J=P_J, eta=eta,
                    heat_oil=heat_oil, convected=convected, Q=0.0 if p["L"] is None else s.side_leakage)

    T, b, stats = _solve_balance(balance, params, heat.oil_flow, _default_tol(heat.T_supply, tol), max_iter)
    T_out = 2 * T - heat.T_supply if heat.oil_flow else T
    out = _result(T, T_out, b, stats, lubricant.T_max, heat)
    _report("thermal_journal_bearing", out, heat.T_limit, throw)
    return out


def _result(T, T_out, b, stats, T_max_film, heat):
    above = lambda T_max: jnp.asarray(False) if T_max is None else T > T_max    # noqa: E731
    f = jnp.result_type(float)
    return ThermalResult(
        temperature=T, outlet_temperature=jnp.asarray(T_out, f), body_temperature=T, power=b["P"],
        power_film=jnp.asarray(b.get("P_film", 0.0), f), power_housing=jnp.asarray(b["P_B"], f),
        power_shaft=jnp.asarray(b["P_J"], f), heat_oil=jnp.asarray(b["heat_oil"], f), heat_convected=b["convected"],
        side_leakage=jnp.asarray(b.get("Q", 0.0), f), viscosity=jnp.asarray(b.get("eta", jnp.nan), f),
        film_overheated=above(T_max_film), body_overheated=above(heat.T_max_body), scene=b["scene"],
        iterations=stats.iterations, residual=stats.residual,
        result=jnp.where(b["valid"] | (stats.result != _solve.SUCCESS), stats.result, _solve.INNER_FAILED))


# ---- the dry scenes --------------------------------------------------------------------------------
def _dry(what, scene_fn, power_fn, heat, params, tol, max_iter, throw):
    checks.instance("heat", heat, HeatTransfer, "a vjax.HeatTransfer")

    def balance(T, p):
        s = scene_fn(T, p)
        P_B, P_J = power_fn(s)
        P = P_B + P_J
        T_star, heat_oil, convected = _removal(p["heat"], T, p["heat"].ambient, 0.0, P)
        return dict(T_star=T_star, valid=s.converged, scene=s, P=P, P_B=P_B, P_J=P_J, heat_oil=heat_oil,
                    convected=convected)

    T, b, stats = _solve_balance(balance, dict(params, heat=heat), False, _default_tol(heat.ambient, tol), max_iter)
    out = _result(T, T, b, stats, None, heat)
    _report(what, out, heat.T_limit, throw)
    return out


def thermal_pin(housing, R, radial_clearance, load, heat: HeatTransfer, *, shift, omega_shaft=0.0,
                omega_housing=0.0, options=None, throw=True, tol=None, max_iter=60, **scene_arguments):
    """:func:`vjax.pin_in_hole` with the housing at the bulk temperature T (C) its own
    hysteresis sets: P(T) = -Omega torque (W/m, Omega the patch speed) = ``heat.hA`` (T -
    T_ambient) (hA in W/(m K), per unit axial length; no oil). The housing's material is
    evaluated at T through ``shift``. Returns a :class:`ThermalResult` (``scene``: a
    :class:`~vjax.PinResult`); runaway and failures as :func:`thermal_journal_bearing`."""
    kw = dict(scene_arguments, **({} if options is None else dict(options=options)))

    def scene(T, p):
        return pin_in_hole(p["housing"], p["R"], p["c"], p["load"], omega_shaft=p["wJ"], omega_housing=p["wB"],
                           temperature=T, shift=p["shift"], throw=False, **kw)

    params = dict(housing=housing, R=R, c=radial_clearance, load=load, wJ=omega_shaft, wB=omega_housing, shift=shift)
    return _dry("thermal_pin", scene, lambda s: (-s.patch_speed * s.torque, 0.0 * s.torque), heat, params, tol,
                max_iter, throw)


def thermal_roller(housing, shaft, R_outer, R_inner, roller_diameter, n_rollers, load, heat: HeatTransfer, *,
                   shift, omega_shaft=0.0, omega_housing=0.0, options=None, throw=True, tol=None, max_iter=60,
                   **scene_arguments):
    """:func:`vjax.roller_bearing` with both rings at the bulk temperature T (C) their
    hysteresis sets: P = Omega_O T_O + Omega_I T_I (W/m, Omega the patch speeds relative to
    each ring, T each ring's torque about its own centre: the inner ring's centre is shifted
    by ``ring_shift`` along the load) = ``heat.hA`` (T - T_ambient) (W/(m K)). Returns a
    :class:`ThermalResult` (``scene``: a :class:`~vjax.RollerResult`)."""
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
