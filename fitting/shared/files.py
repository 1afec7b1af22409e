"""The one way files are written (fitting, the CLIs and the experiments): atomically.

A file is written to a temporary file in the target's directory, flushed and fsync'ed,
given the mode a newly created file gets (0666 less the umask: 0644 under the usual 022),
then ``os.replace``'d over the target. A reader never sees half a file, and a failed write
leaves no partial file and an existing target unchanged. A set of files (an FEM export)
is written all to temporaries first and renamed at the end (:func:`write_all_atomic`).
"""
from __future__ import annotations

import io
import os
import tempfile
from pathlib import Path

__all__ = ["umask", "write_atomic", "write_all_atomic", "write_temporary", "save_figure"]


def umask() -> int:
    """This process's umask (read by setting it and setting it back)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_temporary(path, data: bytes | str) -> Path:
    """Write ``data`` (bytes, or str as UTF-8) to a new temporary file next to ``path``,
    flushed, fsync'ed and given a new file's mode; returns the temporary's path (the caller
    renames or removes it). A failed write leaves nothing."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data.encode("utf-8") if isinstance(data, str) else data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~umask())     # mkstemp makes it 0600
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return Path(tmp)


def write_atomic(path, data: bytes | str) -> Path:
    """Write ``data`` (bytes, or str as UTF-8) to ``path`` atomically; returns the path."""
    return write_all_atomic([(path, data)])[0]


def write_all_atomic(items) -> list:
    """Write every ``(path, data)`` of ``items`` as a set: all to temporaries first
    (:func:`write_temporary`), then all renamed over their targets. An error while writing
    leaves no temporary and no target touched; an error while renaming also removes the
    targets already renamed (a set is never left half-written). Returns the paths."""
    temps, done = [], []
    try:
        for path, data in items:
            temps.append((write_temporary(path, data), Path(path)))
        for tmp, path in temps:
            os.replace(tmp, path)
            done.append(path)
    except BaseException:
        for tmp, _ in temps:
            if os.path.exists(tmp):
                os.unlink(tmp)
        for path in done:
            os.unlink(path)
        raise
    return done


def save_figure(fig, path, dpi: int = 150, **savefig_kw) -> Path:
    """Render a matplotlib figure (format from the suffix) and write it atomically."""
    buf = io.BytesIO()
    fig.savefig(buf, format=Path(path).suffix.lstrip(".") or "png", dpi=dpi, **savefig_kw)
    return write_atomic(path, buf.getvalue())
