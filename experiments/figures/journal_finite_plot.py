"""The figure of the journal stage's finite-length HS case (``journal_finite_hs.png``), drawn
from the solutions :func:`experiments.figures.journal_figures.finite_length` computes: the
mid-plane film, the film along the land, the pressure over the land at L/D = 1, and the bore
torque with its viscoelastic share per case."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from experiments import _common


def draw(path, sols, rows, grid, clearance, E0, case):
    """Save the figure to ``path``: ``sols`` name -> journal solution ("long" and "L/D = ..."),
    ``rows`` name -> their table row (eps, hmid_over_c, CB, share_pct), ``grid`` the finite
    bearings' (n, m), ``clearance`` c (m), ``E0`` the rubbery modulus (Pa), ``case`` the
    parameters' line for the title."""
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5), layout="constrained")
    axes = axes.ravel()
    for name, s in sols.items():
        h = np.asarray(s.film)
        mid = h if h.ndim == 1 else h[:, h.shape[1] // 2]
        theta = s.theta if name != "long" else s.theta + s.attitude_angle     # both from the load line
        theta = np.mod(np.degrees(theta) + 180.0, 360.0) - 180.0
        order = np.argsort(theta)
        axes[0].plot(theta[order], mid[order] / clearance,
                     label=f"{name}: eps = {rows[name]['eps']:.3f}, min film {rows[name]['hmid_over_c']:.4f} c")
        if name != "long":   # along the land at the thinnest angle: the film pinches at the ends
            i = int(np.argmin(np.min(h, axis=1)))
            z = np.asarray(s.z)
            axes[1].plot(2 * z / (z[-1] - z[0]), h[i] / clearance, ".-",
                         label=f"{name}, theta = {float(np.degrees(s.theta[i])):.0f} deg")
    axes[0].set_xlabel("theta from the load line [deg]")
    axes[0].set_ylabel("film h / c at the mid-plane")
    axes[0].set_yscale("log")
    thinnest = min(rows[name]["hmid_over_c"] for name in sols)
    axes[0].set_ylim(bottom=thinnest / 10.0)        # a decade below the film's tips for the legend
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("2 z / L")
    axes[1].set_ylabel("film h / c at its thinnest angle")
    axes[1].legend(fontsize=8)
    s = sols["L/D = 1"]
    theta = np.mod(np.degrees(s.theta) + 180.0, 360.0) - 180.0
    order = np.argsort(theta)
    pressure = np.maximum(np.asarray(s.pressure)[order], 0.0) / E0
    pm = axes[2].contourf(theta[order], np.asarray(s.z) * 1e3, pressure.T, np.linspace(0, pressure.max(), 16),
                          cmap="viridis")
    fig.colorbar(pm, ax=axes[2], label="p / E0", format="%.1e")
    loaded = theta[order][np.max(pressure, axis=1) > 0.01 * pressure.max()]    # the narrow loaded arc
    axes[2].set_xlim(loaded.min() - 10.0, loaded.max() + 10.0)
    axes[2].set_xlabel("theta from the load line [deg]")
    axes[2].set_ylabel("z [mm]")
    axes[2].set_title("pressure over the land, L/D = 1", fontsize=9)
    names = list(sols)
    x = np.arange(len(names))
    torque = axes[3].bar(x - 0.2, [abs(rows[k]["CB"]) for k in names], 0.4, color="C0",
                         label="|bore torque| / (total load R_B), left axis")
    axes[3].set_ylabel("|bore torque| / (total load R_B)", color="C0")
    share = axes[3].twinx()
    shares = share.bar(x + 0.2, [rows[k]["share_pct"] for k in names], 0.4, color="C1",
                       label="viscoelastic share of the bore torque [%], right axis")
    share.set_ylabel("viscoelastic share of the bore torque [%]", color="C1")
    share.set_ylim(0, 1.3 * max(rows[k]["share_pct"] for k in names))     # room for the legend
    axes[3].set_ylim(0, 1.3 * max(abs(rows[k]["CB"]) for k in names))
    share.legend(handles=[torque, shares], fontsize=8, loc="upper center")
    axes[3].set_xticks(x, names)
    fig.suptitle("HS case of finite length beside the infinitely long bearing (the thesis's Hersey number, same mean "
                 f"pressure,\ngroove fixed opposite the load; finite bores: the hole in 3D, {grid[0]} x {grid[1]})\n"
                 f"{case}", fontsize=9)
    _common.save_figure(fig, path)
