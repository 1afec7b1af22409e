"""Bonded layers (liner, sleeve): modal compliances against independent limits, the element
operator against the aliased modal sum, and the scenes built on them."""
import subprocess
import sys

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import Material, PinOptions, green

NUS = (0.3, 0.45, 0.5)


def lame_bonded(kind, nu, tau):
    """Uniform pressure 1 on a ring bonded on its other surface, from Lame's u = A r + B/r
    with the Lame constants (E = 1, loaded radius 1): the displacement into the body."""
    lam, mu = nu / ((1 + nu) * (1 - 2 * nu)) if nu < 0.5 else np.inf, 1 / (2 * (1 + nu))
    b = 1 + tau if kind == "liner" else 1 - tau
    if not np.isfinite(lam):
        return 0.0                     # incompressible: no change of area without moving the bond
    # sigma_rr(1) = 2 (lam + mu) A - 2 mu B = -1, u(b) = A b + B / b = 0
    A = -1.0 / (2 * (lam + mu) + 2 * mu * b * b)
    return abs(A * (1 - b * b))


@pytest.mark.parametrize("nu", NUS)
@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_mode_zero_is_lame_with_a_bonded_surface(kind, nu):
    for tau in (1e-3, 1e-2, 0.1, 0.5, 0.9 if kind == "sleeve" else 2.0):
        c0 = float(green.mode_compliance(kind, 0, nu, thickness_ratio=tau))
        assert c0 == pytest.approx(lame_bonded(kind, nu, tau), rel=1e-10, abs=1e-15)


@pytest.mark.parametrize("nu", NUS)
def test_thick_liner_is_a_hole_and_full_sleeve_a_disc(nu):
    n = jnp.arange(2, 40)
    hole = green.mode_compliance("hole", n, nu)
    assert np.allclose(green.mode_compliance("liner", n, nu, thickness_ratio=1e3), hole, rtol=1e-5)
    disc = green.mode_compliance("disc", n, nu)
    assert np.allclose(green.mode_compliance("sleeve", n, nu, thickness_ratio=1 - 1e-6), disc, rtol=1e-5)
    # and both layers stiffen as they thin
    for kind in ("liner", "sleeve"):
        c = [float(green.mode_compliance(kind, 3, nu, thickness_ratio=t)) for t in (1e-3, 1e-2, 1e-1, 0.5)]
        assert np.all(np.diff(c) > 0)


@pytest.mark.parametrize("nu", [0.3, 0.45])
@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_thin_layer_is_oedometric(kind, nu):
    """t << R/n: every mode sees the constrained modulus, c = (t/R)(1+nu)(1-2nu)/(1-nu)."""
    tau = 1e-3
    c = np.asarray(green.mode_compliance(kind, jnp.arange(0, 6), nu, thickness_ratio=tau))
    assert np.allclose(c, tau * (1 + nu) * (1 - 2 * nu) / (1 - nu), rtol=5e-3)


@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_thin_incompressible_layer_scales_with_the_cube_of_its_thickness(kind):
    """nu = 0.5: no volume change, the layer can only squeeze sideways: c_n ~ n^2 (t/R)^3."""
    n = jnp.arange(1, 6)
    c1 = np.asarray(green.mode_compliance(kind, n, 0.5, thickness_ratio=1e-3))
    c2 = np.asarray(green.mode_compliance(kind, n, 0.5, thickness_ratio=2e-3))
    assert np.allclose(c2 / c1, 8.0, rtol=1e-2)
    assert np.allclose(c1 / np.asarray(n) ** 2, c1[0], rtol=1e-2)
    # far stiffer than the compressible oedometric layer of the same thickness
    assert np.all(c1 < 1e-4 * float(green.mode_compliance(kind, 1, 0.45, thickness_ratio=1e-3)))


@pytest.mark.slow      # each body's operator stays fast in its own tests
def test_element_symbol_is_the_aliased_modal_sum():
    """The piecewise-constant operator = the continuous one integrated over the elements:
    sum over m = k (mod n) of c_m sinc(m/n), here summed directly over 2^20 modes."""
    n, R, t, nu = 32, 0.006, 0.002, 0.3
    sym = np.asarray(vjax.element_symbol("liner", n, R, nu, thickness=t))
    m = np.arange(0, 1 << 20)
    c = np.asarray(green.mode_compliance("liner", m, nu, thickness_ratio=t / R))
    w = c * np.sinc(m / n)
    full = np.zeros(n)
    np.add.at(full, m % n, w)
    np.add.at(full, (-m[1:]) % n, w[1:])
    assert np.allclose(sym, full[: n // 2 + 1], rtol=2e-6)


def test_small_batched_solve_matches_lapack():
    """The layers' 4x4 Michell systems are solved by vjax's own Gaussian elimination with
    partial pivoting (green._solve_small): it equals LAPACK's, real and complex, also where
    the first pivot is zero, and on the layers' own matrices (the compliance above)."""
    rng = np.random.default_rng(0)
    real = rng.normal(size=(500, 4, 4))
    for a in (real, real + 1j * rng.normal(size=real.shape)):
        a[:, 0, 0] = 0.0
        b = rng.normal(size=a.shape[:-1]).astype(a.dtype)
        x = np.asarray(green._solve_small(jnp.asarray(a), jnp.asarray(b)))
        ref = np.linalg.solve(a, b[..., None])[..., 0]
        assert np.max(np.abs(x - ref) / np.abs(ref).max(-1, keepdims=True)) < 1e-10


def test_liner_and_sleeve_in_one_program_do_not_deadlock():
    """A journal bearing with a liner and a sleeve builds both layers' operators in one compiled
    program. With LAPACK's batched solve there, the two ran side by side and, on two cores,
    jaxlib's kernels could wait for each other forever (seen in one run of three). Three
    bearings in a fresh interpreter must finish (each one a chance to hang)."""
    code = (
        "import jax; jax.config.update('jax_enable_x64', True)\n"
        "import vjax\n"
        "sls = vjax.Material.sls(1e9, 3e9, 1e-3, 0.4)\n"
        "for load in (2e5, 3e5, 4e5):\n"
        "    s = vjax.journal_bearing(0.05, 5e-5, 0.01, load, omega_shaft=100.0, housing=vjax.liner(sls, 2e-3),\n"
        "                             shaft=vjax.sleeve(sls, 3e-3), options=vjax.JournalOptions(n=64))\n"
        "    assert bool(s.converged)\n")
    done = subprocess.run([sys.executable, "-c", code], timeout=150, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]


def test_gradient_with_respect_to_thickness_and_nu():
    f = lambda t, nu: green.mode_compliance("liner", 4, nu, thickness_ratio=t)
    g = jax.grad(f, argnums=(0, 1))(0.1, 0.3)
    for i, (x, h) in enumerate(((0.1, 1e-6), (0.3, 1e-6))):
        args = [0.1, 0.3]
        up, dn = list(args), list(args)
        up[i] += h
        dn[i] -= h
        assert float(g[i]) == pytest.approx((float(f(*up)) - float(f(*dn))) / (2 * h), rel=1e-6)


# ---------------------------------------------------------------------- finite elements
def _annulus(a, b, nr, nt):
    """A structured triangulation of the annulus a < r < b (nt points around, periodic)."""
    from skfem import MeshTri
    r = np.linspace(a, b, nr + 1)
    th = 2 * np.pi * np.arange(nt) / nt
    Rg, Tg = np.meshgrid(r, th, indexing="ij")
    points = np.stack([(Rg * np.cos(Tg)).ravel(), (Rg * np.sin(Tg)).ravel()])
    idx = lambda i, j: i * nt + (j % nt)
    tri = [[idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)] for i in range(nr) for j in range(nt)]
    tri += [[idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)] for i in range(nr) for j in range(nt)]
    return MeshTri(points, np.array(tri).T)


def _fem_surface_displacement(kind, R, t, nu, patch, nr=10, nt=960):
    """Plane-strain P2 finite elements (scikit-fem) of the layer, E = 1: the radial
    displacement into the body at the loaded surface's nodes, by angle."""
    from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, FacetBasis, LinearForm, asm, condense, solve
    from skfem.helpers import ddot, dot, sym_grad, trace
    a, b = (R, R + t) if kind == "liner" else (R - t, R)
    mesh = _annulus(a, b, nr, nt)
    element = ElementVector(ElementTriP2())
    basis = Basis(mesh, element)
    lam, mu = nu / ((1 + nu) * (1 - 2 * nu)), 1 / (2 * (1 + nu))

    @BilinearForm
    def stiffness(u, v, w):
        return 2 * mu * ddot(sym_grad(u), sym_grad(v)) + lam * trace(sym_grad(u)) * trace(sym_grad(v))

    @LinearForm
    def pressure(v, w):              # traction -p n on the loaded surface
        return -patch(np.arctan2(w.x[1], w.x[0])) * dot(w.n, v)

    on = lambda radius: (lambda x: np.abs(np.hypot(x[0], x[1]) - radius) < 1e-3 * t)
    f = asm(pressure, FacetBasis(mesh, element, facets=mesh.facets_satisfying(on(R))))
    fixed = basis.get_dofs(mesh.facets_satisfying(on(b if kind == "liner" else a))).all()
    u = solve(*condense(asm(stiffness, basis), f, D=fixed))
    nodes = np.nonzero(on(R)(mesh.p))[0]
    th = np.arctan2(mesh.p[1, nodes], mesh.p[0, nodes])
    ur = u[basis.nodal_dofs[0, nodes]] * np.cos(th) + u[basis.nodal_dofs[1, nodes]] * np.sin(th)
    order = np.argsort(np.mod(th, 2 * np.pi))
    return np.mod(th, 2 * np.pi)[order], (ur if kind == "liner" else -ur)[order]


@pytest.mark.parametrize("nu", [0.3, 0.45])
@pytest.mark.parametrize("kind", ["liner", "sleeve"])
def test_layer_operator_matches_finite_elements(kind, nu):
    """Bonded liner R = 6 mm, t = 2 mm, and sleeve R = 6 mm on a 4 mm core, under a cos^2
    patch pressure 0.6 rad wide: vjax's surface displacement within 0.5% of its peak."""
    R, t, width = 6e-3, 2e-3, 0.3
    patch = lambda th: np.where(np.abs(th) < width, np.cos(np.pi * th / (2 * width)) ** 2, 0.0)
    th_fem, u_fem = _fem_surface_displacement(kind, R, t, nu, patch)
    n = 480
    theta = 2 * np.pi * np.arange(n) / n
    sub = theta[:, None] + ((np.arange(32) + 0.5) / 32 - 0.5)[None, :] * (2 * np.pi / n)
    p = patch(np.angle(np.exp(1j * sub))).mean(axis=1)              # element means
    u = np.asarray(vjax.ring_operator(kind, Material.elastic(1.0, nu), R, n, thickness=t)(jnp.asarray(p)))
    u_ref = np.interp(theta, th_fem, u_fem, period=2 * np.pi)
    assert np.max(np.abs(u - u_ref)) <= 5e-3 * np.max(np.abs(u_ref))


# ---------------------------------------------------------------------- scenes
SLS = Material.sls(1e6, 1e7, 0.01, 0.5)
R, C, LOAD, N = 0.08, 0.005, 2800.0, 256


def _pin(omega_tilde, thickness=0.01, material=SLS, n=N):
    W = omega_tilde / 0.01
    return vjax.pin_in_hole(vjax.liner(material, thickness), R, C, LOAD,
                            omega_shaft=vjax.pin_shaft_speed(W, R, C), options=PinOptions(n=n))


@pytest.mark.parametrize("omega_tilde", [1e-9, 1e9])
def test_pin_in_a_liner_elastic_limits(omega_tilde):
    r = _pin(omega_tilde)
    p = np.asarray(r.pressure)
    mirror = np.roll(p[::-1], 1)
    assert np.max(np.abs(p - mirror)) < 1e-6 * p.max()
    assert abs(float(r.torque)) < 1e-8 * LOAD * R


def test_pin_in_a_liner_torque_times_speed_is_the_modal_dissipation():
    omega = 0.3 / 0.01
    r = _pin(0.3)
    sig = np.fft.rfft(np.asarray(r.pressure))
    k = np.arange(N // 2)
    L = np.asarray(vjax.element_symbol("liner", N, R, 0.5, thickness=0.01))[k]
    loss = -np.imag(np.asarray(SLS.compliance(k * omega)))
    dissipation = omega * R**2 * 2 * np.pi / N**2 * 2 * np.sum(k * L * loss * np.abs(sig[k]) ** 2)
    assert dissipation > 0
    assert np.isclose(-omega * float(r.torque), dissipation, rtol=1e-9)


@pytest.mark.slow
def test_pin_in_a_liner_gradient_vs_finite_differences_and_vmap():
    torque = lambda t: _pin(0.3, thickness=t).torque
    g = float(jax.grad(torque)(0.01))
    h = 1e-6
    assert g == pytest.approx((float(torque(0.01 + h)) - float(torque(0.01 - h))) / (2 * h), rel=1e-5)
    many = jax.jit(jax.vmap(torque))(jnp.array([0.005, 0.01, 0.02]))
    assert np.all(np.isfinite(np.asarray(many))) and float(many[0]) != float(many[2])


def test_thin_bushing_tends_to_a_winkler_foundation():
    """A thin compressible liner is a bed of independent springs (Winkler, vjax.reference):
    the pin's contact angle and its pressure inside the contact approach that limit."""
    m, t, c, F = Material.elastic(1e8, 0.3), 1e-4, 1e-4, 2e4
    r = vjax.pin_in_hole(vjax.liner(m, t), R, c, F, options=PinOptions(n=2048))
    k = vjax.reference.oedometric_stiffness(1e8, 0.3, t)
    alpha, _, p_winkler = vjax.reference.winkler_pin(F, R, c, k)
    assert float(r.contact_angle) == pytest.approx(float(alpha), rel=0.02)
    p = np.asarray(r.pressure)
    inside = p > 0.2 * p.max()                   # away from the edges, where the layer shears
    assert np.allclose(p[inside], np.asarray(k * np.asarray(r.displacement))[inside], rtol=0.03)
    assert float(p.max()) == pytest.approx(float(p_winkler(0.0)), rel=0.03)


def test_a_liner_has_no_reference_length_and_checks_its_input():
    """A hole's pin offset moves with the log reference length (its rigid mode 1); a bonded
    liner has none: the pin sinks only by the layer's compression (tens of micrometres)."""
    hole = [vjax.pin_in_hole(vjax.hole(SLS, ref_length=l), R, C, LOAD, options=PinOptions(n=N)).pin_offset
            for l in (1.0, 10.0)]
    assert abs(float(hole[1] - hole[0])) > 1e-4
    assert 0 < float(_pin(0.3).pin_offset) - C < 1e-4
    with pytest.raises(ValueError, match="thickness"):
        vjax.liner(SLS, -1.0)
    with pytest.raises(ValueError, match="thickness"):
        vjax.pin_in_hole(vjax.liner(SLS, 1e-6), R, C, LOAD, options=PinOptions(n=64))
    with pytest.raises(ValueError, match="housing must be one of the bodies hole, liner"):
        vjax.pin_in_hole(vjax.sleeve(SLS, 0.01), R, C, LOAD, options=PinOptions(n=64))


@pytest.mark.slow
def test_roller_with_a_bushing_and_a_sleeve():
    """The thesis's test-bearing layout (a bushing pressed into a rigid holder) with a sleeved
    inner ring: elastic at low speed (symmetric loads, no torque), and at a finite speed each
    ring's torque x patch speed is its modal dissipation (to the lever-arm factor max|u|/R)."""
    RO, RI, D, Z, n = 6e-3, 4e-3, 2e-3, 9, 256
    run = lambda w: vjax.roller_bearing(vjax.liner(SLS, 2e-3), vjax.sleeve(SLS, 1e-3), RO, RI, D, Z, 39.0,
                                        omega_shaft=w, options=vjax.RollerOptions(n=n))
    slow = run(1e-8)
    loads = np.asarray(slow.roller_loads[0])
    assert np.allclose(loads, loads[(-np.arange(Z)) % Z], rtol=0, atol=1e-6 * loads.max())
    assert abs(float(slow.torque)) < 1e-6 * 39.0 * RO
    r = run(0.4 / 0.01 * (RI + RO) / RI)
    _, w_outer, w_inner = (float(v) for v in (r.cage_speed, *r.patch_speed))
    about_own_centre = float(r.torque_shaft) - float(r.ring_shift) * float(r.force_shaft[1])
    k = np.arange(n // 2)
    rings = (("liner", RO, 2e-3, w_outer, r.pressure, r.displacement, float(r.torque)),
             ("sleeve", RI, 1e-3, w_inner, r.pressure_shaft, r.displacement_shaft, about_own_centre))
    for kind, Rr, t, w, p, u, torque in rings:
        L = np.asarray(vjax.element_symbol(kind, n, Rr, 0.5, thickness=t))[k]
        loss = -np.imag(np.asarray(SLS.compliance(k * abs(w))))
        dissipation = abs(w) * Rr**2 * 2 * np.pi / n**2 * 2 * np.sum(k * L * loss * np.abs(np.fft.rfft(p)[k]) ** 2)
        arm = np.max(np.abs(np.asarray(u))) / Rr
        assert dissipation > 0
        np.testing.assert_allclose(w * torque, dissipation, rtol=max(arm, 1e-9))

