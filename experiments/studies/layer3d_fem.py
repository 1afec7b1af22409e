"""The 3D bonded layer's modal compliance (vjax.layer3d) against 3D finite elements (scikit-fem).

    PYTHONPATH=. python -m experiments.studies.layer3d_fem [out_dir]

One mode p = cos(n theta) cos(k z) on a sector of the layer bounded by symmetry planes:
theta in [0, pi/n] (the planes theta = 0 and pi/n are planes of symmetry of cos(n theta):
no normal displacement, no shear), z in [0, pi/k] (half a wavelength: u_z = 0 and no shear
on both ends, the sliding-shoulder condition of the modal solution), r between the loaded
and the bonded surface (u = 0 there). Triquadratic hexahedra (27 nodes, scikit-fem's
ElementHex2) on a structured (r, theta, z) grid mapped with quadratic geometry (MeshHex2:
the mid-nodes on the arcs), E = 1, R = 1. The radial displacement into the body at every
node of the loaded surface is compared with c cos(n theta) cos(k z); the error is stated
relative to the peak c. n = 2 keeps both theta planes axis-aligned (y = 0 and x = 0), so
the roller conditions are single displacement components.

Writes ``layer3d_fem.csv`` (mesh, dofs, error / peak, seconds) to the output directory.
"""
from __future__ import annotations

import sys
import time

import numpy as np

CASE = dict(n=2, kR=4.0, nu=0.45, tau=0.25)    # half wavelength pi/4 R: c 42% (liner), 26% (sleeve) above plane strain


def fem_mode(kind, n, kR, nu, tau, nr, nt, nz):
    """Radial displacement into the body at the loaded surface's nodes of the FE model of one
    mode (module docstring): (theta, z, u) arrays, E = 1, loaded radius 1, pressure amplitude 1."""
    from skfem import (Basis, BilinearForm, ElementHex2, ElementVector, FacetBasis, LinearForm, MeshHex,
                       MeshHex2, asm, condense, solve)
    from skfem.helpers import ddot, dot, sym_grad, trace
    if n != 2:
        raise ValueError("the sector's planes are axis-aligned for n = 2 only")
    a, b = (1.0, 1.0 + tau) if kind == "liner" else (1.0 - tau, 1.0)
    z_end = np.pi / kR
    grid = MeshHex2.from_mesh(MeshHex.init_tensor(np.linspace(a, b, nr + 1), np.linspace(0, np.pi / n, nt + 1),
                                                  np.linspace(0, z_end, nz + 1)))
    r, th, z = grid.doflocs                      # every node (mid-nodes too) mapped onto the cylinder
    mesh = MeshHex2(np.stack([r * np.cos(th), r * np.sin(th), z]), grid.t)
    element = ElementVector(ElementHex2())
    basis = Basis(mesh, element, intorder=5)
    lam, mu = nu / ((1 + nu) * (1 - 2 * nu)), 1 / (2 * (1 + nu))

    @BilinearForm
    def stiffness(u, v, w):
        return 2 * mu * ddot(sym_grad(u), sym_grad(v)) + lam * trace(sym_grad(u)) * trace(sym_grad(v))

    @LinearForm
    def pressure(v, w):                          # traction -p n_out: the pressure pushes into the body
        return -np.cos(n * np.arctan2(w.x[1], w.x[0])) * np.cos(kR * w.x[2]) * dot(w.n, v)

    radius = lambda x: np.hypot(x[0], x[1])

    def surface(rad):                            # facets with all four corners on the arc r = rad
        return np.nonzero(np.all(np.abs(radius(mesh.p[:, mesh.facets]) - rad) < 1e-9, axis=0))[0]
    loaded, bonded = surface(1.0), surface(b if kind == "liner" else a)
    plane = lambda i, value: mesh.facets_satisfying(lambda x: np.abs(x[i] - value) < 1e-9)
    fixed = np.unique(np.concatenate([
        basis.get_dofs(bonded).all(),
        basis.get_dofs(plane(1, 0.0)).all("u^2"),      # theta = 0: u_y = 0
        basis.get_dofs(plane(0, 0.0)).all("u^1"),      # theta = pi/2: u_x = 0
        basis.get_dofs(plane(2, 0.0)).all("u^3"),      # z = 0, z = pi/k: u_z = 0
        basis.get_dofs(plane(2, z_end)).all("u^3")]))
    f = asm(pressure, FacetBasis(mesh, element, facets=loaded))
    u = solve(*condense(asm(stiffness, basis), f, D=fixed))
    (ux, bx), (uy, _), _ = basis.split(u)
    X = bx.doflocs
    on = np.abs(radius(X) - 1.0) < 1e-9
    theta = np.arctan2(X[1, on], X[0, on])
    ur = ux[on] * np.cos(theta) + uy[on] * np.sin(theta)
    return theta, X[2, on], (ur if kind == "liner" else -ur), basis.N


def error_over_peak(kind, nr, nt, nz, case=CASE):
    """max |u_FE - c cos(n theta) cos(k z)| / |c| over the loaded surface's nodes, and the dofs."""
    from vjax.layer3d import layer_modes
    theta, z, u, dofs = fem_mode(kind, case["n"], case["kR"], case["nu"], case["tau"], nr, nt, nz)
    c = float(layer_modes(kind, np.array([case["n"]]), np.array([case["kR"]]), case["nu"], case["tau"])[0, 0])
    return float(np.max(np.abs(u - c * np.cos(case["n"] * theta) * np.cos(case["kR"] * z))) / abs(c)), c, dofs


def main(out_dir="experiments/out"):
    from experiments import _common
    out = _common.setup(out_dir)
    from vjax.green import mode_compliance
    rows = []
    for kind in ("liner", "sleeve"):
        c2 = float(mode_compliance(kind, np.array([CASE["n"]]), CASE["nu"], thickness_ratio=CASE["tau"])[0])
        for mesh in ((2, 4, 4), (3, 6, 6), (4, 8, 8), (5, 10, 10), (6, 12, 12)):
            t0 = time.perf_counter()
            err, c, dofs = error_over_peak(kind, *mesh)
            rows.append(dict(kind=kind, nr=mesh[0], ntheta=mesh[1], nz=mesh[2], dofs=dofs, c_3d=c, c_plane_strain=c2,
                             error_over_peak=err, seconds=round(time.perf_counter() - t0, 2)))
            print(rows[-1], flush=True)
    header = list(rows[0])
    _common.write_csv(out / "layer3d_fem.csv", header, [[r[h] for h in header] for r in rows],
                      comments=[f"one mode {CASE}, E = 1, R = 1; error_over_peak = max |u_FE - u_modal| / |c|"])
    return rows


if __name__ == "__main__":
    main(*sys.argv[1:2])
