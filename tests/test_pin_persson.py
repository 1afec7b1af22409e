"""Validation of the pin-in-hole scene against the analytical (Persson-type) solution.

Thesis Figs. 2.5-2.6: R = 0.08 m, dR = 4e-5 m, E = 1 MPa, nu = 0.5, rigid pin. The closed
form (vjax.reference, checked in tests/test_reference.py) is derived for a rigid pin in an
incompressible plane with
small displacements. ``small_displacement_pin`` picks the arbitrary rigid-body reference
(ref_length) so that pin_in_hole's finite-displacement terms vanish; see its docstring.
"""
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from experiments.figures import persson as P
from vjax import reference

E, R, DR, NU = 1e6, 0.08, 4e-5, 0.5
N = 2048
LOADS = (1e-3, 5e-3, 1e-2, 2.3e-2)   # F~ = F / (E R)


@pytest.fixture(scope="module")
def numerical():
    m = vjax.Material.elastic(E, NU)
    out = {}
    for Ft in LOADS:
        r, ref = P.small_displacement_pin(m, R, DR, Ft * E * R, N)
        assert float(r.residual) < 1e-9
        out[Ft] = r
    return out


@pytest.mark.parametrize("Ft", LOADS)
def test_pressure_matches_persson(numerical, Ft):
    r = numerical[Ft]
    b = reference.persson_b_from_load(Ft * E * R, E, R, DR)
    th = np.asarray(r.theta)
    p_an = reference.persson_pressure(th, b, E, R, DR)
    err = np.abs(np.asarray(r.pressure) - p_an) / p_an.max()
    alpha = 2 * np.arctan(b)
    thw = np.abs(np.angle(np.exp(1j * th)))
    interior = thw < alpha - 2 * (2 * np.pi / N)      # all but the two elements at each edge
    assert err[interior].max() < 1e-3                  # measured 1.7e-4 .. 3.0e-4
    assert err.max() < 1.5e-2                          # edge elements: sqrt edge, one element off
    # contact angle to sub-element accuracy (p^2 linear at the edge); element size 3.1e-3 rad
    assert P.edge_angle(th, r.pressure) == pytest.approx(alpha, abs=5e-4)
    assert float(r.pin_offset) == pytest.approx(DR, rel=1e-6)


def test_load_parameter_curve(numerical):
    """E' dR/F of the numerics, at their measured contact angle, against Persson's curve."""
    for Ft, r in numerical.items():
        b_num = np.tan(P.edge_angle(r.theta, r.pressure) / 2)
        lp_num = E / (1 - NU**2) * DR / (Ft * E * R)
        b_an = reference.persson_b_from_load(Ft * E * R, E, R, DR)
        assert b_num == pytest.approx(b_an, rel=1e-3)
        # the curve is steep near the neat fit: compare in load parameter with a looser bound
        assert reference.persson_load_parameter(b_num) == pytest.approx(lp_num, rel=1e-2)


def _linear_interference(q, args):
    theta, dR, R = args
    return q[0] * jnp.cos(theta) - dR


def _linear_force(sigma, u, args):
    theta, dR, R = args
    return (2 * jnp.pi / theta.shape[0]) * R * jnp.sum(sigma * jnp.cos(theta))[None]


def test_linear_interference_solve_contact():
    """The same problem posed directly with the linear interference e cos(theta) - dR."""
    m = vjax.Material.elastic(E, NU)
    op = vjax.ring_operator("hole", m, R, N, 0.0)
    th, al = vjax.grid(N)
    F = 1e-2 * E * R
    sol = vjax.solve_contact(op, _linear_interference, (th, DR, R), jnp.array([DR]), _linear_force,
                             jnp.array([F]))
    b = reference.persson_b_from_load(F, E, R, DR)
    p_an = reference.persson_pressure(np.asarray(th), b, E, R, DR)
    err = np.abs(np.asarray(sol.pressure) - p_an) / p_an.max()
    interior = np.abs(np.angle(np.exp(1j * np.asarray(th)))) < 2 * np.arctan(b) - 4 * np.pi / N
    deep = np.abs(np.angle(np.exp(1j * np.asarray(th)))) < 0.9 * 2 * np.arctan(b)
    assert bool(sol.converged) and err[interior].max() < 1e-3 and err[deep].max() < 1e-5


def test_reference_length_dependence_is_a_finite_displacement_effect():
    """With the thesis's ref_length = 1 m the pin offset is ~1e-3 m >> dR and the exact circle
    geometry / slope terms shift the pressure by O(1%): documented, not hidden."""
    m = vjax.Material.elastic(E, NU)
    F = 2.3e-2 * E * R
    r1 = vjax.pin_in_hole(m, R, DR, F, options=vjax.PinOptions(n=N))
    b = reference.persson_b_from_load(F, E, R, DR)
    peak = reference.persson_pressure(np.array([0.0]), b, E, R, DR)[0]
    assert float(r1.pin_offset) > 10 * DR
    assert 1e-3 < abs(float(r1.pressure.max()) / peak - 1) < 5e-2
