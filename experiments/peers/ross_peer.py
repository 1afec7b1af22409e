"""ROSS's PlainJournal on the rigid case of ``experiments/studies/journal_finite.py``, timed: a peer run.

ROSS 3.x (``ross-rotordynamics``) needs Python >= 3.13, so it lives in a side venv and this script
runs in its interpreter; it imports only the standard library, numpy and ross (not vjax, not jax)::

    python3.13 -m venv /tmp/ross-venv && /tmp/ross-venv/bin/pip install ross-rotordynamics
    /tmp/ross-venv/bin/python experiments/peers/ross_peer.py --load 16122.75 [--n-theta 40 --n-z 20 --ny 10]
        [--groove opposite-load | --groove max-film --attitude 48.5]    # or --eccentricity 0.65

It prints one line of JSON (ROSS's own chatter goes to stderr). ``journal_finite.py`` runs it
when ``VJAX_ROSS_PYTHON`` names that interpreter.

Case: bore radius R = 50 mm, radial clearance c = 50 um (journal diameter 2 (R - c)), L = 0.1 m
(L/D = 1), isoviscous 0.01 Pa s (``thermal_type=None`` and a lubricant whose two-point viscosity
law is flat), journal at 100 rad/s counter-clockwise, rigid, cavitation and groove at 0 Pa.

ROSS's conventions, and what this script does about them:

- Its 360-degree land switches to the short-bearing equation (uncavitated K, C), so the bore is
  ONE land of 359 degrees; PlainJournal puts its 1-degree groove at +x, and the load is turned to
  place it: ``--groove opposite-load`` (default, vjax's benchmark point: the groove fixed opposite
  the load) or ``--groove max-film`` (at the maximum film: the load direction is iterated from
  ``--attitude`` until the groove is within 0.05 deg of it; ``aim_solves``). With
  ``--eccentricity`` the line of centres lies along -x (groove at the maximum film) and the load
  is ROSS's film force.
- Its cross-film integration over ny layers makes every force, K and C 1/(1 - 1/ny^2) too
  large: ROSS is given load / (1 - 1/ny^2) (``load_ross_N``), and K, C are reported times
  (1 - 1/ny^2); all outputs belong to ``load_N``.
- With h_min/ny below 1 um its mesh matching breaks (``hmin_over_ny_um``, ``mesh_ok``).
- Its ``attitude`` is measured from -y; ``attitude_deg`` here is vjax's: from the load line to
  the line of centres, positive in the direction of rotation. K (N/m) and C (N s/m) are turned
  into vjax's frame (load along -y), rows and columns (x, y).

Timing: ``wall_first_s`` is the first construction + solve in this process (ROSS's numba
kernels are cached on disk, so JIT compilation only counts in a fresh venv's first run),
``wall_median_s`` the median of 3 more at the final load direction; neither includes
``import ross`` (``import_s``).
"""
import argparse
import json
import os
import statistics
import sys
import time
import warnings

import numpy as np

R, C, ETA, OMEGA, L = 0.05, 5e-5, 0.01, 100.0, 0.1
LUBRICANT = dict(liquid_viscosity1=ETA, temperature1=313.15, liquid_viscosity2=ETA, temperature2=373.15,
                 liquid_density=870.0, liquid_specific_heat=1950.0, liquid_thermal_conductivity=0.13)


def solve(args, load_angle, load_ross):
    """One PlainJournal construction + solve; returns (seconds, results dict)."""
    from ross.bearings.plain_journal import PlainJournal
    if args.eccentricity is None:
        kw = dict(fxs_load=load_ross * np.cos(load_angle), fys_load=load_ross * np.sin(load_angle))
    else:                                # line of centres along -x; ROSS returns the film force
        kw = dict(fxs_load=-1.0, equilibrium_type="match_eccentricity", initial_position=(-args.eccentricity, 0.0))
    t = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        b = PlainJournal(n=0, pad_axial_length=L, journal_diameter=2 * (R - C), radial_clearance=C, n_pads=1,
                         pad_arc=np.radians(359.0), oil_supply_temperature=313.15, speed=[OMEGA], lubricant=LUBRICANT,
                         thermal_type=None, total_ex_film=args.n_theta, total_ez_film=args.n_z,
                         total_ey_film=args.ny, **kw)
    return time.perf_counter() - t, b._results.outputs[0]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--load", type=float, help="load (N)")
    g.add_argument("--eccentricity", type=float, help="eccentricity ratio (instead of a load)")
    p.add_argument("--groove", choices=("opposite-load", "max-film"), default="opposite-load")
    p.add_argument("--attitude", type=float, default=50.0, help="max-film: first guess of the attitude (deg)")
    p.add_argument("--n-theta", type=int, default=40)
    p.add_argument("--n-z", type=int, default=20)
    p.add_argument("--ny", type=int, default=10)
    args = p.parse_args()
    shrink = 1.0 - 1.0 / args.ny**2
    aim = args.load is not None and args.groove == "max-film"
    stdout = os.dup(1)
    os.dup2(2, 1)                        # ROSS (CoolProp) prints to stdout: send it to stderr
    t = time.perf_counter()
    import ross
    import_s = time.perf_counter() - t

    # the groove is at +x: opposite a load along -x, or at the max film if the centres lie along -x
    load_angle = np.pi - np.radians(args.attitude) if aim else np.pi
    load_ross = None if args.load is None else args.load / shrink
    first, out = solve(args, load_angle, load_ross)
    solves = 1
    while aim and solves < 10:
        miss = np.pi - np.arctan2(out["yj_cb"][0], out["xj_cb"][0]) % (2 * np.pi)
        if abs(np.degrees(miss)) < 0.05:
            break
        load_angle += miss
        out = solve(args, load_angle, load_ross)[1]
        solves += 1
    times = []
    for _ in range(3):
        dt, out = solve(args, load_angle, load_ross)
        times.append(dt)
    xj, yj = out["xj_cb"][0], out["yj_cb"][0]
    if args.eccentricity is not None:    # the load balances the film force
        load_angle = np.arctan2(-out["fy_hydro"][0], -out["fx_hydro"][0])
        load = float(np.hypot(out["fx_hydro"][0], out["fy_hydro"][0])) * shrink
    else:
        load = args.load
    turn = -np.pi / 2 - load_angle                       # ROSS's frame -> vjax's (load along -y)
    Q = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    K, Cd = (shrink * Q @ np.array([[out[a + "xx"][0], out[a + "xy"][0]], [out[a + "yx"][0], out[a + "yy"][0]]]) @ Q.T
             for a in ("k", "c"))
    eps = float(np.hypot(xj, yj))
    hmin_ny = C * (1 - eps) / args.ny * 1e6
    os.dup2(stdout, 1)
    print(json.dumps({
        "ross_version": ross.__version__, "n_theta": args.n_theta, "n_z": args.n_z, "ny": args.ny,
        "load_N": load, "load_ross_N": load / shrink, "eccentricity": eps,
        "attitude_deg": float(np.degrees((np.arctan2(yj, xj) - load_angle + np.pi) % (2 * np.pi) - np.pi)),
        "wall_first_s": first, "wall_median_s": statistics.median(times), "import_s": import_s,
        "K": K.tolist(), "C": Cd.tolist(), "groove": "max-film" if args.eccentricity is not None else args.groove,
        "groove_from_max_film_deg": float(np.degrees(np.pi - np.arctan2(yj, xj) % (2 * np.pi))), "aim_solves": solves,
        "hmin_over_ny_um": hmin_ny, "mesh_ok": hmin_ny >= 1.0, "python": sys.version.split()[0]}))


if __name__ == "__main__":
    main()
