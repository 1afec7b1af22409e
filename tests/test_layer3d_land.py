"""The 3D bonded layer's operator on the finite bearing's land grid (vjax.layer3d_land): single
modes against the direct sum of 3D modal compliances over the exact cosine series, the plane-strain slices as the
land grows long, and its axially uniform column equal to the plane ring's operator; the same for a
hole through the land (kind "hole")."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax import Material, bodies
from vjax.layer3d import layer_modes
from vjax.layer3d_land import dct1, idct1, land_operator, whirl_symbol
from vjax.operator import ring_operator

E, NU = 2e9, 0.42
R, T = 0.05, 0.01


def test_dct1_round_trip_and_definition():
    x = np.random.default_rng(0).normal(size=(3, 9)) + 1j * np.random.default_rng(1).normal(size=(3, 9))
    m = 8
    i = np.arange(m + 1)
    direct = np.array([[row[0] + (-1) ** j * row[m] + 2 * np.sum(row[1:m] * np.cos(np.pi * i[1:m] * j / m))
                        for j in range(m + 1)] for row in x])
    np.testing.assert_allclose(dct1(jnp.asarray(x)), direct, atol=1e-13)
    np.testing.assert_allclose(idct1(dct1(jnp.asarray(x))), x, atol=1e-14)


def cosine_coefficients(zp, p, Q):
    """b_q, q = 0..Q, of the cosine series on [0, L] of the piecewise-linear interpolant of the
    nodal values p at zp: exact integrals of each linear segment times cos(q pi z / L)."""
    L = zp[-1]
    kq = np.arange(Q + 1)[:, None] * np.pi / L
    a, b, pa, pb = zp[:-1], zp[1:], p[:-1], p[1:]
    slope = (pb - pa) / (b - a)
    with np.errstate(divide="ignore", invalid="ignore"):
        prim = lambda z, f: f * np.sin(kq * z) / kq + slope * np.cos(kq * z) / kq**2
        integral = np.sum(prim(b, pb) - prim(a, pa), axis=1)
    integral[0] = np.sum(0.5 * (pa + pb) * (b - a))
    return integral * np.where(np.arange(Q + 1) == 0, 1.0, 2.0) / L


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["liner", "hole"])
def test_single_modes_match_the_direct_sum_of_3d_modes(kind):
    """p = cos(k theta) cos(j pi (z + L/2) / L) at the nodes of a 16 x 8 grid, element-constant in
    theta and piecewise linear in z: the exact cosine coefficients b_q of the piecewise-linear
    profile (q = 0..600, segment integrals), times the sum over 81 theta aliases of vjax.layer3d's
    c(|k + l n|, q pi R / L) sinc((k + l n)/n) (the hole's with ref_length 1 m, q = 0 the plane
    hole's), summed at the nodes, against the operator (whose axial images beyond 4 are the flat
    layer's, or the half-space's): within 1e-4 of the mode (1e-3 at the theta Nyquist mode, where
    the far aliases keep plane strain; measured 4.0e-4 there, at most 5.7e-5 (liner) and 7.5e-5
    (hole) elsewhere)."""
    n, m, L, Q = 16, 8, 0.1, 600
    hole = kind == "hole"
    op = land_operator(kind, Material.elastic(E, NU), R, None if hole else T, L, n, m)
    th, zp = 2 * np.pi * np.arange(n) / n, np.linspace(0, L, m + 1)
    for k, j in [(0, 3), (1, 0), (1, 2), (3, 5), (5, 1), (2, 8), (8, 8)]:
        images = np.abs(k + np.arange(-40, 41) * n)
        kR = np.arange(Q + 1) * np.pi * R / L
        c = np.asarray(layer_modes(kind, images, kR, NU, ref_length_ratio=1.0 / R) if hole else
                       layer_modes(kind, images, kR, NU, T / R))
        C = np.sum(c * np.sinc(images / n)[:, None], axis=0) * R / E
        b = cosine_coefficients(zp, np.cos(j * np.pi * zp / L), Q)
        exact = np.cos(np.outer(zp, np.arange(Q + 1)) * np.pi / L) @ (C * b)
        u = np.asarray(op(jnp.asarray(np.cos(k * th)[:, None] * np.cos(j * np.pi * zp / L)[None, :])))
        err = np.max(np.abs(u - np.cos(k * th)[:, None] * exact[None, :])) / np.max(np.abs(exact))
        assert err < (1e-3 if k == n // 2 else 1e-4), (k, j, err)


@pytest.mark.slow
def test_long_land_tends_to_plane_strain_slices():
    """A smooth pressure over the land, p ~ cos^2(pi z / L) (zero with zero slope at the ends),
    liner t/R = 0.2, the axial spacing fixed (L / m = 1.25 R): the 3D layer's displacement tends to
    the plane-strain slices' (the ring operator applied to each axial section) as (R/L)^2:
    4.7e-3 of the peak at L/R = 10, 3.1e-4 at 40 (measured)."""
    mat = Material.elastic(E, 0.4)
    n = 32
    th = 2 * np.pi * np.arange(n) / n
    ring = ring_operator("liner", mat, R, n, thickness=T)
    diffs = []
    for LR, m in ((10, 8), (40, 32)):
        L = LR * R
        z = np.linspace(-L / 2, L / 2, m + 1)
        p = jnp.asarray(1e6 * np.exp(-3 * (1 - np.cos(th)))[:, None] * (np.cos(np.pi * z / L) ** 2)[None, :])
        u3 = land_operator("liner", mat, R, T, L, n, m)(p)
        u2 = jax.vmap(ring, in_axes=1, out_axes=1)(p)
        diffs.append(float(jnp.max(jnp.abs(u3 - u2)) / jnp.max(jnp.abs(u2))))
    assert diffs[1] < 5e-4 and diffs[0] / diffs[1] > 12, diffs


@pytest.mark.slow
def test_piecewise_linear_pressure_is_resolved_on_any_axial_grid():
    """The operator takes the pressure piecewise linear between the axial nodes: a pressure that
    is piecewise linear on the coarse grid gives, at the coarse nodes, the same displacement on a
    grid 4x finer (1e-6; measured 2.2e-7, the far axial images' flat-layer model), where a cosine
    interpolant of the nodes would ring at the ends' kinks."""
    mat = Material.elastic(E, 0.4)
    n, L = 32, 0.1
    th = 2 * np.pi * np.arange(n) / n
    us = []
    for m in (16, 64):
        z = np.linspace(-L / 2, L / 2, m + 1)
        pz = np.minimum(1.0, 8 * (1 - np.abs(2 * z / L)))      # a trapezoid: kinks on coarse nodes
        p = jnp.asarray(1e6 * np.exp(-2 * (1 - np.cos(th)))[:, None] * pz[None, :])
        us.append(np.asarray(land_operator("liner", mat, R, 5e-3, L, n, m)(p))[:, :: m // 16])
    assert np.max(np.abs(us[0] - us[1])) < 1e-6 * np.max(np.abs(us[1]))


def test_axially_uniform_column_is_the_ring_operator():
    """j = 0 (a pressure uniform over the land): the symbol is the plane ring's (viscoelastic SLS,
    the pattern moving at 40 rad/s), to round-off; the other columns differ."""
    mat = Material.sls(1e8, 2e9, 0.01, 0.45)
    op = land_operator("sleeve", mat, R, T, 0.08, 32, 8, omega=40.0)
    ring = ring_operator("sleeve", mat, R, 32, omega=40.0, thickness=T)
    np.testing.assert_allclose(op.symbol[:, 0], ring.symbol, rtol=1e-12)
    assert np.max(np.abs(op.symbol[:, 4] / ring.symbol - 1)) > 0.05


@pytest.mark.slow
def test_whirl_response_at_zero_whirl_is_the_steady_operator():
    """The whirl response of the 3D layer (full FFT in theta, DCT-I in z) at whirl 0 applied to a
    pressure is the steady land operator's (each theta mode at -k omega; periodic memory), to
    round-off; at whirl 300 rad/s it differs (the material's frequency dependence)."""
    mat = Material.sls(1e8, 2e9, 0.01, 0.45)
    p = jnp.asarray(np.random.default_rng(2).normal(size=(32, 9)))
    steady = land_operator("sleeve", mat, R, T, 0.08, 32, 8, omega=40.0)(p)
    for whirl, same in ((0.0, True), (300.0, False)):
        S = whirl_symbol("sleeve", mat, R, T, 0.08, 32, 8, 40.0, whirl)
        u = jnp.fft.ifft(idct1(S * dct1(jnp.fft.fft(p, axis=0), axis=1), axis=1), axis=0)
        err = float(jnp.max(jnp.abs(u - steady)) / jnp.max(jnp.abs(steady)))     # the imaginary part too
        assert (err < 1e-12) if same else (err > 1e-2), (whirl, err)


# ------------------------------------------------------------------------------ the hole (kind "hole")
def test_hole_axially_uniform_pressure_is_the_plane_hole_ring():
    """A hole through the land (bodies.hole(mat, ref_length, axial="3d")): a z-uniform pressure
    (random in theta) gives on every section the plane hole's ring operator applied to it
    (bodies.hole(mat).operator(R, n)), to round-off (1e-12 of the peak; measured 3.6e-16), for the
    default ref_length 1 m and for ref_length = R, on an SLS material moving at 40 rad/s; the
    reference length changes the j = 0 column only (the other columns agree to 1e-12, measured
    2.0e-15 of the peak; column 0 changes by 0.22 of it); a pressure
    varying along z does not give the slices (the other columns differ by more than 5%)."""
    mat = Material.sls(1e8, 2e9, 0.01, 0.45)
    n, m, L = 32, 8, 0.08
    pt = np.random.default_rng(3).normal(size=n)
    syms = []
    for ref in (1.0, R):
        body = bodies.hole(mat, ref_length=ref, axial="3d")
        op = body.land_operator(R, n, m, L, omega=40.0)
        ring = bodies.hole(mat, ref_length=ref).operator(R, n, omega=40.0)
        u = np.asarray(op(jnp.asarray(np.repeat(pt[:, None], m + 1, axis=1))))
        u2 = np.asarray(ring(jnp.asarray(pt)))
        assert np.max(np.abs(u - u2[:, None])) < 1e-12 * np.max(np.abs(u2)), ref
        assert np.max(np.abs(op.symbol[:, 4] / ring.symbol - 1)) > 0.05
        syms.append(np.asarray(op.symbol))
    assert np.max(np.abs(syms[0][:, 1:] - syms[1][:, 1:])) < 1e-12 * np.max(np.abs(syms[0]))
    assert np.max(np.abs(syms[0][:, 0] - syms[1][:, 0])) > 0.1 * np.max(np.abs(syms[0]))


def test_hole_is_symmetric_in_z_and_spreads_a_middle_load():
    """The hole's land operator commutes with the reflection z -> -z (a random pressure, to
    round-off, measured 2.2e-16); a pressure on the land's middle half (|z| <= L/4, a bump in theta, ref_length 1 m,
    L = 2 R) deforms the 3D hole less than the plane-strain slices at every node of the loaded patch
    (p >= 0.1 of its peak; measured at most 0.70 of the slices there) and moves its unloaded ends
    (z = +-L/2, where the slices do not move; measured 0.40 of the slices' peak at theta = 0)."""
    mat = Material.elastic(E, NU)
    n, m, L = 32, 16, 0.1
    op = land_operator("hole", mat, R, None, L, n, m)
    p = jnp.asarray(np.random.default_rng(4).normal(size=(n, m + 1)))
    u, uf = np.asarray(op(p)), np.asarray(op(p[:, ::-1]))
    assert np.max(np.abs(uf - u[:, ::-1])) < 1e-13 * np.max(np.abs(u))
    th, z = 2 * np.pi * np.arange(n) / n, np.linspace(-L / 2, L / 2, m + 1)
    P = 1e6 * np.exp(-3 * (1 - np.cos(th)))[:, None] * (np.abs(z) <= L / 4 + 1e-12)[None, :]
    u3 = np.asarray(op(jnp.asarray(P)))
    ring = ring_operator("hole", mat, R, n)
    u2 = np.asarray(jax.vmap(ring, in_axes=1, out_axes=1)(jnp.asarray(P)))
    patch = P >= 0.1 * P.max()
    assert np.all(u3[patch] < 0.8 * u2[patch])
    assert np.all(np.abs(u2[:, [0, -1]]) < 1e-12 * u2.max()) and np.all(u3[0, [0, -1]] > 0.2 * u2.max())


def test_hole_whirl_response_and_arguments():
    """The hole's whirl symbol at whirl 0 is its steady land operator (to round-off) and passes
    the body's ref_length (Body.land_whirl_symbol; measured 2.4e-16; with ref_length 1 m instead of
    0.2 m the symbol differs by 0.12 of its peak); a hole takes no thickness, a layer needs one."""
    mat = Material.sls(1e8, 2e9, 0.01, 0.45)
    body = bodies.hole(mat, ref_length=0.2, axial="3d")
    p = jnp.asarray(np.random.default_rng(5).normal(size=(32, 9)))
    steady = body.land_operator(R, 32, 8, 0.08, omega=40.0)(p)
    S = body.land_whirl_symbol(R, 32, 8, 0.08, 40.0, 0.0)
    u = jnp.fft.ifft(idct1(S * dct1(jnp.fft.fft(p, axis=0), axis=1), axis=1), axis=0)
    assert float(jnp.max(jnp.abs(u - steady)) / jnp.max(jnp.abs(steady))) < 1e-12
    S1 = whirl_symbol("hole", mat, R, None, 0.08, 32, 8, 40.0, 0.0)         # ref_length 1 m
    assert float(jnp.max(jnp.abs(S1 - S))) > 1e-2 * float(jnp.max(jnp.abs(S)))
    with pytest.raises(ValueError, match="a hole has no thickness"):
        land_operator("hole", mat, R, T, 0.08, 32, 8)
    with pytest.raises(ValueError, match="a liner needs one"):
        land_operator("liner", mat, R, None, 0.08, 32, 8)
    with pytest.raises(ValueError, match="axial"):
        bodies.hole(mat, axial="2d")
