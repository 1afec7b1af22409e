"""Netzsch Gabo Eplexor Excel exports (``.xls``, the Eplexor software's "Excel Export!" with its
default template), read into :mod:`fitting.measurements.dma` blocks.

* **raw** files: sheet "Exported Data", a row of names (``f``, ``T``, ``E'``, ``E''`` or
  ``G'``, ``G''``, ...) and a row of units (``Hz``, ``°C``, ``MPa``), one row per point, the
  isothermal sweeps one after the other. A sweep ends where the frequency drops.
* **master-curve** files: the same sheet holding the shifted master curve at the reference
  temperature (``f`` is the reduced frequency a_T f), plus a sheet "Shiftlist" (reference
  temperature, the Eplexor's WLF constants, and log10 a_T per sweep temperature). The sweeps
  are rebuilt: points are grouped by measurement time (the ``Time`` column; sweeps are
  separated by more than the header's soak time), and each group gets the
  shift-list row whose log10 a_T brings its frequencies back onto the measured frequency grid
  of the "Data header" sheet (frequency range and points per decade). The result is the raw
  data again: f = f_reduced / a_T, at the sweep's temperature.

Needs ``xlrd`` (``pip install xlrd``), imported only when such a file is read.
:func:`shift_list` returns the file's own shift factors and WLF constants.
"""
from __future__ import annotations

import math
import os

import numpy as np

from fitting.measurements.rawfile import Block, DMAFormatError

__all__ = ["is_ole2", "blocks", "shift_list"]

OLE2_MAGIC = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"       # legacy Excel (.xls) container


def is_ole2(head: bytes) -> bool:
    """True for the first bytes of a legacy Office (.xls) file."""
    return head.startswith(OLE2_MAGIC)


def _book(path):
    try:
        import xlrd
    except ImportError:
        raise DMAFormatError(path, None, "reading Netzsch Eplexor .xls files needs xlrd: pip install xlrd") from None
    try:
        return xlrd.open_workbook(path)
    except Exception as e:      # xlrd raises its own XLRDError and struct errors for damaged files
        raise DMAFormatError(path, None, f"not a readable Excel .xls file ({e})") from None


def _sheet(book, name, path):
    if name not in book.sheet_names():
        raise DMAFormatError(path, None, f"Excel file without a sheet {name!r} (sheets: {book.sheet_names()}); "
                                         "not a Netzsch Eplexor export")
    return book.sheet_by_name(name)


def _number(v) -> float:
    if isinstance(v, (int, float)):
        return float(v)
    s = str(v).strip()
    if s in ("", "---", "--", "nan", "NaN"):
        return math.nan
    return float(s)


def shift_list(path):
    """The "Shiftlist" sheet of an Eplexor master-curve file: ``(T, log10_aT, T_ref, wlf)`` with
    temperatures in C and ``wlf`` = {"C1", "C2"} (None when the sheet has none)."""
    sh = _sheet(_book(path), "Shiftlist", path)
    try:
        T_ref = float(str(sh.cell_value(0, 1)).replace("°C", "").replace("\ufffdC", "").strip())
    except ValueError:
        raise DMAFormatError(path, 1, f"Shiftlist: cannot read the reference temperature {sh.cell_value(0, 1)!r}")
    wlf = None
    if str(sh.cell_value(1, 0)).strip().upper() == "WLF":
        try:
            wlf = {"C1": float(str(sh.cell_value(1, 1)).split(":")[1]),
                   "C2": float(str(sh.cell_value(1, 2)).split(":")[1].replace("K", ""))}
        except (IndexError, ValueError):
            wlf = None
    T, a = [], []
    for r in range(3, sh.nrows):
        row = sh.row_values(r)
        if all(str(v).strip() == "" for v in row):
            continue
        try:
            T.append(_number(row[0]))
            a.append(_number(row[1]))
        except ValueError:
            raise DMAFormatError(path, r + 1, f"Shiftlist: not a number in {row[:2]!r}")
    if not T:
        raise DMAFormatError(path, None, "Shiftlist sheet without shift factors")
    return np.array(T), np.array(a), T_ref, wlf


def _header(book, path):
    """(log10 of the measured frequencies in Hz, soak time in s or None) from the "Data header"
    sheet: 'Frequency range:' fmin, fmax; 'Frequency increment:' points per decade; 'Soak time:'."""
    h = _sheet(book, "Data header", path)
    for r in range(h.nrows - 1):
        names = [str(v).strip().lower() for v in h.row_values(r)]
        if "frequency range:" in names and "frequency increment:" in names:
            vals = h.row_values(r + 1)
            i, j = names.index("frequency range:"), names.index("frequency increment:")
            fmin, fmax, per_decade = _number(vals[i]), _number(vals[i + 1]), _number(vals[j])
            n = int(round(math.log10(fmax / fmin) * per_decade))
            soak = _number(vals[names.index("soak time:")]) if "soak time:" in names else math.nan
            return np.linspace(math.log10(fmin), math.log10(fmax), n + 1), (soak if soak > 0 else None)
    raise DMAFormatError(path, None, "Data header sheet without 'Frequency range:' and 'Frequency increment:'")


def _master_sets(book, path, col, data, rows):
    """Set index and temperature per row of a master-curve file (see the module docstring)."""
    T_list, a_list, _, _ = shift_list(path)
    if "Time" not in col:
        raise DMAFormatError(path, 1, "master-curve file without a 'Time' column: cannot tell its sweeps apart")
    grid, soak = _header(book, path)
    t = data[:, col["Time"]]
    order = np.argsort(t, kind="stable")
    gaps = np.diff(t[order])
    # sweeps are separated by the soak time at the next temperature; within a sweep the points
    # follow each other after a few periods (a master curve may lack some sweeps)
    limit = soak if soak else math.sqrt(max(gaps.max(), 1e-9) * max(np.median(gaps), 1e-9))
    groups = np.split(order, np.flatnonzero(gaps > limit) + 1)
    n_sets = len(T_list)
    if len(groups) > n_sets:
        raise DMAFormatError(path, None, f"{len(groups)} sweeps (by measurement time) for {n_sets} shift-list rows")
    logf = np.log10(data[:, col["f"]])
    cost = np.empty((len(groups), n_sets))
    for g, idx in enumerate(groups):
        for s, a in enumerate(a_list):
            x = logf[idx] - a
            outside = np.maximum(grid[0] - x, 0) + np.maximum(x - grid[-1], 0)
            cost[g, s] = np.max(np.min(np.abs(x[:, None] - grid[None, :]), axis=1) + 10 * outside)
    # cheapest pairs first, each sweep and each shift-list row used once
    gi, si, used_g, used_s = [], [], set(), set()
    for flat in np.argsort(cost, axis=None, kind="stable"):
        g, s = divmod(int(flat), n_sets)
        if g not in used_g and s not in used_s:
            gi.append(g), si.append(s), used_g.add(g), used_s.add(s)
    gi, si = np.array(gi), np.array(si)
    if cost[gi, si].max() > 0.02:
        g = gi[np.argmax(cost[gi, si])]
        raise DMAFormatError(path, int(rows[groups[g][0]]),
                             "cannot match this sweep of the master curve to a shift-list row (its frequencies do "
                             "not return onto the measured grid of the Data header)")
    set_id, T_set, a_pt = np.empty(len(t), int), np.empty(len(t)), np.empty(len(t))
    for g, s in zip(gi, si):
        set_id[groups[g]], T_set[groups[g]], a_pt[groups[g]] = s, T_list[s], a_list[s]
    return set_id, T_set, a_pt


def blocks(path) -> list:
    """The :class:`fitting.measurements.rawfile.Block` of an Eplexor .xls file (raw or master curve)."""
    book = _book(path)
    sh = _sheet(book, "Exported Data", path)
    if sh.nrows < 3:
        raise DMAFormatError(path, None, "sheet 'Exported Data' holds no data rows")
    names = [str(v).strip() for v in sh.row_values(0)]
    units = [str(v).strip() for v in sh.row_values(1)]
    col = {n: j for j, n in enumerate(names) if n}
    rows, lines = [], []
    for r in range(2, sh.nrows):
        vals = sh.row_values(r)
        if all(str(v).strip() == "" for v in vals):
            continue
        try:
            rows.append([_number(v) for v in vals])
        except ValueError:
            bad = next(v for v in vals if not _is_number(v))
            raise DMAFormatError(path, r + 1, f"not a number: {bad!r}")
        lines.append(r + 1)
    if "f" not in col:
        raise DMAFormatError(path, 1, f"sheet 'Exported Data' without a frequency column 'f'; found {names}")
    data = np.asarray(rows, float)
    if "Shiftlist" in book.sheet_names():
        set_id, T_set, a_pt = _master_sets(book, path, col, data, np.asarray(lines))
        data[:, col["f"]] = data[:, col["f"]] / 10.0 ** a_pt          # back to the measured frequency
        if "T" not in col:
            names, units, col["T"] = names + ["T"], units + ["°C"], len(names)
            data = np.column_stack([data, T_set])
        data[:, col["T"]] = T_set                                       # the sweep's, not T_ref
        order = np.lexsort((data[:, col["f"]], set_id))
        data, lines, set_id = data[order], list(np.asarray(lines)[order]), set_id[order]
    else:
        f = data[:, col["f"]]
        set_id = np.concatenate([[0], np.cumsum(np.diff(f) < 0)])       # a sweep ends where f drops
    names, units = names + ["Set"], units + ["-"]
    data = np.column_stack([data, set_id])
    return [Block(os.fspath(path), names, units, data.tolist(), lines, 2)]


def _is_number(v) -> bool:
    try:
        _number(v)
        return True
    except ValueError:
        return False
