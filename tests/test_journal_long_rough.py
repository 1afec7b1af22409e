"""Mixed lubrication in the infinitely long journal bearing (issue 43), per unit length: its
limits, an independent 1D peer, the finite bearing's long limit, derivatives, stiffness and a
lined bearing across the Stribeck range. The bearing is the issue's per unit length: bore
radius 25.05 mm, c = 50 um, eta = 0.03 Pa s, W = 2 kN over L = D (39.9 kN/m), a groove at the
widest gap (the long bearing's datum; it lies in the cavity), Reynolds cavitation; a smooth
steel journal (210 GPa, 0.3) in a rough polymer bush (3 GPa, 0.4), sigma = 1 um, eta_s beta
sigma = 0.05, sigma/beta = 0.005, mu_b = 0.1."""
import dataclasses

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax

from float32 import run_in_float32

R, C, ETA = 25.05e-3, 50e-6, 0.03
W = 2000.0 / (2 * R)                      # N/m
ROUGH = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
OPT = vjax.JournalOptions(n=64)
LINER = vjax.liner(vjax.Material.sls(1.5e9, 3e9, 0.01, 0.4), 2e-3)     # a 2 mm polymer liner (Pa, Pa, s)


def solve(omega, roughness=ROUGH, **kw):
    return vjax.journal_bearing(R, C, ETA, W, omega_shaft=omega, roughness=roughness, **{"options": OPT, **kw})


def test_smooth_limit_is_the_full_film():
    """sigma -> 0: the flow factors -> 1, the expected gap -> h, no asperity pressure: the smooth
    long bearing to 1e-8."""
    smooth = solve(30.0, roughness=None)
    tiny = solve(30.0, roughness=dataclasses.replace(ROUGH, sigma=1e-12))
    for name in ("eccentricity", "attitude_angle", "torque_shaft", "torque", "friction_coefficient",
                 "friction_viscous", "dissipation_fluid", "rupture_angle", "min_film"):
        a, b = float(getattr(tiny, name)), float(getattr(smooth, name))
        assert abs(a - b) <= 1e-8 * abs(b), (name, a, b)
    assert np.max(np.abs(tiny.pressure - smooth.pressure)) <= 1e-8 * float(np.max(smooth.pressure))
    assert float(tiny.asperity_share) == 0.0 and float(smooth.asperity_share) == 0.0
    assert float(smooth.friction_boundary) == 0.0 and float(smooth.film_parameter) == np.inf
    # the smooth friction coefficient is the journal's shear torque over R_J, over the load
    assert float(smooth.friction_coefficient) == pytest.approx(-float(smooth.torque_shaft) / (R - C) / W, rel=1e-12)


def wrap_factor(r):
    """int p_a ds / |int p_a n ds| on the grid, from the returned asperity pressure."""
    theta, p_a = np.asarray(r.theta), np.asarray(r.asperity_pressure)
    return np.sum(p_a) / np.hypot(np.sum(p_a * np.cos(theta)), np.sum(p_a * np.sin(theta)))


def test_boundary_limit_is_dry_sliding_with_the_wrap_factor():
    """omega -> 0: the asperities carry the load and the friction coefficient tends to mu_b times
    the contact arc's wrap factor (from the returned asperity pressure map); the asperity force
    balances the load alone, the journal past the clearance."""
    r = solve(1e-4)
    assert r.converged and float(r.asperity_share) > 0.999
    wrap = wrap_factor(r)
    assert 1.0 < wrap < 1.02
    assert float(r.friction_coefficient) == pytest.approx(float(ROUGH.mu_b) * wrap, rel=2e-3)
    assert float(r.friction_boundary) / W == pytest.approx(float(ROUGH.mu_b) * wrap * float(r.asperity_share),
                                                           rel=1e-12)
    np.testing.assert_allclose(np.asarray(r.asperity_force), [0.0, -W], atol=2e-3 * W)
    np.testing.assert_allclose(np.asarray(r.force), [0.0, -W], atol=1e-8 * W)
    assert float(r.eccentricity) > 1.0 and float(r.film_parameter) < 0
    assert abs(float(r.attitude_angle)) < 1e-3


# ---- an independent peer: the same 1D model written with numpy from the equations, the
# roughness functions from tests/mixed_peer.py (numpy and scipy), solved at vjax's position
def _peer(eps, attitude, omega, n, sigma=1e-6):
    """Film pressure (Pa), asperity pressure (Pa), force of both on the journal (N/m, line-of-
    centres axes) and friction coefficient of the rigid rough long bearing with the journal at
    eccentricity ratio eps (grid theta_i = 2 pi i / n from the line of centres, h = c (1 - eps cos
    theta)), turning at omega (only the journal), a groove at the cell nearest theta = pi at 0 Pa.
    Finite volumes: face film the mean of its cells, flux -phi_x(H_c) h_c^3/(12 eta) dp/ds +
    v (h_T + Vr sigma Phi_s(H_c)), H_c = max(h/sigma, 0.5), v = omega R_J / 2; Reynolds
    conditions by an active set with the rupture located within its cell (the outflow
    W (1 - beta)_+^2 / 2 of the cell holding it, beta from sqrt p, as tests/mixed_peer.py)."""
    import mixed_peer as mp
    RJ = R - C
    dth = 2 * np.pi / n
    theta = dth * np.arange(n)
    h = C * (1 - eps * np.cos(theta))
    hf = 0.5 * (h + np.roll(h, -1))
    Hc = np.maximum(hf / sigma, mp.CLIP)
    g = mp.phi_x(Hc) * (sigma * Hc) ** 3 / (12 * ETA) / (R * dth)      # face conductances
    v = 0.5 * omega * RJ
    cf = v * (sigma * mp.expected_gap(hf / sigma) + mp.VR * sigma * mp.Phi_s(Hc))
    # net outflow of cell i: A p + b, q_i = g_i (p_i - p_{i+1}) + cf_i through face i + 1/2
    A = np.zeros((n, n))
    for i in range(n):
        A[i, i] += g[i] + g[i - 1]
        A[i, (i + 1) % n] -= g[i]
        A[i, i - 1] -= g[i - 1]
    b = cf - np.roll(cf, 1)
    groove = int(round(np.pi / dth)) % n
    Wp = np.maximum(b, 0.0)
    up = np.roll(np.arange(n), 1)

    def share(p):          # the rupture's outflow and its derivatives in p_i and p_{i-1}
        s = np.sqrt(np.maximum(p, 0.0))
        su = s[up]
        falling = su > s
        d = np.where(falling, su - s, 1.0)
        f = np.where(falling, np.maximum((su - 2 * s) / d, 0.0), 0.0)
        ds = np.where(f > 0, -su / d**2, 0.0) * 0.5 / np.maximum(s, 1e-300) * (p > 0)
        dsu = np.where(f > 0, s / d**2, 0.0) * 0.5 / np.maximum(su, 1e-300) * (su > 0)
        return Wp * f**2 / 2, Wp * f * ds, Wp * f * dsu

    active = np.ones(n, bool)
    active[groove] = False
    scale = np.max(np.abs(b))
    for _ in range(200):
        S = np.flatnonzero(active)
        p = np.zeros(n)
        p[S] = np.linalg.solve(A[np.ix_(S, S)], -b[S])
        for _ in range(50):            # Newton with the rupture's share on the active cells
            sh, dself, dup = share(p)
            r = (A @ p + b - sh)[S]
            if np.max(np.abs(r)) <= 1e-13 * scale:
                break
            J = A - np.diag(dself)
            J[np.arange(n), up] -= dup
            dp = np.linalg.solve(J[np.ix_(S, S)], r)
            for t in 0.5 ** np.arange(40):
                q = p.copy()
                q[S] -= t * dp
                if np.max(np.abs((A @ q + b - share(q)[0])[S])) < np.max(np.abs(r)):
                    break
            p = q
        outflow = A @ p + b - share(p)[0]
        new = (active & (p > 0)) | (~active & (outflow < 0))
        new[groove] = False
        if np.array_equal(new, active):
            break
        active = new
    else:
        raise RuntimeError("the peer's active set did not settle")
    p_a = mp.K_GT * mp.E_PRIME * mp.F52(h / sigma)
    F = -R * dth * np.array([np.sum((p + p_a) * np.cos(theta)), np.sum((p + p_a) * np.sin(theta))])
    dpds = (np.roll(p, -1) - p) / (R * dth)
    hc = sigma * Hc
    tau = ETA * omega * RJ / hc * (mp.phi_f(Hc) - mp.VR * mp.Phi_fs(Hc)) + mp.phi_fp(Hc) * 0.5 * hc * dpds
    friction = R * dth * (np.sum(tau) + mp.MU_B * np.sum(p_a))
    return p, p_a, F, friction / np.hypot(*F)


@pytest.mark.parametrize("omega", [30.0, 1.0, 0.03])
def test_against_an_independent_peer(omega):
    """At vjax's converged position, the peer's film and asperities carry the load (magnitude
    and direction, to 1e-8 W), with the same pressure and asperity pressure and the same friction
    coefficient: full film (30 rad/s), mixed (1 rad/s, ~6 % asperity share) and nearly boundary
    (0.03 rad/s, ~90 %)."""
    r = solve(omega)
    n = OPT.n
    p, p_a, F, mu = _peer(float(r.eccentricity), float(r.attitude_angle), omega, n)
    phi = float(r.attitude_angle)
    # the load on the journal points at -attitude from the line of centres: the film and the
    # asperities push back
    np.testing.assert_allclose(F, W * np.array([-np.cos(phi), np.sin(phi)]), atol=1e-8 * W)
    scale = max(np.max(p), np.max(p_a))
    assert np.max(np.abs(np.asarray(r.pressure) - p)) <= 1e-8 * scale
    assert np.max(np.abs(np.asarray(r.asperity_pressure) - p_a)) <= 1e-10 * scale
    assert float(r.friction_coefficient) == pytest.approx(mu, rel=1e-8)


@pytest.mark.slow
def test_finite_bearing_tends_to_the_long_one():
    """A finite rough rigid bearing carrying the same load per unit length (no groove, ambient
    ends) approaches the long one as L/D grows from 1 to 8, in the mixed regime (1 rad/s, ~6 %
    asperity share): the differences in eccentricity, asperity share and friction coefficient
    shrink at every step (measured: share 0.018 -> 0.0039, friction coefficient 28 % -> 6 %). The
    same 128 cells round both films: the asperities' narrow contact needs them (on 32 the contact
    spans three cells and the difference jumps with where the minimum film falls between nodes)."""
    speed, n = 1.0, 128
    long = solve(speed, options=vjax.JournalOptions(n=n))
    errors = []
    for L_over_D in (1.0, 2.0, 4.0, 8.0):
        L = L_over_D * 2 * R
        fin = vjax.journal_bearing(R, C, ETA, W * L, omega_shaft=speed, length=L, supply_angle=None,
                                   roughness=ROUGH, options=vjax.FiniteJournalOptions(n=n, m=16, spacing="cosine"))
        errors.append([abs(float(fin.eccentricity) - float(long.eccentricity)) / float(long.eccentricity),
                       abs(float(fin.asperity_share) - float(long.asperity_share)),
                       abs(float(fin.friction_coefficient) - float(long.friction_coefficient))
                       / float(long.friction_coefficient)])
    errors = np.array(errors)
    assert np.all(np.diff(errors, axis=0) < 0), errors
    assert np.all(errors[-1] < 0.3 * errors[0]), errors


# ---- derivatives through the mixed regime, against central differences
def _check_derivatives(fn, x, steps, rtol=1e-6):
    J = jax.jacfwd(fn, argnums=tuple(range(len(x))))(*x)
    for k, step in enumerate(steps):
        up, down = list(x), list(x)
        up[k] += step
        down[k] -= step
        fd = (np.asarray(fn(*up)) - np.asarray(fn(*down))) / (2 * step)
        np.testing.assert_allclose(np.asarray(J[k]), fd, rtol=rtol, atol=1e-9 * np.max(np.abs(fd)))


@pytest.mark.slow
def test_derivatives_in_the_mixed_regime_rigid():
    """d(friction coefficient, eccentricity, asperity share) with respect to sigma, mu_b, the
    speed and the viscosity, implicit, against central differences, where the asperities carry
    ~6 % of the load."""
    opt = dataclasses.replace(OPT, tol=1e-12)
    start = solve(1.0, options=opt)
    assert 0.01 < float(start.asperity_share) < 0.2

    def outputs(sigma, mu_b, omega, eta):
        r = vjax.journal_bearing(R, C, eta, W, omega_shaft=omega, initial=start, options=opt,
                                 roughness=dataclasses.replace(ROUGH, sigma=sigma, mu_b=mu_b))
        return jnp.stack([r.friction_coefficient, r.eccentricity, r.asperity_share])

    _check_derivatives(outputs, (1e-6, 0.1, 1.0, ETA), (1e-10, 1e-5, 1e-4, 3e-6))


@pytest.mark.slow
def test_derivatives_in_the_mixed_regime_lined():
    """With a polymer liner (the asperity pressure an unknown per cell): d(friction coefficient,
    eccentricity, asperity share) with respect to sigma, mu_b, the speed and the liner's modulus,
    against central differences."""
    opt = dataclasses.replace(OPT, tol=1e-12)
    start = solve(0.3, options=opt, housing=LINER)
    assert 0.05 < float(start.asperity_share) < 0.9

    def outputs(sigma, mu_b, omega, E):
        liner = vjax.liner(vjax.Material.sls(E, 3e9, 0.01, 0.4), 2e-3)
        r = vjax.journal_bearing(R, C, ETA, W, omega_shaft=omega, initial=start, options=opt, housing=liner,
                                 roughness=dataclasses.replace(ROUGH, sigma=sigma, mu_b=mu_b))
        return jnp.stack([r.friction_coefficient, r.eccentricity, r.asperity_share])

    _check_derivatives(outputs, (1e-6, 0.1, 0.3, 1.5e9), (1e-10, 1e-5, 1e-4, 1e6))


@pytest.mark.slow
def test_mixed_stiffness_is_the_static_stiffness():
    """K at zero whirl, with the asperities' stiffness, equals the inverse of d(journal
    position)/d(load vector) of the steady solves (the groove turning with the line of centres,
    as the load turns); a groove fixed in the bearing (at the load's direction) is checked on the
    load's magnitude alone: d position / d W_y = K^-1 e_y."""
    speed = 0.3
    for groove in ("line_of_centres", "fixed"):
        start = solve(speed, groove=groove)
        assert 0.1 < float(start.asperity_share) < 0.9
        co = vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=speed, roughness=ROUGH, initial=start,
                                       options=OPT, groove=groove)

        def position(load):
            r = vjax.journal_bearing(R, C, ETA, load, omega_shaft=speed, roughness=ROUGH, initial=start, options=OPT,
                                     groove=groove)
            g = r.line_of_centres_angle
            return r.eccentricity * C * jnp.stack([jnp.cos(g), jnp.sin(g)])

        compliance = np.asarray(jax.jacfwd(position)(jnp.array([0.0, -W])))
        K = np.asarray(co.stiffness[0])
        if groove == "line_of_centres":
            np.testing.assert_allclose(K, np.linalg.inv(compliance), rtol=1e-6)
        else:
            np.testing.assert_allclose(np.linalg.inv(K)[:, 1], compliance[:, 1], rtol=1e-6)
        # the asperities add stiffness only: the damping is the film's, finite
        assert np.all(np.isfinite(np.asarray(co.damping)))


def test_stribeck_sweep_of_the_long_bearing():
    """stribeck_curve with length=None: every point converges, the asperity share falls with
    speed from ~1 to 0, the friction coefficient tends to mu_b times the wrap factor at the lowest
    speed and has its minimum inside the sweep, above the lift-off speed; Hersey numbers per unit
    length (p_mean = W / D)."""
    curve = vjax.stribeck_curve(R, C, ETA, W, np.logspace(-3, 2, 11), roughness=ROUGH, options=OPT)
    assert curve.converged.all(), curve.result
    assert curve.asperity_share[0] > 0.99 and curve.asperity_share[-1] < 1e-6
    assert np.all(np.diff(curve.asperity_share) <= 1e-9)
    assert curve.speed[0] < curve.lift_off_speed < curve.minimum_speed < curve.speed[-1]
    low = curve.results[0]
    assert curve.friction_coefficient[0] == pytest.approx(
        float(ROUGH.mu_b) * wrap_factor(low) * float(low.asperity_share), rel=0.01)
    np.testing.assert_allclose(curve.hersey, ETA * curve.speed / (W / (2 * R)), rtol=1e-12)


@pytest.mark.slow
def test_a_lined_bearing_across_the_stribeck_range():
    """A 2 mm polymer liner: with sigma -> 0 the lined mixed bearing is the lined smooth one (to
    1e-8); from full film down to a barely turning journal every point converges, the forces
    balance the load, the asperity pressure loads the liner (it yields by more than sigma) and
    spreads the contact wider than on a rigid bore."""
    opt = OPT
    smooth = solve(30.0, roughness=None, housing=LINER, options=opt)
    tiny = solve(30.0, roughness=dataclasses.replace(ROUGH, sigma=1e-12), housing=LINER, options=opt)
    for name in ("eccentricity", "attitude_angle", "torque_shaft", "friction_coefficient"):
        a, b = float(getattr(tiny, name)), float(getattr(smooth, name))
        assert abs(a - b) <= 1e-8 * abs(b), (name, a, b)
    curve = vjax.stribeck_curve(R, C, ETA, W, np.logspace(-3, 2, 11), roughness=ROUGH, options=opt, housing=LINER)
    assert curve.converged.all(), curve.result
    assert curve.asperity_share[0] > 0.98 and curve.asperity_share[-1] < 1e-6
    slow = curve.results[0]
    np.testing.assert_allclose(np.asarray(slow.force), [0.0, -W], atol=1e-8 * W)
    assert float(np.max(slow.displacement)) > float(ROUGH.sigma)
    rigid = solve(1e-3, options=opt)
    arc = lambda r: np.mean(np.asarray(r.asperity_pressure) > 1e-3 * float(np.max(r.asperity_pressure)))  # noqa: E731
    assert arc(slow) > arc(rigid)        # n = 64: 9 cells against 7


def test_roughness_refusals_of_the_long_bearing():
    with pytest.raises(ValueError, match="linear_solver='krylov'"):
        solve(1.0, housing=LINER, options=vjax.JournalOptions(n=64, linear_solver="krylov"))
    with pytest.raises(ValueError, match="dynamic coefficients of a mixed film on a deformable body"):
        vjax.journal_coefficients(R, C, ETA, W, 0.0, omega_shaft=30.0, roughness=ROUGH, housing=LINER, options=OPT)
    with pytest.raises(ValueError, match="roughness"):
        solve(1.0, roughness="rough")
    with pytest.raises(ValueError, match="cavitation='jfo'"):
        solve(1.0, cavitation="jfo")


@pytest.mark.slow
def test_float32_runs_without_nan():
    """In float32 the rough long bearing, rigid and lined, converges (to the looser default
    tolerance) from mixed film to nearly boundary, and nothing is NaN or inf (a fresh interpreter
    without x64)."""
    run_in_float32("""
        import vjax
        rough = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
        liner = vjax.liner(vjax.Material.sls(1.5e9, 3e9, 0.01, 0.4), 2e-3)
        for w, kw in ((1.0, {}), (0.01, {}), (0.3, dict(housing=liner))):
            check(vjax.journal_bearing(25.05e-3, 50e-6, 0.03, 39920.0, omega_shaft=w, roughness=rough,
                                       options=vjax.JournalOptions(n=32), throw=False, **kw))
        print("ok")
    """)


def test_a_closing_smooth_film_says_a_roughness_would_carry_it():
    """Without a roughness the rigid long bearing's thin-film failure names the film it would
    need and the roughness that would carry the load; with one the same bearing converges."""
    message = r"journal_bearing did not converge.* A film of ~9\.4e-05 c.*roughness=vjax\.Roughness"
    with pytest.raises(vjax.ConvergenceError, match=message):
        solve(0.01, roughness=None)
    assert solve(0.01).converged


@pytest.mark.slow
def test_dry_limit_against_the_pin_contact():
    """The lined long bearing barely turning is dry contact of the journal in its bore, per unit
    length: against the pin-in-hole contact solver (smooth surfaces, another solver) on the same
    geometry, liner and load, the journal sits where the pin does to within half a sigma (measured
    0.09 sigma); the asperity layer's own compliance spreads the contact wider and lowers its
    peak (measured 11 %)."""
    r = solve(1e-4, housing=LINER)
    pin = vjax.pin_in_hole(LINER, R, C, W, omega_shaft=1e-6, load_angle=-np.pi / 2, options=vjax.PinOptions(n=OPT.n))
    assert float(r.asperity_share) > 0.998 and pin.converged
    p_a, contact = np.asarray(r.asperity_pressure), np.asarray(pin.pressure)
    assert abs(float(r.eccentricity) - float(pin.pin_offset) / C) * C < 0.5 * float(ROUGH.sigma)
    assert 0.8 < p_a.max() / contact.max() < 0.95
    assert np.sum(p_a > 0.01 * p_a.max()) > np.sum(contact > 0.01 * contact.max())
