"""The objective and the fit: :func:`evaluate`, :func:`residual_jacobian`, :func:`fit_torque`
(Adam, then Levenberg-Marquardt; :mod:`fitting.torque`), the identifiability report."""
from __future__ import annotations

import dataclasses
import math
import sys
import time

import jax
import jax.numpy as jnp
import numpy as np

from vjax import Material, WLF
from fitting.shared import optim
from .data import TorqueData
from .models import pin_model, roller_model
from .params import EXTRAS, Params


def evaluate(model, material, shift, rpm, T, load, extras=None):
    """(torque, converged) of ``model`` at the points (arrays rpm, T, load), with the scene
    keywords ``extras`` (dict, e.g. mu_b, sigma, hA; the same at every point): batched by vmap,
    or one point after the other when ``model.sequential`` (the journal: its solve's fallbacks,
    restarts and continuation, are branches, which vmap turns into selects that run every
    branch for every point)."""
    extras = extras or {}
    # jax arrays: a numpy array closed over by a jitted caller and vmapped into the thermal
    # scenes' implicit root fails as a non-canonical constant
    rpm, T, load = (jnp.asarray(a) for a in (rpm, T, load))
    point = lambda a, b, c: model(material, shift, a, b, c, **extras)     # noqa: E731
    if getattr(model, "sequential", False):
        return jax.lax.map(lambda p: point(*p), (rpm, T, load))
    return jax.vmap(point)(rpm, T, load)


def _residual_fn(params: Params, model, data: TorqueData, rel_scatter, dma_table, w_dma, s_dma):
    unknown = [e for e in params.extras if e not in getattr(model, "extras", ())]
    if unknown:
        raise ValueError(f"extras: the model ({getattr(model, 'scene', model)}) takes no {unknown}; it takes "
                         f"{list(getattr(model, 'extras', ())) or 'none'} (a roughness= gives mu_b and sigma, a "
                         f"heat_transfer= gives hA)")
    rpm, T, load = (jnp.asarray(a) for a in (data.rpm, data.T, data.load))
    meas = jnp.asarray(data.torque)
    sig = jnp.asarray(data.sigma(rel_scatter))
    if dma_table is not None and w_dma > 0:
        from fitting.calibration.prony import log_residual
    else:
        dma_table = None

    def residuals(x):
        mat, shift = params.unpack(x)
        tq, ok = evaluate(model, mat, shift, rpm, T, load, params.unpack_extras(x))
        r_t = (tq - meas) / sig
        if dma_table is not None:
            r_d = math.sqrt(w_dma) * log_residual(mat, shift, dma_table) / s_dma
            r = jnp.concatenate([r_t, r_d])
        else:
            r = r_t
        return r, (r_t, tq, ok)

    return residuals


def residual_jacobian(params: Params, model, data: TorqueData, rel_scatter=0.05, dma_table=None, w_dma=0.0,
                      s_dma=0.02):
    """Compiled ``x -> (J, (r, r_torque, torque_model, converged))``: the stacked weighted
    residuals r (torque, then sqrt(w_dma) DMA) and their Jacobian J = dr/dx (forward mode)."""
    res = _residual_fn(params, model, data, rel_scatter, dma_table, w_dma, s_dma)

    def with_aux(x):
        r, aux = res(x)
        return r, (r,) + aux

    return jax.jit(jax.jacfwd(with_aux, has_aux=True)), jax.jit(lambda x: res(x)[0])


def gauss_newton_cov(J, rcond=1e-8):
    """Gauss-Newton covariance (J^T J)^-1 of the log-parameters from the Jacobian of
    noise-scaled residuals, by SVD: directions with s < rcond s_max are dropped, and a
    parameter with more than 1% of its weight in dropped directions gets sd = inf (it is not
    determined; a plain pseudo-inverse would report a misleadingly small sd). Returns
    (cov, sd)."""
    cov, sd, resolved = optim.covariance(J, rcond)
    return cov, np.where(resolved < 0.99, np.inf, sd)


def identifiability(J_torque, names, threshold=0.1, rcond=1e-10):
    """Which log-parameters the torque data identify, from the Jacobian of the noise-scaled
    torque residuals (rows: points, columns: log-parameters).

    Returns a dict: ``singular_values`` (descending), ``sd`` (Gauss-Newton standard deviation
    of each log-parameter from the torque alone, sqrt diag pinv(J^T J); a relative error),
    ``identifiable`` (sd < ``threshold``, i.e. determined to better than ~10%),
    ``identified_directions`` (singular directions with 1/s < threshold, i.e. combinations
    of parameters the data fix to better than ~10%, with their three largest components)
    with ``identified_basis`` their unit vectors (rows), and ``weakest`` (the three least
    determined directions).
    """
    J = np.asarray(J_torque, float)
    _, s, Vt = np.linalg.svd(J, full_matrices=False)
    _, sd, resolved = optim.covariance(J, rcond)
    # a parameter with no projection on the retained directions is not identified at all
    sd = np.where(resolved < 0.5, np.inf, sd)
    def describe(i):
        v = Vt[i]
        top = np.argsort(-np.abs(v))[:3]
        return {"singular_value": float(s[i]), "direction": {names[j]: round(float(v[j]), 3) for j in top}}

    # a direction v (unit, in log-parameters) is determined to sd 1/s: identified if 1/s < threshold
    strong = [describe(i) for i in range(len(s)) if s[i] > 1.0 / threshold]
    basis = Vt[s > 1.0 / threshold]
    weak = [describe(i) for i in np.argsort(s)[: min(3, len(s))]]
    return {"singular_values": s.tolist(), "sd": dict(zip(names, sd.tolist())),
            "identifiable": [n for n, d in zip(names, sd) if d < threshold],
            "not_identifiable": [n for n, d in zip(names, sd) if not d < threshold],
            "identified_directions": strong, "identified_basis": basis.tolist(), "weakest": weak}


@dataclasses.dataclass
class TorqueFit:
    """Result of :func:`fit_torque`.

    material, shift: refined (checked) material and WLF law. x0, x: log-parameters before
    and after; names: their names. history: per iteration (iteration, loss, grad norm,
    seconds). iterations, wall_time (s), compile_time (s). loss0, loss. torque0, torque:
    model torque at the data points before/after. converged: all scene solves converged at
    the final point. cov: Gauss-Newton covariance of x (torque + DMA terms). sd: its
    standard deviations (relative errors of the parameters). ident: :func:`identifiability`
    of the torque term alone at the final point. extras: the fitted scene parameters (dict,
    e.g. mu_b, sigma in m, hA in W/K).
    """

    material: Material
    shift: WLF
    params: Params
    names: list
    x0: np.ndarray
    x: np.ndarray
    history: list
    iterations: int
    wall_time: float
    compile_time: float
    loss0: float
    loss: float
    torque0: np.ndarray
    torque: np.ndarray
    converged: bool
    cov: np.ndarray
    sd: np.ndarray
    ident: dict
    extras: dict = dataclasses.field(default_factory=dict)

    def table(self, truth=None):
        """Rows (name, before, after, sd_rel, [truth, err_before, err_after]) with values in
        SI units and relative errors."""
        v0, v1 = np.exp(self.x0), np.exp(self.x)
        rows = []
        for i, n in enumerate(self.names):
            row = [n, float(v0[i]), float(v1[i]), float(self.sd[i])]
            if truth is not None:
                t = float(np.exp(truth[i]))
                row += [t, float(v0[i] / t - 1.0), float(v1[i] / t - 1.0)]
            rows.append(row)
        return rows


def fit_torque(data: TorqueData, material: Material, shift: WLF, model, *, dma_table=None, w_dma=1.0,
               s_dma=0.02, rel_scatter=0.05, fit_times=False, extras=None, steps=100, lr=0.05, lr_end=0.005,
               gtol=1e-6, polish=20, progress=True, every=5, log=None) -> TorqueFit:
    """Refine ``material`` and its WLF ``shift`` against the torque ``data`` (see module docs).

    Args:
      data: :class:`TorqueData`. material, shift: the start (a Prony material, WLF law).
      model: ``model(material, shift, rpm, T, load) -> (torque, converged)``, e.g.
        :func:`roller_model` or :func:`pin_model`.
      dma_table: optional :class:`fitting.measurements.dma.DMATable` for the consistency term, weight
        ``w_dma``, scatter ``s_dma`` (decades of log10 modulus).
      rel_scatter: torque scatter relative to the torque when the data have none.
      fit_times: also refine the relaxation times (the torque rarely identifies them).
      extras: scene parameters fitted with the material, a dict of start values (> 0) by name
        (:data:`EXTRAS`: ``mu_b`` and ``sigma`` (m) of a journal model with a roughness, ``hA``
        of a model with a heat transfer); None or {}: the material alone.
      steps: Adam iterations.
      lr: Adam's learning rate at the start (log units), cosine-decayed to
      lr_end: at the end.
      gtol: stop when the gradient norm falls below it.
      polish: at most this many Levenberg-Marquardt iterations after Adam (0: none).
      progress: print (iteration, loss, gradient norm) every ``every`` iterations to
        ``log`` (stderr).
    """
    import optax

    log = log or sys.stderr
    extras = dict(extras or {})
    params = Params.of(material, shift, fit_times, tuple(extras))
    names = params.names()
    x0 = params.pack(material, shift, extras)
    jac_fn, _ = residual_jacobian(params, model, data, rel_scatter, dma_table, w_dma, s_dma)
    Nt = len(data)
    t0 = time.perf_counter()
    J, aux = jac_fn(jnp.asarray(x0))
    jax.block_until_ready(J)
    compile_time = time.perf_counter() - t0
    r, r_t, tq0, ok = aux
    loss0 = float(jnp.sum(r ** 2) / Nt)
    sched = optax.cosine_decay_schedule(lr, max(steps, 1), alpha=lr_end / lr)
    opt = optax.adam(sched)
    x = jnp.asarray(x0)
    state = opt.init(x)
    history = []
    t_start = time.perf_counter()

    def loss_grad(J, aux):
        r = aux[0]
        return float(jnp.sum(r ** 2) / Nt), 2.0 * (J.T @ r) / Nt

    def usable(loss, aux):           # finite, and every bearing solve converged
        return np.isfinite(loss) and bool(np.all(np.asarray(aux[3])))

    if not usable(loss0, aux):
        raise ValueError(f"the bearing solves do not converge at the start material ({getattr(model, 'scene', '')})"
                         "; check the geometry, loads and material")
    best = (loss0, x, J, aux)
    for it in range(steps + 1):
        loss, g = loss_grad(J, aux)
        gn = float(jnp.linalg.norm(g))
        history.append((it, loss, gn, time.perf_counter() - t_start))
        if usable(loss, aux) and loss < best[0]:
            best = (loss, x, J, aux)
        if progress and (it % every == 0 or it == steps):
            print(f"  iter {it:4d}  loss {loss:.6g}  |grad| {gn:.3e}  {time.perf_counter() - t_start:7.1f} s",
                  file=log, flush=True)
        if it == steps or not np.isfinite(loss) or gn < gtol:
            break
        upd, state = opt.update(g, state, x)
        x = optax.apply_updates(x, upd)
        J, aux = jac_fn(x)
    loss, x, J, aux = best
    # Levenberg-Marquardt from Adam's best point, on the Jacobian Adam already uses: Adam
    # crawls once the loss is a narrow valley; Gauss-Newton steps reach the noise floor.
    # The steps and damping of fitting.shared.optim's Levenberg-Marquardt, driven from here
    # (fitting.shared.optim.levenberg_marquardt_host: each trial is a set of bearing solves,
    # reported, and kept only if they all converged).
    lm_log = []

    def resid_jac(x_try):
        J_try, aux_try = jac_fn(jnp.asarray(x_try))
        return np.asarray(aux_try[0], float), np.asarray(J_try, float), (J_try, aux_try)

    def accepted(k, cost, x_new, extra):
        loss_new, g_new = loss_grad(*extra)
        lm_log.append((it + k, loss_new, float(jnp.linalg.norm(g_new)), time.perf_counter() - t_start))
        if progress:
            print(f"  LM   {it + k:4d}  loss {loss_new:.6g}  {time.perf_counter() - t_start:7.1f} s",
                  file=log, flush=True)

    if polish > 0 and float(jnp.linalg.norm(2.0 * (J.T @ aux[0]) / Nt)) >= gtol:
        xl, _, _, (J, aux), _, k, _ = optim.levenberg_marquardt_host(
            resid_jac, np.asarray(x), max_iter=polish, ftol=1e-6, floor=1e-4, on_accept=accepted,
            usable=lambda extra: usable(loss_grad(*extra)[0], extra[1]),
            start=(np.asarray(aux[0], float), np.asarray(J, float), (J, aux)))   # Adam's best: no solve again
        x, loss, it = jnp.asarray(xl), float(jnp.sum(aux[0] ** 2) / Nt), it + k
        history += lm_log
    r, r_t, tq, ok = aux
    if progress:
        print(f"  best  loss {loss:.6g} (start {loss0:.6g}) after {it} iterations, "
              f"{time.perf_counter() - t_start:.1f} s", file=log, flush=True)
    wall = time.perf_counter() - t0
    Jn = np.asarray(J, float)
    cov, sd = gauss_newton_cov(Jn)
    ident = identifiability(Jn[:Nt], names)
    mat, sh = params.physical(np.asarray(x))
    return TorqueFit(mat, sh, params, names, np.asarray(x0), np.asarray(x), history, it, wall, compile_time,
                     loss0, loss, np.asarray(tq0), np.asarray(tq), bool(np.all(np.asarray(ok))), cov, sd, ident,
                     params.physical_extras(np.asarray(x)))


def gradient_check(params: Params, model, data: TorqueData, x, *, rel_scatter=0.05, dma_table=None, w_dma=0.0,
                   s_dma=0.02, h=1e-4, coords=None, seed=0):
    """Loss gradient (from the implicit-derivative Jacobian) versus central finite
    differences of the loss, for a few coordinates and one random direction.
    Returns rows (what, analytic, finite difference, relative error)."""
    jac_fn, val_fn = residual_jacobian(params, model, data, rel_scatter, dma_table, w_dma, s_dma)
    Nt = len(data)
    x = jnp.asarray(x)
    J, aux = jac_fn(x)
    g = 2.0 * (J.T @ aux[0]) / Nt
    loss = lambda y: float(jnp.sum(val_fn(y) ** 2) / Nt)
    names = params.names()
    coords = list(range(len(names))) if coords is None else coords
    dirs = [(names[i], np.eye(len(names))[i]) for i in coords]
    v = np.random.default_rng(seed).normal(size=len(names))
    dirs.append(("random direction", v / np.linalg.norm(v)))
    rows = []
    for what, d in dirs:
        d = jnp.asarray(d)
        fd = (loss(x + h * d) - loss(x - h * d)) / (2 * h)
        an = float(g @ d)
        rows.append((what, an, fd, abs(an - fd) / max(abs(fd), abs(an), 1e-300)))
    return rows
