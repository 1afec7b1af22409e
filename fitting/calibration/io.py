"""Material JSON files: save and load a fitted Prony material with its shift law.

Schema (temperatures in C, moduli in Pa, times in s)::

    {"kind": "prony", "E0": 1.2e6, "moduli": [...], "times": [...], "nu": 0.5,
     "modulus": "E" | "G",
     "shift": {"law": "WLF", "C1": 8.86, "C2": 101.6, "T_ref": 25.0}
            | {"law": "Arrhenius", "Ea": 2.0e5, "T_ref": 25.0}
            | {"law": "table", "T": [...], "log10_aT": [...], "T_ref": 25.0},
     "shift_alternatives": {"WLF": {"C1": ..., "C2": ..., "T_ref": 25.0, "sigma": {...},
                                    "errors": {...}, "delta_log10_aT_vs_table": {"rms", "max"}},
                            "Arrhenius": {...}},  # optional: closed-form laws fitted as well
     "uncertainty": {...}, "fit": {...}}          # optional, informative only

:func:`closed_form_shift` returns one of the alternatives (e.g. the WLF law that
``vjax-fit-torque`` refines when the material's own law is a table).

Writes are atomic: the JSON goes to a temporary file in the target directory, is flushed
and fsync'ed, then ``os.replace``'d over the target, so a reader never sees half a file.
"""
from __future__ import annotations

import json
import math
import os

import numpy as np

from vjax import Arrhenius, Material, WLF

from fitting.shared.files import write_atomic as atomic_write
from fitting.calibration.master import ShiftTable

__all__ = ["save_material", "load_material", "material_to_dict", "material_from_dict", "closed_form_shift"]


def shift_to_dict(shift) -> dict:
    if isinstance(shift, WLF):
        return {"law": "WLF", "C1": float(shift.C1), "C2": float(shift.C2), "T_ref": float(shift.T_ref)}
    if isinstance(shift, Arrhenius):
        return {"law": "Arrhenius", "Ea": float(shift.Ea), "T_ref": float(shift.T_ref)}
    if isinstance(shift, ShiftTable):
        return {"law": "table", "T": [float(t) for t in np.asarray(shift.T)],
                "log10_aT": [float(v) for v in np.asarray(shift.values)], "T_ref": float(shift.T_ref)}
    raise TypeError(f"cannot save shift law of type {type(shift).__name__}")


def _clean(o):
    """JSON-safe copy: numpy scalars/arrays to Python, non-finite floats to None."""
    if isinstance(o, dict):
        return {str(k): _clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_clean(v) for v in o]
    if isinstance(o, np.ndarray) or hasattr(o, "tolist") and not isinstance(o, (str, bytes)):
        return _clean(np.asarray(o).tolist())
    if isinstance(o, float):
        return o if math.isfinite(o) else None
    return o


def material_to_dict(material: Material, shift, modulus: str = "E", uncertainty=None, fit=None,
                     shift_alternatives=None) -> dict:
    """The JSON object of the module docstring."""
    if modulus not in ("E", "G"):
        raise ValueError(f"modulus must be 'E' or 'G', got {modulus!r}")
    d = {"kind": "prony", "E0": float(material.E0), "moduli": [float(v) for v in np.asarray(material.moduli)],
         "times": [float(v) for v in np.asarray(material.times)], "nu": float(material.nu),
         "modulus": modulus, "shift": shift_to_dict(shift)}
    if shift_alternatives:
        d["shift_alternatives"] = _clean(shift_alternatives)
    if uncertainty:
        d["uncertainty"] = _clean(uncertainty)
    if fit:
        d["fit"] = _clean(fit)
    return d


def save_material(path, material: Material, shift, modulus: str = "E", uncertainty=None, fit=None,
                  shift_alternatives=None) -> None:
    """Save ``material`` (a Prony :class:`vjax.Material`, moduli in Pa) and its shift law
    to ``path`` as JSON, atomically. ``modulus`` says whether the moduli are tensile (E) or
    shear (G)."""
    d = material_to_dict(material, shift, modulus, uncertainty, fit, shift_alternatives)
    atomic_write(path, json.dumps(d, indent=2) + "\n")


def _need(d, key, where):
    if key not in d:
        raise ValueError(f"{where}: missing key {key!r}")
    return d[key]


def material_from_dict(d: dict, where: str = "material"):
    """Inverse of :func:`material_to_dict`: returns ``(Material, shift, modulus)``."""
    if not isinstance(d, dict):
        raise ValueError(f"{where}: expected a JSON object")
    if _need(d, "kind", where) != "prony":
        raise ValueError(f"{where}: kind must be 'prony', got {d['kind']!r}")
    modulus = d.get("modulus", "E")
    if modulus not in ("E", "G"):
        raise ValueError(f"{where}: modulus must be 'E' or 'G', got {modulus!r}")
    E0 = d.get("E0")
    if isinstance(E0, (int, float)) and E0 == 0:
        raise ValueError(f"{where}: E0 = 0, a liquid (no equilibrium modulus): vjax's contact and bearing models "
                         "need a solid (E0 > 0); vjax-export writes such a material's FEM cards (G_inf = 0)")
    try:
        moduli = np.asarray(_need(d, "moduli", where), float)
        times = np.asarray(_need(d, "times", where), float)
        mat = Material.prony(float(_need(d, "E0", where)), moduli, times, float(_need(d, "nu", where)))
    except (TypeError, ValueError) as e:
        raise ValueError(f"{where}: {e}") from None
    s = _need(d, "shift", where)
    law = _need(s, "law", where + " shift")
    T_ref = float(_need(s, "T_ref", where + " shift"))
    try:
        if law == "WLF":
            shift = WLF(float(_need(s, "C1", where)), float(_need(s, "C2", where)), T_ref)
        elif law == "Arrhenius":
            shift = Arrhenius(float(_need(s, "Ea", where)), T_ref)
        elif law == "table":
            shift = ShiftTable.make(_need(s, "T", where), _need(s, "log10_aT", where), T_ref)
        else:
            raise ValueError(f"unknown shift law {law!r} (WLF, Arrhenius or table)")
    except (TypeError, ValueError) as e:
        raise ValueError(f"{where} shift: {e}") from None
    return mat, shift, modulus


def _read_json(path) -> dict:
    path = os.fspath(path)
    with open(path, encoding="utf-8") as fh:
        try:
            return json.load(fh)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}, line {e.lineno}: invalid JSON ({e.msg})") from None


def closed_form_shift(path, law: str = "WLF"):
    """The ``law`` ('WLF' or 'Arrhenius') of a material JSON file: its own shift law if it is
    that law, else the alternative fitted with it (``shift_alternatives``). Raises ValueError
    naming the file when it carries neither."""
    d = _read_json(path)
    own = (d.get("shift") or {}).get("law")
    if own == law:
        return material_from_dict(d, where=os.fspath(path))[1]
    alt = (d.get("shift_alternatives") or {}).get(law)
    if not isinstance(alt, dict):
        raise ValueError(f"{os.fspath(path)}: the shift law is {own!r} and the file carries no fitted {law} "
                         f"alternative; refit with vjax-fit (which fits WLF and Arrhenius as well) or --law {law}")
    return material_from_dict(dict(d, shift=dict(alt, law=law)), where=os.fspath(path))[1]


def load_material(path):
    """Load a material JSON file; returns ``(Material, shift, modulus)`` with modulus 'E' or
    'G'. Raises ValueError naming the file for malformed content."""
    return material_from_dict(_read_json(path), where=os.fspath(path))
