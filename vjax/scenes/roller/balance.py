"""Needle roller bearing balance equations (internal; see :mod:`vjax.scenes.roller`).

The unknowns are the split of each roller's deflection, x_j = delta_j^O (Eq. 2.37), and the
ring shift delta_r. The equations are the radial balance of each roller, F_j^O = F_j^I, with
F_j the patch resultant projected on the roller's radial direction, and the load balance
R_I int p_I cos(theta' - load_angle) dtheta' = load. A roller touching neither ring carries
nothing and its position is indeterminate, so each roller's balance is written as

    (F_j^O - k g_j^O) - (F_j^I - k g_j^I) = 0,

with g_j the smallest gap between the roller and each deformed ring (zero while it touches)
and k a stiffness scale (the softer ring's E0). Each bracket is continuous and strictly
monotone in x_j: one root, F^O = F^I for a loaded roller, k g^O = k g^I for an unloaded one;
the Jacobian stays regular when rollers lose contact. The load equation subtracts k times the
smallest roller gap (zero once one roller touches), so a start with no contact is regular
too. A rigid ring replaces the balance of each roller by "touches the rigid ring".
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp

from .geometry import inner_interference, outer_interference, owner, roller_centres, wrap
from ...contact.solve import ContactOptions, solve_contact
from ...bodies.operator import RingOperator, grid


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Params:
    """Differentiable parameters of a bearing (SI units); ``op_outer``/``op_inner`` None when rigid."""

    R_O: jax.Array
    R_I: jax.Array
    r: jax.Array                 # roller radius of the matched set
    Pd: jax.Array                # diametral clearance
    load: jax.Array
    load_angle: jax.Array
    psi: jax.Array               # roller angles (Z,)
    k: jax.Array                 # stiffness scale of the gap terms (Pa)
    op_outer: RingOperator | None
    op_inner: RingOperator | None


@dataclasses.dataclass(frozen=True)
class Config:
    """Static configuration: grid, number of rollers, contact options."""

    n: int
    Z: int
    contact: ContactOptions

    def rings(self, P: Params):
        """(name, operator, radius, interference) of each deformable ring."""
        out = []
        if P.op_outer is not None:
            out.append(("O", P.op_outer, P.R_O, outer_interference))
        if P.op_inner is not None:
            out.append(("I", P.op_inner, P.R_I, inner_interference))
        return out


def fields(x, P: Params, cfg: Config, warm):
    """Contact solves of both rings at the unknowns x = (delta^O_1..Z, delta_r); ``warm`` (2, n)
    starting pressures (zeros: cold). Returns per-ring fields and the roller geometry."""
    Z = cfg.Z
    rho, rho_i, psi_i, C, e, eL = roller_centres(x[:Z], x[Z], P.psi, P.r, P.R_O, P.load_angle)
    out = {}
    for name, op, R, interf in cfg.rings(P):
        rr, pp = (rho, P.psi) if name == "O" else (rho_i, psi_i)
        theta, alpha = grid(cfg.n)
        own = owner(theta, P.psi, Z)
        delta = wrap(theta - pp[own])
        args = (rr[own], jnp.cos(delta), jnp.sin(delta), P.r, R)
        sol = solve_contact(op, interf, args, options=cfg.contact, sigma_init=warm[int(name == "I")])
        p, u = sol.pressure, sol.displacement
        d = interf(None, args)
        hit = (P.r**2 - (rr[own] * jnp.sin(delta)) ** 2) > 0
        cells = own[None, :] == jnp.arange(Z)[:, None]             # (Z, n)
        # radial force of each patch along the roller's direction e_j
        F = R * 2 * alpha * jnp.sum(jnp.where(cells, p * jnp.cos(theta - P.psi[own]), 0.0), axis=1)
        g = u - d
        gmin = jnp.min(jnp.where(cells & hit, g, 10.0 * R), axis=1)
        gmin = jnp.where(F > 0, 0.0, jnp.maximum(gmin, 0.0))
        out[name] = dict(sol=sol, theta=theta, alpha=alpha, p=p, u=u, g=g, F=F, gmin=gmin, R=R)
    geo = dict(rho=rho, rho_i=rho_i, psi_i=psi_i, C=C, eL=eL, e=e, dO=x[:Z], dI=P.R_I + P.r - rho_i)
    return out, geo


def equations(x, P: Params, cfg: Config, warm):
    """The scaled balance equations (Z + 1,) and what the outputs need."""
    out, geo = fields(x, P, cfg, warm)
    Z = cfg.Z
    Fs = P.load / Z
    zero = jnp.zeros(Z, x.dtype)
    has_O, has_I = "O" in out, "I" in out
    FO = out["O"]["F"] if has_O else None
    FI = out["I"]["F"] if has_I else None
    gO = out["O"]["gmin"] if has_O else zero
    gI = out["I"]["gmin"] if has_I else zero
    if has_O and has_I:
        r_roll = ((FO - P.k * gO) - (FI - P.k * gI)) / Fs
    elif has_I:   # rigid outer ring: the roller rests on it
        r_roll = geo["dO"] * P.k / Fs
    else:         # rigid inner ring: the roller rests on it
        r_roll = geo["dI"] * P.k / Fs
    # a gap to a rigid ring can only open on the other side (the roller rests on it)
    if not has_O:
        gO, FO = zero, FI
    if not has_I:
        gI, FI = zero, FO
    gap = gO + gI
    if has_I:
        o = out["I"]
        F_load = o["R"] * 2 * o["alpha"] * jnp.sum(o["p"] * jnp.cos(o["theta"] - P.load_angle))
    else:
        # rigid inner ring: each roller pushes it along the line of centres
        F_load = jnp.sum(FO * jnp.cos(geo["psi_i"] - P.load_angle))
    r_load = (F_load - P.k * jnp.min(gap) - P.load) / P.load
    return jnp.concatenate([r_roll, r_load[None]]), (out, geo, FO, FI, gap)


def contacts_converged(out):
    return jnp.all(jnp.stack([o["sol"].converged for o in out.values()]))


def pressures(out, n, dtype):
    """(2, n) pressures of the outer and inner ring (zeros for a rigid ring): the warm start."""
    z = jnp.zeros(n, dtype)
    return jnp.stack([out["O"]["p"] if "O" in out else z, out["I"]["p"] if "I" in out else z])


def initial_guess(P: Params, cfg: Config):
    """Deflections from a linear spring per roller and ring (E0 per unit overlap), Stribeck-like:
    sum_j k max(delta_r cos - Pd/2, 0) cos = load, solved for zero clearance."""
    c = jnp.cos(P.psi - P.load_angle)
    has_O, has_I = P.op_outer is not None, P.op_inner is not None
    k = P.k / (has_O + has_I)                                      # springs in series
    dr = P.load / (k * jnp.sum(jnp.maximum(c, 0.0) ** 2)) + 0.5 * P.Pd
    dj = dr * c - 0.5 * P.Pd
    share = 0.5 if (has_O and has_I) else float(has_O)
    return jnp.concatenate([dj * share, dr[None]])
