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

# The fast tier (the default `-m "not slow"`, the README's command) compiles with XLA:CPU's LLVM
# optimization passes off (--xla_backend_optimization_level=0): most of its time is XLA compiling
# programs that then run for a fraction of a second, and LLVM's passes were about half of each
# compile (a finite bearing's Newton: 5.1 -> 2.4 CPU-s; the pin, roller and journal dynamics
# tests: 61 -> 25 CPU-s, the n = 512 ones included, whose heavy work is in XLA's library calls).
# The whole tier: 585 -> 369-406 CPU-s, every test passing (docs/benchmarks.md, "Fast tier
# (issue 42)"). Where compared, results agree with the default level's to round-off (1e-16 to
# 4e-15 of the largest value; a converged pin pressure 2e-12). Not everywhere: with the classic
# emitters above, level 0 makes the roller on n = 4096 per ring produce non-finite values (the
# slow tier's test_roller.py::test_torque_is_resolved_on_a_coarse_grid; either flag alone
# converges; the roller's own program now takes level 1 whatever XLA_FLAGS says,
# vjax._core.xla.NOT_LEVEL_0), so rerun a fast test that fails with non-finite values with
# XLA_FLAGS=--xla_backend_optimization_level=2 before looking for the bug in vjax. The slow tier
# keeps JAX's default, so `.ci/run` still checks vjax compiled as users compile it. Set before
# pytest-xdist starts its workers (they inherit it) and before any test module starts JAX's
# backend; an xla_backend_optimization_level given in XLA_FLAGS is left as it is.
FAST_TIER_XLA_FLAGS = "--xla_backend_optimization_level=0"


@pytest.hookimpl(tryfirst=True)
def pytest_configure(config):
    flags = os.environ.get("XLA_FLAGS", "")
    if config.option.markexpr == "not slow" and "xla_backend_optimization_level" not in flags:
        os.environ["XLA_FLAGS"] = f"{flags} {FAST_TIER_XLA_FLAGS}".strip()
    _pin_worker()
    # JAX's tracing makes millions of short-lived objects: at Python's default threshold (700
    # allocations) the cyclic collector's young passes are a few percent of a compile-bound run
    gc.set_threshold(50_000)


def _pin_worker():
    """A pytest-xdist worker on a core of its own when there are as many cores as workers, before
    JAX's backend starts (:func:`experiments._common.pin_to_core`)."""
    worker, count = os.environ.get("PYTEST_XDIST_WORKER", ""), os.environ.get("PYTEST_XDIST_WORKER_COUNT", "")
    if worker.startswith("gw") and count.isdigit():
        from experiments import _common
        _common.pin_to_core(int(worker[2:]), int(count))


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
# (fitting.shared.jax_cache); tests of the cache run the tools in subprocesses without this
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


# The slow tier (`python -m pytest -m slow`; the default run excludes it through pyproject's
# addopts, `.ci/run` runs both tiers). Most slow tests carry `@pytest.mark.slow` in their own
# file; the ones below are marked here because their files were being edited by others when
# the tiers were drawn. Node ids relative to the repository root; a listed id that no longer
# exists fails the collection, so the list cannot silently go stale.
SLOW_TESTS = (
    # each notebook re-executed in a Jupyter kernel (30-70 s each); the scenes they show are
    # checked in the fast tier by the scene tests
    "tests/test_notebooks.py::test_stored_outputs_are_current",
    # the finite bearing's coefficients through the CLI; the long one keeps vjax-bearing fast
    "tests/test_bearing_cli.py::test_finite_journal_coefficients_read_back",
    "tests/test_export.py::test_melt_with_three_terms_has_no_equilibrium_modulus",
    # float32 without NaN stays fast for the pin (tests/test_pin.py)
    "tests/test_roughness.py::test_float32_runs_without_nan",
    # single parametrizations: the same checks stay fast for the rigid and half-Sommerfeld
    # bearings, and for the pin and the long journal
    "tests/test_journal_krylov.py::test_same_solution_as_dense[liner and sleeve]",
    "tests/test_journal_krylov.py::test_same_solution_as_dense[jfo, fixed groove]",
    "tests/test_journal_krylov.py::test_same_solution_as_dense[thesis HS (soft SLS bore)]",
    "tests/test_contract.py::test_failure_path_inside_and_outside_jit[roller_bearing]",
    # the ISO 7902 case whose substitution diverges (its slope against the peer); 1500 rpm stays fast
    "tests/test_thermal.py::test_iso7902_against_an_independent_peer[1.0-6000-1000000.0]",
    "tests/test_journal_dynamics.py::test_rigid_closed_form[0.1-half_sommerfeld]",
)


@pytest.hookimpl(tryfirst=True)   # before `-m` deselects by marker
def pytest_collection_modifyitems(config, items):
    listed = set(SLOW_TESTS)
    found = set()
    modules = {}
    for item in items:
        modules.setdefault(item.nodeid.split("::")[0], getattr(item, "module", None))
        for nodeid in (item.nodeid, item.nodeid.split("[")[0]):
            if nodeid in listed:
                item.add_marker(pytest.mark.slow)
                found.add(nodeid)
    # A listed test must exist: its function in its file whenever that file was collected, and
    # each listed parametrization when whole files were collected (no -k, no node ids given).
    whole = not config.getoption("keyword") and not any("::" in a for a in config.args)
    missing = []
    for nodeid in sorted(listed - found):
        path, _, name = nodeid.partition("::")
        if path in modules and (whole or not hasattr(modules[path], name.split("[")[0])):
            missing.append(nodeid)
    if missing:
        raise pytest.UsageError("conftest.py SLOW_TESTS lists tests that do not exist: "
                                + ", ".join(missing))
