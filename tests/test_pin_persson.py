"""Validation of the pin-in-hole scene against the analytical (Persson-type) solution.

Thesis Figs. 2.5-2.6: R = 0.08 m, dR = 4e-5 m, E = 1 MPa, nu = 0.5, rigid pin. The closed
form (experiments/persson.py) is derived for a rigid pin in an incompressible plane with
small displacements. ``small_displacement_pin`` picks the arbitrary rigid-body reference
(ref_length) so that pin_in_hole's finite-displacement terms vanish; see its docstring.
"""
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from experiments import persson as P

E, R, DR, NU = 1e6, 0.08, 4e-5, 0.5
N = 2048
LOADS = (1e-3, 5e-3, 1e-2, 2.3e-2)   # F~ = F / (E R)


def test_closed_form_matches_gauss_chebyshev():
    for b in (0.1, 0.4, 0.7, 1.0):
        theta, p_gc, p0_gc, f_gc = P.gauss_chebyshev_pressure(b, 60)
        p0, f = P.persson_coefficients(b)
        p = P.persson_pressure(theta, b, 1.0 + NU, 1.0, 1.0)     # K = E dR/((1+nu) R) = 1
        assert np.max(np.abs(p - p_gc)) <= 1e-11 * np.max(np.abs(p_gc))
        assert p0 == pytest.approx(p0_gc, rel=1e-11) and f == pytest.approx(f_gc, rel=1e-11)


def test_moments_against_closed_forms():
    """Quadrature of the moments against the ones derived in closed form (S = sqrt(1+b^2)):
    int gC = 2 pi (S-1)/S, int gC cos = 2 pi (S-1)/S^2, int gB = pi b^2/S^3."""
    for b in (0.05, 0.4, 0.73):
        S = np.sqrt(1 + b * b)
        m0, m1 = P._moments(b)
        assert m0[1] == pytest.approx(2 * np.pi * (S - 1) / S, rel=1e-12)
        assert m1[1] == pytest.approx(2 * np.pi * (S - 1) / S**2, rel=1e-12)
        assert m0[2] == pytest.approx(np.pi * b * b / S**3, rel=1e-12)


def test_limiting_angle_and_load_parameter():
    # thesis: contact semi-angle 1.24 rad at F~ = 2.3e-2 (E' dR/F = 0.029 with E' = E/(1-nu^2))
    b = P.persson_b_from_load(2.3e-2 * E * R, E, R, DR)
    assert 2 * np.arctan(b) == pytest.approx(1.24, abs=5e-3)
    bc = P.persson_limit_b()
    assert 2 * np.arctan(bc) == pytest.approx(1.26272, abs=1e-5)            # neat fit, F -> inf
    lp = P.persson_load_parameter(np.array([0.05, 0.3, 0.6, bc, bc * 1.01]))
    assert np.all(np.diff(lp) < 0) and abs(lp[3]) < 1e-9 and lp[4] < 0
    # small loads: Hertz limit of a conforming contact, half-width a = R alpha with
    # a^2 = 4 F R_eff / (pi E'), R_eff = R R_pin / dR
    alpha = 2 * np.arctan(0.01)
    F = E / (1 - NU**2) * DR / P.persson_load_parameter(0.01)
    a_hertz = np.sqrt(4 * F * R * (R - DR) / DR / (np.pi * E / (1 - NU**2)))
    assert R * alpha == pytest.approx(a_hertz, rel=2e-3)


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
    b = P.persson_b_from_load(Ft * E * R, E, R, DR)
    th = np.asarray(r.theta)
    p_an = P.persson_pressure(th, b, E, R, DR)
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
        b_an = P.persson_b_from_load(Ft * E * R, E, R, DR)
        assert b_num == pytest.approx(b_an, rel=1e-3)
        # the curve is steep near the neat fit: compare in load parameter with a looser bound
        assert P.persson_load_parameter(b_num) == pytest.approx(lp_num, rel=1e-2)


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
    b = P.persson_b_from_load(F, E, R, DR)
    p_an = P.persson_pressure(np.asarray(th), b, E, R, DR)
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
    b = P.persson_b_from_load(F, E, R, DR)
    peak = P.persson_pressure(np.array([0.0]), b, E, R, DR)[0]
    assert float(r1.pin_offset) > 10 * DR
    assert 1e-3 < abs(float(r1.pressure.max()) / peak - 1) < 5e-2
