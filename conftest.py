"""Tests and doctests run in float64. (Strict dtype promotion is not used: it rejects
float64 * 1j, which the complex-modulus code needs everywhere.)"""
import gc
import os

import jax
import pytest

jax.config.update("jax_enable_x64", True)
# command-line tools called in-process must not write the user's compilation cache
# (fitting.jax_cache); tests of the cache run the tools in subprocesses without this
os.environ.setdefault("VJAX_NO_CACHE", "1")


@pytest.fixture(autouse=True, scope="module")
def _release_compiled_code():
    """Drop JAX's compiled functions after each test module. Each XLA:CPU executable maps
    its code into memory; the whole suite in one process compiles enough of them to reach
    the kernel's limit of memory maps (vm.max_map_count, 65530), and the next compilation
    then dies with a segmentation fault."""
    yield
    jax.clear_caches()
    gc.collect()
