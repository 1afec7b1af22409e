"""Readers for DMA frequency sweeps: many file formats in, one table out.

:func:`read` loads one or more files (or directories) and returns a :class:`DMATable`:
temperature ``T`` (C), frequency ``f`` (Hz), angular frequency ``omega`` (rad/s), storage and
loss modulus (Pa), and ``kind`` = ``'E'`` (tensile) or ``'G'`` (shear). Every point belongs to
a temperature *set* (one isothermal frequency sweep); ``T`` is the nominal temperature of its
set.

Formats (detected from the content, not the extension):

* **pyvisco CSV**: two header rows, names then units, e.g. ``f,E_stor,E_loss,T,Set`` /
  ``Hz,MPa,MPa,C,-`` (or ``G_stor``, ``G_loss``). Sets come from the ``Set`` column.
* **tidy CSV**: one header row whose names carry their units, e.g. ``T [C]``, ``f [Hz]`` or
  ``omega [rad/s]``, ``E' [MPa]``, ``E'' [MPa]`` (parentheses also accepted). Sets come
  from a ``Set`` column if present, else from temperature clusters.
* **TRIOS** (TA Instruments "LIMS export" text): one ``[Step]`` block per temperature, tab
  separated ``Variables`` / ``Units`` / ``Data point`` rows. A rotational rheometer export is
  shear (``G``) unless the geometry or instrument says tension.
* **whitespace instrument export** with a unit row, e.g. ``Index Ts t f ... E' E" ...`` /
  ``[#] [C] [s] [Hz] ... [MPa] [MPa]`` (as in ``dmasuite_E_0to105C``). A trailing footer
  line that is not numeric ends the data.
* **Netzsch Eplexor Excel** (``.xls``, raw sweeps or master curve with its shift list), read
  by :mod:`fitting.measurements.eplexor` (needs ``xlrd``). Other binary files are refused.
* **one file per temperature**: any of the above without a temperature column (or with it)
  whose file name holds the temperature, e.g. ``T85.txt``, ``sweep_-20C.csv``,
  ``PA66_23.5degC.txt``. The name wins over setpoint and measured columns.

Bad files raise :class:`DMAFormatError` (a ``ValueError``) naming the file, the line and the
problem. Non-positive moduli are refused unless ``drop_nonpositive=True``, in which case the
points are dropped and counted in :attr:`DMATable.dropped`.
"""
from __future__ import annotations

import dataclasses
import math
import os
import re

import numpy as np

from fitting.measurements.rawfile import Block, DMAFormatError

__all__ = ["DMATable", "DMAFormatError", "read", "read_file", "from_arrays"]


@dataclasses.dataclass(frozen=True)
class DMATable:
    """DMA frequency sweeps at several temperatures, in SI units.

    Attributes (all 1-D numpy arrays of one length, one entry per measured point):
      T: nominal temperature of the point's set (C).
      T_measured: measured sample temperature (C), NaN when the file has none.
      f: frequency (Hz).
      omega: angular frequency 2 pi f (rad/s).
      storage: storage modulus E' or G' (Pa).
      loss: loss modulus E'' or G'' (Pa).
      set: integer id of the isothermal sweep, 0..n_sets-1 in order of increasing T.
      source: ``"file:line"`` of each point.
    And: ``kind`` ('E' tensile or 'G' shear), ``dropped`` (number of points removed by
    ``drop_nonpositive``), ``files`` (the files read).
    """

    T: np.ndarray
    T_measured: np.ndarray
    f: np.ndarray
    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    set: np.ndarray
    source: np.ndarray
    kind: str
    dropped: int = 0
    files: tuple = ()

    domain = "frequency"     # (relaxation data: fitting.measurements.relaxation.RelaxationTable, domain 'time')

    def __len__(self) -> int:
        return len(self.f)

    def errors(self, material, shift) -> dict:
        """Errors of ``material`` with ``shift`` on these raw points (:func:`fitting.shared.evaluate.raw_errors`)."""
        from fitting.shared.evaluate import raw_errors
        return raw_errors(material, shift, self)

    temperatures = property(lambda self: set_temperatures(self.T, self.set),
                            doc="Nominal temperature of each set (C), increasing.")
    n_sets = property(lambda self: int(self.set.max()) + 1 if len(self.set) else 0, doc="Number of sets.")

    def subset(self, mask) -> "DMATable":
        """The points where ``mask`` is true (sets renumbered)."""
        mask = np.asarray(mask, bool)
        _, new_set = np.unique(self.set[mask], return_inverse=True)
        return dataclasses.replace(
            self, T=self.T[mask], T_measured=self.T_measured[mask], f=self.f[mask],
            omega=self.omega[mask], storage=self.storage[mask], loss=self.loss[mask],
            set=new_set.astype(int), source=self.source[mask])

    def summary(self) -> str:
        """One line: points, sets, temperature and frequency range."""
        return (f"{len(self)} points of {self.kind}', {self.kind}'' in {self.n_sets} sweeps, "
                f"T = {self.T.min():.4g}..{self.T.max():.4g} C, f = {self.f.min():.3g}..{self.f.max():.3g} Hz"
                + (f", {self.dropped} non-positive points dropped" if self.dropped else ""))


def set_temperatures(T, setid) -> np.ndarray:
    """Nominal temperature of each set 0..max(setid) (C), from per-point arrays."""
    return np.array([T[setid == s][0] for s in range(int(setid.max()) + 1 if len(setid) else 0)])


# ---- units ------------------------------------------------------------------------------
_MODULUS_UNITS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/m2": 1.0, "n/m^2": 1.0,
                  "n/mm2": 1e6, "n/mm^2": 1e6, "n/mm²": 1e6, "psi": 6894.757293168, "ksi": 6894757.293168,
                  "dyn/cm2": 0.1, "dyn/cm^2": 0.1, "dyn/cm²": 0.1}
_FREQ_UNITS = {"hz": ("f", 1.0), "khz": ("f", 1e3), "1/s": ("omega", 1.0), "rad/s": ("omega", 1.0),
               "rad s-1": ("omega", 1.0), "rad/sec": ("omega", 1.0)}
_TEMP_UNITS = {"c": 0.0, "°c": 0.0, "degc": 0.0, "celsius": 0.0,
               "k": -273.15, "kelvin": -273.15}


def clean_unit(u: str) -> str:
    u = u.strip().strip("[]()").strip().lower()
    return u.replace("\ufffd", "°").replace("\xba", "°").replace(" ", "")


def _lookup_unit(table, unit, path, line, col, what, give, known):
    """The cleaned unit and its entry in ``table``; a clear error for a missing or unknown unit."""
    u = clean_unit(unit)
    if u == "":
        raise DMAFormatError(path, line, f"column {col!r} has no unit (give {give})")
    if u not in table:
        raise DMAFormatError(path, line, f"unknown {what} unit {unit.strip()!r} in column {col!r} (known: {known})")
    return u, table[u]


def modulus_scale(unit, path, line, col):
    return _lookup_unit(_MODULUS_UNITS, unit, path, line, col, "modulus", "Pa, kPa, MPa or GPa",
                        "Pa, kPa, MPa, GPa, N/mm2, psi")[1]


def temp_offset(unit, path, line, col):
    return _lookup_unit(_TEMP_UNITS, unit, path, line, col, "temperature", "C or K", "C, K")[1]


def _freq_kind(unit, name, path, line):
    u, _ = _lookup_unit(_FREQ_UNITS, unit, path, line, name, "frequency", "Hz or rad/s", "Hz, kHz, rad/s")
    kind, scale = _FREQ_UNITS[u]
    if u == "1/s" and canon_name(name) == "f":
        kind = "f"  # "f [1/s]" is cycles per second
    return kind, scale


# ---- column names -----------------------------------------------------------------------
def canon_name(name: str):
    """Map a column header (without unit) to 'f', 'omega', 'T', 'Tset', 'set', ('stor', kind),
    ('loss', kind), or None for columns we do not use."""
    if name.strip() == "t":
        return None  # lower-case t is time; T is temperature
    n = name.strip().lower().replace("\u2019", "'").replace("\u2032", "'").replace("\u2033", "''")
    n = n.replace('"', "''").replace("`", "'")
    n = re.sub(r"\s+", " ", n)
    if n in ("f", "freq", "frequency", "f_set", "frequency (hz)"):
        return "f"
    if n in ("omega", "w", "ω", "angular frequency", "ang. frequency", "angular freq"):
        return "omega"
    if n in ("t", "temp", "temperature", "ts", "t_sample", "sample temperature", "t_round"):
        return "T"
    if n in ("tr", "t_set", "tset", "set temperature", "temperature setpoint", "setpoint"):
        return "Tset"
    if n in ("set", "set id", "sweep", "step"):
        return "set"
    for k in ("e", "g"):
        K = k.upper()
        if n in (f"{k}'", f"{k}_stor", f"{k}stor", f"{k}_storage", f"{k} storage", f"{k}1", f"{k}_1"):
            return ("stor", K)
        if n in (f"{k}''", f"{k}_loss", f"{k}loss", f"{k} loss", f"{k}2", f"{k}_2"):
            return ("loss", K)
    if n in ("storage modulus", "storage"):
        return ("stor", None)
    if n in ("loss modulus", "loss"):
        return ("loss", None)
    return None


UNIT_IN_NAME = re.compile(r"^(?P<name>.*?)\s*[\[(](?P<unit>[^\[\]()]*)[\])]\s*$")
_TEMP_IN_FILENAME = re.compile(
    r"(?:^|[^a-z0-9])t_?(?P<a>[-+]?\d+(?:[.p]\d+)?)(?=$|[^0-9])"
    r"|(?P<b>[-+]?\d+(?:[.p]\d+)?)\s*_?(?:°|deg|o)?c(?=$|[^a-z])", re.I)


def temperature_from_filename(path) -> float | None:
    """Temperature (C) written in a file name: ``T85.txt``, ``T-20.csv``, ``sweep_-20C.csv``,
    ``x_23.5degC.txt``, ``T12p5.txt``; None if the name holds none (or two different ones)."""
    stem = os.path.splitext(os.path.basename(str(path)))[0]
    found = set()
    for m in _TEMP_IN_FILENAME.finditer(stem):
        s = m.group("a") or m.group("b")
        found.add(float(s.replace("p", ".")))
    return found.pop() if len(found) == 1 else None


# ---- file text --------------------------------------------------------------------------
def _read_lines(path) -> list[str]:
    with open(path, "rb") as fh:
        raw = fh.read()
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    return text.splitlines()


def _to_float(tok: str) -> float:
    t = tok.strip().strip('"')
    if t.lower() in ("", "nan", "na", "n/a", "---", "--", "-nan"):
        return math.nan
    return float(t)


def _parse_numeric_rows(path, lines, start, ncol, sep, footer_ok):
    rows, nums = [], []
    for i in range(start, len(lines)):
        s = lines[i].strip()
        if not s:
            continue
        toks = s.split(sep) if sep else s.split()
        try:
            vals = [_to_float(t) for t in toks]
        except ValueError:
            rest = [l for l in lines[i + 1:] if l.strip()]
            if footer_ok and rows and not rest:
                break  # trailing footer (e.g. a sample id line) ends the data
            bad = next(t for t in toks if _is_bad_number(t))
            raise DMAFormatError(path, i + 1, f"not a number: {bad.strip()!r}")
        if len(vals) != ncol:
            if sep and len(vals) > ncol and all(math.isnan(v) for v in vals[ncol:]):
                vals = vals[:ncol]
            else:
                raise DMAFormatError(path, i + 1, f"expected {ncol} values, found {len(vals)}")
        rows.append(vals)
        nums.append(i + 1)
    return rows, nums


def _is_bad_number(t):
    try:
        _to_float(t)
        return False
    except ValueError:
        return True


def _looks_like_unit_row(tokens) -> bool:
    known = set(_MODULUS_UNITS) | set(_FREQ_UNITS) | set(_TEMP_UNITS) | {"-", "", "#", "s", "n", "rad", "1/mpa", "%"}
    toks = [clean_unit(t) for t in tokens]
    hits = sum(t in known for t in toks)
    return hits >= max(2, len(toks) // 2) and not any(_is_number(t) for t in toks if t not in ("-", ""))


def _is_number(t):
    try:
        float(t)
        return True
    except ValueError:
        return False


def blocks_from_file(path) -> list[Block]:
    with open(path, "rb") as fh:
        head = fh.read(4096)
    from fitting.measurements import eplexor
    if eplexor.is_ole2(head):
        return eplexor.blocks(path)
    if b"\0" in head or head.startswith(b"PK\x03\x04"):
        raise DMAFormatError(path, None, "binary file that is neither a text DMA export nor a Netzsch Eplexor .xls; "
                                         "export the data as CSV or text (an .xlsx workbook: save it as CSV)")
    lines = _read_lines(path)
    first = next((i for i, l in enumerate(lines) if l.strip()), None)
    if first is None:
        raise DMAFormatError(path, None, "file is empty")
    head = lines[first].strip()
    if head.startswith("[") and any(l.strip().lower() == "[step]" for l in lines) or "LIMS export" in head:
        return _trios_blocks(path, lines)
    if "," in head or ";" in head:
        sep = "," if head.count(",") >= head.count(";") else ";"
        names = [t.strip().strip('"') for t in head.split(sep)]
        second = next((i for i in range(first + 1, len(lines)) if lines[i].strip()), None)
        if second is not None and _looks_like_unit_row(lines[second].split(sep)):
            units = [t.strip().strip('"') for t in lines[second].split(sep)]
            if len(units) != len(names):
                raise DMAFormatError(path, second + 1, f"unit row has {len(units)} entries for {len(names)} columns")
            start, hdr = second + 1, second + 1
        else:
            units = []
            for j, n in enumerate(names):
                m = UNIT_IN_NAME.match(n)
                names[j], u = (m.group("name").strip(), m.group("unit")) if m else (n, "")
                units.append(u)
            start, hdr = first + 1, first + 1
        rows, nums = _parse_numeric_rows(path, lines, start, len(names), sep, footer_ok=False)
        return [Block(str(path), names, units, rows, nums, hdr)]
    # whitespace-separated: header row, unit row ([..] tokens), numbers
    names = head.split()
    second = next((i for i in range(first + 1, len(lines)) if lines[i].strip()), None)
    if second is None:
        raise DMAFormatError(path, first + 1, "header but no data")
    utoks = lines[second].split()
    if all(t.startswith("[") and t.endswith("]") for t in utoks) and len(utoks) == len(names):
        units, start, hdr = [t[1:-1] for t in utoks], second, second + 1
    elif _looks_like_unit_row(utoks) and len(utoks) == len(names):
        units, start, hdr = utoks, second, second + 1
    elif all(_is_number(t) for t in utoks):
        raise DMAFormatError(path, second + 1, "missing unit row after the header "
                                               "(whitespace exports need a row like '[Hz] [MPa] [C]')")
    else:
        raise DMAFormatError(path, second + 1, f"cannot read the unit row: {lines[second].strip()[:60]!r}")
    rows, nums = _parse_numeric_rows(path, lines, start + 1, len(names), None, footer_ok=True)
    return [Block(str(path), names, units, rows, nums, hdr)]


def _trios_blocks(path, lines) -> list[Block]:
    text = "\n".join(lines[:120]).lower()
    tensile = any(w in text for w in ("tension", "tensile", "film", "dma 850", "rsa", "3-point", "cantilever"))
    kind = "E" if tensile else "G"
    blocks, i, step = [], 0, 0
    while i < len(lines):
        if lines[i].strip().lower() != "[step]":
            i += 1
            continue
        j, names, units, hdr, name_line, T_nom = i + 1, None, None, None, None, None
        rows, nums = [], []
        while j < len(lines) and not (lines[j].strip().startswith("[") and lines[j].strip().endswith("]")):
            toks = lines[j].rstrip("\r\n").split("\t")
            key = toks[0].strip().lower()
            if key == "step name":
                name_line = " ".join(toks[1:])
                m = re.search(r"\(\s*([-+]?\d+(?:\.\d+)?)\s*(?:°|\ufffd|deg)?\s*C\s*\)", name_line)
                T_nom = float(m.group(1)) if m else None
            elif key == "variables":
                names, hdr = [t.strip() for t in toks[1:]], j + 1
            elif key == "units":
                units = [t.strip() for t in toks[1:]]
            elif key == "data point":
                if names is None or units is None:
                    raise DMAFormatError(path, j + 1, "TRIOS data point before its Variables/Units rows")
                vals = toks[1:]
                if len(vals) < len(names):
                    vals = vals + [""] * (len(names) - len(vals))
                # TRIOS rows hold hex status bits and dates: convert only the columns we use
                row = [math.nan] * len(names)
                for c, nm in enumerate(names):
                    if canon_name(nm) is not None:
                        try:
                            row[c] = _to_float(vals[c])
                        except ValueError:
                            raise DMAFormatError(path, j + 1, f"not a number in column {nm!r}: {vals[c].strip()!r}")
                rows.append(row)
                nums.append(j + 1)
            j += 1
        if rows:
            if len(units) < len(names):
                units = units + [""] * (len(names) - len(units))
            blocks.append(Block(str(path), names, units[:len(names)], rows, nums, hdr,
                                 T_nominal=T_nom, set_hint=step, kind_hint=kind))
            step += 1
        i = j
    if not blocks:
        raise DMAFormatError(path, None, "TRIOS file without any [Step] holding data points")
    return blocks


# ---- block -> columns -------------------------------------------------------------------
def _convert(block: Block, kind_override):
    path = block.path
    cols = {}
    for j, (n, u) in enumerate(zip(block.names, block.units)):
        c = canon_name(n)
        if c is None:
            continue
        key = c if isinstance(c, str) else c[0]
        if key in cols:
            # TRIOS has both 'Temperature' and nothing else; keep the first occurrence
            continue
        cols[key] = (j, n, u, None if isinstance(c, str) else c[1])
    missing = [w for w, k in (("storage modulus", "stor"), ("loss modulus", "loss")) if k not in cols]
    if "f" not in cols and "omega" not in cols:
        missing.insert(0, "frequency (f [Hz] or omega [rad/s])")
    if missing:
        raise DMAFormatError(path, block.header_line,
                             f"missing column(s): {', '.join(missing)}; found {block.names} (relaxation data "
                             "need a time column t [s] and a relaxation modulus E_relax [MPa]: fitting.measurements.relaxation)")
    data = np.asarray(block.rows, float).reshape(len(block.rows), len(block.names))
    lines = np.asarray(block.lines)
    line = block.header_line
    kinds = {cols[k][3] for k in ("stor", "loss")} - {None}
    if len(kinds) > 1:
        raise DMAFormatError(path, line, "storage and loss columns mix tensile (E) and shear (G)")
    kind = kinds.pop() if kinds else (block.kind_hint or None)
    if kind_override is not None:
        kind = kind_override
    if kind is None:
        raise DMAFormatError(path, line, "cannot tell tensile (E) from shear (G): pass kind='E' or 'G'")
    out = {}
    for k in ("stor", "loss"):
        j, n, u, _ = cols[k]
        out[k] = data[:, j] * modulus_scale(u, path, line, n)
    fk = "f" if "f" in cols else "omega"
    j, n, u, _ = cols[fk]
    which, scale = _freq_kind(u, n, path, line)
    fr = data[:, j] * scale
    out["f"] = fr if which == "f" else fr / (2 * math.pi)
    for k in ("T", "Tset"):
        if k in cols:
            j, n, u, _ = cols[k]
            out[k] = data[:, j] + temp_offset(u, path, line, n)
    if "set" in cols:
        out["set"] = data[:, cols["set"][0]]
    # NaN checks, with the line of the first offender
    for k, label in (("f", "frequency"), ("stor", "storage modulus"), ("loss", "loss modulus"),
                     ("T", "temperature"), ("Tset", "temperature setpoint"), ("set", "Set")):
        if k in out:
            bad = ~np.isfinite(out[k])
            if bad.any():
                raise DMAFormatError(path, int(lines[np.argmax(bad)]), f"{label} is NaN or missing")
    if np.any(out["f"] <= 0):
        raise DMAFormatError(path, int(lines[np.argmax(out["f"] <= 0)]), "frequency must be > 0")
    return out, kind, lines


def read_file(path, kind=None, drop_nonpositive=False, T=None):
    """Read one DMA file; see :func:`read`. Returns a list of per-set dicts (internal)."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise DMAFormatError(path, None, "no such file")
    T_name = temperature_from_filename(path) if T is None else float(T)
    sets = []
    for block in blocks_from_file(path):
        cols, k, lines = _convert(block, kind)
        n = len(lines)
        if n == 0:
            raise DMAFormatError(path, block.header_line, "no data rows")
        Tm = cols.get("T", np.full(n, np.nan))
        # which temperature names the set: file name > TRIOS step name > setpoint > measured
        if T_name is not None and block.T_nominal is None:
            groups = [(np.ones(n, bool), T_name)]
        elif block.T_nominal is not None:
            groups = [(np.ones(n, bool), block.T_nominal)]
        elif "set" in cols:
            groups = []
            for s in np.unique(cols["set"]):
                m = cols["set"] == s
                src = cols["Tset"][m] if "Tset" in cols else Tm[m]
                if not np.all(np.isfinite(src)):
                    raise DMAFormatError(path, int(lines[m][0]), f"set {s:g} has no temperature")
                groups.append((m, round(float(np.mean(src)), 1)))
        elif "Tset" in cols or "T" in cols:
            src = cols["Tset"] if "Tset" in cols else Tm
            groups = [(m, round(float(np.mean(src[m])), 1)) for m in cluster(src)]
        else:
            raise DMAFormatError(path, block.header_line,
                                 "no temperature: add a T column or put it in the file name (e.g. T85.txt)")
        for m, Tn in groups:
            sets.append(dict(T=Tn, T_measured=Tm[m], f=cols["f"][m], storage=cols["stor"][m],
                             loss=cols["loss"][m], lines=lines[m], path=path, kind=k))
    return sets


def cluster(T, tol=1.0):
    """Masks of temperature clusters: sorted values closer than ``tol`` (C) share a set."""
    order = np.argsort(T, kind="stable")
    Ts = T[order]
    breaks = np.flatnonzero(np.diff(Ts) > tol) + 1
    masks = []
    for idx in np.split(order, breaks):
        m = np.zeros(len(T), bool)
        m[idx] = True
        masks.append(m)
    return masks


def expand(paths) -> list[str]:
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    out = []
    for p in paths:
        p = os.fspath(p)
        if os.path.isdir(p):
            names = sorted(n for n in os.listdir(p) if os.path.isfile(os.path.join(p, n))
                           and n.lower().endswith((".txt", ".csv", ".dat", ".tsv", ".xls"))
                           and not n.lower().startswith(("readme", "source", "license")))
            with_T = [n for n in names if temperature_from_filename(n) is not None]
            chosen = with_T or names
            if not chosen:
                raise DMAFormatError(p, None, "directory holds no .txt/.csv/.dat/.xls DMA files")
            out += [os.path.join(p, n) for n in chosen]
        else:
            out.append(p)
    return out


def read(paths, kind=None, drop_nonpositive=False) -> DMATable:
    """Read DMA frequency sweeps from files and/or directories into one :class:`DMATable`.

    Args:
      paths: a file, a directory (its files with a temperature in the name, e.g. ``T85.txt``,
        else all .txt/.csv/.dat) or a list of them.
      kind: 'E' or 'G' to override what the headers say (needed when they don't say).
      drop_nonpositive: drop points with storage or loss <= 0 and count them in ``dropped``
        instead of refusing the file.

    Raises :class:`DMAFormatError` (a ValueError) naming the file, line and problem for:
    missing columns or units, unknown units, NaN values, non-positive moduli, duplicated
    points, frequencies not monotonic within a sweep, E and G mixed across files.

    >>> t = read(default_data("pyvisco"))            # doctest: +SKIP
    """
    if kind is not None and kind not in ("E", "G"):
        raise ValueError(f"kind must be 'E' or 'G', got {kind!r}")
    files = expand(paths)
    if not files:
        raise ValueError("no input files")
    sets = []
    for p in files:
        sets += read_file(p, kind=kind)
    kinds = {s["kind"] for s in sets}
    if len(kinds) > 1:
        raise DMAFormatError(", ".join(files), None, f"files mix tensile (E) and shear (G) data: {sorted(kinds)}; "
                                                     "pass kind= to override")
    dropped = 0
    for s in sets:
        bad = (s["storage"] <= 0) | (s["loss"] <= 0)
        if bad.any():
            if not drop_nonpositive:
                i = int(np.argmax(bad))
                raise DMAFormatError(s["path"], int(s["lines"][i]),
                                     f"non-positive modulus (storage {s['storage'][i]:.4g} Pa, loss {s['loss'][i]:.4g} Pa); "
                                     "use drop_nonpositive=True (CLI: --drop-nonpositive) to drop such points")
            dropped += int(bad.sum())
            for k in ("T_measured", "f", "storage", "loss", "lines"):
                s[k] = s[k][~bad]
        f = s["f"]
        if len(f) >= 2:
            d = np.diff(f)
            if np.any(d == 0):
                i = int(np.argmax(d == 0)) + 1
                raise DMAFormatError(s["path"], int(s["lines"][i]),
                                     f"duplicated point: frequency {f[i]:.6g} Hz repeated at T = {s['T']:g} C")
            if not (np.all(d > 0) or np.all(d < 0)):
                i = int(np.argmax(np.sign(d) != np.sign(d[0]))) + 1
                raise DMAFormatError(s["path"], int(s["lines"][i]),
                                     f"frequency not monotonic within the sweep at T = {s['T']:g} C "
                                     f"({f[i - 1]:.6g} -> {f[i]:.6g} Hz)")
    sets = [s for s in sets if len(s["f"])]
    # merge sets of equal nominal temperature from different files? refuse: ambiguous
    Ts = [s["T"] for s in sets]
    seen = {}
    for s in sets:
        if s["T"] in seen:
            a = seen[s["T"]]
            raise DMAFormatError(s["path"], int(s["lines"][0]),
                                 f"duplicated points: a second sweep at T = {s['T']:g} C "
                                 f"(first one in {a['path']}, line {int(a['lines'][0])})")
        seen[s["T"]] = s
    order = np.argsort(Ts, kind="stable")
    cat = lambda k: np.concatenate([np.asarray(sets[i][k], float) for i in order])
    T = np.concatenate([np.full(len(sets[i]["f"]), sets[i]["T"], float) for i in order])
    setid = np.concatenate([np.full(len(sets[i]["f"]), r, int) for r, i in enumerate(order)])
    source = np.concatenate([np.array([f"{sets[i]['path']}:{l}" for l in sets[i]["lines"]], dtype=object)
                             for i in order])
    f = cat("f")
    return DMATable(T=T, T_measured=cat("T_measured"), f=f, omega=2 * math.pi * f, storage=cat("storage"),
                    loss=cat("loss"), set=setid, source=source, kind=kinds.pop(), dropped=dropped,
                    files=tuple(files))


def from_arrays(T, f, storage, loss, kind="E", omega=None) -> DMATable:
    """A :class:`DMATable` from arrays: T (C), f (Hz) (or omega in rad/s), storage, loss (Pa).
    Points of equal T form a set. No file checks beyond positivity and finiteness."""
    T = np.asarray(T, float)
    if omega is not None:
        f = np.asarray(omega, float) / (2 * math.pi)
    f = np.asarray(f, float)
    storage, loss = np.asarray(storage, float), np.asarray(loss, float)
    for name, a in (("T", T), ("f", f), ("storage", storage), ("loss", loss)):
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite")
    if np.any(storage <= 0) or np.any(loss <= 0) or np.any(f <= 0):
        raise ValueError("f, storage and loss must be > 0")
    order = np.lexsort((f, T))
    T, f, storage, loss = T[order], f[order], storage[order], loss[order]
    _, setid = np.unique(T, return_inverse=True)
    return DMATable(T=T, T_measured=T.copy(), f=f, omega=2 * math.pi * f, storage=storage, loss=loss,
                    set=setid.astype(int), source=np.array([f"array:{i}" for i in range(len(f))], dtype=object),
                    kind=kind)


_DATA_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data")


def default_data(name: str = "pyvisco") -> str:
    """Path of a shipped example data set: ``'pyvisco'`` (freq_user_raw.csv, tensile, 21
    temperatures -50..100 C, BSD-3, from NREL/pyvisco) or ``'dmasuite'`` (directory of 22
    files T0..T105.txt, tensile, MIT, from MahdiTBT/DMA-analysis-suite)."""
    paths = {"pyvisco": os.path.join(_DATA_DIR, "pyvisco_examples", "freq_user_raw.csv"),
             "dmasuite": os.path.join(_DATA_DIR, "dmasuite_E_0to105C")}
    if name not in paths:
        raise ValueError(f"unknown data set {name!r}; known: {sorted(paths)}")
    return paths[name]
