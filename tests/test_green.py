"""Green's functions: closed-form element integrals, Michell per-mode compliances, limits."""
import numpy as np
import pytest
from scipy.integrate import quad

from vjax import green, element_symbol

R = 0.08


@pytest.mark.parametrize("kind", green.KINDS)
@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_element_integral_equals_quadrature_of_point_kernel(kind, nu):
    n = 64
    alpha = np.pi / n
    # the singular element (theta = 0), its neighbours, far ones, across the +-pi seam
    for theta in [0.0, 2 * alpha, 0.7, 3.0, np.pi, -np.pi + alpha / 2]:
        def f(t):
            return float(green.point_kernel(kind, t, R, nu))
        singular = [p for p in (0.0, np.pi, -np.pi) if theta - alpha < p < theta + alpha]
        exact = quad(f, theta - alpha, theta + alpha, points=singular or None, limit=400,
                     epsabs=1e-15, epsrel=1e-13)[0]
        closed = float(green.element_kernel(kind, theta, alpha, R, nu))
        assert abs(closed - exact) <= 1e-8 * abs(exact), (kind, theta, closed, exact)


def michell(kind, n, nu):
    """Per-mode radial compliance E u_n / (p_n R) of a pressure p_n cos(n theta), n >= 2.

    From the Michell Airy function f(r) cos(n theta) (hole: r^-n, r^(2-n); disc: r^n,
    r^(n+2)), traction sigma_rr = -p cos, tau_r_theta = 0 at r = R, plane-strain Hooke
    and integration of eps_rr (derived with sympy; the shear strain checked against
    tau/mu). Displacement measured into the body.
    """
    if kind == "hole":
        return (1 + nu) * (2 * n * (1 - nu) + 1 - 2 * nu) / (n**2 - 1)
    return (1 + nu) * (2 * n * (1 - nu) - 1 + 2 * nu) / (n**2 - 1)


@pytest.mark.parametrize("nu", [0.3, 0.5])
@pytest.mark.parametrize("kind", ["hole", "cylinder", "diametral"])
def test_mode_compliances_match_michell(kind, nu):
    n_el = 8192
    # discrete symbol of the collocation scheme -> 2 pi x continuous Fourier coefficient,
    # which is pi x (cos coefficient) x 2 ... i.e. symbol[n] -> michell(n) for n << N
    sym = np.asarray(element_symbol(kind, n_el, R, nu))
    modes = np.arange(2, 12)
    if kind == "diametral":  # two opposite forces: even modes doubled, odd modes cancel
        expected = np.where(modes % 2 == 0, 2 * michell("cylinder", modes, nu), 0.0)
        assert np.allclose(sym[modes], expected, atol=1e-6)
    else:
        assert np.allclose(sym[modes], michell(kind, modes, nu), rtol=1e-5)


@pytest.mark.parametrize("nu", [0.3, 0.45, 0.5])
def test_mode_zero_lame(nu):
    """Uniform pressure: hole u = p R (1+nu)/E (Lame); disc u = p R (1+nu)(1-2nu)/E inward."""
    sym_hole = float(element_symbol("hole", 256, R, nu)[0])
    sym_cyl = float(element_symbol("cylinder", 256, R, nu)[0])
    assert np.isclose(sym_hole, 1 + nu, rtol=1e-12)
    assert np.isclose(sym_cyl, (1 + nu) * (1 - 2 * nu), rtol=1e-12, atol=1e-12)


def test_ref_length_changes_only_mode_one():
    a = np.asarray(element_symbol("hole", 512, R, 0.3, ref_length=1.0))
    b = np.asarray(element_symbol("hole", 512, R, 0.3, ref_length=0.01))
    diff = np.abs(a - b)
    assert diff[1] > 1e-3 and np.max(np.delete(diff, 1)) < 1e-12


def test_hole_approaches_half_plane_for_large_radius():
    """Fixed patch (arc length 2 mm), growing R: the local displacement shape of the hole
    tends to the half-plane one (up to the additive constant fixed by the references)."""
    nu, half_arc = 0.4, 1e-3
    errs = []
    for Rbig in [0.01, 0.1, 1.0]:
        theta = np.linspace(-3, 3, 61) * half_arc / Rbig
        h = np.asarray(green.element_kernel("hole", theta, half_arc / Rbig, Rbig, nu))
        p = np.asarray(green.element_kernel("half_plane", theta, half_arc / Rbig, Rbig, nu))
        h, p = h - h[30], p - p[30]   # remove the constant
        errs.append(np.max(np.abs(h - p)) / np.max(np.abs(p)))
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-3


def test_kernels_finite_with_finite_gradients_at_edges():
    import jax
    import jax.numpy as jnp
    for kind in green.KINDS:
        f = lambda t: green.element_kernel(kind, t, 0.05, R, 0.3)
        for t in [0.0, 0.05, -0.05, jnp.pi, -jnp.pi]:
            assert np.isfinite(f(t)) and np.isfinite(jax.grad(f)(jnp.asarray(t)))
