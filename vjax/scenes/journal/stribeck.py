"""Stribeck curves: a journal bearing with rough surfaces (finite, or infinitely long with
``length=None``: per unit length) swept in speed, from boundary friction (the asperities carry
the load) through mixed lubrication to a full film.

Each point is the steady state of :func:`vjax.journal_bearing` with ``roughness=``. The sweep
runs up from the lowest speed (the asperities carry nearly the whole load: the rigid estimate,
which holds their capacity, starts Newton well), each point from the last converged one;
points that fail on the way up run again downwards from the converged point above them. A
point that still fails is kept, with its result code, not dropped.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..._core import checks
from .bearing import journal_bearing
from .finite.steady import nests
from .options import FiniteJournalOptions
from .setup import oil_and_bodies

LIFT_OFF_SHARE = 0.01     # the lift-off speed: where the asperities' share of the load falls to this


@dataclasses.dataclass(frozen=True)
class StribeckCurve:
    """A Stribeck sweep (numpy arrays over ``speed``, ascending).

    ``speed`` (rad/s, the turning surface's), ``hersey`` eta omega / p_mean (p_mean = W / (L D),
    D = 2 R; the infinitely long bearing's W / D, W per unit length), ``friction_coefficient``,
    ``friction_viscous`` and ``friction_boundary`` (N; N/m for the infinitely long bearing),
    ``asperity_share``, ``eccentricity``, ``film_parameter`` lambda = h_min / sigma, ``converged``
    and ``result`` (the solver's code, 0 = converged) per point; ``results`` the scene's
    :class:`~vjax.FiniteJournalResult` (:class:`~vjax.JournalResult`) of each point.
    ``lift_off_speed``: where the asperity
    share falls to 1 % (log-linear interpolation between converged points; None if the sweep
    does not cross it); ``minimum_speed``: the Stribeck minimum, the speed of least friction
    (a parabola in log speed through the least converged point and its neighbours; None if the
    least is at an end of the sweep)."""

    speed: np.ndarray
    hersey: np.ndarray
    friction_coefficient: np.ndarray
    friction_viscous: np.ndarray
    friction_boundary: np.ndarray
    asperity_share: np.ndarray
    eccentricity: np.ndarray
    film_parameter: np.ndarray
    converged: np.ndarray
    result: np.ndarray
    results: tuple
    lift_off_speed: float | None
    minimum_speed: float | None

    def __repr__(self):
        lift = "none" if self.lift_off_speed is None else f"{self.lift_off_speed:.4g} rad/s"
        return (f"StribeckCurve({self.speed.size} speeds {self.speed[0]:.3g}..{self.speed[-1]:.3g} rad/s, "
                f"{int(self.converged.sum())} converged, lift-off {lift})")


def stribeck_curve(R, radial_clearance, viscosity, load, speeds, *, length=None, roughness, turning: str = "shaft",
                   progress=None, **kw) -> StribeckCurve:
    """Sweep a journal bearing with rough surfaces over ``speeds`` (rad/s, positive) of the
    ``turning`` surface ("shaft" or "housing", the other at rest). The other arguments are those
    of :func:`vjax.journal_bearing` (``roughness`` required; ``length`` None: the infinitely long
    bearing, ``load`` per unit length; ``throw`` is False for every point). ``progress``: called
    as progress(done, total) after each solve."""
    checks.one_of("turning", turning, ("shaft", "housing"))
    if roughness is None:
        raise ValueError("roughness: a Stribeck curve needs rough surfaces (a vjax.Roughness)")
    for name in ("omega_shaft", "omega_housing", "initial", "throw"):
        if name in kw:
            raise ValueError(f"{name}: set by the sweep (the speeds, the warm starts, throw=False)")
    speeds = np.sort(np.asarray(speeds, float).ravel())
    if speeds.size < 2 or not np.all(np.isfinite(speeds)) or not np.all(speeds > 0):
        raise ValueError(f"speeds must be two or more positive finite angular speeds (rad/s), got {speeds!r}")
    speed_name = "omega_shaft" if turning == "shaft" else "omega_housing"
    eta, _ = oil_and_bodies(viscosity, kw.get("temperature"), kw.get("oil_temperature"), kw.get("housing"),
                            kw.get("shaft"), None)     # the oil's viscosity (Pa s) for the Hersey number

    def solve(w, initial):
        return journal_bearing(R, radial_clearance, viscosity, load, length=length, roughness=roughness,
                               initial=initial, throw=False, **{speed_name: float(w)}, **kw)

    # on a grid whose cold solves start from a coarser grid's solution, that start is nearer the
    # root than the last point's (a speed step moves a film's cavity by many cells, one per
    # Newton step from a warm start): cold starts, the warm one kept for failures
    options = kw.get("options")
    cold = isinstance(options, FiniteJournalOptions) and nests(options)
    results = [None] * speeds.size
    done, total = 0, speeds.size
    last = None
    # up from the slowest speed: there the asperities carry nearly the whole load, which the
    # rigid estimate holds (their capacity in it), and each faster point lifts the film a little
    # from the last one; down from the full film, a step into the mixed regime can move the
    # contact by more than a warm Newton follows (the main job's lined bearing: one point of 13
    # fell back to continuation, 400 steps, 3x the whole sweep's other steps)
    for i in range(speeds.size):
        results[i] = solve(speeds[i], None if cold else last)
        if cold and not bool(results[i].converged) and last is not None:
            results[i] = solve(speeds[i], last)
        done += 1
        if progress is not None:
            progress(done, total)
        if bool(results[i].converged):
            last = results[i]
    for i in range(speeds.size - 2, -1, -1):           # the failures again, down from above
        if not bool(results[i].converged) and bool(results[i + 1].converged):
            retry = solve(speeds[i], results[i + 1])
            if bool(retry.converged):
                results[i] = retry
    field = lambda name: np.array([float(np.asarray(getattr(r, name))) for r in results])   # noqa: E731
    converged = np.array([bool(r.converged) for r in results])
    W = float(np.linalg.norm(np.atleast_1d(np.asarray(load, float))))
    p_mean = W / ((1.0 if length is None else float(length)) * 2 * float(R))
    mu = field("friction_coefficient")
    share = field("asperity_share")
    return StribeckCurve(
        speed=speeds, hersey=float(eta) * speeds / p_mean, friction_coefficient=mu,
        friction_viscous=field("friction_viscous"), friction_boundary=field("friction_boundary"),
        asperity_share=share, eccentricity=field("eccentricity"), film_parameter=field("film_parameter"),
        converged=converged, result=np.array([int(np.asarray(r.result)) for r in results]), results=tuple(results),
        lift_off_speed=_lift_off(speeds, share, converged), minimum_speed=_minimum(speeds, mu, converged))


def _lift_off(speed, share, converged):
    """The speed where the asperity share falls through LIFT_OFF_SHARE (log-linear between the
    converged points around the highest crossing), or None."""
    s, a = speed[converged], share[converged]
    above = np.flatnonzero(a >= LIFT_OFF_SHARE)
    if above.size == 0 or above[-1] == a.size - 1:
        return None
    i = above[-1]
    t = (math.log(a[i]) - math.log(LIFT_OFF_SHARE)) / (math.log(a[i]) - math.log(max(a[i + 1], 1e-300)))
    return float(math.exp(math.log(s[i]) + t * (math.log(s[i + 1]) - math.log(s[i]))))


def _minimum(speed, mu, converged):
    """The speed of least friction: the vertex of the parabola in log speed through the least
    converged point and its two neighbours, or None at an end of the sweep."""
    s, m = np.log(speed[converged]), mu[converged]
    i = int(np.argmin(m)) if m.size else 0
    if m.size < 3 or i in (0, m.size - 1):
        return None
    a, b, c = np.polyfit(s[i - 1:i + 2], m[i - 1:i + 2], 2)
    return float(np.exp(-b / (2 * a))) if a > 0 else float(np.exp(s[i]))
