"""Tests and doctests run in float64. (Strict dtype promotion is not used: it rejects
float64 * 1j, which the complex-modulus code needs everywhere.)"""
import jax

jax.config.update("jax_enable_x64", True)
