"""The finite journal bearing with deformable bodies (``journal_bearing(..., length=L,
housing=..., shaft=...)``): each axial section deforms as the plane ring under its own pressure.

References: the infinitely long bearing with the same bodies as L/D -> infinity; the ring
operator applied slice by slice to the solved pressure (an independent evaluation of the
deformation); the rigid finite bearing as the bodies stiffen; the power balance with the
bodies' hysteresis; finite differences.
"""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import FiniteJournalOptions, JournalOptions, journal_bearing, journal_finite, reference

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
V = 0.5 * WJ * (R - C)
D = 2 * R
SLS = vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4)
LINER = vjax.liner(SLS, 2e-3)
# one grid for the solves (compiled once per kind of body and cavitation model), Newton's
# steps by GMRES (the default from 512 cells on; tests/test_journal_finite_layer3d.py solves
# its 32 x 16 grid by the dense LU)
OPT = FiniteJournalOptions(n=32, m=16, linear_solver="krylov")


def long_load(eps):
    return float(reference.long_bearing(eps, R, C, ETA, V, "reynolds")["load"])


def finite(load, LD, **kw):
    kw.setdefault("options", OPT)
    return journal_bearing(R, C, ETA, load, omega_shaft=WJ, length=LD * D, **kw)


SLEEVE = vjax.sleeve(SLS, 3e-3)
W_HALF = 0.5 * long_load(0.5) * D
LOAD = jnp.array([0.0, -W_HALF])        # the load vector (N): its derivatives give the static stiffness


GAMMA = jnp.array([1e-4, -5e-5])        # a misalignment (rad): the journal's ends up to 0.1 c off its centre


def lined(load=LOAD, liner=LINER, sleeve=SLEEVE, tilt=None, **kw):
    """A bearing of L/D = 1 with a polymer liner in a rigid housing and a polymer sleeve on the
    shaft, fed at 1e4 Pa: one compiled program for the tests below (their loads and bodies'
    parameters are traced values), one with a tilt given (the whole width)."""
    return finite(load, 1.0, housing=liner, shaft=sleeve, supply_pressure=1e4, tilt=tilt, **kw)


@pytest.fixture(scope="module")
def solution():
    return lined(tilt=jnp.zeros(2))      # a tilt given: the program of the tilted bearing below


def outputs(q):
    """(journal position x, y (m), moment x, y (N m), eps, attitude, shaft torque) of the tilted
    lined bearing at q = (load x, load y (N), liner thickness (m), liner E0 (Pa), tilt gamma_x,
    gamma_y (rad)), solved by Newton-Krylov."""
    s = lined(q[:2], vjax.liner(vjax.Material.sls(q[3], 3e9, 1e-3, 0.4), q[2]), tilt=q[4:])
    return jnp.concatenate([s.position, s.moment, jnp.stack([s.eccentricity, s.attitude_angle, s.torque_shaft])])


def test_slices_deform_as_the_plane_ring(solution):
    """At the solution every axial section's displacement is the ring operator (the body's own,
    at the pattern's speed relative to it) applied to that section's pressure: the slices'
    first mode taken from the load during the solve is exact at equilibrium. Housing and
    shaft deform; the end sections, at ambient pressure, do not."""
    s = solution
    assert bool(s.converged)
    p = np.asarray(s.pressure)
    for body, radius, omega, u in ((LINER, R, 0.0, s.displacement), (SLEEVE, R - C, -WJ, s.displacement_shaft)):
        op = body.operator(radius, OPT.n, omega)
        expected = np.asarray(jax.vmap(op, in_axes=1, out_axes=1)(jnp.asarray(p)))
        u = np.asarray(u)
        assert np.abs(u).max() > 0.05 * C
        assert np.max(np.abs(u - expected)) < 1e-8 * np.abs(u).max()
        assert np.abs(u[:, [0, -1]]).max() < 1e-8 * np.abs(u).max()


def test_power_balance_with_hysteresis(solution):
    """The sleeve turning with the shaft through the pattern fixed in space dissipates
    -omega_J torque_viscoelastic_shaft > 0 (the liner, at rest under a pattern at rest, none);
    the power put in equals the film's dissipation plus the sleeve's, to the discretization's
    accuracy (here 2e-3 of the sleeve's hysteresis: the balance without it is off by all of it)."""
    s = solution
    hysteresis = -WJ * float(s.torque_viscoelastic_shaft)
    assert hysteresis > 1e-3 * float(s.power_loss)
    assert abs(float(s.torque_viscoelastic)) < 1e-12 * hysteresis / WJ
    power_in = -WJ * float(s.torque_shaft) + 1e4 * float(s.supply_flow)
    assert abs(power_in - float(s.power_loss) - hysteresis) < 2e-3 * hysteresis


# ---------------------------------------------------------------- the long-bearing limit
@pytest.mark.slow
def test_long_bearing_limit_with_a_liner():
    """L/D -> infinity with a 2 mm polymer liner (full Sommerfeld film, the groove fixed opposite
    the load, cosine axial spacing): Richardson's extrapolation from L/D = 50 and 100 meets the
    long bearing with the same liner (vjax.journal_bearing and vjax.journal_dynamics, an
    independent discretization and linearization) to 3e-3 in eps (measured 1.3e-3; the rigid
    bearings' 7.6e-4) and attitude, and in Z(Omega) = K + i Omega C per unit length to 3e-3 of
    |Z| at whirl 0, 300 and 3000 rad/s (measured 1.5e-3, 9.7e-4, 9.3e-4). The liner moves the
    journal by 0.11 c and its relaxation (tau = 1 ms) changes K by 24 times |Z(0)| over these
    frequencies: dropping either fails the test."""
    W1 = long_load(0.4)
    whirl = [0.0, 300.0, 3000.0]
    kw = dict(omega_shaft=WJ, cavitation="sommerfeld")
    opt = JournalOptions(n=OPT.n)
    long = vjax.journal_coefficients(R, C, ETA, W1, whirl, housing=LINER, groove="fixed", options=opt, **kw)
    rigid = journal_bearing(R, C, ETA, W1, groove="fixed", options=opt, **kw)
    finite_ = {LD: vjax.journal_coefficients(R, C, ETA, W1 * LD * D, whirl, length=LD * D, housing=LINER,
                                             options=FiniteJournalOptions(n=OPT.n, m=32, spacing="cosine", linear_solver="dense"), **kw)
               for LD in (50.0, 100.0)}
    extrapolate = lambda f: 2 * f(finite_[100.0]) - f(finite_[50.0])
    e0, p0 = float(long.steady.eccentricity), float(long.steady.attitude_angle)
    assert e0 - float(rigid.eccentricity) > 0.1
    assert abs(extrapolate(lambda co: float(co.steady.eccentricity)) / e0 - 1) < 3e-3
    assert abs(extrapolate(lambda co: float(co.steady.attitude_angle)) - p0) < 3e-3
    Zl = np.asarray(long.impedance)
    assert np.abs(Zl[2].real - Zl[0].real).max() > 10 * np.abs(Zl[0]).max()
    Z = extrapolate(lambda co: np.asarray(co.impedance) / float(co.length))
    for k in range(len(whirl)):
        assert np.abs(Z[k] - Zl[k]).max() < 3e-3 * np.abs(Zl[k]).max(), whirl[k]


# ---------------------------------------------------------------- dynamic coefficients
def blocks(A):
    """The 2 x 2 blocks of a (..., 4, 4) array in (position, tilt) x (position, tilt): each in
    its own units."""
    return [A[..., i:i + 2, j:j + 2] for i in (0, 2) for j in (0, 2)]


@pytest.mark.slow
def test_derivatives_and_the_static_stiffness():
    """jax.jacfwd of the tilted lined bearing's (position, moment, eps, attitude, torque) with
    respect to (load vector, liner thickness, liner E0, tilt), by implicit differentiation (GMRES
    at the root), against central differences (1e-5; not across the load: the grid, and the
    groove with it, is set along the load's direction, so a difference across it turns the
    bearing, which the derivative holds fixed). The 4 x 4 K(0) in position and tilt of the
    bearing (a liner at rest, a sleeve turning with the shaft; matrix-free whirl solves,
    :func:`vjax.journal_finite.tilt_coefficients`) predicts every block of d(position,
    moment)/d(load vector, tilt): dX = K_xx^-1 (dW - K_xg dgamma), dM = -K_gx dX - K_gg dgamma
    (1e-7 of each block's largest entry; measured 1e-11 to 2e-10): the bodies' whirl operators
    at Omega = 0 are their steady ones. K at 100 rad/s differs (by 19 %: the polymers'
    frequency dependence). Bodies 1e6 times stiffer (E ~ 3e14-3e15 Pa) give the rigid bearing:
    its steady state to 1e-6, each block of its K and C to 1e-5 (measured 0.9e-6 to 4.9e-6:
    the compliance ratio). One test: the Jacobian's program serves both."""
    q = jnp.concatenate([jnp.array([0.0, -W_HALF, 2e-3, 0.3e9]), GAMMA])
    J = np.asarray(jax.jit(jax.jacfwd(outputs))(q))
    for i, h in ((1, 1e-5 * W_HALF), (2, 2e-7), (3, 3e4), (4, 1e-7)):
        fd = (np.asarray(outputs(q.at[i].add(h))) - np.asarray(outputs(q.at[i].add(-h)))) / (2 * h)
        assert np.allclose(J[:, i], fd, rtol=1e-5, atol=1e-9 * np.abs(fd).max()), (i, J[:, i], fd)

    whirl = [0.0, 100.0]
    kw = dict(omega_shaft=WJ, housing=LINER, shaft=SLEEVE, supply_pressure=1e4, tilt=GAMMA, options=OPT)
    _, K4, C4 = journal_finite.tilt_coefficients(R, C, ETA, LOAD, D, whirl=whirl, **kw)
    K = np.asarray(K4[0])
    Kxx_inv = np.linalg.inv(K[:2, :2])
    predicted = {"dX/dW": Kxx_inv, "dX/dgamma": -Kxx_inv @ K[:2, 2:], "dM/dW": -K[2:, :2] @ Kxx_inv,
                 "dM/dgamma": -K[2:, 2:] + K[2:, :2] @ Kxx_inv @ K[:2, 2:]}
    computed = {"dX/dW": J[:2, :2], "dX/dgamma": J[:2, 4:6], "dM/dW": J[2:4, :2], "dM/dgamma": J[2:4, 4:6]}
    for name, block in computed.items():
        assert np.max(np.abs(block - predicted[name])) < 1e-7 * np.abs(block).max(), name
    assert np.max(np.abs(np.asarray(K4[1, :2, :2] - K4[0, :2, :2]))) > 1e-3 * np.abs(K[:2, :2]).max()

    stiff = vjax.Material.sls(0.3e15, 3e15, 1e-3, 0.4)
    hard = journal_finite.tilt_coefficients(R, C, ETA, LOAD, D, whirl=whirl, **dict(
        kw, housing=vjax.liner(stiff, 2e-3), shaft=vjax.sleeve(stiff, 3e-3)))
    rigid = journal_finite.tilt_coefficients(R, C, ETA, LOAD, D, whirl=whirl, **dict(kw, housing=None, shaft=None))
    for name in ("eccentricity", "attitude_angle"):
        assert abs(float(getattr(hard[0], name)) - float(getattr(rigid[0], name))) < 1e-6
    assert abs(float(hard[0].torque_shaft) / float(rigid[0].torque_shaft) - 1) < 1e-6
    for a, b in zip(blocks(np.asarray(hard[1])) + blocks(np.asarray(hard[2])),
                    blocks(np.asarray(rigid[1])) + blocks(np.asarray(rigid[2]))):
        assert np.max(np.abs(a - b)) < 1e-5 * np.abs(b).max()


@pytest.mark.slow
def test_mass_conserving_cavity_with_bodies():
    """cavitation="jfo" with the liner and the sleeve, the groove 2 rad from the load (the film
    re-forms inside the land, its cavity partly filled; the dense LU, cheaper to compile on this
    grid, with the same matrix-free products as GMRES): K(0) from the whirl solves (the
    cavity's fraction with its own dynamics, the bodies by their whirl operators) is the
    static stiffness: its inverse's column along the load is the central difference of the
    steady position in the load's magnitude (1e-7, measured 1.7e-9; across the load a difference
    would turn the bearing, see above). At 100 rad/s K differs (by 18 %)."""
    kw = dict(omega_shaft=WJ, length=D, housing=LINER, shaft=SLEEVE, supply_pressure=1e4,
              options=FiniteJournalOptions(n=OPT.n, m=OPT.m, linear_solver="dense"), cavitation="jfo",
              supply_angle=2.0)
    co = vjax.journal_coefficients(R, C, ETA, LOAD, [0.0, 100.0], **kw)
    assert float(np.min(np.asarray(co.steady.film_fraction))) < 0.9
    position = lambda load: np.asarray(journal_bearing(R, C, ETA, load, **kw).position)     # noqa: E731
    h = 1e-5
    along = (position(LOAD * (1 + h)) - position(LOAD * (1 - h))) / (2 * h * W_HALF)     # d position / d W_y
    K = np.asarray(co.stiffness[0])
    compliance = -np.linalg.inv(K)[:, 1]          # LOAD points along -y
    assert np.max(np.abs(along - compliance)) < 1e-7 * np.abs(compliance).max(), (along, compliance)
    assert np.max(np.abs(np.asarray(co.stiffness[1]) - K)) > 0.05 * np.abs(K).max()
