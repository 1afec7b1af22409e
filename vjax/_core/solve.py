"""The solver core every scene is built on (internal).

One of each:

- :class:`Stats`: the convergence record every solve returns (``iterations``, ``residual``,
  ``result`` code; ``converged`` is ``result == SUCCESS``). ``iterations`` always counts the
  steps of the solve's *outer* Newton-type iteration (active-set steps of a contact solve,
  Newton steps of a bearing's balance equations), never inner Krylov steps.
- :func:`report`: the one failure path. With ``throw=True`` a failed solve raises
  :class:`ConvergenceError` naming it, outside ``jit`` directly and inside ``jit`` from a host
  callback (JAX then re-raises it wrapped in its runtime error, with the same message). Under
  ``vmap`` one failed point raises for the whole batch. ``throw=False`` only returns the flag.
  Its hint names the physical cause and what the user can change, from the failed point's
  numbers if need be (a thermal runaway's temperatures).
- :func:`newton`: damped Newton with an Armijo backtracking line search.
- :func:`implicit_root`: derivatives of a root by the implicit function theorem (forward and
  reverse mode, dense or matrix-free linear solve at the root), never through iterations.
- :func:`bisect`: vectorized bisection of a bracketed root (the root searched upwards for its
  bracket, by secant steps: :func:`vjax._core.root.rising_root`).
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

from .checks import is_concrete

# Result codes (``Stats.result``). RUNAWAY: the iterate passed the bound of its search with no
# root below it (a heat balance's thermal runaway: the heat generated outgrowing the removed).
SUCCESS, MAX_ITERATIONS, STALLED, NONFINITE, INNER_FAILED, NONPHYSICAL, RUNAWAY = range(7)
MESSAGES = ("converged", "reached its iteration limit",
            "stalled (no decrease along the Newton step, or the residual stopped falling)",
            "produced non-finite values", "an inner solve failed",
            "converged to the non-physical branch",
            "ran past the bound of its search with no root below it (a runaway)")


class ConvergenceError(RuntimeError):
    """A solve did not reach its tolerance (see the message for which solve and why).

    ``solution``: the unconverged result (a scene's result record) when raised outside jit,
    to inspect without solving again with ``throw=False``; None when raised inside jit."""

    def __init__(self, message, solution=None):
        super().__init__(message)
        self.solution = solution


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Stats:
    """Convergence record: outer iterations, final residual (the solve's own scaled norm) and
    result code (0 = success, see :data:`MESSAGES`)."""

    iterations: jax.Array
    residual: jax.Array
    result: jax.Array

    @property
    def converged(self):
        return self.result == SUCCESS


def _fail_message(what, result, iterations, residual, values=None, hint=""):
    result, iterations, residual = (np.asarray(a) for a in (result, iterations, residual))
    bad = np.flatnonzero(result.ravel() != SUCCESS)
    if bad.size == 0:
        return None
    i = bad[0]
    where = f" at {bad.size} of {result.size} points (first: flat index {i})" if result.size > 1 else ""
    if callable(hint):
        point = {k: np.ravel(np.broadcast_to(np.asarray(v), result.shape))[i].item() for k, v in (values or {}).items()}
        hint = hint(int(result.ravel()[i]), **point)
    return (f"{what} did not converge{where}: {MESSAGES[int(result.ravel()[i])]} after "
            f"{int(np.ravel(iterations)[i])} iterations, residual {float(np.ravel(residual)[i]):.3e}. "
            f"The error's .solution holds the unconverged result (outside jit), as throw=False would; "
            f"or change the options.{hint}")


def _raise(what, result, iterations, residual, values=None, solution=None, hint=""):
    message = _fail_message(what, result, iterations, residual, values, hint)
    if message is not None:
        raise ConvergenceError(message, solution)


def report(what: str, stats: Stats, throw: bool, hint="", values=None) -> None:
    """Raise :class:`ConvergenceError` if ``stats`` failed and ``throw``; inside jit too.

    ``stats``: a :class:`Stats`, or a scene's result record with its three fields (the error's
    ``.solution`` outside jit). ``hint``: a closing sentence for the message (the cause, what
    else the user could do), or a function ``hint(result, **point) -> str`` of the first failed
    point's result code and ``values`` there: ``values`` a dict of arrays shaped as
    ``stats.result`` (or broadcasting to it), passed to the host inside jit too, so that the
    sentence can name the numbers the solve reached."""
    if not throw:
        return
    args = (stats.result, stats.iterations, stats.residual, {} if values is None else dict(values))
    if is_concrete(args):
        _raise(what, *args, solution=stats, hint=hint)
    else:
        # The host callback only on failure: run on every call it cost ~0.4 ms, more than
        # a whole pin solve at n = 512. (Under vmap the cond runs both branches, as before.)
        jax.lax.cond(jnp.any(stats.result != SUCCESS),
                     lambda a: jax.debug.callback(lambda *b: _raise(what, *b, hint=hint), *a), lambda a: None,
                     args)


def newton(fn, x0, state0, *, tol, max_iter, max_step=None, max_halvings=30, linear_solve=None,
           jacobian=None, keep_jacobian=True, return_jacobian=False, stall_window=None):
    """Damped Newton on ``fn(x, state) -> (r, state, valid)`` with an exact (``jacfwd``) Jacobian,
    or with ``linear_solve(x, state, r) -> dx`` solving J dx = -r (a matrix-free Krylov solve).

    ``state`` is carried from one accepted point to the next and not differentiated (e.g. the
    pressures that warm-start a nested contact solve); ``valid`` marks points the equations
    accept (finite film, converged inner solves). Each iteration takes the Newton step
    (scaled down so that ``|dx_i| <= max_step_i``) and halves it until the trial point is valid
    and 0.5|r|^2 decreased by the Armijo factor ``1 - 1e-4 lam``. Converged when
    ``max|r| <= tol`` at a valid point. Returns ``(x, state, Stats)``, and the last Jacobian
    used, ``(x, state, Stats, J)``, with ``return_jacobian`` or ``jacobian``.

    ``jacobian``: an (m, m) Jacobian of a nearby problem (the previous point of a
    continuation), for equations whose Jacobian costs many evaluations of ``fn`` (a tangent
    solve per column). Newton starts with it and keeps it while its steps shrink ``max|r|``
    at least fourfold with no line search, Broyden-updated after each step (cheap steps,
    superlinear near the root); otherwise it recomputes it at the current point. A step that
    fails with a kept Jacobian is retried with a fresh one, not reported as stalled. (Under
    ``vmap`` both branches of that choice run: continuation belongs in a loop or ``scan``.)
    ``keep_jacobian`` (a traced bool): False ignores ``jacobian`` and takes exact Newton steps
    throughout, so that a cold start and a warm one share one compiled program.

    ``stall_window``: stop as STALLED when ``max|r|`` has not halved in this many steps (a
    semismooth Newton caught on a complementarity kink takes tiny accepted steps for as long
    as it may; a caller with a fallback start wants it back early).
    """
    def fn_aux(x, state):
        out = fn(x, state)
        return out[0], out

    exact_jacobian = jax.jacfwd(fn_aux, has_aux=True)
    reuse = jacobian is not None
    carry = reuse or return_jacobian
    if carry and linear_solve is not None:
        raise ValueError("newton: jacobian= and return_jacobian= need the dense Jacobian, not a linear_solve")
    half_sq = lambda r: 0.5 * jnp.sum(r * r)
    r0, s0, v0 = fn(x0, state0)
    ok0 = jnp.all(jnp.isfinite(r0)) & v0
    done0 = ok0 & (jnp.max(jnp.abs(r0)) <= tol)
    result0 = jnp.where(done0, SUCCESS, jnp.where(ok0, MAX_ITERATIONS, NONFINITE))

    def cond(c):
        k, _, _, _, result = c[:5]
        return (result == MAX_ITERATIONS) & (k < max_iter)

    def body(c):
        k, x, r, state, _ = c[:5]
        keep = False
        if reuse:
            J, keep = c[5:]
            # only the Jacobian: r and state at x are those of the accepted point already
            J = jax.lax.cond(keep, lambda: J, lambda: exact_jacobian(x, state)[0])
            dx = jnp.linalg.solve(J, -r)
        elif linear_solve is None:
            J, (r, state, _) = exact_jacobian(x, state)
            dx = jnp.linalg.solve(J, -r)
        else:
            dx = linear_solve(x, state, r)
        if max_step is not None:
            ratio = jnp.max(jnp.abs(dx) / max_step)
            dx = dx / jnp.maximum(1.0, ratio)
        finite = jnp.all(jnp.isfinite(dx))
        dx = jnp.where(finite, dx, 0.0)
        m = half_sq(r)

        def trial(lam):
            rt, st, vt = fn(x + lam * dx, state)
            mt = half_sq(rt)
            return rt, st, vt & jnp.isfinite(mt) & (mt <= (1.0 - 1e-4 * lam) * m)

        def ls_cond(t):
            lam, _, _, ok, j = t
            return ~ok & (j < max_halvings)

        def ls_body(t):
            lam, *_, j = t
            lam = 0.5 * lam
            return (lam, *trial(lam), j + 1)

        # the full step is the loop's first turn (from lam = 2), not a call before it: one copy
        # of fn in the compiled line search instead of two (fn is most of a Newton's program)
        lam, rt, st, ok, _ = jax.lax.while_loop(ls_cond, ls_body,
                                                (jnp.asarray(2.0, r.dtype), r, state, jnp.asarray(False), -1))
        ok = ok & finite
        x_new = jnp.where(ok, x + lam * dx, x)
        r_new = jnp.where(ok, rt, r)
        state = jax.tree_util.tree_map(lambda a, b: jnp.where(ok, a, b), st, state)
        retry = ~ok & keep      # a failed step with a kept Jacobian is retried with a fresh one
        result = jnp.where(~finite & ~retry, NONFINITE, jnp.where(~ok & ~retry, STALLED, jnp.where(
            jnp.max(jnp.abs(r_new)) <= tol, SUCCESS, MAX_ITERATIONS)))
        out = (k + 1, x_new, r_new, state, result)
        if reuse:
            # Broyden's rank-one update makes the kept J exact along the step just taken
            s_ = lam * dx
            J = jnp.where(ok, J + jnp.outer(rt - r - J @ s_, s_) / jnp.maximum(s_ @ s_, jnp.finfo(r.dtype).tiny), J)
            reduced = jnp.max(jnp.abs(rt)) <= 0.25 * jnp.max(jnp.abs(r))
            out += (J, keep_jacobian & ok & (lam == 1.0) & reduced)
        elif carry:
            out += (J, jnp.asarray(False))
        return out

    def body_with_stall(c):
        out = body(c[:-2])
        best, k_best = c[-2:]
        norm = jnp.max(jnp.abs(out[2]))
        halved = norm <= 0.5 * best
        best, k_best = jnp.where(halved, norm, best), jnp.where(halved, out[0], k_best)
        result = jnp.where((out[4] == MAX_ITERATIONS) & (out[0] - k_best >= stall_window), STALLED, out[4])
        return out[:4] + (result,) + out[5:] + (best, k_best)

    init = (0, x0, r0, s0, result0)
    if carry:
        J0 = jnp.zeros((r0.shape[0], x0.shape[0]), r0.dtype) if jacobian is None else jnp.asarray(jacobian, r0.dtype)
        init += (J0, jnp.asarray(reuse) & keep_jacobian)
    if stall_window is not None:
        init += (jnp.max(jnp.abs(r0)), 0)
    k, x, r, state, result, *kept = jax.lax.while_loop(cond, body if stall_window is None else body_with_stall, init)
    residual = jnp.where(jnp.all(jnp.isfinite(r)), jnp.max(jnp.abs(r)), jnp.inf)
    stats = Stats(jnp.asarray(k), residual, result)
    return (x, state, stats, kept[0]) if carry else (x, state, stats)


def homotopy(solve, x0, schedule):
    """``solve(x, t) -> (x, Stats)`` at ``schedule[0]`` from x0; if that fails, again from x0
    through ``schedule[1:]`` in turn, each turn from the last one's solution (a turn that ends
    NONFINITE keeps its start). One loop with one solve in it: compiled once, t traced.
    Returns (x, Stats of the last turn with the iterations of all)."""
    schedule = jnp.asarray(schedule, x0.dtype)

    def cond(s):
        i, _, _, st = s
        return (i < schedule.shape[0]) & ~((i == 1) & st.converged)

    def body(s):
        i, x, its, _ = s
        x1, st = solve(jnp.where(i == 1, x0, x), schedule[i])
        return i + 1, jnp.where(st.result == NONFINITE, x, x1), its + st.iterations, st

    init = Stats(jnp.asarray(0), jnp.asarray(jnp.inf, x0.dtype), jnp.asarray(MAX_ITERATIONS))
    _, x, its, st = jax.lax.while_loop(cond, body, (jnp.asarray(0), x0, jnp.asarray(0), init))
    return x, Stats(its, st.residual, st.result)


def in_turn(solve, x0, schedule):
    """``solve(x, t) -> (x, Stats)`` at each t of ``schedule`` in turn, each from the last
    one's solution (the first from x0), stopping at the first that fails. One loop with one
    solve in it: compiled once, t traced. Returns (x, Stats of the last turn with the
    iterations of all)."""
    schedule = jnp.asarray(schedule, x0.dtype)

    def cond(s):
        i, _, _, st = s
        return (i < schedule.shape[0]) & ((i == 0) | st.converged)

    def body(s):
        i, x, its, _ = s
        x1, st = solve(x, schedule[i])
        return i + 1, x1, its + st.iterations, st

    init = Stats(jnp.asarray(0), jnp.asarray(jnp.inf, x0.dtype), jnp.asarray(MAX_ITERATIONS))
    _, x, its, st = jax.lax.while_loop(cond, body, (jnp.asarray(0), x0, jnp.asarray(0), init))
    return x, Stats(its, st.residual, st.result)


def continuation(solve, guess, x0=None, max_stages=40, end=2.0):
    """Adaptive continuation in a parameter t from 0 to ``end``: ``solve(x, t) -> (x, Stats)``,
    the first stage (t = 0) from ``guess``, each later one from the last converged solution; a
    failed stage halves the step, a converged one lets it grow by 1.5 (to at most end / 4). At
    most ``max_stages`` solves. With ``x0``, a direct solve of the target (t = end) from x0 comes
    first and the continuation runs only if it fails; its steps count in the iterations, not in
    the stages. One loop with one solve in it (compiled once, t traced).
    Returns (x, Stats, number of stages); a run that does not reach t = end reports its last
    stage's failure, or MAX_ITERATIONS if that stage converged."""
    dtype = guess.dtype
    DIRECT, FIRST, STEP = 0, 1, 2     # phases: the direct solve, the first stage (t = 0), later stages

    def cond(s):
        phase, t, dt, _, _, nst, _, dead = s
        return (t < end) & (nst < max_stages) & (dt > 5e-4 * end) & ~dead

    def body(s):
        phase, t, dt, x, its, nst, _, _ = s
        t1 = jnp.where(phase == DIRECT, end, jnp.where(phase == FIRST, 0.0, jnp.minimum(t + dt, end)))
        x1, st = solve(jnp.where(phase == FIRST, guess, x), t1)
        ok = st.converged
        grown = jnp.where(phase == STEP, jnp.minimum(1.5 * dt, 0.25 * end), dt)
        return (jnp.where(phase == DIRECT, FIRST, STEP), jnp.where(ok, t1, t),
                jnp.where(ok, grown, jnp.where(phase == STEP, 0.5 * dt, dt)), jnp.where(ok, x1, x),
                its + st.iterations, nst + (phase != DIRECT), st,
                ~ok & (phase == FIRST))       # the easiest stage failed: nothing to continue from

    zero = jnp.asarray(0)
    stats0 = Stats(zero, jnp.asarray(jnp.inf, dtype), jnp.asarray(MAX_ITERATIONS))
    init = (jnp.asarray(FIRST if x0 is None else DIRECT), jnp.asarray(0.0, dtype), jnp.asarray(end / 8, dtype),
            guess if x0 is None else x0, zero, zero, stats0, jnp.asarray(False))
    _, t, _, x, its, nst, stats, _ = jax.lax.while_loop(cond, body, init)
    result = jnp.where(t >= end, stats.result, jnp.where(stats.converged, MAX_ITERATIONS, stats.result))
    return x, Stats(its, stats.residual, result), nst


def _zero_tangent(x):
    x = jnp.asarray(x)
    if jnp.issubdtype(x.dtype, jnp.inexact):
        return jnp.zeros_like(x)
    return np.zeros(x.shape, dtype=jax.dtypes.float0)


def implicit_root(solver, residual, linear_solver=None):
    """Wrap ``solver(params) -> (x, aux)`` so that ``x`` is differentiated implicitly.

    At the returned root of ``residual(x, aux, params) = 0`` (``x`` 1-D; ``aux`` anything the
    solver found that the residual needs frozen, such as an active set, plus statistics),

        dx = -J^{-1} (d residual / d params) dparams,    J = d residual / d x.

    The linear solve at the root is ``lax.custom_linear_solve``, so forward mode (``jvp``,
    ``jacfwd``) and reverse mode (``grad``, ``vjp``: one transposed solve) both work.
    ``linear_solver=None`` factors a dense ``J`` from ``jacfwd`` (systems of up to a few
    thousand unknowns); otherwise ``linear_solver(x, aux, params)`` returns matrix-free
    ``(solve, transpose_solve)``, each ``b -> J^{-1} b`` resp. ``J^{-T} b``. ``aux`` gets zero
    tangents. Nothing is differentiated through the iterations; at an unconverged point the
    derivative is that of the linearization there (meaningful only when converged).
    ``params`` is a PyTree of arrays; pass static configuration by closure.
    """

    @jax.custom_jvp
    def solve(params):
        return solver(params)

    def rebound(params):
        # vmap over a numpy array closed over by a jitted function hands BatchTracers holding
        # that numpy array, which custom_jvp refuses ("non-canonical constant"): one add each
        # makes their values JAX arrays
        return jax.tree_util.tree_map(
            lambda a: a + jnp.zeros((), a.dtype) if isinstance(a, jax.core.Tracer) and jnp.issubdtype(a.dtype, jnp.inexact)
            else a, params)

    @solve.defjvp
    def _jvp(primals, tangents):
        (params,), (dparams,) = primals, tangents
        x, aux = solve(params)
        at_root = lambda xx: residual(xx, aux, params)
        _, dr = jax.jvp(lambda p: residual(x, aux, p), (params,), (dparams,))
        matvec = lambda v: jax.jvp(at_root, (x,), (v,))[1]
        if linear_solver is None:
            lu = jax.scipy.linalg.lu_factor(jax.jacfwd(at_root)(x))
            forward = lambda b: jax.scipy.linalg.lu_solve(lu, b)
            transpose = lambda b: jax.scipy.linalg.lu_solve(lu, b, trans=1)
        else:
            forward, transpose = linear_solver(x, aux, params)
        dx = jax.lax.custom_linear_solve(matvec, -dr, lambda _, b: forward(b), lambda _, b: transpose(b))
        return (x, aux), (dx, jax.tree_util.tree_map(_zero_tangent, aux))

    return lambda params: solve(rebound(params))


def bisect(fn, lo, hi, iterations: int, sign_lo=None):
    """Roots of ``fn`` (element-wise) bracketed by ``lo`` and ``hi``; ``iterations`` halvings.

    ``fn(lo)`` and ``fn(hi)`` must have opposite signs element-wise; give ``sign_lo`` (+1 or
    -1) when ``fn`` cannot be evaluated at ``lo`` (a pole). ``fn`` is evaluated at midpoints
    only otherwise. No derivative flows through it (wrap it in :func:`implicit_root`).
    """
    sign_lo = jnp.sign(fn(lo)) if sign_lo is None else sign_lo

    def halve(_, bounds):
        a, b = bounds
        mid = 0.5 * (a + b)
        same = jnp.sign(fn(mid)) == sign_lo
        return jnp.where(same, mid, a), jnp.where(same, b, mid)

    a, b = jax.lax.fori_loop(0, iterations, halve, (lo, hi))
    return 0.5 * (a + b)
