"""Modal compliance of a bonded cylindrical layer in 3D elasticity (issue 27, item 3(b)).

A layer a <= r <= b of a linear elastic material (Young modulus E, Poisson ratio nu) is bonded
(u_r = u_theta = u_z = 0) on its far surface and loaded on the other by the normal pressure

    p(theta, z) = P cos(n theta) cos(k z)        (Pa, pushing into the body; no shear)

- ``"liner"``: loaded on its bore r = a = R, bonded at b = R + t (a bushing in a housing);
- ``"sleeve"``: loaded on its outer surface r = b = R, bonded at a = R - t (a sleeved shaft);
- ``"hole"``: the limit t -> infinity of the liner, a hole in an infinite body (below).

The radial displacement of the loaded surface, positive into the body, is

    u(theta, z) = c(n, k R, nu, t / R) (R / E) P cos(n theta) cos(k z),

c dimensionless, exactly the units and sign of the plane-strain layer compliance
:func:`vjax.bodies.green.mode_compliance` (``"liner"``, ``"sleeve"``), which is its k -> 0 limit. With
a constant Poisson ratio the viscoelastic layer is c / E*(omega) at each circumferential
mode's own frequency, as in 2D (correspondence principle).

Axial end condition
-------------------
The fields below have u_r, u_theta ~ cos(k z) and u_z, sigma_rz, sigma_thetaz ~ sin(k z): on the
planes z = 0 and z = L with k = j pi / L they satisfy u_z = 0 and zero shear. So each mode is
exact for a layer of length L whose ends slide on rigid, frictionless shoulders, and the
cosine series of the land's pressure, k_j = j pi / L, gives that layer's displacement
exactly (a land longer than the layer, or a layer overhanging the land, is not this case).

Solution
--------
Dimensionless: R = 1, E = 1, mu = 1 / (2 (1 + nu)). Every field is the sum of six
displacement solutions built from harmonic functions (Papkovich-Neuber form
2 mu u = 4 (1 - nu) B - grad(x . B + B_0) with harmonic B, B_0), with
H = Z_n(k r) cos(n theta) cos(k z), Z = I (growing) or K (decaying):

    (1) u = grad H                                            (B = 0, B_0 = -H)
    (2) u = -4 (1 - nu) dH/dz e_z - grad(r dH/dr)             (B = -dH/dz e_z; x.B + B_0 = r dH/dr)
    (3) u = 4 (1 - nu) B - grad(r B_r),  B = Z_(n+-1)(k r) cos(k z) (cos n theta e_r +- sin n theta e_theta)

(3) takes n + 1 with I and n - 1 with K (B_x +- i B_y = Z_(n+-1) e^(+-i (n+-1) theta) cos kz is
harmonic). This choice, rather than (1) and two Papkovich vectors of equal order, keeps the six
columns distinct as k -> 0: (1) and (2) tend to Michell's r^(n-1) (I) or r^(-n-1) (K) field
and, through u_z / k, to the antiplane r^(+-n); (3) to Michell's r^(n+1) (I) or r^(1-n) (K).
With amplitudes u_r = U(r) cos n theta cos kz, u_theta = V(r) sin n theta cos kz,
u_z = k w(r) cos n theta sin kz (so w stays finite as k -> 0), f = Z_n(k r) for (1), (2) and
g = Z_(n+-1)(k r) for (3) (f', f'' by r; f'' = -f'/r + (k^2 + n^2/r^2) f, Bessel's equation):

    (1) U = f',              V = -n f / r,        w = -f,                     div B = 0
    (2) U = -(f' + r f''),   V = n f',            w = 4 (1 - nu) f + r f',    div B = k^2 f
    (3) U = (3 - 4 nu) g - r g',  V = (n +- 4 (1 - nu)) g,  w = r g,          div B = g' + (1 +- n) g / r

and the tractions on a surface r = const (lambda div u = 4 mu nu div B for the Papkovich
solutions: finite for an incompressible layer)

    sigma_rr = 4 mu nu div B + 2 mu U',   sigma_r theta = mu (V' - (V + n U) / r),
    sigma_rz / k = mu (w' - U).

Boundary conditions, six per mode: sigma_rr = -P, sigma_r theta = 0, sigma_rz / k = 0 on the
loaded surface; U = V = w = 0 on the bonded one. One 6 x 6 solve per (n, k) (rows
equilibrated, Gaussian elimination with partial pivoting). n = 0 has no theta fields: the
theta rows then pin solution (2)'s coefficients to zero (the axisymmetric pair is (1), (3)).
k = 0 exactly is the plane-strain layer (:func:`vjax.bodies.green.mode_compliance`), the limit.

Hole in an infinite body
------------------------
``"hole"``: a cylindrical hole of radius R in an infinite body, loaded on its bore by the same
pressure (no shear), u = c(n, k R, nu) (R / E) P cos(n theta) cos(k z) into the body (units and
sign of :func:`vjax.bodies.green.mode_compliance` ``"hole"``). For k > 0 only the three decaying K
solutions (1), (2), (3) (K_n, K_n, K_(n-1)) stay finite at infinity; the three traction rows on
r = R (sigma_rr = -P, sigma_r theta = 0, sigma_rz / k = 0) give one 3 x 3 solve per (n, k)
(n = 0: the theta row pins solution (2), as for the layer). n >= 2 and n = 0 tend to the plane
hole as k -> 0 (O((kR)^2), with a log for n = 2); mode 1, a rigid translation in plane strain,
grows like -(1 + nu) kappa / (kappa + 1) log(k R) (kappa = 3 - 4 nu): the plane hole's
log R / ref_length coefficient with the reference length ~ 1/k (numerically, to 1e-10 at
nu = 0, 0.3, 0.45, 0.5: c(1, kR) -> the plane hole's with ref_length = 2 exp((kappa + 1) / (2 kappa)
- gamma_Euler) / k; an identification, not derived here). k = 0 exactly is the plane
hole (:func:`vjax.bodies.green.mode_compliance`, its mode 1 fixed by ``ref_length_ratio`` =
ref_length / R, as the thesis fixes it); large k R and n tend to the half-space
2 (1 - nu^2) / sqrt((k R)^2 + n^2).

Bessel functions without overflow: each column is scaled by its function's value on the
surface where it is largest (I on the outer radius, K on the inner one), so the ratios
Z_m(k r) / Z_m(k r_ref) <= 1 and the logarithmic derivatives are all that is needed.
I: ratios I_(m+1)/I_m by backward recurrence (Miller; the minimal solution of the
recurrence I_(m-1) - I_(m+1) = (2 m / x) I_m) from order max(n) + 2 + ``_MILLER_DEPTH``,
log I_0 from jax's i0e; K: K_0 e^x, K_1 e^x by the trapezoidal rule on
K_nu(x) e^x = int_0^inf exp(-2 x sinh^2(t/2)) cosh(nu t) dt (exponentially convergent), then
forward recurrence of K_(m-1)/K_m (stable: K is dominant). Checked against scipy's ive, kve
for x = k r from 1e-9 to 1e4 and orders 0 to 600 (1e-13); the recurrence depth is sized for
x <= 2500 from an arbitrary start, the uniform start estimate makes it converge further.
"""
from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from .green import LAYERS, _michell_modes, _solve_small, mode_compliance

KINDS = LAYERS + ("hole",)

X_MAX = 2.5e3          # k r for which the backward recurrence converges even from a crude start
_MILLER_DEPTH = int(np.ceil(np.sqrt(45.0 * X_MAX))) + 16   # extra orders: errors damp ~ exp(-D^2 / x)
_K_NODES = 128         # trapezoidal nodes of the K_0, K_1 integrals


# ------------------------------------------------------------------------------ Bessel helpers
def k01e(x):
    """(K_0(x) e^x, K_1(x) e^x) for x > 0: trapezoidal rule on the even, entire integrand of
    K_nu(x) e^x = int_0^inf exp(-2 x sinh^2(t/2)) cosh(nu t) dt. Step h = min(0.2, 0.7/sqrt(x)):
    the error ~ exp(-2 pi d / h) with d ~ 1.4 (small x) and ~ exp(-2 pi^2 / (x h^2)) (large x,
    a Gaussian of width 1/sqrt(x)), both below 1e-16; 128 nodes reach past the integrand's
    decay from x = 1e-9 on."""
    x = jnp.asarray(x)
    h = jnp.minimum(0.2, 0.7 / jnp.sqrt(x))
    t = h[..., None] * jnp.arange(_K_NODES, dtype=x.dtype)
    e = jnp.exp(-2.0 * x[..., None] * jnp.sinh(0.5 * t) ** 2)
    w = jnp.ones(_K_NODES, x.dtype).at[0].set(0.5)
    return h * jnp.sum(w * e, -1), h * jnp.sum(w * e * jnp.cosh(t), -1)


def i_table(x, m_max: int):
    """log I_m(x) and r_m = I_(m+1)(x) / I_m(x) for m = 0 .. m_max (two arrays (m_max + 1, *x.shape)),
    x > 0. r by backward recurrence r_(m-1) = 1 / (2 m / x + r_m) from order m_max + _MILLER_DEPTH
    (started from the uniform estimate x / (m + 1/2 + sqrt((m + 1/2)^2 + x^2))); log I_m by
    log I_0 = log i0e(x) + x and cumulative sums of log r."""
    x = jnp.asarray(x)
    top = m_max + _MILLER_DEPTH
    start = x / (top + 0.5 + jnp.sqrt((top + 0.5) ** 2 + x * x))

    def step(r, m):                                   # r = r_m -> r_(m-1)
        prev = 1.0 / (2.0 * m / x + r)
        return prev, prev
    orders = jnp.arange(top, 0, -1, dtype=x.dtype)   # m = top .. 1 gives r_(top-1) .. r_0
    _, rs = jax.lax.scan(step, start, orders)
    r = rs[::-1][: m_max + 1]                         # r_0 .. r_m_max
    log0 = jnp.log(jax.scipy.special.i0e(x)) + x
    logI = log0 + jnp.concatenate([jnp.zeros_like(x)[None], jnp.cumsum(jnp.log(r[:-1]), 0)], 0)
    return logI, r


def k_table(x, m_max: int):
    """log K_m(x) and q_m = K_(m-1)(x) / K_m(x) for m = 0 .. m_max (q_0 = K_1 / K_0, as
    K_(-1) = K_1), x > 0: K_0, K_1 from :func:`k01e`, then the forward recurrence
    q_(m+1) = 1 / (q_m + 2 m / x) (K dominant: stable) and log K_(m+1) = log K_m - log q_(m+1)."""
    x = jnp.asarray(x)
    k0, k1 = k01e(x)
    q1 = k0 / k1

    def step(q, m):                                   # q = q_m -> q_(m+1)
        nxt = 1.0 / (q + 2.0 * m / x)
        return nxt, nxt
    if m_max >= 2:
        _, qs = jax.lax.scan(step, q1, jnp.arange(1, m_max, dtype=x.dtype))
        q = jnp.concatenate([(1.0 / q1)[None], q1[None], qs], 0)
    else:
        q = jnp.stack([1.0 / q1, q1], 0)[: m_max + 1]
    logK1 = jnp.log(k1) - x
    tail = logK1 - jnp.cumsum(jnp.log(q[2:]), 0) if m_max >= 2 else jnp.zeros((0,) + x.shape, x.dtype)
    logK = jnp.concatenate([(jnp.log(k0) - x)[None], logK1[None], tail], 0)[: m_max + 1]
    return logK, q


# ------------------------------------------------------------------------------ the six fields
def _fields(family, n, k, r, nu, f, f1, order):
    """Rows [U, V, w, sigma_rr, sigma_r theta, sigma_rz / k] (E = 1) at radius r of solution
    ``family`` (1, 2, 3 of the module docstring; 3 with order n + 1 (I) or n - 1 (K), sign
    s = +1 / -1) from its radial function f = Z_order(k r) and f' = df/dr."""
    mu = 0.5 / (1.0 + nu)
    f2 = -f1 / r + (k * k + order * order / (r * r)) * f
    if family == 1:
        U, dU = f1, f2
        V, dV = -n * f / r, -n * (f1 / r - f / (r * r))
        w, dw = -f, -f1
        divB = jnp.zeros_like(f)
    elif family == 2:
        f3 = -f2 / r + f1 / (r * r) + (k * k + order * order / (r * r)) * f1 - 2.0 * order * order * f / r**3
        U, dU = -(f1 + r * f2), -(2.0 * f2 + r * f3)
        V, dV = n * f1, n * f2
        w, dw = 4.0 * (1.0 - nu) * f + r * f1, (5.0 - 4.0 * nu) * f1 + r * f2
        divB = k * k * f
    else:
        s = jnp.where(order > n, 1.0, -1.0)
        U, dU = (3.0 - 4.0 * nu) * f - r * f1, (2.0 - 4.0 * nu) * f1 - r * f2
        V, dV = (n + s * 4.0 * (1.0 - nu)) * f, (n + s * 4.0 * (1.0 - nu)) * f1
        w, dw = r * f, f + r * f1
        divB = f1 + (1.0 + s * n) * f / r
    srr = 4.0 * mu * nu * divB + 2.0 * mu * dU
    srt = mu * (dV - (V + n * U) / r)
    srz = mu * (dw - U)
    return jnp.stack([U, V, w, srr, srt, srz], -1)


def layer_modes(kind: str, n, kR, nu, thickness_ratio=None, n_max: int | None = None, ref_length_ratio=None):
    """Dimensionless 3D compliance c(n, k R) of a bonded layer or of a hole (module docstring),
    shape ``n.shape + kR.shape``.

    ``kind``: "liner" (loaded on its bore, bonded outside), "sleeve" (loaded outside, bonded on a
    core) or "hole" (in an infinite body); ``n``: circumferential orders (integers); ``kR``: axial
    wavenumber times the loaded radius R (>= 0; k = j pi / L for a layer between sliding
    shoulders); ``nu``: Poisson ratio (<= 0.5, 0.5 allowed); ``thickness_ratio``: a layer's t / R
    (a sleeve's below 1; not for a hole); ``ref_length_ratio``: a hole's ref_length / R, which
    fixes its mode 1 at k = 0 only (default 1). u = c (R / E) P into the body; k = 0 gives
    :func:`vjax.bodies.green.mode_compliance`'s plane-strain value. Differentiable in kR, nu and t/R.
    ``n_max``: a static bound on the orders (needed when ``n`` is traced; else max(n) rounded up to
    a power of two, so that calls share compiles)."""
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    if kind in LAYERS and thickness_ratio is None:
        raise ValueError(f"a {kind} needs thickness_ratio = t / R")
    if n_max is None:
        top = int(np.max(np.abs(np.asarray(n)))) if np.size(n) else 0
        n_max = max(16, 1 << int(np.ceil(np.log2(top + 1))))
    extra = 1.0 if ref_length_ratio is None else ref_length_ratio
    dtype = jnp.result_type(kR, nu, extra if thickness_ratio is None else thickness_ratio)
    dtype = dtype if jnp.issubdtype(dtype, jnp.floating) else jnp.result_type(float)
    n = jnp.asarray(n)
    out_shape = n.shape + jnp.shape(kR)
    m, kR = jnp.abs(n).reshape(-1).astype(jnp.int32), jnp.asarray(kR, dtype).reshape(-1)
    if kind == "hole":
        c = _hole_core(int(n_max), m, kR, jnp.asarray(nu, dtype), jnp.asarray(extra, dtype))
    else:
        c = _layer_core(int(n_max), m, kR, jnp.asarray(nu, dtype), jnp.asarray(thickness_ratio, dtype),
                        kind == "liner")
    return c.reshape(out_shape)


@partial(jax.jit, static_argnums=(0,))
def _hole_core(n_max, m, kR, nu, ref):
    """c (N, P) of the hole for orders m (N,) <= n_max and kR (P,): the three K solutions, each
    scaled by its value on the bore (f = 1, f' = k K_o'/K_o), and the three traction rows there;
    k = 0 exactly: the plane hole with ref_length / R = ``ref``."""
    dtype = kR.dtype
    zero_k = kR == 0
    k = jnp.where(zero_k, 1.0, kR)
    _, qK = k_table(k, n_max)                            # (n_max + 1, P)
    nf, kk = m.astype(dtype)[:, None], k[None, :]
    cols = []
    for family, o in zip((1, 2, 3), (m, m, jnp.abs(m - 1))):
        of = o.astype(dtype)[:, None]
        dlog = -kk * qK[o] - of                          # K_o'/K_o in r at r = 1
        cols.append(_fields(family, nf, kk, 1.0, nu, jnp.ones_like(dlog), dlog, of))
    fields = jnp.stack(cols, -1)                         # (N, P, 6, 3)
    eye = jnp.eye(3, dtype=dtype)
    A = fields[..., 3:, :]
    A = A.at[..., 1, :].set(jnp.where((m == 0)[:, None, None], eye[1], A[..., 1, :]))   # n = 0: pin (2)
    rhs = jnp.broadcast_to(-eye[0], A.shape[:-1])
    scale = jnp.max(jnp.abs(A), -1)
    coef = _solve_small(A / scale[..., None], rhs / scale)
    c3 = jnp.sum(fields[..., 0, :] * coef, -1)
    c2 = mode_compliance("hole", nf, nu, ref_length_ratio=ref)
    return jnp.where(zero_k[None, :], c2.astype(dtype), c3)


@partial(jax.jit, static_argnums=(0,))
def _layer_core(n_max, m, kR, nu, tau, liner):
    """c (N, P) for orders m (N,) <= n_max and kR (P,); ``liner`` a (traced) bool: liner and
    sleeve share one compiled program."""
    dtype = kR.dtype
    one = jnp.ones((), dtype)
    liner = jnp.asarray(liner)
    radii = (jnp.where(liner, one, one - tau), jnp.where(liner, one + tau, one))    # inner, outer
    zero_k = kR == 0
    k = jnp.where(zero_k, 1.0, kR)                      # k = 0 exactly: the plane-strain limit below
    x = k[:, None] * jnp.stack(radii)                   # (P, 2)
    logI, rI = i_table(x, n_max + 2)                    # (n_max + 3, P, 2)
    logK, qK = k_table(x, n_max + 1)
    nf = m.astype(dtype)[:, None]                       # (N, 1)
    kk = k[None, :]                                     # (1, P)

    # (log Z_o(k r_i), k Z_o'/Z_o) at radius index i for the orders o (N,), (N, P) each;
    # Z' = dZ/dx: I_o'/I_o = r_o + o/x, K_o'/K_o = -(q_o + o/x)
    def I_at(o, i):
        return logI[o, :, i], kk * rI[o, :, i] + o.astype(dtype)[:, None] / radii[i]

    def K_at(o, i):
        return logK[o, :, i], -kk * qK[o, :, i] - o.astype(dtype)[:, None] / radii[i]

    I_orders, K_orders = (m, m, m + 1), (m, m, jnp.abs(m - 1))

    def block(i):
        """The six solutions' field rows at radius index i, (N, P, 6, 6); the I functions scaled
        by their value on the outer surface (index 1), the K ones on the inner one (index 0)."""
        cols = []
        for at, orders, ref in ((I_at, I_orders, 1), (K_at, K_orders, 0)):
            for family, o in zip((1, 2, 3), orders):
                logz, dlog = at(o, i)
                f = jnp.exp(logz - at(o, ref)[0])
                cols.append(_fields(family, nf, kk, radii[i], nu, f, f * dlog, o.astype(dtype)[:, None]))
        return jnp.stack(cols, -1)

    inner, outer = block(0), block(1)
    loaded = jnp.where(liner, inner, outer)             # the liner is loaded on its bore
    bonded = jnp.where(liner, outer, inner)
    A = jnp.concatenate([loaded[..., 3:, :], bonded[..., :3, :]], -2)
    # n = 0: no theta fields; pin solution (2)'s two coefficients instead
    axisym = (m == 0)[:, None, None]
    eye = jnp.eye(6, dtype=dtype)
    A = A.at[..., 1, :].set(jnp.where(axisym, eye[1], A[..., 1, :]))
    A = A.at[..., 4, :].set(jnp.where(axisym, eye[4], A[..., 4, :]))
    rhs = jnp.broadcast_to(-eye[0], A.shape[:-1])
    scale = jnp.max(jnp.abs(A), -1)                     # row equilibration (stress and displacement rows)
    coef = _solve_small(A / scale[..., None], rhs / scale)
    u = jnp.sum(loaded[..., 0, :] * coef, -1)
    c3 = jnp.where(liner, u, -u)                        # into the body
    c2 = jnp.where(liner, _michell_modes("liner", nf, nu, tau), _michell_modes("sleeve", nf, nu, tau))
    return jnp.where(zero_k[None, :], c2.astype(dtype), c3)
