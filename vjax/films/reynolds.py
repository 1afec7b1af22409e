"""Reynolds equation of an infinitely long film on a ring: finite volumes and cavitation.

    d/ds (h^3/(12 eta) dp/ds) = v dh/ds,   s = R theta,   v the entrainment speed (Eq. 3.41)

on N cells of width R dtheta, pressure at the cell centres; the flux through a face is
q = -h_f^3/(12 eta) dp/ds + v h_f with h_f the mean film of its two cells (second order).
A cell's net outflow w = q_out - q_in is its mass balance. Cavitation (``cavitation=``):

- ``"reynolds"``: Swift-Stieber / Reynolds conditions (p >= 0, p = dp/ds = 0 at rupture) as
  the linear complementarity p >= 0, w >= 0, p w = 0 (a cavitated cell may lose flow, a
  pressurized one conserves it), written as the Fischer-Burmeister equation
  p + w - sqrt(p^2 + w^2) = 0: semismooth, so Newton with an AD Jacobian works and the
  solution is differentiable where the cavitated set does not change. The rupture is
  located within its cell (w shifted by :func:`rupture_outflow`, the outflow the exact
  profile p ~ (theta_b - theta)^2 leaves the cell that holds it): the solution is then C^1
  in the parameters and the dynamic coefficients (its derivatives) converge steadily with
  the grid, where a rupture held on a face makes them scatter by O(dtheta).
- ``"jfo"``: Jakobsson-Floberg-Olsson / Elrod-Adams conditions, which conserve mass. Each
  cell holds a pressure p >= 0 and a liquid film fraction 0 <= f <= 1 with p (1 - f) = 0;
  in a cavity the film is striated and carries the Couette flow of its liquid part only,
  v h f. Both are one universal unknown u (Elrod's switch, as a semismooth function):
  p = p_ref max(u, 0), f = 1 + min(u, 0), so the complementarity holds by construction and
  every cell, pressurized or cavitated, conserves mass (w = 0). The Couette flux through a
  face takes the fraction of the upwind cell (f jumps at a rupture or a re-formation).
  Rupture and re-formation boundaries follow from the mass balance, not from a rule.
- ``"half_sommerfeld"``: the full-Sommerfeld pressure with negative values set to zero
  when it loads the surfaces.
- ``"sommerfeld"``: full Sommerfeld (w = 0 everywhere), negative pressures kept.

Rough surfaces (``rough=``, a :class:`~vjax.films.roughness.Roughness`): Patir and Cheng's
average flow, q = -phi_x(H_c) h_c^3/(12 eta) dp/ds + v h_T + (U_J - U_B)/2 Vr sigma Phi_s(H_c)
at the face film (:func:`couette_flux`, :func:`conductance_gap`; docs/theory.md §18).

The Reynolds model lets the cavity carry a full-film Couette flow, i.e. it does not conserve
mass across the cavity; where the film re-forms only from the groove (a groove at the
widest gap), JFO and Reynolds give the same pressure, elsewhere (a groove fixed in the
bearing away from the widest gap, starved films) they differ.
"""
from __future__ import annotations

import jax.numpy as jnp

from .roughness import shear_flow_factor

CAVITATION = ("reynolds", "jfo", "half_sommerfeld", "sommerfeld")
JFO_SMOOTHING = (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4)   # the solvers' homotopy of the "jfo" switch, if needed


def fischer_burmeister(a, b):
    """a + b - sqrt(a^2 + b^2): zero iff a >= 0, b >= 0, a b = 0. Where a + b > 0 it is
    evaluated as 2 a b / (a + b + sqrt(a^2 + b^2)), which has no cancellation, so that its
    derivative stays exact when one argument is tiny and the other's derivative is large.
    Double where: at (0, 0) the derivative is (1, 1), an element of its generalized Jacobian."""
    s = a * a + b * b
    ok = s > 0
    r = jnp.where(ok, jnp.sqrt(jnp.where(ok, s, 1.0)), 0.0)
    plus = a + b > 0
    return jnp.where(plus, 2 * a * b / jnp.where(plus, a + b + r, 1.0), a + b - r)


def load_pressure(p, cavitation):
    """The pressure that loads the surfaces (Pa): negative values clipped for half-Sommerfeld
    (and for ``"jfo"``, whose negative unknowns are film fractions - 1, not pressures)."""
    return jnp.maximum(p, 0.0) if cavitation in ("half_sommerfeld", "jfo") else p


def load_slope(p, cavitation):
    """Weights w_i of a small pressure change dp_i in the load: d p_load = w dp. 1 except for
    half-Sommerfeld, where w is the fraction of cell i on which the piecewise-linear
    pressure is positive (0 or 1 away from the zeros of p): a perturbation that does not
    vanish where p does (a squeeze film) then loads a clipped film to second order in the
    cell size, as the closed-form pi film does, not to first order as a 0/1 mask would."""
    if cavitation == "jfo":
        return (p > 0).astype(p.dtype)
    if cavitation != "half_sommerfeld":
        return jnp.ones_like(p)

    def positive_fraction(a, b):     # of a linear function from a to b
        opposite = a * b < 0
        frac = jnp.maximum(a, b) / jnp.where(opposite, jnp.abs(a - b), 1.0)
        return jnp.where(opposite, frac, jnp.where(a + b > 0, 1.0, jnp.where(a + b < 0, 0.0, 0.5)))
    left, right = 0.5 * (jnp.roll(p, 1) + p), 0.5 * (p + jnp.roll(p, -1))
    return 0.5 * (positive_fraction(left, p) + positive_fraction(p, right))


def pressure_and_fraction(u, cavitation, smoothing=0.0):
    """(p / p_ref, film fraction) of the scaled unknowns u: the universal variable of
    ``"jfo"`` (p = max(u, 0), f = 1 + min(u, 0) = 1 + u - p), else (u, 1). ``smoothing``
    mu > 0 rounds the switch, p = (u + sqrt(u^2 + mu^2))/2 (then p (1 - f) = mu^2/4): a
    homotopy for the solver, not a physical model."""
    if cavitation != "jfo":
        return u, jnp.ones_like(u)
    if isinstance(smoothing, (int, float)) and smoothing == 0:
        p = jnp.maximum(u, 0.0)
    else:   # mu traced (the solver's homotopy loop): the exact switch at mu = 0, no 0/0 slope
        s = u * u + smoothing**2
        smooth = 0.5 * (u + jnp.sqrt(jnp.where(s > 0, s, 1.0)))
        p = jnp.where(smoothing > 0, smooth, jnp.maximum(u, 0.0))
    return p, 1.0 + u - p


def face_fraction(fraction, v):
    """Film fraction carried through the face between cell i and i + 1: the upwind cell's."""
    return jnp.where(v >= 0, fraction, jnp.roll(fraction, -1))


def couette_flux(h, v, rough=None, sliding=0.0):
    """The flux the surfaces' motion carries through a film ``h`` (m^2/s per unit width): v h
    for smooth surfaces; with ``rough`` (:class:`~vjax.films.roughness.Roughness`) Patir and
    Cheng's v h_T + (sliding/2) Vr sigma Phi_s(H_c), ``sliding`` (m/s) the speed of the
    surface whose roughness counts positive in Vr (the journal) relative to the other (h_T
    the expected gap, or h with ``rough.couette == "nominal"``)."""
    if rough is None:
        return v * h
    Hc, _ = rough.clipped(h)
    base = rough.expected_gap(h) if rough.couette == "expected" else h
    return v * base + 0.5 * sliding * rough.Vr * rough.sigma * shear_flow_factor(Hc, rough.gamma)


def conductance_gap(h, rough=None):
    """The Poiseuille conductance's gap term (m^3): h^3, or with ``rough`` Patir and Cheng's
    phi_x(H_c) h_c^3 (:meth:`~vjax.films.roughness.Roughness.poiseuille`)."""
    return h**3 if rough is None else rough.poiseuille(h)


def face_fluxes(p, h, R, eta, v, fraction=None, rough=None, sliding=0.0):
    """Face film h_f (m), pressure gradient dp/ds (Pa/m) and flux q (m^2/s) at the face
    between cell i and i + 1; with a film ``fraction`` (``"jfo"``) the Couette part carries
    the upwind cell's liquid only; with ``rough`` surfaces Patir and Cheng's average flow
    (:func:`conductance_gap`, :func:`couette_flux` with the surfaces' ``sliding`` speed)."""
    dth = 2 * jnp.pi / p.shape[0]
    hf = 0.5 * (h + jnp.roll(h, -1))
    dpds = (jnp.roll(p, -1) - p) / (R * dth)
    couette = couette_flux(hf, v, rough, sliding)
    if fraction is not None:
        couette = couette * face_fraction(fraction, v)
    return hf, dpds, -conductance_gap(hf, rough) * dpds / (12 * eta) + couette


# The solvers find a Reynolds film in two stages, the rupture on a face, then within its cell
# from there (a few steps; from a cold start the sub-cell rupture's square root makes Newton
# creep); a start whose equations are already below this (max-norm) skips the first stage.
WARM_RESIDUAL = 1e-3
ROUND_OFF_PRESSURE = 1e-16   # p / p_ref: below it a pressure is round-off (a cavity's are ~1e-18)


def rupture_outflow(p_scaled, couette_outflow, v, axis=0):
    """The net outflow that the discrete balances give the cell holding a rupture, in the
    units of ``couette_outflow`` (the cells' net Couette outflow, W): W (1 - beta)_+^2 / 2.

    Near a Reynolds rupture at theta_b the pressure is p = A (theta_b - theta)^2 (p and dp/ds
    vanish there), so sqrt(p) is linear and the last pressurized node i lies
    beta = s_i / (s_{i-1} - s_i) cells upstream of it (s = sqrt(p), i - 1 the node upstream in
    the flow). Sampling that profile, the standard fluxes leave cell i a net outflow of
    W (1 - beta)^2 / 2 for 0 <= beta <= 1 (the cavitated part of its volume, beta < 1/2, and the
    face gradient p_i / dtheta where the profile's is smaller), 0 for beta >= 1. The
    complementarity p w = 0 would force that to 0, i.e. put the rupture on a face: an O(dtheta)
    error in the flow that jumps as the rupture crosses cells, and first-order scatter in the
    dynamic coefficients. Shifting w by this outflow locates the rupture within its cell; the
    shift is C^1 in the pressures (so is the discrete solution in the parameters) and vanishes
    where the pressure does not fall in the flow direction. ``axis``: the circumferential axis."""
    upstream = jnp.where(v >= 0, jnp.roll(p_scaled, 1, axis=axis), jnp.roll(p_scaled, -1, axis=axis))
    # sqrt(p + tau) - sqrt(tau): the root, but with a finite slope at p = 0, where a cavity's
    # round-off pressures would otherwise give the Jacobian entries of 1e9 and more
    root = lambda p: jnp.sqrt(jnp.maximum(p, 0.0) + ROUND_OFF_PRESSURE) - ROUND_OFF_PRESSURE**0.5     # noqa: E731
    s, s_up = root(p_scaled), root(upstream)
    falling = s_up > s
    one_minus_beta = jnp.where(falling, (s_up - 2 * s) / jnp.where(falling, s_up - s, 1.0), 0.0)
    return jnp.maximum(couette_outflow, 0.0) * jnp.maximum(one_minus_beta, 0.0) ** 2 / 2


def cell_equations(p_scaled, q, q_ref, cavitation, squeeze=0.0, couette=None, v=0.0, subcell=1.0):
    """Mass balance of each cell, scaled to O(1) per unit angle by ``q_ref`` (m^2/s, a number or
    one per cell); complementarity with the (scaled) pressure under Reynolds conditions.
    ``squeeze``: R dh/dt at the cell centres (m^2/s per radian), the film's own growth, which
    the net outflow must supply (the unsteady term of d/ds(h^3/(12 eta) dp/ds) = v dh/ds +
    dh/dt). ``couette``: the faces' Couette fluxes (m^2/s) at entrainment speed ``v``; under
    Reynolds conditions the rupture is then located within its cell (:func:`rupture_outflow`),
    times ``subcell`` (0: on a face, the solvers' first stage)."""
    dth = 2 * jnp.pi / q.shape[0]
    w = (q - jnp.roll(q, 1)) / (q_ref * dth) + squeeze / q_ref
    if cavitation != "reynolds":
        return w
    if couette is not None:
        w = w - subcell * rupture_outflow(p_scaled, (couette - jnp.roll(couette, 1)) / (q_ref * dth), v)
    return fischer_burmeister(p_scaled, w)


def rupture_angle(p, theta, v, cavitation):
    """Angle where p first reaches 0 downstream of its maximum (rad, grid frame)."""
    n = p.shape[0]
    dth = 2 * jnp.pi / n
    imax = jnp.argmax(p)
    direction = jnp.where(v >= 0, 1, -1)
    idx = (imax + direction * jnp.arange(n)) % n
    pk = p[idx]
    thr = 1e-9 * jnp.max(jnp.abs(p))
    kc = jnp.maximum(jnp.argmax(pk <= thr), 2)
    a, b, z = pk[kc - 2], pk[kc - 1], pk[kc]
    if cavitation == "sommerfeld":  # p changes sign between kc - 1 and kc: interpolate
        den = b - z
        frac = jnp.where(den > 0, b / jnp.where(den > 0, den, 1.0), 0.0)
    else:
        # the last two pressurized nodes, extrapolated: p ~ (theta_r - theta)^2 before a
        # Reynolds rupture (sqrt(p) linear), p linear at a half-Sommerfeld zero
        f = jnp.sqrt if cavitation in ("reynolds", "jfo") else (lambda y: y)
        sa, sb = f(jnp.maximum(a, 0.0)), f(jnp.maximum(b, 0.0))
        den = sa - sb
        frac = jnp.where(den > 0, sb / jnp.where(den > 0, den, 1.0), 0.0)
    # the discrete free boundary lies within the first cavitated cell: frac <= 1.5
    ang = theta[imax] + direction * (kc - 1 + jnp.clip(frac, 0.0, 1.5)) * dth
    return jnp.angle(jnp.exp(1j * ang))
