"""The finite rigid bearing's stiffness and damping against an independent peer computation.

The peer (below, numpy and scipy.sparse, written from the equations, not from
vjax.journal_finite): the finite-volume Reynolds equation over the land, one control volume
R dtheta x w_j per node (w_j the trapezoidal node widths), face films the mean of the two
nodes, the pressure ambient at both ends and at the axial groove's column, a full-width
groove, and Reynolds conditions (p >= 0, the cell's net outflow >= its rupture share, one of
them an equality) by an active set: solve the balances on the pressurized cells (Newton: the
rupture share is nonlinear), move cells with p < 0 out and cavitated cells short of liquid in,
until the set stops changing. The rupture share locates each line's rupture within its cell,
as vjax does: a cell whose pressure falls from its upstream neighbour's, at
beta = sqrt(p) / (sqrt(p_up) - sqrt(p)) cells before the rupture, may lose
W (1 - beta)^2 / 2 (W its net Couette outflow; written here from that formula). Its
stiffness and damping are central differences of its own solves at perturbed journal positions
and velocities (position control, the classical definition), where vjax linearizes its
Fischer-Burmeister system by forward-mode derivatives and solves the block-tridiagonal system:
two methods that agree only if both are right. Settings: vjax's 48 x 32 grid, L/D = 1 and
0.5, eps about 0.3 to 0.7, the groove at the maximum film (as ROSS's single 359-degree land).
"""
import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import vjax
from vjax import FiniteJournalOptions, reference

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
V = 0.5 * WJ * (R - C)                    # entrainment speed (m/s), journal turning
D = 2 * R
OPT = FiniteJournalOptions(n=48, m=32)    # test_journal_finite.py's grid: its compiled solve is shared


def peer_force(theta, z, groove, position, velocity=(0.0, 0.0)):
    """Film force on the journal (N, the axes of ``position``) of the rigid finite bearing whose
    journal centre sits at ``position`` (m) moving at ``velocity`` (m/s); ``theta`` (n,) the
    node angles in the same axes, ``z`` (m + 1,) the axial nodes (m), ``groove`` the index of
    the ambient-pressure column. Returns (force, pressure (n, m + 1))."""
    n, M = len(theta), len(z)
    dth = 2 * np.pi / n
    cos, sin = np.cos(theta)[:, None], np.sin(theta)[:, None]
    h = C - position[0] * cos - position[1] * sin + 0 * z[None, :]
    hdot = -velocity[0] * cos - velocity[1] * sin + 0 * z[None, :]
    dz = np.diff(z)
    w = 0.5 * (np.concatenate([[0.0], dz]) + np.concatenate([dz, [0.0]]))        # node widths
    hx = 0.5 * (h + np.roll(h, -1, axis=0))            # face (i + 1/2, j)
    hz = 0.5 * (h[:, 1:] + h[:, :-1])                   # face (i, j + 1/2)
    gx = hx**3 / (12 * ETA) / (R * dth) * w[None, :]   # conductances
    gz = hz**3 / (12 * ETA) / dz[None, :] * R * dth
    # cell (i, j) net outflow = sum_faces g (p_i - p_nb) + Couette + squeeze: A p + b
    interior = [(i, j) for i in range(n) for j in range(1, M - 1) if i != groove]
    index = {cell: k for k, cell in enumerate(interior)}
    rows, cols, vals = [], [], []
    b = np.zeros(len(interior))
    for k, (i, j) in enumerate(interior):
        neighbours = (((i + 1) % n, j, gx[i, j]), ((i - 1) % n, j, gx[(i - 1) % n, j]),
                      (i, j + 1, gz[i, j]), (i, j - 1, gz[i, j - 1]))
        for i2, j2, g in neighbours:
            rows.append(k), cols.append(k), vals.append(g)
            if (i2, j2) in index:
                rows.append(k), cols.append(index[(i2, j2)]), vals.append(-g)
        b[k] = V * (hx[i, j] - hx[(i - 1) % n, j]) * w[j] + R * dth * w[j] * hdot[i, j]
    A = sp.csr_matrix((vals, (rows, cols)), shape=(len(interior),) * 2)
    couette = np.array([V * (hx[i, j] - hx[(i - 1) % n, j]) * w[j] for i, j in interior])
    upstream = np.array([index.get(((i - 1) % n, j), -1) for i, j in interior])

    def share(p):
        """Rupture share W (1 - beta)_+^2 / 2 of every cell and its derivatives in p and p_up."""
        s = np.sqrt(np.maximum(p, 0.0))
        su = np.where(upstream >= 0, s[upstream], 0.0)
        falling = su > s
        d = np.where(falling, su - s, 1.0)
        a = np.where(falling, np.maximum((su - 2 * s) / d, 0.0), 0.0)      # (1 - beta)_+
        da_ds = np.where(a > 0, -su / d**2, 0.0)
        da_dsu = np.where(a > 0, s / d**2, 0.0)
        ds = 0.5 / np.maximum(s, 1e-300)
        Wp = np.maximum(couette, 0.0)
        dsu_dpu = 0.5 / np.maximum(su, 1e-300)
        return Wp * a**2 / 2, Wp * a * da_ds * ds * (p > 0), Wp * a * da_dsu * dsu_dpu * (su > 0)

    active = np.ones(len(interior), bool)
    for _ in range(200):
        S = np.flatnonzero(active)
        p = np.zeros(len(interior))
        p[S] = spla.spsolve(A[S][:, S].tocsc(), -b[S])
        for _ in range(50):          # Newton on the active balances A p + b - share(p) = 0
            sh, dself, dup = share(p)
            r = (A @ p + b - sh)[S]
            if np.max(np.abs(r)) <= 1e-13 * np.max(np.abs(b)):
                break
            rows_up = np.flatnonzero(upstream >= 0)
            Jsh = sp.csr_matrix((dself, (np.arange(len(p)), np.arange(len(p)))), shape=A.shape) \
                + sp.csr_matrix((dup[rows_up], (rows_up, upstream[rows_up])), shape=A.shape)
            J = (A - Jsh).tocsr()[S][:, S]
            p[S] -= spla.spsolve(J.tocsc(), r)
        else:
            raise RuntimeError("the peer's Newton did not converge")
        outflow = A @ p + b - share(p)[0]
        new = (p > 0) | (~active & (outflow < 0))
        new &= ~(active & (p <= 0))
        if np.array_equal(new, active):
            break
        active = new
    else:
        raise RuntimeError("the peer's active set did not settle")
    P = np.zeros((n, M))
    for k, (i, j) in enumerate(interior):
        P[i, j] = p[k]
    F = -R * dth * np.array([np.cos(theta) @ P @ w, np.sin(theta) @ P @ w])
    return F, P


def peer_coefficients(theta, z, groove, position):
    """K, C (N/m, N s/m) by central differences of the peer's film force, dF = -(K dx + C dx/dt)."""
    K, Cd = np.zeros((2, 2)), np.zeros((2, 2))
    for j in range(2):
        e = np.zeros(2)
        e[j] = 1e-5 * C
        K[:, j] = -(peer_force(theta, z, groove, position + e)[0] - peer_force(theta, z, groove, position - e)[0]) \
            / (2 * e[j])
        u = e * WJ
        Cd[:, j] = -(peer_force(theta, z, groove, position, u)[0] - peer_force(theta, z, groove, position, -u)[0]) \
            / (2 * u[j])
    return K, Cd


@pytest.mark.parametrize("LD, eps", [(1.0, 0.3), (1.0, 0.7), (0.5, 0.5)])
def test_coefficients_against_an_independent_peer(LD, eps):
    """The load that puts the long bearing at eps, times L / 4 (the finite bearing then runs at
    eps 0.34, 0.60 and 0.69); the groove at the maximum film (two passes). The peer, held at
    vjax's journal position, carries vjax's load (measured to 1.4e-10: vjax's square root of
    the pressure is floored at 1e-16 p_ref, and its Newton stops at 1e-10) on vjax's pressure
    (4e-10 of the peak), and its K and C equal vjax's to 1e-8 of the largest entry (measured
    2.7e-10 to 1.7e-9 for K, 1.6e-10 to 7.7e-9 for C, the central differences' error)."""
    L = LD * D
    W = float(reference.long_bearing(eps, R, C, ETA, V, "reynolds")["load"]) * L / 4
    phi = 0.6
    for _ in range(2):
        co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=WJ, length=L, supply_angle=np.pi + phi,
                                       options=OPT)
        phi = float(co.steady.attitude_angle)
    co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=WJ, length=L, supply_angle=np.pi + phi,
                                   options=OPT)
    s = co.steady
    assert bool(s.converged)
    n = OPT.n
    groove = int(round(((np.pi + phi) % (2 * np.pi)) / (2 * np.pi / n))) % n
    # the peer in absolute axes: the grid's theta is measured from the load's direction (-y)
    theta = np.asarray(s.theta) - np.pi / 2
    z, position = np.asarray(s.z), np.asarray(s.position)
    F, P = peer_force(theta, z, groove, position)
    assert np.allclose(F, [0.0, W], rtol=0, atol=1e-9 * W)             # the film carries the load (-y)
    assert np.max(np.abs(P - np.asarray(s.pressure))) < 1e-9 * np.max(P)
    K, Cd = peer_coefficients(theta, z, groove, position)
    assert np.max(np.abs(np.asarray(co.stiffness[0]) - K)) < 1e-8 * np.abs(K).max()
    assert np.max(np.abs(np.asarray(co.damping[0]) - Cd)) < 1e-8 * np.abs(Cd).max()
