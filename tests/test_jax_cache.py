"""The command-line tools' persistent compilation cache (fitting.jax_cache): where it lives,
that a small compilation is stored (the default 1 s threshold would skip it), and that
VJAX_NO_CACHE / --no-cache turn it off. Run in subprocesses: the cache is per process."""
import os
import subprocess
import sys

from fitting import jax_cache

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SNIPPET = ("import sys, jax, jax.numpy as jnp\n"
           "from fitting import jax_cache\n"
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
    monkeypatch.setenv("XDG_CACHE_HOME", "/some/where")
    assert jax_cache.cache_dir() == os.path.join("/some/where", "vjax", "jax")
    monkeypatch.delenv("XDG_CACHE_HOME")
    assert jax_cache.cache_dir() == os.path.join(os.path.expanduser("~"), ".cache", "vjax", "jax")


def test_small_compilations_are_stored_and_switches_turn_it_off(tmp_path):
    cache = tmp_path / "vjax" / "jax"
    assert _run(tmp_path, "--no-cache") == "None" and _files(tmp_path) == 0
    assert _run(tmp_path, VJAX_NO_CACHE="1") == "None" and _files(tmp_path) == 0
    assert _run(tmp_path) == str(cache)
    assert _files(cache) >= 1
