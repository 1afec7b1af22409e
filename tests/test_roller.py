"""Needle roller bearing scene (vjax.roller): balances, limits, load sharing, derivatives, checks.

Thesis case (Section 2.3.2) on a coarse grid (n = 256 per ring) so that the whole file runs
in about two minutes: the compiled solve is cached per configuration and reused.
"""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax import Material, RollerOptions, roller_bearing
from vjax.operator import grid

RO, RI, D, Z = 6e-3, 4e-3, 2e-3, 9
E0, EINF, TAU, NU = 1e6, 1e7, 0.01, 0.5
LOAD = 6.5e-3 * E0 * RO                      # F~ = 6.5e-3
N = 256
SLS = Material.sls(E0, EINF, TAU, NU)


def shaft_speed(w_tilde):
    """Shaft speed giving |omega_O,c| tau = w_tilde with the outer ring fixed."""
    return w_tilde / TAU * (RI + RO) / RI


def run(w_tilde=0.0, outer=SLS, inner=SLS, n=N, **kw):
    return roller_bearing(outer, inner, RO, RI, D, Z, LOAD, omega_shaft=shaft_speed(w_tilde),
                          options=RollerOptions(n=n), **kw)


def mirror(a):
    """Values at -psi_j: roller j <-> roller Z - j (roller 1 on the load line)."""
    a = np.asarray(a)
    return a[(-np.arange(Z)) % Z]


@pytest.mark.parametrize("w_tilde", [1e-10, 1e10])
def test_elastic_limits_symmetric_and_torque_free(w_tilde):
    r = run(w_tilde)
    loads = np.asarray(r.roller_loads[0])
    assert bool(r.converged)
    np.testing.assert_allclose(loads, mirror(loads), rtol=0, atol=1e-6 * loads.max())
    assert abs(float(r.torque)) < 1e-6 * LOAD * RO and abs(float(r.torque_shaft)) < 1e-6 * LOAD * RO
    assert abs(float(r.force_angle)) < 1e-6


def test_intermediate_speed_is_asymmetric_and_dissipates():
    # the check above can fail: at omega~ = 0.01 the pattern is not symmetric
    r = run(0.01)
    loads = np.asarray(r.roller_loads[0])
    assert np.max(np.abs(loads - mirror(loads))) > 1e-2 * loads.max()
    # housing dragged along the shaft's rotation, shaft braked
    assert float(r.torque) > 1e-3 * LOAD * RO
    assert float(r.torque_shaft) < -1e-3 * LOAD * RO
    assert 0 < float(r.friction_angle) < 0.2


def test_energy_balance_each_ring_torque_times_speed_equals_modal_dissipation():
    """Omega_rel T = power dissipated in the ring = Omega sum_k k R^2 L_k J''(k Omega) |p_k|^2
    (2 pi / N^2) x 2, with T the torque about the ring's own centre. Equal up to the
    geometric factor (R +- u)/R of the torque arm: to within max |u|/R."""
    from vjax import element_symbol
    r = run(0.4)
    wc, w_rel_outer, w_rel_inner = (float(v) for v in (r.cage_speed, *r.patch_speed))
    C = np.array([float(r.ring_shift), 0.0])                      # inner centre, load along x
    F_inner = np.asarray(r.force_shaft)
    torque_about_centre = [float(r.torque), float(r.torque_shaft) - (C[0] * F_inner[1] - C[1] * F_inner[0])]
    k = np.arange(N // 2)
    rings = ((0, "hole", RO, w_rel_outer, r.pressure, r.displacement),
             (1, "cylinder", RI, w_rel_inner, r.pressure_shaft, r.displacement_shaft))
    for ring, kind, R, w, pressure, displacement in rings:
        p_hat = np.fft.rfft(np.asarray(pressure))
        L = np.asarray(element_symbol(kind, N, R, NU))[k]
        loss = -np.imag(np.asarray(SLS.compliance(k * abs(w))))
        dissipation = abs(w) * R**2 * 2 * np.pi / N**2 * 2 * np.sum(k * L * loss * np.abs(p_hat[k]) ** 2)
        assert dissipation > 0
        arm = np.max(np.abs(np.asarray(displacement))) / R       # 4e-3 here
        assert arm < 1e-2
        np.testing.assert_allclose(w * torque_about_centre[ring], dissipation, rtol=arm)


@pytest.mark.slow
def test_torque_is_resolved_on_a_coarse_grid():
    """The patches are a few elements wide at n = 256, yet the torque is within 15% of a
    16x finer grid (the spectral slope makes it the modal dissipation over the speed)."""
    for w_tilde in (0.04, 0.4, 1.2):
        coarse = run(w_tilde)
        fine = run(w_tilde, n=16 * N)
        np.testing.assert_allclose([coarse.torque, coarse.torque_shaft], [fine.torque, fine.torque_shaft], rtol=0.15)


@pytest.mark.parametrize("w_tilde", [0.0, 0.01, 1.4])
def test_load_balance_and_roller_balance(w_tilde):
    r = run(w_tilde)
    assert bool(r.converged)
    theta, alpha = grid(N)
    Fx = RI * 2 * alpha * np.sum(np.asarray(r.pressure_shaft) * np.cos(np.asarray(theta)))
    assert abs(Fx - LOAD) <= 1e-10 * LOAD
    FO, FI = np.asarray(r.roller_loads)
    np.testing.assert_allclose(FO, FI, rtol=0, atol=1e-10 * LOAD)
    # complementarity per roller: loaded rollers have no gap, open gaps carry nothing
    gaps = np.asarray(r.gaps)
    assert np.all(gaps >= -1e-12 * RO)
    assert np.all(np.where(FO > 0, np.abs(gaps), 0.0) <= 1e-12 * RO)
    assert np.all(np.asarray(r.active) == (FO > 0))
    # rollers outside the load zone (|psi| > 90 deg) carry nothing at zero clearance
    assert np.all(FO[3:6] == 0)
    # net forces on the rings (Eq. 2.38 with the slope terms of the deformed profile and the
    # tangential patch forces the cage takes): along +load (outer) and -load (inner), within
    # a few per cent on this coarse grid (about 1% at n = 512)
    assert abs(float(r.force[0]) / LOAD - 1) < 5e-2 and abs(float(r.force_shaft[0]) / LOAD + 1) < 5e-2


def test_rollers_3_and_8_lose_contact_at_intermediate_speed():
    lo, mid = run(0.0), run(1.4)
    assert np.all(np.asarray(lo.roller_loads[0])[[2, 7]] > 0)
    assert np.all(np.asarray(mid.roller_loads[0])[[2, 7]] == 0)
    assert np.all(np.asarray(mid.gaps)[[2, 7]] > 0)
    assert np.all(np.asarray(mid.roller_loads[0])[[0, 1, 8]] > 0)


@pytest.mark.slow
@pytest.mark.parametrize("rigid", ["outer", "inner"])
def test_rigid_ring_is_the_stiff_ring_limit(rigid):
    # A 1000x stiffer ring's contact is far narrower than an element, so it is resolved like
    # the rigid one only where a roller sits on an element centre: n a multiple of Z does that
    # for the outer ring; on the inner ring the rollers are seen from its shifted centre, off
    # the grid by up to half an element, hence the looser tolerance there.
    n = 32 * Z
    tol = 3e-3 if rigid == "outer" else 3e-2
    # the stiff ring 1000x the SLS (at omega~ = 0.01 nearly elastic): both parameters then share
    # one compiled reference program (SLS rings, n = 288), where an elastic stiff ring makes two
    stiff = Material.sls(1e3 * E0, 1e3 * EINF, TAU, NU)
    base = dict(outer=SLS, inner=SLS)
    rig = run(0.01, **{**base, rigid: None}, n=n)
    ref = roller_bearing(*{**base, rigid: stiff}.values(), RO, RI, D, Z, LOAD, omega_shaft=shaft_speed(0.01),
                         options=RollerOptions(n=n, tol=1e-9))
    assert bool(rig.converged)
    FO, FI = np.asarray(rig.roller_loads)
    np.testing.assert_array_equal(FO, FI)
    np.testing.assert_allclose(FO, np.asarray(ref.roller_loads[0]), rtol=0, atol=tol * LOAD)
    # the rigid ring has no pressure field and its penetration is zero; the other carries the load
    k = 0 if rigid == "outer" else 1
    assert np.all(np.asarray((rig.pressure, rig.pressure_shaft)[k]) == 0)
    pen = rig.penetration_outer if rigid == "outer" else rig.penetration_inner
    assert np.max(np.abs(np.asarray(pen))) < 1e-15
    assert abs(float(rig.ring_shift) / float(ref.ring_shift) - 1) < tol


def test_stribeck_harris_load_distribution():
    """Elastic rings (the SLS rings at rest), zero clearance: Q_max Z / F_r against
    Stribeck/Harris for line contact.

    Harris (Rolling Bearing Analysis, J_r(eps = 0.5) = 0.2453 for line contact) gives
    Q_max = F_r / (Z J_r) = 4.08 F_r / Z; the discrete Stribeck sum for Z = 9 with
    Q ~ delta^(10/9) gives 9 / sum cos^(2.11) = 4.11. The circular rings share the load
    slightly more evenly (see the experiment's note): the ratio must be within 3%.
    """
    r = run(0.0)          # SLS rings at rest: elastic with their relaxed modulus E0, exactly
    Q = np.asarray(r.roller_loads[0])
    ratio = Q.max() * Z / LOAD
    psi = np.asarray(r.roller_angles)
    c = np.maximum(np.cos(psi), 0)
    stribeck = Z / np.sum(c ** (1 + 1 / 0.9))
    print(f"Q_max Z / F_r = {ratio:.4f} (Harris 4.08, discrete Stribeck {stribeck:.4f})")
    assert abs(ratio / 4.08 - 1) < 0.03
    assert np.argmax(Q) == 0


def _outputs(p, w_tilde):
    e0, tau, pd, ro, ri = p
    m = Material.sls(e0, EINF, tau, NU)
    r = roller_bearing(m, m, ro, ri, D, Z, LOAD, diametral_clearance=pd, omega_shaft=w_tilde / TAU * (ri + ro) / ri,
                       options=RollerOptions(n=N), throw=False)
    return jnp.stack([r.torque, r.penetration_outer[2], r.roller_loads[0, 2]])


@jax.jit
def _derivatives(p, w_tilde):
    """The outputs, their Jacobian by forward mode and the torque's gradient by reverse mode
    (the transpose of the same linearization, which is what jax.grad runs): one solve in one
    compiled program, whose warm calls (~20 ms) also give the finite differences' torques."""
    y, linear = jax.linearize(lambda q: _outputs(q, w_tilde), p)
    jac = jax.vmap(linear, out_axes=1)(jnp.eye(p.shape[0], dtype=p.dtype))
    (g,) = jax.linear_transpose(linear, p)(jnp.zeros_like(y).at[0].set(1.0))
    return y[0], jac, g


@pytest.mark.slow
@pytest.mark.parametrize("w_tilde", [0.01, 1.4])
def test_torque_gradients_vs_finite_differences(w_tilde):
    """d torque / d (E0, tau, clearance, R_O, R_I); at omega~ = 1.4 rollers 3/8 are unloaded."""
    p0 = jnp.array([E0, TAU, 2e-6, RO, RI])
    T0, jac, g = _derivatives(p0, w_tilde)
    assert np.all(np.isfinite(np.asarray(jac)))        # incl. the unloaded roller 3
    np.testing.assert_allclose(np.asarray(jac[0]), np.asarray(g), rtol=1e-7)
    T0 = float(T0)
    torque = lambda p: float(_derivatives(p, w_tilde)[0])
    for i, h in enumerate([1e1, 1e-7, 1e-8, 1e-8, 1e-8]):
        e = jnp.zeros(5).at[i].set(h)
        fd = (torque(p0 + e) - torque(p0 - e)) / (2 * h)
        assert abs(float(g[i]) - fd) <= 1e-5 * abs(fd) + 1e-9 * abs(T0) / float(p0[i]), (i, g[i], fd)
    if w_tilde > 1:
        assert float(jac[2, 0]) == 0.0    # roller 3 carries nothing, nor does its derivative


def test_bad_geometry_raises_naming_the_argument():
    opts = RollerOptions(n=N)
    with pytest.raises(ValueError, match="n_rollers"):
        roller_bearing(SLS, SLS, RO, RI, D, 20, LOAD, options=opts)           # 20 rollers of 2 mm do not fit
    with pytest.raises(ValueError, match="diametral_clearance"):
        roller_bearing(SLS, SLS, RO, RI, D, Z, LOAD, diametral_clearance=-2.5e-3, options=opts)
    with pytest.raises(ValueError, match="R_inner"):
        roller_bearing(SLS, SLS, 4e-3, 6e-3, D, Z, LOAD, options=opts)
    with pytest.raises(ValueError, match="housing and shaft"):
        roller_bearing(None, None, RO, RI, D, Z, LOAD, options=opts)
    with pytest.raises(ValueError, match="load"):
        roller_bearing(SLS, SLS, RO, RI, D, Z, -1.0, options=opts)
    with pytest.raises(ValueError, match="temperature= moves no body"):
        roller_bearing(SLS, SLS, RO, RI, D, Z, LOAD, options=opts, temperature=30.0)


@pytest.mark.slow      # warm starts stay fast in tests/test_contract.py
def test_speed_sweep_with_kept_jacobians_equals_cold_solves():
    """Continuation along speed (initial=: deflections, pressures and the Jacobian, which Newton
    keeps and Broyden-updates) lands on the cold solutions."""
    prev = None
    for w in (1e-2, 0.1, 0.3, 1.0, 3.0, 10.0):
        warm = run(w, initial=prev)
        cold = run(w)
        assert bool(warm.converged) and bool(cold.converged)
        np.testing.assert_allclose(np.asarray(warm.roller_loads), np.asarray(cold.roller_loads), rtol=0,
                                   atol=1e-8 * LOAD)
        assert abs(float(warm.torque) - float(cold.torque)) <= 1e-8 * abs(float(cold.torque))
        assert warm.jacobian.shape == (10, 10) and bool(jnp.all(jnp.isfinite(warm.jacobian)))
        prev = warm
