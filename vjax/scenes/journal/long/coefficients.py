"""The infinitely long journal bearing's dynamic coefficients (linearization).
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
body (:func:`vjax.bodies.operator.whirl_symbol`: a material point of a body rotating at omega_b
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

Rough surfaces (mixed lubrication, rigid bodies): the film is Patir and Cheng's average flow,
whose stored volume per unit area is the expected gap h_T (the gap its Couette flux carries), so
the squeeze term is R dh_T/dt = R (dh_T/dh) dh/dt; the surfaces' sliding speed, which sets the
shear flow, is left unchanged by the frame's turning (its change c dgamma/dt is O(c/R), as the
entrainment speed's R dgamma/dt is taken at the bore's radius). The asperities' force follows
the film at once: it adds a stiffness, d(asperity force)/d(position), and no damping (their
force turns with the frame as the film's does).
"""
from __future__ import annotations

import dataclasses
import math

import jax
import jax.numpy as jnp

from ...._core import solve as _solve, xla
from ....bodies.operator import circulant, grid
from ....films import reynolds
from ..options import JournalOptions
from . import film
from .steady import long_journal_bearing


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
    rough = pr.rough
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
    sliding = film.sliding(pr)
    hf, _, q = reynolds.face_fluxes(p, h, pr.R, pr.eta, v, fraction if jfo else None, rough, sliding)
    # the film's own growth R d(h f)/dt, f the liquid fraction (1 but in a "jfo" cavity); on rough
    # surfaces the stored gap is the expected one, h_T (or h with rough.couette == "nominal")
    stored = (lambda g: g) if rough is None or rough.couette == "nominal" else rough.expected_gap
    gap, gap_rate = jax.jvp(stored, (h,), (hdot,))
    fraction_rate = jnp.where(pz < 0, pzdot, 0.0) if jfo else 0.0
    squeeze = pr.R * (gap_rate * fraction + gap * fraction_rate)
    r = reynolds.cell_equations(pz, q, pr.q_ref, cfg.cavitation, squeeze=squeeze,
                                couette=reynolds.couette_flux(hf, v, rough, sliding), v=v)
    r = r.at[pr.groove].set(pz[pr.groove] - pr.ps / pr.p_ref)
    p_load = reynolds.load_pressure(p, cfg.cavitation)
    if rough is not None:     # the asperities' pressure at this film (rigid bodies: U is zero)
        p_load = p_load + rough.asperity_pressure(h)
    F = -pr.R * 2 * alpha * jnp.stack([jnp.sum(p_load * cos), jnp.sum(p_load * sin)])
    return r, F


@xla.jit(static_argnums=(2,))
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
    F0 = eqs(*args)[1]     # the film's and the asperities' force: it turns with the frame
    J_p, J_pd, J_U, J_Ud, J_s = jax.jacfwd(lambda *a: eqs(*a)[0], argnums=(0, 1, 2, 3, 4))(*args)
    # the asperities' force follows the position at once (rigid bodies): a stiffness, per unit
    # dX, dY; none without them (the film's force changes only through its pressure, G_p dp)
    F_s = jnp.zeros((2, 2), x0.dtype)
    if pr.rough is not None:
        F_s = jax.jacfwd(lambda m: eqs(*args[:4], m)[1])(args[4])[:, :2]
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
        dF = G_p @ dpz + F_s
        if not cfg.fixed_groove:     # the steady force turns with the frame by dY / e
            dF = dF.at[:, 1].add(jnp.stack([-F0[1], F0[0]]) / e)
        return -dF

    Z_grid = jax.vmap(one)(whirl)
    g = pr.load_angle + phi - film.offset(x0, cfg)     # the grid's absolute angle
    R = jnp.array([[jnp.cos(g), -jnp.sin(g)], [jnp.sin(g), jnp.cos(g)]])
    return jnp.einsum("ij,mjk,lk->mil", R, Z_grid, R)


@xla.jit(static_argnames="cfg")
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


def long_coefficients(R, radial_clearance, viscosity, load, whirl, *, housing=None, shaft=None, omega_shaft=0.0,
                      omega_housing=0.0, load_angle=-math.pi / 2, cavitation="reynolds", supply_angle=math.pi,
                      supply_pressure=0.0, groove=None, temperature=None, shift=None, initial=None,
                      options: JournalOptions = JournalOptions(), throw=True, roughness=None):
    """The steady :class:`JournalResult` (periodic memory) and its (Z, C) (complex N/m^2, N s/m^2;
    (k, 2, 2), absolute axes) at the whirl frequencies ``whirl`` (k,) (rad/s), for
    :func:`vjax.journal_coefficients` without ``length`` (its arguments; ``roughness`` with rigid
    bodies only)."""
    groove = "line_of_centres" if groove is None else groove
    if roughness is not None and (housing is not None or shaft is not None):
        raise ValueError("roughness with a deformable body: the dynamic coefficients of a mixed film on a "
                         "deformable body are not built yet (rigid bodies: housing=None, shaft=None)")
    arguments = dict(housing=housing, shaft=shaft, omega_shaft=omega_shaft, omega_housing=omega_housing,
                     load_angle=load_angle, memory="periodic", cavitation=cavitation, supply_angle=supply_angle,
                     supply_pressure=supply_pressure, groove=groove, temperature=temperature, shift=shift,
                     options=options, roughness=roughness)
    sol = long_journal_bearing(R, radial_clearance, viscosity, load, initial=initial, throw=throw, **arguments)
    pr, cfg, hb, sb = film.setup(R, radial_clearance, viscosity, load, **arguments)
    x0 = film.start(sol.pressure, sol.film_fraction, sol.eccentricity, sol.attitude_angle, pr.p_ref)
    Z, C, stats = _linearized(x0, pr, ((hb, pr.R, -pr.omega_B), (sb, pr.RJ, -pr.omega_J)), whirl, cfg)
    if stats is not None:
        _solve.report("journal_coefficients (half-Sommerfeld pressure)", stats, throw)
    return sol, Z, C
