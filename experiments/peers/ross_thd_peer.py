"""ROSS 3.x's thermohydrodynamic (THD) plain journal bearing on issue 40's Level-2 cases: a peer run.

ROSS 3.x (``ross-rotordynamics``) needs Python >= 3.13, so it lives in a side venv and this script
runs in its interpreter; it imports only the standard library, numpy and ross (not vjax, not jax)::

    python3.13 -m venv /tmp/ross-venv && /tmp/ross-venv/bin/pip install ross-rotordynamics
    /tmp/ross-venv/bin/python experiments/peers/ross_thd_peer.py [--n-theta 40 --n-z 20 --ny 10]
        [--only 1.0:3000:1.0] [--out experiments/peers/ross_thd_cases.json]

It prints a table to stderr and writes JSON (the cases, the ROSS lubricant dict, the viscosity fit)
to ``--out``; ROSS's own chatter goes to stderr. Results were produced with ROSS 3.1.0.

Cases (issue 40, Level 2): journal diameter D = 100 mm, bore radius 50.075 mm (c = 75 um), L/D = 0.5
and 1, rigid, aligned, one axial groove at 0 Pa fixed opposite the load, Reynolds cavitation at 0 Pa;
ISO VG 32 (Walther / ASTM D341 through 32.0 and 5.34 cSt at 40 and 100 C), rho = 874 kg/m^3,
c_p = 1949 J/(kg K), k = 0.13 W/(m K); supply at 40 C; 1500, 3000, 6000 rpm; W/(L D) = 1 and 2.5 MPa.
Plus one isothermal reference (``thermal_type=None``) at 3000 rpm, 1 MPa, L/D = 1 with the Walther
40 C viscosity (32 cSt * rho).

Geometry and load conventions are those of ``ross_peer.py`` (read its docstring): one land of 359
degrees with PlainJournal's 1-degree groove at +x, the load along -x (groove opposite the load);
ROSS is given W / (1 - 1/ny^2) (its cross-film integration makes film forces 1/(1 - 1/ny^2) too
large; with ``"adiabatic"`` the viscosity is uniform across the film, so the same factor holds);
``attitude_deg`` is vjax's (from the load line to the line of centres, positive with rotation,
journal turning counter-clockwise). Other outputs (power, flows, temperatures) are ROSS's as they
are, for the load ROSS was given (0.99 W at ny = 10): NOT rescaled.

What ROSS 3.1's ``thermal_type="adiabatic"`` solves (read from ross/bearings/fluid_film/, 3.1.0)
--------------------------------------------------------------------------------------------------
Reynolds: the generalised (cross-film) Reynolds equation on the (theta, z) land, ny layers across
the film, cavitation p >= 0 (``cavitation_pressure`` 0), groove and axial ends at 0 Pa; Newton on
the journal position for the load (``match_load``). Laminar below Re 500 (all cases here; the
maximum local Re is recorded as ``re_max``).

Energy equation (thermal.py ``pde_coeff_adiab`` / ``element_adiab`` / ``temp_adiabatic``): ONE
temperature per (theta, z) node, uniform across the film (``temp_3d_adiab`` copies it to every
layer), solved by bilinear Galerkin FE on the Reynolds mesh, in the advective form::

    rho c_p (U_m dT/dx + W_m dT/dz) - k (d2T/dx2 + d2T/dz2) = (1/h) int_0^h mu (u_y^2 + w_y^2) dy

with U_m = (1/h) int u dy, W_m = (1/h) int w dy the film-mean Couette + Poiseuille velocities, k the
oil's conductivity (in-plane conduction only) and the full-film viscous dissipation. Heat leaves ONLY
with the oil (no conduction to bush or journal: the walls are adiabatic; ``temp_j_type`` sets a
journal temperature that only feeds thermal growth, off here). Boundary conditions: T = T_inlet on
the land's leading edge (x = 0); natural (zero conductive flux) everywhere else, axial ends included.
The dissipation and the convection use the full-film velocity profiles everywhere: the cavitated
zone is NOT reduced to a film fraction in the energy equation.

Viscosity: mu(T) = mu1 * exp(beta (T - T1)), beta = ln(mu2/mu1) / (T2 - T1) (state.py ``Lubricant
.viscosity``), DYNAMIC viscosity through the lubricant dict's two points (``liquid_viscosity1/2``
at ``temperature1/2``, K), evaluated node by node at the film temperature (uniform across the
film). Here the two points are chosen so ln(nu) of the exponential is the minimax (equal-ripple)
fit of Walther's ln(nu) over 40-100 C: the exponential has the chord's slope and equioscillates at
40 C, ~67 C and 100 C; it crosses Walther at ~47.5 C and ~89.8 C, and those two Walther points (times
rho) are the ones given to ROSS. Mismatch (ROSS / Walther - 1): -7.9 % at 40 C, +7.4 % at 60 C,
+5.6 % at 80 C, -7.9 % at 100 C (``viscosity_fit`` in the JSON, in cSt).

Groove mixing (thd.py ``temp_mixing_carryover``, _numba_kernels.py flow rates): per land,
q_in = circumferential flow at the film onset (leading edge), q_out = circumferential flow through
the MINIMUM FILM (not the trailing edge), capped at q_in; q_sides = q_in - q_out is therefore the
side leakage between the leading edge and h_min only (the pressure field's whole leakage,
``q_side_fd_m3s``, is larger). The carry-over is
q_carry = lambda * q_out with ``hot_oil_lambda`` lambda = 0.8 (default), and the land's inlet
temperature is the flow-weighted mix of the carried-over oil at the upstream land's outlet
temperature (a single land is its own upstream) and fresh oil at the sump temperature::

    T_inlet = (lambda q_out T_out + (q_in - lambda q_out) T_sump) / q_in   (= T_out if lambda q_out > q_in)

T_out (``temp_out_let``, used in the mix) is the trailing-edge row average of the film temperature
weighted by film area (h dz), NOT by flow; ``temp_out_let_bulk`` is the u-weighted (bulk) one.
With ``sump_type="supply_temperature"`` (default) T_sump = the supply temperature, 40 C. The saved
cases reproduce this rule from their own numbers (e.g. L/D = 1, 3000 rpm, 1 MPa:
(32.06 * 71.61 + 34.66 * 40) / 66.72 = 55.19 C = ``t_inlet_C``). The supply
flow (``oil_flow_v``) is not given: PlainJournal assumes a flooded 1e-2 m^3/s, which only enters the
reported drain temperature T_supply + P / (rho c_p 1e-2) (``sump_drain_temperature``).

Outputs kept here: eccentricity, attitude; ``tpad_max`` (max film temperature = max bush-surface
temperature, the walls being adiabatic); T_inlet, T_out (area-weighted), T_out_bulk; the full
radially averaged film-temperature field's mean (``t_film_mean``); power loss (journal-surface shear
times U, multiplied by ROSS's ``scale_dissip`` = q_out / q_x(theta) downstream of h_min, a film-
fraction-like factor the energy equation does not use); max pressure (0 in ROSS's isothermal mode);
the largest local Reynolds number; flows q_in, q_out, q_sides, q_carryover.

Heat balance (``heat_*``): the oil carries rho c_p [q_out T_out_bulk + q_side T_side - q_in T_inlet]
(equal to rho c_p (Q_fresh)(T_leaving - T_supply) by the mixing rule). ROSS reports no side-leakage
temperature, so T_side is reconstructed here from its field outputs: q_z = -h^3/(12 mu(T)) dp/dz at
both ends (second-order one-sided difference), T weighted by q_z; ``q_side_fd`` checks that flow
against ROSS's q_sides. ``heat_ratio`` = that carried heat / ROSS's power loss.

Timing: ``wall_s`` = one construction + solve (numba kernels cached on disk after the first run).
"""
import argparse
import json
import os
import sys
import time
import warnings

import numpy as np

D, RB = 0.100, 0.050075
C = RB - D / 2
RHO, CP, K_OIL = 874.0, 1949.0, 0.13
T_SUPPLY = 313.15
NU40, NU100 = 32.0, 5.34          # cSt at 40 and 100 C (Walther / ASTM D341)
SPEEDS_RPM = (1500.0, 3000.0, 6000.0)
LOADS_MPA = (1.0, 2.5)
L_OVER_D = (0.5, 1.0)


def walther_cst(t_k):
    """Kinematic viscosity (cSt) of the oil at t_k (K): ASTM D341 through (40 C, 32) and (100 C, 5.34)."""
    w = lambda nu: np.log10(np.log10(nu + 0.7))
    t1, t2 = 313.15, 373.15
    b = (w(NU40) - w(NU100)) / (np.log10(t2) - np.log10(t1))
    a = w(NU40) + b * np.log10(t1)
    return 10 ** (10 ** (a - b * np.log10(t_k))) - 0.7


def exponential_fit():
    """Minimax fit of ln(nu) by a line in T over 40-100 C; returns (T1, T2) where it meets Walther (K)."""
    t = np.linspace(313.15, 373.15, 60001)
    y = np.log(walther_cst(t))
    slope = (y[-1] - y[0]) / (t[-1] - t[0])      # ln(nu) is convex in T: minimax slope = chord's
    d = y - (y[0] + slope * (t - t[0]))
    e = y[0] + 0.5 * d.min() + slope * (t - t[0]) - y   # equal ripple at both ends and the tangent
    cross = t[np.nonzero(np.diff(np.sign(e)))[0]]
    return float(cross[0]), float(cross[-1])


def lubricant(isothermal_cst=None):
    """ROSS lubricant dict (SI): the minimax exponential, or a flat law at isothermal_cst."""
    if isothermal_cst is None:
        t1, t2 = exponential_fit()
        mu1, mu2 = RHO * walther_cst(t1) * 1e-6, RHO * walther_cst(t2) * 1e-6
    else:
        t1, t2, mu1, mu2 = 313.15, 373.15, RHO * isothermal_cst * 1e-6, RHO * isothermal_cst * 1e-6
    return dict(liquid_viscosity1=mu1, temperature1=t1, liquid_viscosity2=mu2, temperature2=t2,
                liquid_density=RHO, liquid_specific_heat=CP, liquid_thermal_conductivity=K_OIL)


def side_leak(fields, lube):
    """(q_side m^3/s, flow-weighted T_side K) from ROSS's fields: q_z = -h^3/(12 mu) dp/dz at both ends."""
    th, z = fields["theta"][0], fields["axial_position"][0]
    p, h, t = fields["pressure"][0], fields["film_thickness"][0], fields["film_temperature"][0]
    beta = np.log(lube["liquid_viscosity2"] / lube["liquid_viscosity1"]) / (lube["temperature2"] - lube["temperature1"])
    mu = lube["liquid_viscosity1"] * np.exp(beta * (t - lube["temperature1"]))
    dx = np.gradient(th[:, 0]) * D / 2               # arc length per node (m), trapezoid weights below
    w = np.full(th.shape[0], 1.0)
    w[0] = w[-1] = 0.5
    dz = z[0, 1] - z[0, 0]
    q_tot, qt_tot = 0.0, 0.0
    for i0, i1, i2 in ((0, 1, 2), (-1, -2, -3)):     # the two ends; second-order one-sided difference
        dpdn = -(-3 * p[:, i0] + 4 * p[:, i1] - p[:, i2]) / (2 * dz)   # along the outward normal
        qz = np.maximum(-h[:, i0] ** 3 / (12 * mu[:, i0]) * dpdn, 0.0) * dx * w
        q_tot += qz.sum()
        qt_tot += (qz * t[:, i0]).sum()
    return q_tot, qt_tot / q_tot if q_tot > 0 else float("nan")


def solve(l_over_d, rpm, p_mpa, args, thermal_type="adiabatic", isothermal_cst=None):
    """One PlainJournal THD case; returns a results dict (or the failure)."""
    from ross.bearings.plain_journal import PlainJournal
    length = l_over_d * D
    load = p_mpa * 1e6 * length * D
    shrink = 1.0 - 1.0 / args.ny ** 2
    lube = lubricant(isothermal_cst)
    rec = dict(l_over_d=l_over_d, speed_rpm=rpm, specific_load_MPa=p_mpa, load_N=load, load_ross_N=load / shrink,
               thermal_type=thermal_type)
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            b = PlainJournal(n=0, pad_axial_length=length, journal_diameter=D, radial_clearance=C, n_pads=1,
                             pad_arc=np.radians(359.0), oil_supply_temperature=T_SUPPLY, speed=[rpm * np.pi / 30],
                             lubricant=lube, thermal_type=thermal_type, total_ex_film=args.n_theta,
                             total_ez_film=args.n_z, total_ey_film=args.ny, fxs_load=-load / shrink, fys_load=0.0)
        out = b._results.outputs[0]
    except Exception as exc:                          # record ROSS's failure, keep going
        rec.update(ok=False, error=f"{type(exc).__name__}: {exc}", wall_s=time.perf_counter() - t0)
        return rec
    wall = time.perf_counter() - t0
    xj, yj = out["xj_cb"][0], out["yj_cb"][0]
    load_angle = np.pi
    eps = float(np.hypot(xj, yj))
    r = b._results                                    # the solved fields, (pads, n_theta + 1, n_z + 1)
    f = dict(theta=r.theta_grids[0], axial_position=r.z_grids[0], pressure=r.pressure_fields[0],
             film_thickness=r.film_thickness_fields[0], film_temperature=r.temperature_fields[0])
    tf = f["film_temperature"][0]
    q_in, q_out, q_s = out["q_in"][0][0], out["q_out"][0][0], out["q_sides"][0][0]
    t_in, t_out, t_outb = out["temp_in_let"][0][0], out["temp_out_let"][0][0], out["temp_out_let_bulk"][0][0]
    power = float(out["power_loss"][0])
    q_fd, t_side = side_leak(f, lube)
    heat = RHO * CP * (q_out * t_outb + q_s * t_side - q_in * t_in)
    rec.update(
        ok=True, wall_s=wall, eccentricity=eps,
        attitude_deg=float(np.degrees((np.arctan2(yj, xj) - load_angle + np.pi) % (2 * np.pi) - np.pi)),
        h_min_um=C * (1 - eps) * 1e6, hmin_over_ny_um=C * (1 - eps) / args.ny * 1e6,
        mesh_ok=C * (1 - eps) / args.ny >= 1e-6,      # below 1 um per layer ROSS's mesh matching breaks
        t_max_C=float(out["tpad_max"][0]) - 273.15, t_inlet_C=t_in - 273.15, t_out_area_C=t_out - 273.15,
        t_out_bulk_C=t_outb - 273.15, t_film_mean_C=float(tf.mean()) - 273.15, t_film_min_C=float(tf.min()) - 273.15,
        t_side_C=t_side - 273.15, t_drain_C=float(out["sump_drain_temperature"][0]) - 273.15,
        power_W=power, q_in_m3s=q_in, q_out_m3s=q_out, q_sides_m3s=q_s, q_carryover_m3s=out["q_carry_over"][0][0],
        q_fresh_m3s=q_in - out["q_carry_over"][0][0], q_side_fd_m3s=q_fd, heat_carried_W=heat,
        heat_ratio=heat / power if power else float("nan"), max_pressure_MPa=float(out["max_pressure"][0]) / 1e6,
        re_max=float(np.max(out["dhc_re_max"][0])))
    if thermal_type is None:                          # ROSS reports 0 degF sentinels for the temperatures
        rec.update({k: None for k in rec if k.startswith(("t_", "heat_"))})
    return rec


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--n-theta", type=int, default=40)
    p.add_argument("--n-z", type=int, default=20)
    p.add_argument("--ny", type=int, default=10)
    p.add_argument("--only", help="one case L/D:rpm:MPa, e.g. 1.0:3000:1.0 (no file written)")
    p.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "ross_thd_cases.json"))
    args = p.parse_args()
    stdout = os.dup(1)
    os.dup2(2, 1)                                     # ROSS (CoolProp) prints to stdout: send it to stderr
    import ross
    if args.only:
        ld, rpm, mpa = (float(v) for v in args.only.split(":"))
        cases = [solve(ld, rpm, mpa, args)]
    else:
        cases = [solve(ld, rpm, mpa, args) for ld in L_OVER_D for mpa in LOADS_MPA for rpm in SPEEDS_RPM]
        cases.append(solve(1.0, 3000.0, 1.0, args, thermal_type=None, isothermal_cst=NU40))
    t1, t2 = exponential_fit()
    lube = lubricant()
    ross_cst = lambda tc: lube["liquid_viscosity1"] / RHO * 1e6 * np.exp(
        np.log(lube["liquid_viscosity2"] / lube["liquid_viscosity1"]) / (t2 - t1) * (tc + 273.15 - t1))
    fit = {f"{tc:g}C": dict(walther_cSt=float(walther_cst(tc + 273.15)), ross_cSt=float(ross_cst(tc)),
                            mismatch_pct=float(100 * (ross_cst(tc) / walther_cst(tc + 273.15) - 1)))
           for tc in (40.0, 60.0, 80.0, 100.0)}
    doc = dict(ross_version=ross.__version__, python=sys.version.split()[0], n_theta=args.n_theta, n_z=args.n_z,
               ny=args.ny, bore_radius_m=RB, journal_diameter_m=D, clearance_m=C, supply_C=T_SUPPLY - 273.15,
               hot_oil_lambda=0.8, lubricant_ross=lube, viscosity_fit=dict(points_C=[t1 - 273.15, t2 - 273.15], **fit),
               cases=cases)
    os.dup2(stdout, 1)
    hdr = "L/D   rpm  MPa    eps   att_deg  Tmax_C  Tin_C  Tout_C  Tmean_C  P_W     q_in_ml/s q_side_ml/s heat/P  wall_s"
    print(hdr, file=sys.stderr)
    for c in cases:
        if not c["ok"]:
            print(f"{c['l_over_d']:.1f} {c['speed_rpm']:5.0f} {c['specific_load_MPa']:4.1f}  FAILED {c['error']}",
                  file=sys.stderr)
            continue
        if c["thermal_type"] is None:
            print(f"{c['l_over_d']:.1f} {c['speed_rpm']:5.0f} {c['specific_load_MPa']:4.1f}  {c['eccentricity']:.4f} "
                  f"{c['attitude_deg']:7.2f}  isothermal at 40 C: P = {c['power_W']:.1f} W, q_in = "
                  f"{c['q_in_m3s'] * 1e6:.2f}, q_side = {c['q_sides_m3s'] * 1e6:.2f} ml/s", file=sys.stderr)
            continue
        print(f"{c['l_over_d']:.1f} {c['speed_rpm']:5.0f} {c['specific_load_MPa']:4.1f}  {c['eccentricity']:.4f} "
              f"{c['attitude_deg']:7.2f}  {c['t_max_C']:6.2f} {c['t_inlet_C']:6.2f} {c['t_out_bulk_C']:6.2f}  "
              f"{c['t_film_mean_C']:6.2f}  {c['power_W']:7.1f} {c['q_in_m3s'] * 1e6:8.2f} {c['q_sides_m3s'] * 1e6:9.2f}"
              f"   {c['heat_ratio']:.3f} {c['wall_s']:6.1f}", file=sys.stderr)
    if not args.only:
        with open(args.out, "w") as fh:
            json.dump(doc, fh, indent=1)
    print(json.dumps(doc if args.only is None else cases[0]))


if __name__ == "__main__":
    main()
