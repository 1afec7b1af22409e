"""A finite film's shear: the liquid fraction of a striated cavity and the film's friction power
(internal; docs/theory.md §19, "The film's power").

Under Reynolds conditions the cavity is not a full film: the flux through the last full face
upstream, h_r U / 2, is carried on by streamers of liquid between the surfaces, which shear
only the liquid, a fraction h_r / h of the gap (:func:`striated_fraction`). The friction power
is U times the journal's shear over the land with the Couette part scaled by that fraction
(:func:`film_power`); the scenes' own torques and ``power_loss`` count the cavity full
(Raimondi and Boyd). Both take the film on the Reynolds grid (:mod:`.film2d`).
"""
from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from . import film2d


def striated_fraction(p, h, z, R, eta, v, full):
    """Liquid fraction of each theta face (n, m + 1) of a Reynolds film: 1 where the upstream
    node is full (pressurized, a groove's or the film outside the cavity), h_r / h_face in the
    cavity, h_r = q_x / v the flux (m^2/s) through the last full face upstream on the same
    axial line (the finite-volume flux into the cavity; the striated film carries it on at
    the surfaces' mean speed v > 0). ``full`` (n, m + 1): bool, or a weight in [0, 1] (a node
    partly full: its flux and the cavity's blended, a continuous switch). End lines take their
    inner neighbours' fractions (the cavity reaches the edge). Returns (fraction, the fluxes
    :func:`vjax.films.film2d.fluxes`)."""
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


def film_power(p, h, z, R, radial_clearance, eta, omega_shaft, omega_housing, supply_angle, supply_width,
               cavitation="reynolds", film_fraction=None):
    """Friction power (W) of a finite bearing's film: U times the integral of the journal's
    shear tau_J = -h/2 dp/dx + phi eta (U_B - U_J)/h over the land (both surfaces' shear and
    speeds when the housing turns), on the theta faces as the scenes' torques, with the
    Couette part scaled by the liquid fraction phi (:func:`striated_fraction` under Reynolds
    conditions, the full nodes those with p > sqrt(eps) p_max and the axial groove's at
    ``supply_angle`` (rad; None: no groove) over the central ``supply_width`` of the land;
    for "jfo" the upwind node's ``film_fraction``). ``p`` (Pa), ``h`` (m) on the nodes (n,
    m + 1), ``z`` (m + 1,) the axial nodes (m), ``eta`` (Pa s), speeds (rad/s). Returns (P, phi)."""
    n = p.shape[0]
    RJ = R - radial_clearance
    v = 0.5 * (omega_housing * R + omega_shaft * RJ)
    dU = omega_housing * R - omega_shaft * RJ
    if cavitation == "jfo":
        frac, f = film2d.upwind(film_fraction, v), film2d.fluxes(p, h, R, z, eta, v)
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
