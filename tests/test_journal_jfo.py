"""Mass-conserving (JFO / Elrod-Adams) cavitation of the journal bearing (cavitation="jfo").

References: the Reynolds-condition solution where the two must agree (the film re-forms only
at a groove at the widest gap), mass conservation (the flux through every face of a steady
film is the same), the power balance, finite differences of the solution, and jax.jacfwd of
the steady solution for the dynamic coefficients' static limit.
"""
import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from vjax import JournalOptions, journal_bearing, journal_coefficients

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
OPT = JournalOptions(n=256)


def solve(load, cavitation, **kw):
    return journal_bearing(R, C, ETA, load, omega_shaft=WJ, cavitation=cavitation, options=kw.pop("options", OPT),
                           **kw)


def face_flux(s):
    """Mass flux through the face between cells i and i + 1 (m^2/s), from the result's fields
    only: Poiseuille part from the pressure, Couette part carrying the upwind liquid."""
    n = s.pressure.shape[0]
    h, p, f = map(np.asarray, (s.film, s.pressure, s.film_fraction))
    v = 0.5 * WJ * (R - C)
    hf = 0.5 * (h + np.roll(h, -1))
    dpds = (np.roll(p, -1) - p) / (R * 2 * np.pi / n)
    return -hf**3 * dpds / (12 * ETA) + v * hf * f


@pytest.mark.parametrize("load", [2e4, 1e5, 6e5])      # eps ~ 0.03, 0.15, 0.74
def test_equal_to_reynolds_with_groove_at_widest_gap(load):
    """Groove at the widest gap (the default, turning with the line of centres): the film
    re-forms only there, so JFO and Reynolds give the same pressure; JFO's cavity is a
    striated film (fraction < 1) that conserves mass, Reynolds' loses flow."""
    jfo, rey = solve(load, "jfo"), solve(load, "reynolds")
    assert bool(jfo.converged)
    # the same film but for the rupture's cell: Reynolds' within it, JFO's on a face (measured:
    # eps 1.6e-7 ... 3.2e-6, attitude up to 1.5e-5 rad, pressure up to 3.2e-5 of the peak)
    assert abs(float(jfo.eccentricity - rey.eccentricity)) < 1e-5
    assert abs(float(jfo.attitude_angle - rey.attitude_angle)) < 5e-5
    assert np.max(np.abs(np.asarray(jfo.pressure - rey.pressure))) < 1e-4 * float(jnp.max(rey.pressure))
    cavity = np.asarray(jfo.film_fraction) < 1.0 - 1e-12
    assert cavity.sum() > 10 and np.all(np.asarray(jfo.film_fraction) > 0)
    assert np.all(np.asarray(jfo.pressure)[cavity] == 0)            # p (1 - f) = 0
    q = face_flux(jfo)
    assert np.max(np.abs(q - q.mean())) < 1e-9 * abs(q.mean())      # steady: one flux everywhere
    assert abs(float(jfo.supply_flow)) < 1e-9 * abs(q.mean())      # no side leakage: nothing supplied
    assert abs(float(rey.supply_flow)) > 1e-3 * abs(q.mean())      # Reynolds' cavity loses flow
    # the striated cavity shears only its liquid: less friction, and the power still balances
    assert abs(float(jfo.torque_shaft)) < abs(float(rey.torque_shaft))
    assert abs(-WJ * float(jfo.torque_shaft) - float(jfo.dissipation_fluid)) < 1e-9 * float(jfo.dissipation_fluid)


@pytest.mark.slow
@pytest.mark.parametrize("supply_angle", [2.0, 5.5])
def test_groove_away_from_widest_gap(supply_angle):
    """A groove fixed in the bearing away from the widest gap. Before the widest gap (2.0 rad
    from the load direction, in the diverging film) the film ruptures at the groove and the
    striated film carries only the liquid that left the pressure zone: it re-forms where
    that liquid meets the closing gap, later than Reynolds' film, which re-forms full wherever
    the pressure can rise. Past the widest gap (5.5 rad) the groove cuts into the converging
    film and the cavity before it is fed from upstream only. In both the pressurized arc is
    shorter than Reynolds', so the journal runs more eccentric; mass is conserved (one flux
    through every face)."""
    jfo = solve(1e5, "jfo", groove="fixed", supply_angle=supply_angle)
    rey = solve(1e5, "reynolds", groove="fixed", supply_angle=supply_angle)
    assert bool(jfo.converged)
    assert float(jfo.eccentricity) > float(rey.eccentricity) + 0.05
    q = face_flux(jfo)
    assert np.max(np.abs(q - q.mean())) < 1e-8 * abs(q.mean())
    # the pressurized arc is shorter than Reynolds' (it re-forms later or is starved)
    assert np.sum(np.asarray(jfo.pressure) > 0) < np.sum(np.asarray(rey.pressure) > 0)
    if supply_angle == 2.0:
        # one cavity, from the groove on (the film ruptures at once in the diverging gap)
        f = np.asarray(jfo.film_fraction)
        k = np.flatnonzero(f < 1.0 - 1e-12)
        p = np.asarray(jfo.pressure)
        assert np.all(np.diff(k) == 1) and abs(p[k[0] - 1]) <= 1e-12 * p.max()

@pytest.mark.slow
def test_gradient_against_finite_differences():
    """d eps / d viscosity through the implicit derivative of the JFO solve (groove fixed,
    the film re-forming inside the bearing), against central differences."""
    eps = lambda eta, initial=None: journal_bearing(R, C, eta, 1e5, omega_shaft=WJ, cavitation="jfo", groove="fixed",
                                                    supply_angle=2.0, initial=initial,
                                                    options=JournalOptions(n=128)).eccentricity
    # the derivative is implicit, at the root: Newton may start there (then the differentiated
    # solve compiles without the nested coarse start), jitted to trace it as one program
    start = journal_bearing(R, C, ETA, 1e5, omega_shaft=WJ, cavitation="jfo", groove="fixed", supply_angle=2.0,
                            options=JournalOptions(n=128))
    g = float(jax.jit(jax.grad(lambda eta: eps(eta, start)))(ETA))
    d = 1e-5 * ETA
    fd = (float(eps(ETA + d)) - float(eps(ETA - d))) / (2 * d)
    assert abs(g - fd) < 1e-5 * abs(fd)


def _position(kw, initial):
    """Journal centre (m) against the load, for jax.jacfwd, jitted (traced as one program). Newton
    starts from ``initial``, the steady solution at the load it is differentiated at: the
    derivative is implicit, at the root, and the solve compiles without the nested coarse start."""
    @jax.jit
    def position(W):
        s = journal_bearing(R, C, ETA, W, initial=initial, **kw)
        g = s.line_of_centres_angle
        return s.eccentricity * C * jnp.stack([jnp.cos(g), jnp.sin(g)])
    return position


@pytest.mark.slow
def test_dynamic_coefficients():
    """JFO stiffness at zero whirl = the static stiffness (jax.jacfwd of the steady solution);
    with the groove at the widest gap the cavity's liquid flows into the groove, so the
    coefficients equal Reynolds' at every whirl frequency (up to the rupture's cell). With the film re-forming inside the
    bearing they depend on the whirl frequency even for a rigid bearing: the cavity carries
    its liquid to the re-formation point with a delay of the order of its arc over the
    entrainment rate (here ~0.05 s), so the re-formation point, and with it the force,
    follows slow whirl (static stiffness) but not fast whirl."""
    load = jnp.array([0.0, -1e5])
    kw = dict(omega_shaft=WJ, options=JournalOptions(n=128))
    whirl = [0.0, 30.0, 300.0]
    jfo = journal_coefficients(R, C, ETA, load, whirl, cavitation="jfo", **kw)
    rey = journal_coefficients(R, C, ETA, load, whirl, cavitation="reynolds", **kw)
    K = np.linalg.inv(np.asarray(jax.jacfwd(_position(dict(kw, cavitation="jfo"), jfo.steady))(load)))
    assert np.max(np.abs(np.asarray(jfo.stiffness[0]) - K)) < 1e-7 * np.abs(K).max()
    # up to the rupture's cell: JFO's on a face gives its K and C an O(dtheta) error that
    # jumps with the grid (here 4.6e-4 and 2.2e-3), Reynolds' within its cell does not
    for a, b in ((jfo.stiffness, rey.stiffness), (jfo.damping, rey.damping)):
        assert np.max(np.abs(np.asarray(a) - np.asarray(b))) < 5e-3 * np.abs(np.asarray(b)).max()

    kw = dict(omega_shaft=WJ, groove="fixed", supply_angle=2.0, options=JournalOptions(n=128), cavitation="jfo")
    co = journal_coefficients(R, C, ETA, 1e5, [0.0, 1e-3, 1e3], **kw)
    along = np.asarray(jax.jacfwd(_position(kw, co.steady))(1e5))     # compliance along the load (-y)
    from_coefficients = np.linalg.solve(np.asarray(co.stiffness[0]), np.array([0.0, -1.0]))
    assert np.max(np.abs(along - from_coefficients)) < 1e-7 * np.abs(along).max()
    Z = np.asarray(co.impedance)
    assert np.max(np.abs(Z[1] - Z[0])) < 1e-3 * np.abs(Z[0]).max()       # continuous at slow whirl
    assert np.max(np.abs(Z[2].real - Z[0].real)) > 0.3 * np.abs(Z[0].real).max()   # fast whirl differs
