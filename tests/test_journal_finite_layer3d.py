"""The finite journal bearing with a 3D bonded layer (``vjax.liner(..., axial="3d")``,
``vjax.sleeve(..., axial="3d")``) or a 3D hole (``vjax.hole(..., axial="3d")``): at the solution each body's displacement is its land
operator (vjax.layer3d_land) applied to the solved pressure, evaluated independently; the
dynamic coefficients at zero whirl are the static stiffness; what the 3D layer does not
support is refused by name."""
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import FiniteJournalOptions, journal_bearing, reference
from vjax.films import film2d

R, C, ETA, WJ = 0.05, 5e-5, 0.01, 100.0
D = 2 * R
SLS = vjax.Material.sls(0.3e9, 3e9, 1e-3, 0.4)
OPT = FiniteJournalOptions(n=32, m=16)
W = 0.5 * float(reference.long_bearing(0.5, R, C, ETA, 0.5 * WJ * (R - C), "reynolds")["load"]) * D
LOAD = jnp.array([0.0, -W])           # a load vector: its derivatives give the static stiffness
LINER, SLEEVE = vjax.liner(SLS, 2e-3, axial="3d"), vjax.sleeve(SLS, 3e-3, axial="3d")
KW = dict(omega_shaft=WJ, length=D, housing=LINER, shaft=SLEEVE, supply_pressure=1e4, options=OPT)


@pytest.fixture(scope="module")
def solution():
    return LINER, SLEEVE, journal_bearing(R, C, ETA, LOAD, **KW)


@pytest.mark.slow
def test_bodies_deform_as_their_3d_land_operators(solution):
    """The bore's displacement is the liner's land operator (pattern fixed: omega 0) and the
    journal's the sleeve's (pattern at -omega_shaft relative to it: each mode at its own
    frequency) applied to the solved pressure, to 1e-9 of the peak; and they differ from the
    plane-strain slices' by more than that (the 3D coupling is seen)."""
    liner, sleeve, s = solution
    assert bool(s.converged)
    for body, radius, omega, u in ((liner, R, 0.0, s.displacement), (sleeve, R - C, -WJ, s.displacement_shaft)):
        op = body.land_operator(radius, OPT.n, OPT.m, D, omega)
        peak = float(jnp.max(jnp.abs(u)))
        assert float(jnp.max(jnp.abs(op(s.pressure) - u))) < 1e-9 * peak
        ring = vjax.Body(body.material, thickness=body.thickness, kind=body.kind).operator(radius, OPT.n, omega)
        slices = jnp.fft.irfft(ring.symbol[:, None] * jnp.fft.rfft(s.pressure, axis=0), OPT.n, axis=0)
        assert float(jnp.max(jnp.abs(slices - u))) > 1e-3 * peak


def test_what_the_3d_layer_does_not_support_is_refused():
    liner = vjax.liner(SLS, 5e-3, axial="3d")
    with pytest.raises(ValueError, match="uniform axial nodes"):
        journal_bearing(R, C, ETA, W, omega_shaft=WJ, length=D, housing=liner,
                        options=FiniteJournalOptions(n=32, m=16, spacing="cosine"))
    with pytest.raises(ValueError, match="axial"):
        vjax.liner(SLS, 5e-3, axial="3D")
    assert vjax.liner(SLS, 5e-3).axial == "slices"


@pytest.mark.slow
def test_coefficients_at_zero_whirl_are_the_static_stiffness():
    """K(0) of the bearing with a 3D bore (a hole through a body of the land's thickness, its
    plane mode 1 held at ref_length = R, not the default 1 m: the whirl response must use it too;
    it carries the journal past the clearance, 0.6 c of it its rigid translation)
    at rest and a 3D sleeve turning with the shaft, from the bodies' whirl responses, is the
    inverse of jax.jacfwd of the steady position with respect to the load vector (implicit
    derivatives through the solve) to 1e-7; K at 100 rad/s differs (the polymer's frequency
    dependence)."""
    bore = vjax.hole(vjax.Material.sls(3e9, 3e10, 1e-3, 0.4), ref_length=R, axial="3d")    # SLS x 10: eps 1.18
    kw = dict(KW, housing=bore)
    J = np.asarray(jax.jit(jax.jacfwd(lambda load: journal_bearing(R, C, ETA, load, **kw).position))(LOAD))
    co = vjax.journal_coefficients(R, C, ETA, LOAD, [0.0, 100.0], **kw)
    K = np.linalg.inv(J)
    assert np.max(np.abs(np.asarray(co.stiffness[0]) - K)) < 1e-7 * np.abs(K).max()
    assert np.max(np.abs(np.asarray(co.stiffness[1] - co.stiffness[0]))) > 1e-3 * np.abs(K).max()


@pytest.mark.slow
def test_asperities_load_the_3d_bodies():
    """Mixed lubrication on 3D bodies (issue 43: every body, in slices and in 3D): a slow journal
    whose asperities carry a part of the load; the liner's and the sleeve's displacements are
    their land operators applied to the film's and the asperities' pressure together, to 1e-9
    of the peak, not to the film's alone (the asperities' share is felt), and the two
    pressures balance the load."""
    rough = vjax.Roughness.from_surfaces(0.0, 1e-6, 210e9, 0.3, 3e9, 0.4)
    w = 0.3
    s = journal_bearing(R, C, ETA, LOAD, omega_shaft=w, length=D, housing=LINER, shaft=SLEEVE, roughness=rough,
                        options=FiniteJournalOptions(n=32, m=8))
    assert bool(s.converged) and 0.05 < float(s.asperity_share) < 0.95
    total = s.pressure + s.asperity_pressure
    for body, radius, omega, u in ((LINER, R, 0.0, s.displacement), (SLEEVE, R - C, -w, s.displacement_shaft)):
        op = body.land_operator(radius, 32, 8, D, omega)
        peak = float(jnp.max(jnp.abs(u)))
        assert float(jnp.max(jnp.abs(op(total) - u))) < 1e-9 * peak
        assert float(jnp.max(jnp.abs(op(s.pressure) - u))) > 1e-3 * peak
    F, _ = film2d.resultants(total, 2 * jnp.pi * jnp.arange(32) / 32, s.z, R)     # grid axes
    assert abs(float(jnp.hypot(*F)) / W - 1) < 1e-8
