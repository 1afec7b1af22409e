"""The finite journal bearing's set-up: checked arguments -> parameters and configuration
(the groove's nodes, the axial spacing, the bodies' operators on the land grid), and a start
from a previous solution."""
from __future__ import annotations

import math
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from ...._core import checks, scene as _scene
from ....films import film2d, reynolds
from ....films.roughness import Roughness
from ..options import FiniteJournalOptions
from ..setup import bodies_at, check_arguments
from .film import Config, Params, as_unknowns, rotation, unknowns


GROOVES = ("fixed", "circumferential")


def setup(R, radial_clearance, viscosity, load, length, *, housing=None, shaft=None, omega_shaft=0.0,
          omega_housing=0.0, load_angle=-math.pi / 2, memory="periodic", cavitation="reynolds",
          supply_angle=math.pi, supply_pressure=0.0, supply_width=1.0, tilt=None, temperature=None, shift=None,
          groove="fixed", roughness: Roughness | None = None,
          options: FiniteJournalOptions = FiniteJournalOptions()):
    """Checked arguments -> (:class:`Params` with a zero start, :class:`Config`); ``groove``
    "fixed" (an axial groove at ``supply_angle``) or "circumferential"; ``roughness`` a
    :class:`~vjax.Roughness` (mixed lubrication) or None (smooth surfaces)."""
    checks.one_of("groove", groove, GROOVES)
    checks.instance("options", options, FiniteJournalOptions, "a vjax.FiniteJournalOptions (with length=)")
    check_arguments(R, radial_clearance, viscosity, load, omega_shaft=omega_shaft, omega_housing=omega_housing,
                    load_angle=load_angle, memory=memory, cavitation=cavitation, supply_pressure=supply_pressure,
                    length=length)
    sw = checks.values("supply_width", supply_width)
    if sw is None or not (0 < sw <= 1):
        raise ValueError(f"supply_width must be a concrete number in (0, 1] (a fraction of the length), "
                         f"got {supply_width!r}")
    housing, shaft = bodies_at(R, radial_clearance, housing, shaft, temperature, shift)
    if any(b is not None and b.axial == "3d" for b in (housing, shaft)) and options.spacing != "uniform":
        raise ValueError("a 3D layer (axial='3d') needs uniform axial nodes (its cosine modes): "
                         "FiniteJournalOptions(spacing='uniform')")
    if roughness is not None:
        checks.instance("roughness", roughness, Roughness, "a vjax.Roughness (or None: smooth surfaces)")
    if tilt is not None:
        checks.finite("tilt", tilt)
        if np.shape(tilt) != (2,):
            raise ValueError(f"tilt must be two angles (gamma_x, gamma_y) (rad), got shape {np.shape(tilt)}")
        _check_tilt_fits(tilt, length, radial_clearance, roughness)
    n, m = options.n, options.m
    s = film2d.unit_nodes(m, options.spacing)     # z / (L/2)
    mask = np.zeros((n, m + 1))
    circumferential = groove == "circumferential"
    if circumferential:
        if supply_width != 1.0:
            raise ValueError("supply_width is the axial extent of an axial groove; a circumferential groove "
                             "(groove='circumferential') runs round the mid-width: leave supply_width at 1")
        mask[:, m // 2] = 1.0            # the mid-width nodes (m is even: z = 0 is a node)
    elif supply_angle is not None:
        _scene.scalars(checks.finite, supply_angle=supply_angle)
        sa = checks.values("supply_angle", supply_angle)
        if sa is None:
            raise ValueError("supply_angle must be a concrete number (it selects a grid column)")
        g = int(round(float(sa) % (2 * math.pi) / (2 * math.pi / n))) % n
        mask[g] = np.abs(s) <= float(sw) * (1 + 1e-12)
    floor = 1e-10 if jnp.result_type(float) == jnp.float64 else 1e-4
    rigid = housing is None and shaft is None
    cfg = Config(cavitation, n, m, float(options.tol if options.tol is not None else floor), options.max_iter,
                 krylov=options.krylov and not rigid)
    pr = _params(*_scene.canonical(R, radial_clearance, viscosity, length, load, load_angle, tilt, omega_housing,
                                   omega_shaft, supply_pressure), mask, float(circumferential), s, housing, shaft,
                 roughness, unknowns=unknowns(cfg), memory=memory)
    return pr, cfg


def _check_tilt_fits(tilt, length, radial_clearance, roughness):
    """Refuse a tilt that moves the journal's ends by a clearance or more: a smooth film
    cannot carry that (the ends would cut through the bore); rough surfaces can (edge contact
    on the asperities)."""
    values = [checks.values(k, v) for k, v in (("tilt", tilt), ("length", length),
                                                ("radial_clearance", radial_clearance))]
    if roughness is not None or any(v is None for v in values):
        return
    gamma, L, c = values
    ends = float(np.hypot(*np.asarray(gamma, float))) * float(L) / 2
    if ends >= c:
        raise ValueError(f"tilt={tuple(float(g) for g in np.asarray(gamma, float))} moves the journal's ends by {ends / c:.3g} "
                         f"clearances: a smooth film cannot carry it (the ends would cut through the bore). The "
                         f"largest tilt this clearance allows is |tilt| < 2 c / L = {2 * c / L:.3g} rad; with a "
                         f"roughness (roughness=vjax.Roughness(...)) the asperities carry the edge contact")


@partial(jax.jit, static_argnames=("unknowns", "memory"))
def _params(R, radial_clearance, viscosity, length, load, load_angle, tilt, omega_housing, omega_shaft,
            supply_pressure, groove, circumferential, s, housing, shaft, roughness, *, unknowns, memory):
    """Checked arguments -> :class:`Params` with a zero start, in one compiled program (eager,
    each of its operations would compile on a first call)."""
    dtype = jnp.result_type(float)
    f = lambda v: jnp.asarray(v, dtype)
    load = f(load)
    Wvec = jnp.stack([load * jnp.cos(load_angle), load * jnp.sin(load_angle)]) if load.ndim == 0 else load
    frame = jax.lax.stop_gradient(jnp.arctan2(Wvec[1], Wvec[0]))
    turn = lambda a: rotation(frame).T @ a
    tilt = jnp.zeros(2, dtype) if tilt is None else f(tilt)
    W = jnp.hypot(Wvec[0], Wvec[1])
    v = 0.5 * (omega_housing * R + omega_shaft * (R - radial_clearance))
    return Params(R=f(R), RJ=f(R - radial_clearance), c=f(radial_clearance), L=f(length), eta=f(viscosity), v=f(v),
                  W=W, load=turn(Wvec), frame=frame, tilt=turn(tilt), ps=f(supply_pressure), omega_B=f(omega_housing),
                  omega_J=f(omega_shaft), p_ref=W / (2 * f(R) * f(length)), groove=f(groove),
                  circumferential=f(circumferential), s=f(s),
                  # the pressure pattern is fixed in space: it moves at -omega relative to each body
                  op_B=_operator(housing, R, groove.shape, length, -omega_housing, memory),
                  op_J=_operator(shaft, R - radial_clearance, groove.shape, length, -omega_shaft, memory),
                  compliance=f(1.0), smoothing=f(0.0), rough=roughness, x0=jnp.zeros(unknowns + 2, dtype))


def _operator(body, R, shape, length, omega, memory):
    """A body's operator on the (n, m + 1) grid: None (rigid), the plane ring's for the slices, a
    3D layer's land operator."""
    if body is None:
        return None
    if body.axial == "3d":
        return body.land_operator(R, shape[0], shape[1] - 1, length, omega, memory)
    return body.operator(R, shape[0], omega, memory)


@partial(jax.jit, static_argnums=(2,))
def start_from(solution, pr: Params, cfg: Config):
    """Unknowns from a :class:`FiniteJournalResult` (:func:`as_unknowns`), as a start that is not
    differentiated."""
    x = as_unknowns(solution.pressure / pr.p_ref, solution.position, pr, cfg, solution.asperity_pressure)
    return jax.lax.stop_gradient(x).astype(pr.x0.dtype)


def check_supported(length, groove, cavitation):
    """Refuse, naming the argument, what the finite bearing does not have: a groove turning with
    the line of centres; and tilt without a length."""
    if length is None:
        raise ValueError("tilt and supply_width need a finite bearing: give its length (m)")
    if groove not in (None,) + GROOVES:
        raise ValueError(f"groove must be 'fixed' (an axial groove fixed in the bearing) or 'circumferential' "
                         f"with length=, got {groove!r}")
    checks.one_of("cavitation", cavitation, reynolds.CAVITATION)
