"""The heat balance of a level 1 thermal scene: ISO 7902-1's effective temperature (internal).

A scene dissipates a power P(T) that depends on the temperature T at which its oil and its
bodies are evaluated (the lubricant's viscosity law, each body's material through its shift
law). The power leaves with the oil and through housing and shaft (docs/theory.md §19,
"Thermal balance (level 1)"):

    P(T) = rho c_p Q (T_out - T_in) + hA (T - T_amb),       T_out = 2 T - T_in (journal bearing)

The effective temperature T is the root of r(T) = T - T*(T), with

    T*(T) = T_amb + (P(T) + G(T) (T_in - T_amb)) / (G(T) + hA),     G = 2 rho c_p Q,

the temperature the balance would give if the mechanics were frozen at T (plain successive
substitution iterates T <- T*(T), which diverges where |dT*/dT| > 1: ISO 7902's heavily
loaded fast bearings). The root is bracketed and found by secant steps safeguarded by
bisection (:func:`vjax._core.root.rising_root`); each residual is a full solve of the scene at
T. Derivatives are implicit (:func:`vjax._core.solve.implicit_root`): dT = dr/dparams / (dr/dT),
never through the iterations; jit, vmap and grad go through. Outside jit the iterations run in
Python over the scene's own compiled solve (no new compilation); under a trace, in a
``lax.while_loop``.

No root below ``HeatTransfer.T_limit`` (the generated heat outgrowing the removed heat, or no
removal at all) is thermal runaway: the one failure path (:func:`report`) raises
:class:`~vjax.ConvergenceError` naming it and the temperatures reached, or with ``throw=False``
the result code :data:`RUNAWAY`.
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

from ..._core import checks, root, scene as _scene, solve as _solve

RUNAWAY = _solve.RUNAWAY       # result code: no steady state below T_limit (the core's: no root below the bound)


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
            code = int(self.result)
            words = "thermal runaway: no steady state below T_limit" if code == _solve.RUNAWAY else _solve.MESSAGES[code]
            parts.append(f"status: {words}")
        return sep.join(parts)


def default_tol(T_ref, tol):
    """The balance's tolerance on |T - T*(T)| (K): ``tol``, or a few hundred round-offs of the
    absolute temperature ``T_ref`` (C; traced: of 100 C)."""
    if tol is not None:
        return tol
    eps = float(jnp.finfo(jnp.result_type(float)).eps)
    T_ref = checks.values("T_supply", T_ref)
    T_K = 373.15 if T_ref is None else 273.15 + abs(float(np.max(T_ref)))      # traced: a 100 C scale
    return (1e3 if eps < 1e-10 else 30.0) * eps * T_K


def solve_balance(balance, params, oil_in: bool, tol, max_iter):
    """The effective temperature of ``balance(T, params) -> dict`` (T_star, valid, ...),
    differentiated implicitly; then the balance at it. ``params["heat"]``: the HeatTransfer;
    ``oil_in``: the oil's supply temperature bounds the root from below too. Returns
    (T, the balance at T, Stats)."""
    def solver(p):
        h = p["heat"]
        lo = jnp.minimum(h.T_supply, h.ambient) if oil_in else h.ambient

        def residual(T):
            b = balance(T, p)
            return T - b["T_star"], b["valid"]
        T, stats = root.rising_root(residual, lo, h.T_limit, tol, max_iter)
        return jnp.atleast_1d(T), stats

    def residual(x, aux, p):
        return jnp.atleast_1d(x[0] - balance(x[0], p)["T_star"])

    x, stats = _solve.implicit_root(solver, residual)(params)
    return x[0], balance(x[0], params), stats


def removal(heat, T, T_in, G_oil, P):
    """T* and the heat flows at T for the power P and the oil's conductance G_oil = 2 rho c_p Q."""
    hA, T_amb = heat.hA, heat.ambient
    G = G_oil + hA
    T_star = T_amb + jnp.where(G > 0, (P + G_oil * (T_in - T_amb)) / jnp.where(G > 0, G, 1.0), jnp.inf)
    T_star = jnp.where(jnp.isinf(hA), T_amb, T_star)
    heat_oil = G_oil * (T - T_in)
    convected = jnp.where(jnp.isinf(hA), P - heat_oil, hA * (T - T_amb))
    return T_star, heat_oil, convected


def result_at(T, T_out, b, stats, T_max_film, heat):
    """The :class:`ThermalResult` at the root T of the balance ``b``; a scene that did not
    converge there makes a converged root INNER_FAILED."""
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


def _hint(result, T, P, removed, T_limit):
    """The failed balance's cause and what the user can change (W: W/m for the per-unit-length scenes)."""
    if result == RUNAWAY:
        return (f" This is thermal runaway: the heat generated grows faster with temperature than the heat "
                f"removed, and no steady state exists up to T_limit = {T_limit:.6g} C; reached T = {T:.6g} C "
                f"generating {P:.6g} W against {removed:.6g} W removed. More cooling (a larger hA or oil flow), or "
                f"a higher HeatTransfer.T_limit if the material holds there.")
    if result == _solve.INNER_FAILED:
        return (f" The scene itself did not converge at T = {T:.6g} C (outside jit its result is the error's "
                f".solution.scene): the scene's options, or an operating point it solves.")
    return (f" Its iterations are scene solves, its residual |T - T*(T)| (K), at T = {T:.6g} C: a larger max_iter "
            f"or tol.")


def report(what: str, out: ThermalResult, T_limit, throw: bool):
    """The one failure path (:func:`vjax._core.solve.report`), its hint naming the balance's cause."""
    _solve.report(f"{what}'s heat balance", out, throw, hint=_hint,
                  values=dict(T=out.temperature, P=out.power, removed=out.heat_oil + out.heat_convected,
                              T_limit=T_limit))
