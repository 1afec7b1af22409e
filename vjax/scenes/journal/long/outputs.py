"""The infinitely long journal bearing's result: force, torques (shear and viscoelastic),
dissipation, film and eccentricity (with rough surfaces the asperities' share and boundary
friction), from converged unknowns."""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp

from ...._core import scene as _scene
from ....films import reynolds
from ....films.roughness import friction_factor, shear_stress_factors
from . import film


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class JournalResult(_scene.SceneResult):
    """Solution of :func:`journal_bearing` (SI units, per unit axial length).

    Arrays on the ring grid (line-of-centres frame, theta = 0 at the smallest rigid gap):
    ``theta`` (rad), ``pressure`` (Pa, gauge), ``film`` h (m), ``displacement`` of the
    housing's bore u_B (m, outward, into the housing), ``displacement_shaft`` u_J (m, inward,
    into the journal).

    ``force``: pressure force of the film on the housing (N/m, absolute x, y; the load at
    equilibrium). ``film_fraction``: liquid fraction of the film (1 in a full film, below 1
    in a "jfo" cavity; 1 everywhere for the other conditions). ``torque``: by the fluid on
    the housing about O; ``torque_shaft``: on the journal about O'; ``torque_shaft_about_O``; ``torque_viscoelastic``,
    ``torque_viscoelastic_shaft``: the pressure-on-deformed-profile parts (N m/m, CCW
    positive; see the module docstring). ``friction_radius``: |torque|/|force| (m).
    ``eccentricity`` eps = e/c of the journal centre; ``eccentricity_effective`` first Fourier
    mode of h over c (positive on the physical branch; independent of the log reference
    length); ``attitude_angle`` (rad, signed angle from the load line to the line of centres,
    counter-clockwise positive); ``line_of_centres_angle`` (absolute, rad); ``min_film`` (m);
    ``rupture_angle`` (rad, line-of-centres frame, where the film cavitates; for "sommerfeld"
    the downstream zero of p); dissipation (W/m) ``dissipation_fluid``,
    ``dissipation_housing``, ``dissipation_shaft``; ``supply_flow`` Q_s (m^2/s, net outflow of
    the groove cell; can be negative: the Swift-Stieber cavity does not conserve mass);
    ``hersey`` H = eta v R_B/|F| (signed, as the thesis).

    Mixed lubrication (``roughness=``; per unit length as everything here): ``force`` is that
    of the film and the asperities together, ``asperity_force`` (N/m, on the housing, absolute)
    the asperities' part, ``asperity_share`` its magnitude over the load, ``asperity_pressure``
    (Pa, on the grid) their Greenwood-Tripp pressure; the shear torques carry Patir and Cheng's
    shear stress factors and the asperities' friction mu_b p_a. Friction (N/m, resisting the
    surfaces' sliding, positive): the shear on the journal over the film's arc R dtheta (its
    torque over R_J), ``friction_viscous`` from the film's shear and ``friction_boundary`` from
    mu_b p_a; ``friction_coefficient`` their sum over the load; ``film_parameter`` lambda =
    min_film / sigma (inf for smooth surfaces); ``dissipation_fluid`` the film's with the
    factors, ``dissipation_boundary`` the asperities' friction times the sliding speed (W/m; 0
    for smooth surfaces).

    Convergence: ``iterations`` (Newton steps on this grid, summed over stages; a nested
    coarse-grid start is not counted), ``stages`` (continuation stages, 0 = direct),
    ``residual`` (max-norm of the scaled equations), ``result``; ``converged`` is ``result == 0``.
    """

    theta: jax.Array
    pressure: jax.Array
    film: jax.Array
    displacement: jax.Array
    displacement_shaft: jax.Array
    film_fraction: jax.Array
    force: jax.Array
    torque: jax.Array
    torque_shaft: jax.Array
    torque_shaft_about_O: jax.Array
    torque_viscoelastic: jax.Array
    torque_viscoelastic_shaft: jax.Array
    friction_radius: jax.Array
    eccentricity: jax.Array
    eccentricity_effective: jax.Array
    attitude_angle: jax.Array
    line_of_centres_angle: jax.Array
    min_film: jax.Array
    rupture_angle: jax.Array
    dissipation_fluid: jax.Array
    dissipation_housing: jax.Array
    dissipation_shaft: jax.Array
    supply_flow: jax.Array
    hersey: jax.Array
    asperity_pressure: jax.Array
    asperity_force: jax.Array
    asperity_share: jax.Array
    friction_viscous: jax.Array
    friction_boundary: jax.Array
    friction_coefficient: jax.Array
    film_parameter: jax.Array
    dissipation_boundary: jax.Array
    iterations: jax.Array
    stages: jax.Array
    residual: jax.Array
    result: jax.Array


def outputs(x, pr: film.Params, cfg: film.Config, stats, stages):
    n = cfg.options.n
    f = film.fields(x, pr, cfg)
    p, h, hf, dpds, th, dth = f["p"], f["h"], f["hf"], f["dpds"], f["theta"], f["dth"]
    R, RJ, eta, c = pr.R, pr.RJ, pr.eta, pr.c
    eps, phi = x[n], x[n + 1]
    pres = f["p_load"]
    dU = pr.omega_B * R - pr.omega_J * RJ
    # a striated ("jfo") cavity shears only its liquid: the upwind fraction of each face
    liquid = reynolds.face_fraction(f["fraction"], pr.v)
    rough, p_a = pr.rough, f["p_asp"]
    if rough is None:
        tauB = -0.5 * hf * dpds - liquid * eta * dU / hf
        tauJ = -0.5 * hf * dpds + liquid * eta * dU / hf
        couette_gap = hf
    else:
        # Patir and Cheng (1979): the mean shear on each surface, the factors at H_c; the shear
        # stress factor Phi_fs enters the journal's with -Vr, the bore's with +Vr
        Hc, hc = rough.clipped(hf)
        fs, fp = shear_stress_factors(Hc, rough.gamma)
        ff = friction_factor(Hc)
        tauB = -0.5 * fp * hc * dpds - liquid * eta * dU / hc * (ff + rough.Vr * fs)
        tauJ = -0.5 * fp * hc * dpds + liquid * eta * dU / hc * (ff - rough.Vr * fs)
        couette_gap = hc / ff      # the Couette shear's mean factor phi_f (the two surfaces' Phi_fs cancel)
    # the asperities' friction mu_b p_a opposes the sliding on both surfaces (per unit length)
    sliding = film.sliding(pr)
    boundary = -jnp.sign(sliding) * (0.0 if rough is None else rough.mu_b) * R * dth * jnp.sum(p_a)
    central = lambda u: 0.5 * (jnp.roll(u, -1) - jnp.roll(u, 1))
    CvB = -R * jnp.sum(pres * central(f["uB"]))
    CvJ = -R * jnp.sum(pres * central(f["uJ"]))
    CJ_visc = RJ * R * dth * jnp.sum(tauJ)
    CB = R * R * dth * jnp.sum(tauB) - R * boundary + CvB
    CJ = CJ_visc + RJ * boundary + CvJ
    # pressure force on the journal in the line-of-centres frame (th: angles from it); the
    # housing gets minus it
    off = film.offset(x, cfg)
    th = th - off
    Fx = -R * dth * jnp.sum((pres + p_a) * jnp.cos(th))
    Fy = -R * dth * jnp.sum((pres + p_a) * jnp.sin(th))
    Fa = -R * dth * jnp.stack([jnp.sum(p_a * jnp.cos(th)), jnp.sum(p_a * jnp.sin(th))])
    Df = R * dth * jnp.sum(reynolds.conductance_gap(hf, rough) * dpds**2 / (12 * eta)
                           + liquid * eta * dU**2 / couette_gap)
    # friction on the journal's surface resisting its sliding (N/m): its shear over the film's
    # arc R dtheta, the torque's parts over R_J
    resisting = -jnp.sign(sliding) / RJ
    friction_viscous, friction_boundary = resisting * CJ_visc, resisting * RJ * boundary
    g = pr.groove
    gamma = pr.load_angle + phi
    rot = jnp.array([[jnp.cos(gamma), -jnp.sin(gamma)], [jnp.sin(gamma), jnp.cos(gamma)]])
    force = -rot @ jnp.stack([Fx, Fy])
    return JournalResult(
        theta=th, pressure=pres, film=h, displacement=f["uB"], displacement_shaft=f["uJ"],
        film_fraction=f["fraction"], force=force,
        torque=CB, torque_shaft=CJ, torque_shaft_about_O=CJ + eps * c * Fy, torque_viscoelastic=CvB,
        torque_viscoelastic_shaft=CvJ, friction_radius=jnp.abs(CB) / jnp.hypot(Fx, Fy), eccentricity=eps,
        eccentricity_effective=film.effective_eps(h, c, off), attitude_angle=phi,
        line_of_centres_angle=jnp.angle(jnp.exp(1j * gamma)), min_film=jnp.min(h),
        # half-Sommerfeld: the zero crossing of the unclipped (full-Sommerfeld) pressure
        rupture_angle=reynolds.rupture_angle(p, th, pr.v, "sommerfeld" if cfg.cavitation == "half_sommerfeld"
                                             else cfg.cavitation),
        dissipation_fluid=Df, dissipation_housing=-pr.omega_B * CvB, dissipation_shaft=-pr.omega_J * CvJ,
        supply_flow=f["q"][g] - f["q"][(g - 1) % n], hersey=eta * pr.v * R / pr.W,
        asperity_pressure=p_a, asperity_force=-rot @ Fa, asperity_share=jnp.hypot(Fa[0], Fa[1]) / pr.W,
        friction_viscous=friction_viscous, friction_boundary=friction_boundary,
        friction_coefficient=(friction_viscous + friction_boundary) / pr.W,
        film_parameter=jnp.full((), jnp.inf, h.dtype) if rough is None else jnp.min(h) / rough.sigma,
        dissipation_boundary=jnp.abs(boundary * dU),
        iterations=stats.iterations, stages=stages, residual=stats.residual, result=stats.result)
