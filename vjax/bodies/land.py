"""The bonded 3D layer's (or hole's) operator on a finite bearing's land grid: FFT in theta, DCT-I in z.

Grid (:mod:`vjax.films.film2d`): n elements in theta (centres 2 pi i / n) by m + 1 uniformly spaced
axial nodes z_0 = -L/2 ... z_m = L/2. The layer (:mod:`vjax.bodies.layer3d`) spans the land and its
ends slide on rigid shoulders at z = +-L/2: its axial modes are cos(k_q (z + L/2)), k_q = q pi / L,
and its response is that of the pressure mirrored about each end (a period 2 L). The pressure
is taken element-constant in theta (as the plane ring's operator takes it) and piecewise linear
in z between the nodes (the finite-volume film's own profile). The Fourier coefficients of such
a field are the nodal values' (real FFT in theta, DCT-I in z) times the element factors
sinc(k_theta / n) and sinc^2(q / (2 m)) (a hat of half-width L/m), every mode q = j + 2 m l
folding onto the nodes' j = 0 .. m; so the displacement into the body at the nodes is

    u_kj = R J_eff(k) G_kj P_kj,
    G_kj = L_k + sum_(|l| <= 4) sinc((k + l n)/n) [ sum_(|s| <= 4) sinc^2((j + 2 m s)/(2 m)) c(|k + l n|, k_|j + 2 m s| R)
                                                  - c_2D(|k + l n|) ]

with L_k the plane ring's element symbol of the layer (:func:`vjax.bodies.operator.element_symbol`,
E = 1: every theta mode aliased onto k, element-averaged), c the 3D modal compliance
(:func:`vjax.bodies.layer3d.layer_modes`), c_2D its plane-strain limit (:func:`vjax.bodies.green.mode_compliance`)
and J_eff(k) the material's compliance at mode k's own frequency (-k omega relative to the body,
:func:`vjax.bodies.operator.effective_compliance`: the correspondence principle with a constant Poisson
ratio, as in 2D). Since sum_s sinc^2((j + 2 m s)/(2 m)) = 1, a z-independent compliance gives back
L_k: the plane-strain slices (each node's own pressure), and at j = 0 G is L_k exactly (a
z-uniform pressure deforms the layer as the slices do). The 3D correction is carried by the
base theta mode and its eight nearest aliases (the farther ones keep plane strain: weight
~ 1/(pi l), 3D correction O((k_q R / |k + l n|)^2)), by nine axial images in full and the next
ones (|s| <= 200, weight ~ 1/(pi s)^2) by the flat bonded layer of the same wavenumber (their
waves are at most L / (4.5 m) long: short against the layer's curvature).

A hole (kind ``"hole"``, :func:`vjax.bodies.layer3d.layer_modes`): a hole of radius R through a body of
thickness L (the land) whose faces slide on rigid frictionless shoulders at z = +-L/2, so the
cosine modes are exact as for the layer. The same G with L_k the plane hole's element symbol
(A.45, its mode 1 fixed by ``ref_length``, so that a z-uniform pressure gives the plane hole's
ring operator), c the 3D hole's compliance (c_2D the plane hole's, with the same ``ref_length``,
which thus cancels from every column but j = 0: the 3D hole has no rigid mode for k > 0), and the
far axial images by the half-space 2 (1 - nu^2) / (K R), the flat layer's infinite-thickness limit.

One application: rfft in theta, a length-2m FFT of the even extension in z and their inverses,
O(N log N) for N = n (m + 1).
"""
from __future__ import annotations

import dataclasses
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks
from . import green
from .layer3d import KINDS, layer_modes
from ..materials.viscoelastic import Material
from .operator import effective_compliance, element_symbol, memory_revolutions, whirl_compliance

ALIASES = tuple(range(-4, 5))   # images k + l n of a theta mode that carry the 3D correction
Z_IMAGES = tuple(range(-4, 5))  # images j + 2 m s of an axial node mode (the hat's aliases), 3D layer
Z_TAIL = 200                    # farther images, |s| <= Z_TAIL, by the flat bonded layer


def dct1(x, axis=-1):
    """DCT-I along ``axis`` (length m + 1): X_j = x_0 + (-1)^j x_m + 2 sum_{i=1}^{m-1} x_i cos(pi i j / m),
    the FFT of the even extension (real or complex x)."""
    x = jnp.moveaxis(x, axis, -1)
    ext = jnp.concatenate([x, x[..., -2:0:-1]], axis=-1)
    return jnp.moveaxis(jnp.fft.fft(ext, axis=-1)[..., : x.shape[-1]], -1, axis)


def idct1(X, axis=-1):
    """Inverse of :func:`dct1`: x_i = (X_0 + (-1)^i X_m + 2 sum_{j=1}^{m-1} X_j cos(pi i j / m)) / (2 m)."""
    X = jnp.moveaxis(X, axis, -1)
    ext = jnp.concatenate([X, X[..., -2:0:-1]], axis=-1)
    return jnp.moveaxis(jnp.fft.ifft(ext, axis=-1)[..., : X.shape[-1]], -1, axis)


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class LandOperator:
    """u = M p on the land grid (n theta elements x m + 1 uniform axial nodes); u and p positive
    into the body (m, Pa). ``symbol`` (n // 2 + 1, m + 1) (m/Pa) multiplies the pressure's
    coefficients: real FFT in theta (rows), DCT-I in z (columns)."""

    symbol: jax.Array
    n: int = dataclasses.field(metadata=dict(static=True))

    def __call__(self, p):
        """Displacement (n, m + 1) (m) under the pressure ``p`` (n, m + 1) (Pa) on every node."""
        return self.apply_theta_modes(jnp.fft.rfft(p, axis=0))

    def apply_theta_modes(self, P):
        """The same from the pressure's real FFT in theta ``P`` (n // 2 + 1, m + 1)."""
        U = idct1(self.symbol * dct1(P, axis=1), axis=1)
        return jnp.fft.irfft(U, self.n, axis=0)

    @property
    def plane_symbol(self):
        """The symbol (n // 2 + 1,) (m/Pa) for a pressure uniform along the axis: the plane
        ring's (the DCT's column 0; a z-uniform pressure deforms the layer as the slices do)."""
        return self.symbol[:, 0]


def land_operator(kind: str, material: Material, R, thickness, length, n: int, m: int, omega=0.0,
                  memory="periodic", ref_length=1.0) -> LandOperator:
    """The 3D bonded layer's or hole's :class:`LandOperator` (module docstring).

    ``kind`` "liner" (loaded on its bore of radius ``R``, bonded outside), "sleeve" (loaded on
    its outer surface of radius ``R``, bonded on a core) or "hole" (in a body of thickness
    ``length``); ``thickness`` (m) a layer's (None for a hole); ``length`` L (m) of the land and
    of the layer or body (its ends sliding on rigid shoulders); ``n`` theta elements, ``m`` axial
    intervals (uniform nodes); ``omega`` (rad/s) the pressure pattern's speed relative to the
    body, ``memory`` as :func:`vjax.bodies.operator.ring_operator`; ``ref_length`` (m) a hole's plane
    mode 1 reference length (:func:`vjax.bodies.hole`; the axially uniform column only)."""
    _check_kind(kind, thickness)
    name, val = ("ref_length", ref_length) if kind == "hole" else ("thickness", thickness)
    checks.positive(name, val)
    checks.scalar(name, val)
    if not isinstance(n, (int, np.integer)) or n < 4 or not isinstance(m, (int, np.integer)) or m < 2:
        raise ValueError(f"n >= 4 and m >= 2 must be integers, got n={n!r}, m={m!r}")
    checks.instance("material", material, Material, "a vjax.Material")
    for name, val in (("R", R), ("length", length)):
        checks.positive(name, val)
        checks.scalar(name, val)
    memory_revolutions(memory)
    return LandOperator(_symbol(kind, material, R, thickness, length, int(n), int(m), omega, memory, ref_length),
                        int(n))


def _check_kind(kind, thickness):
    """A layer's kind (which needs a thickness), or a hole's (which has none)."""
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    if (kind == "hole") != (thickness is None):
        raise ValueError(f"a hole has no thickness, a {kind} needs one, got thickness={thickness!r}")


@partial(jax.jit, static_argnums=(0, 5, 6, 8))
def _symbol(kind, material, R, thickness, length, n, m, omega, memory, ref_length):
    """(n // 2 + 1, m + 1) symbol (m/Pa); compiled once per (kind, n, m, memory, material shape)."""
    J = effective_compliance(material, jnp.arange(n // 2 + 1), omega, memory)
    return R * J[:, None] * _geometry(kind, material.nu, R, thickness, length, n, m, ref_length)


def _flat_layer(KR, tau, nu):
    """Compliance (units of c) of a flat layer of thickness tau R bonded to a rigid base under a
    surface pressure of wavenumber K: 2 (1 - nu^2)/(K R) (kappa sinh 2s - 2s)/(kappa cosh 2s +
    2 s^2 + (1 + kappa^2)/2), s = K t, written with 1/cosh 2s (no overflow at large K t)."""
    kap = 3.0 - 4.0 * nu
    s = KR * tau
    sech = 2.0 * jnp.exp(-2.0 * s) / (1.0 + jnp.exp(-4.0 * s))
    return 2.0 * (1.0 - nu**2) / KR * (kap * jnp.tanh(2.0 * s) - 2.0 * s * sech) / (
        kap + (2.0 * s * s + 0.5 * (1.0 + kap * kap)) * sech)


def _far_image(kind, KR, tau, nu):
    """The far axial images' compliance (units of c) at wavenumber K: the flat bonded layer, or
    for a hole its infinite-thickness limit, the half-space 2 (1 - nu^2) / (K R)."""
    if kind == "hole":
        return 2.0 * (1.0 - nu**2) / KR
    return _flat_layer(KR, tau, nu)


def _geometry(kind, nu, R, thickness, length, n, m, ref_length=1.0):
    """The symbol's elastic part, E = 1 (n // 2 + 1, m + 1): G_kj of the module docstring; the
    axial images beyond ``Z_IMAGES`` (up to ``Z_TAIL``: their wavenumber is then at least 10 m pi / L,
    a short wave on the layer) by the flat bonded layer (a hole: the half-space) of wavenumber
    sqrt((k/R)^2 + k_q^2)."""
    k = np.arange(n // 2 + 1)
    images = np.abs(k[:, None] + n * np.array(ALIASES)[None, :])           # (n/2 + 1, theta images)
    j = np.arange(m + 1)
    q = np.abs(j[:, None] + 2 * m * np.array(Z_IMAGES)[None, :])          # (m + 1, z images)
    hat = jnp.asarray(np.sinc(q / (2.0 * m)) ** 2)                          # piecewise-linear in z
    kR = jnp.asarray(q.ravel(), float) * jnp.pi * R / length
    tau, ref = (None, ref_length / R) if kind == "hole" else (thickness / R, None)
    c3 = layer_modes(kind, images, kR, nu, tau, ref_length_ratio=ref).reshape(images.shape + q.shape)
    c3 = jnp.sum(c3 * hat, axis=-1)                                          # (n/2 + 1, theta images, m + 1)
    far = np.array([s for s in range(-Z_TAIL, Z_TAIL + 1) if s not in Z_IMAGES])
    qf = np.abs(j[:, None] + 2 * m * far[None, :])                         # (m + 1, far images)
    KR = jnp.sqrt(images[..., None, None] ** 2 + (jnp.asarray(qf, float) * jnp.pi * R / length) ** 2)
    c3 = c3 + jnp.sum(_far_image(kind, KR, tau, nu) * jnp.asarray(np.sinc(qf / (2.0 * m)) ** 2), axis=-1)
    c2 = green.mode_compliance(kind, images, nu, thickness_ratio=tau, ref_length_ratio=ref)   # (n/2 + 1, theta images)
    weight = jnp.sinc(images / n)                                           # sin(m alpha) / (m alpha)
    correction = jnp.sum((c3 - c2[..., None]) * weight[..., None], axis=1)
    return element_symbol(kind, n, R, nu, ref_length, thickness)[:, None] + correction


def whirl_symbol(kind, material, R, thickness, length, n: int, m: int, omega, whirl, ref_length=1.0):
    """Symbol (n, m + 1) (m/Pa, complex) of the 3D layer's (or hole's) response to a small pressure
    perturbation p(theta, z) e^(i whirl t) on a pattern moving at ``omega`` (rad/s) relative to
    the body, on the full FFT in theta (``fftfreq`` order) and the DCT-I in z:
    u = ifft(idct1(S dct1(fft(p)))). Theta mode k (signed) responds at its own frequency
    -k omega + whirl (:func:`vjax.bodies.operator.whirl_compliance`), times the geometry G of
    :func:`land_operator` (``ref_length``: a hole's, as there)."""
    _check_kind(kind, thickness)
    G = _geometry(kind, material.nu, R, thickness, length, n, m, ref_length)   # (n/2 + 1, m + 1)
    J = whirl_compliance(material, n, omega, whirl)
    return R * J[:, None] * G[np.abs(np.fft.fftfreq(n, 1.0 / n)).astype(int)]
