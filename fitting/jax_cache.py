"""JAX's persistent compilation cache for the command-line tools (``vjax-fit``,
``vjax-fit-torque``).

A fit compiles many small functions; without a cache every call of a tool compiles them
again. :func:`enable` points ``jax_compilation_cache_dir`` at ``$XDG_CACHE_HOME/vjax/jax``
(``~/.cache/vjax/jax`` when XDG_CACHE_HOME is unset) and caches every compilation
(``jax_persistent_cache_min_compile_time_secs = 0``: the default of 1 s would skip the fit's
many sub-second compilations). Turn it off with ``VJAX_NO_CACHE=1`` or the tools'
``--no-cache``; delete the directory to clear it. Library use (``import vjax``) is not
affected: only the tools call :func:`enable`.
"""
from __future__ import annotations

import os

__all__ = ["cache_dir", "enable", "add_argument"]


def cache_dir() -> str:
    """The cache directory: $XDG_CACHE_HOME/vjax/jax or ~/.cache/vjax/jax."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "vjax", "jax")


def enable(disabled: bool = False):
    """Turn the persistent cache on (before the first compilation); returns its directory,
    or None when ``disabled`` or VJAX_NO_CACHE is set (to anything but '', '0'), or when the
    directory cannot be created (the tool then runs uncached)."""
    if disabled or os.environ.get("VJAX_NO_CACHE", "") not in ("", "0"):
        return None
    path = cache_dir()
    try:
        os.makedirs(path, exist_ok=True)
    except OSError:
        return None
    import jax
    jax.config.update("jax_compilation_cache_dir", path)
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.0)
    jax.config.update("jax_persistent_cache_min_entry_size_bytes", 0)
    return path


def add_argument(parser) -> None:
    """The ``--no-cache`` switch."""
    parser.add_argument("--no-cache", action="store_true",
                        help="do not use the persistent JAX compilation cache (also: VJAX_NO_CACHE=1); "
                             "default cache: $XDG_CACHE_HOME/vjax/jax or ~/.cache/vjax/jax")
