"""The 3D bonded layer's operator on the finite bearing's land grid (vjax.layer3d_land): single
modes against the direct aliased sum of 3D modal compliances, the plane-strain slices as the
land grows long, and its axially uniform column equal to the plane ring's operator."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax import Material
from vjax.layer3d import layer_modes
from vjax.layer3d_land import dct1, idct1, land_operator, whirl_matrix
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


def test_single_modes_match_the_direct_aliased_sum(kind="liner"):
    """p = cos(k theta) cos(j pi (z + L/2) / L) on a 16 x 8 grid (element-constant in theta): the
    operator gives u = R/E sum_l c(|k + l n|, k_j R) sinc((k + l n)/n) p at every node, the sum
    over 81 aliases of vjax.layer3d's modal compliance done directly; within 2e-4 of the mode
    (the Nyquist corner, measured 1e-4) and 2e-5 for the others."""
    n, m, L = 16, 8, 0.1
    op = land_operator(kind, Material.elastic(E, NU), R, T, L, n, m)
    th, zp = 2 * np.pi * np.arange(n) / n, np.linspace(0, L, m + 1)
    for k, j in [(0, 3), (1, 0), (1, 2), (3, 5), (5, 1), (8, 8)]:
        p = np.cos(k * th)[:, None] * np.cos(j * np.pi * zp / L)[None, :]
        u = np.asarray(op(jnp.asarray(p)))
        images = np.abs(k + np.arange(-40, 41) * n)
        c = np.asarray(layer_modes(kind, images, np.array([j * np.pi * R / L]), NU, T / R))[:, 0]
        exact = np.sum(c * np.sinc(images / n)) * R / E
        assert np.max(np.abs(u - exact * p)) <= (2e-4 if (k, j) == (8, 8) else 2e-5) * abs(exact), (k, j)


def test_long_land_tends_to_plane_strain_slices():
    """A smooth pressure over the land, liner t/R = 0.2: the 3D layer's displacement tends to the
    plane-strain slices' (the ring operator applied to each axial section) as L/R grows, as
    (R/L)^2: 9.1e-4 of the peak at L/R = 40, 5.8e-5 at 160 (measured, ratio 15.9)."""
    mat = Material.elastic(E, 0.4)
    n, m = 32, 8
    th = 2 * np.pi * np.arange(n) / n
    ring = ring_operator("liner", mat, R, n, thickness=T)
    diffs = []
    for L in (40 * R, 160 * R):
        z = np.linspace(-L / 2, L / 2, m + 1)
        p = jnp.asarray(1e6 * np.exp(-3 * (1 - np.cos(th)))[:, None] * (1 - (2 * z / L) ** 2)[None, :])
        u3 = land_operator("liner", mat, R, T, L, n, m)(p)
        u2 = jax.vmap(ring, in_axes=1, out_axes=1)(p)
        diffs.append(float(jnp.max(jnp.abs(u3 - u2)) / jnp.max(jnp.abs(u2))))
    assert diffs[0] < 5e-3 and diffs[1] < 5e-4 and diffs[0] / diffs[1] > 8, diffs


def test_axially_uniform_column_is_the_ring_operator():
    """j = 0 (a pressure uniform over the land): the symbol is the plane ring's (viscoelastic SLS,
    the pattern moving at 40 rad/s), to round-off; the other columns differ."""
    mat = Material.sls(1e8, 2e9, 0.01, 0.45)
    op = land_operator("sleeve", mat, R, T, 0.08, 32, 8, omega=40.0)
    ring = ring_operator("sleeve", mat, R, 32, omega=40.0, thickness=T)
    np.testing.assert_allclose(op.symbol[:, 0], ring.symbol, rtol=1e-12)
    assert np.max(np.abs(op.symbol[:, 4] / ring.symbol - 1)) > 0.05


def test_whirl_matrix_at_zero_whirl_is_the_steady_operator():
    """The dense whirl response of the 3D layer at whirl 0 applied to a pressure is the steady land
    operator's (each theta mode at -k omega; periodic memory), to round-off; at whirl 300 rad/s it
    differs (the material's frequency dependence)."""
    mat = Material.sls(1e8, 2e9, 0.01, 0.45)
    p = jnp.asarray(np.random.default_rng(2).normal(size=(32, 9)))
    steady = land_operator("sleeve", mat, R, T, 0.08, 32, 8, omega=40.0)(p)
    for whirl, same in ((0.0, True), (300.0, False)):
        M = whirl_matrix("sleeve", mat, R, T, 0.08, 32, 8, 40.0, whirl)
        u = jnp.einsum("abil,il->ab", M, p)
        err = float(jnp.max(jnp.abs(u - steady)) / jnp.max(jnp.abs(steady)))
        assert (err < 1e-12) if same else (err > 1e-2), (whirl, err)
