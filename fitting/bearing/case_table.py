"""Reading a case file's TOML tables (``vjax-bearing``): typed getters that name the file and the
dotted key in every error, and refuse keys nobody asked for (:class:`Table.close`)."""
from __future__ import annotations

import difflib
import os

import numpy as np

from fitting.bearing.case_units import UnitError, parse, parse_load

__all__ = ["CaseError", "Table", "REQUIRED", "sweep", "positive_quantity"]

REQUIRED = object()


class CaseError(ValueError):
    """Bad input in a case file: ``file``, ``key`` (dotted, e.g. "geometry.radial_clearance")
    and the problem with what is expected."""

    def __init__(self, file, key, problem):
        self.file, self.key = os.fspath(file), key
        super().__init__(f"{self.file}: {key}: {problem}" if key else f"{self.file}: {problem}")


class Table:
    """One TOML table: typed getters that name the key on error, and :meth:`close`, which
    refuses keys nobody asked for (a misspelt key is an error, not a silent default)."""

    def __init__(self, data, key, file):
        if not isinstance(data, dict):
            raise CaseError(file, key, f"expected a table, got {data!r}")
        self.data, self.key, self.file, self.asked = data, key, file, []

    def path(self, name):
        return f"{self.key}.{name}" if self.key else name

    def error(self, name, problem):
        return CaseError(self.file, self.path(name), problem)

    def raw(self, name, default=REQUIRED):
        self.asked.append(name)
        if name in self.data:
            return self.data[name]
        if default is REQUIRED:
            near = difflib.get_close_matches(name, [k for k in self.data if k not in self.asked], 1)
            if near:                         # a misspelling: name the key as written
                raise self.error(near[0], f"unknown key; did you mean {name!r}?")
            raise self.error(name, "missing (required)")
        return default

    def quantity(self, name, dim, default=REQUIRED, positive=True):
        v = self.raw(name, default)
        if v is None:
            return None
        try:
            x = parse(v, dim)
        except UnitError as e:
            raise self.error(name, str(e)) from None
        if positive and not x > 0:
            raise self.error(name, f"must be > 0, got {v!r}")
        return x

    def number(self, name, default=REQUIRED, lo=None, hi=None, integer=False):
        v = self.raw(name, default)
        if v is None:
            return None
        if isinstance(v, bool) or not isinstance(v, (int, float)) or (integer and not isinstance(v, int)):
            raise self.error(name, f"expected {'an integer' if integer else 'a number'} (no unit), got {v!r}")
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            raise self.error(name, f"must be in [{lo}, {hi}], got {v!r}")
        return v

    def choice(self, name, options, default=REQUIRED):
        v = self.raw(name, default)
        if v not in options:
            raise self.error(name, f"expected one of {', '.join(map(repr, options))}, got {v!r}")
        return v

    def table(self, name, default=REQUIRED):
        v = self.raw(name, default)
        return None if v is None else Table(v, self.path(name), self.file)

    def close(self):
        extra = [k for k in self.data if k not in self.asked]
        if extra:
            near = difflib.get_close_matches(extra[0], self.asked, 1)
            hint = f"did you mean {near[0]!r}? " if near else ""
            raise self.error(extra[0], f"unknown key; {hint}expected one of {', '.join(sorted(set(self.asked)))}")


def sweep(t: Table, name, dim, default=REQUIRED, load=False):
    """A list of values, one value, or a range {from, to, points, spacing}."""
    v = t.raw(name, default)
    if v is default:
        return v
    one = (lambda x, k: parse_load(x)) if load else (lambda x, k: (parse(x, dim), dim))
    try:
        if isinstance(v, dict):
            r = Table(v, t.path(name), t.file)
            a = one(r.raw("from"), "from")
            b = one(r.raw("to"), "to")
            k = r.number("points", lo=1, integer=True)
            spacing = r.choice("spacing", ("linear", "log"), "linear")
            r.close()
            if a[1] != b[1]:
                raise r.error("to", f"must have the dimension of 'from' ({a[1]}), got {b[1]}")
            if spacing == "log" and not (a[0] > 0 and b[0] > 0):
                raise r.error("spacing", "'log' needs positive 'from' and 'to'")
            vals = np.geomspace(a[0], b[0], k) if spacing == "log" else np.linspace(a[0], b[0], k)
            return vals, a[1]
        items = v if isinstance(v, list) else [v]
        if not items:
            raise t.error(name, "is empty")
        got = [one(x, i) for i, x in enumerate(items)]
        if len({d for _, d in got}) > 1:
            raise t.error(name, "mixes forces and forces per length")
        return np.array([x for x, _ in got]), got[0][1]
    except UnitError as e:
        raise t.error(name, str(e) + " (or a list of them, or {from, to, points, spacing})") from None


def positive_quantity(t: Table, name, x, dim):
    try:
        x = parse(x, dim)
    except UnitError as e:
        raise t.error(name, str(e)) from None
    if not x > 0:
        raise t.error(name, f"values must be > 0, got {x!r}")
    return x
