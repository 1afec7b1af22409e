"""The torque file: :class:`TorqueData`, :func:`read_torque_csv`, :func:`write_torque_csv`
(the columns: :mod:`fitting.torque`)."""
from __future__ import annotations

import csv
import dataclasses
import math

import numpy as np


class TorqueFormatError(ValueError):
    """A torque CSV that cannot be used; the message names the file, the line and the problem."""

    def __init__(self, path, line, problem):
        where = f"{path}" + (f", line {line}" if line else "")
        super().__init__(f"{where}: {problem}")


@dataclasses.dataclass(frozen=True)
class TorqueData:
    """Torque points: rpm (rev/min), T (C), load (N/m), torque (N m/m), scatter (N m/m or None)."""

    rpm: np.ndarray
    T: np.ndarray
    load: np.ndarray
    torque: np.ndarray
    scatter: np.ndarray | None = None
    source: str = "arrays"

    def __len__(self) -> int:
        return len(self.rpm)

    @property
    def omega(self):
        """Shaft angular speed (rad/s)."""
        return self.rpm * (2 * math.pi / 60.0)

    def sigma(self, rel_scatter=0.05):
        """Per-point standard deviation: the scatter column, else rel_scatter * |torque|."""
        if self.scatter is not None:
            return self.scatter
        return rel_scatter * np.maximum(np.abs(self.torque), 1e-300)

    def conditions(self):
        """Distinct (T, load) pairs, in order of appearance."""
        seen = []
        for t, f in zip(self.T, self.load):
            if (t, f) not in seen:
                seen.append((t, f))
        return seen


_ALIASES = {
    "rpm": ("speed_rpm", "rpm", "speed", "shaft_speed", "n_rpm", "shaft_speed_rpm"),
    "T": ("temperature_c", "temperature", "t", "t_c", "temp", "temp_c"),
    "load": ("load_n_per_m", "load", "f", "force", "load_n/m", "f_n_per_m"),
    "torque": ("torque_nm_per_m", "torque", "c_t", "torque_n_m_per_m", "torque_nm/m"),
    "scatter": ("scatter_nm_per_m", "scatter", "sigma", "std", "torque_std", "scatter_n_m_per_m"),
}


def _canon(name: str):
    key = name.strip().lower().replace(" ", "_").replace("[", "_").replace("]", "").replace("(", "_") \
        .replace(")", "").strip("_")
    while "__" in key:
        key = key.replace("__", "_")
    for canon, names in _ALIASES.items():
        if key in names:
            return canon
    return None


def read_torque_csv(path) -> TorqueData:
    """Read a torque CSV (module docstring); raises :class:`TorqueFormatError` naming the
    file and line for: an empty file, missing or duplicated columns, non-numeric or
    non-finite values, speed or load <= 0, scatter <= 0, or a curve with a repeated speed."""
    path = str(path)
    try:
        with open(path, encoding="utf-8-sig") as fh:    # -sig: a spreadsheet's byte-order mark
            lines = fh.read().splitlines()
    except OSError as e:
        raise TorqueFormatError(path, None, f"cannot read ({e.strerror})") from None
    except UnicodeDecodeError:
        raise TorqueFormatError(path, None, "not a UTF-8 text file (a CSV saved as UTF-16 or a binary "
                                            "file? save it as CSV UTF-8)") from None
    body = [(i + 1, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    if not body:
        raise TorqueFormatError(path, None, "no header and no data (empty file or only comments)")
    hline, header = body[0]
    names = [h.strip() for h in next(csv.reader([header]))]
    cols = {}
    for j, h in enumerate(names):
        c = _canon(h)
        if c is None:
            continue
        if c in cols:
            raise TorqueFormatError(path, hline, f"two columns mean {c!r}: {names[cols[c]]!r} and {h!r}")
        cols[c] = j
    missing = [c for c in ("rpm", "T", "load", "torque") if c not in cols]
    if missing:
        want = {"rpm": "speed_rpm", "T": "temperature_C", "load": "load_N_per_m", "torque": "torque_Nm_per_m"}
        raise TorqueFormatError(path, hline, f"missing column(s) {[want[m] for m in missing]}; found {names}")
    rows = {c: [] for c in cols}
    for lineno, ln in body[1:]:
        toks = [t.strip() for t in next(csv.reader([ln]))]
        if len(toks) < len(names):
            raise TorqueFormatError(path, lineno, f"expected {len(names)} values, got {len(toks)}")
        for c, j in cols.items():
            try:
                v = float(toks[j])
            except ValueError:
                raise TorqueFormatError(path, lineno, f"{names[j]!r} is not a number: {toks[j]!r}") from None
            if not math.isfinite(v):
                raise TorqueFormatError(path, lineno, f"{names[j]!r} is not finite: {toks[j]!r}")
            if c in ("rpm", "load", "scatter") and v <= 0:
                raise TorqueFormatError(path, lineno, f"{names[j]!r} must be > 0, got {v!r}")
            rows[c].append(v)
    if not rows["rpm"]:
        raise TorqueFormatError(path, None, "header but no data rows")
    a = {c: np.asarray(v, float) for c, v in rows.items()}
    for t, f in {(t, f) for t, f in zip(a["T"], a["load"])}:
        sel = (a["T"] == t) & (a["load"] == f)
        s = a["rpm"][sel]
        if len(np.unique(s)) != len(s):
            raise TorqueFormatError(path, None, f"repeated speed in the curve at T={t:g} C, load={f:g} N/m")
    return TorqueData(a["rpm"], a["T"], a["load"], a["torque"], a.get("scatter"), source=path)


def write_torque_csv(path, data: TorqueData, comments=()) -> None:
    """Write ``data`` in the format :func:`read_torque_csv` reads (atomically)."""
    from fitting.calibration.io import atomic_write
    lines = [f"# {c}" for c in comments]
    head = ["speed_rpm", "temperature_C", "load_N_per_m", "torque_Nm_per_m"]
    if data.scatter is not None:
        head.append("scatter_Nm_per_m")
    lines.append(",".join(head))
    for i in range(len(data)):
        vals = [data.rpm[i], data.T[i], data.load[i], data.torque[i]]
        if data.scatter is not None:
            vals.append(data.scatter[i])
        lines.append(",".join(repr(float(v)) for v in vals))
    atomic_write(path, "\n".join(lines) + "\n")
