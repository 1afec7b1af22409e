"""The command-line tools' persistent compilation cache (fitting.shared.jax_cache): where it lives,
that a small compilation is stored (the default 1 s threshold would skip it), and that
VJAX_NO_CACHE / --no-cache turn it off. Run in subprocesses: the cache is per process."""
import os
import subprocess
import sys

import pytest

from fitting.shared import jax_cache

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SNIPPET = ("import sys, jax, jax.numpy as jnp\n"
           "from fitting.shared import jax_cache\n"
           "print(jax_cache.enable('--no-cache' in sys.argv))\n"
           "jax.jit(lambda x: jnp.sin(x) * 3.0 + 1.0)(jnp.arange(7.0)).block_until_ready()\n")


def _run(tmp_path, *args, **env):
    e = {k: v for k, v in os.environ.items() if k != "VJAX_NO_CACHE"}
    e.update(XDG_CACHE_HOME=str(tmp_path), PYTHONPATH=ROOT, **env)
    p = subprocess.run([sys.executable, "-c", SNIPPET, *args], env=e, capture_output=True, text=True, check=True)
    return p.stdout.strip()


def _files(path):
    return sum(len(f) for _, _, f in os.walk(path))


def test_cache_dir_follows_xdg(monkeypatch):
    from vjax._core.cache import default_cache_dir
    monkeypatch.setenv("XDG_CACHE_HOME", "/some/where")
    assert default_cache_dir() == os.path.join("/some/where", "vjax", "jax")
    monkeypatch.delenv("XDG_CACHE_HOME")
    assert default_cache_dir() == os.path.join(os.path.expanduser("~"), ".cache", "vjax", "jax")


def test_small_compilations_are_stored_and_switches_turn_it_off(tmp_path):
    cache = tmp_path / "vjax" / "jax"
    assert _run(tmp_path, "--no-cache") == "None" and _files(tmp_path) == 0
    assert _run(tmp_path, VJAX_NO_CACHE="1") == "None" and _files(tmp_path) == 0
    assert _run(tmp_path) == str(cache)
    assert _files(cache) >= 1


EXPORT_SNIPPET = ("import sys, jax, jax.numpy as jnp, numpy as np\n"
                  "jax.config.update('jax_enable_x64', True)\n"
                  "import functools\n"
                  "from fitting.shared import jax_cache\n"
                  "traced = []\n"
                  "@functools.partial(jax.jit, static_argnames='n')\n"
                  "def f(x, pair, *, n):\n"
                  "    traced.append(1)\n"
                  "    return jnp.sin(x) * n + pair[0], jnp.cumsum(x) ** pair[1]\n"
                  "if '--enable' in sys.argv:\n"
                  "    jax_cache.enable()\n"
                  "n = 4 if '--other-static' in sys.argv else 3\n"
                  "out = jax_cache.call(f, (np.linspace(0.1, 2.0, 6), (2.0, 3)), n=n)\n"
                  "print(len(traced), [float(v).hex() for o in out for v in np.asarray(o)])\n")


def _export_run(tmp_path, *args):
    e = {k: v for k, v in os.environ.items() if k != "VJAX_NO_CACHE"}
    e.update(XDG_CACHE_HOME=str(tmp_path), PYTHONPATH=ROOT)
    p = subprocess.run([sys.executable, "-c", EXPORT_SNIPPET, *args], env=e, capture_output=True, text=True, check=True)
    traces, values = p.stdout.split(" ", 1)
    return int(traces), values


@pytest.mark.slow
def test_exported_programs_skip_tracing_and_give_the_same_bits(tmp_path):
    """jax_cache.call: the first process with the cache on traces and stores the program, a
    later one loads it without tracing; both give the bits of the plain call. A different
    static argument is a different program; a damaged file is exported again."""
    exported = tmp_path / "vjax" / "jax" / "exported"
    traces, plain = _export_run(tmp_path)
    assert traces == 1 and not exported.exists()
    assert _export_run(tmp_path, "--enable") == (1, plain)
    assert _files(exported) == 1
    assert _export_run(tmp_path, "--enable") == (0, plain)          # loaded: nothing traced
    traces, other = _export_run(tmp_path, "--enable", "--other-static")
    assert traces == 1 and other != plain and _files(exported) == 2
    for f in exported.iterdir():
        f.write_bytes(b"not a program")
    assert _export_run(tmp_path, "--enable") == (1, plain)
    assert _export_run(tmp_path, "--enable") == (0, plain)


def test_library_users_opt_in_to_the_cache(tmp_path):
    """vjax.enable_compilation_cache(path): a vjax scene's programs are written there, and a
    second process finds them (a cache hit per program, no new files); import alone writes none."""
    snippet = ("import sys, jax\njax.config.update('jax_enable_x64', True)\nimport vjax\n"
               "if len(sys.argv) > 1: vjax.enable_compilation_cache(sys.argv[1])\n"
               "m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)\n"
               "print(float(vjax.pin_in_hole(m, 0.08, 0.005, 2800.0, omega_shaft=-6.67,"
               " options=vjax.PinOptions(n=64)).torque))\n")
    run = lambda *a: subprocess.run([sys.executable, "-c", snippet, *a], capture_output=True, text=True,  # noqa: E731
                                    check=True).stdout
    plain = run()
    cache = tmp_path / "mine"
    first = run(str(cache))
    written = _files(cache)
    assert written >= 1 and first == plain
    assert run(str(cache)) == plain and _files(cache) == written
