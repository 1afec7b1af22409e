"""Tests of the journal bearing scene (vjax.journal_bearing, thesis Chapter 3).

Rigid limit: the classical infinitely long bearing. Closed forms (full and half
Sommerfeld) are those of e.g. Hamrock, Schmid & Jacobson, "Fundamentals of Fluid Film
Lubrication" (2004), ch. 10, or Szeri, "Fluid Film Lubrication" (2011), ch. 3, with
U = sum of the surface speeds:

    full:  W = 12 pi eta U R^2 eps / (c^2 (2 + eps^2) sqrt(1 - eps^2)),  attitude pi/2,
           journal friction torque 4 pi eta U R^2 (1 + 2 eps^2) / (c (2 + eps^2) sqrt(1 - eps^2))
    half:  W = 6 eta U R^2 eps sqrt(pi^2 (1 - eps^2) + 4 eps^2) / (c^2 (2 + eps^2)(1 - eps^2)),
           tan(attitude) = pi sqrt(1 - eps^2) / (2 eps).

Reynolds (Swift-Stieber) conditions have no closed form: the reference is an independent
semi-analytical solution (the film flux q = v h(theta_2) fixed by the rupture point,
p(theta) = 12 eta R v int (h - h_2)/h^3 from the groove, theta_2 the root of p(theta_2) = 0,
by scipy quadrature and brentq), the classical construction of Pinkus & Sternlicht,
"Theory of Hydrodynamic Lubrication" (1961), ch. 3.
"""
import dataclasses

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy import integrate, optimize

import vjax
from vjax.journal import journal_bearing

# A rigid bearing: R = 50 mm, c = 50 um, eta = 0.01 Pa s, journal at 100 rad/s.
R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
V = 0.5 * WJ * (R - C)  # entrainment speed
U = 2 * V

# The thesis case (DESIGN.md section 4).
RB, CB, ETAB, E0 = 0.1, 5e-4, 1e-3, 1e6
SLS = vjax.Material.sls(E0, 1e8, 1.0, 0.5)
LOAD = 2.2e-3 * E0 * RB


def full_sommerfeld_load(eps):
    return 12 * np.pi * ETA * U * R**2 * eps / (C**2 * (2 + eps**2) * np.sqrt(1 - eps**2))


def half_sommerfeld(eps):
    W = (6 * ETA * U * R**2 * eps * np.sqrt(np.pi**2 * (1 - eps**2) + 4 * eps**2)
         / (C**2 * (2 + eps**2) * (1 - eps**2)))
    return W, np.arctan(np.pi * np.sqrt(1 - eps**2) / (2 * eps))


def reynolds_reference(eps):
    """Load, attitude and rupture angle with Reynolds conditions, groove at theta = pi."""
    def h(t):
        return C * (1 - eps * np.cos(t))

    def p(t, t2):
        h2 = h(t2)
        return 12 * ETA * R * V * integrate.quad(lambda s: (h(s) - h2) / h(s) ** 3, -np.pi, t,
                                                 epsabs=0, epsrel=1e-12, limit=200)[0]

    t2 = optimize.brentq(lambda t2: p(t2, t2), 1e-6, np.pi - 1e-6, xtol=1e-14)
    Fx = -R * integrate.quad(lambda t: p(t, t2) * np.cos(t), -np.pi, t2, epsrel=1e-11, limit=200)[0]
    Fy = -R * integrate.quad(lambda t: p(t, t2) * np.sin(t), -np.pi, t2, epsrel=1e-11, limit=200)[0]
    return np.hypot(Fx, Fy), np.arctan2(Fy, -Fx), t2


@pytest.fixture(scope="module")
def reynolds_refs():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # quad's roundoff notes near the 1e-12 target
        return {eps: reynolds_reference(eps) for eps in (0.3, 0.6, 0.8)}


def order(ns, errs):
    """Observed convergence order: least-squares slope of log err vs log n."""
    return -np.polyfit(np.log(ns), np.log(np.abs(errs)), 1)[0]


# ---------------------------------------------------------------- rigid limit


@pytest.mark.parametrize("eps", [0.3, 0.6, 0.8])
def test_full_sommerfeld_closed_form(eps):
    sol = journal_bearing(R, C, ETA, WJ, load=full_sommerfeld_load(eps), n=128, cavitation="sommerfeld")
    assert bool(sol.converged)
    assert abs(float(sol.eccentricity) - eps) < 3e-4
    assert abs(float(sol.attitude_angle) - np.pi / 2) < 1e-10   # exactly 90 degrees
    # friction torque on the journal (the closed form's lever arm is R, ours R_J)
    T = 4 * np.pi * ETA * U * R**2 * (1 + 2 * eps**2) / (C * (2 + eps**2) * np.sqrt(1 - eps**2))
    assert float(sol.torque_journal) * R / (R - C) == pytest.approx(-T, rel=3e-4)


@pytest.mark.parametrize("eps", [0.3, 0.6, 0.8])
def test_half_sommerfeld_closed_form(eps):
    W, phi = half_sommerfeld(eps)
    sol = journal_bearing(R, C, ETA, WJ, load=W, n=128, cavitation="half_sommerfeld")
    assert bool(sol.converged)
    assert abs(float(sol.eccentricity) - eps) < 5e-4
    assert abs(float(sol.attitude_angle) - phi) < 5e-4
    # p changes sign at the minimum film; estimated by extrapolation: O(dtheta^2)
    assert abs(float(sol.rupture_angle)) < (2 * np.pi / 128) ** 2
    assert float(jnp.min(sol.pressure)) >= 0.0


def test_sommerfeld_second_order():
    # (the half-Sommerfeld solve is the same linear system, clipped afterwards)
    ns = np.array([32, 64, 128])
    errs = [float(journal_bearing(R, C, ETA, WJ, load=full_sommerfeld_load(0.6), n=int(n),
                                  cavitation="sommerfeld").eccentricity) - 0.6 for n in ns]
    assert order(ns, errs) == pytest.approx(2.0, abs=0.1)


def test_reynolds_conditions_vs_reference(reynolds_refs):
    n = 256
    for eps, (W, phi, t2) in reynolds_refs.items():
        sol = journal_bearing(R, C, ETA, WJ, load=W, n=n)
        assert bool(sol.converged)
        assert abs(float(sol.eccentricity) - eps) < 1e-4
        assert abs(float(sol.attitude_angle) - phi) < 1e-4
        assert abs(float(sol.rupture_angle) - t2) < 1.5 * 2 * np.pi / n
        p = np.asarray(sol.pressure)
        assert p.min() > -1e-8 * p.max()    # p >= 0 (complementarity)
        if eps == 0.6:  # rotating the journal the other way mirrors the solution
            mirror = journal_bearing(R, C, ETA, -WJ, load=W, n=n)
            assert float(mirror.attitude_angle) == pytest.approx(-float(sol.attitude_angle), abs=1e-9)


def test_reynolds_grid_convergence(reynolds_refs):
    W, phi, _ = reynolds_refs[0.3]
    ns = np.array([64, 128, 256])
    errs = [float(journal_bearing(R, C, ETA, WJ, load=W, n=int(n)).eccentricity) - 0.3 for n in ns]
    # the free boundary snaps to the grid, so the error is not monotone; the fit is ~2
    assert order(ns, errs) > 1.7
    assert abs(errs[-1]) < 2e-5


def test_supply_pressure_datum_and_power_balance():
    W = 3e5
    ps = 0.02 * W / (2 * R)
    sol = journal_bearing(R, C, ETA, WJ, load=W, n=128, supply_pressure=ps)
    assert bool(sol.converged)
    assert float(sol.pressure[64]) == pytest.approx(ps, rel=1e-12)    # groove at theta = pi
    # rigid bodies: journal motor + supply pump = fluid dissipation (exact discretely)
    power_in = -WJ * float(sol.torque_journal) + ps * float(sol.supply_flow)
    assert power_in == pytest.approx(float(sol.dissipation_fluid), rel=1e-9)


# ---------------------------------------------------------------- (visco)elastic


@pytest.fixture(scope="module")
def ss():
    """Soft-on-soft thesis case (Fig. 3.5 SS), periodic memory."""
    return journal_bearing(RB, CB, ETAB, omega_journal=-0.4, omega_bearing=0.2, load=LOAD,
                           n=128, bearing=SLS, journal=SLS)


def test_force_balance_and_hersey(ss):
    assert bool(ss.converged) and int(ss.iterations) > 0
    np.testing.assert_allclose(np.asarray(ss.force), [0.0, LOAD], atol=1e-9 * LOAD)
    assert float(ss.hersey) == pytest.approx(-4.5e-9, rel=0.01)   # thesis: H = -4.5e-9
    assert float(ss.min_film) > 0 and float(ss.eccentricity_effective) > 0


def test_dissipation_nonnegative_and_mode_by_mode(ss):
    n = 128
    for D, kind, Rr, omega in ((ss.dissipation_bearing, "hole", RB, 0.2),
                               (ss.dissipation_journal, "cylinder", RB - CB, -0.4)):
        assert float(D) > 0
        # D = -Omega R int p u' dtheta with Omega = -omega the pattern speed: by Parseval,
        # D = Omega R (2 pi / n^2) sum_k w_k k Im(S_k) |P_k|^2 (loss part of the compliance)
        S = vjax.ring_operator(kind, SLS, Rr, n, omega=-omega).symbol
        P = jnp.fft.rfft(ss.pressure)
        k = jnp.arange(n // 2 + 1)
        w = jnp.where((k == 0) | (k == n // 2), 1.0, 2.0)
        D_modes = -omega * RB * 2 * np.pi / n**2 * jnp.sum(w * k * S.imag * jnp.abs(P) ** 2)
        assert float(D) == pytest.approx(float(D_modes), rel=2e-2)
    # the viscoelastic torques resist each body's rotation
    assert float(ss.torque_viscoelastic) * 0.2 < 0
    assert float(ss.torque_viscoelastic_journal) * -0.4 < 0


def test_torque_identities(ss):
    # power balance (exact for the discrete equations): motors = fluid + hysteresis
    power_in = -0.2 * float(ss.torque_bearing) - (-0.4) * float(ss.torque_journal)
    dissipated = float(ss.dissipation_fluid + ss.dissipation_bearing + ss.dissipation_journal)
    assert power_in == pytest.approx(dissipated, rel=1e-9)
    # fluid moment balance about O: C_B + C_J(O) = 0 up to the thin-film O(c/R) terms
    assert abs(float(ss.torque_bearing + ss.torque_journal_about_O)) < 2 * CB / RB * abs(float(ss.torque_bearing))
    # C_J(O) = C_J(O') + e x F
    e = float(ss.eccentricity) * CB
    Fy_loc = -RB * 2 * np.pi / 128 * float(jnp.sum(ss.pressure * jnp.sin(ss.theta)))
    assert float(ss.torque_journal_about_O) == pytest.approx(float(ss.torque_journal) + e * Fy_loc, rel=1e-12)


def test_elastic_limits_have_no_hysteresis():
    # elastic bearing (E = E0): no dissipation in the solid, symmetric physics
    sol = journal_bearing(RB, CB, ETAB, -0.4, 0.2, load=LOAD, n=64, bearing=vjax.Material.elastic(E0, 0.5))
    assert abs(float(sol.dissipation_bearing)) < 1e-12 * float(sol.dissipation_fluid)
    # Fig. 3.4: the half-plane kernel with a 1 m reference length gives a thinner film
    hp = journal_bearing(RB, CB, ETAB, -0.4, 0.2, load=LOAD, n=64, green="half_plane",
                         bearing=vjax.Material.elastic(E0, 0.5))
    assert float(hp.min_film) < 0.9 * float(sol.min_film)


# ---------------------------------------------------------------- gradients


def _hs(params):
    eta, c, load, e0 = params
    mat = vjax.Material.sls(e0, 1e8, 1.0, 0.5)
    s = journal_bearing(RB, c, eta, -0.4, 0.2, load=load, n=64, bearing=mat, throw=False)
    return jnp.stack([s.torque_bearing, s.eccentricity, s.torque_journal])


def test_gradients_vs_finite_differences():
    x0 = np.array([ETAB, CB, LOAD, E0])
    jac = np.asarray(jax.jacrev(_hs)(jnp.asarray(x0)))
    assert np.all(np.isfinite(jac))
    f = jax.jit(_hs)
    for i in range(4):
        h = 1e-5 * x0[i]
        fd = (np.asarray(f(jnp.asarray(x0).at[i].add(h))) - np.asarray(f(jnp.asarray(x0).at[i].add(-h)))) / (2 * h)
        np.testing.assert_allclose(jac[:, i], fd, rtol=2e-4, atol=1e-9 * np.abs(fd).max())


# ---------------------------------------------------------------- solver behaviour


def test_stiff_regime_converges_by_continuation():
    # thesis geometry, elastic liner, 100x lower speeds: film ~ 1e-3 of the deformation
    sol = journal_bearing(RB, CB, ETAB, -0.004, 0.002, load=LOAD, n=128,
                          bearing=vjax.Material.elastic(E0, 0.5))
    ratio = float(sol.min_film) / float(jnp.ptp(sol.displacement_bearing))
    assert bool(sol.converged)
    assert ratio < 3e-3
    assert int(sol.stages) > 0 and int(sol.iterations) > 0
    print(f"stiff case: h_min/ptp(u) = {ratio:.2e}, {int(sol.iterations)} Newton steps, "
          f"{int(sol.stages)} continuation stages")


def test_failure_is_reported_not_nan_and_auto_recovers():
    # a concentric start with a soft liner: plain Newton fails (and says so); "auto"
    # notices and continues from a rigid solution at a higher speed
    el = vjax.Material.elastic(E0, 0.5)
    ref = journal_bearing(RB, CB, ETAB, -0.4, 0.2, load=LOAD, n=64, bearing=el)
    concentric = dataclasses.replace(ref, pressure=jnp.full(64, 0.1 * LOAD / (2 * np.pi * RB)),
                                     eccentricity=jnp.asarray(0.0), attitude_angle=jnp.asarray(0.0))
    kw = dict(load=LOAD, n=64, bearing=el, initial=concentric)
    with pytest.raises(RuntimeError, match="iterations"):
        journal_bearing(RB, CB, ETAB, -0.4, 0.2, solver="newton", **kw)
    sol = jax.jit(lambda eta: journal_bearing(RB, CB, eta, -0.4, 0.2, throw=False, solver="newton", **kw))(ETAB)
    assert not bool(sol.converged)
    assert int(sol.iterations) >= 1
    for leaf in jax.tree_util.tree_leaves(sol):
        assert np.all(np.isfinite(np.asarray(leaf, dtype=float)))
    with pytest.raises(RuntimeError):
        sol.check()
    auto = journal_bearing(RB, CB, ETAB, -0.4, 0.2, **kw)
    assert bool(auto.converged) and int(auto.stages) > 0
    assert float(auto.eccentricity) == pytest.approx(float(ref.eccentricity), abs=1e-8)


def test_jit_vmap_and_warm_start():
    etas = jnp.array([0.01, 0.02, 0.04])
    f = jax.vmap(lambda eta: journal_bearing(R, C, eta, WJ, load=4e5, n=64, throw=False).eccentricity)
    eps = np.asarray(f(etas))
    assert np.all(np.diff(eps) < 0)     # more viscous, less eccentric
    s0 = journal_bearing(R, C, 0.02, WJ, load=4e5, n=64)
    assert float(s0.eccentricity) == pytest.approx(eps[1], abs=1e-10)
    s1 = journal_bearing(R, C, 0.02, WJ, load=4e5, n=64, initial=s0)
    assert int(s1.iterations) <= 1


@pytest.mark.parametrize("kwargs, name", [
    (dict(clearance=0.2), "clearance"),
    (dict(viscosity=-1.0), "viscosity"),
    (dict(n=63), "n"),
    (dict(cavitation="jfo"), "cavitation"),
    (dict(green="flat"), "green"),
    (dict(load=[0.0, 0.0]), "load"),
    (dict(omega_journal=0.0), "entrainment"),
    (dict(memory="forever"), "memory"),
    (dict(bearing="steel"), "bearing"),
    (dict(supply_pressure=-1.0), "supply_pressure"),
])
def test_argument_validation(kwargs, name):
    args = dict(R_bearing=R, clearance=C, viscosity=ETA, omega_journal=WJ, load=1e5)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        journal_bearing(**args)


def test_float32_runs_without_nan():
    """vjax does not force float64: in float32 the solves converge to the looser default
    tolerance (1e-4) and nothing is NaN (run in a fresh interpreter without x64)."""
    import subprocess
    import sys
    import textwrap
    code = textwrap.dedent("""
        import warnings; warnings.simplefilter("ignore")
        import jax, numpy as np, vjax
        m = vjax.Material.sls(1e6, 1e8, 1.0, 0.5)
        for args, kw in (((0.05, 5e-5, 0.01, 100.0), dict(load=2e5)),
                         ((0.1, 5e-4, 1e-3, -0.4, 0.2), dict(load=220.0, bearing=m))):
            s = vjax.journal_bearing(*args, n=32, throw=False, **kw)
            leaves = [np.asarray(l, dtype=float) for l in jax.tree_util.tree_leaves(s)]
            assert s.pressure.dtype == np.float32, s.pressure.dtype
            assert bool(s.converged) and all(np.all(np.isfinite(l)) for l in leaves)
        print("ok")
    """)
    import os
    env = dict(os.environ, JAX_ENABLE_X64="0")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         cwd=str(__import__("pathlib").Path(__file__).resolve().parents[1]), timeout=300)
    assert out.returncode == 0 and "ok" in out.stdout, out.stderr[-2000:]
