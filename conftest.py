"""Tests and doctests run in float64. (Strict dtype promotion is not used: it rejects
float64 * 1j, which the complex-modulus code needs everywhere.)"""
import atexit
import gc
import os
import shutil
import tempfile

# One BLAS thread per process: the suite runs one pytest-xdist worker per core, and the
# OpenBLAS bundled with scipy (jaxlib's dense LU calls it) then oversubscribes the cores,
# making each dense solve 10-20x slower. Set before numpy loads it; the workers inherit it.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# XLA:CPU's classic fusion emitters for the test processes (and the notebooks and scripts
# they start): most of the suite's time is XLA compiling the solvers' programs, which the
# newer MLIR emitters take about 1.4x as long over (the suite on two cores: 730-780 s -> 570 s),
# to the same results up to round-off. Only when this jaxlib accepts the flag (probed once, in
# the first process that loads this file; pytest-xdist's workers inherit the result);
# XLA_FLAGS=--xla_cpu_use_fusion_emitters=true runs the suite with the default emitters.
if "VJAX_TEST_XLA_FLAGS_CHECKED" not in os.environ:
    os.environ["VJAX_TEST_XLA_FLAGS_CHECKED"] = "1"
    from experiments import _common as _experiments_common
    if "xla_cpu_use_fusion_emitters" not in os.environ.get("XLA_FLAGS", "") and \
            _experiments_common.classic_fusion_emitters_accepted():
        _experiments_common.use_classic_fusion_emitters()

import jax  # noqa: E402
import pytest  # noqa: E402

jax.config.update("jax_enable_x64", True)

# One XLA compilation per program for the whole run. _release_compiled_code (below) drops
# JAX's in-memory caches after each module, and pytest-xdist's workers are separate
# processes: without a shared persistent cache, every module and worker that solves the same
# scene compiles it again (most of the suite's time is XLA compiling the solvers). The first
# process to import this file (pytest-xdist's controller) makes the folder and removes it at
# exit; workers inherit it through the environment. VJAX_TEST_XLA_CACHE="" turns it off.
if "VJAX_TEST_XLA_CACHE" not in os.environ:
    os.environ["VJAX_TEST_XLA_CACHE"] = tempfile.mkdtemp(prefix="vjax-test-xla-")
    atexit.register(shutil.rmtree, os.environ["VJAX_TEST_XLA_CACHE"], ignore_errors=True)
if os.environ["VJAX_TEST_XLA_CACHE"]:
    jax.config.update("jax_compilation_cache_dir", os.environ["VJAX_TEST_XLA_CACHE"])
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.2)   # not the many tiny eager ops
# command-line tools called in-process must not write the user's compilation cache
# (fitting.jax_cache); tests of the cache run the tools in subprocesses without this
os.environ.setdefault("VJAX_NO_CACHE", "1")


def _memory_maps():
    """Memory maps of this process (Linux), or None where /proc is not there."""
    try:
        with open("/proc/self/maps") as f:
            return sum(1 for _ in f)
    except OSError:
        return None


@pytest.fixture(autouse=True, scope="module")
def _release_compiled_code():
    """Drop JAX's compiled functions after a test module once this process holds many memory
    maps. Each XLA:CPU executable maps its code into memory; the whole suite in one process
    compiles enough of them to reach the kernel's limit of memory maps (vm.max_map_count,
    65530), and the next compilation then dies with a segmentation fault. Below a third of
    that limit the compiled functions are kept: a later module calling the same solver skips
    its tracing, lowering and compilation (the persistent cache above skips only the last)."""
    yield
    maps = _memory_maps()
    if maps is None or maps > 20000:
        jax.clear_caches()
        gc.collect()
