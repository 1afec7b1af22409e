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

The linearization of each film: :mod:`vjax.scenes.journal.long.coefficients` and
:mod:`vjax.scenes.journal.finite.coefficients`.
"""
from __future__ import annotations

import csv
import dataclasses
import io
import math
import os
import tempfile
import warnings

import jax
import jax.numpy as jnp
import numpy as np

from ..._core import checks
from .bearing import is_finite
from .finite import FiniteJournalResult, finite_coefficients
from .finite.setup import check_supported
from .long import JournalResult
from .long.coefficients import long_coefficients
from .options import FiniteJournalOptions, JournalOptions
from .setup import oil_and_bodies


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


def journal_coefficients(R, radial_clearance, viscosity, load, whirl, *, housing=None, shaft=None,
                         omega_shaft=0.0, omega_housing=0.0, load_angle=-math.pi / 2, cavitation: str = "reynolds",
                         supply_angle=math.pi, supply_pressure=0.0, groove: str | None = None, temperature=None,
                         oil_temperature=None, initial: JournalResult | FiniteJournalResult | None = None,
                         options: JournalOptions | FiniteJournalOptions | None = None, throw: bool = True, length=None,
                         tilt=None, supply_width=1.0, roughness=None, shift=None) -> JournalCoefficients:
    """Stiffness and damping of a (visco)elastic journal bearing at whirl frequencies ``whirl``.

    The arguments are those of :func:`vjax.journal_bearing` (which solves the steady state,
    with the periodic-memory bodies) plus ``whirl`` (rad/s, a scalar or 1-D array; negative
    for backward whirl). Returns :class:`JournalCoefficients` (module docstring for the frame
    and the sign convention). Differentiable in the bearing's parameters.

    With ``length=L`` (m; and optionally ``tilt``, ``supply_width``): the finite bearing of
    :mod:`vjax.scenes.journal.finite`, its groove fixed in the bearing; K (N/m) and C (N s/m) are the
    bearing's totals, the 2D film linearized in the journal's position and velocity, and the
    bodies by their whirl operators (:func:`vjax.scenes.journal.finite.impedance`); rigid bodies
    give K and C independent of the whirl frequency (but for the "jfo" cavity's own dynamics).

    With ``roughness=`` (rigid bodies, long or finite): the mixed film linearized with its rough
    fluxes, and the asperities' force, which follows the position at once, adds its derivative
    to K (no damping); a deformable body with rough surfaces is refused.

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
    viscosity, temperature = oil_and_bodies(viscosity, temperature, oil_temperature, housing, shaft, shift)
    common = dict(housing=housing, shaft=shaft, omega_shaft=omega_shaft, omega_housing=omega_housing,
                  load_angle=load_angle, cavitation=cavitation, supply_angle=supply_angle,
                  supply_pressure=supply_pressure, temperature=temperature, shift=shift, initial=initial, throw=throw)
    speed = jnp.asarray(omega_shaft, whirl.dtype)
    if is_finite(length, tilt, supply_width):   # Z, K, C the bearing's totals
        check_supported(length, groove, cavitation)
        sol, Z, K, C = finite_coefficients(
            R, radial_clearance, viscosity, load, length, whirl, supply_width=supply_width, tilt=tilt,
            groove=groove or "fixed", roughness=roughness,
            options=FiniteJournalOptions() if options is None else options, **common)
        return JournalCoefficients(whirl=whirl, impedance=Z, stiffness=K, damping=C, speed=speed, steady=sol,
                                   length=jnp.asarray(length, whirl.dtype))
    sol, Z, C = long_coefficients(R, radial_clearance, viscosity, load, whirl, groove=groove, roughness=roughness,
                                  options=JournalOptions() if options is None else options, **common)
    return JournalCoefficients(whirl=whirl, impedance=Z, stiffness=Z.real, damping=C, speed=speed, steady=sol)


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
