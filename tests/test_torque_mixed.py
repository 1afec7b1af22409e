"""fitting.torque in mixed lubrication: a rough journal model's torque derivatives with respect
to log mu_b and log sigma (implicit, through the mixed-regime solve) against central
differences, the fit recovering mu_b and sigma from noise-free Stribeck data, and the
argument checks of the extras."""
import numpy as np
import pytest

import vjax
from fitting import torque as ft
from vjax import WLF, Material

L = 0.05
MAT = Material.prony(1e9, [1e9, 1e9], [1e-3, 0.1], 0.4)
SHIFT = WLF(8.0, 100.0, 25.0)
TRUTH = {"mu_b": 0.1, "sigma": 1e-6}
# a Stribeck curve at 2 kN: boundary-dominated (3 rpm), mixed (30 rpm), full film (300 rpm)
RPM = np.array([3.0, 30.0, 300.0])


def _model():
    rough = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
    return ft.journal_model(length=L, thickness=3e-3, viscosity=0.03, turning="shaft", n=16, m=4,
                            roughness=rough, supply_angle=None)


def _data(torque=None):
    n = len(RPM)
    t = np.ones(n) if torque is None else torque
    return ft.TorqueData(RPM, np.full(n, 40.0), np.full(n, 2000.0 / L), t, np.ones(n))


@pytest.mark.slow      # the fit compiles its Jacobian; the extras checks stay fast
def test_mixed_torque_derivatives_vs_central_differences():
    """d torque / d log mu_b and d log sigma (unit scatter: the residual Jacobian is the torque's
    derivative) against central differences of the converged torque, from one compiled
    residual-Jacobian function; the boundary friction moves the mixed points in proportion to
    their asperity friction and the full-film point not at all."""
    import jax.numpy as jnp
    model = _model()
    P = ft.Params.of(MAT, SHIFT, extras=("mu_b", "sigma"))
    x = P.pack(MAT, SHIFT, TRUTH)
    jac, _ = ft.residual_jacobian(P, model, _data())
    J, aux = jac(jnp.asarray(x))
    J, tq = np.asarray(J), np.asarray(aux[2])
    assert np.all(np.asarray(aux[3]))
    assert tq[0] > tq[1] > tq[2] > 0            # falling through the mixed regime
    h = 1e-5
    for name in ("mu_b", "sigma"):
        i = P.names().index(name)
        e = np.zeros_like(x)
        e[i] = h
        fd = (np.asarray(jac(jnp.asarray(x + e))[1][2]) - np.asarray(jac(jnp.asarray(x - e))[1][2])) / (2 * h)
        np.testing.assert_allclose(J[:, i], fd, rtol=1e-6, atol=1e-9 * np.max(np.abs(fd)))
    # the friction of the asperities is linear in mu_b: where they carry load the derivative is a
    # sizeable part of the torque, in full film (300 rpm) it vanishes
    i = P.names().index("mu_b")
    assert J[0, i] > 0.5 * tq[0] and J[2, i] < 1e-6 * tq[2]


@pytest.mark.slow
def test_fit_recovers_mu_b_and_sigma_from_noise_free_stribeck_data():
    """Noise-free torques of the truth; the fit starts with mu_b and sigma 30-40 % off (the
    material at the truth, free) and must land on the truth."""
    model = _model()
    tq, ok = ft.evaluate(model, MAT, SHIFT, RPM, np.full(3, 40.0), np.full(3, 2000.0 / L), TRUTH)
    assert np.all(np.asarray(ok))
    tq = np.asarray(tq)
    data = ft.TorqueData(RPM, np.full(3, 40.0), np.full(3, 2000.0 / L), tq, 0.01 * tq)
    fit = ft.fit_torque(data, MAT, SHIFT, model, extras={"mu_b": 0.14, "sigma": 0.7e-6}, steps=0, polish=25,
                        progress=False)
    assert fit.converged
    np.testing.assert_allclose(fit.extras["mu_b"], TRUTH["mu_b"], rtol=1e-4)
    np.testing.assert_allclose(fit.extras["sigma"], TRUTH["sigma"], rtol=1e-4)


def test_extras_are_checked():
    with pytest.raises(ValueError, match="extras"):
        ft.Params.of(MAT, SHIFT, extras=("mu",))
    P = ft.Params.of(MAT, SHIFT, extras=("mu_b", "sigma"))
    with pytest.raises(ValueError, match="sigma"):
        P.pack(MAT, SHIFT, {"mu_b": 0.1})
    with pytest.raises(ValueError, match="mu_b"):
        P.pack(MAT, SHIFT, {"mu_b": 0.0, "sigma": 1e-6})
    x = P.pack(MAT, SHIFT, TRUTH)
    assert P.names()[-2:] == ["mu_b", "sigma"]
    np.testing.assert_allclose(list(P.physical_extras(x).values()), [0.1, 1e-6], rtol=1e-14)
    m, s = P.physical(x)
    np.testing.assert_allclose([float(m.E0), float(s.C1), float(s.C2)], [1e9, 8.0, 100.0], rtol=1e-14)
    with pytest.raises(ValueError, match="takes no"):      # a smooth model has no mu_b
        ft.residual_jacobian(P, ft.journal_model(), _data())
    with pytest.raises(ValueError, match="roughness"):
        ft.journal_model(roughness=1e-6)
    both = ft.journal_model(roughness=vjax.Roughness(1e-6, 3e9), heat_transfer=10.0)   # rough and self-heating
    assert both.extras == ("mu_b", "sigma", "hA")
    with pytest.raises(ValueError, match="heat_transfer"):
        ft.journal_model(heat_transfer=-1.0)
