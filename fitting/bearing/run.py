"""The sweep of a bearing case (``vjax-bearing``): one vjax scene solve per operating point.

Points run in the order of :attr:`fitting.bearing.case.Case.points` (speed innermost); each solve
starts from the previous converged point of the same temperature and load (``initial=``), and
a warm start that fails is retried cold. A point that still fails is kept, with the solver's
reason (the :class:`vjax.ConvergenceError` message) in its row; the sweep goes on. Only vjax's
public API is used: ``journal_bearing`` (``length=`` for the finite bearing),
``journal_coefficients``, ``roller_bearing``, ``pin_in_hole``, the bodies and ``Material``.

Definitions (docs/bearing_files.md): the *friction torque* is the torque on the stationary
body, positive when it is dragged along (what a torque arm on it measures); the *friction
coefficient* of a journal bearing is the library's, the journal's friction force over the load
(Raimondi and Boyd's f; the housing's torque differs from the journal's by the load times the
eccentricity's moment arm), and of a dry contact the friction torque over load x radius (bore
radius; a roller bearing's inner raceway, the catalogues' mu = 2 M / (F d)); the *viscoelastic
share* is the fraction of the
power put in that the bodies' hysteresis takes (the rest heats the film; 1 for the dry
contacts, where all friction is hysteresis).
"""
from __future__ import annotations

import dataclasses
import math
import sys
import time

import numpy as np

__all__ = ["Point", "run_case"]


@dataclasses.dataclass
class Point:
    """One operating point: inputs, ``row`` (the points.csv columns), the scene's ``result``
    (None when it failed without one), its ``coefficients`` (journal), ``reason`` ('' if
    converged)."""

    index: int
    temperature: float | None
    load: float
    speed: float
    row: dict
    result: object = None
    coefficients: object = None
    reason: str = ""

    @property
    def converged(self):
        return not self.reason


# G. I. Taylor (1923): between concentric cylinders, the inner one turning, laminar Couette flow
# gives way to toroidal vortices above Re = rho omega R c / eta = 41.3 sqrt(R / c) (as in
# Hamrock's Fundamentals of Fluid Film Lubrication); with the outer one turning it stays laminar
# until it turns turbulent, at about Re = 2000 (Taylor 1936)
TAYLOR = 41.3
TURBULENT_REYNOLDS = 2000.0


def outside_the_model(case, reynolds: float) -> str:
    """Why an operating point lies outside the model's laminar, inertia-free film ('' when it
    does not)."""
    R, c = case.geometry["R"], case.geometry["c"]
    limit = TAYLOR * math.sqrt(R / c) if case.turning == "shaft" else TURBULENT_REYNOLDS
    if reynolds <= limit:
        return ""
    what = "Taylor vortices" if case.turning == "shaft" and reynolds < TURBULENT_REYNOLDS else "turbulence"
    return (f"Reynolds number {reynolds:.3g} above the laminar limit {limit:.3g} ({what}): the laminar "
            f"Reynolds equation underestimates the friction and misstates the load capacity")


def _body(vjax, b, T):
    if b.kind == "rigid":
        return None
    T = b.temperature if b.temperature is not None else T      # the body's own, where it has one
    mat = b.material if b.shift is None or T is None else b.material.with_shift(b.shift).at_temperature(T)
    if b.kind in ("liner", "sleeve"):
        return getattr(vjax, b.kind)(mat, b.thickness)
    return getattr(vjax, b.kind)(mat, ref_length=b.ref_length)


class _Scene:
    """The case's scene with its bodies at one temperature: ``solve(load, speed, initial)``."""

    def __init__(self, case, T):
        import vjax
        self.vjax, self.case, self.T = vjax, case, T
        self.housing, self.shaft = _body(vjax, case.housing, T), _body(vjax, case.shaft, T)
        self.speeds = lambda w: {"omega_shaft": w} if case.turning == "shaft" else {"omega_housing": w}

    def _journal_args(self, load):
        c, g = self.case, self.case.geometry
        eta = c.eta(self.T)
        finite = c.scene == "finite_journal"
        kw = dict(housing=self.housing, shaft=self.shaft, load_angle=c.load_angle, cavitation=c.cavitation)
        if finite:
            kw.update(length=g["length"], supply_angle=g["supply_angle"],
                      options=self.vjax.FiniteJournalOptions(n=c.n, m=c.m))
        else:
            kw.update(options=self.vjax.JournalOptions(n=c.n))     # the load is per length (N/m)
        return (g["R"], g["c"], eta, load), kw, eta

    def solve(self, load, speed, initial):
        v, c, g = self.vjax, self.case, self.case.geometry
        if c.journal:
            args, kw, _ = self._journal_args(load)
            if c.scene == "long_journal":
                kw["memory"] = c.memory         # the steady state's; the coefficients are periodic
            return v.journal_bearing(*args, initial=initial, **kw, **self.speeds(speed))
        if c.scene == "roller":
            return v.roller_bearing(self.housing, self.shaft, g["R_outer"], g["R_inner"], g["D"], g["Z"], load,
                                    diametral_clearance=g["clearance"], load_angle=c.load_angle, memory=c.memory,
                                    initial=initial, options=v.RollerOptions(n=c.n), **self.speeds(speed))
        return v.pin_in_hole(self.housing, g["R"], g["c"], load, load_angle=c.load_angle, memory=c.memory,
                             initial=initial, options=v.PinOptions(n=c.n), **self.speeds(speed))

    def coefficients(self, load, speed, steady):
        args, kw, _ = self._journal_args(load)
        whirl = np.asarray(self.case.whirl_ratios) * speed
        return self.vjax.journal_coefficients(*args, whirl, initial=steady, **kw, **self.speeds(speed))


def _row(case, p: Point, r, eta):
    """The points.csv columns of one point (SI; ``r`` the scene's result or None)."""
    c, g = case, case.geometry
    total = c.scene == "finite_journal" or c.length is not None     # totals (N, N m) or per length
    per = 1.0 if c.scene == "finite_journal" else (c.length or 1.0)  # per-length results -> totals
    lu, tu = ("N", "Nm") if total else ("N_per_m", "Nm_per_m")
    load_out = p.load if c.scene == "finite_journal" else p.load * per
    row = {"point": p.index, "temperature_C": p.temperature, "speed_rad_s": p.speed,
           "speed_rpm": p.speed * 60 / (2 * math.pi), f"load_{lu}": load_out}
    if c.journal:
        row["viscosity_Pa_s"] = eta
    names = (["eccentricity", "attitude_deg", "min_film_m", "min_film_over_c"] if c.journal else
             ["pin_offset_m", "contact_angle_deg"] if c.scene == "pin" else
             ["ring_shift_m", "cage_speed_rad_s", f"max_roller_load_{'N_per_m' if c.scene else ''}"])
    names += ["max_pressure_Pa", f"friction_torque_{tu}", f"torque_housing_{tu}", f"torque_shaft_{tu}",
              "friction_coefficient", "power_W" if total else "power_W_per_m", "viscoelastic_share"]
    if c.journal:
        names += ["side_leakage_m3_s", "supply_flow_m3_s", "inlet_flow_m3_s", "reynolds_number", "validity"]
    for k in names:
        row[k] = None
    if c.journal:      # from the inputs alone: a failed point says it too
        row["reynolds_number"] = c.density * p.speed * g["R"] * g["c"] / eta
        row["validity"] = outside_the_model(c, row["reynolds_number"])
    row.update(converged=r is not None and p.converged, iterations=None, residual=None, reason=p.reason)
    if r is None:
        return row
    f = lambda x: float(np.asarray(x))                       # noqa: E731
    T_h = f(r.torque) * per
    T_s = f(r.torque_shaft) * per if hasattr(r, "torque_shaft") else -T_h   # the pin: the reaction
    w_h, w_s = (0.0, p.speed) if c.turning == "shaft" else (p.speed, 0.0)
    friction = T_h if c.turning == "shaft" else T_s
    power = -w_h * T_h - w_s * T_s
    radius = g["R_inner"] if c.scene == "roller" else g["R"]
    row.update({f"torque_housing_{tu}": T_h, f"torque_shaft_{tu}": T_s, f"friction_torque_{tu}": friction,
                "friction_coefficient": f(r.friction_coefficient) if c.journal else friction / (load_out * radius),
                "power_W" if total else "power_W_per_m": power,
                "iterations": int(np.asarray(r.iterations)), "residual": f(r.residual)})
    if c.journal:
        hyst = -w_h * f(r.torque_viscoelastic) * per - w_s * f(r.torque_viscoelastic_shaft) * per
        row.update(eccentricity=f(r.eccentricity), attitude_deg=math.degrees(f(r.attitude_angle)),
                   min_film_m=f(r.min_film), min_film_over_c=f(r.min_film) / g["c"],
                   viscoelastic_share=hyst / power + 0.0 if power else None)   # + 0.0: no -0.0
        # the groove's net outflow is the flow the bearing takes only where the cells conserve
        # mass (JFO); Reynolds' and Sommerfeld's conditions lose or make some in the cavity
        supply = f(r.supply_flow) * per if c.cavitation == "jfo" else None
        if c.scene == "finite_journal":
            row.update(max_pressure_Pa=f(r.max_pressure), side_leakage_m3_s=f(r.side_leakage),
                       supply_flow_m3_s=supply, inlet_flow_m3_s=f(r.inlet_flow))
        else:
            row.update(max_pressure_Pa=float(np.max(np.asarray(r.pressure))), supply_flow_m3_s=supply)
    elif c.scene == "pin":
        row.update(pin_offset_m=float(np.linalg.norm(np.asarray(r.pin_offset))),
                   contact_angle_deg=math.degrees(f(r.contact_angle)),
                   max_pressure_Pa=float(np.max(np.asarray(r.pressure))), viscoelastic_share=1.0)
    else:
        row.update({"ring_shift_m": float(np.linalg.norm(np.asarray(r.ring_shift))),
                    "cage_speed_rad_s": f(r.cage_speed), names[2]: float(np.max(np.asarray(r.roller_loads))) * per,
                    "max_pressure_Pa": float(max(np.max(np.asarray(r.pressure)), np.max(np.asarray(r.pressure_shaft)))),
                    "viscoelastic_share": 1.0})
    return row


def _one_line(e):
    return " ".join(str(e).split())


class _Progress:
    """A text progress bar on stderr (one line per point when stderr is not a terminal)."""

    def __init__(self, total, enabled=True, stream=None):
        self.total, self.enabled, self.stream, self.t0 = total, enabled and total > 1, stream or sys.stderr, time.time()
        self.tty = getattr(self.stream, "isatty", lambda: False)()

    def update(self, done, text):
        if not self.enabled:
            return
        k = round(30 * done / self.total)
        line = f"[{'#' * k}{'.' * (30 - k)}] {done}/{self.total} {time.time() - self.t0:5.1f} s  {text}"
        self.stream.write(("\r" + line.ljust(110)) if self.tty else line + "\n")
        if self.tty and done == self.total:
            self.stream.write("\n")
        self.stream.flush()


def run_case(case, progress=True, stream=None) -> list:
    """Solve every operating point of ``case``; returns the :class:`Point` list."""
    import vjax
    points, scenes, prev_key, prev = [], {}, None, None
    bar = _Progress(len(case.points), progress, stream)
    for i, (T, W, w) in enumerate(case.points):
        if T not in scenes:
            scenes[T] = _Scene(case, T)       # the bodies at T (each material under its own shift law)
        scene = scenes[T]
        p = Point(i, T, float(W), float(w), {})
        eta = case.eta(T) if case.journal else None
        if (T, W) != prev_key:
            prev_key, prev = (T, W), None
        result, reasons = None, []
        for start in ([prev, None] if prev is not None else [None]):
            try:
                result = scene.solve(p.load, p.speed, start)
                break
            except vjax.ConvergenceError as e:
                reasons.append(("warm start: " if start is not None else "") + _one_line(e))
                result = e.solution
            except (ValueError, FloatingPointError) as e:
                reasons.append(_one_line(e))
                result = None
                break
        if reasons and (result is None or not bool(np.asarray(result.converged))):
            p.reason, result = reasons[-1], None      # an unconverged state's numbers are not reported
        else:
            prev = result
            if case.journal:
                try:
                    p.coefficients = scene.coefficients(p.load, p.speed, result)
                except (vjax.ConvergenceError, ValueError) as e:
                    p.reason = "coefficients: " + _one_line(e)
        p.result = result
        p.row = _row(case, p, result, eta)
        if p.reason and result is not None:
            p.row["converged"] = False
        points.append(p)
        unit = "N" if case.scene == "finite_journal" else "N/m"
        what = (f"T = {T:g} C, " if T is not None else "") + f"load {W:.4g} {unit}, {w * 60 / (2 * math.pi):.4g} rpm"
        bar.update(i + 1, what + (": FAILED" if p.reason else ""))
    return points
