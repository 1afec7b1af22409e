"""The scene contract: the same inputs, result fields and failure path in every scene."""
import dataclasses
import logging

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax import JournalOptions, Material, PinOptions, RollerOptions

SLS = Material.sls(1e6, 1e7, 0.01, 0.5)
COMMON = ("pressure", "displacement", "force", "torque", "iterations", "residual", "result")


def pin(load=2800.0, throw=True, **options):
    return vjax.pin_in_hole(SLS, 0.08, 0.005, load, omega_shaft=-5.0, options=PinOptions(n=64, **options),
                            throw=throw)


# test_roller.py's bearing, materials and grid: the two files then share the roller's compiled
# programs (through the suite's persistent compilation cache) instead of compiling their own
ROLLER_N = 256


def roller(load=39.0, throw=True, **options):
    return vjax.roller_bearing(SLS, SLS, 6e-3, 4e-3, 2e-3, 9, load, omega_shaft=10.0,
                               options=RollerOptions(n=ROLLER_N, **options), throw=throw)


def journal(load=2e4, throw=True, **options):
    return vjax.journal_bearing(0.05, 5e-5, 0.01, load, omega_shaft=100.0, options=JournalOptions(n=32, **options),
                                throw=throw)


def coefficients(load=2e4):
    """The journal's dynamic coefficients, half-Sommerfeld: their linearization re-solves the
    unclipped film (a Newton loop) after the scene's own solve."""
    return vjax.journal_coefficients(0.05, 5e-5, 0.01, load, [0.0, 50.0], omega_shaft=100.0,
                                     cavitation="half_sommerfeld", options=JournalOptions(n=32))


# A load each scene cannot carry within its iteration cap: 50x the pin's and roller's
# design load in one step, and a rigid journal bearing at 1e6 times its load (eps -> 1)
# with a single continuation stage.
IMPOSSIBLE = {"pin_in_hole": (pin, 50 * 2800.0, dict(max_iter=2)),
              "roller_bearing": (roller, 50 * 39.0, dict(max_iter=1)),
              "journal_bearing": (journal, 2e10, dict(max_iter=3, stages=1))}


@pytest.mark.parametrize("scene", [pin, roller, journal])
def test_every_result_has_the_common_fields_and_a_short_repr(scene):
    r = scene()
    names = {f.name for f in dataclasses.fields(r)}
    assert set(COMMON) <= names
    assert bool(r.converged) and int(r.result) == 0 and int(r.iterations) >= 1
    assert np.shape(r.torque) == () and np.shape(r.force) == (2,)
    assert len(repr(r)) < 1500 and "array" in repr(r) and "converged" in r.summary()


@pytest.mark.parametrize("scene", [pin, roller, journal, coefficients])
def test_a_repeated_call_compiles_nothing(scene):
    """A second call with the same shapes reuses every compiled function: no step of a scene
    runs as a new closure through an eager lax loop (the journal's rigid start once cost a
    compilation per call, ~0.1 s, seven times its solve; the coefficients' half-Sommerfeld
    re-solve 5 s per call)."""
    scene()
    compiled = []

    class Collect(logging.Handler):
        def emit(self, record):
            if record.getMessage().startswith("Compiling"):
                compiled.append(record.getMessage()[:120])
    handler = Collect()
    logging.getLogger("jax").addHandler(handler)
    try:
        with jax.log_compiles(True):
            scene()
    finally:
        logging.getLogger("jax").removeHandler(handler)
    assert not compiled, compiled


@pytest.mark.parametrize("name", IMPOSSIBLE)
def test_failure_path_inside_and_outside_jit(name):
    scene, load, caps = IMPOSSIBLE[name]
    r = scene(load, throw=False, **caps)
    assert not bool(r.converged)
    assert np.all(np.isfinite(np.asarray(r.pressure))) and np.isfinite(float(r.torque))
    with pytest.raises(vjax.ConvergenceError, match=f"{name} did not converge") as error:
        scene(load, **caps)
    # outside jit the error carries the unconverged result: no second solve to inspect it
    assert not bool(error.value.solution.converged)
    assert float(error.value.solution.residual) == float(r.residual)
    with pytest.raises(Exception, match=f"{name} did not converge"):
        jax.jit(lambda f: scene(f, **caps).torque)(load).block_until_ready()


def test_under_vmap_one_failed_point_raises_for_the_batch():
    """A tenth of the design load converges in 3 active-set steps, 200 times it needs 7."""
    loads = jnp.array([280.0, 200 * 2800.0])
    ok = jax.vmap(lambda f: pin(f, throw=False, max_iter=5).converged)(loads)
    assert list(np.asarray(ok)) == [True, False]
    with pytest.raises(Exception, match="pin_in_hole did not converge"):
        jax.vmap(lambda f: pin(f, max_iter=5).torque)(loads).block_until_ready()


@pytest.mark.slow
def test_every_scene_warm_starts_from_a_previous_result():
    p0, r0, j0 = pin(), roller(), journal()
    p1 = vjax.pin_in_hole(SLS, 0.08, 0.005, 2800.0, omega_shaft=-5.0, options=PinOptions(n=64), initial=p0)
    r1 = vjax.roller_bearing(SLS, SLS, 6e-3, 4e-3, 2e-3, 9, 39.0, omega_shaft=10.0,
                             options=RollerOptions(n=ROLLER_N), initial=r0)
    j1 = vjax.journal_bearing(0.05, 5e-5, 0.01, 2e4, omega_shaft=100.0, options=JournalOptions(n=32), initial=j0)
    for cold, warm in ((p0, p1), (r0, r1), (j0, j1)):
        assert int(warm.iterations) < int(cold.iterations)
        assert np.isclose(float(warm.torque), float(cold.torque), rtol=1e-8)
