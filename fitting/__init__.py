"""fitting: calibrate vjax materials from DMA data (readers, master curve, Prony fit, CLI).

>>> import jax; jax.config.update("jax_enable_x64", True)
>>> from fitting import calibrate, dma
>>> mat, shift, report = calibrate(dma.default_data("pyvisco"), T_ref=25.0)   # doctest: +SKIP
>>> print(report.table())                                                      # doctest: +SKIP

Modules: :mod:`fitting.dma` (readers), :mod:`fitting.master` (shift factors, WLF/Arrhenius),
:mod:`fitting.rawfile` (what the readers share), :mod:`fitting.prony` (Prony fit with free times,
refinement), :mod:`fitting.spectrum` (smooth spectra: fixed times, penalty chosen by GCV),
:mod:`fitting.evaluate` (fits evaluated in numpy: errors, loss-modulus extrema, G/E),
:mod:`fitting.optim` (NNLS, the Levenberg-Marquardt rule and its two drivers, covariances),
:mod:`fitting.relaxation` (relaxation data E(t)), :mod:`fitting.calibration` (the whole chain),
:mod:`fitting.io` (material JSON), :mod:`fitting.files` (atomic writes),
:mod:`fitting.plots` (and :mod:`fitting.figures`, a calibration's set of figures, drawn in
parallel by the command line), :mod:`fitting.cli` (``vjax-fit``), :mod:`fitting.eplexor` (Netzsch
Eplexor .xls), :mod:`fitting.export` and :mod:`fitting.export_cli` (``vjax-export``: Abaqus,
ANSYS, LS-DYNA, COMSOL; docs/fem_export.md), :mod:`fitting.compact` (the fewest-term series
for FEM codes), :mod:`fitting.jax_cache` (the tools' compilation cache).
"""
import importlib

# Lazy: ``import fitting`` (or a submodule such as ``fitting.files``, or the command-line
# tools) must not import vjax and JAX before the caller has chosen float64.
_EXPORTS = {"calibrate": "calibration", "Report": "calibration", "read": "dma", "DMATable": "dma",
            "DMAFormatError": "dma", "default_data": "dma", "load_material": "io", "save_material": "io",
            "ShiftTable": "master"}
__all__ = list(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        return getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
    raise AttributeError(f"module 'fitting' has no attribute {name!r}")
