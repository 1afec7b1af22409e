"""The finite journal bearing's result: forces and moment, position, film, torques (Couette,
Poiseuille, viscoelastic; with rough surfaces the asperities' share and boundary friction),
flows and power, from converged unknowns."""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp

from ...._core import scene as _scene
from ....films import film2d
from ....films.roughness import friction_factor, shear_stress_factors
from .film import Config, Params, fields, rotation, sliding


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class FiniteJournalResult(_scene.SceneResult):
    """Solution of ``journal_bearing(..., length=L)`` (SI totals for the bearing; see
    :mod:`vjax.scenes.journal.finite`). Arrays on the grid: ``theta`` (n,) from the load direction
    (rad), ``z`` (m + 1,) axial nodes (m), ``pressure`` and ``film`` (n, m + 1) (Pa, m),
    ``film_fraction`` (n, m + 1): the liquid fraction of the film (below 1 in a "jfo" cavity),
    ``displacement`` of the bore and ``displacement_shaft`` of the journal (n, m + 1) (m,
    each positive where it opens the film; zero for a rigid body). ``force`` and ``moment``
    are those of the film and, with rough surfaces, the asperities together (the load at
    equilibrium); ``asperity_force`` (N, on the housing, absolute) the asperities' part,
    ``asperity_share`` its magnitude over the load, ``asperity_pressure`` (n, m + 1) (Pa) their
    Greenwood-Tripp pressure. Friction (N, resisting the surfaces' sliding, positive): the
    shear on the journal over the film's area R dtheta dz (its torque over R_J),
    ``friction_viscous`` from the film's shear (Patir and Cheng's
    shear stress factors on rough surfaces) and ``friction_boundary`` from mu_b p_a;
    ``friction_coefficient`` their sum over the load; ``film_parameter`` lambda = min_film /
    sigma (inf for smooth surfaces). Convergence: ``iterations``, ``residual``, ``result``;
    ``converged`` is ``result == 0``."""

    theta: jax.Array
    z: jax.Array
    pressure: jax.Array
    film: jax.Array
    film_fraction: jax.Array
    displacement: jax.Array
    displacement_shaft: jax.Array
    force: jax.Array
    moment: jax.Array
    position: jax.Array
    eccentricity: jax.Array
    attitude_angle: jax.Array
    line_of_centres_angle: jax.Array
    min_film: jax.Array
    min_film_theta: jax.Array
    min_film_z: jax.Array
    max_pressure: jax.Array
    torque: jax.Array
    torque_shaft: jax.Array
    torque_poiseuille: jax.Array
    torque_poiseuille_shaft: jax.Array
    torque_viscoelastic: jax.Array
    torque_viscoelastic_shaft: jax.Array
    side_leakage: jax.Array
    supply_flow: jax.Array
    inlet_flow: jax.Array
    power_loss: jax.Array
    asperity_pressure: jax.Array
    asperity_force: jax.Array
    asperity_share: jax.Array
    friction_viscous: jax.Array
    friction_boundary: jax.Array
    friction_coefficient: jax.Array
    film_parameter: jax.Array
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array


def outputs(x, pr: Params, cfg: Config, stats):
    f = fields(x, pr, cfg)
    n = cfg.n
    R, RJ, eta, z, theta = pr.R, pr.RJ, pr.eta, f["z"], f["theta"]
    dth = 2 * jnp.pi / n
    wz = film2d.node_widths(z)
    hx, dpdx, eta_x = f["hx"], f["dpdx"], f["eta_x"]
    dU = pr.omega_B * R - pr.omega_J * RJ
    # a striated ("jfo") cavity shears only its liquid: the upwind fraction of each face
    liquid = film2d.upwind(f["fraction"], pr.v)
    arc = R * dth
    rough, p_a = pr.rough, f["p_asp"]
    if rough is None:
        poiseuille = (-0.5 * hx * dpdx) @ wz
        TB_p = R * arc * jnp.sum(poiseuille)
        TJ_p = RJ * arc * jnp.sum(poiseuille)
        couette_B = couette_J = (liquid * eta_x * dU / hx) @ wz
    else:
        # Patir and Cheng (1979): the mean shear on each surface, the factors at H_c; the shear
        # stress factor Phi_fs enters the journal's with -Vr, the bore's with +Vr
        Hc, hc = rough.clipped(hx)
        fs, fp = shear_stress_factors(Hc, rough.gamma)
        ff = friction_factor(Hc)
        poiseuille = (-0.5 * fp * hc * dpdx) @ wz
        TB_p = R * arc * jnp.sum(poiseuille)
        TJ_p = RJ * arc * jnp.sum(poiseuille)
        couette_J = (liquid * eta_x * dU / hc * (ff - rough.Vr * fs)) @ wz
        couette_B = (liquid * eta_x * dU / hc * (ff + rough.Vr * fs)) @ wz
    # the asperities' friction mu_b p_a opposes the sliding on both surfaces (p_a on the nodes)
    boundary = -jnp.sign(sliding(pr)) * (0.0 if rough is None else rough.mu_b) * arc * jnp.sum(p_a @ wz)
    # the pressure on each slice's deformed profile: its moment about the body's centre
    # (the viscoelastic torque of the long bearing, per slice; central differences in theta)
    central = lambda u: 0.5 * (jnp.roll(u, -1, axis=0) - jnp.roll(u, 1, axis=0))
    TvB, TvJ = (-R * jnp.sum(f["p_load"] * central(u), axis=0) @ wz for u in (f["uB"], f["uJ"]))
    TB_visc = TB_p - R * arc * jnp.sum(couette_B)
    TJ_visc = TJ_p + RJ * arc * jnp.sum(couette_J)
    TB = TB_visc - R * boundary + TvB
    TJ = TJ_visc + RJ * boundary + TvJ
    # the film's dissipation (Poiseuille and Couette); with rough surfaces the conductances'
    # gap terms and the Couette shear's mean factor phi_f (the two surfaces' Phi_fs cancel),
    # plus the asperities' friction mu_b p_a times the sliding speed
    couette_gap = hx if rough is None else hc / ff
    power = arc * jnp.sum((f["gx"] * dpdx**2 / (12 * eta_x) + liquid * eta_x * dU**2 / couette_gap) @ wz) \
        + arc * jnp.sum(f["gz"] * f["dpdz"] ** 2 / (12 * f["eta_z"]) * jnp.diff(z)[None, :]) \
        + jnp.abs(boundary * dU)
    # under JFO the cells conserve mass: the end faces' flow, exactly what the groove supplies;
    # Reynolds' and Sommerfeld's conditions lose or make mass in the cavity, so the groove's
    # outflow is not what leaves: the ends' flow from their pressure gradient (closer at a grid)
    leakage = (film2d.end_outflow(f, R) if cfg.cavitation == "jfo"
               else film2d.end_gradient_outflow(f["p"], f["h"], z, R, eta, rough))
    # friction on the journal's surface resisting its sliding (N): its shear over the film's
    # area R dtheta dz, the torque's parts over R_J
    resisting = -jnp.sign(sliding(pr)) / RJ
    friction_viscous, friction_boundary = resisting * TJ_visc, resisting * RJ * boundary
    # the groove's net outflow: its interior cells, the ones held at the supply pressure; its
    # downstream flow into the land: every node of its column (the end nodes' half cells carry
    # Couette flow too)
    supply = jnp.sum(pr.groove[:, 1:-1] * film2d.net_outflow(f, R, z))
    qx = f["qx"]
    downstream = jnp.where(pr.v >= 0, qx, -jnp.roll(qx, 1, axis=0))
    # a circumferential groove feeds the land axially: all its outflow goes in
    inlet = jnp.where(pr.circumferential > 0, supply, jnp.sum(pr.groove * downstream * wz[None, :]))
    F, M = film2d.resultants(f["p_load"] + p_a, theta, z, R)
    F_asp, _ = film2d.resultants(p_a, theta, z, R)
    rot = lambda a: rotation(pr.frame) @ a
    e = f["e"]
    h = f["h"]
    k = jnp.argmin(h)
    i, j = k // h.shape[1], k % h.shape[1]
    load_dir = jnp.arctan2(pr.load[1], pr.load[0])
    phi = jnp.angle(jnp.exp(1j * (jnp.arctan2(e[1], e[0]) - load_dir)))
    return FiniteJournalResult(
        theta=theta, z=z, pressure=f["p_load"], film=h, film_fraction=f["fraction"], displacement=f["uB"],
        displacement_shaft=f["uJ"], force=-rot(F),
        moment=rot(M), position=rot(e), eccentricity=jnp.hypot(e[0], e[1]) / pr.c, attitude_angle=phi,
        line_of_centres_angle=jnp.angle(jnp.exp(1j * (pr.frame + jnp.arctan2(e[1], e[0])))),
        min_film=h[i, j], min_film_theta=theta[i], min_film_z=z[j], max_pressure=jnp.max(f["p_load"]),
        torque=TB, torque_shaft=TJ, torque_poiseuille=TB_p, torque_poiseuille_shaft=TJ_p,
        torque_viscoelastic=TvB, torque_viscoelastic_shaft=TvJ,
        side_leakage=leakage, supply_flow=supply, inlet_flow=inlet, power_loss=power,
        asperity_pressure=p_a, asperity_force=-rot(F_asp), asperity_share=jnp.hypot(*F_asp) / pr.W,
        friction_viscous=friction_viscous, friction_boundary=friction_boundary,
        friction_coefficient=(friction_viscous + friction_boundary) / pr.W,
        film_parameter=jnp.full((), jnp.inf, h.dtype) if rough is None else h[i, j] / rough.sigma,
        iterations=stats.iterations, residual=stats.residual, result=stats.result)
