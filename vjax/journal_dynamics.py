"""Dynamic coefficients of the (visco)elastic journal bearing: the linearized force response to
a small harmonic motion of the journal centre (docs/theory.md, journal dynamics).

Convention
----------
The journal centre moves by dx(t) = Re(dx^ e^{i Omega t}) about its steady position (absolute
frame of the load vector: x = 0 rad, CCW positive; ``Omega`` the whirl frequency, rad/s,
negative for backward whirl). The film force on the journal changes by
dF = Re(dF^ e^{i Omega t}) with

    dF^ = -Z(Omega) dx^,   Z(Omega) = K(Omega) + i Omega C(Omega)      (2 x 2, per unit length)

so that a rotor model reads M x'' + C x' + K x = external forces. K (N/m per m of bearing
length: N/m^2) is Re Z, C (N s/m^2) is Im Z / Omega (its limit at Omega = 0). Rigid bodies give
K and C independent of Omega; at Omega -> 0, K is the static stiffness of the steady solution
(the inverse of d(journal position)/d(load), which ``jax.jacfwd`` of
:func:`vjax.journal_bearing` gives).

Linearization
-------------
The steady problem lives in the line-of-centres frame (phi = theta - gamma). A motion of the
centre is a change de of the eccentricity (along the line of centres, X) and a rotation
dgamma = dY / e of the line of centres (Y, 90 degrees ahead). In a frame turning with the
line of centres the rigid film is c - e cos phi exactly, the groove stays where it is, and
the surfaces' entrainment speed drops by R dgamma/dt (the classical omega - 2 gamma'). The
perturbation of the Reynolds equation (finite volumes, with the squeeze term R dh/dt and the
Fischer-Burmeister complementarity linearized as is: a cavitated cell stays at p = 0, a
pressurized one conserves mass; half-Sommerfeld's clipped region moves with the zero of
the pressure; a "jfo" cavity conserves mass with its film fraction f as the unknown and
R d(h f)/dt as its squeeze term, so its boundaries move as the mass balance says) is then

    A(Omega) dp = -(b_e de + b_e' i Omega de + b_v i Omega dgamma + (G_U + i Omega G_U') dU_rot)

with dU = M(Omega) dp + dU_rot the bodies' response: M(Omega) the whirl operator of each
body (:func:`vjax.operator.whirl_symbol`: a material point of a body rotating at omega_b
sees mode m of the perturbation at Omega + m omega_b, so modes m and -m differ), and
dU_rot = (M(0) - M(Omega)) p0' dgamma the part of the steady deformation that lags behind the
rotating pattern (zero for elastic bodies and for Omega = 0). The force in the fixed frame
is the turning frame's plus the steady force turned by dgamma. A dense complex solve per
Omega (n x n): fine up to n ~ 2048.

The pressure datum is the groove. One that turns with the line of centres (the default of
:func:`vjax.journal_bearing`) stays on its element in the turning frame. One fixed in the
bearing (``groove="fixed"``) is on the grid of the load line, fixed in space: there the
motion changes the film directly, -(dX cos theta + dY sin theta), and its rate is the squeeze
(the turning frame is not needed, and the linearization is again the exact derivative of the
steady model). Memory is the periodic steady state (a truncated load history has no steady
small-motion response).
"""
from __future__ import annotations

import csv
import dataclasses
import io
import math
import os
import tempfile
import warnings
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from . import _solve, checks, journal_finite, reynolds
from . import _journal_film as film
from .journal import JournalOptions, JournalResult, journal_bearing
from .operator import circulant, grid

__all__ = ["JournalCoefficients", "journal_coefficients", "lund", "stability_threshold"]


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True, repr=False)
class JournalCoefficients:
    """Dynamic coefficients of :func:`journal_coefficients` (SI, per unit axial length of the
    infinitely long bearing; totals of a finite bearing).

    ``whirl`` Omega (rad/s, shape (m,)); ``impedance`` Z (complex, (m, 2, 2), N/m^2);
    ``stiffness`` K = Re Z (N/m^2); ``damping`` C = Im Z / Omega (N s/m^2; at Omega = 0 its
    limit), all in the absolute x, y frame (``[..., i, j]``: force component i per motion
    component j); ``speed`` the journal's angular velocity (rad/s); ``steady`` the
    :class:`~vjax.JournalResult` they linearize about. Convention: dF = -(K dx + C dx/dt).
    ``length``: None for the infinitely long bearing (per unit length); the axial length (m)
    of a finite bearing (``journal_coefficients(..., length=L)``), whose Z, K (N/m) and C
    (N s/m) are the bearing's totals and ``steady`` a :class:`~vjax.FiniteJournalResult`.
    """

    whirl: jax.Array
    impedance: jax.Array
    stiffness: jax.Array
    damping: jax.Array
    speed: jax.Array
    steady: JournalResult
    length: jax.Array | None = None

    def __repr__(self):
        return f"JournalCoefficients({self.whirl.shape[0]} whirl frequencies, eps = {float(self.steady.eccentricity):.4g})"

    def in_line_of_centres(self):
        """(K, C) turned into the line-of-centres frame (X from the bore's centre to the
        journal's, Y 90 degrees counter-clockwise from it)."""
        g = self.steady.line_of_centres_angle
        rot = jnp.array([[jnp.cos(g), -jnp.sin(g)], [jnp.sin(g), jnp.cos(g)]])
        turn = lambda A: rot.T @ A @ rot  # noqa: E731
        return jax.vmap(turn)(self.stiffness), jax.vmap(turn)(self.damping)

    def table(self, length=None) -> dict:
        """Columns for a rotordynamics code: ``speed`` (rad/s), ``frequency`` (the whirl, rad/s),
        ``kxx, kxy, kyx, kyy`` (N/m), ``cxx, cxy, cyx, cyy`` (N s/m) - the names of ROSS's
        bearing tables (``ross.BearingElement``).

        A finite bearing's coefficients (computed with ``length=``) are written as they are
        (``length`` None or equal to theirs). The infinitely long bearing's are scaled by
        ``length`` (m, default 1): **the infinitely long bearing's coefficients times the
        length, not a finite bearing's.** Side leakage makes a real bearing's differ by
        factors (issue 27: K_yy 2.4-4x, C_xx 1.5-2x at L/D = 1); this warns so. For a real
        bearing compute them with ``journal_coefficients(..., length=L)``."""
        if self.length is not None:
            if length is not None and not np.isclose(float(length), float(self.length), rtol=1e-12, atol=0.0):
                raise ValueError(f"length={length!r}: these are the coefficients of a finite bearing of length "
                                 f"{float(self.length)!r} m; compute them again for another length")
            scale = 1.0
        else:
            length = 1.0 if length is None else length
            checks.positive("length", length)
            warnings.warn("JournalCoefficients.table/save_csv: the infinitely long bearing's coefficients times the "
                          f"length ({float(length)!r} m), not those of a finite bearing (side leakage ignored: "
                          "stiffness and damping off by factors at L/D ~ 1); use journal_coefficients(..., length=L)",
                          UserWarning, stacklevel=3)
            scale = length
        K, C = np.asarray(self.stiffness) * scale, np.asarray(self.damping) * scale
        cols = {"speed": np.full(K.shape[0], float(self.speed)), "frequency": np.asarray(self.whirl)}
        for name, A in (("k", K), ("c", C)):
            for i, a in enumerate("xy"):
                for j, b in enumerate("xy"):
                    cols[f"{name}{a}{b}"] = A[:, i, j]
        return cols

    def save_csv(self, path, length=None) -> str:
        """Write :meth:`table` as CSV (one header line of column names; SI units as in
        :meth:`table`, whose warning about the infinitely long bearing's ``length`` scaling
        applies), atomically: a temporary file in the target directory, then ``os.replace``."""
        cols = self.table(length)
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(list(cols))
        for row in zip(*cols.values()):
            w.writerow([repr(float(v)) for v in row])
        path = os.fspath(path)
        fd, tmp = tempfile.mkstemp(prefix=".coeffs.", suffix=".tmp", dir=os.path.dirname(os.path.abspath(path)))
        try:
            with os.fdopen(fd, "w") as fh:
                fh.write(buf.getvalue())
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
        return path


def _perturbed_equations(pz, pzdot, U, Udot, motion, x0, pr: film.Params, cfg: film.Config):
    """Scaled cell equations (with the groove datum) and the film force on the journal (grid
    axes) for pressure ``pz`` (/p_ref; the universal unknown for "jfo") and its rate
    ``pzdot`` (1/s; a "jfo" cavity's film fraction changes at that rate), body displacement
    ``U`` (m, u_B + u_J) and its rate ``Udot`` (m/s), and a journal motion ``motion`` =
    (dX, dY, dX/dt, dY/dt) (m, m/s) in the grid's axes. Grid on the line of centres (a
    groove turning with it): the frame turns with the line of centres, dX changes the
    eccentricity, dY only turns the frame (no film change) and its rate lowers the
    entrainment speed by R dgamma/dt = R (dY/dt) / e. Grid on the load line (a fixed
    groove): the frame is fixed and the motion changes the film."""
    n = pz.shape[0]
    theta, alpha = grid(n)
    cos, sin = jnp.cos(theta), jnp.sin(theta)
    pz_p, fraction = reynolds.pressure_and_fraction(pz, cfg.cavitation)
    p = pz_p * pr.p_ref
    h = pr.c * (1 - x0[n] * jnp.cos(theta - film.offset(x0, cfg))) + U
    if cfg.fixed_groove:
        h = h - motion[0] * cos - motion[1] * sin
        hdot = -motion[2] * cos - motion[3] * sin + Udot
        v = pr.v
    else:
        h = h - motion[0] * cos
        hdot = -motion[2] * cos + Udot
        v = pr.v - pr.R * motion[3] / (x0[n] * pr.c)
    jfo = cfg.cavitation == "jfo"
    hf, _, q = reynolds.face_fluxes(p, h, pr.R, pr.eta, v, fraction if jfo else None)
    # the film's own growth R d(h f)/dt, f the liquid fraction (1 but in a "jfo" cavity)
    fraction_rate = jnp.where(pz < 0, pzdot, 0.0) if jfo else 0.0
    squeeze = pr.R * (hdot * fraction + h * fraction_rate)
    r = reynolds.cell_equations(pz, q, pr.q_ref, cfg.cavitation, squeeze=squeeze, couette=v * hf, v=v)
    r = r.at[pr.groove].set(pz[pr.groove] - pr.ps / pr.p_ref)
    p_load = reynolds.load_pressure(p, cfg.cavitation)
    F = -pr.R * 2 * alpha * jnp.stack([jnp.sum(p_load * cos), jnp.sum(p_load * sin)])
    return r, F


@partial(jax.jit, static_argnums=(2,))
def _impedance(x0, pr: film.Params, cfg: film.Config, bodies, whirl):
    """Z(Omega) (complex, (m, 2, 2), absolute frame) about the steady unknowns ``x0``;
    ``bodies``: (housing, R_housing, omega relative to it, shaft, ...) or None entries."""
    n = x0.shape[0] - 2
    theta, _ = grid(n)
    pz0 = x0[:n]
    eps, phi = x0[n], x0[n + 1]
    e = eps * pr.c
    zero = jnp.zeros(n, x0.dtype)
    U0 = zero
    for op in (pr.op_B, pr.op_J):
        if op is not None:
            U0 = U0 + op(reynolds.load_pressure(pz0 * pr.p_ref, cfg.cavitation))

    def eqs(pz, pzdot, U, Udot, motion):
        return _perturbed_equations(pz, pzdot, U, Udot, motion, x0, pr, cfg)

    args = (pz0, zero, U0, zero, jnp.zeros(4, x0.dtype))
    F0 = eqs(*args)[1]
    J_p, J_pd, J_U, J_Ud, J_s = jax.jacfwd(lambda *a: eqs(*a)[0], argnums=(0, 1, 2, 3, 4))(*args)
    # d p_load = w dp (w: the pressurized fraction of each cell under half-Sommerfeld) and the
    # film force it makes, per unit change of pz
    p_load0 = reynolds.load_pressure(pz0 * pr.p_ref, cfg.cavitation)
    load_slope = reynolds.load_slope(pz0, cfg.cavitation)
    G_p = -pr.R * (2 * jnp.pi / n) * pr.p_ref * load_slope * jnp.stack([jnp.cos(theta), jnp.sin(theta)])
    dp_load0 = jnp.fft.ifft(1j * jnp.fft.fftfreq(n, 1.0 / n) * jnp.fft.fft(p_load0))   # d p_load / d theta
    dp_load0 = dp_load0.at[n // 2].set(0.0) if n % 2 == 0 else dp_load0   # Nyquist: no derivative

    def one(W):
        M = jnp.zeros((n, n), complex)
        rot = jnp.zeros(n, complex)            # (M(0) - M(W)) p0', per unit dgamma
        for body, R_b, omega_b in bodies:
            if body is not None:
                sym, sym0 = body.whirl_symbol(R_b, n, omega_b, W), body.whirl_symbol(R_b, n, omega_b, 0.0)
                M = M + circulant(sym)
                rot = rot + jnp.fft.ifft((sym0 - sym) * jnp.fft.fft(dp_load0))
        GU = J_U + 1j * W * J_Ud
        A = J_p + 1j * W * J_pd + GU @ (M * (load_slope * pr.p_ref)[None, :])
        # right-hand sides per unit journal motion dX, dY (grid axes)
        b_X = J_s[:, 0] + 1j * W * J_s[:, 2]
        b_Y = J_s[:, 1] + 1j * W * J_s[:, 3]
        if not cfg.fixed_groove:     # the turning steady deformation lags in a viscoelastic body
            b_Y = b_Y + GU @ rot / e
        dpz = jnp.linalg.solve(A, -jnp.stack([b_X, b_Y], axis=1))
        dF = G_p @ dpz
        if not cfg.fixed_groove:     # the steady force turns with the frame by dY / e
            dF = dF.at[:, 1].add(jnp.stack([-F0[1], F0[0]]) / e)
        return -dF

    Z_grid = jax.vmap(one)(whirl)
    g = pr.load_angle + phi - film.offset(x0, cfg)     # the grid's absolute angle
    R = jnp.array([[jnp.cos(g), -jnp.sin(g)], [jnp.sin(g), jnp.cos(g)]])
    return jnp.einsum("ij,mjk,lk->mil", R, Z_grid, R)


@partial(jax.jit, static_argnames="cfg")
def _linearized(x0, pr: film.Params, bodies, whirl, cfg: film.Config):
    """(Z, C, Stats of the half-Sommerfeld pressure's solve or None) about the steady unknowns
    ``x0``; one compiled program per configuration (the solve of the unclipped pressure's
    Newton, traced outside jit, compiled anew on every call)."""
    stats = None
    if cfg.cavitation == "half_sommerfeld":     # the result holds the clipped pressure: recover the film's own
        pr = dataclasses.replace(pr, x0=jax.lax.stop_gradient(x0))
        x0, stats = _solve.implicit_root(lambda prm: film.newton(prm.x0, prm, cfg),
                                         lambda x, aux, prm: film.equations(x, prm, cfg)[0])(pr)
    # Z and dZ/dOmega (each Z_m depends on Omega_m only): C = Im Z / Omega, or its limit
    # d(Im Z)/dOmega at Omega = 0
    Z, dZ = jax.jvp(lambda w: _impedance(x0, pr, cfg, bodies, w), (whirl,), (jnp.ones_like(whirl),))
    at_rest = (whirl == 0)[:, None, None]
    C = jnp.where(at_rest, dZ.imag, Z.imag / jnp.where(at_rest, 1.0, whirl[:, None, None]))
    return Z, C, stats


def journal_coefficients(R, radial_clearance, viscosity, load, whirl, *, housing=None, shaft=None,
                         omega_shaft=0.0, omega_housing=0.0, load_angle=-math.pi / 2, cavitation: str = "reynolds",
                         supply_angle=math.pi, supply_pressure=0.0, groove: str | None = None, temperature=None,
                         shift=None,
                         initial: JournalResult | None = None, options: JournalOptions = JournalOptions(),
                         throw: bool = True, length=None, tilt=None, supply_width=1.0) -> JournalCoefficients:
    """Stiffness and damping of a (visco)elastic journal bearing at whirl frequencies ``whirl``.

    The arguments are those of :func:`vjax.journal_bearing` (which solves the steady state,
    with the periodic-memory bodies) plus ``whirl`` (rad/s, a scalar or 1-D array; negative
    for backward whirl). Returns :class:`JournalCoefficients` (module docstring for the frame
    and the sign convention). Differentiable in the bearing's parameters.

    With ``length=L`` (m; and optionally ``tilt``, ``supply_width``): the finite bearing of
    :mod:`vjax.journal_finite`, its groove fixed in the bearing; K (N/m) and C (N s/m) are the
    bearing's totals, the 2D film linearized in the journal's position and velocity, and the
    bodies by their whirl operators (:func:`vjax.journal_finite.impedance`); rigid bodies
    give K and C independent of the whirl frequency (but for the "jfo" cavity's own dynamics).

    >>> import jax; jax.config.update("jax_enable_x64", True)
    >>> co = journal_coefficients(0.05, 5e-5, 0.01, 2e4, [0.0, 100.0], omega_shaft=100.0,
    ...                           options=JournalOptions(n=64))
    >>> co.stiffness.shape, bool(co.stiffness[0, 1, 1] > 0)
    ((2, 2, 2), True)
    """
    whirl = jnp.atleast_1d(jnp.asarray(whirl, jnp.result_type(float)))
    if whirl.ndim != 1:
        raise ValueError(f"whirl must be a number or a 1-D array of whirl frequencies (rad/s), got shape {whirl.shape}")
    checks.finite("whirl", whirl)
    if length is not None or tilt is not None or supply_width != 1.0:
        # the finite bearing (vjax.journal_finite): Z, K, C the bearing's totals
        journal_finite.check_supported(length, groove, cavitation)
        opts = journal_finite.FiniteJournalOptions() if options == JournalOptions() else options
        sol, Z, K, C = journal_finite.finite_coefficients(
            R, radial_clearance, viscosity, load, length, whirl, housing=housing, shaft=shaft,
            omega_shaft=omega_shaft, omega_housing=omega_housing, load_angle=load_angle, cavitation=cavitation,
            supply_angle=supply_angle, supply_pressure=supply_pressure, supply_width=supply_width, tilt=tilt,
            temperature=temperature, shift=shift, groove=groove or "fixed", initial=initial, options=opts,
            throw=throw)
        return JournalCoefficients(whirl=whirl, impedance=Z, stiffness=K, damping=C,
                                   speed=jnp.asarray(omega_shaft, whirl.dtype), steady=sol,
                                   length=jnp.asarray(length, whirl.dtype))
    groove = "line_of_centres" if groove is None else groove
    sol = journal_bearing(R, radial_clearance, viscosity, load, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
                          omega_housing=omega_housing, load_angle=load_angle, memory="periodic",
                          cavitation=cavitation, supply_angle=supply_angle, supply_pressure=supply_pressure,
                          groove=groove, temperature=temperature, shift=shift, initial=initial, options=options, throw=throw)
    pr, cfg, hb, sb = film.setup(
        R, radial_clearance, viscosity, load, housing=housing, shaft=shaft, omega_shaft=omega_shaft,
        omega_housing=omega_housing, load_angle=load_angle, memory="periodic", cavitation=cavitation,
        supply_angle=supply_angle, supply_pressure=supply_pressure, temperature=temperature, shift=shift,
        options=options, groove=groove)
    x0 = film.start(sol.pressure, sol.film_fraction, sol.eccentricity, sol.attitude_angle, pr.p_ref)
    Z, C, stats = _linearized(x0, pr, ((hb, pr.R, -pr.omega_B), (sb, pr.RJ, -pr.omega_J)), whirl, cfg)
    if stats is not None:
        _solve.report("journal_coefficients (half-Sommerfeld pressure)", stats, throw)
    return JournalCoefficients(whirl=whirl, impedance=Z, stiffness=Z.real, damping=C,
                               speed=jnp.asarray(omega_shaft, whirl.dtype), steady=sol)


def lund(K, C):
    """Lund's threshold (K_eq, W^2) (N/m, rad^2/s^2) of stiffness and damping arrays K, C
    (..., 2, 2) (N/m, N s/m): the equations of :func:`stability_threshold`, in plain array
    arithmetic, so that they trace under jit and differentiate (a design's whirl constraint)."""
    Keq = (K[..., 0, 0] * C[..., 1, 1] + K[..., 1, 1] * C[..., 0, 0] - K[..., 0, 1] * C[..., 1, 0]
           - K[..., 1, 0] * C[..., 0, 1]) / (C[..., 0, 0] + C[..., 1, 1])
    W2 = ((K[..., 0, 0] - Keq) * (K[..., 1, 1] - Keq) - K[..., 0, 1] * K[..., 1, 0]) \
        / (C[..., 0, 0] * C[..., 1, 1] - C[..., 0, 1] * C[..., 1, 0])
    return Keq, W2


def stability_threshold(coefficients: JournalCoefficients, length=1.0) -> dict:
    """Onset of oil whirl of a symmetric rigid rotor on two identical bearings (cylindrical
    mode; Lund's classical analysis): per bearing a mass M on the coefficients K, C,

        M x'' + C x' + K x = 0,  threshold det(K - M W^2 + i W C) = 0 with real W:
        K_eq = (K_xx C_yy + K_yy C_xx - K_xy C_yx - K_yx C_xy) / (C_xx + C_yy),
        W^2 = ((K_xx - K_eq)(K_yy - K_eq) - K_xy K_yx) / (C_xx C_yy - C_xy C_yx),
        M_crit = K_eq / W^2.

    Frequency-independent coefficients (rigid bodies) need one whirl frequency; for
    frequency-dependent ones (viscoelastic liners) the coefficients are taken at the whirl
    frequency of the threshold itself: the root of W^2(W) - W^2 on the ``whirl`` grid of
    ``coefficients`` (linear interpolation of the coefficients; None if no sign change).

    Returns dict ``whirl`` W (rad/s), ``whirl_ratio`` W / omega_journal, ``critical_mass``
    M_crit (kg per bearing of axial ``length`` m; ignored for a finite bearing's coefficients,
    which are its totals), ``stiffness`` K_eq (N/m for that length);
    a mass below M_crit runs stable. None values when no threshold exists (stable at any mass).
    """
    if coefficients.length is not None:      # a finite bearing's totals
        length = 1.0
    checks.positive("length", length)
    K = np.asarray(coefficients.stiffness) * length
    C = np.asarray(coefficients.damping) * length
    W = np.asarray(coefficients.whirl)
    speed = float(coefficients.speed)
    none = dict(whirl=None, whirl_ratio=None, critical_mass=None, stiffness=None)

    if W.size == 1:
        keq, w2 = lund(K[0], C[0])
    else:
        forward = np.flatnonzero(W > 0)
        forward = forward[np.argsort(W[forward])]
        W, K, C = W[forward], K[forward], C[forward]
        at = lambda t, i: (K[i] + t * (K[i + 1] - K[i]), C[i] + t * (C[i + 1] - C[i]), W[i] + t * (W[i + 1] - W[i]))  # noqa: E731
        f = lund(K, C)[1] - W ** 2      # the threshold: W^2 from the coefficients at W equals W^2
        cross = np.flatnonzero(np.sign(f[:-1]) != np.sign(f[1:]))
        if cross.size == 0:
            return none
        i, lo, hi = cross[0], 0.0, 1.0
        for _ in range(60):             # bisection on the linearly interpolated coefficients
            mid = 0.5 * (lo + hi)
            Km, Cm, Wm = at(mid, i)
            if np.sign(lund(Km, Cm)[1] - Wm ** 2) == np.sign(f[i]):
                lo = mid
            else:
                hi = mid
        keq, w2 = lund(*at(lo, i)[:2])
    if not (w2 > 0 and keq > 0):
        return none
    w = math.sqrt(w2)
    return dict(whirl=w, whirl_ratio=w / speed if speed else None, critical_mass=float(keq / w2),
                stiffness=float(keq))
