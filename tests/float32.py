"""Helper of the float32 tests: run a snippet in a fresh interpreter without x64 (internal to tests/)."""
import os
import pathlib
import subprocess
import sys
import textwrap

PRELUDE = textwrap.dedent("""
    import warnings; warnings.simplefilter("ignore")
    import jax, numpy as np

    def check(s):
        '''A converged float32 result with no NaN or inf in any field.'''
        leaves = [np.asarray(l, dtype=float) for l in jax.tree_util.tree_leaves(s)]
        assert s.pressure.dtype == np.float32, s.pressure.dtype
        assert bool(s.converged) and all(np.all(np.isfinite(l)) for l in leaves)
""")


def run_in_float32(code: str) -> None:
    """Run ``code`` (after :data:`PRELUDE`: ``check(result)``) with JAX_ENABLE_X64=0 from the
    repository root; it must exit 0 and print "ok"."""
    env = dict(os.environ, JAX_ENABLE_X64="0")
    out = subprocess.run([sys.executable, "-c", PRELUDE + textwrap.dedent(code)], capture_output=True, text=True,
                         env=env, cwd=str(pathlib.Path(__file__).resolve().parents[1]), timeout=300)
    assert out.returncode == 0 and "ok" in out.stdout, out.stderr[-2000:]
