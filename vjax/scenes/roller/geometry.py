"""Needle roller bearing geometry: exact circles, no parabola (internal; see :mod:`vjax.scenes.roller`).

Roller j's centre is at distance rho_j from the bearing centre O. Its overlap with the
undeformed outer ring along the ray theta from O, and with the undeformed inner ring along
the ray theta' from the inner centre C = delta_r e_L, is

    d_O(theta)  = rho cos(theta - psi) + sqrt(r^2 - rho^2 sin^2(theta - psi)) - R_O,
    d_I(theta') = R_I - rho' cos(theta' - psi') + sqrt(r^2 - rho'^2 sin^2(theta' - psi')),

with (rho', psi') the roller centre seen from C. Each element belongs to the roller nearest
in angle (its Voronoi cell), so one ring holds all roller patches as one contact problem.
"""
from __future__ import annotations

import jax
import jax.numpy as jnp


def safe_sqrt_abs(x):
    """sqrt(|x|) with finite gradients at 0 (double where)."""
    a = jnp.abs(x)
    ok = a > 0
    return jnp.where(ok, jnp.sqrt(jnp.where(ok, a, 1.0)), 0.0)


def outer_interference(q, args):
    """Overlap of the rollers with the undeformed hole (one roller per element)."""
    rho, cos_d, sin_d, r, R = args
    disc = r**2 - (rho * sin_d) ** 2
    return rho * cos_d + jnp.sign(disc) * safe_sqrt_abs(disc) - R


def inner_interference(q, args):
    """Overlap of the rollers with the undeformed inner cylinder (frame of its centre)."""
    rho, cos_d, sin_d, r, R = args
    disc = r**2 - (rho * sin_d) ** 2
    return R - rho * cos_d + jnp.sign(disc) * safe_sqrt_abs(disc)


def wrap(phi):
    """Angle to [-pi, pi]."""
    return phi - 2.0 * jnp.pi * jnp.round(phi / (2.0 * jnp.pi))


def owner(theta, psi, Z):
    """Index of the roller nearest in angle to each element (its Voronoi cell)."""
    psi0 = jax.lax.stop_gradient(psi[0])
    k = jnp.round((jax.lax.stop_gradient(theta) - psi0) / (2.0 * jnp.pi / Z)).astype(int)
    return k % Z


def roller_centres(outer_penetration, ring_shift, psi, r, R_O, load_angle):
    """Roller centres: distance rho from O, and (rho', psi') seen from the inner centre C.

    The outer penetration delta^O_j = rho_j + r - R_O places roller j on its ray psi_j; the
    inner ring's centre C sits at ring_shift along the load."""
    eL = jnp.stack([jnp.cos(load_angle), jnp.sin(load_angle)])
    C = ring_shift * eL
    rho = R_O - r + outer_penetration
    e = jnp.stack([jnp.cos(psi), jnp.sin(psi)], axis=1)            # (Z, 2)
    v = rho[:, None] * e - C
    return rho, jnp.linalg.norm(v, axis=1), jnp.arctan2(v[:, 1], v[:, 0]), C, e, eL
