"""XLA options for vjax's largest compiled programs (internal).

Most of a scene's first call is XLA compiling its solver: a whole damped Newton with its
equations, their block Jacobian and its factorization in one program. On the CPU backend the
options below compile such programs much faster, to the same results up to round-off
(measurements in docs/benchmarks.md: a rigid finite bearing on 256 x 64, its two Newton
programs, 7.1 s of XLA at the defaults, 2.6 s with these and a smaller fine-grid program):

- ``xla_cpu_use_fusion_emitters=False``: XLA:CPU's classic loop emitters in place of the
  MLIR fusion emitters (about 1.5x faster to compile for these programs; as fast to run,
  the long JFO bearing's ~10 % slower);
- ``xla_backend_optimization_level=1`` (:data:`CLASSIC`): faster to compile than the default
  level, as fast to run for these loops of small dense steps;
- ``xla_backend_optimization_level=0`` (:data:`START`) for programs that run briefly (a coarse
  grid's cold start): 2-3x faster to compile, several times slower to run.

:func:`jit` is ``jax.jit`` with these options. An option the user sets in ``XLA_FLAGS`` is
theirs (the per-program option would override it, so it is not passed), but for one a program
needs to compute correctly (:data:`NOT_LEVEL_0`); on other backends, or with a jaxlib that
does not know an option, none is passed.
"""
from __future__ import annotations

import functools
import os

import jax

from .checks import is_concrete

CLASSIC = {"xla_cpu_use_fusion_emitters": False, "xla_backend_optimization_level": 1}   # solver programs
START = {**CLASSIC, "xla_backend_optimization_level": 0}     # a start's program: runs briefly
# XLA:CPU at optimization level 0 (jaxlib 0.10.2) computes a NaN Jacobian where jacfwd runs
# inside a conditional of Newton's loop (the roller's kept-Jacobian Newton; the same Jacobian
# outside it is finite): programs with that structure take level 1 whatever XLA_FLAGS says
NOT_LEVEL_0 = {"xla_backend_optimization_level": 1}


@functools.lru_cache(maxsize=None)
def _accepted(items: tuple, required: tuple = ()) -> tuple:
    """The options of ``items`` to pass: none off the CPU backend or where the installed jaxlib
    rejects them (probed once on a trivial program), and none that XLA_FLAGS sets; those of
    ``required`` whatever XLA_FLAGS says."""
    if jax.default_backend() != "cpu":
        return ()
    flags = os.environ.get("XLA_FLAGS", "")
    keys = {k for k, _ in required}
    items = tuple((k, v) for k, v in items if f"--{k}=" not in flags and k not in keys) + required
    try:
        jax.jit(lambda x: x + 1, compiler_options=dict(items)).lower(1.0).compile()
    except Exception:        # an older jaxlib: an unknown option, or no compiler_options at all
        return ()
    return items


def jit(fun=None, *, options=CLASSIC, required=None, **jit_kwargs):
    """``jax.jit(fun, **jit_kwargs)`` compiled with the XLA ``options`` (:data:`CLASSIC`,
    :data:`START`) that apply here (:func:`_accepted`), and the ``required`` ones
    (:data:`NOT_LEVEL_0`) even where XLA_FLAGS sets them, decided at the first call (after the
    user's JAX configuration); inside another transformation, plain ``jax.jit``. Usable as a
    decorator, with or without arguments."""
    if fun is None:
        return functools.partial(jit, options=options, required=required, **jit_kwargs)

    plain = jax.jit(fun, **jit_kwargs)

    @functools.lru_cache(maxsize=None)
    def compiled():
        chosen = _accepted(tuple(sorted(options.items())), tuple(sorted((required or {}).items())))
        return jax.jit(fun, **jit_kwargs, compiler_options=dict(chosen)) if chosen else plain

    def choose(args, kwargs):
        # inside another transformation (jit, grad, vmap) the program is the caller's: JAX takes
        # compiler options only on a top-level jit
        return compiled() if is_concrete((args, kwargs)) else plain

    @functools.wraps(fun)
    def call(*args, **kwargs):
        return choose(args, kwargs)(*args, **kwargs)
    call.lower = lambda *args, **kwargs: choose(args, kwargs).lower(*args, **kwargs)
    return call
