"""Dry frictionless contact on a ring: complementarity solve with implicit derivatives.

Given a ring operator u = M sigma (:class:`~vjax.RingOperator`, circulant, not symmetric for
a viscoelastic body) and the interference d(q) of rigid indenters with the undeformed ring
(positive where they overlap it; q are rigid-body unknowns such as a pin offset or roller
penetrations), find the pressure sigma (Pa) with

    sigma >= 0,   g = M sigma - d(q) >= 0,   sigma * g = 0         (Signorini, element-wise)

and, under load control, the k rigid-body unknowns q from k force conditions force(sigma) = F.
Several patches on one ring are one problem (they interact through the ring).

The optimality condition is the projected fixed point
``sigma = max(0, sigma - c g)`` (c > 0 a scaling, 1/diagonal of M), written as the
residual ``r(sigma) = where(A, g, sigma)`` on the active set A = {sigma - c g > 0}.

**Forward solve** (thesis Section 2.1, made matrix-free): a primal-dual active-set /
semismooth Newton iteration. Each step solves the linear problem on the current active
set, M_AA sigma_A = d_A (plus the bordered load conditions and the linearized d(q)), by
BiCGSTAB with FFT matrix-vector products preconditioned by the restriction of the
circulant inverse M^-1 (converges in 5-10 Krylov steps independently of N and of
the size of the contact), then updates A. No dense N x N matrix is formed: each step
costs O(N log N) per Krylov iteration. M_AA and its preconditioner depend only on offsets
within A, so when A spans at most an eighth of the ring, the Krylov solve runs on a window
of N/4 elements instead, with FFTs a quarter as long.

**Derivatives**: implicit, at the solution (:func:`vjax._core.solve.implicit_root`): the tangent
solves the same linearized system with the active set frozen, matrix-free by the bordered
Krylov solve below (forward and reverse mode; the reverse pass is one transposed solve). Nothing is
differentiated through the iterations. Where the contact set is about to change the
derivative is the one-sided derivative of the current set: finite, never NaN.

Convergence: the solution carries ``iterations``, ``residual`` (complementarity, relative
to the peak pressure, plus the relative force misfit) and ``converged``.
"""
from __future__ import annotations

import dataclasses
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from .._core import checks, krylov as _krylov, solve as _solve
from .._core.checks import is_concrete
from ..bodies.operator import RingOperator


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class ContactSolution:
    """Pressure (Pa), displacement (m), rigid-body unknowns q, the active set, and the solve's
    report: ``iterations`` (active-set Newton steps), ``residual``, ``result`` (a code of
    :mod:`vjax._core.solve`; ``converged`` is ``result == 0``)."""

    pressure: jax.Array
    displacement: jax.Array
    q: jax.Array
    active: jax.Array
    iterations: jax.Array
    residual: jax.Array
    result: jax.Array

    @property
    def converged(self):
        return self.result == _solve.SUCCESS


@dataclasses.dataclass(frozen=True)
class ContactOptions:
    """Static options of a contact solve.

    tol: relative residual (complementarity / peak pressure + relative force misfit).
    max_iter: active-set (semismooth Newton) iterations. krylov: iteration cap of each
    inner solve (preconditioned, they need about 5-10). krylov_tol: relative tolerance of the
    inner solves of the derivatives (tangent and adjoint). krylov_tol_step: that of the
    active-set steps: each step corrects the last iterate against the true residual
    (iterative refinement), so a looser inner solve costs no accuracy, only, rarely, a step.
    krylov_method: "bicgstab" (default, about 2x faster) or "gmres" (restarted, never
    breaks down: used when the operator is indefinite, e.g. a hole whose log-R reference
    length makes the rigid-body mode 1 compliance negative; see :func:`solve_with_fallback`).
    window: solve a contact set that spans at most an eighth of the ring on a window of a
    quarter of it (FFTs a quarter as long; same iterates): 2.7x faster inner solves for one
    short patch (a pin, Hertz); it costs compile time where it never applies, as on a roller
    bearing's rings with patches all round (the roller scene's default turns it off).
    """

    tol: float = 1e-10
    max_iter: int = 50
    krylov: int = 60
    krylov_tol: float = 1e-12
    krylov_tol_step: float = 1e-8
    krylov_method: str = "bicgstab"
    window: bool = True

    def __post_init__(self):
        checks.option_number("tol", self.tol)
        checks.option_number("krylov_tol", self.krylov_tol)
        checks.option_number("krylov_tol_step", self.krylov_tol_step)
        checks.option_count("max_iter", self.max_iter)
        checks.option_count("krylov", self.krylov)
        checks.one_of("krylov_method", self.krylov_method, ("bicgstab", "gmres"))
        if not isinstance(self.window, bool):
            raise ValueError(f"window must be True or False, got {self.window!r}")


def _transpose(op: RingOperator) -> RingOperator:
    """M^T: a circulant's transpose has the conjugate symbol."""
    return RingOperator(jnp.conj(op.symbol), op.n)


def _inverse(op: RingOperator) -> RingOperator:
    """Circulant inverse M^-1 (the preconditioner); mode symbols are never zero for a ring
    with non-zero compliance, except the incompressible disc's mode 0, guarded here."""
    s = op.symbol
    tiny = jnp.abs(s) <= 1e-12 * jnp.max(jnp.abs(s))
    return RingOperator(jnp.where(tiny, 0.0, 1.0 / jnp.where(tiny, 1.0, s)), op.n)


def _krylov_restricted(op, inv, active, rhs, opts):
    """Solve M_AA x_A = rhs_A (x = 0 off A) by preconditioned Krylov, for one or several
    right-hand sides (last axis). Returns the solutions and the largest relative residual."""
    krylov = _krylov.gmres if opts.krylov_method == "gmres" else _krylov.bicgstab

    def matvec(x):
        return jnp.where(active, op(jnp.where(active, x, 0.0)), x)

    def precond(x):
        return jnp.where(active, inv(jnp.where(active, x, 0.0)), x)

    def one(b):
        x, rel = krylov(matvec, jnp.where(active, b, 0.0), precond, opts.krylov_tol, opts.krylov)
        return jnp.where(active, x, 0.0), rel

    if rhs.ndim == 1:
        return one(rhs)
    x, rel = jax.vmap(one)(rhs)
    return x, jnp.max(rel)


# A contact arc of at most n/8 elements is solved on a window of n/4 elements of the ring
# instead of the whole ring; rings below _WINDOW_MIN_N always use the whole.
_WINDOW_FRACTION = 4
_WINDOW_MIN_N = 256


class _System(NamedTuple):
    """M, its circulant inverse (the preconditioner), and both on a window of the ring."""

    op: RingOperator
    inv: RingOperator
    window: tuple     # (M, M^-1) on n / _WINDOW_FRACTION elements, or () (off, or below _WINDOW_MIN_N)


def _window(op: RingOperator, size: int) -> RingOperator:
    """The size-periodic circulant with op's entries for offsets within +-size/2: on any run
    of at most size/2 elements it is op restricted to that run (a Toeplitz block), at the
    cost of FFTs of length size."""
    offsets = (np.arange(size) + size // 2) % size - size // 2
    return RingOperator(jnp.fft.rfft(op.kernel[offsets % op.n]), size)


def _system(op: RingOperator, window: bool) -> _System:
    inv = _inverse(op)
    size = op.n // _WINDOW_FRACTION
    return _System(op, inv, (_window(op, size), _window(inv, size)) if window and op.n >= _WINDOW_MIN_N else ())


def _transposed(system: _System) -> _System:
    return _System(*map(_transpose, system[:2]), tuple(map(_transpose, system.window)))


def _arc(active):
    """(start, length): the shortest circular run of elements holding every active one
    (length n + 1 when none is active)."""
    n = active.shape[0]
    idx = jnp.arange(n)
    first = jnp.argmax(active)
    pos = jnp.where(active, idx, n + first)
    # the next active element after each i, wrapping round to the first one
    nxt = jax.lax.cummin(jnp.concatenate([pos[1:], (n + first)[None]]), reverse=True)
    gap = jnp.where(active, nxt - idx - 1, -1)          # inactive elements following i
    i = jnp.argmax(gap)
    return nxt[i] % n, n - gap[i]


def _restricted_solve(system: _System, active, rhs, opts):
    """Solve M_AA x_A = rhs_A (x = 0 off A) for one or several right-hand sides (last axis N).

    M_AA and its preconditioner, the restriction of the circulant inverse, depend only on
    offsets within A: when A fits in half the window, the same Krylov iteration runs on the
    window, with FFTs a quarter as long (the thesis pin's arc is 7% of the ring: 2.7x faster
    at n = 4096). Returns the solutions and the largest relative residual."""
    whole = lambda system, active, rhs, start: _krylov_restricted(system.op, system.inv, active, rhs, opts)
    if not system.window:
        return whole(system, active, rhs, None)
    n = system.op.n
    start, length = _arc(active)

    def on_window(system, active, rhs, start):
        op_w, inv_w = system.window
        idx = (start + jnp.arange(op_w.n)) % n
        x, rel = _krylov_restricted(op_w, inv_w, active[idx], rhs[..., idx], opts)
        return jnp.zeros_like(rhs).at[..., idx].set(x), rel

    @jax.custom_batching.custom_vmap
    def solve(fits, *args):
        return jax.lax.cond(fits, on_window, whole, *args)

    @solve.def_vmap
    def solve_batch(axis_size, in_batched, fits, system, active, rhs, start):
        # Each member takes the path it would take alone, so its result does not depend on
        # the batch; a path runs only if some member needs it, and the other members give it
        # an empty set (a trivial solve). A batched lax.cond would run both for every member.
        sys_b, act_b, rhs_b, start_b = in_batched[1:]
        fits = jnp.broadcast_to(fits, (axis_size,))
        active = active if act_b else jnp.broadcast_to(active, (axis_size,) + active.shape)
        axes = jax.tree.map(lambda b: 0 if b else None, [sys_b, True, rhs_b, start_b])
        x_shape = (axis_size,) + (rhs.shape[1:] if rhs_b else rhs.shape)

        def path(solver, members):
            run = lambda: jax.vmap(solver, in_axes=axes)(system, active & members[:, None], rhs, start)
            skip = lambda: (jnp.zeros(x_shape, rhs.dtype), jnp.zeros(axis_size, rhs.dtype))
            return jax.lax.cond(jnp.any(members), run, skip)

        (x_w, rel_w), (x_f, rel_f) = path(on_window, fits), path(whole, ~fits)
        pick = lambda a, b: jnp.where(fits.reshape((-1,) + (1,) * (a.ndim - 1)), a, b)
        return (pick(x_w, x_f), pick(rel_w, rel_f)), (True, True)

    return solve(length <= system.window[0].n // 2, system, active, rhs, start)


def _bordered_solve(system, active, J, W, b_sigma, b_q, opts):
    """Solve  [A rows: M s - J q = b_s ; off A: s = b_s ; W s = b_q]  for (s, q).

    The inactive part is known; the active part is y0 + Y q with M_AA y0 and M_AA Y
    (k + 1 restricted solves), and q follows from the k x k system (W Y) q = ...
    Returns (s, q, largest relative Krylov residual).
    """
    s_off = jnp.where(active, 0.0, b_sigma)
    rhs0 = b_sigma - system.op(s_off)
    k = W.shape[0]
    if k == 0:
        y0, rel = _restricted_solve(system, active, rhs0, opts)
        return s_off + y0, jnp.zeros((0,), b_sigma.dtype), rel
    sols, rel = _restricted_solve(system, active, jnp.concatenate([rhs0[None], J.T], axis=0), opts)
    y0, Y = sols[0], sols[1:]            # Y: (k, N)
    q = jnp.linalg.solve(W @ Y.T, b_q - W @ s_off - W @ y0)
    return s_off + y0 + q @ Y, q, rel


def _bordered_transpose_solve(system, active, J, W, c_sigma, c_q, opts):
    """Solve the transposed bordered system K^T (lam, mu) = (c_sigma, c_q); see module docs."""
    systemT = _transposed(system)
    opT = systemT.op
    k = W.shape[0]
    if k == 0:
        lam_a, _ = _restricted_solve(systemT, active, c_sigma, opts)
        return jnp.where(active, lam_a, c_sigma - opT(lam_a)), jnp.zeros((0,), c_sigma.dtype)
    sols, _ = _restricted_solve(systemT, active, jnp.concatenate([c_sigma[None], W], axis=0), opts)
    z0, Z = sols[0], sols[1:]
    JA = jnp.where(active[:, None], J, 0.0)
    mu = jnp.linalg.solve(JA.T @ Z.T, c_q + JA.T @ z0)
    lam_a = z0 - mu @ Z
    lam_off = c_sigma - opT(lam_a) - W.T @ mu
    return jnp.where(active, lam_a, lam_off), mu


def _scale(op):
    """c = 1 / diagonal of M (Pa/m): makes sigma - c g dimensionally consistent."""
    return 1.0 / jnp.real(op.kernel[0])


def _no_force(sigma, u, args):
    return jnp.zeros((0,), sigma.dtype)


def _force_and_rows(force, op, args, sigma, u):
    """force(sigma, u, args) (k,) at u = M sigma, and its rows d force / d sigma (k, N) with
    u's dependence on sigma included: one reverse pass per row, one M^T for all of them."""
    f, pull = jax.vjp(lambda s, u_: force(s, u_, args), sigma, u)
    w_sigma, w_u = jax.vmap(pull)(jnp.eye(f.shape[0], dtype=f.dtype))
    return f, w_sigma + _transpose(op)(w_u)


def _solve_forward(op, interference, force, args, q0, F, opts, sigma_init):
    """Primal-dual active-set iteration with Newton on q: (sigma, q), (active set, Stats)."""
    step_opts = dataclasses.replace(opts, krylov_tol=opts.krylov_tol_step)
    system = _system(op, opts.window)
    c = _scale(op)
    k = q0.shape[0]
    d_of = lambda q: interference(q, args)
    jac_of = (lambda q: jax.jacfwd(d_of)(q)) if k else (lambda q: jnp.zeros(d_of(q).shape + (0,), q.dtype))
    tiny = jnp.finfo(q0.dtype).tiny
    # The residual cannot go below rounding: in float32 a 1e-10 tolerance would never be met.
    tol = max(opts.tol, 1e3 * float(jnp.finfo(q0.dtype).eps))

    def residual(sigma, q, u):
        g = u - d_of(q)
        comp = jnp.max(jnp.abs(jnp.minimum(sigma, c * g))) / jnp.maximum(jnp.max(sigma), tiny)
        misfit = jnp.max(jnp.abs(force(sigma, u, args) - F) / jnp.maximum(jnp.abs(F), tiny)) if k else 0.0
        return comp + misfit

    def active_set(sigma, q, u):
        d = d_of(q)
        act = sigma - c * (u - d) > 0
        if k:  # load control needs at least one contact point: take the deepest overlap
            act = jnp.where(jnp.any(act), act, d == jnp.max(d))
        return act

    def body(state):
        sigma, q, u, act, it, _, _ = state
        d, J = d_of(q), jac_of(q)
        # Newton step on the current set, solved as a correction of (sigma, q) so that the
        # inner solver's error does not set a floor on the residual (iterative refinement):
        # on A, M ds - J dq = d - u; off A, ds = -sigma; linearized force rows = F - force.
        r_sigma = jnp.where(act, d - u, -sigma)
        if k:
            f, W = _force_and_rows(force, op, args, sigma, u)
            r_q = F - f
        else:
            W, r_q = jnp.zeros((0, sigma.shape[0]), sigma.dtype), jnp.zeros((0,), sigma.dtype)
        ds, dq, inner = _bordered_solve(system, act, J, W, r_sigma, r_q, step_opts)
        sigma_new, q_new = sigma + ds, q + dq
        u_new = op(sigma_new)
        return (sigma_new, q_new, u_new, active_set(sigma_new, q_new, u_new), it + 1,
                residual(sigma_new, q_new, u_new), inner)

    def cond(state):
        # The residual certifies the solution by itself: a zero-pressure edge element that
        # still flips in or out of the set does not keep the loop going.
        *_, it, res, _ = state
        return (res > tol) & (it < opts.max_iter) & ~jnp.isnan(res)

    sigma0 = sigma_init.astype(q0.dtype)  # zeros for a cold start
    u0 = op(sigma0)
    inf = jnp.asarray(jnp.inf, q0.dtype)
    init = (sigma0, q0, u0, active_set(sigma0, q0, u0), jnp.asarray(0), inf, jnp.zeros((), q0.dtype))
    sigma, q, u, _, it, res, inner = jax.lax.while_loop(cond, body, init)
    # an inner solve that missed its tolerance by far explains an outer failure
    result = jnp.where(res <= tol, _solve.SUCCESS, jnp.where(
        ~jnp.isfinite(res), _solve.NONFINITE, jnp.where(
            inner > jnp.sqrt(opts.krylov_tol_step), _solve.INNER_FAILED, _solve.MAX_ITERATIONS)))
    # the active set of the derivative: the set of the converged solution
    return jnp.concatenate([sigma, q]), (active_set(sigma, q, u), _solve.Stats(it, res, result))


def _solve_implicit(op, interference, force, args, q0, F, opts, sigma_init):
    """The forward solve with implicit derivatives of (sigma, q) in (op, args, F)."""
    n, k = op.n, q0.shape[0]

    def residual(x, aux, params):
        """The optimality system on the frozen active set: zero at the solution."""
        op_, args_, F_ = params[:3]
        sigma, q = x[:n], x[n:]
        act = aux[0]
        r_s = jnp.where(act, op_(sigma) - interference(q, args_), sigma)
        return jnp.concatenate([r_s, force(sigma, op_(sigma), args_) - F_])

    def linear_solver(x, aux, params):
        op_, args_ = params[:2]
        sigma, q, act = x[:n], x[n:], aux[0]
        if k:
            J = jax.jacfwd(lambda qq: interference(qq, args_))(q)
            W = _force_and_rows(force, op_, args_, sigma, op_(sigma))[1]
        else:
            J, W = jnp.zeros((n, 0), sigma.dtype), jnp.zeros((0, n), sigma.dtype)
        system = _system(op_, opts.window)
        forward = lambda b: jnp.concatenate(_bordered_solve(system, act, J, W, b[:n], b[n:], opts)[:2])
        transpose = lambda b: jnp.concatenate(_bordered_transpose_solve(system, act, J, W, b[:n], b[n:], opts))
        return forward, transpose

    # The starting point travels with the parameters (the residual ignores it), so that
    # the custom derivative closes over no traced value; it gets no derivative.
    def solver(params):
        op_, args_, F_, q_start, s_start = params
        return _solve_forward(op_, interference, force, args_, q_start, F_, opts, s_start)

    start = jax.lax.stop_gradient((q0, sigma_init))
    x, (act, stats) = _solve.implicit_root(solver, residual, linear_solver)((op, args, F, *start))
    sigma, q = x[:n], x[n:]
    return ContactSolution(sigma, op(sigma), q, act, stats.iterations, stats.residual, stats.result)


def solve_contact(op: RingOperator, interference, args=None, q0=None, force=None, F=None,
                  options: ContactOptions = ContactOptions(), sigma_init=None) -> ContactSolution:
    """Frictionless contact of rigid indenters with a ring.

    Args:
      op: the ring's operator u = M sigma.
      interference: ``interference(q, args) -> d`` (N,), the overlap (m) of the rigid
        indenters with the undeformed ring, positive where they overlap. A pure,
        module-level function (hashable, so jit caches it); parameters that need
        derivatives go in ``args``.
      args: PyTree of parameters of ``interference`` and ``force`` (differentiable).
      q0: (k,) initial guess of the rigid-body unknowns under load control, or None for
        displacement control (k = 0).
      force: ``force(sigma, u, args) -> (k,)`` the resultants that load control imposes
        (any differentiable function of pressure and displacement, e.g. Eq. 2.21 with its
        slope terms). F: (k,) their target values.
      options: :class:`ContactOptions` (static).
      sigma_init: optional (N,) starting pressure (Pa), e.g. the solution of a nearby
        problem: a warm start needs fewer active-set iterations. Not differentiated.
        Default None: zero pressure (cold start).

    Returns a :class:`ContactSolution`; ``converged`` is False when the residual is above
    ``options.tol`` after ``options.max_iter`` iterations, and ``result`` says why (an inner
    Krylov solve that failed is reported as such). It never raises on non-convergence: the
    scenes decide (``throw=``).
    """
    checks.instance("op", op, RingOperator, "a vjax.RingOperator (see ring_operator)")
    checks.instance("options", options, ContactOptions, "a vjax.ContactOptions")
    if not callable(interference):
        raise ValueError(f"interference must be a function interference(q, args) -> (N,), got {interference!r}")
    if q0 is not None:
        if not callable(force):
            raise ValueError(f"load control (q0 given) needs a function force(sigma, u, args), got {force!r}")
        checks.finite("q0", q0)
        checks.finite("F", F)
    if sigma_init is not None:
        checks.finite("sigma_init", sigma_init)
        if jnp.shape(sigma_init) != (op.n,):
            raise ValueError(f"sigma_init must have shape ({op.n},), got {jnp.shape(sigma_init)}")
    if q0 is None:
        dtype = jnp.result_type(op.symbol.real.dtype)
        q0, F, force = jnp.zeros((0,), dtype), jnp.zeros((0,), dtype), _no_force
    else:
        q0 = jnp.atleast_1d(jnp.asarray(q0))
        F = jnp.atleast_1d(jnp.asarray(F, dtype=q0.dtype))
        if force is None or F.shape != q0.shape:
            raise ValueError(f"load control needs a force function and F of shape {q0.shape}, got "
                             f"force={force!r} and F of shape {F.shape}")
    # The overlap's shape (abstractly, also under jit) and, when concrete, its values: a
    # wrong-length or NaN interference would otherwise come back as a silent NaN pressure.
    d = jax.eval_shape(interference, q0, args)
    if getattr(d, "shape", None) != (op.n,):
        raise ValueError(f"interference(q, args) must return shape ({op.n},) (one overlap per element), "
                         f"got {getattr(d, 'shape', d)}")
    if checks.is_concrete((q0, args)):
        checks.finite("interference(q0, args)", interference(q0, args))
    sigma_init = jnp.zeros(op.n, q0.dtype) if sigma_init is None else jnp.asarray(sigma_init, q0.dtype)
    return _solve_implicit(op, interference, force, args, q0, F, options, sigma_init)


def solve_with_fallback(run, options: ContactOptions):
    """``run(options)`` and, if it did not converge with BiCGSTAB, once more with GMRES.

    BiCGSTAB can break down (NaN) on an indefinite operator. The retry happens only on
    concrete values (eager calls); under jit the first result is returned and its
    ``converged`` flag reports the failure. ``run`` returns a result with ``converged``.
    """
    result = run(options)
    if (options.krylov_method == "bicgstab" and is_concrete(result.converged)
            and not bool(np.all(np.asarray(result.converged)))):
        result = run(dataclasses.replace(options, krylov_method="gmres", krylov=max(options.krylov, 60)))
    return result
