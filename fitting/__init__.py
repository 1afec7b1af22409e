"""fitting: calibrate vjax materials from DMA data (readers, master curve, Prony fit, CLI).

>>> import jax; jax.config.update("jax_enable_x64", True)
>>> from fitting import calibrate, dma
>>> mat, shift, report = calibrate(dma.default_data("pyvisco"), T_ref=25.0)   # doctest: +SKIP
>>> print(report.table())                                                      # doctest: +SKIP

Modules: :mod:`fitting.dma` (readers), :mod:`fitting.master` (shift factors, WLF/Arrhenius),
:mod:`fitting.prony` (Prony fit and refinement), :mod:`fitting.io` (material JSON),
:mod:`fitting.plots`, :mod:`fitting.cli` (``vjax-fit``).
"""
from .calibrate import Report, calibrate
from .dma import DMAFormatError, DMATable, default_data, read
from .io import load_material, save_material
from .master import ShiftTable

__all__ = ["calibrate", "Report", "read", "DMATable", "DMAFormatError", "default_data", "load_material",
           "save_material", "ShiftTable"]
