"""fitting: the inverse problems, data I/O and command-line tools beside vjax.

>>> import jax; jax.config.update("jax_enable_x64", True)
>>> from fitting import calibrate
>>> from fitting.measurements import dma
>>> mat, shift, report = calibrate(dma.default_data("pyvisco"), T_ref=25.0)   # doctest: +SKIP
>>> print(report.table())                                                      # doctest: +SKIP

Rooms, one concern each (a room imports those above it, never a private name of another):

- :mod:`fitting.measurements`: DMA and relaxation files read into tables (numpy only);
- :mod:`fitting.calibration`: shift factors and laws, Prony series, smooth spectra and the fewest-term
  series, the material JSON file, the whole chain (:func:`fitting.calibrate`) and its figures;
- :mod:`fitting.fem`: the cards for Abaqus, ANSYS, LS-DYNA, COMSOL and their readers;
- :mod:`fitting.torque`: a material refined against measured bearing friction torque;
- :mod:`fitting.bearing`: a bearing case file and its sweep (``vjax-bearing``);
- :mod:`fitting.cli`: the four command-line tools;
- :mod:`fitting.shared`: atomic writes, a material's formulas in numpy, least squares, the
  compilation cache.
"""
import importlib

# Lazy: ``import fitting`` (or a submodule such as ``fitting.shared.files``, or the command-line
# tools) must not import vjax and JAX before the caller has chosen float64.
_EXPORTS = {"calibrate": "calibration.pipeline", "Report": "calibration.pipeline", "read": "measurements.dma",
            "DMATable": "measurements.dma", "DMAFormatError": "measurements.dma",
            "default_data": "measurements.dma", "load_material": "calibration.io", "save_material": "calibration.io",
            "ShiftTable": "calibration.master"}
__all__ = list(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        return getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
    raise AttributeError(f"module 'fitting' has no attribute {name!r}")
