"""Writes the three example notebooks (nbformat 4) from the cell sources below.

Run ``python notebooks/_make.py --execute`` after editing; the notebooks are generated, not
edited by hand. It runs them (each in a fresh Jupyter kernel,
about 20-40 s each) and stores them with their outputs, figures included, so the repository
page shows them; tests/test_notebooks.py re-executes them and fails when the stored outputs
are stale. Files a notebook writes go to ``VJAX_NOTEBOOK_OUT`` (default ``nb_out``, in a
temporary folder when run from here).
"""
import os
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

SETUP = '''import os, sys
# run from the notebooks/ folder or the repository root without installing vjax
for _p in (os.path.abspath(".."), os.path.abspath(".")):
    if os.path.isdir(os.path.join(_p, "vjax")) and _p not in sys.path:
        sys.path.insert(0, _p)
import jax
jax.config.update("jax_enable_x64", True)   # before any JAX computation
import jax.numpy as jnp
import numpy as np
import matplotlib.pyplot as plt
import vjax
OUT = os.environ.get("VJAX_NOTEBOOK_OUT", "nb_out")
os.makedirs(OUT, exist_ok=True)
print("output folder:", OUT)'''

NB1 = [
    ("md", "# 1. Calibrate a viscoelastic material from DMA data\n\n"
           "Read a DMA file (storage and loss modulus at several temperatures and frequencies), "
           "build the master curve, fit a Prony series and a shift law, and save the material as "
           "JSON for the bearing scenes. Data: the pyvisco example shipped with `fitting` "
           "(tensile, 21 temperatures from -50 to 100 C, BSD-3)."),
    ("code", SETUP),
    ("code", '''import fitting
from fitting.measurements import dma
from fitting.calibration import master, prony
path = dma.default_data("pyvisco")
table = dma.read(path)
print(table.summary())'''),
    ("md", "## Master curve and shift law\n\n`fitting.calibrate` chains: shift factors from the "
           "overlap of neighbouring sweeps, a Prony fit (number of terms by BIC), an end-to-end "
           "refinement on the raw data and a shift law. Step by step here, on the operating range "
           "10-100 C, above the glass transition, where a WLF law holds (over the whole -50..100 C a "
           "single WLF law misses the measured shifts by about 3 decades; the one call below picks a "
           "table instead)."),
    ("code", '''sub = table.subset((table.T >= 10) & (table.T <= 100))
T_ref = 25.0
shifts = master.shift_factors(sub, T_ref)           # log10 a_T per sweep from the data overlap
wlf, rms = master.fit_law(shifts, "WLF")
print(f"WLF: C1 = {float(wlf.C1):.3g}, C2 = {float(wlf.C2):.3g} C (rms {rms:.3f} decades)")
wr = sub.omega * 10.0 ** np.asarray(wlf.log10_aT(sub.T))   # reduced frequency at T_ref
E0, Ek, tau = prony.fit_master(wr, sub.storage, sub.loss, density=1.0)
start = vjax.Material.prony(E0, Ek, tau, 0.5)
fit = prony.refine(sub, start, wlf, max_iter=300)
material, shift = fit.material, fit.shift
print(f"{fit.terms} Prony terms, rms log10 error {fit.rms:.4f}, shift {shift}")
err = prony.raw_errors(material, shift, sub)        # |log10(fit/data)|, in decades
print(f"storage: median {err['storage_median']:.4f}, p90 {err['storage_p90']:.4f} decades; "
      f"loss: median {err['loss_median']:.4f}, p90 {err['loss_p90']:.4f} decades")'''),
    ("code", '''fig, ax = plt.subplots(1, 2, figsize=(11, 4))
w = np.logspace(np.log10(wr.min()) - 1, np.log10(wr.max()) + 1, 300)
E = np.asarray(material.modulus(w))
ax[0].loglog(wr, sub.storage, ".", ms=3, label="data (shifted)")
ax[0].loglog(w, E.real, "k-", label="Prony fit")
ax[1].loglog(wr, sub.loss, ".", ms=3)
ax[1].loglog(w, E.imag, "k-")
for a, lab in zip(ax, ("E' (Pa)", "E'' (Pa)")):
    a.set_xlabel(f"reduced frequency at {T_ref:g} C (rad/s)"); a.set_ylabel(lab)
ax[0].legend()
fig.savefig(os.path.join(OUT, "01_master_curve.png"), dpi=100)'''),
    ("md", "## One call, with plots and JSON\n\n`fitting.calibrate(paths, T_ref, out_dir)` does all of "
           "the above (and picks the shift law by BIC), and writes the material and its plots. It takes about ten seconds on the "
           "whole data set."),
    ("code", '''json_path = os.path.join(OUT, "material.json")
material, shift, report = fitting.calibrate(path, T_ref, out_dir=OUT)
print(report.table())
from IPython.display import Image, display   # two of the plots calibrate wrote next to the JSON
for f in report.outputs:
    if f.endswith(("_master.png", "_shift.png")):
        display(Image(filename=f))
mat2, shift2, kind = fitting.load_material(json_path)
print("reloaded:", kind, "E0 =", float(mat2.E0), "Pa,", mat2.moduli.shape[0], "terms,", type(shift2).__name__)'''),
    ("md", "## Use it in a scene\n\nThe material takes its shift law once, `mat2.with_shift(shift2)`; every "
           "scene's `temperature=` then moves it (the material alone at 60 C is "
           "`mat2.with_shift(shift2).at_temperature(60.0)`). Friction torque of a polymer pin joint "
           "(rigid pin in a plate of this material) versus shaft speed, vmapped over speeds:"),
    ("code", '''R, R_pin = 0.01, 0.0099
load = 1e-2 * float(mat2.E0) * R
rpm = np.geomspace(10, 3000, 20)
def torque(rpm_, T):
    return vjax.pin_in_hole(mat2.with_shift(shift2), R, R - R_pin, load, omega_shaft=rpm_ * 2 * np.pi / 60,
                            temperature=T, options=vjax.PinOptions(n=256), throw=False).torque
fig, ax = plt.subplots()
for T in (40.0, 70.0):
    tq = jax.jit(jax.vmap(lambda s: torque(s, T)))(jnp.asarray(rpm))
    ax.loglog(rpm, np.asarray(tq), "o-", label=f"{T:g} C")
ax.set_xlabel("shaft speed (rpm)"); ax.set_ylabel("friction torque (N m/m)"); ax.legend()
fig.savefig(os.path.join(OUT, "01_pin_torque.png"), dpi=100)'''),
]

NB2 = [
    ("md", "# 2. Explore and optimize a needle roller bearing\n\n"
           "The thesis bearing (Section 2.3): outer ring R_O = 6 mm, inner ring R_I = 4 mm, 9 rigid "
           "rollers of 2 mm, both rings of a standard linear solid (E0 = 1 MPa, Einf = 10 MPa, "
           "tau = 0.01 s, nu = 0.5), load F~ = F/(E0 R_O) = 6.5e-3, outer ring fixed."),
    ("code", SETUP),
    ("code", '''m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)
R_O, R_I, D, Z = 6e-3, 4e-3, 2e-3, 9
load = 6.5e-3 * 1e6 * R_O
n = 256
opts = vjax.RollerOptions(n=n)
r = vjax.roller_bearing(m, m, R_O, R_I, D, Z, load, omega_shaft=10.0, options=opts)
print(r.summary())
print("converged:", bool(r.converged), "Newton iterations:", int(r.iterations))
print("roller loads (N/m):", np.round(np.asarray(r.roller_loads[0]), 2))
print("friction torque on the outer ring (N m/m):", float(r.torque))'''),
    ("code", '''fig, ax = plt.subplots(subplot_kw={"projection": "polar"})
ax.plot(np.asarray(r.theta[0]), np.asarray(r.pressure[0]) / 1e6, label="outer ring")
ax.plot(np.asarray(r.theta[1]), np.asarray(r.pressure[1]) / 1e6, label="inner ring")
ax.set_title("contact pressure (MPa)"); ax.legend(loc="lower left")
fig.savefig(os.path.join(OUT, "02_pressure.png"), dpi=100)'''),
    ("md", "## Speed sweep with continuation\n\nEach speed starts from the previous solution "
           "(`initial=`), which is faster and stays on the same branch. The thesis speed is "
           "omega~ = |omega_c - omega_O| tau."),
    ("code", '''speeds = np.geomspace(1.0, 300.0, 12)     # shaft speed, rad/s
torques, prev = [], None
for w in speeds:
    prev = vjax.roller_bearing(m, m, R_O, R_I, D, Z, load, omega_shaft=float(w), options=opts, initial=prev)
    torques.append(float(prev.torque))
fig, ax = plt.subplots()
wt = np.abs(np.asarray([vjax.roller_patch_speeds(w, 0.0, R_I, R_O)[1] for w in speeds])) * 0.01
ax.semilogx(wt, torques, "o-")
ax.set_xlabel("omega~ = |omega_c| tau"); ax.set_ylabel("friction torque (N m/m)")
fig.savefig(os.path.join(OUT, "02_torque_speed.png"), dpi=100)'''),
    ("md", "**How far to trust a torque:** the torque comes from the spectral slope of the deformed "
           "rings, so R * sum(p u') is exactly the power the ring dissipates divided by the patch speed: "
           "it vanishes for an elastic ring on any grid, and at n = 256 (patches a few elements wide) "
           "it is within about 15% of a 16x finer grid (`tests/test_roller.py`). Compare with a run at "
           "`n = 1024` before quoting a number."),
    ("md", "## Gradients with respect to design parameters\n\nThe bearing is differentiable "
           "(implicit differentiation at the converged solution). The design objective below is the "
           "friction torque plus a quadratic penalty when the peak contact pressure exceeds a bound; "
           "one compiled function gives it, the torque, the peak pressure and the gradient with "
           "respect to the diametral clearance (negative = preload) and the shaft speed."),
    ("code", '''p_max = 1.2 * float(jnp.max(r.pressure))              # allowed peak pressure (Pa)
scale = abs(float(r.torque))
def objective(clearance, omega):
    res = vjax.roller_bearing(m, m, R_O, R_I, D, Z, load, diametral_clearance=clearance, omega_shaft=omega,
                              options=opts, throw=False)
    tq, peak = jnp.abs(res.torque), jnp.max(res.pressure)
    return tq + 10.0 * scale * jnp.maximum(peak / p_max - 1.0, 0.0) ** 2, (tq, peak)
grad_fn = jax.jit(jax.value_and_grad(objective, argnums=(0, 1), has_aux=True))
(f0, (tq0, pk0)), (df_dc, df_dw) = grad_fn(0.0, 30.0)
print(f"torque {float(tq0):.4g} N m/m, peak pressure {float(pk0) / 1e6:.3f} MPa")
print(f"d objective/d clearance = {float(df_dc):.4g} (N m/m)/m, d objective/d omega = {float(df_dw):.4g}")
h = 1e-7
fd = (objective(h, 30.0)[0] - objective(-h, 30.0)[0]) / (2 * h)
print(f"finite difference d/d clearance: {float(fd):.4g}")'''),
    ("md", "## Which body? A bushing in a holder versus the thesis's infinite plane\n\n"
           "The thesis models the outer ring as a hole in an infinite plane; a real polymer outer race is "
           "a bushing pressed into a steel holder: `vjax.liner(material, thickness)`. A polymer-sleeved "
           "shaft is `vjax.sleeve(material, thickness)`. Pick a hole or a disc for a part much thicker "
           "than the contact and the clearance, a liner or a sleeve for a layer whose thickness is "
           "comparable to the contact width or the radius. Layers have no log reference length."),
    ("code", '''for name, housing in (("infinite plane", m), ("2 mm bushing", vjax.liner(m, 2e-3)),
                      ("0.5 mm bushing", vjax.liner(m, 0.5e-3))):
    rb = vjax.roller_bearing(housing, None, R_O, R_I, D, Z, load, omega_shaft=10.0, options=opts)
    print(f"{name:15s} torque {float(rb.torque):.4g} N m/m, roller loads "
          + " ".join(f"{q:.1f}" for q in rb.roller_loads[0, :3]) + " N/m")'''),
    ("md", "## A small design optimization\n\nMinimize the penalized torque over the clearance "
           "(preload allowed down to -20 um) by sign-gradient steps with a shrinking step (scale-free); "
           "each step is one solve plus its implicit gradient."),
    ("code", '''c, step = 0.0, 4e-6
for k in range(12):
    (f, (tq, pk)), (g, _) = grad_fn(c, 30.0)
    print(f"step {k}: clearance {c * 1e6:7.2f} um, torque {float(tq):.5g}, peak {float(pk) / 1e6:.3f} MPa")
    c = float(np.clip(c - step * np.sign(g), -20e-6, 20e-6))
    step *= 0.7
(f, (tq, pk)), _ = grad_fn(c, 30.0)
print(f"final: clearance {c * 1e6:.2f} um, torque {float(tq):.5g} N m/m, peak pressure "
      f"{float(pk) / 1e6:.3f} MPa (bound {p_max / 1e6:.3f})")'''),
]

NB3 = [
    ("md", "# 3. Journal bearing with a viscoelastic liner (VEHL)\n\n"
           "Thesis Chapter 3: bore R_B = 0.1 m, clearance c = 0.5 mm, eta = 1e-3 Pa s, soft bearing "
           "liner (SLS, Einf = 100 MPa, Einf/E0 = 100, tau = 1 s, nu = 0.5), rigid journal (HS), "
           "F~ = |F|/(E0 R_B) = 2.2e-3, omega~_B = 0.2, omega~_J = -0.4."),
    ("code", SETUP),
    ("code", '''bearing = vjax.Material.sls(1e6, 1e8, 1.0, 0.5)
R_B, c, eta = 0.1, 5e-4, 1e-3
load = 2.2e-3 * 1e6 * R_B
n = 256
opts = vjax.JournalOptions(n=n)
sol = vjax.journal_bearing(R_B, c, eta, load, housing=bearing, omega_shaft=-0.4, omega_housing=0.2, options=opts)
print(sol.summary())
print("converged:", bool(sol.converged), "| eps =", float(sol.eccentricity),
      "| effective eps =", float(sol.eccentricity_effective))
print("min film (um):", 1e6 * float(sol.min_film), "| bearing torque (N m/m):", float(sol.torque),
      "| viscoelastic part:", float(sol.torque_viscoelastic))'''),
    ("code", '''th = np.asarray(sol.theta)
fig, ax = plt.subplots(1, 2, figsize=(11, 4))
ax[0].plot(th, np.asarray(sol.pressure) / 1e3); ax[0].set_ylabel("pressure (kPa)")
ax[1].plot(th, 1e6 * np.asarray(sol.film)); ax[1].set_ylabel("film h (um)")
for a in ax:
    a.set_xlabel("theta (rad, line-of-centres frame)")
fig.savefig(os.path.join(OUT, "03_profiles.png"), dpi=100)'''),
    ("md", "## Speed sweep (warm-started)\n\nThe journal speed changes with the bearing speed fixed; "
           "each solve starts from the previous one."),
    ("code", '''wj = -np.geomspace(0.4, 1.6, 10)
rows, prev = [], sol
for w in wj:
    s = vjax.journal_bearing(R_B, c, eta, load, housing=bearing, omega_shaft=float(w), omega_housing=0.2,
                             options=opts, initial=prev, throw=False)
    print(f"omega_J = {w:.3f}: converged {bool(s.converged)}")
    if bool(s.converged):
        prev = s
        rows.append((float(w), float(s.min_film), float(s.torque), float(s.torque_viscoelastic)))
rows = np.array(rows)
fig, ax = plt.subplots()
ax.plot(-rows[:, 0], rows[:, 2], "o-", label="bearing torque")
ax.plot(-rows[:, 0], rows[:, 3], "s--", label="viscoelastic part")
ax.set_xlabel("-omega_J (rad/s)"); ax.set_ylabel("torque (N m/m)"); ax.legend()
fig.savefig(os.path.join(OUT, "03_sweep.png"), dpi=100)
print(rows)'''),
    ("md", "## Design gradients: clearance and viscosity\n\nPower loss and minimum film as functions "
           "of the clearance and the viscosity, with their gradients (implicit differentiation "
           "through the coupled Reynolds-elasticity Newton solve)."),
    ("code", '''def loss_and_film(log_c, log_eta):
    s = vjax.journal_bearing(R_B, jnp.exp(log_c), jnp.exp(log_eta), load, housing=bearing, omega_shaft=-0.4,
                             omega_housing=0.2, options=vjax.JournalOptions(n=n, strategy="newton"), initial=sol,
                             throw=False)
    power = s.dissipation_fluid + s.dissipation_housing
    return power, s.min_film
x = (jnp.log(c), jnp.log(eta))
(power, film) = loss_and_film(*x)
jac = jax.jacfwd(lambda a, b: jnp.stack(loss_and_film(a, b)), argnums=(0, 1))(*x)
print(f"power loss {float(power):.4g} W/m, min film {1e6 * float(film):.3f} um")
print("d(power, film)/d log c  :", np.asarray(jac[0]))
print("d(power, film)/d log eta:", np.asarray(jac[1]))
h = 1e-5
fd = (np.asarray(loss_and_film(x[0] + h, x[1])) - np.asarray(loss_and_film(x[0] - h, x[1]))) / (2 * h)
print("finite differences d/d log c:", fd)'''),
]


NOTEBOOKS = {"01_calibrate_material.ipynb": NB1, "02_roller_bearing.ipynb": NB2, "03_journal_bearing.ipynb": NB3}


def notebook(cells):
    """An nbformat-4 notebook (no outputs) from (kind, source) pairs; cell ids are stable."""
    import nbformat
    nb = nbformat.v4.new_notebook(metadata={
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {"name": "python"}})
    for i, (kind, src) in enumerate(cells):
        new = nbformat.v4.new_markdown_cell if kind == "md" else nbformat.v4.new_code_cell
        nb.cells.append(new(src, id=f"cell-{i}"))
    return nb


def execute(nb, workdir, timeout=600, env=None):
    """Runs `nb` in place in a fresh ``python3`` Jupyter kernel started in `workdir` (where the
    notebook's files go) and returns it with its outputs; figures become image/png outputs
    through the kernel's inline backend. `env`: extra environment variables for the kernel;
    `timeout`: per cell, in s. This checkout's vjax and fitting come first on the path.
    Raises nbclient's CellExecutionError naming the cell if one fails."""
    import nbclient
    env = dict(os.environ, **(env or {}))
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), env.get("PYTHONPATH")) if p)
    env.pop("MPLBACKEND", None)            # a non-inline backend would leave the figures out
    env.pop("VJAX_NOTEBOOK_OUT", None)     # files go to workdir/nb_out, the path printed
    # record_timing=False: no wall-clock stamps in the stored metadata
    nbclient.NotebookClient(nb, timeout=timeout, kernel_name="python3", record_timing=False,
                            resources={"metadata": {"path": str(workdir)}}).execute(env=env)
    for cell in nb.cells:   # one stdout block per cell, however the kernel flushed it
        merged = []
        for o in cell.get("outputs", []):
            if merged and o.output_type == "stream" and merged[-1].output_type == "stream" \
                    and merged[-1].name == o.name:
                merged[-1].text += o.text
            else:
                merged.append(o)
        if "outputs" in cell:
            cell.outputs = merged
    return nb


def main(argv=None):
    import argparse
    import tempfile
    import time
    import nbformat
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--execute", action="store_true",
                    help="run each notebook and store it with its outputs (figures included)")
    ap.add_argument("names", nargs="*", help="notebooks to write (default: all), e.g. 02_roller_bearing")
    args = ap.parse_args(argv)
    chosen = [n for n in NOTEBOOKS if not args.names or any(n.startswith(a) for a in args.names)]
    if not chosen:
        ap.error(f"no notebook matches {args.names}; known: {', '.join(NOTEBOOKS)}")
    for name in chosen:
        nb = notebook(NOTEBOOKS[name])
        if args.execute:
            t0 = time.perf_counter()
            with tempfile.TemporaryDirectory(prefix="vjax-nb-") as work:
                execute(nb, work)
            figures = sum(o.get("output_type") == "display_data" and "image/png" in o.get("data", {})
                          for c in nb.cells if c.cell_type == "code" for o in c.outputs)
            print(f"executed {name} in {time.perf_counter() - t0:.1f} s, {figures} figures")
        nbformat.write(nb, HERE / name)
        print("wrote", HERE / name)


if __name__ == "__main__":
    main()
