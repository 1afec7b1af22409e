"""Level 1 thermal scenes: each scene at the one effective temperature its own dissipation sets,
a scene over the scenes (docs/theory.md §19).

- :mod:`.balance`: :class:`HeatTransfer`, :class:`ThermalResult` and the heat balance, ISO
  7902-1's effective temperature as the root of r(T) = T - T*(T), its failures (thermal
  runaway: :data:`RUNAWAY`) through the core's one failure path;
- :mod:`.journal`: :func:`thermal_journal_bearing`, the film's friction power and the bodies'
  hysteresis carried off by the oil and ``hA``;
- :mod:`.dry`: :func:`thermal_pin`, :func:`thermal_roller`, the polymer ring's hysteresis
  against ``hA``.

The film's temperature field (level 2) is the finite bearing's thermal film:
:mod:`vjax.scenes.journal.finite.thermal`.
"""
from .balance import RUNAWAY, HeatTransfer, ThermalResult
from .dry import thermal_pin, thermal_roller
from .journal import thermal_journal_bearing

__all__ = ["RUNAWAY", "HeatTransfer", "ThermalResult", "thermal_journal_bearing", "thermal_pin", "thermal_roller"]
