"""Tests of the journal bearing scene (vjax.journal_bearing, thesis Chapter 3).

Rigid limit: the classical infinitely long bearing, :func:`vjax.reference.long_bearing`
(full and half Sommerfeld in closed form, Reynolds / Swift-Stieber conditions by quadrature;
each checked independently in tests/test_reference.py).
"""
import dataclasses

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import JournalOptions, journal_bearing, reference

from float32 import run_in_float32

# A rigid bearing: R = 50 mm, c = 50 um, eta = 0.01 Pa s, journal at 100 rad/s.
R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
V = 0.5 * WJ * (R - C)  # entrainment speed

# The thesis case (Fig. 3.5; docs/theory.md §11).
RB, CB, ETAB, E0 = 0.1, 5e-4, 1e-3, 1e6
SLS = vjax.Material.sls(E0, 1e8, 1.0, 0.5)
LOAD = 2.2e-3 * E0 * RB
THESIS_SPEEDS = dict(omega_shaft=-0.4, omega_housing=0.2)
OPT64, OPT128 = JournalOptions(n=64), JournalOptions(n=128)


def rigid(eps, conditions):
    return reference.long_bearing(eps, R, C, ETA, V, conditions)


@pytest.fixture(scope="module")
def reynolds_refs():
    return {eps: rigid(eps, "reynolds") for eps in (0.3, 0.6, 0.8)}


def order(ns, errs):
    """Observed convergence order: least-squares slope of log err vs log n."""
    return -np.polyfit(np.log(ns), np.log(np.abs(errs)), 1)[0]


# ---------------------------------------------------------------- rigid limit


@pytest.mark.parametrize("eps", [0.3, 0.6, 0.8])
def test_full_sommerfeld_closed_form(eps):
    sol = journal_bearing(R, C, ETA, rigid(eps, "sommerfeld")["load"], omega_shaft=WJ, cavitation="sommerfeld",
                          options=OPT128)
    assert bool(sol.converged)
    assert abs(float(sol.eccentricity) - eps) < 3e-4
    assert abs(float(sol.attitude_angle) - np.pi / 2) < 1e-10   # exactly 90 degrees
    # friction torque on the journal, 8 pi eta v R^2 (1 + 2 eps^2) / (c (2 + eps^2) sqrt(1 - eps^2))
    # (Hamrock, Schmid & Jacobson 2004, ch. 10; the closed form's lever arm is R, ours R_J)
    T = 8 * np.pi * ETA * V * R**2 * (1 + 2 * eps**2) / (C * (2 + eps**2) * np.sqrt(1 - eps**2))
    assert float(sol.torque_shaft) * R / (R - C) == pytest.approx(-T, rel=3e-4)


@pytest.mark.parametrize("eps", [0.3, 0.6, 0.8])
def test_half_sommerfeld_closed_form(eps):
    ref = rigid(eps, "half_sommerfeld")
    W, phi = float(ref["load"]), float(ref["attitude"])
    sol = journal_bearing(R, C, ETA, W, omega_shaft=WJ, cavitation="half_sommerfeld", options=OPT128)
    assert bool(sol.converged)
    assert abs(float(sol.eccentricity) - eps) < 5e-4
    assert abs(float(sol.attitude_angle) - phi) < 5e-4
    # p changes sign at the minimum film; estimated by extrapolation: O(dtheta^2)
    assert abs(float(sol.rupture_angle)) < (2 * np.pi / 128) ** 2
    assert float(jnp.min(sol.pressure)) >= 0.0


def test_sommerfeld_second_order():
    # (the half-Sommerfeld solve is the same linear system, clipped afterwards)
    ns = np.array([32, 64, 128])
    errs = [float(journal_bearing(R, C, ETA, rigid(0.6, "sommerfeld")["load"], omega_shaft=WJ, cavitation="sommerfeld",
                                  options=JournalOptions(n=int(n))).eccentricity) - 0.6 for n in ns]
    assert order(ns, errs) == pytest.approx(2.0, abs=0.1)


def test_reynolds_conditions_vs_reference(reynolds_refs):
    n = 256
    for eps, ref in reynolds_refs.items():
        W, phi, t2 = (float(ref[k]) for k in ("load", "attitude", "rupture"))
        sol = journal_bearing(R, C, ETA, W, omega_shaft=WJ, options=JournalOptions(n=n))
        assert bool(sol.converged)
        assert abs(float(sol.eccentricity) - eps) < 1e-4
        assert abs(float(sol.attitude_angle) - phi) < 1e-4
        assert abs(float(sol.rupture_angle) - t2) < 1.5 * 2 * np.pi / n
        p = np.asarray(sol.pressure)
        assert p.min() > -1e-8 * p.max()    # p >= 0 (complementarity)
        if eps == 0.6:  # rotating the journal the other way mirrors the solution
            mirror = journal_bearing(R, C, ETA, W, omega_shaft=-WJ, options=JournalOptions(n=n))
            assert float(mirror.attitude_angle) == pytest.approx(-float(sol.attitude_angle), abs=1e-9)


def test_reynolds_grid_convergence(reynolds_refs):
    W = float(reynolds_refs[0.3]["load"])
    ns = np.array([64, 128, 256])
    errs = [float(journal_bearing(R, C, ETA, W, omega_shaft=WJ, options=JournalOptions(n=int(n))).eccentricity) - 0.3
            for n in ns]
    # the free boundary snaps to the grid, so the error is not monotone; the fit is ~2
    assert order(ns, errs) > 1.7
    assert abs(errs[-1]) < 2e-5


def rupture_work(sol, R, eta, v):
    """Pressure energy of the flow that leaves the pressurized film within the cell holding
    its rupture (W/m): sum of p_i (q_out - q_in) over the cells but the groove's. Zero with the
    rupture on a face; within its cell the last pressurized cell lets W (1 - beta)^2 / 2 out
    (:func:`vjax.reynolds.rupture_outflow`)."""
    p = sol.pressure
    _, _, q = vjax.reynolds.face_fluxes(p, sol.film, R, eta, v)
    w = q - jnp.roll(q, 1)
    groove = jnp.argmax(jnp.abs(sol.theta - jnp.pi) < 1e-9)
    return float(jnp.sum(jnp.where(jnp.arange(p.shape[0]) == groove, 0.0, p * w)))


def test_supply_pressure_datum_and_power_balance():
    W = 3e5
    ps = 0.02 * W / (2 * R)
    sol = journal_bearing(R, C, ETA, W, omega_shaft=WJ, supply_pressure=ps, options=OPT128)
    assert bool(sol.converged)
    assert float(sol.pressure[64]) == pytest.approx(ps, rel=1e-12)    # groove at theta = pi
    # rigid bodies: journal motor + supply pump + the pressure energy of the flow let out
    # within the rupture's cell = fluid dissipation (exact discretely)
    power_in = -WJ * float(sol.torque_shaft) + ps * float(sol.supply_flow)
    work = rupture_work(sol, R, ETA, V)
    assert power_in + work == pytest.approx(float(sol.dissipation_fluid), rel=1e-12)
    assert 0 < work < 1e-6 * power_in


# ---------------------------------------------------------------- (visco)elastic


@pytest.fixture(scope="module")
def ss():
    """Soft-on-soft thesis case (Fig. 3.5 SS), periodic memory."""
    return journal_bearing(RB, CB, ETAB, LOAD, housing=SLS, shaft=SLS, **THESIS_SPEEDS, options=OPT128)


def test_force_balance_and_hersey(ss):
    assert bool(ss.converged) and int(ss.iterations) > 0
    # the film pushes the housing as the load pushes the shaft (load_angle -pi/2: downward)
    np.testing.assert_allclose(np.asarray(ss.force), [0.0, -LOAD], atol=1e-9 * LOAD)
    assert float(ss.hersey) == pytest.approx(-4.5e-9, rel=0.01)   # thesis: H = -4.5e-9
    assert float(ss.min_film) > 0 and float(ss.eccentricity_effective) > 0


def test_dissipation_nonnegative_and_mode_by_mode(ss):
    n = 128
    for D, kind, Rr, omega in ((ss.dissipation_housing, "hole", RB, 0.2),
                               (ss.dissipation_shaft, "cylinder", RB - CB, -0.4)):
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
    assert float(ss.torque_viscoelastic_shaft) * -0.4 < 0


def test_torque_identities(ss):
    # power balance (exact for the discrete equations): motors + the pressure energy let out
    # within the rupture's cell = fluid + hysteresis
    power_in = -0.2 * float(ss.torque) - (-0.4) * float(ss.torque_shaft)
    work = rupture_work(ss, RB, ETAB, 0.5 * (0.2 * RB - 0.4 * (RB - CB)))
    dissipated = float(ss.dissipation_fluid + ss.dissipation_housing + ss.dissipation_shaft)
    assert power_in + work == pytest.approx(dissipated, rel=1e-10)
    # fluid moment balance about O: C_B + C_J(O) = 0 up to the thin-film O(c/R) terms
    assert abs(float(ss.torque + ss.torque_shaft_about_O)) < 2 * CB / RB * abs(float(ss.torque))
    # C_J(O) = C_J(O') + e x F
    e = float(ss.eccentricity) * CB
    Fy_loc = -RB * 2 * np.pi / 128 * float(jnp.sum(ss.pressure * jnp.sin(ss.theta)))
    assert float(ss.torque_shaft_about_O) == pytest.approx(float(ss.torque_shaft) + e * Fy_loc, rel=1e-12)


def test_elastic_limits_have_no_hysteresis():
    # elastic bearing (E = E0): no dissipation in the solid, symmetric physics
    elastic = vjax.Material.elastic(E0, 0.5)
    sol = journal_bearing(RB, CB, ETAB, LOAD, housing=elastic, **THESIS_SPEEDS, options=OPT64)
    assert abs(float(sol.dissipation_housing)) < 1e-12 * float(sol.dissipation_fluid)
    # Fig. 3.4: the half-plane kernel with a 1 m reference length gives a thinner film
    hp = journal_bearing(RB, CB, ETAB, LOAD, housing=vjax.half_plane(elastic), **THESIS_SPEEDS, options=OPT64)
    assert float(hp.min_film) < 0.9 * float(sol.min_film)


# ---------------------------------------------------------------- gradients


def _hs(params):
    eta, c, load, e0 = params
    mat = vjax.Material.sls(e0, 1e8, 1.0, 0.5)
    s = journal_bearing(RB, c, eta, load, housing=mat, **THESIS_SPEEDS, options=OPT64, throw=False)
    return jnp.stack([s.torque, s.eccentricity, s.torque_shaft])


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
    sol = journal_bearing(RB, CB, ETAB, LOAD, housing=vjax.Material.elastic(E0, 0.5), omega_shaft=-0.004,
                          omega_housing=0.002, options=OPT128)
    ratio = float(sol.min_film) / float(jnp.ptp(sol.displacement))
    assert bool(sol.converged)
    assert ratio < 3e-3
    assert int(sol.stages) > 0 and int(sol.iterations) > 0
    print(f"stiff case: h_min/ptp(u) = {ratio:.2e}, {int(sol.iterations)} Newton steps, "
          f"{int(sol.stages)} continuation stages")


def test_failure_is_reported_not_nan_and_auto_recovers():
    # a concentric start with a soft liner: plain Newton fails (and says so); "auto"
    # notices and continues from a rigid solution at a higher speed
    el = vjax.Material.elastic(E0, 0.5)
    ref = journal_bearing(RB, CB, ETAB, LOAD, housing=el, **THESIS_SPEEDS, options=OPT64)
    concentric = dataclasses.replace(ref, pressure=jnp.full(64, 0.1 * LOAD / (2 * np.pi * RB)),
                                     eccentricity=jnp.asarray(0.0), attitude_angle=jnp.asarray(0.0))
    kw = dict(housing=el, initial=concentric, **THESIS_SPEEDS)
    newton = JournalOptions(n=64, strategy="newton")
    with pytest.raises(vjax.ConvergenceError, match="journal_bearing did not converge"):
        journal_bearing(RB, CB, ETAB, LOAD, options=newton, **kw)
    sol = jax.jit(lambda eta: journal_bearing(RB, CB, eta, LOAD, throw=False, options=newton, **kw))(ETAB)
    assert not bool(sol.converged)
    assert int(sol.iterations) >= 1
    assert float(sol.film_parameter) == np.inf      # h_min / sigma of smooth surfaces
    for leaf in jax.tree_util.tree_leaves(dataclasses.replace(sol, film_parameter=sol.min_film)):
        assert np.all(np.isfinite(np.asarray(leaf, dtype=float)))
    auto = journal_bearing(RB, CB, ETAB, LOAD, options=OPT64, **kw)
    assert bool(auto.converged) and int(auto.stages) > 0
    assert float(auto.eccentricity) == pytest.approx(float(ref.eccentricity), abs=1e-8)


ISSUE_BORE = dict(R=0.05, radial_clearance=5e-5, viscosity=0.01, load=2e4)


def _prony_bore(scale, nu):
    """The Prony bore of the issue report: E0 = scale MPa, three terms up to 10 scale MPa."""
    return vjax.Material.prony(1e6 * scale, [3e6 * scale] * 3, [1e-3, 1e-2, 1e-1], nu)


@pytest.mark.parametrize("omega", [100.0, 1000.0])
def test_nearly_rigid_bore_converges_directly(omega):
    """A bore whose mode-1 (rigid) displacement is ~0.3 clearances but whose film barely
    deforms: Newton from the start that moves the journal with the bore converges without
    continuation (it took 259 and 548 steps over 11 and 21 continuation stages when the
    translation had to be found by Newton), at the same eccentricity as a plain continuation."""
    kw = dict(ISSUE_BORE, housing=_prony_bore(1000, 0.4), omega_shaft=omega)
    sol = journal_bearing(**kw, options=JournalOptions(n=256))
    # from the nested (n = 64) start: 6 and 3 steps with the rupture on a cell face (34 and 36
    # from the rigid estimate), 13 and 9 with the second stage that locates it within its cell
    assert int(sol.stages) == 0 and int(sol.iterations) <= 15
    assert float(sol.eccentricity) > 5 * float(sol.eccentricity_effective)      # mostly translation
    cont = journal_bearing(**kw, options=JournalOptions(n=256, strategy="continuation"))
    assert float(sol.eccentricity) == pytest.approx(float(cont.eccentricity), abs=1e-8)


@pytest.mark.parametrize("omega, load", [(10.0, 2e2), (31.6, 2e3), (1000.0, 6.32e3)])
def test_soft_bore_converges_directly_up_to_tens_of_clearances(omega, load):
    """The soft Prony bore (1 MPa) at loads that deform the film's shape by 2, 20 and 63
    clearances: direct Newton from the nested start converges (these failed, or needed 9-40
    continuation stages, when a cold start began from the rigid estimate on the fine grid),
    to the solution that a continuation in compliance and speed reaches independently."""
    kw = dict(ISSUE_BORE, load=load, housing=_prony_bore(1, 0.5), omega_shaft=omega)
    sol = journal_bearing(**kw, options=JournalOptions(n=256))
    assert int(sol.stages) == 0 and int(sol.iterations) <= 25
    assert float(sol.min_film) > 0 and float(sol.eccentricity_effective) > 0
    cont = journal_bearing(**kw, options=JournalOptions(n=256, strategy="continuation", max_iter=100))
    assert bool(cont.converged) and int(cont.stages) > 0
    assert float(sol.eccentricity) == pytest.approx(float(cont.eccentricity), rel=1e-8)
    np.testing.assert_allclose(np.asarray(sol.pressure), np.asarray(cont.pressure), rtol=0,
                               atol=1e-7 * float(np.max(sol.pressure)))


def test_thin_elastohydrodynamic_film_failure_says_why():
    """The thesis's elastic bore slowed down 1e4 times: the rigid film would be ~7e-7 c, the
    load rides on a film far thinner than the bore's deformation; the error says so, and either
    how many elements it would take (slowed down 1e3 times: it converges at n = 2048) or that
    no grid will do (1e4 times: seen to fail up to n = 32768)."""
    kw = dict(housing=vjax.Material.elastic(1e6, 0.5), options=JournalOptions(n=64))
    with pytest.raises(vjax.ConvergenceError, match=r"elastohydrodynamic film .* 64 elements do not resolve: about"):
        journal_bearing(0.1, 5e-4, 1e-3, 2.2e-3 * 1e6 * 0.1, omega_shaft=-0.4e-3, omega_housing=0.2e-3, **kw)
    with pytest.raises(vjax.ConvergenceError, match=r"elastohydrodynamic film .* beyond this solver on any grid"):
        journal_bearing(0.1, 5e-4, 1e-3, 2.2e-3 * 1e6 * 0.1, omega_shaft=-0.4e-4, omega_housing=0.2e-4, **kw)


def test_soft_bore_failure_says_why():
    """The issue's soft bore (1 MPa) deforms the film's shape by ~200 clearances: the failure
    names that, not only the Newton statistics."""
    with pytest.raises(vjax.ConvergenceError, match="clearances under this load"):
        journal_bearing(**ISSUE_BORE, housing=_prony_bore(1, 0.5), omega_shaft=100.0, options=JournalOptions(n=64))


def test_jit_vmap_and_warm_start():
    etas = jnp.array([0.01, 0.02, 0.04])
    f = jax.vmap(lambda eta: journal_bearing(R, C, eta, 4e5, omega_shaft=WJ, options=OPT64, throw=False).eccentricity)
    eps = np.asarray(f(etas))
    assert np.all(np.diff(eps) < 0)     # more viscous, less eccentric
    s0 = journal_bearing(R, C, 0.02, 4e5, omega_shaft=WJ, options=OPT64)
    assert float(s0.eccentricity) == pytest.approx(eps[1], abs=1e-10)
    s1 = journal_bearing(R, C, 0.02, 4e5, omega_shaft=WJ, options=OPT64, initial=s0)
    assert int(s1.iterations) <= 1


@pytest.mark.parametrize("kwargs, name", [
    (dict(radial_clearance=0.2), "radial_clearance"),
    (dict(viscosity=-1.0), "viscosity"),
    (dict(cavitation="elrod"), "cavitation"),
    (dict(housing=vjax.disc(SLS)), "housing"),
    (dict(load=[0.0, 0.0]), "load"),
    (dict(omega_shaft=0.0), "entrainment"),
    (dict(memory="forever"), "memory"),
    (dict(housing="steel"), "housing"),
    (dict(supply_pressure=-1.0), "supply_pressure"),
    (dict(temperature=40.0), "shift"),
])
def test_argument_validation(kwargs, name):
    args = dict(R=R, radial_clearance=C, viscosity=ETA, omega_shaft=WJ, load=1e5)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        journal_bearing(**args)


@pytest.mark.parametrize("kwargs, name", [(dict(n=63), "n must be even"), (dict(n=8), "n"),
                                          (dict(strategy="magic"), "strategy"), (dict(max_iter=0), "max_iter")])
def test_options_validate_themselves(kwargs, name):
    with pytest.raises(ValueError, match=name):
        JournalOptions(**kwargs)


@pytest.mark.slow
def test_float32_runs_without_nan():
    """vjax does not force float64: in float32 the solves converge to the looser default
    tolerance (1e-4) and nothing is NaN (run in a fresh interpreter without x64)."""
    run_in_float32("""
        import dataclasses, vjax
        m = vjax.Material.sls(1e6, 1e8, 1.0, 0.5)
        for args, kw in (((0.05, 5e-5, 0.01, 2e5), dict(omega_shaft=100.0)),
                         ((0.1, 5e-4, 1e-3, 220.0), dict(omega_shaft=-0.4, omega_housing=0.2, housing=m))):
            s = vjax.journal_bearing(*args, options=vjax.JournalOptions(n=32), throw=False, **kw)
            assert float(s.film_parameter) == np.inf      # h_min / sigma of smooth surfaces
            check(dataclasses.replace(s, film_parameter=s.min_film))
        # the finite bearing, tilted; and with a polymer liner and the mass-conserving film (one
        # interpreter for all: each costs a JAX import)
        liner = vjax.liner(vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4), 2e-3)
        for kw in (dict(tilt=(1e-4, 0.0)), dict(housing=liner, cavitation="jfo")):
            s = vjax.journal_bearing(0.05, 5e-5, 0.01, 2000.0, omega_shaft=100.0, length=0.1,
                                     options=vjax.FiniteJournalOptions(n=16, m=4), throw=False, **kw)
            assert float(s.film_parameter) == np.inf      # h_min / sigma of smooth surfaces
            check(dataclasses.replace(s, film_parameter=s.min_film))
        print("ok")
    """)
