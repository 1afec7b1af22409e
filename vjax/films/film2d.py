"""Reynolds equation of a finite film over the bearing's land: finite volumes on theta x z (internal).

    d/dx (h^3/(12 eta) dp/dx) + d/dz (h^3/(12 eta) dp/dz) = v dh/dx + dh/dt      (docs/theory.md §16)

x = R theta in [0, 2 pi R) (periodic), z in [-L/2, L/2], v the entrainment speed (the mean of
the surface speeds), p = ambient (0, gauge) at both ends z = +-L/2. Grid: n cells in theta
(centres theta_i = 2 pi i / n, as the ring) times m + 1 axial nodes z_0 = -L/2 < ... < z_m =
L/2 (vertex-centred in z, so the end pressure is held exactly on the end nodes); the unknowns
live on the n x (m - 1) interior nodes, each the centre of a control volume R dtheta by
dz_j = (z_{j+1} - z_{j-1})/2. Fluxes through the faces (second order, the face film the mean
of its two nodes, as in the ring's :mod:`vjax.films.reynolds`):

    q_x = -h_f^3/(12 eta) dp/dx + v h_f   (m^2/s per unit width, theta faces)
    q_z = -h_f^3/(12 eta) dp/dz           (m^2/s per unit arc, z faces)

and the net outflow of a cell, w = (q_x+ - q_x-) dz_j + (q_z+ - q_z-) R dtheta (m^3/s), plus
the squeeze term R dtheta dz_j dh/dt, is its mass balance. Each balance is divided by the sum
of its four face conductances times p_ref: the equation then reads "p minus the weighted
mean of its neighbours minus a source" in units of p_ref, O(1) and with a round-off floor of
a few machine epsilons whatever the cells' aspect ratio. Cavitation as in 1D
(:mod:`vjax.films.reynolds`): "reynolds" (Fischer-Burmeister complementarity of p and w),
"half_sommerfeld" (the Sommerfeld field, negative part clipped when it loads the surfaces),
"sommerfeld". Cells of a supply groove hold the supply pressure instead of a balance.

Film of a journal tilted in the bearing (grid axes: theta from the grid's x axis):

    h(theta, z) = c - (e_x + z gamma_x) cos theta - (e_y + z gamma_y) sin theta + deformations
"""
from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from . import reynolds
from .roughness import shear_flow_factor

SPACINGS = ("uniform", "cosine")


def unit_nodes(m: int, spacing: str = "uniform"):
    """Axial nodes over L/2 (m + 1,), -1 ... 1 (numpy: static grid data): uniform, or "cosine"
    (Chebyshev-Lobatto, -cos(pi j / m)): nodes clustered at the ends, where a long bearing's
    pressure falls to ambient over a distance of about R while it is flat over the rest."""
    j = np.arange(m + 1)
    s = -np.cos(np.pi * j / m) if spacing == "cosine" else 2.0 * j / m - 1.0
    return 0.5 * (s - s[::-1])       # exact ends and mirror symmetry (the cosine's round-off)


def axial_nodes(m: int, length, spacing: str = "uniform"):
    """z nodes (m + 1,) from -L/2 to L/2 (m): :func:`unit_nodes` times L/2."""
    return 0.5 * length * unit_nodes(m, spacing)


def node_widths(z):
    """Axial widths of the nodes' control volumes (m + 1,) (m): (z_{j+1} - z_{j-1})/2 inside,
    half a spacing at the ends (the trapezoidal weights)."""
    d = jnp.diff(z)
    return 0.5 * (jnp.concatenate([d[:1] * 0, d]) + jnp.concatenate([d, d[:1] * 0]))


def film(theta, z, c, eccentricity, tilt):
    """Rigid film h (n, m + 1) (m) of a journal whose centre at axial position z sits at
    ``eccentricity`` + z ``tilt`` (m, rad; grid axes) in the bore."""
    ex = eccentricity[0] + z[None, :] * tilt[0]
    ey = eccentricity[1] + z[None, :] * tilt[1]
    return c - ex * jnp.cos(theta)[:, None] - ey * jnp.sin(theta)[:, None]


def with_ends(p_interior):
    """Pressure on all nodes (n, m + 1): ambient (0) on the end nodes."""
    zero = jnp.zeros_like(p_interior[:, :1])
    return jnp.concatenate([zero, p_interior, zero], axis=1)


def upwind(fraction, v):
    """Liquid fraction carried through the theta face (i + 1/2, j): the upwind node's."""
    return jnp.where(v >= 0, fraction, jnp.roll(fraction, -1, axis=0))


def couette_flux(h, v, rough=None, sliding=0.0):
    """The flux the surfaces' motion carries through a face of film ``h`` (m^2/s per unit
    width): v h for smooth surfaces; with ``rough`` (:class:`~vjax.films.roughness.Roughness`)
    Patir and Cheng's v h_T + (sliding/2) Vr sigma Phi_s(H_c), ``sliding`` = U_journal - U_bore
    (m/s) the speed of the surface whose roughness counts positive in Vr relative to the other
    (h_T the expected gap, or h with ``rough.couette == "nominal"``)."""
    if rough is None:
        return v * h
    Hc, _ = rough.clipped(h)
    base = rough.expected_gap(h) if rough.couette == "expected" else h
    return v * base + 0.5 * sliding * rough.Vr * rough.sigma * shear_flow_factor(Hc, rough.gamma)


def face_viscosity(eta):
    """Viscosity on the theta faces (n, m + 1) and the z faces (n, m) (Pa s): the mean of the
    two nodes' for a node field ``eta`` (n, m + 1) (a film at a varying temperature), ``eta``
    itself for a number."""
    eta = jnp.asarray(eta)
    if eta.ndim < 2:
        return eta, eta
    return 0.5 * (eta + jnp.roll(eta, -1, axis=0)), 0.5 * (eta[:, 1:] + eta[:, :-1])


def fluxes(p, h, R, z, eta, v, fraction=None, rough=None, sliding=0.0):
    """Face films, gradients and fluxes of pressure ``p`` and film ``h`` on all nodes (n, m + 1):
    theta faces (i + 1/2, j): ``hx``, ``dpdx`` (Pa/m), ``qx`` (m^2/s per unit width), its
    Couette part ``cx``; z faces (i, j + 1/2), shape (n, m): ``hz``, ``dpdz``, ``qz`` (m^2/s per
    unit arc); the conductances' gap terms ``gx``, ``gz`` (m^3: h^3, or with ``rough`` Patir
    and Cheng's phi h_c^3 along and across the sliding; the Couette flux :func:`couette_flux`
    with ``sliding``), the faces' viscosities ``eta_x``, ``eta_z`` (:func:`face_viscosity`:
    ``eta`` a number or a node field). With a liquid ``fraction`` (n, m + 1) ("jfo") the Couette flux carries
    the upwind node's liquid only (a striated cavity, as in 1D); the axial flux is the
    pressure's alone."""
    dth = 2 * jnp.pi / p.shape[0]
    hx = 0.5 * (h + jnp.roll(h, -1, axis=0))
    dpdx = (jnp.roll(p, -1, axis=0) - p) / (R * dth)
    hz = 0.5 * (h[:, 1:] + h[:, :-1])
    dpdz = jnp.diff(p, axis=1) / jnp.diff(z)[None, :]
    gx = hx**3 if rough is None else rough.poiseuille(hx)
    gz = hz**3 if rough is None else rough.poiseuille_across(hz)
    couette = couette_flux(hx, v, rough, sliding)
    if fraction is not None:
        couette = couette * upwind(fraction, v)
    eta_x, eta_z = face_viscosity(eta)
    return dict(hx=hx, dpdx=dpdx, qx=-gx * dpdx / (12 * eta_x) + couette, cx=couette, gx=gx, eta_x=eta_x,
                hz=hz, dpdz=dpdz, qz=-gz * dpdz / (12 * eta_z), gz=gz, eta_z=eta_z)


def net_outflow(f, R, z):
    """Net outflow (m^3/s) of each interior cell (n, m - 1) from the fluxes ``f`` of :func:`fluxes`."""
    dth = 2 * jnp.pi / f["qx"].shape[0]
    dz = node_widths(z)[1:-1]
    qx = f["qx"][:, 1:-1]
    return (qx - jnp.roll(qx, 1, axis=0)) * dz[None, :] + jnp.diff(f["qz"], axis=1) * R * dth


def conductance(f, R, z):
    """Sum of the four face conductances of each interior cell (n, m - 1) (m^3/(Pa s)) from the
    fluxes ``f`` of :func:`fluxes`: the diagonal of the pressure operator, the scale of its balance."""
    dth = 2 * jnp.pi / f["hx"].shape[0]
    dz = node_widths(z)[1:-1]
    kx = (f["gx"] / (12 * f["eta_x"]))[:, 1:-1]
    gx = (kx + jnp.roll(kx, 1, axis=0)) * dz[None, :] / (R * dth)
    gz = f["gz"] / (12 * f["eta_z"]) * R * dth / jnp.diff(z)[None, :]
    return gx + gz[:, 1:] + gz[:, :-1]


def cell_equations(p_scaled, outflow, scale, cavitation, groove, supply, couette_outflow=None, v=0.0, subcell=1.0):
    """Scaled cell equations (n, m - 1): the balance w / ``scale`` (``scale`` = conductance
    times p_ref, m^3/s) or, under Reynolds conditions, its Fischer-Burmeister complementarity
    with the scaled pressure; ``groove`` cells (a 0/1 mask) hold the scaled ``supply`` pressure.
    ``couette_outflow`` (n, m - 1) (m^3/s): the cells' net Couette outflow at entrainment speed
    ``v``; under Reynolds conditions each axial line's rupture is then located within its cell
    as in 1D (:func:`vjax.films.reynolds.rupture_outflow`, along theta), times ``subcell``."""
    w = outflow / scale
    if cavitation == "reynolds" and couette_outflow is not None:
        w = w - subcell * reynolds.rupture_outflow(p_scaled, couette_outflow / scale, v)
    r = reynolds.fischer_burmeister(p_scaled, w) if cavitation == "reynolds" else w
    return jnp.where(groove > 0, p_scaled - supply, r)


def resultants(p_load, theta, z, R):
    """Force (N, grid axes) and moment about the bearing's centre plane (N m, grid axes) of the
    pressure ``p_load`` (Pa, on all nodes) on the journal: F = -int p e_r R dtheta dz,
    M = int z e_z x dF = (-int z dF_y, int z dF_x) (the radial force has no moment about the axis)."""
    dth = 2 * jnp.pi / p_load.shape[0]
    wz = node_widths(z)
    per_z = -R * dth * jnp.stack([jnp.cos(theta) @ p_load, jnp.sin(theta) @ p_load])   # (2, m + 1) N/m
    F = per_z @ wz
    M = jnp.stack([-(per_z[1] * z) @ wz, (per_z[0] * z) @ wz])
    return F, M


def end_gradient_outflow(p, h, z, R, eta, rough=None):
    """Flow out of the land through both end planes (m^3/s) from the pressure gradient at the
    end nodes, -h^3/(12 eta) dp/dz at z = +-L/2
    outward (with ``rough``: phi_y h_c^3 for h^3), the gradient from the quadratic through the
    end node and its two neighbours (second order on any spacing; a flux at the last face would
    be first order). ``eta``: a number or a node field (n, m + 1) (Pa s)."""
    dth = 2 * jnp.pi / p.shape[0]
    eta = jnp.broadcast_to(eta, p.shape)

    def upper(p, h, z, eta):
        d1, d2 = z[-1] - z[-2], z[-1] - z[-3]
        dpdz = p[:, -1] * (1 / d1 + 1 / d2) - p[:, -2] * d2 / (d1 * (d2 - d1)) + p[:, -3] * d1 / (d2 * (d2 - d1))
        g = h[:, -1] ** 3 if rough is None else rough.poiseuille_across(h[:, -1])
        return -jnp.sum(g * dpdz / (12 * eta[:, -1])) * R * dth
    return upper(p, h, z, eta) + upper(p[:, ::-1], h[:, ::-1], -z[::-1], eta[:, ::-1])


def end_outflow(f, R):
    """Flow out of the land through both end planes (m^3/s): the axial flux ``qz`` of the end
    faces of ``f`` (:func:`fluxes`; with roughness, Patir and Cheng's), the fluxes the cell
    balances use, so it is what the cells pass on: in a steady state under JFO exactly what the
    groove supplies (the balances telescope). In a steady film the flow through every axial plane
    outside the groove is the same (the circumferential flow's divergence sums to zero round the
    bore), so the end faces' flow is the ends'. Its grid error is the pressure field's: on a
    rigid bearing at L/D = 1, eps 0.67, 4.3, 2.1, 1.1 % below the Richardson-extrapolated value on
    64 x 16, 128 x 32, 256 x 64 (:func:`end_gradient_outflow`: 2.2, 1.1, 0.5 % above it, and not
    what the groove supplies; the scenes use it where the cavitation model does not conserve
    mass, so that no groove flow equals it anyway)."""
    dth = 2 * jnp.pi / f["qz"].shape[0]
    return jnp.sum(f["qz"][:, -1] - f["qz"][:, 0]) * R * dth
