"""fitting.torque.journal_model: the torque's derivatives w.r.t. the log-parameters (implicit,
through the finite journal solve) against central finite differences, and that the torque of
a turning liner depends on the liner's material at all."""
import numpy as np
import pytest

from fitting import torque as ft
from vjax import WLF, Material

L = 0.05
# an elastomer-like liner (|E*| ~ 10-20 MPa at the tested speeds) in a water-lubricated bearing
MAT = Material.prony(1e6, [8e6, 6e6], [0.03, 1.0], 0.5)
SHIFT = WLF(8.0, 100.0, 25.0)


def test_journal_model_arguments():
    with pytest.raises(ValueError, match="thickness"):
        ft.journal_model(thickness=0.0)
    with pytest.raises(ValueError, match="turning"):
        ft.journal_model(turning="housing")
    with pytest.raises(ValueError, match="radial_clearance"):
        ft.journal_model(R=0.01, radial_clearance=0.02)
    with pytest.raises(ValueError, match="viscosity"):
        ft.journal_model(viscosity=-1.0)


def test_water_viscosity():
    # tabulated (CRC): 1.0016e-3 Pa s at 20 C, 0.5465e-3 at 50 C, 0.2822e-3 at 100 C
    np.testing.assert_allclose([ft.water_viscosity(T) for T in (20.0, 50.0, 100.0)],
                               [1.0016e-3, 0.5465e-3, 0.2822e-3], rtol=0.03)


def test_oil_viscosity():
    """Walther's equation through the data sheet's two kinematic viscosities (cSt) times the
    density: the anchors in Pa s, thinner when hotter (its derivative in T by jax.grad), and the
    arguments checked."""
    import jax
    eta = ft.oil_viscosity(32.0, 5.4, 870.0)
    np.testing.assert_allclose([eta(40.0), eta(100.0)], [870e-6 * 32.0, 870e-6 * 5.4], rtol=1e-12)
    assert 870e-6 * 5.4 < eta(70.0) < 870e-6 * 32.0
    assert float(jax.grad(eta)(60.0)) < 0
    with pytest.raises(ValueError, match="nu100"):
        ft.oil_viscosity(5.4, 32.0)
    with pytest.raises(ValueError, match="density"):
        ft.oil_viscosity(32.0, 5.4, density=0.0)


@pytest.mark.slow
def test_journal_torque_derivatives_vs_finite_differences():
    """One compiled residual Jacobian serves the derivatives and the finite differences (its
    residuals at x +- h e_i): the torque's derivative w.r.t. each log-parameter, from the
    implicit derivatives of the finite bearing with a viscoelastic liner, matches central
    differences of the converged torque; and the material matters (the Prony terms and C1
    move the torque, not only E0, because the liner turns through the pressure field)."""
    import jax.numpy as jnp
    model = ft.journal_model(length=L, n=16, m=4)
    rpm, T, load = np.array([60.0, 200.0]), np.array([40.0, 60.0]), np.array([20.0, 20.0]) / L
    ones = np.ones(2)
    data = ft.TorqueData(rpm, T, load, ones, ones)      # unit scatter: the residual Jacobian is d torque / d x
    P = ft.Params.of(MAT, SHIFT)
    jac_fn, _ = ft.residual_jacobian(P, model, data)
    x = jnp.asarray(P.pack(MAT, SHIFT))
    J, (_, _, tq, ok) = jac_fn(x)
    assert bool(np.all(ok)) and np.all(np.asarray(tq) > 0)
    J, tq = np.asarray(J), np.asarray(tq)
    h = 1e-4
    for i, name in enumerate(P.names()):
        e = h * np.eye(len(x))[i]
        up, dn = jac_fn(x + e)[1], jac_fn(x - e)[1]
        assert bool(np.all(up[3])) and bool(np.all(dn[3]))
        fd = (np.asarray(up[2]) - np.asarray(dn[2])) / (2 * h)
        np.testing.assert_allclose(J[:, i], fd, rtol=1e-4, atol=1e-6 * np.max(np.abs(tq)), err_msg=name)
    sens = J / tq[:, None]                                 # d ln torque / d ln parameter
    assert np.max(np.abs(sens[:, 1:3])) > 0.02, sens      # the Prony moduli
    assert np.max(np.abs(sens[:, 3])) > 0.02, sens        # C1
