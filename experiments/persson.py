"""Analytical solution of a rigid pin in a clearance hole in an incompressible elastic plane.

The reference solution of thesis Figs. 2.5-2.6 is its Ref. [34]: A. Persson, "On the stress
distribution of cylindrical elastic bodies in contact", PhD thesis, Chalmers, Goteborg,
1964. The same problem is treated in K. L. Johnson, *Contact Mechanics*, CUP 1985, Ch. 5
(conforming contact, pin in a hole), and by M. Ciavarella & P. Decuzzi, "The state of
stress induced by the plane frictionless cylindrical contact", parts I (elastic
similarity) and II (general case), Int. J. Solids Struct. 38 (2001). These bibliographic
details are quoted from memory: none of the texts was available here to check pages or
equation numbers. Persson treats a pin and a plate of the same material. Here the pin is
rigid and the plate incompressible (nu = 1/2, plane strain). Dundurs' beta is then 0, as
for elastic similarity, so the normal problem again reduces to one Cauchy equation on the
arc. The n = 0 (hole-widening) mode differs from Persson's elastically similar pair, so
his numbers do not carry over unchanged. The closed form below is **derived here** by
Persson's route (the tan(theta/2) map to a finite-interval Cauchy equation). It is
verified independently, not against a printed formula: a Gauss-Chebyshev solution of the
same integral equation agrees to 1e-13 (``tests/test_pin_persson.py``), and so does the
Hertz limit at small loads.

Derivation (all in plane strain, nu = 1/2, kappa = 1, E the Young's modulus of the plane):

1. Hole kernel (vjax.green, thesis A.39): u(theta) = (R/E) int G(theta - phi) p(phi) dphi
   with G = (1+nu)/(2 pi) [c cos - 2 log|2 sin(theta/2)| cos]. Its Fourier compliance is
   (1+nu) n/(n^2-1) R/E for n >= 2 and (1+nu) R/E for n = 0; n = 1 is a rigid translation
   (c depends on the log-R reference length) and is absorbed by the pin offset e.
2. On the contact arc |theta| < alpha the rigid pin imposes u = e cos(theta) - dR (small
   offset, e << R). Apply (d^2/dtheta^2 + 1): it removes e and mode 1 and turns the
   symbol n/(n^2-1) into -n, i.e. minus the derivative of a Hilbert transform. The mode-1
   part of p, F cos(theta)/(pi R), reappears because the hole operator annihilates it
   while (H p)' does not, and the n = 0 part because (H p)' annihilates it:
       (H p)'(theta) = K + P0/(2 pi) + F/(pi R) cos(theta),   K = E dR / ((1+nu) R),
   with (H p)(theta) = (1/2pi) PV int cot((theta-phi)/2) p(phi) dphi, P0 = int p dtheta,
   F = R int p cos(theta) dtheta (the load). Integrated once (p even):
       H p = (K + P0/2pi) theta + (F/(pi R)) sin(theta).
3. t = tan(theta/2), s = tan(phi/2), b = tan(alpha/2), q(s) = p/(1+s^2):
   cot((theta-phi)/2) becomes (1+t^2)/(t-s) - t, and the equation becomes the finite-interval Cauchy equation
       (1/pi) PV int_{-b}^{b} q(s)/(t-s) ds = f(t)
       f = [2 (K + P0/2pi) arctan t + (2F/(pi R)) t/(1+t^2) + (P0/2pi) t] / (1+t^2).
4. f is odd, so the solution bounded at both ends exists for every b (smooth contact
   edges, as in Hertz). With w = sqrt(b^2-t^2) it is q = (w/pi) PV int f(s)/(w(s)(s-t)) ds.
   For f = s/(s^2+g^2) this is w g/(sqrt(g^2+b^2)(t^2+g^2)); writing
   arctan(s) = int_0^1 s/(1+l^2 s^2) dl and integrating over l in closed form gives,
   with S = sqrt(1+b^2) and cos^2(theta/2) = 1/(1+t^2):

       p(theta) = (2K + P0/pi) gK + (P0/2pi) gC + (2F/(pi R)) gB,
       gK = artanh(w/S) - w ln(S)/S,
       gC = w/S,
       gB = (w/S) (cos^2(theta/2) - b^2/(2 S^2)).

5. P0 and F appear on both sides: int p dtheta = P0 and R int p cos = F give two linear
   equations. Their solution fixes P0/K and F/(R K) as functions of b alone. With
   E' = E/(1-nu^2) (plane strain) the load parameter is

       E' dR / F = (R K / F) / (1 - nu) = 2 R K / F        (nu = 1/2).

   The neat fit (E' dR/F -> 0) is the b where the 2 x 2 system is singular: the limiting
   contact angle, reached at infinite load (or zero clearance).

The moments int g dtheta and int g cos(theta) dtheta of the three shape functions are
integrals of analytic functions after t = b sin(phi). They are computed by Gauss-Legendre
quadrature in phi, exact to rounding. Checks in closed form (from
int w/(t^2+g^2) dt = pi (sqrt(g^2+b^2) - g)/g and its derivative in g^2):
int gC dtheta = 2 pi (S-1)/S, int gC cos = 2 pi (S-1)/S^2, int gB dtheta = pi b^2/S^3.

Definitions used for the comparison with the thesis: E' = E/(1-nu^2) = 4E/3 (plane-strain
modulus; the thesis says "equivalent Young's modulus" without a formula. With
E/(1+nu) = E'/2 instead, every value of E' dR/F halves; the contact angle at a given load
does not change). alpha is the contact semi-angle, b = tan(alpha/2). The analytical part
is pure numpy/scipy.

Results (R = 0.08 m, dR = 4e-5 m, E = 1 MPa): alpha = 1.2395 rad at F~ = F/(E R) =
2.3e-2 (the thesis's "limit angle 1.24"), and the neat-fit asymptote is
alpha_c = 1.26272 rad (b_c = 0.73120). The small-load limit is Hertz's conforming
contact with R_eff = R R_pin/dR.
"""
from __future__ import annotations

import functools

import numpy as np

NU = 0.5

__all__ = ["shape_functions", "persson_coefficients", "persson_pressure", "persson_load_parameter",
           "persson_b_from_load", "persson_limit_b", "persson_limit_angle", "gauss_chebyshev_pressure"]


def shape_functions(theta, b):
    """The three shape functions (gK, gC, gB) of the pressure at angles ``theta`` (rad), 0 off contact."""
    theta = np.asarray(theta, dtype=float)
    th = np.angle(np.exp(1j * theta))            # to (-pi, pi]
    t = np.tan(th / 2)
    S = np.sqrt(1.0 + b * b)
    inside = np.abs(t) < b
    w = np.sqrt(np.where(inside, b * b - t * t, 0.0))
    gK = np.arctanh(w / S) - w * np.log(S) / S
    gC = w / S
    gB = w / S * (1.0 / (1.0 + t * t) - b * b / (2.0 * S * S))
    z = lambda g: np.where(inside, g, 0.0)
    return z(gK), z(gC), z(gB)


@functools.lru_cache(maxsize=None)
def _gauss_legendre(n):
    return np.polynomial.legendre.leggauss(n)      # an n x n eigenproblem: compute once


def _moments(b, n=400):
    """int g dtheta and int g cos(theta) dtheta over the arc for g in (gK, gC, gB): arrays (3,), (3,)."""
    x, wq = _gauss_legendre(n)
    phi = 0.5 * np.pi * x
    t = b * np.sin(phi)
    jac = 0.5 * np.pi * wq * 2.0 * b * np.cos(phi) / (1.0 + t * t)      # dtheta = 2 dt / (1+t^2)
    theta = 2.0 * np.arctan(t)
    g = np.stack(shape_functions(theta, b))
    return g @ jac, g @ (jac * np.cos(theta))


def _system(b):
    """(I - M) x = a for x = (P0/K, F/(R K)), see module docstring step 5."""
    m0, m1 = _moments(b)
    a = np.array([2.0 * m0[0], 2.0 * m1[0]])
    M = np.array([[(2.0 * m0[0] + m0[1]) / (2.0 * np.pi), 2.0 * m0[2] / np.pi],
                  [(2.0 * m1[0] + m1[1]) / (2.0 * np.pi), 2.0 * m1[2] / np.pi]])
    return np.eye(2) - M, a


def persson_coefficients(b):
    """(P0/K, F/(R K)) for semi-angle b = tan(alpha/2): P0 = int p dtheta, F the load, K = E dR/((1+nu)R)."""
    A, a = _system(float(b))
    return np.linalg.solve(A, a)


def persson_load_parameter(b, nu=NU):
    """E' dR / F with E' = E/(1-nu^2), as a function of b = tan(alpha/2) (scalar or array).

    Zero at the neat-fit limit :func:`persson_limit_b`, negative beyond it (interference fit).
    Only nu = 1/2 is the analytical case; ``nu`` only converts the modulus definition.
    """
    b = np.asarray(b, dtype=float)
    out = np.empty(b.shape)
    for i, bi in np.ndenumerate(b):
        A, a = _system(float(bi))
        # E' dR/F = (1+nu)/(1-nu^2) * R K / F; solve with Cramer so that det -> 0 is smooth.
        det = np.linalg.det(A)
        f_times_det = A[0, 0] * a[1] - A[1, 0] * a[0]
        out[i] = det / f_times_det / (1.0 - nu)
    return out[()] if out.ndim == 0 else out


@functools.lru_cache(maxsize=None)
def persson_limit_b():
    """b = tan(alpha_c/2) of the neat-fit (limiting) contact angle: det(I - M) = 0."""
    from scipy.optimize import brentq
    return brentq(lambda b: np.linalg.det(_system(b)[0]), 0.2, 5.0, xtol=1e-14, rtol=1e-14)


def persson_limit_angle():
    """Limiting (neat-fit) contact semi-angle alpha_c (rad)."""
    return 2.0 * np.arctan(persson_limit_b())


def persson_pressure(theta, b, E, R, dR, nu=NU):
    """Pressure p(theta) (Pa) for contact semi-angle tan(alpha/2) = b, clearance dR, modulus E.

    Contact centred at theta = 0. Returns 0 outside the arc. Only nu = 1/2 is exact.
    """
    K = E * dR / ((1.0 + nu) * R)
    p0, f = persson_coefficients(b)
    gK, gC, gB = shape_functions(theta, b)
    return K * ((2.0 + p0 / np.pi) * gK + p0 / (2.0 * np.pi) * gC + 2.0 * f / np.pi * gB)


def persson_b_from_load(load, E, R, dR, nu=NU):
    """b = tan(alpha/2) for load F (N/m) and clearance dR > 0: inverts the load parameter."""
    from scipy.optimize import brentq
    target = E / (1.0 - nu**2) * dR / load
    bc = persson_limit_b()
    return brentq(lambda b: persson_load_parameter(b, nu) - target, 1e-6, bc * (1 - 1e-12),
                  xtol=1e-15, rtol=1e-15)


def gauss_chebyshev_pressure(b, m=200):
    """Independent check: solve the arc equation (step 2) by Gauss-Chebyshev collocation.

    Unknown q(s) = p/(1+s^2) = w(s) sum_j c_j U_j(s/b) (bounded at both ends), equations in
    t at the Chebyshev nodes of the second kind, with P0 and F as two more unknowns and their
    definitions as two more equations; K = 1. Returns (theta nodes, p at nodes, P0, F/R).
    Uses (1/pi) PV int_{-1}^{1} sqrt(1-x^2) U_j(x)/(y-x) dx = T_{j+1}(y).
    """
    k = np.arange(1, m + 1)
    y = np.cos(np.pi * k / (m + 1))                      # U_m zeros (collocation)
    t = b * y
    j = np.arange(m)
    T = np.cos((j[None, :] + 1) * np.arccos(y)[:, None])  # T_{j+1}(y)
    # (1/pi) PV int q/(t-s) ds with s = b x: (1/pi) int b sqrt(1-x^2) U_j/(b(y-x)) b dx = b T_{j+1}
    lhs = b * T
    # f(t) = [2 (1 + P0/2pi) arctan t + 2 F/(pi R) t/(1+t^2) + P0/2pi t]/(1+t^2)
    n_unknown = m + 2
    A = np.zeros((m + 2, n_unknown))
    rhs = np.zeros(m + 2)
    A[:m, :m] = lhs
    A[:m, m] = -(np.arctan(t) / np.pi + t / (2.0 * np.pi)) / (1.0 + t * t)
    A[:m, m + 1] = -2.0 / np.pi * t / (1.0 + t * t) ** 2
    rhs[:m] = 2.0 * np.arctan(t) / (1.0 + t * t)
    # moments by Gauss-Chebyshev (2nd kind) quadrature of q: int w U_j g ds
    nq = 4 * m
    xq = np.cos(np.pi * np.arange(1, nq + 1) / (nq + 1))
    wq = np.pi / (nq + 1) * np.sin(np.pi * np.arange(1, nq + 1) / (nq + 1)) ** 2   # weight sqrt(1-x^2)
    U = np.sin((j[None, :] + 1) * np.arccos(xq)[:, None]) / np.sqrt(1 - xq**2)[:, None]
    s = b * xq
    # P0 = int p dtheta = 2 int q ds ; F/R = 2 int q (1-s^2)/(1+s^2) ds; ds = b dx, q = b sqrt(1-x^2) U
    base = (wq[:, None] * U) * b * b
    A[m, :m] = 2.0 * base.sum(0)
    A[m, m] = -1.0
    A[m + 1, :m] = 2.0 * (base * ((1 - s**2) / (1 + s**2))[:, None]).sum(0)
    A[m + 1, m + 1] = -1.0
    sol = np.linalg.solve(A, rhs)
    c, P0, FR = sol[:m], sol[m], sol[m + 1]
    Uy = np.sin((j[None, :] + 1) * np.arccos(y)[:, None]) / np.sqrt(1 - y**2)[:, None]
    q = b * np.sqrt(1 - y**2) * (Uy @ c)
    return 2.0 * np.arctan(t), q * (1.0 + t * t), P0, FR


# --------------------------------------------------------------------------------------
# Helpers to compare the numerical pin-in-hole model with the analytical solution.

def edge_angle(theta, p, npts=4):
    """Contact semi-angle from a sampled pressure, to sub-element accuracy.

    Near a smooth (Hertz-like) edge p^2 is linear in theta: fit the last ``npts`` loaded
    elements on each side and extrapolate p^2 = 0; returns the mean of both sides.
    """
    th = np.angle(np.exp(1j * np.asarray(theta, dtype=float)))
    p = np.asarray(p, dtype=float)
    out = []
    for sign in (1.0, -1.0):
        side = (sign * th >= 0) & (p > 0)
        x, y = sign * th[side], p[side] ** 2
        idx = np.argsort(x)[-npts:]
        c = np.polyfit(x[idx], y[idx], 1)
        out.append(-c[1] / c[0])
    return 0.5 * (out[0] + out[1])


def small_displacement_pin(material, R, dR, load, n, iterations=6, **kw):
    """``vjax.pin_in_hole`` with the rigid-body reference chosen so that the pin offset e = dR.

    The infinite plane's mode-1 (rigid) displacement is fixed by the log-R reference length
    and is physically arbitrary. Persson's theory is linear in the displacements
    (interference e cos(theta) - dR, load R int p cos). pin_in_hole keeps two
    finite-displacement terms: the exact circle geometry, with e^2 sin^2(theta)/(2 R_pin),
    and the slope terms u'/R of Eq. 2.21. Both depend on that reference. Choosing
    ``ref_length`` so that e = dR (the contact region of the hole does not translate)
    makes them O(dR^2/R) and recovers the linear problem; the pressure is then
    independent of the reference. Fixed-slope iteration on log(ref_length) (2-3 solves).
    Returns (PinResult, ref_length).
    """
    import vjax

    def offset(log_ref):
        # throw=False: the solver's residual can stall just above its 1e-10 default
        # tolerance at small loads; the caller checks ``residual``.
        # e = dR needs a negative mode-1 compliance (ref_length < R), so the operator is
        # indefinite and a Krylov solve can break down (NaN) at isolated reference
        # lengths; e is continuous in ref_length, so nudge it and retry.
        for k in range(5):
            housing = vjax.hole(material, ref_length=R * np.exp(log_ref + 1e-6 * k))
            r = vjax.pin_in_hole(housing, R, dR, load, options=vjax.PinOptions(n=n, **kw), throw=False)
            if np.isfinite(float(r.pin_offset)):
                break
        return float(r.pin_offset) - dR, r

    # e is linear in log(ref_length) up to the O(e^2/R) terms: changing the reference adds
    # a rigid translation (mode 1), de/dlog(ref) = (ds_1/dlog(ref)) F / (pi E0) with s_1
    # the mode-1 element symbol. Start at ref_length = R and iterate with that slope.
    s_r = vjax.element_symbol("hole", n, R, float(material.nu), R)[1]
    s_e = vjax.element_symbol("hole", n, R, float(material.nu), R * np.e)[1]
    slope = float(s_e - s_r) * load / (np.pi * float(material.E0))
    l1 = 0.0
    f1, r = offset(l1)
    for _ in range(iterations):
        if not abs(f1) > 1e-7 * dR:       # e to 1e-7 dR: far below every tolerance
            break
        l1 = l1 - f1 / slope
        f1, r = offset(l1)
    return r, R * np.exp(l1)
