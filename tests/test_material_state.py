"""One material state (issue 51): a material carries its shift law and the temperature its
relaxation times hold at; each body of a scene answers at its own temperature, the oil at its
own; the 0.2 call forms (a shift law passed beside the material) warn and give the same
numbers. And every scene's viscosity argument takes a number and a Lubricant alike (issue 52)."""
import warnings

import numpy as np
import pytest

import vjax

WLF = vjax.WLF(8.86, 101.6, 20.0)
SOFT = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)
LINER_MATERIAL = vjax.Material.prony(1.5e9, [1.0e9, 0.5e9], [1e-3, 1e-1], 0.4)
OIL = vjax.Lubricant.iso_vg(46)


def wlf_factor(T, C1=8.86, C2=101.6, T_ref=20.0):
    """a_T of the WLF law written out (base 10), apart from vjax.WLF."""
    return 10.0 ** (-C1 * (T - T_ref) / (C2 + T - T_ref))


def by_hand(material, T):
    """The material at T with its relaxation times scaled by the written-out a_T."""
    return vjax.Material.prony(material.E0, material.moduli, material.times * wlf_factor(T), material.nu)


def test_a_material_at_a_temperature_is_its_master_curve_shifted():
    """E*(omega, T) = E*(a_T omega, T_ref), and moving a material twice is moving it once."""
    hot = LINER_MATERIAL.with_shift(WLF).at_temperature(60.0)
    omega = np.logspace(-2, 5, 15)
    np.testing.assert_allclose(np.asarray(hot.modulus(omega)),
                               np.asarray(LINER_MATERIAL.modulus(wlf_factor(60.0) * omega)), rtol=1e-12)
    twice = LINER_MATERIAL.with_shift(WLF).at_temperature(35.0).at_temperature(60.0)
    np.testing.assert_allclose(np.asarray(twice.times), np.asarray(hot.times), rtol=1e-12)
    assert float(hot.temperature) == 60.0 and hot.shift is WLF


def test_the_0_2_forms_warn_and_agree():
    with pytest.warns(DeprecationWarning, match="with_shift"):
        old = LINER_MATERIAL.at_temperature(WLF, 60.0)
    np.testing.assert_allclose(np.asarray(old.times), LINER_MATERIAL.times * wlf_factor(60.0), rtol=1e-12)
    with pytest.warns(DeprecationWarning):
        body = vjax.liner(LINER_MATERIAL, 2e-3).at_temperature(WLF, 60.0)
    np.testing.assert_allclose(np.asarray(body.material.times), np.asarray(old.times), rtol=1e-12)


def test_pin_and_roller_old_and_new_forms_give_the_same_numbers():
    opts = vjax.PinOptions(n=256)
    args = (0.08, 0.005, 2800.0)
    with pytest.warns(DeprecationWarning, match="shift="):
        old = vjax.pin_in_hole(SOFT, *args, omega_shaft=-6.67, temperature=40.0, shift=WLF, options=opts)
    new = vjax.pin_in_hole(SOFT.with_shift(WLF), *args, omega_shaft=-6.67, temperature=40.0, options=opts)
    hand = vjax.pin_in_hole(by_hand(SOFT, 40.0), *args, omega_shaft=-6.67, options=opts)
    assert float(old.torque) == float(new.torque)
    assert float(new.torque) == pytest.approx(float(hand.torque), rel=1e-10)
    cold = vjax.pin_in_hole(SOFT, *args, omega_shaft=-6.67, options=opts)
    assert abs(float(new.torque) - float(cold.torque)) > 1e-3 * abs(float(cold.torque))   # the shift matters

    ring = vjax.Material.sls(2e9, 4e9, 1e-3, 0.35)
    geometry = dict(R_outer=0.026, R_inner=0.02, roller_diameter=0.006, n_rollers=12, load=5e4,
                    omega_shaft=50.0, options=vjax.RollerOptions(n=512))
    with pytest.warns(DeprecationWarning):
        old = vjax.roller_bearing(ring, ring, temperature=60.0, shift=WLF, **geometry)
    new = vjax.roller_bearing(ring.with_shift(WLF), ring.with_shift(WLF), temperature=60.0, **geometry)
    hand = vjax.roller_bearing(by_hand(ring, 60.0), by_hand(ring, 60.0), **geometry)
    assert float(old.torque) == float(new.torque)
    assert float(new.torque) == pytest.approx(float(hand.torque), rel=1e-9)


def test_two_bodies_at_two_temperatures_and_the_oil_at_a_third():
    """A liner put at 70 C, a sleeved journal that follows the scene's 40 C, VG 46 at 55 C: the
    same bearing as the one built from materials shifted by hand and the oil's viscosity at 55 C."""
    common = dict(omega_shaft=300.0, options=vjax.JournalOptions(n=128))
    R, c, W = 0.02, 4e-5, 2e5
    housing = vjax.liner(LINER_MATERIAL.with_shift(WLF).at_temperature(70.0), 2e-3)
    shaft = vjax.sleeve(LINER_MATERIAL.with_shift(WLF), 3e-3)
    sol = vjax.journal_bearing(R, c, OIL, W, housing=housing, shaft=shaft, temperature=40.0, oil_temperature=55.0,
                               **common)
    hand = vjax.journal_bearing(R, c, float(OIL.viscosity(55.0)), W, housing=vjax.liner(by_hand(LINER_MATERIAL, 70.0), 2e-3),
                                shaft=vjax.sleeve(by_hand(LINER_MATERIAL, 40.0), 3e-3), **common)
    assert bool(sol.converged)
    for name in ("eccentricity", "attitude_angle", "torque_shaft", "friction_coefficient"):
        assert float(getattr(sol, name)) == pytest.approx(float(getattr(hand, name)), rel=1e-9), name
    # the oil alone at the scene's temperature: the bodies are not moved when none has a law
    oil_only = vjax.journal_bearing(R, c, OIL, W, temperature=55.0, **common)
    rigid = vjax.journal_bearing(R, c, float(OIL.viscosity(55.0)), W, **common)
    assert float(oil_only.eccentricity) == pytest.approx(float(rigid.eccentricity), rel=1e-12)


def test_what_a_temperature_cannot_move_is_refused():
    with pytest.raises(ValueError, match="moves no body"):
        vjax.pin_in_hole(SOFT, 0.08, 0.005, 2800.0, omega_shaft=-6.67, temperature=40.0)
    with pytest.raises(ValueError, match="no shift law"):
        SOFT.at_temperature(40.0)
    with pytest.raises(ValueError, match="oil_temperature"):
        vjax.journal_bearing(0.02, 4e-5, 0.02, 2e5, omega_shaft=300.0, oil_temperature=50.0)
    with pytest.raises(ValueError, match="temperature"):
        vjax.journal_bearing(0.02, 4e-5, OIL, 2e5, omega_shaft=300.0)
    with pytest.raises(ValueError, match="shift"):
        SOFT.with_shift(3.0)


def test_every_scene_takes_a_lubricant_as_its_viscosity():
    """journal_bearing, journal_coefficients and stribeck_curve: a Lubricant at T is the number
    eta(T) (the stribeck curve's Hersey number included)."""
    R, c, W, T = 0.02, 4e-5, 2e5, 60.0
    eta = float(OIL.viscosity(T))
    opts = vjax.JournalOptions(n=64)
    a = vjax.journal_bearing(R, c, OIL, W, omega_shaft=300.0, temperature=T, options=opts)
    b = vjax.journal_bearing(R, c, eta, W, omega_shaft=300.0, options=opts)
    assert float(a.eccentricity) == float(b.eccentricity)
    ka = vjax.journal_coefficients(R, c, OIL, W, [0.0, 100.0], omega_shaft=300.0, temperature=T, options=opts)
    kb = vjax.journal_coefficients(R, c, eta, W, [0.0, 100.0], omega_shaft=300.0, options=opts)
    np.testing.assert_array_equal(np.asarray(ka.stiffness), np.asarray(kb.stiffness))
    rough = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
    speeds = np.logspace(0, 2, 3)
    sa = vjax.stribeck_curve(R, c, OIL, W, speeds, roughness=rough, options=opts, temperature=T)
    sb = vjax.stribeck_curve(R, c, eta, W, speeds, roughness=rough, options=opts)
    np.testing.assert_allclose(sa.hersey, eta * speeds / (W / (2 * R)), rtol=1e-12)
    np.testing.assert_array_equal(sa.friction_coefficient, sb.friction_coefficient)


def test_the_thermal_scenes_take_materials_with_their_laws():
    """thermal_pin with the material's own law is thermal_pin with the 0.2 shift= argument."""
    heat = vjax.HeatTransfer(T_supply=20.0, hA=2.0)        # W/(m K), per unit length
    kw = dict(omega_shaft=-6.67, heat=heat, options=vjax.PinOptions(n=256))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        old = vjax.thermal_pin(SOFT, 0.08, 0.005, 2800.0, shift=WLF, **kw)
    new = vjax.thermal_pin(SOFT.with_shift(WLF), 0.08, 0.005, 2800.0, **kw)
    assert float(new.temperature) == pytest.approx(float(old.temperature), rel=1e-12)
