"""The energy equation of a finite film: its mean temperature over the land (internal).

Steady, the film's temperature averaged across its thickness, T(theta, z), is carried by the
film's flow, heated by its shear and cooled through the walls (docs/theory.md §19.2):

    rho c_p div(q T) = Phi - h_B (T - T_B) - h_J (T - T_J)

q (m^2/s) the film's volume flux per unit width (:func:`vjax.films.film2d.fluxes`; in a
striated cavity the liquid's, ``frac`` times the Couette flux), Phi (W/m^2) the dissipation
across the film, eta U^2 / h (times ``frac`` in a cavity) + h^3 |grad p|^2 / (12 eta), h_B and
h_J (W/(m^2 K)) the walls' heat-transfer coefficients to T_B and T_J. No conduction along the
film (its Peclet number is 10^3-10^5).

Finite volumes on the Reynolds grid's node volumes (R dtheta by the node widths, half at the
ends), the flux through each face the one the Reynolds equation balances, its temperature
the upwind node's. Written for the rise T' = T - T_supply in conservative form, the sum over
all volumes telescopes: the dissipation equals the heat carried out through the open
boundaries (the end planes, the groove's discharge) plus the walls', to round-off, whether
or not the (Reynolds-cavitation) fluxes conserve mass in every volume (what a volume gains
is supply oil, T' = 0). Each face's dissipation is shared equally by its two nodes.

An axial groove's nodes hold the mixed inlet temperature: the oil arriving from upstream,
F_a at T_a, of which a fraction ``carry_over`` stays in the film, mixes with supply oil to
make up the groove's outflow F_o:

    T'_groove = carry_over F_a T'_a / max(F_o, carry_over F_a)

(the rest of the hot oil leaves through the groove's discharge). The unknowns are the
n (m + 1) node temperatures; the operator couples each node to its axial neighbours and,
along theta, to one upwind neighbour per face: a cyclic block-tridiagonal matrix (blocks of
one axial line), solved directly (:func:`cyclic_block_solve`). Where the film's flow runs one
way round everywhere (the net flux q_theta = U h / 2 - h^3 dp/dx / (12 eta) keeps its sign: in
a long bearing always, q_theta = U h* / 2), each line takes from one neighbour only and the
solve is a recurrence around the ring, 3-4x faster.
"""
from __future__ import annotations

import jax
import jax.numpy as jnp

from .film2d import node_widths


def face_flows(f, frac, R, z):
    """Volume flows (m^3/s) through the theta faces (n, m + 1), (i + 1/2, j), positive towards
    i + 1, and the z faces (n, m), (i, j + 1/2), positive towards j + 1, of the fluxes ``f``
    (:func:`vjax.films.film2d.fluxes`), the Couette part times the liquid fraction ``frac``
    (n, m + 1) of each theta face (1 in a full film)."""
    dth = 2 * jnp.pi / f["qx"].shape[0]
    qx = f["qx"] - f["cx"] + frac * f["cx"]
    return qx * node_widths(z)[None, :], f["qz"] * R * dth


def dissipation(f, frac, dU, R, z):
    """Heat generated in each node's volume (n, m + 1) (W): the shear across the film, eta dU^2
    / h (the Couette part, times ``frac`` in a striated cavity) + g dp/dx^2 / (12 eta) on the
    theta faces, g dp/dz^2 / (12 eta) on the z faces (g = h^3 for smooth surfaces), each
    face's half to each of its two nodes. ``dU`` (m/s): the surfaces' sliding speed."""
    dth = 2 * jnp.pi / f["qx"].shape[0]
    wz = node_widths(z)
    on_x = (f["gx"] * f["dpdx"] ** 2 / (12 * f["eta_x"]) + frac * f["eta_x"] * dU ** 2 / f["hx"]) * R * dth * wz
    on_z = f["gz"] * f["dpdz"] ** 2 / (12 * f["eta_z"]) * R * dth * jnp.diff(z)[None, :]
    nodes = 0.5 * (on_x + jnp.roll(on_x, 1, axis=0))
    return nodes + 0.5 * (jnp.pad(on_z, ((0, 0), (0, 1))) + jnp.pad(on_z, ((0, 0), (1, 0))))


def end_flows(Fx, Fz):
    """Flow out through the end planes (n, 2) (m^3/s) of the end nodes j = 0 and m: what their
    volumes' other faces bring in (each end volume's mass balance; negative: oil drawn in)."""
    inflow_x = jnp.roll(Fx, 1, axis=0) - Fx
    return jnp.stack([inflow_x[:, 0] - Fz[:, 0], inflow_x[:, -1] + Fz[:, -1]], axis=1)


def operator(Fx, Fz, groove, carry_over, wall, v_positive=True):
    """The energy equation's matrix as cyclic blocks (one per axial line i): ``lower`` (n, k)
    the coupling of node (i, j) to (i - 1, j), ``diagonal`` (n, k, k) within line i, ``upper``
    (n, k) to (i + 1, j) (k = m + 1), for the rise T' (K) in rho c_p-scaled units (m^3/s):
    outflow faces on the diagonal, inflow faces on the upwind neighbour's column, the end
    planes' outflow on the diagonal, ``wall`` (n, m + 1) (m^3/s: the walls' h A / (rho c_p))
    on the diagonal. ``groove`` (n, m + 1) 0/1: rows holding the mixed inlet temperature
    (module docs), the upstream line being i - 1 for ``v_positive`` (the film's flow along
    +theta), i + 1 otherwise. Returns ((lower, diagonal, upper), mixing fraction (n, k))."""
    n, k = Fx.shape
    out_x, in_x = jnp.maximum(Fx, 0.0), jnp.maximum(-Fx, 0.0)        # face i+1/2: out of i / into i from i+1
    prev_out, prev_in = jnp.roll(out_x, 1, axis=0), jnp.roll(in_x, 1, axis=0)   # face i-1/2, from i-1 / out of i
    out_z, in_z = jnp.maximum(Fz, 0.0), jnp.maximum(-Fz, 0.0)        # face j+1/2: out of j / into j from j+1
    pad_hi = lambda a: jnp.pad(a, ((0, 0), (0, 1)))                  # noqa: E731  (a face's value on node j)
    pad_lo = lambda a: jnp.pad(a, ((0, 0), (1, 0)))                  # noqa: E731  (on node j + 1)
    ends = jnp.maximum(end_flows(Fx, Fz), 0.0)
    end_out = jnp.zeros((n, k), Fx.dtype).at[:, 0].set(ends[:, 0]).at[:, -1].set(ends[:, 1])
    diag = out_x + prev_in + pad_hi(out_z) + pad_lo(in_z) + end_out + wall
    lower, upper = -prev_out, -in_x
    z_up, z_down = -pad_hi(in_z), -pad_lo(out_z)       # row j's coupling to node j + 1; to node j - 1
    # the groove's rows: T' = lambda T'_upstream, lambda the carried-over share of its outflow
    arriving = prev_out if v_positive else in_x
    leaving = out_x + prev_in + pad_hi(out_z) + pad_lo(in_z) + end_out
    lam = carry_over * arriving / jnp.maximum(jnp.maximum(leaving, carry_over * arriving), jnp.finfo(Fx.dtype).tiny)
    g = groove > 0
    diag = jnp.where(g, 1.0, diag)
    lower = jnp.where(g, -lam if v_positive else 0.0, lower)
    upper = jnp.where(g, 0.0 if v_positive else -lam, upper)
    z_up, z_down = jnp.where(g, 0.0, z_up), jnp.where(g, 0.0, z_down)
    eye = jnp.eye(k, dtype=Fx.dtype)
    blocks = (diag[:, :, None] * eye + z_up[:, :, None] * jnp.eye(k, k, 1, dtype=Fx.dtype)
              + z_down[:, :, None] * jnp.eye(k, k, -1, dtype=Fx.dtype))
    return (lower, blocks, upper), jnp.where(g, lam, 0.0)


def matvec(blocks, T):
    """The operator of :func:`operator` times a node field T (n, k)."""
    lower, diagonal, upper = blocks
    return lower * jnp.roll(T, 1, axis=0) + jnp.einsum("ijk,ik->ij", diagonal, T) + upper * jnp.roll(T, -1, axis=0)


def cyclic_block_solve(blocks, b, transposed=False):
    """Solve the cyclic block-tridiagonal system of :func:`operator` (or its transpose) for the
    right side b (n, k): by the recurrence of :func:`_one_way_solve` where every line couples to
    one neighbour only (all ``upper`` or all ``lower`` zero: the flow one way round), else by
    :func:`_block_thomas_solve`. The choice is traced: one program for both."""
    lower, diagonal, upper = blocks
    if transposed:      # A^T: block (i, i-1) of A^T is (block (i-1, i) of A)^T = diag(upper[i - 1])
        lower, upper = jnp.roll(upper, 1, axis=0), jnp.roll(lower, -1, axis=0)
        diagonal = jnp.swapaxes(diagonal, 1, 2)
    flip = lambda a: jnp.flip(a, axis=0)        # noqa: E731  (line i <-> n - 1 - i: i + 1 becomes i - 1)
    return jax.lax.cond(
        jnp.all(upper == 0), lambda: _one_way_solve(lower, diagonal, b),
        lambda: jax.lax.cond(jnp.all(lower == 0), lambda: flip(_one_way_solve(flip(upper), flip(diagonal), flip(b))),
                             lambda: _block_thomas_solve(lower, diagonal, upper, b)))


def _one_way_solve(lower, diagonal, b):
    """The cyclic system D_i x_i + lower_i x_{i-1} = b_i (x_{-1} = x_{n-1}), D_i tridiagonal (a
    line's axial coupling): x_i = A_i x_{i-1} + c_i with A_i = -D_i^-1 diag(lower_i), c_i = D_i^-1
    b_i (batched tridiagonal solves), so that x_i = Z_i s + y_i for s = x_{n-1} (one scan of
    k x k products), s from (I - Z_{n-1}) s = y_{n-1}. O(n k^3) in one short scan."""
    n, k = b.shape
    bands = [jnp.diagonal(diagonal, offset, axis1=1, axis2=2) for offset in (-1, 0, 1)]
    sub, main, sup = jnp.pad(bands[0], ((0, 0), (1, 0))), bands[1], jnp.pad(bands[2], ((0, 0), (0, 1)))
    eye = jnp.eye(k, dtype=b.dtype)
    solved = jax.lax.linalg.tridiagonal_solve(sub, main, sup, jnp.concatenate(
        [jnp.broadcast_to(eye, (n, k, k)), b[:, :, None]], axis=2))
    A, c = -solved[:, :, :k] * lower[:, None, :], solved[:, :, k]

    def step(carry, xs):
        Z, y = carry
        A_i, c_i = xs
        Z, y = A_i @ Z, A_i @ y + c_i
        return (Z, y), (Z, y)

    _, (Z, y) = jax.lax.scan(step, (eye, jnp.zeros(k, b.dtype)), (A, c))
    s = jnp.linalg.solve(eye - Z[-1], y[-1])
    return Z @ s + y


def _block_thomas_solve(lower, diagonal, upper, b):
    """The general cyclic block-tridiagonal system: line 0's unknowns are carried as k extra
    right sides through a block Thomas sweep over lines 1 ... n - 1 (its coupling to lines 1 and
    n - 1 moved to the right), then found from line 0's equations: O(n k^3), one scan each way."""
    n, k = b.shape
    # right sides of lines 1 .. n-1: [b_i, -(coupling to line 0's unknowns)]
    couple = jnp.zeros((n, k, k), b.dtype)
    couple = couple.at[1].add(-jnp.diag(lower[1])).at[n - 1].add(-jnp.diag(upper[n - 1]))
    rhs = jnp.concatenate([b[:, :, None], couple], axis=2)[1:]                      # (n - 1, k, 1 + k)
    L, D = lower[1:], diagonal[1:]
    U = upper[1:].at[-1].set(0.0)                                                  # line n-1 -> line 0: moved right

    def forward(carry, xs):
        C_prev, d_prev = carry
        L_i, D_i, U_i, r_i = xs
        M = D_i - L_i[:, None] * C_prev
        sol = jnp.linalg.solve(M, jnp.concatenate([jnp.diag(U_i), r_i - L_i[:, None] * d_prev], axis=1))
        return (sol[:, :k], sol[:, k:]), (sol[:, :k], sol[:, k:])

    zero = (jnp.zeros((k, k), b.dtype), jnp.zeros((k, 1 + k), b.dtype))
    _, (C, d) = jax.lax.scan(forward, zero, (L, D, U, rhs))

    def backward(y_next, xs):
        C_i, d_i = xs
        y = d_i - C_i @ y_next
        return y, y

    _, y = jax.lax.scan(backward, jnp.zeros((k, 1 + k), b.dtype), (C, d), reverse=True)
    Y, Z = y[:, :, 0], y[:, :, 1:]                                                  # lines 1 .. n-1: Y + Z x0
    A0 = diagonal[0] + lower[0][:, None] * Z[-1] + upper[0][:, None] * Z[0]
    x0 = jnp.linalg.solve(A0, b[0] - lower[0] * Y[-1] - upper[0] * Y[0])
    return jnp.concatenate([x0[None], Y + Z @ x0], axis=0)
