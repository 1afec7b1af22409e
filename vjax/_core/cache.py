"""Opt-in persistent compilation cache: most of a first call is XLA compiling the solvers.

vjax never changes JAX's configuration on import. A library user who calls the same scenes
in many processes (scripts, notebooks, sweeps) turns the cache on once, before the first
computation::

    import vjax
    vjax.enable_compilation_cache()        # ~/.cache/vjax/jax, or a path

and every later process loads the compiled programs instead of compiling them again (the
command-line tools do this themselves; ``VJAX_NO_CACHE=1`` turns it off for them).
"""
from __future__ import annotations

import os

import jax


def default_cache_dir() -> str:
    """``$XDG_CACHE_HOME/vjax/jax``, or ``~/.cache/vjax/jax``."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "vjax", "jax")


def enable_compilation_cache(path: str | os.PathLike | None = None) -> str:
    """Point JAX's persistent compilation cache at ``path`` (None: :func:`default_cache_dir`),
    creating it, and cache every compilation (JAX's default skips those under 1 s, which are
    most of a scene's). Returns the directory. Call it before the first computation: programs
    compiled earlier in the process are not written."""
    path = os.fspath(default_cache_dir() if path is None else path)
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as e:
        raise ValueError(f"path: cannot create the compilation cache directory {path!r} ({e})") from None
    jax.config.update("jax_compilation_cache_dir", path)
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.0)
    jax.config.update("jax_persistent_cache_min_entry_size_bytes", 0)
    return path
