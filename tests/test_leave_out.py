"""Each scene builds only what it needs, shown on the traced programs (``jax.make_jaxpr``).

No global counters and no timing: a jaxpr lists every primitive the compiled program will
run (sub-jaxprs of jit, loops, conditionals and custom derivatives included), so what a
scene leaves out is simply absent from it.

- an elastic material: no memory terms, i.e. no creep-spectrum bisection (a ``scan``) and no
  exponential of the memory factor in the operator symbol, for either memory model;
- a ring kernel (closed-form element integral, A.45/A.60) costs exactly three ``log``
  primitives (the safe x log x of its antiderivatives): one kernel in a pin scene, two in a
  roller bearing with two deformable rings, one when a ring is rigid;
- a rigid body builds no operator: no FFT for it (a rigid journal bearing has none at all);
- a dry scene (pin, roller) builds no Reynolds system: matrix-free, no array of n x n or
  larger anywhere, while the journal bearing's Newton system is an (n + 2) x (n + 2) LU.
"""
import collections

import jax
import jax.extend
import jax.numpy as jnp

import vjax
from vjax import Material

N = 64
ELASTIC = Material.elastic(1e6, 0.5)
SLS = Material.sls(1e6, 1e7, 0.01, 0.5)
LOGS_PER_KERNEL = 3


def _eqns(jaxpr, out):
    for eqn in jaxpr.eqns:
        out.append(eqn)
        for v in eqn.params.values():
            for sub in (v if isinstance(v, (tuple, list)) else (v,)):
                if isinstance(sub, jax.extend.core.ClosedJaxpr):
                    _eqns(sub.jaxpr, out)
                elif isinstance(sub, jax.extend.core.Jaxpr):
                    _eqns(sub, out)
    return out


def eqns(fn, *args):
    """Every equation of the traced program, sub-jaxprs included."""
    return _eqns(jax.make_jaxpr(fn)(*args).jaxpr, [])


def count(fn, *args):
    return collections.Counter(e.primitive.name for e in eqns(fn, *args))


def largest_matrix(fn, *args):
    """Largest min(rows, cols) over the 2-D (or higher) arrays any equation produces."""
    best = 0
    for e in eqns(fn, *args):
        for v in e.outvars:
            shape = getattr(v.aval, "shape", ())
            if len(shape) >= 2:
                best = max(best, min(sorted(shape)[-2:]))
    return best


def _symbol(material, memory):
    return lambda w: vjax.ring_operator("hole", material, 0.08, N, omega=w, memory=memory).symbol


# ---------------------------------------------------------------------- elastic: no memory
def test_elastic_material_builds_no_memory_terms():
    for memory in ("periodic", "thesis", 1e6):
        el = count(_symbol(ELASTIC, memory), 1.0)
        assert el["scan"] == 0 and el["while"] == 0, memory        # no creep-spectrum bisection
        assert el["exp"] == 0, memory                               # no memory factor
        assert el["log"] == LOGS_PER_KERNEL                         # the kernel itself
    ve = count(_symbol(SLS, "thesis"), 1.0)
    assert ve["scan"] + ve["while"] >= 1 and ve["exp"] >= 1         # the viscoelastic one has them
    # and an elastic operator does not depend on the speed at all
    grad = jax.grad(lambda w: jnp.sum(_symbol(ELASTIC, "thesis")(w)))(3.0)
    assert float(grad) == 0.0


def test_elastic_pin_scene_has_no_memory_terms():
    pin = lambda m: vjax.pin_in_hole(m, 0.08, 0.075, 2800.0, 100.0, n=N, memory="thesis", throw=False).torque
    el, ve = count(pin, ELASTIC), count(pin, SLS)
    assert el["exp"] == 0 and el["scan"] == 0
    assert ve["exp"] >= 1 and ve["scan"] >= 1


# ---------------------------------------------------------------------- kernels per scene
def test_one_ring_kernel_costs_three_logs():
    assert count(lambda: vjax.ring_operator("hole", SLS, 0.08, N).symbol)["log"] == LOGS_PER_KERNEL
    assert count(lambda: vjax.ring_operator("cylinder", SLS, 0.08, N).symbol)["log"] == LOGS_PER_KERNEL


def test_pin_scene_builds_one_ring_kernel():
    c = count(lambda m: vjax.pin_in_hole(m, 0.08, 0.075, 2800.0, 100.0, n=N, throw=False).torque, SLS)
    assert c["log"] == LOGS_PER_KERNEL        # the hole's kernel only: no inner-ring (cylinder) kernel


def _roller(outer, inner):
    return lambda: vjax.roller_bearing(outer, inner, 6e-3, 4e-3, 2e-3, 9, 39.0, n=N, throw=False).torque


def test_roller_builds_one_kernel_per_deformable_ring_and_none_for_a_rigid_one():
    both = count(_roller(SLS, SLS))
    assert both["log"] == 2 * LOGS_PER_KERNEL
    for outer, inner in ((None, SLS), (SLS, None)):
        one = count(_roller(outer, inner))
        assert one["log"] == LOGS_PER_KERNEL
        # the rigid ring has no operator and no contact solve: half the FFTs
        assert one["fft"] * 2 == both["fft"]


# ---------------------------------------------------------------------- rigid: no operator
def _journal(bearing, journal, n=N):
    return lambda: vjax.journal_bearing(0.05, 5e-5, 0.01, 100.0, load=2e4, n=n, bearing=bearing, journal=journal,
                                        throw=False).eccentricity


def test_rigid_bodies_build_no_operator():
    rigid = count(_journal(None, None))
    hs, ss = count(_journal(SLS, None)), count(_journal(SLS, SLS))
    assert rigid["fft"] == 0 and rigid["log"] == 0       # no ring kernel, no FFT at all
    assert hs["log"] == LOGS_PER_KERNEL and ss["log"] == 2 * LOGS_PER_KERNEL
    assert 0 < hs["fft"] < ss["fft"]


# ---------------------------------------------------------------------- dry: no Reynolds
def test_dry_scenes_build_no_reynolds_system():
    pin = lambda m: vjax.pin_in_hole(m, 0.08, 0.075, 2800.0, 100.0, n=N, throw=False).torque
    # matrix-free contact solves: nothing of size n x n (Z + 1 = 10 Newton unknowns in the roller)
    assert largest_matrix(pin, SLS) < N
    assert largest_matrix(_roller(SLS, SLS)) < N
    for fn, args in ((pin, (SLS,)), (_roller(SLS, SLS), ())):
        lus = [e for e in eqns(fn, *args) if e.primitive.name == "lu"]
        assert all(max(e.invars[0].aval.shape) <= 10 for e in lus)
    # the lubricated scene does assemble its (n + 2) x (n + 2) Newton (Reynolds) system
    lus = [e for e in eqns(_journal(SLS, None)) if e.primitive.name == "lu"]
    assert any(e.invars[0].aval.shape == (N + 2, N + 2) for e in lus)
