"""Quantities with units in a bearing case file (``vjax-bearing``): "50 mm", "3000 rpm", "40 C".

Every dimensional value of a case is a string: a number, a space (optional) and a unit from
the table below; a bare number where a unit is expected is refused (so "0.05" never silently
means metres when millimetres were meant). Dimensionless values (Poisson's ratio, counts, WLF's
C1, whirl ratios) are plain TOML numbers. :func:`parse` returns SI (temperatures in C, as the
rest of vjax).
"""
from __future__ import annotations

import math
import re

__all__ = ["UNITS", "UnitError", "parse", "parse_load"]

#: dimension -> {unit: factor to SI}; temperatures are handled apart (offsets)
UNITS = {
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6},
    "force": {"N": 1.0, "kN": 1e3},
    "force per length": {"N/m": 1.0, "N/mm": 1e3, "kN/m": 1e3},
    "angular speed": {"rad/s": 1.0, "rpm": 2 * math.pi / 60, "rev/s": 2 * math.pi},
    "temperature": {"C": 0.0, "degC": 0.0, "°C": 0.0, "K": -273.15},
    "temperature difference": {"K": 1.0, "C": 1.0, "degC": 1.0, "°C": 1.0},
    "viscosity": {"Pa s": 1.0, "Pa.s": 1.0, "Pa*s": 1.0, "mPa s": 1e-3, "mPa.s": 1e-3, "cP": 1e-3},
    "kinematic viscosity": {"cSt": 1.0, "mm2/s": 1.0, "mm^2/s": 1.0},   # kept in cSt (oil data sheets)
    "modulus": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9},
    "time": {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6},
    "density": {"kg/m3": 1.0, "kg/m^3": 1.0},
    "angle": {"deg": math.pi / 180, "rad": 1.0},
    "molar energy": {"J/mol": 1.0, "kJ/mol": 1e3},
}
EXAMPLE = {"length": "50 mm", "force": "2.5 kN", "force per length": "6500 N/m", "angular speed": "3000 rpm",
           "temperature": "40 C", "temperature difference": "101.6 K", "viscosity": "0.01 Pa s",
           "kinematic viscosity": "32 cSt", "modulus": "1 MPa", "time": "10 ms", "density": "860 kg/m3",
           "angle": "180 deg", "molar energy": "200 kJ/mol"}

_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


class UnitError(ValueError):
    """A value that is not a number with a unit of the expected dimension (the message says
    what was expected; the caller adds the file and the key)."""


def _split(value, dims):
    expect = " or ".join(f"a {d} with its unit, e.g. \"{EXAMPLE[d]}\"" for d in dims)
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise UnitError(f"expected {expect}, got {value!r}")
    if not isinstance(value, str):
        raise UnitError(f"missing unit: expected {expect}, got the bare number {value!r}")
    m = _NUMBER.match(value)
    if not m:
        raise UnitError(f"expected {expect}, got {value!r}")
    number, unit = float(m.group(1)), m.group(2)
    if not unit:
        raise UnitError(f"missing unit: expected {expect}, got {value!r}")
    for d in dims:
        if unit in UNITS[d]:
            return number, unit, d
    known = ", ".join(u for d in dims for u in UNITS[d])
    raise UnitError(f"unknown unit {unit!r} in {value!r}: expected {expect} (units: {known})")


def parse(value, dim: str) -> float:
    """``value`` (e.g. "50 mm") in SI for dimension ``dim`` (a key of :data:`UNITS`);
    temperatures in C. Raises :class:`UnitError`."""
    number, unit, _ = _split(value, (dim,))
    if dim == "temperature":
        return number + UNITS[dim][unit]
    return number * UNITS[dim][unit]


def parse_load(value) -> tuple[float, str]:
    """A load: a force ("2.5 kN", returned in N) or a force per axial length ("6500 N/m", in
    N/m); returns (value, dimension)."""
    number, unit, dim = _split(value, ("force", "force per length"))
    return number * UNITS[dim][unit], dim
