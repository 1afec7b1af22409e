"""Tests and doctests run in float64. (Strict dtype promotion is not used: it rejects
float64 * 1j, which the complex-modulus code needs everywhere.)"""
import os

import jax

jax.config.update("jax_enable_x64", True)
# command-line tools called in-process must not write the user's compilation cache
# (fitting.jax_cache); tests of the cache run the tools in subprocesses without this
os.environ.setdefault("VJAX_NO_CACHE", "1")
