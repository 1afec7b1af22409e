"""Plots of a calibration (master curve, shift factors with the WLF and Arrhenius laws,
residuals, relaxation spectrum, temperature sweeps at fixed frequency, van Gurp-Palmen) and
of a torque fit (torque before/after, moduli before/after).

Each function draws on a new matplotlib :class:`~matplotlib.figure.Figure` on the Agg canvas
(no pyplot: no display, no global figure list) and, when ``path`` is given, saves it
atomically (temporary file + os.replace). The layouts are fixed margins in inches (see
:func:`_figure`): the constrained-layout engine cost half the drawing time of a cached
``vjax-fit`` call. :mod:`fitting.calibration.figures` draws a calibration's set of figures (in parallel
worker processes for the command line); :mod:`fitting.calibration.pipeline` and the command lines
import this module (and matplotlib) only when they plot.
"""
from __future__ import annotations

import os
import re

import matplotlib.ticker as ticker
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from fitting.shared import evaluate
from fitting.shared import files

__all__ = ["master_curve", "relaxation_curve", "shift_factors", "residuals", "spectrum", "temperature_sweep", "van_gurp_palmen",
           "torque_fit", "moduli"]


_SUPERSCRIPT = str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079")


def _plain(label: str) -> str:
    """A mathtext log tick label ('$\\mathdefault{2\\times10^{-4}}$') as plain text (2×10⁻⁴)."""
    if not label.startswith("$"):
        return label
    label = label.strip("$").replace(r"\mathdefault", "").replace(r"\times", "\u00d7").replace(r"\minus", "-")
    label = re.sub(r"\^\{([^}]*)\}", lambda m: m.group(1).translate(_SUPERSCRIPT), label)
    return label.replace("{", "").replace("}", "")


class _PlainLogFormatter(ticker.LogFormatterSciNotation):
    """Log-axis tick labels in plain text: matplotlib's mathtext labels cost more to parse than
    the rest of a figure (about a third of a cached ``vjax-fit`` call went into them)."""

    def __call__(self, x, pos=None):
        return _plain(super().__call__(x, pos))


# fixed margins (inches): room for the tick labels and axis label on the left and below, for
# a title above, for a colorbar with its label on the right, and between panels
_LEFT, _RIGHT, _BOTTOM, _TOP, _TITLE, _GAP, _COLORBAR = 0.95, 0.2, 0.6, 0.25, 0.55, 0.95, 1.05


def _figure(width, height, ncols=1, *, title=False, colorbar=False, sharey=False):
    """A figure of ``width`` x ``height`` inches with ``ncols`` axes in a row at fixed margins;
    ``title``: room for a title or suptitle; ``colorbar``: a colorbar axes at the right.
    Returns ``(fig, axes)`` (one Axes, or an array for ``ncols`` > 1) or, with ``colorbar``,
    ``(fig, axes, colorbar_axes)``."""
    fig = Figure(figsize=(width, height))
    FigureCanvasAgg(fig)
    right = _RIGHT + (_COLORBAR if colorbar else 0.0)
    top = _TITLE if title else _TOP
    gap = 0.3 if sharey else _GAP
    axw = (width - _LEFT - right - gap * (ncols - 1)) / ncols
    axes = fig.subplots(1, ncols, sharey=sharey,
                        gridspec_kw=dict(left=_LEFT / width, right=1 - right / width, bottom=_BOTTOM / height,
                                         top=1 - top / height, wspace=gap / axw))
    if not colorbar:
        return fig, axes
    cax = fig.add_axes(((width - right + 0.2) / width, _BOTTOM / height, 0.15 / width,
                        1 - (_BOTTOM + top) / height))
    return fig, axes, cax


def _save(fig, path):
    if path is None:
        return fig
    for ax in fig.axes:
        for axis, lim in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            if axis.get_scale() == "log":
                axis.set_major_formatter(_PlainLogFormatter(10.0))
                axis.set_minor_formatter(_PlainLogFormatter(10.0, labelOnlyBase=False))
                # minor ticks at 2 and 5 per decade, none over more than three decades
                # (unlabelled clutter there): matplotlib builds every tick as five artists,
                # and ticks were most of the drawing time
                axis.set_minor_locator(ticker.NullLocator() if max(lim) > 1e3 * min(lim)
                                       else ticker.LogLocator(10.0, subs=(2.0, 5.0)))
    # zlib level 1: a third of the encoding time of the default 6, files about 8% larger
    files.save_figure(fig, path, dpi=110, pil_kwargs={"compress_level": 1})
    return os.fspath(path)


def _reduced(table, shift):
    return table.omega * 10.0 ** evaluate.log10_aT(shift, table.T)


def master_curve(table, material, shift, path=None):
    """Storage and loss (Pa) versus reduced angular frequency a_T omega (rad/s) at T_ref:
    data coloured by temperature, fitted Prony series as lines."""
    wr = _reduced(table, shift)
    fig, ax, cax = _figure(11, 4.2, 2, title=True, colorbar=True)
    sc = None
    for a, y, lab in ((ax[0], table.storage, "storage"), (ax[1], table.loss, "loss")):
        sc = a.scatter(wr, y, c=table.T, s=9, cmap="coolwarm")
        a.set_xscale("log")
        a.set_yscale("log")
        a.set_xlabel("reduced angular frequency a_T ω (rad/s)")
        a.set_ylabel(f"{lab} modulus {table.kind}{chr(39) if lab == 'storage' else 2 * chr(39)} (Pa)")
    w = np.logspace(np.log10(wr.min()) - 0.5, np.log10(wr.max()) + 0.5, 400)
    E = evaluate.modulus(material, w)
    ax[0].plot(w, E.real, "k-", lw=1.2, label=f"Prony, {material.moduli.shape[0]} terms")
    ax[1].plot(w, E.imag, "k-", lw=1.2)
    ax[0].legend(loc="lower right")
    fig.colorbar(sc, cax=cax, label="T (C)")
    fig.suptitle(f"master curve at T_ref = {float(shift.T_ref):g} C")
    return _save(fig, path)


def shift_factors(data_shift, shift, path=None, laws=None):
    """log10 a_T per sweep (``data_shift``, a ShiftTable estimated from the data or refined)
    with the material's shift law and both closed-form laws: the material's own WLF or
    Arrhenius, the other one (or both, for a table law) from ``laws`` ({'WLF': law, ...}, e.g.
    fitted end to end by :func:`fitting.calibrate`) or else fitted to the per-sweep factors
    (:func:`fitting.calibration.master.fit_law`); the legend gives each one's rms distance from the table
    and says which law the material uses."""
    from fitting.calibration.master import fit_law
    T, values = np.asarray(data_shift.T, float), np.asarray(data_shift.values, float)
    if T.size == 0 or T.shape != values.shape or not (np.all(np.isfinite(T)) and np.all(np.isfinite(values))):
        raise ValueError("data_shift must hold finite per-sweep shift factors (T and log10 a_T of equal length)")
    own = type(shift).__name__
    own = "table" if own == "ShiftTable" else own
    fig, ax = _figure(6.2, 4.4, title=True)
    ax.plot(T, values, "o", color="k", ms=5, label="per sweep (table)")
    Tl = np.linspace(T.min() - 5.0, T.max() + 5.0, 300)
    for law, style in (("table", "k-"), ("WLF", "C0--"), ("Arrhenius", "C3-.")):
        if law == own:
            fitted, note = shift, "the material's law"
        elif law == "table":
            continue
        elif laws and law in laws:
            fitted = laws[law]
            rms = float(np.sqrt(np.mean((evaluate.log10_aT(fitted, T) - values) ** 2)))
            note = f"fitted end to end, rms {rms:.3f} dec from the table"
        else:
            fitted, rms = fit_law(data_shift, law)
            note = f"fitted to the table, rms {rms:.3f} dec"
        Tv = Tl
        if law == "WLF":   # only above the WLF asymptote T_ref - C2
            Tv = Tl[Tl > float(fitted.T_ref) - float(fitted.C2) + 1e-6 * max(1.0, float(fitted.C2))]
        consts = {"table": "", "WLF": f": C1 = {float(getattr(fitted, 'C1', 0)):.4g}, "
                                      f"C2 = {float(getattr(fitted, 'C2', 0)):.4g} K",
                  "Arrhenius": f": Ea = {float(getattr(fitted, 'Ea', 0)) / 1e3:.4g} kJ/mol"}[law]
        ax.plot(Tv, evaluate.log10_aT(fitted, Tv), style, lw=2.0 if law == own else 1.2,
                label=f"{law}{consts} ({note})")
    ax.axvline(float(shift.T_ref), color="0.7", lw=0.8)
    ax.set_xlabel("temperature T (°C)")
    ax.set_ylabel("log₁₀ a_T")
    ax.set_title(f"shift factors, T_ref = {float(shift.T_ref):g} °C; the material uses: {own}", fontsize=10)
    ax.legend(fontsize=8)
    return _save(fig, path)


def _check_frequencies(frequencies):
    f = np.atleast_1d(np.asarray(frequencies, float))
    if f.size == 0 or f.ndim != 1 or not np.all(np.isfinite(f) & (f > 0)):
        raise ValueError(f"frequencies must be a non-empty list of finite values > 0 (Hz), got {frequencies!r}")
    return f


def _check_table(table):
    if len(table) == 0:
        raise ValueError("the DMA table holds no points")


def _valid_temperatures(shift, T):
    """``T`` without the temperatures at or below a WLF law's asymptote T_ref - C2."""
    if hasattr(shift, "C2"):
        T = T[T > float(shift.T_ref) - float(shift.C2) + 1e-6 * max(1.0, float(shift.C2))]
    return T


def temperature_sweep(table, material, shift, frequencies=(1.0, 10.0), path=None):
    """A DMA temperature sweep rebuilt from the fit: storage, loss (Pa) and tan delta versus
    temperature (°C) at fixed ``frequencies`` (Hz), E*(2 pi f a_T(T)) (time-temperature
    superposition, docs/theory.md §14), lines; the measured points at those frequencies
    (within 2 %), markers."""
    _check_table(table)
    freqs = _check_frequencies(frequencies)
    k = table.kind
    T = _valid_temperatures(shift, np.linspace(table.T.min(), table.T.max(), 300))
    if T.size == 0:
        raise ValueError("the shift law is undefined over the data's temperatures")
    aT = 10.0 ** evaluate.log10_aT(shift, T)
    fig, ax = _figure(15, 4.2, 3, title=True)
    for j, f in enumerate(freqs):
        E = evaluate.modulus(material, 2 * np.pi * f * aT)
        c = f"C{j % 10}"
        for a, y in zip(ax, (E.real, E.imag, E.imag / E.real)):
            a.plot(T, y, "-", color=c, label=f"fit, {f:g} Hz")
        m = np.abs(np.log10(table.f / f)) < np.log10(1.02)
        if m.any():
            for a, y in zip(ax, (table.storage[m], table.loss[m], table.loss[m] / table.storage[m])):
                a.plot(table.T[m], y, "o", color=c, ms=4, mfc="none", label=f"data, {f:g} Hz")
    labels = (f"storage modulus {k}′ (Pa)", f"loss modulus {k}″ (Pa)", "loss factor tan δ")
    for a, lab in zip(ax, labels):
        a.set_yscale("log")
        a.set_xlabel("temperature T (°C)")
        a.set_ylabel(lab)
    ax[0].legend(fontsize=8)
    fig.suptitle("temperature sweep at fixed frequency, rebuilt from the fitted master curve and shift law")
    return _save(fig, path)


def van_gurp_palmen(table, material, shift, path=None):
    """Van Gurp-Palmen plot: phase angle delta = atan(loss/storage) (degrees) versus |E*| (Pa),
    data coloured by temperature and the fit over the data's reduced-frequency range (one
    curve when time-temperature superposition holds)."""
    _check_table(table)
    mag, delta = np.hypot(table.storage, table.loss), np.degrees(np.arctan2(table.loss, table.storage))
    wr = _reduced(table, shift)
    w = np.logspace(np.log10(wr.min()) - 0.5, np.log10(wr.max()) + 0.5, 400)
    E = evaluate.modulus(material, w)
    fig, ax, cax = _figure(6.2, 4.4, title=True, colorbar=True)
    sc = ax.scatter(mag, delta, c=table.T, s=10, cmap="coolwarm", label="data")
    ax.plot(np.abs(E), np.degrees(np.angle(E)), "k-", lw=1.2, label=f"Prony fit, {material.moduli.shape[0]} terms")
    ax.set_xscale("log")
    ax.set_xlabel(f"complex modulus |{table.kind}*| (Pa)")
    ax.set_ylabel("phase angle δ (°)")
    ax.legend(fontsize=8)
    fig.colorbar(sc, cax=cax, label="T (°C)")
    ax.set_title("van Gurp-Palmen plot")
    return _save(fig, path)


def residuals(table, material, shift, path=None):
    """log10(model/measured) of storage and loss versus reduced frequency, by temperature."""
    wr = _reduced(table, shift)
    E = evaluate.modulus(material, wr)
    fig, ax = _figure(7, 4.2)
    ax.scatter(wr, np.log10(E.real / table.storage), c=table.T, s=9, cmap="coolwarm", marker="o", label="storage")
    ax.scatter(wr, np.log10(E.imag / table.loss), c=table.T, s=12, cmap="coolwarm", marker="x", label="loss")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlabel("reduced angular frequency a_T ω (rad/s)")
    ax.set_ylabel("log₁₀(model / measured)")
    ax.legend()
    return _save(fig, path)


def spectrum(material, path=None):
    """Relaxation spectrum: E_k (Pa) at tau_k (s), and the relaxation modulus E(t)."""
    tau, Ek = np.asarray(material.times), np.asarray(material.moduli)
    fig, ax = _figure(6, 4.2)
    ax.vlines(tau, 1e-300, Ek, color="C0")
    ax.plot(tau, Ek, "o", color="C0", label="E_k at τ_k")
    t = np.logspace(np.log10(tau.min()) - 1, np.log10(tau.max()) + 1, 300)
    ax.plot(t, evaluate.relaxation(material, t), "k-", lw=1, label="E(t)")
    ax.axhline(float(material.E0), color="0.6", ls="--", lw=0.8, label=f"E0 = {float(material.E0):.3g} Pa")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(max(Ek.min(), float(material.E0) if float(material.E0) > 0 else Ek.min()) / 10, float(material.Einf) * 2)
    ax.set_xlabel("relaxation time (s)")
    ax.set_ylabel("modulus (Pa)")
    ax.legend()
    return _save(fig, path)


def relaxation_curve(table, material, shift, path=None):
    """Relaxation data (a :class:`fitting.measurements.relaxation.RelaxationTable`) against reduced time
    t / a_T, coloured by temperature, with the fitted E(t) at T_ref."""
    tr = table.t / 10.0 ** evaluate.log10_aT(shift, table.T)
    fig, ax, cax = _figure(6.4, 4.4, title=True, colorbar=True)
    sc = ax.scatter(tr, table.modulus, c=table.T, s=9, cmap="coolwarm")
    t = np.logspace(np.log10(tr.min()) - 0.5, np.log10(tr.max()) + 0.5, 400)
    ax.plot(t, evaluate.relaxation(material, t), "k-", lw=1.2, label=f"Prony, {material.moduli.shape[0]} terms")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("reduced time t / a_T (s)")
    ax.set_ylabel(f"relaxation modulus {table.kind}(t) (Pa)")
    ax.legend()
    fig.colorbar(sc, cax=cax, label="T (C)")
    ax.set_title(f"relaxation master curve at T_ref = {float(shift.T_ref):g} C", fontsize=10)
    return _save(fig, path)


def torque_fit(data, fits, sigma, path=None, truth=None):
    """Torque versus speed (rpm of the turning part: the shaft, or a journal bearing's lined
    housing), one colour per (temperature, load): data with error bars, model at the start
    (dotted) and after the fit (dashed), one panel per fit in ``fits``
    (label -> :class:`fitting.torque.TorqueFit`); ``truth`` (optional, twin experiments):
    torques of the true material (thin line)."""
    conds = sorted(set(zip(data.T.tolist(), data.load.tolist())))
    fig, axes = _figure(6 * len(fits), 4.2, len(fits), title=True, sharey=True)
    axes = np.atleast_1d(axes)
    for ax, (label, fit) in zip(axes, fits.items()):
        for j, (Tc, Fc) in enumerate(conds):
            sel = (data.T == Tc) & (data.load == Fc)
            o = np.argsort(data.rpm[sel])
            c = f"C{j % 10}"
            ax.errorbar(data.rpm[sel][o], data.torque[sel][o], yerr=sigma[sel][o], fmt="o", color=c, ms=4,
                        label=f"{Tc:g} C, {Fc:.3g} N/m")
            if truth is not None:
                ax.plot(data.rpm[sel][o], truth[sel][o], "-", color=c, lw=1, alpha=0.5)
            ax.plot(data.rpm[sel][o], fit.torque0[sel][o], ":", color=c)
            ax.plot(data.rpm[sel][o], fit.torque[sel][o], "--", color=c)
        ax.set_xscale("log")
        if np.all(data.torque > 0):
            ax.set_yscale("log")
        ax.set_xlabel("speed (rpm)")
        ax.set_title(f"{label}: start (dotted), fitted (dashed)" + (", truth (thin)" if truth is not None else ""),
                     fontsize=9)
    axes[0].set_ylabel("friction torque (N m/m)")
    axes[0].legend(fontsize=7)
    return _save(fig, path)


def moduli(curves, path=None, bands=()):
    """Storage and loss moduli (Pa) at the shift law's reference temperature for
    ``curves`` = [(Material, label, matplotlib style)], over 1e-8..1e6 rad/s; ``bands``:
    (low, high) reduced-frequency ranges to shade (e.g. what a torque data set probes)."""
    w = np.logspace(-8, 6, 300)
    fig, axes = _figure(11, 4.2, 2, title=True)
    for mat, label, style in curves:
        E = evaluate.modulus(mat, w)
        axes[0].loglog(w, E.real, style, label=label)
        axes[1].loglog(w, E.imag, style, label=label)
    for ax in axes:
        for lo, hi in bands:
            ax.axvspan(lo, hi, color="0.9", zorder=0)
        ax.set_xlabel("reduced angular frequency (rad/s)")
    axes[0].set_ylabel("E' (Pa)")
    axes[1].set_ylabel("E'' (Pa)")
    axes[0].legend(fontsize=8)
    axes[0].set_title("storage modulus" + (" (grey: probed by the torque data)" if bands else ""))
    axes[1].set_title("loss modulus")
    return _save(fig, path)
