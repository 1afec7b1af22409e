"""JAX's persistent compilation cache for the command-line tools (``vjax-fit``,
``vjax-fit-torque``).

A fit compiles many small functions; without a cache every call of a tool compiles them
again. :func:`enable` points ``jax_compilation_cache_dir`` at ``$XDG_CACHE_HOME/vjax/jax``
(``~/.cache/vjax/jax`` when XDG_CACHE_HOME is unset) and caches every compilation
(``jax_persistent_cache_min_compile_time_secs = 0``: the default of 1 s would skip the fit's
many sub-second compilations). Turn it off with ``VJAX_NO_CACHE=1`` or the tools'
``--no-cache``; delete the directory to clear it. Library use (``import vjax``) is not
affected: only the tools call :func:`enable`.

XLA's cache still leaves JAX's own work to every process: tracing the Python function and
lowering it to StableHLO, for the fit's one large solve (:func:`fitting.calibration.spectrum.smooth_fit`)
about 0.5 s of a cached ``vjax-fit`` call, five times the lookup of its compiled code.
:func:`call` keeps that program too: the first call exports it
(:mod:`jax.export`) to ``<cache>/exported/``, later processes load it, skip tracing and
lowering, and run the same compiled program, so their results are bit-identical. The key of an
exported program holds the function's name, its static arguments, the shapes and dtypes of
its arguments, the JAX version and a hash of the vjax and fitting sources (an edited
checkout never runs a stale program). jax.export's serialization needs ``flatbuffers``;
without it :func:`call` just calls the function.
"""
from __future__ import annotations

import functools
import hashlib
import os

__all__ = ["enable", "add_argument", "call"]

_exported_dir = None    # <cache>/exported once enable() has turned the cache on
_programs = {}          # path -> jax.export.Exported, loaded or exported in this process


def enable(disabled: bool = False):
    """Turn the persistent cache on (before the first compilation); returns its directory,
    or None when ``disabled`` or VJAX_NO_CACHE is set (to anything but '', '0'), or when the
    directory cannot be created (the tool then runs uncached)."""
    if disabled or os.environ.get("VJAX_NO_CACHE", "") not in ("", "0"):
        return None
    import vjax
    try:
        path = vjax.enable_compilation_cache()    # $XDG_CACHE_HOME/vjax/jax or ~/.cache/vjax/jax
    except ValueError:
        return None
    global _exported_dir
    _exported_dir = os.path.join(path, "exported")
    return path


@functools.lru_cache(maxsize=None)
def _sources_hash() -> str:
    """sha256 of the vjax and fitting sources (paths and contents, every folder)."""
    import vjax
    h = hashlib.sha256()
    for package in (os.path.dirname(vjax.__file__), os.path.dirname(os.path.dirname(__file__))):   # vjax/, fitting/
        for folder, dirs, files in os.walk(package):
            dirs.sort()
            for name in sorted(files):
                if name.endswith(".py"):
                    path = os.path.join(folder, name)
                    with open(path, "rb") as fh:
                        h.update(os.path.relpath(path, package).encode() + b"\0" + fh.read())
    return h.hexdigest()


def call(fun, args: tuple, **static):
    """``fun(*args, **static)`` for a jitted function of arrays and scalars that returns a
    tuple of arrays, run from the cache of exported programs once :func:`enable` has turned
    the cache on (see the module docstring); ``static``: hashable keyword arguments, part of
    the program."""
    if _exported_dir is None:
        return fun(*args, **static)
    try:
        import flatbuffers  # noqa: F401  (jax.export's serialization)
    except ImportError:
        return fun(*args, **static)
    import jax

    from fitting.shared.files import write_atomic
    leaves, tree = jax.tree.flatten(args)
    # the types keep Python scalars weak-typed ('~float64[]'), as a plain call traces them
    key = repr((getattr(fun, "__module__", ""), getattr(fun, "__qualname__", repr(fun)), sorted(static.items()),
                str(tree), [str(jax.typeof(a)) for a in leaves], jax.__version__, jax.default_backend(),
                _sources_hash()))
    path = os.path.join(_exported_dir, hashlib.sha256(key.encode()).hexdigest()[:32] + ".bin")
    if path not in _programs:
        try:
            with open(path, "rb") as fh:
                _programs[path] = jax.export.deserialize(bytearray(fh.read()))
        except Exception:   # not there yet, or damaged in any way: export it (again)
            _programs[path] = jax.export.export(jax.jit(lambda *a: fun(*a, **static)))(*args)
            try:
                os.makedirs(_exported_dir, exist_ok=True)
                write_atomic(path, _programs[path].serialize())
            except OSError:
                pass    # a read-only cache: run without storing
    return _programs[path].call(*args)


def add_argument(parser) -> None:
    """The ``--no-cache`` switch."""
    parser.add_argument("--no-cache", action="store_true",
                        help="do not use the persistent JAX compilation cache (also: VJAX_NO_CACHE=1); "
                             "default cache: $XDG_CACHE_HOME/vjax/jax or ~/.cache/vjax/jax")
