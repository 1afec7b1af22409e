"""Mixed lubrication in the finite journal bearing (issue 43): its limits, derivatives, stiffness
and refusals. The bearing is the issue's: journal radius 25 mm in a bore of 25.05 mm, c = 50 um,
L/D = 1, eta = 0.03 Pa s, W = 2 kN, no groove (the film periodic, ambient at both ends),
Reynolds cavitation; a smooth steel journal (210 GPa, 0.3) in a rough polymer bush (3 GPa,
0.4), sigma = 1 um, eta_s beta sigma = 0.05, sigma/beta = 0.005, mu_b = 0.1.
The comparison with an independent peer computation of the same model is in test_mixed_peer.py."""
import dataclasses

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax

R, C, ETA, W = 25.05e-3, 50e-6, 0.03, 2000.0
L = 2 * R
ROUGH = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
OPT = vjax.FiniteJournalOptions(n=32, m=16)
BEARING = dict(length=L, supply_angle=None, options=OPT)


def solve(omega, roughness=ROUGH, **kw):
    return vjax.journal_bearing(R, C, ETA, W, omega_shaft=omega, roughness=roughness, **{**BEARING, **kw})


@pytest.mark.slow      # rough and smooth films stay fast in the peer comparison and the boundary limit
def test_smooth_limit_is_the_full_film():
    """sigma -> 0: the flow factors -> 1, the expected gap -> h, no asperity pressure: today's
    smooth bearing to 1e-8 (the power by its own definition: the drive's, to 1e-6)."""
    smooth = solve(30.0, roughness=None)
    tiny = solve(30.0, roughness=dataclasses.replace(ROUGH, sigma=1e-12))
    for name in ("eccentricity", "attitude_angle", "torque_shaft", "torque", "side_leakage", "max_pressure",
                 "friction_coefficient", "min_film"):
        a, b = float(getattr(tiny, name)), float(getattr(smooth, name))
        assert abs(a - b) <= 1e-8 * abs(b), (name, a, b)
    assert np.max(np.abs(tiny.pressure - smooth.pressure)) <= 1e-8 * float(smooth.max_pressure)
    assert float(tiny.asperity_share) == 0.0 and float(smooth.asperity_share) == 0.0
    assert float(tiny.power_loss) == pytest.approx(float(smooth.power_loss), rel=1e-6)
    assert float(smooth.film_parameter) == np.inf


def test_boundary_limit_is_dry_sliding_with_the_wrap_factor():
    """omega -> 0: the asperities carry the load and the friction coefficient tends to mu_b
    times the contact arc's wrap factor, int p_a dA / |int p_a n dA| (computed here from the
    asperity pressure map on the trapezoidal grid)."""
    r = solve(1e-4)
    assert r.converged and float(r.asperity_share) > 0.999
    theta, z, p_a = np.asarray(r.theta), np.asarray(r.z), np.asarray(r.asperity_pressure)
    w = np.diff(z)
    wz = 0.5 * (np.concatenate([[0.0], w]) + np.concatenate([w, [0.0]]))
    dA = R * (2 * np.pi / theta.size) * wz[None, :]
    wrap = np.sum(p_a * dA) / np.hypot(np.sum(p_a * np.cos(theta)[:, None] * dA),
                                       np.sum(p_a * np.sin(theta)[:, None] * dA))
    assert 1.0 < wrap < 1.02
    assert float(r.friction_coefficient) == pytest.approx(float(ROUGH.mu_b) * wrap, rel=2e-3)
    # the asperities' force balances the load: the journal sits past the clearance
    assert float(r.eccentricity) > 1.0 and float(r.film_parameter) < 0


@pytest.mark.slow      # stribeck_curve stays in the fast tier through the peer comparison
def test_stribeck_sweep_crosses_lift_off():
    """A warm-started sweep from boundary to full film: every point converges, the asperity
    share falls with speed from ~1 to 0, friction has its Stribeck minimum inside the sweep,
    above the lift-off speed (1 % share)."""
    curve = vjax.stribeck_curve(R, C, ETA, W, np.logspace(-3, 2, 11), length=L, roughness=ROUGH,
                                supply_angle=None, options=OPT)
    assert curve.converged.all(), curve.result
    assert curve.asperity_share[0] > 0.99 and curve.asperity_share[-1] < 1e-6
    assert np.all(np.diff(curve.asperity_share) <= 1e-9)
    assert curve.lift_off_speed is not None and curve.minimum_speed is not None
    assert curve.speed[0] < curve.lift_off_speed < curve.minimum_speed < curve.speed[-1]
    assert curve.friction_coefficient[0] == pytest.approx(0.1, rel=0.02)
    assert np.all(curve.hersey == pytest.approx(ETA * curve.speed / (W / (L * 2 * R))))


@pytest.mark.slow
def test_derivatives_in_the_mixed_regime():
    """d(friction coefficient, eccentricity) by implicit differentiation, with respect to sigma,
    mu_b, the speed and the viscosity, against central differences, at a point where the
    asperities carry ~5 % of the load."""
    opt = dataclasses.replace(OPT, tol=1e-12)
    start = solve(1.78, options=opt)
    assert 0.01 < float(start.asperity_share) < 0.2

    def outputs(sigma, mu_b, omega, eta):
        r = vjax.journal_bearing(R, C, eta, W, omega_shaft=omega, initial=start,
                                 roughness=dataclasses.replace(ROUGH, sigma=sigma, mu_b=mu_b),
                                 **{**BEARING, "options": opt})
        return jnp.stack([r.friction_coefficient, r.eccentricity])

    x = (1e-6, 0.1, 1.78, ETA)
    J = jax.jacfwd(outputs, argnums=(0, 1, 2, 3))(*x)
    for k, step in enumerate((1e-10, 1e-5, 1e-4, 3e-6)):
        up, down = list(x), list(x)
        up[k] += step
        down[k] -= step
        fd = (np.asarray(outputs(*up)) - np.asarray(outputs(*down))) / (2 * step)
        np.testing.assert_allclose(np.asarray(J[k]), fd, rtol=1e-6, atol=1e-9 * np.max(np.abs(fd)))


@pytest.mark.slow
def test_mixed_stiffness_is_the_static_stiffness():
    """K at zero whirl, with the asperities' stiffness, equals the inverse of d(journal
    position)/d(load vector) of the steady solves (forward-mode through the implicit root)."""
    start = solve(1.78)
    co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=1.78, roughness=ROUGH, initial=start,
                                   **BEARING)

    def position(load):
        return vjax.journal_bearing(R, C, ETA, load, omega_shaft=1.78, roughness=ROUGH, initial=start,
                                    **BEARING).position

    compliance = jax.jacfwd(position)(jnp.array([0.0, -W]))
    # dF_film+asperities = -K dx, the load balances it: d position / d load = K^-1
    np.testing.assert_allclose(np.asarray(co.stiffness[0]), np.linalg.inv(np.asarray(compliance)), rtol=1e-5)


@pytest.mark.slow
def test_tilt_beyond_the_clearance():
    """Smooth surfaces: a tilt that moves the journal's ends by 5 clearances is refused before
    any work, naming the largest the clearance allows (2 c / L). Rough: edge contact (ends moved
    by 1.5 clearances), solved."""
    with pytest.raises(ValueError, match=r"5 clearances.*2 c / L = 0.002 rad"):
        vjax.journal_bearing(R, C, ETA, W, omega_shaft=100.0, length=0.05, tilt=(0.01, 0.0), options=OPT)
    r = vjax.journal_bearing(R, C, ETA, W, omega_shaft=100.0, length=0.05, tilt=(0.003, 0.0), roughness=ROUGH,
                             options=OPT)
    assert r.converged and float(r.film_parameter) < 0 and float(r.asperity_share) > 0
    assert np.allclose(np.asarray(r.force), [0.0, -W], atol=1e-6 * W)
    assert abs(float(r.moment[1])) > 0     # the edges' contact makes a moment the shaft carries


def test_a_closing_smooth_film_says_a_roughness_would_carry_it():
    """Without a roughness the thin-film failure message stays, and names the roughness."""
    with pytest.raises(vjax.ConvergenceError, match="roughness=vjax.Roughness"):
        solve(0.01, roughness=None)


LINER = vjax.liner(vjax.Material.sls(1.5e9, 3e9, 0.01, 0.4), 2e-3)     # a 2 mm polymer liner (Pa, Pa, s)


@pytest.mark.slow
def test_a_lined_bearing_from_boundary_to_full_film():
    """The asperity pressure loads the liner with the film's: with sigma -> 0 the lined mixed
    bearing is the lined smooth one (to 1e-8); at a barely turning journal the asperities carry
    nearly all the load over a wider arc than on a rigid bore (the liner spreads the contact);
    the forces balance the load at every point."""
    smooth = solve(30.0, roughness=None, housing=LINER)
    tiny = solve(30.0, roughness=dataclasses.replace(ROUGH, sigma=1e-12), housing=LINER)
    for name in ("eccentricity", "attitude_angle", "torque_shaft", "max_pressure"):
        a, b = float(getattr(tiny, name)), float(getattr(smooth, name))
        assert abs(a - b) <= 1e-8 * abs(b), (name, a, b)
    slow_lined, slow_rigid = solve(1e-3, housing=LINER), solve(1e-3)
    assert float(slow_lined.asperity_share) > 0.98
    np.testing.assert_allclose(np.asarray(slow_lined.force), [0.0, -W], atol=1e-8 * W)
    arc = lambda r: np.mean(np.asarray(r.asperity_pressure) > 1e-3 * float(np.max(r.asperity_pressure)))  # noqa: E731
    assert arc(slow_lined) > 1.5 * arc(slow_rigid)
    assert float(slow_lined.displacement.max()) > float(ROUGH.sigma)     # the liner yields by more than sigma


def test_roughness_refused_where_it_is_not_built():
    # (the infinitely long bearing's mixed film: tests/test_journal_long_rough.py)
    with pytest.raises(ValueError, match="dynamic coefficients of a mixed film on a deformable body"):
        vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=30.0, roughness=ROUGH, housing=LINER, **BEARING)


@pytest.mark.slow
def test_dry_limit_against_the_pin_contact():
    """The lined bearing barely turning is dry contact of the journal in its bore: against the
    pin-in-hole contact solver on the same geometry and liner, per unit length (W / L), the
    journal sits where the pin does to within a few sigma; the asperity layer's own compliance
    spreads the contact wider and lowers its peak (here ~10 %)."""
    r = solve(1e-4, housing=LINER, options=vjax.FiniteJournalOptions(n=64, m=8))
    pin = vjax.pin_in_hole(LINER, R, C, W / L, omega_shaft=1e-6, load_angle=-np.pi / 2,
                           options=vjax.PinOptions(n=64))
    assert float(r.asperity_share) > 0.999 and pin.converged
    mid = np.asarray(r.asperity_pressure)[:, 4]                  # mid-width, away from the ends
    contact = np.asarray(pin.pressure)
    assert abs(float(r.eccentricity) - float(pin.pin_offset) / C) < 3 * float(ROUGH.sigma) / C
    assert 0.8 < mid.max() / contact.max() < 1.0
    assert np.sum(mid > 0.01 * mid.max()) > np.sum(contact > 0.01 * contact.max())


# ---- against the independent peer (tests/mixed_peer.py: numpy and scipy, written from the
# equations): the four cases along the Stribeck curve, on the peer's grid (the mixed
# regime is far from grid-converged on 32 x 16, so codes are compared on the same grid)
PEER_SPEEDS = (100.0, 10.0, 3.0, 1.0, 0.3, 0.01, 0.001)


def _against_the_peer(L_over_D, sigma):
    import mixed_peer
    peer = mixed_peer.stribeck(L_over_D, sigma, PEER_SPEEDS)
    length = L_over_D * 2 * R
    rough = vjax.Roughness.from_surfaces(0.0, sigma, 210e9, 0.3, 3e9, 0.4)
    curve = vjax.stribeck_curve(R, C, ETA, W, PEER_SPEEDS, length=length, roughness=rough, supply_angle=None,
                                options=OPT)
    order = np.argsort(peer["omega"])
    assert curve.converged.all()
    assert curve.asperity_share[0] > 0.97           # the sweep starts where the asperities carry ~all of it
    np.testing.assert_allclose(curve.eccentricity, peer["eccentricity"][order], rtol=0.01)
    np.testing.assert_allclose(curve.asperity_share, peer["asperity_share"][order], atol=0.02)
    np.testing.assert_allclose(curve.friction_coefficient, peer["friction_coefficient"][order], rtol=0.03)


def test_against_the_peer_L_over_D_1_sigma_1um():
    _against_the_peer(1.0, 1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("L_over_D, sigma", [(0.5, 0.5e-6), (0.5, 1e-6), (1.0, 0.5e-6)])
def test_against_the_peer_other_cases(L_over_D, sigma):
    _against_the_peer(L_over_D, sigma)


def test_squeeze_stores_the_expected_gap():
    """The average flow's transient term is the rate of the volume it stores, the expected gap
    h_T (Patir and Cheng 1978), not the nominal gap: the cell equations' change under a journal
    velocity dX/dt (the dynamic coefficients' damping) equals the change of each cell's stored
    volume R dtheta dz h_T under a displacement dX, by central differences in the position.
    Full film (linear balances), the journal at e/c = 0.97 (H = h/sigma from 1.5): dh_T/dh
    differs from 1 by up to 7 %, so the nominal gap's rate would fail by that much."""
    from vjax.scenes.journal.finite import film, setup as finite_setup
    from vjax.films import film2d
    pr, cfg = finite_setup.setup(R, C, ETA, W, L, omega_shaft=1.0, cavitation="sommerfeld", supply_angle=None,
                                 roughness=ROUGH, options=vjax.FiniteJournalOptions(n=32, m=8))
    N = film.unknowns(cfg)
    x = jnp.concatenate([jnp.full(N, 0.1), jnp.array([0.97, 0.0])])
    V, dX = 1e-3, 1e-9                               # m/s, m
    at = lambda q: film.cell_residual(x, pr, cfg, jnp.asarray(q))[0][:N]    # noqa: E731
    squeeze = at([0.0, 0.0, V, 0.0]) - at([0.0, 0.0, 0.0, 0.0])
    f = film.fields(x, pr, cfg)
    volume = lambda q: pr.rough.expected_gap(film.fields(x, pr, cfg, jnp.asarray(q))["h"])  # noqa: E731
    rate = V * (volume([dX, 0.0, 0.0, 0.0]) - volume([-dX, 0.0, 0.0, 0.0])) / (2 * dX)
    cell_area = pr.R * 2 * np.pi / cfg.n * film2d.node_widths(f["z"])[None, 1:-1]
    scale = film2d.conductance(f, pr.R, f["z"]) * pr.p_ref
    expected = (cell_area * rate[:, 1:-1] / scale).ravel()
    H = np.asarray(f["h"]) / float(pr.rough.sigma)
    assert H.min() < 2.0                             # the regime where h_T and h differ
    np.testing.assert_allclose(np.asarray(squeeze), np.asarray(expected), rtol=1e-6,
                               atol=1e-9 * float(np.max(np.abs(expected))))
