"""Relaxation (time-domain) data: relaxation modulus versus time at several temperatures.

Formats (text, detected from the header like :mod:`fitting.measurements.dma`):

* **pyvisco CSV**: ``t,E_relax,T,Set`` / ``s,MPa,C,-`` (or ``G_relax``);
* **tidy CSV**: ``t [s], E(t) [MPa], T [C]`` (``time``, ``E_relax``, ``relaxation modulus``;
  units s, ms, min, h; Pa, kPa, MPa, GPa; C or K); sets from a ``Set`` column or from
  temperature clusters.

:func:`read` returns a :class:`RelaxationTable`. :func:`fitting.calibrate` (and ``vjax-fit``)
detect such files by :func:`is_relaxation` and fit them with the smooth-spectrum Prony fit
(:mod:`fitting.calibration.spectrum`) of E(t) = E0 + sum_k E_k exp(-(t / a_T) / tau_k) with t / a_T the
reduced time; shift factors start from the overlap of the log E(t) curves
(:func:`fitting.calibration.master.shift_factors` on the curves against 1/t).
"""
from __future__ import annotations

import dataclasses
import math
import os
import re

import numpy as np

from fitting.measurements import dma
from fitting.shared import evaluate
from fitting.measurements.rawfile import DMAFormatError

__all__ = ["RelaxationTable", "read", "is_relaxation"]

_TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0, "hr": 3600.0}


def _canon(name: str):
    """'t', ('relax', 'E'|'G'|None), 'T', 'set' or None."""
    n = re.sub(r"\s+", " ", name.strip())
    low = n.lower()
    if n == "t" or low in ("time", "t_relax"):
        return "t"
    for k in ("E", "G"):
        if low in (f"{k.lower()}_relax", f"{k.lower()}relax", f"{k.lower()}(t)", f"{k.lower()}_t"):
            return ("relax", k)
    if low in ("relaxation modulus", "relaxation"):
        return ("relax", None)
    c = dma.canon_name(n)
    return c if c in ("T", "Tset", "set") else None


@dataclasses.dataclass(frozen=True)
class RelaxationTable:
    """Relaxation modulus versus time at several temperatures, SI units; arrays one entry
    per point: ``T`` nominal temperature of the point's set (C), ``t`` time (s), ``modulus``
    E(t) or G(t) (Pa), ``set`` 0..n_sets-1 in order of increasing T; ``kind`` 'E' or 'G'."""

    T: np.ndarray
    t: np.ndarray
    modulus: np.ndarray
    set: np.ndarray
    kind: str
    files: tuple = ()
    dropped: int = 0
    domain = "time"

    def __len__(self) -> int:
        return len(self.t)

    temperatures = dma.DMATable.temperatures
    n_sets = dma.DMATable.n_sets

    def as_rate_table(self) -> dma.DMATable:
        """The curves as a frequency-like table (omega = 1/t, both moduli = E(t)), for the
        overlap shift of :func:`fitting.calibration.master.shift_factors` (which moves curves along
        log omega; t / a_T = 1 / (a_T omega))."""
        return dma.DMATable(T=self.T, T_measured=self.T.copy(), f=1.0 / (2 * math.pi * self.t), omega=1.0 / self.t,
                            storage=self.modulus, loss=self.modulus, set=self.set,
                            source=np.array([""] * len(self.t), dtype=object), kind=self.kind, files=self.files)

    def errors(self, material, shift) -> dict:
        """Median and 90th percentile of |log10(pred/meas)| of E(t) on the raw points, and the rms."""
        r = np.log10(evaluate.relaxation(material, self.t / 10.0 ** evaluate.log10_aT(shift, self.T)) / self.modulus)
        a = np.abs(r)
        return {"relaxation_median": float(np.median(a)), "relaxation_p90": float(np.percentile(a, 90)),
                "rms": float(np.sqrt(np.mean(r ** 2)))}


def _header_names(path):
    """Header names of a text file (units stripped), or None for binary/unreadable files."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(4096)
    except OSError:
        return None
    if b"\0" in head:
        return None
    lines = [l for l in head.decode("utf-8-sig", errors="replace").splitlines() if l.strip()]
    if not lines:
        return None
    sep = "," if lines[0].count(",") >= lines[0].count(";") else ";"
    return [(dma.UNIT_IN_NAME.match(n.strip()) or re.match(r"(?P<name>.*)", n.strip())).group("name")
            for n in lines[0].split(sep)]


def is_relaxation(paths) -> bool:
    """True when the (first) input file's header has a time and a relaxation-modulus column."""
    try:
        files = dma.expand(paths)
    except (DMAFormatError, OSError):
        return False
    names = _header_names(files[0]) if files and os.path.isfile(files[0]) else None
    canon = [_canon(n) for n in names or []]
    return "t" in canon and any(isinstance(c, tuple) and c[0] == "relax" for c in canon)


def read(paths, kind=None, drop_nonpositive=False) -> RelaxationTable:
    """Read relaxation data (module docstring) from one or more files into a
    :class:`RelaxationTable`. Raises :class:`fitting.measurements.dma.DMAFormatError` naming the file, line
    and problem (missing columns or units, NaN, non-positive time or modulus)."""
    if kind is not None and kind not in ("E", "G"):
        raise ValueError(f"kind must be 'E' or 'G', got {kind!r}")
    cols = {"T": [], "t": [], "E": [], "set": []}
    kinds, dropped, files, next_set = set(), 0, dma.expand(paths), 0
    for path in files:
        for block in dma.blocks_from_file(path):
            found = {}
            for j, (n, u) in enumerate(zip(block.names, block.units)):
                c = _canon(n)
                key = c[0] if isinstance(c, tuple) else c
                if c is not None and key not in found:
                    found[key] = (j, n, u, c[1] if isinstance(c, tuple) else None)
            missing = [w for w, k in (("time (t [s])", "t"), ("relaxation modulus (E_relax [MPa])", "relax"))
                       if k not in found]
            if "T" not in found and "Tset" not in found and dma.temperature_from_filename(path) is None:
                missing.append("temperature (T [C], or in the file name)")
            if missing:
                raise DMAFormatError(path, block.header_line, f"missing column(s): {', '.join(missing)}; "
                                                              f"found {block.names}")
            data = np.asarray(block.rows, float).reshape(len(block.rows), len(block.names))
            line = block.header_line
            j, n, u, k = found["t"]
            tu = dma.clean_unit(u)
            if tu not in _TIME_UNITS:
                raise DMAFormatError(path, line, f"unknown time unit {u.strip()!r} in column {n!r} (known: s, ms, min, h)")
            t = data[:, j] * _TIME_UNITS[tu]
            j, n, u, k = found["relax"]
            E = data[:, j] * dma.modulus_scale(u, path, line, n)
            k = kind or k or block.kind_hint
            if k is None:
                raise DMAFormatError(path, line, "cannot tell tensile (E) from shear (G): pass kind='E' or 'G'")
            kinds.add(k)
            tkey = "Tset" if "Tset" in found else "T" if "T" in found else None
            if tkey:
                j, n, u, _ = found[tkey]
                T = data[:, j] + dma.temp_offset(u, path, line, n)
            else:
                T = np.full(len(t), dma.temperature_from_filename(path))
            for arr, label in ((t, "time"), (E, "relaxation modulus"), (T, "temperature")):
                bad = ~np.isfinite(arr)
                if bad.any():
                    raise DMAFormatError(path, int(block.lines[np.argmax(bad)]), f"{label} is NaN or missing")
            bad = (E <= 0) | (t <= 0)
            if bad.any():
                if not drop_nonpositive or np.any(t <= 0):
                    i = int(np.argmax(bad))
                    raise DMAFormatError(path, int(block.lines[i]), f"time and modulus must be > 0, got t = {t[i]:.4g} s, "
                                         f"modulus {E[i]:.4g} Pa" + ("; use drop_nonpositive=True to drop such points"
                                                                     if t[i] > 0 else ""))
                dropped += int(bad.sum())
                t, E, T = t[~bad], E[~bad], T[~bad]
            groups = ([data[~bad, found["set"][0]] == s for s in np.unique(data[~bad, found["set"][0]])]
                      if "set" in found else dma.cluster(T))
            for m in groups:
                cols["T"].append(np.full(int(m.sum()), round(float(np.mean(T[m])), 1)))
                cols["t"].append(t[m])
                cols["E"].append(E[m])
                cols["set"].append(np.full(int(m.sum()), next_set))
                next_set += 1
    if len(kinds) > 1:
        raise DMAFormatError(", ".join(files), None, "files mix tensile (E) and shear (G) data; pass kind=")
    T = np.concatenate(cols["T"])
    Ts, setid = np.unique(T, return_inverse=True)
    if len(Ts) < next_set:
        raise DMAFormatError(", ".join(files), None, "two sets share a nominal temperature (duplicated points)")
    order = np.lexsort((np.concatenate(cols["t"]), setid))
    return RelaxationTable(T=T[order], t=np.concatenate(cols["t"])[order], modulus=np.concatenate(cols["E"])[order],
                           set=setid[order].astype(int), kind=kinds.pop(), files=tuple(files), dropped=dropped)
