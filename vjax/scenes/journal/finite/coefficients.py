"""The finite journal bearing's dynamic coefficients: the cell equations linearized in the
pressures and the journal's position and tilt and their rates, the bodies by their whirl
operators (:func:`impedance`); stiffness and damping in position (:func:`finite_coefficients`)
and in position and tilt (:func:`tilt_coefficients`); the film force under position control
(:func:`force_at`)."""
from __future__ import annotations

import dataclasses
from functools import partial

import jax
import jax.numpy as jnp

from ...._core import checks, krylov as _krylov, solve as _solve, xla
from ....bodies.land import dct1, idct1
from ....bodies.operator import grid
from ....films import blocks, film2d, reynolds
from ..setup import bodies_at
from . import film as finite_film
from .film import (KRYLOV_MAX_ITER, KRYLOV_TOL, Config, Params, as_unknowns, cell_residual, fields,
                   interior, is_rigid, loading, rotation, stencil_solver, unknowns)
from .outputs import FiniteJournalResult
from .setup import setup
from .steady import finite_journal_bearing, solve


KRYLOV_ACCEPT = 1e-6      # the dynamic coefficients' GMRES solves fail above this relative residual (float32: 1e-3)


def _pressure_solver(cells, pz, cfg: Config):
    """Solve with the rigid film's Jacobian d cells / d pz at pz (the pressures alone, the
    position held: block tridiagonal, :mod:`vjax.films.blocks`)."""
    return blocks.ring_solver(blocks.neighbourhood_blocks(cells, pz, cfg.n, cfg.m - 1))


def _whirl_response(pr: Params, cfg: Config, bodies, W):
    """The bodies' displacement (n, m + 1) (m, complex: u_B + u_J, each opening the film) under a
    small loading pressure dp (n, m + 1) (Pa) e^(i W t) on the pattern fixed in space; ``bodies``
    as in :func:`impedance`. Each theta mode k (full FFT) responds at its own frequency -k omega +
    W: an axial slice as its plane ring (:meth:`vjax.Body.whirl_symbol`), a 3D layer with its
    sections coupled through the DCT-I in z (:func:`vjax.bodies.land.whirl_symbol`): O(N log N)."""
    n, m = cfg.n, cfg.m
    slices = [b for b in bodies if b[0] is not None and b[0].axial != "3d"]
    layers = [b for b in bodies if b[0] is not None and b[0].axial == "3d"]
    S = sum(body.whirl_symbol(R_b, n, omega_b, W) for body, R_b, omega_b in slices)
    S3 = sum(body.land_whirl_symbol(R_b, n, m, pr.L, omega_b, W) for body, R_b, omega_b in layers)

    def response(dp):
        P = jnp.fft.fft(dp, axis=0)
        U = (S[:, None] * P if slices else 0.0) + (idct1(S3 * dct1(P, axis=1), axis=1) if layers else 0.0)
        return pr.compliance * jnp.fft.ifft(U, axis=0)
    return response


@xla.jit(static_argnums=(2, 5))
def impedance(x0, pr: Params, cfg: Config, bodies, whirl, tilt: bool = False):
    """Z(Omega) = K + i Omega C (complex, absolute axes) of the finite bearing about the steady
    unknowns x0 (whole width) at the whirl frequencies ``whirl`` (k,) (rad/s), and the
    :class:`~vjax._core.solve.Stats` of its linear solves. Z is (k, 2, 2) (N/m) in the journal's
    position; with ``tilt`` (k, 4, 4) in its position and tilt q = (X, Y, gamma_x, gamma_y) for
    the film's force and moment (F_x, F_y, M_x, M_y): blocks in N/m, N/rad, N m/m, N m/rad; the
    forces conjugate to q are (F_x, F_y, M_y, -M_x) (gamma_x turns the journal about y, gamma_y
    about -x). ``bodies``: ((body or None, radius, speed of the pattern relative to it), ...) for
    the housing and the shaft.

    The grid is fixed in space (the groove fixed in the bearing): a journal motion changes the
    film by -(dX + z dgamma_x) cos theta - (dY + z dgamma_y) sin theta and adds its rate to
    dh/dt. The bodies respond to the perturbed loading pressure by their whirl operator
    (:func:`_whirl_response`: each theta mode at its own frequency), which adds to the film and,
    times i Omega, to its rate; in a "jfo" cavity the liquid fraction has its own dynamics, h
    df/dt (so K and C depend on Omega even for rigid bodies: the cavity carries its liquid to
    where the film re-forms with a delay). With dU = M(Omega) S dp:

        (A_p + i Omega A_f + (A_U + i Omega A_Udot) M(Omega) S) dp = -(B_q + i Omega B_qdot) dq,
        dQ = G dp,   Z = -dQ/dq

    (S the loading pressure's slope: the half-Sommerfeld clip; A_f diagonal, R dtheta dz h in
    a "jfo" cavity's cells, 0 elsewhere). The products are matrix-free (one FFT each). With
    deformable bodies and ``cfg.krylov`` (``FiniteJournalOptions.linear_solver``, as Newton's
    steps) the solves are GMRES, one per whirl frequency and load column, preconditioned by the
    film's stencil with each node's own whirl compliance on its diagonal (as
    :func:`linear_model`: the exact block solve up to EXACT_WIDTH cells across, the multigrid
    V-cycle above); a relative residual above KRYLOV_ACCEPT is reported as a failure
    (``stats``). Otherwise a dense complex LU of the matrix from N products (small grids).
    Rigid bodies: the block solve alone, exact, up to EXACT_WIDTH cells across; GMRES with the
    V-cycle above. With rough surfaces the asperities' force, which follows the journal's
    position without delay, adds its stiffness to K."""
    n, m = cfg.n, cfg.m
    N = unknowns(cfg)
    pz0 = x0[:N]
    theta, _ = grid(n)
    z = 0.5 * pr.L * pr.s
    f0 = fields(x0, pr, cfg)
    U0, zero, no_rate = f0["uB"] + f0["uJ"], jnp.zeros((n, m + 1), x0.dtype), jnp.zeros(N, x0.dtype)
    k = 4 if tilt else 2
    q0 = jnp.zeros(2 * k, x0.dtype)         # (dX, dY[, dgamma_x, dgamma_y]) and their rates
    rigid = all(body is None for body, _, _ in bodies)
    direct = rigid and m - 1 <= finite_film.EXACT_WIDTH

    def cells(pz, U, Udot, rate, q):
        p = pr
        if tilt:                            # the tilt moves the journal centre at z by z dgamma
            p = dataclasses.replace(pr, tilt=pr.tilt + q[2:4])
            Udot = Udot - z[None, :] * (q[6] * jnp.cos(theta)[:, None] + q[7] * jnp.sin(theta)[:, None])
        motion = jnp.stack([q[0], q[1], q[k], q[k + 1]])
        return cell_residual(jnp.concatenate([pz, x0[N:]]), p, cfg, motion, deformation=(U, Udot), rate=rate)[0]

    def loads(pz):                          # the film's force (and moment) on the journal
        p_load = loading(interior(pz, cfg), pr, cfg)[2]
        return jnp.concatenate(film2d.resultants(p_load, theta, z, pr.R))[:k]

    _, film = jax.linearize(lambda pz, U, Udot, rate: cells(pz, U, Udot, rate, q0), pz0, U0, zero, no_rate)
    B = jax.jacfwd(lambda q: cells(pz0, U0, zero, no_rate, q))(q0)                    # (N, 2 k)
    G = jax.jacrev(loads)(pz0)                                                         # (k, N)
    slope = reynolds.load_slope(pz0, cfg.cavitation).reshape(n, m - 1) * pr.p_ref
    loading_of = lambda v: film2d.with_ends(slope * v.reshape(n, m - 1))                 # noqa: E731
    dense = not (rigid or cfg.krylov)       # the matrix from N products and its LU (small grids)
    if not dense:   # the film's stencils: in the pressures, in the cavity's rate, and through each
        # node's own loading in U and dU/dt (the preconditioner's)
        stencil = lambda fn: blocks.stencil(fn, no_rate, n, m - 1)                    # noqa: E731
        C_p, C_f = stencil(lambda v: film(v, zero, zero, 0 * v)), stencil(lambda v: film(0 * v, zero, zero, v))
        if not rigid:
            C_U = stencil(lambda v: film(0 * v, loading_of(v), zero, 0 * v))
            C_Ud = stencil(lambda v: film(0 * v, zero, loading_of(v), 0 * v))
    unit = jnp.zeros((n, m + 1), x0.dtype).at[0, m // 2].set(1.0)

    def one(W):
        response = None if rigid else _whirl_response(pr, cfg, bodies, W)

        def matvec(v):                  # the complex system's product: the real linear map on Re and Im
            dU = jnp.zeros((n, m + 1), v.dtype) if rigid else response(loading_of(v))
            ri = lambda a: jnp.stack([a.real, a.imag])     # noqa: E731
            parts = jax.vmap(film)(ri(v), ri(dU), ri(1j * W * dU), ri(1j * W * v))
            return parts[0] + 1j * parts[1]

        b = (B[:, :k] + 1j * W * B[:, k:]).T                                               # (k, N)
        if dense:
            return G @ jnp.linalg.solve(jax.vmap(matvec)(jnp.eye(N, dtype=b.dtype)).T, b.T), jnp.zeros(())
        C = C_p + 1j * W * C_f
        if direct:                      # the stencil is the whole matrix: its exact block solve
            dp = jax.vmap(stencil_solver(C))(b)
            residual = jnp.linalg.norm(b - jax.vmap(matvec)(dp)) / jnp.linalg.norm(b)
            return G @ dp.T, residual
        if not rigid:
            C = C + response(unit)[0, m // 2] * (C_U + 1j * W * C_Ud)
        # the preconditioner does not change the solution: no derivatives through its factors
        precondition = stencil_solver(jax.lax.stop_gradient(C))
        dp, residual = jax.vmap(lambda r: _krylov.gmres(matvec, r, precondition, KRYLOV_TOL, KRYLOV_MAX_ITER))(b)
        return G @ dp.T, jnp.max(residual)

    Z, residual = jax.vmap(one)(whirl)
    if pr.rough is not None:    # the asperities' force follows the journal's position at once: a stiffness
        def asperity_loads(q):
            p = dataclasses.replace(pr, tilt=pr.tilt + q[2:4]) if tilt else pr
            motion = jnp.concatenate([q[:2], jnp.zeros(2, q.dtype)])
            f = fields(x0, p, cfg, motion, deformation=(U0, zero))
            return jnp.concatenate(film2d.resultants(f["p_asp"], theta, z, pr.R))[:k]
        Z = Z - jax.jacfwd(asperity_loads)(q0[:k])[None]
    accept = KRYLOV_ACCEPT if x0.dtype == jnp.float64 else 1e-3
    stats = _solve.Stats(jnp.ones(whirl.shape, jnp.int32), residual,
                         jnp.where(residual <= accept, _solve.SUCCESS, _solve.INNER_FAILED))
    rot = jnp.kron(jnp.eye(k // 2, dtype=x0.dtype), rotation(pr.frame))
    return jnp.einsum("ij,wjk,lk->wil", rot, Z, rot), stats


def _bodies(R, radial_clearance, kw):
    """``impedance``'s bodies for the keyword arguments ``kw`` of :func:`finite_journal_bearing`:
    the pressure pattern is fixed in space, so it moves at -omega relative to each body."""
    housing, shaft = bodies_at(R, radial_clearance, kw.get("housing"), kw.get("shaft"), kw.get("temperature"),
                               kw.get("shift"))
    return ((housing, R, -kw.get("omega_housing", 0.0)), (shaft, R - radial_clearance, -kw.get("omega_shaft", 0.0)))


def tilt_coefficients(R, radial_clearance, viscosity, load, length, *, whirl=None, initial=None, throw=True, **kw):
    """Steady :class:`FiniteJournalResult` and the 4 x 4 stiffness and damping in the journal's
    position and tilt (:func:`impedance` with ``tilt``; absolute axes), for a rotor model that
    carries the journal's angular motion (a misaligned or short, stiff bearing): dQ = -(K dq +
    C dq/dt) for q = (X, Y, gamma_x, gamma_y), Q = (F_x, F_y, M_x, M_y). ``whirl`` None: K and C
    (4, 4) at rest (rigid bodies: at every whirl frequency); an array (k,) (rad/s): (k, 4, 4),
    deformable bodies' at their own frequencies. ``kw``: the keyword arguments of
    :func:`finite_journal_bearing`."""
    if kw.get("cavitation", "reynolds") in ("half_sommerfeld", "jfo"):
        raise ValueError(f"cavitation={kw['cavitation']!r}: the tilt coefficients take 'reynolds' or 'sommerfeld'")
    at = jnp.atleast_1d(jnp.asarray(0.0 if whirl is None else whirl, jnp.result_type(float)))
    if at.ndim != 1:
        raise ValueError(f"whirl must be a number or a 1-D array of whirl frequencies (rad/s), got shape {at.shape}")
    checks.finite("whirl", at)
    steady, _, K, C = _solved_coefficients("tilt_coefficients", R, radial_clearance, viscosity, load, length, at,
                                           True, initial, throw, kw)
    return (steady, K[0], C[0]) if whirl is None else (steady, K, C)


def _solved_coefficients(caller, R, radial_clearance, viscosity, load, length, whirl, tilt, initial, throw, kw):
    """The steady solve of the keyword arguments ``kw`` of :func:`finite_journal_bearing` and its
    :func:`coefficients` (steady, Z, K, C); a failed whirl solve reported under ``caller``."""
    pr, cfg = setup(R, radial_clearance, viscosity, load, length, **kw)
    _check_linearizable(pr)
    steady = finite_journal_bearing(R, radial_clearance, viscosity, load, length, initial=initial, throw=throw, **kw)
    Z, K, C, stats = coefficients(steady, pr, cfg, _bodies(R, radial_clearance, kw), whirl, tilt)
    _solve.report(f"{caller} (the finite bearing's whirl solves)", stats, throw)
    return steady, Z, K, C


def _check_linearizable(pr: Params):
    if pr.rough is not None and not is_rigid(pr):
        raise ValueError("roughness with a deformable body: the dynamic coefficients of a mixed film on a "
                         "deformable body are not built yet (rigid bodies: housing=None, shaft=None)")


def coefficients(steady: FiniteJournalResult, pr: Params, cfg: Config, bodies, whirl, tilt: bool = False):
    """(Z, K, C, stats) (complex N/m, N/m, N s/m; (k, 2, 2), or (k, 4, 4) with ``tilt``; absolute
    axes; the :class:`~vjax._core.solve.Stats` of :func:`impedance`'s solves) at the whirl frequencies
    ``whirl`` (k,) about a converged :class:`FiniteJournalResult` of the bearing ``pr``, ``cfg``
    (the steady solve of the same arguments; ``bodies`` as in :func:`impedance`); its pressure
    recovered for the half-Sommerfeld film (whose result holds the clipped pressure) by one more
    solve. C = Im Z / Omega, at Omega = 0 its limit d(Im Z)/dOmega."""
    # "jfo": the universal unknown, the film fraction - 1 in the cavity
    _check_linearizable(pr)
    x0 = as_unknowns(steady.pressure / pr.p_ref + (steady.film_fraction - 1.0), steady.position, pr, cfg)
    if cfg.cavitation == "half_sommerfeld":
        x0, _ = solve(dataclasses.replace(pr, x0=jax.lax.stop_gradient(x0)), cfg)
    Z, dZ, stats = jax.jvp(lambda w: impedance(x0, pr, cfg, bodies, w, tilt), (whirl,), (jnp.ones_like(whirl),),
                           has_aux=True)
    at_rest = (whirl == 0)[:, None, None]
    C = jnp.where(at_rest, dZ.imag, Z.imag / jnp.where(at_rest, 1.0, whirl[:, None, None]))
    return Z, Z.real, C, stats


def finite_coefficients(R, radial_clearance, viscosity, load, length, whirl, *, initial=None, throw=True, **kw):
    """Steady :class:`FiniteJournalResult` and its (Z, K, C) (complex N/m, N/m, N s/m; (k, 2, 2),
    absolute axes) at the whirl frequencies ``whirl`` (k,) for
    ``vjax.journal_coefficients(..., length=L)``; ``kw``: the keyword arguments of
    :func:`finite_journal_bearing` (rigid bodies and no "jfo" cavity: K, C independent of the whirl)."""
    return _solved_coefficients("journal_coefficients", R, radial_clearance, viscosity, load, length, whirl,
                                False, initial, throw, kw)


@partial(jax.jit, static_argnums=(2,))
def force_at(x, pr: Params, cfg: Config, motion):
    """Film force on the journal (N, grid axes) with the journal held at the position of x
    (its last two entries, e/c) plus ``motion`` (dX, dY, dX/dt, dY/dt) (m, m/s): the nonlinear
    cell equations solved by Newton for the pressures from x's (the position control the
    dynamic coefficients linearize); returns (force, :class:`~vjax._core.solve.Stats`). Rigid
    bodies only: a deformable body's first mode is tied to the load (:func:`deformations`),
    which position control does not hold."""
    if not is_rigid(pr):
        raise ValueError("force_at: rigid bodies only (housing=None, shaft=None)")
    N = unknowns(cfg)
    cells = lambda pz: cell_residual(jnp.concatenate([pz, x[N:]]), pr, cfg, motion)[0]
    linear_solve = lambda pz, state, r: _pressure_solver(cells, pz, cfg)(-r)    # noqa: E731
    pz, _, stats = _solve.newton(lambda pz, s: (cells(pz), s, True), x[:N], None, tol=cfg.tol,
                                 max_iter=cfg.max_iter, linear_solve=linear_solve)
    return cell_residual(jnp.concatenate([pz, x[N:]]), pr, cfg, motion)[1], stats
