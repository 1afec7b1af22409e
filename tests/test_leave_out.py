"""Each scene computes only what it needs, checked on what it builds while tracing.

Spies record the calls a scene makes while JAX traces it (caches cleared first, so the
scene's Python runs): which ring operators it builds (one per deformable body, none for a
rigid one), whether it computes a creep spectrum (only a viscoelastic material has memory
terms), and whether it assembles Reynolds cell equations (only the lubricated scene).
What is checked is what gets computed, not how the program spells it.
"""
import collections

import jax
import jax.extend
import jax.numpy as jnp
import pytest

import vjax
from vjax import Material, PinOptions, RollerOptions, JournalOptions

N = 64
ELASTIC = Material.elastic(1e6, 0.5)
SLS = Material.sls(1e6, 1e7, 0.01, 0.5)


@pytest.fixture
def built(monkeypatch):
    """Trace ``fn`` and return what it built: ring operators by kind, "memory" (a
    viscoelastic response), "reynolds" (cell equations)."""
    calls = collections.Counter()

    def spy(name, owner, attr, key=None):
        original = getattr(owner, attr)

        def wrapper(*args, **kwargs):
            calls[name if key is None else key(*args, **kwargs)] += 1
            return original(*args, **kwargs)
        monkeypatch.setattr(owner, attr, wrapper)

    spy("ring_operator", vjax.bodies.body, "ring_operator", key=lambda kind, *a, **k: kind)
    # the viscoelastic response: the complex compliance (periodic memory) or the creep spectrum
    spy("memory", vjax.material.Material, "creep_spectrum")
    spy("memory", vjax.material.Material, "compliance")
    spy("reynolds", vjax.reynolds, "cell_equations")

    def trace(fn, *args):
        jax.clear_caches()
        calls.clear()
        jax.make_jaxpr(fn)(*args)
        return dict(calls)
    return trace


def _pin(material, memory="periodic"):
    return vjax.pin_in_hole(material, 0.08, 0.005, 2800.0, omega_shaft=-100 / 15, memory=memory,
                            options=PinOptions(n=N), throw=False).torque


def _roller(housing, shaft):
    return lambda: vjax.roller_bearing(housing, shaft, 6e-3, 4e-3, 2e-3, 9, 39.0, omega_shaft=10.0,
                                       options=RollerOptions(n=N), throw=False).torque


def _journal(housing, shaft):
    return lambda: vjax.journal_bearing(0.05, 5e-5, 0.01, 2e4, housing=housing, shaft=shaft, omega_shaft=100.0,
                                        options=JournalOptions(n=N), throw=False).eccentricity


def test_elastic_material_has_no_memory(built):
    for memory in ("periodic", "thesis", 1e6):
        assert "memory" not in built(lambda: _pin(ELASTIC, memory)), memory
        assert built(lambda: _pin(SLS, memory)).get("memory", 0) >= 1, memory
    # and an elastic operator does not depend on the speed at all
    symbol = lambda w: vjax.ring_operator("hole", ELASTIC, 0.08, N, omega=w, memory="thesis").symbol
    assert float(jax.grad(lambda w: jnp.sum(jnp.abs(symbol(w))))(3.0)) == 0.0


def test_pin_builds_the_housing_only(built):
    assert {k: v for k, v in built(lambda: _pin(SLS)).items() if k != "memory"} == {"hole": 1}


def test_roller_builds_one_operator_per_deformable_ring(built):
    assert {k: v for k, v in built(_roller(SLS, SLS)).items() if k != "memory"} == {"hole": 1, "cylinder": 1}
    assert "hole" not in built(_roller(None, SLS))
    assert "cylinder" not in built(_roller(SLS, None))


def test_rigid_journal_builds_no_operator(built):
    assert set(built(_journal(None, None))) == {"reynolds"}
    hs = built(_journal(SLS, None))
    assert hs.get("hole") == 1 and "cylinder" not in hs
    assert built(_journal(SLS, SLS)).get("cylinder") == 1


def test_only_the_lubricated_scene_builds_a_reynolds_system(built):
    assert "reynolds" not in built(lambda: _pin(SLS))
    assert "reynolds" not in built(_roller(SLS, SLS))
    assert built(_journal(None, None)).get("reynolds", 0) >= 1


def _largest_matrix(fn):
    """Largest min(rows, cols) over the 2-D (or higher) values of the traced program."""
    best = 0

    def walk(jaxpr):
        nonlocal best
        for eqn in jaxpr.eqns:
            for v in eqn.outvars:
                shape = getattr(v.aval, "shape", ())
                if len(shape) >= 2:
                    best = max(best, min(sorted(shape)[-2:]))
            for p in eqn.params.values():
                for sub in (p if isinstance(p, (tuple, list)) else (p,)):
                    if isinstance(sub, jax.extend.core.ClosedJaxpr):
                        walk(sub.jaxpr)
                    elif isinstance(sub, jax.extend.core.Jaxpr):
                        walk(sub)
    walk(jax.make_jaxpr(fn)().jaxpr)
    return best


def test_dry_scenes_need_memory_linear_in_n():
    """Matrix-free contact solves: no n x n array (memory O(n), not O(n^2))."""
    assert _largest_matrix(lambda: _pin(SLS)) < N
    assert _largest_matrix(_roller(SLS, SLS)) < N
