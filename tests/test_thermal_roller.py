"""The needle roller bearing at its rings' bulk temperature (vjax.thermal_roller): the power is
the rings' hysteresis (against the modal dissipation of each ring, computed here from the
pressures and the material's loss compliance at T with a WLF shift written out below), it
leaves through hA (1e-10), hA = inf is vjax.roller_bearing at T_ambient (1e-10), and the
implicit dT/dhA matches central differences of converged solves (1e-6; slow tier).

A coarse grid (n = 64 per ring: the patches are a few elements wide; every check here is a
consistency of one discretization, not its accuracy), the thesis's SLS rings (tau = 10 ms)
with a WLF law, so that the rings' hysteresis depends on their temperature.
"""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax

RO, RI, D, Z = 6e-3, 4e-3, 2e-3, 9
E0, EINF, TAU, NU = 1e6, 1e7, 0.01, 0.5
SLS = vjax.Material.sls(E0, EINF, TAU, NU)
LOAD = 6.5e-3 * E0 * RO                       # N/m: F~ = 6.5e-3
C1, C2, T_REF = 8.86, 101.6, 40.0
SHIFT = vjax.WLF(C1, C2, T_REF)
HOT = SLS.with_shift(SHIFT)     # the rings' material, moved by the temperature
OPT = vjax.RollerOptions(n=64)
W_SHAFT = 0.3 / TAU * (RI + RO) / RI          # outer ring fixed: patch speed 0.3 / tau on the outer ring
T_AMB = 30.0
HA = 1e-3                                     # W/(m K): ~10 K of self-heating at this speed


def run(hA, T_ambient=T_AMB, **kw):
    heat = vjax.HeatTransfer(T_ambient, hA=hA, oil_flow=False)
    return vjax.thermal_roller(HOT, HOT, RO, RI, D, Z, LOAD, heat, omega_shaft=W_SHAFT, options=OPT,
                               **kw)


def modal_dissipation(scene, T):
    """Both rings' hysteresis (W/m) from their pressures: Omega R^2 (2 pi / N^2) 2 sum_k k L_k
    J''(k Omega a_T) |p_k|^2 (tests/test_roller.py's energy balance), a_T = 10^(-C1 dT / (C2 + dT))."""
    from vjax import element_symbol
    a_T = 10.0 ** (-C1 * (T - T_REF) / (C2 + T - T_REF))
    n = OPT.n
    k = np.arange(n // 2)
    total = 0.0
    for kind, R, w, p in (("hole", RO, scene.patch_speed[0], scene.pressure),
                          ("cylinder", RI, scene.patch_speed[1], scene.pressure_shaft)):
        p_hat = np.fft.rfft(np.asarray(p))
        L = np.asarray(element_symbol(kind, n, R, NU))[k]
        loss = -np.imag(np.asarray(SLS.compliance(k * abs(float(w)) * a_T)))
        total += abs(float(w)) * R**2 * 2 * np.pi / n**2 * 2 * np.sum(k * L * loss * np.abs(p_hat[k]) ** 2)
    return total


def test_energy_balance_closes_on_the_rings_hysteresis():
    """P = hA (T - T_amb) to 1e-10 from the result's own temperature; P is the rings' modal
    dissipation at T (within the torque arm's geometric factor max|u|/R, as in test_roller);
    the rings heat up by several kelvin."""
    r = run(HA)
    assert bool(r.converged)
    T, P = float(r.temperature), float(r.power)
    assert T > T_AMB + 3.0, T
    assert abs(P - HA * (T - T_AMB)) <= 1e-10 * abs(P)
    assert abs(P - float(r.heat_convected)) <= 1e-10 * abs(P)
    s = r.scene
    arm = max(np.max(np.abs(np.asarray(s.displacement))) / RO, np.max(np.abs(np.asarray(s.displacement_shaft))) / RI)
    assert arm < 2e-2
    np.testing.assert_allclose(P, modal_dissipation(s, T), rtol=arm)
    # the scene in the result is the isothermal bearing at T
    iso = vjax.roller_bearing(HOT, HOT, RO, RI, D, Z, LOAD, omega_shaft=W_SHAFT, temperature=T,
                              options=OPT)
    for a, b in ((s.pressure, iso.pressure), (s.torque, iso.torque), (s.torque_shaft, iso.torque_shaft)):
        assert np.max(np.abs(np.asarray(a) - np.asarray(b))) <= 1e-10 * np.max(np.abs(np.asarray(b)))


def test_infinite_removal_is_the_isothermal_bearing():
    r = run(jnp.inf)
    iso = vjax.roller_bearing(HOT, HOT, RO, RI, D, Z, LOAD, omega_shaft=W_SHAFT, temperature=T_AMB,
                              options=OPT)
    assert float(r.temperature) == T_AMB
    for a, b in ((r.scene.pressure, iso.pressure), (r.scene.pressure_shaft, iso.pressure_shaft),
                 (r.scene.torque, iso.torque), (r.scene.torque_shaft, iso.torque_shaft),
                 (r.scene.roller_loads, iso.roller_loads)):
        assert np.max(np.abs(np.asarray(a) - np.asarray(b))) <= 1e-10 * np.max(np.abs(np.asarray(b)))


@pytest.mark.slow
def test_temperature_derivative_in_hA_against_central_differences():
    """dT/dhA by the implicit derivative of the thermal root (one tangent solve) against central
    differences of converged solves, Richardson-extrapolated (error O(h^4)), 1e-6 relative; and
    the sign: more removal, cooler rings. Slow tier: the roller's tangent program compiles in
    25-60 s (as the journal's in tests/test_thermal.py)."""
    T = lambda hA: float(run(hA).temperature)          # noqa: E731
    g = float(jax.grad(lambda hA: run(hA).temperature)(HA))
    h = 1e-2 * HA
    d = lambda h: (T(HA + h) - T(HA - h)) / (2 * h)    # noqa: E731
    fd = (4 * d(h / 2) - d(h)) / 3
    assert fd < 0
    assert abs(g - fd) < 1e-6 * abs(fd), (g, fd)


def test_bad_heat_is_refused_by_name():
    with pytest.raises(ValueError, match="hA"):
        run(-1.0)
    with pytest.raises((TypeError, ValueError), match="heat"):
        vjax.thermal_roller(HOT, HOT, RO, RI, D, Z, LOAD, 0.01, omega_shaft=W_SHAFT, options=OPT)
