"""The bonded 3D layer's operator on a finite bearing's land grid: FFT in theta, DCT-I in z.

Grid (:mod:`vjax._film2d`): n elements in theta (centres 2 pi i / n) by m + 1 uniformly spaced
axial nodes z_0 = -L/2 ... z_m = L/2. The layer (:mod:`vjax.layer3d`) spans the land and its
ends slide on rigid shoulders at z = +-L/2, so its axial modes are cos(k_j (z + L/2)),
k_j = j pi / L, j = 0 .. m, and the nodal pressure's discrete cosine transform (DCT-I, the
cosine interpolant through the m + 1 nodes) is exact in that basis. With P_kj the pressure's
coefficients (real FFT in theta, DCT-I in z), the displacement into the body is

    u_kj = R J_eff(k) [ L_k + sum_{|l| <= 4} (c(|k + l n|, k_j R) - c_2D(|k + l n|)) sinc((k + l n) / n) ] P_kj

with L_k the plane ring's element symbol of the layer (:func:`vjax.operator.element_symbol`,
E = 1: the element average of every mode aliased onto k), c the 3D modal compliance
(:func:`vjax.layer3d.layer_modes`), c_2D its plane-strain limit (:func:`vjax.green.mode_compliance`)
and J_eff(k) the material's compliance at mode k's own frequency (-k omega relative to the body,
:func:`vjax.operator.effective_compliance`: the correspondence principle with a constant Poisson
ratio, as in 2D). The 3D correction is carried by the base mode and its eight nearest aliases;
the farther ones keep the plane-strain value (their weight sinc ~ 1/(pi l), their 3D
correction O((k_j R / |k + l n|)^2)): against the full aliased sum of 3D modes, 1e-4 of the
mode at the Nyquist corner (k = n/2, j = m) of a 16 x 8 grid, 3e-6 to 3e-7 for lower modes. At j = 0 the symbol is the plane ring's
exactly: a z-independent pressure deforms the layer as the plane-strain slices do.

One application: rfft in theta, a length-2m FFT of the even extension in z and their inverses,
O(N log N) for N = n (m + 1).
"""
from __future__ import annotations

import dataclasses
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from . import _checks, green
from .layer3d import layer_modes
from .material import Material
from .operator import effective_compliance, element_symbol, memory_revolutions

ALIASES = tuple(range(-4, 5))   # images k + l n of a theta mode that carry the 3D correction


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


def land_operator(kind: str, material: Material, R, thickness, length, n: int, m: int, omega=0.0,
                  memory="periodic") -> LandOperator:
    """The 3D bonded layer's :class:`LandOperator` (module docstring).

    ``kind`` "liner" (loaded on its bore of radius ``R``, bonded outside) or "sleeve" (loaded on
    its outer surface of radius ``R``, bonded on a core); ``thickness`` (m); ``length`` L (m) of
    the land and of the layer (its ends sliding on rigid shoulders); ``n`` theta elements, ``m``
    axial intervals (uniform nodes); ``omega`` (rad/s) the pressure pattern's speed relative to the
    body, ``memory`` as :func:`vjax.operator.ring_operator`."""
    if kind not in green.LAYERS:
        raise ValueError(f"kind must be one of {', '.join(green.LAYERS)}, got {kind!r}")
    if not isinstance(n, (int, np.integer)) or n < 4 or not isinstance(m, (int, np.integer)) or m < 2:
        raise ValueError(f"n >= 4 and m >= 2 must be integers, got n={n!r}, m={m!r}")
    _checks.instance("material", material, Material, "a vjax.Material")
    for name, val in (("R", R), ("thickness", thickness), ("length", length)):
        _checks.positive(name, val)
        _checks.scalar(name, val)
    memory_revolutions(memory)
    return LandOperator(_symbol(kind, material, R, thickness, length, int(n), int(m), omega, memory), int(n))


@partial(jax.jit, static_argnums=(0, 5, 6, 8))
def _symbol(kind, material, R, thickness, length, n, m, omega, memory):
    """(n // 2 + 1, m + 1) symbol (m/Pa); compiled once per (kind, n, m, memory, material shape)."""
    J = effective_compliance(material, jnp.arange(n // 2 + 1), omega, memory)
    return R * J[:, None] * _geometry(kind, material.nu, R, thickness, length, n, m)


def _geometry(kind, nu, R, thickness, length, n, m):
    """The symbol's elastic part, E = 1 (n // 2 + 1, m + 1): the plane ring's element symbol plus
    the 3D correction of the base mode and its nearest aliases (module docstring)."""
    k = np.arange(n // 2 + 1)
    images = np.abs(k[:, None] + n * np.array(ALIASES)[None, :])           # (n/2 + 1, len(ALIASES))
    kR = jnp.arange(m + 1) * jnp.pi * R / length
    tau = thickness / R
    c3 = layer_modes(kind, images, kR, nu, tau)                             # (n/2 + 1, aliases, m + 1)
    c2 = green.mode_compliance(kind, images, nu, thickness_ratio=tau)      # (n/2 + 1, aliases)
    weight = jnp.sinc(images / n)                                           # sin(m alpha) / (m alpha)
    correction = jnp.sum((c3 - c2[..., None]) * weight[..., None], axis=1)
    return element_symbol(kind, n, R, nu, thickness=thickness)[:, None] + correction


def whirl_matrix(kind, material, R, thickness, length, n: int, m: int, omega, whirl):
    """Dense response (n, m + 1, n, m + 1) (m/Pa, complex) of the 3D layer to a small pressure
    perturbation p(theta, z) e^(i whirl t) on a pattern moving at ``omega`` (rad/s) relative to
    the body: u[a, b] = sum M[a, b, i, l] p[i, l]. Theta mode k (full FFT, signed) responds at its
    own frequency -k omega + whirl, as :func:`vjax.operator.whirl_symbol` (the Nyquist mode the
    mean of its two), times the geometry of :func:`land_operator`; DCT-I in z."""
    G = _geometry(kind, material.nu, R, thickness, length, n, m)            # (n/2 + 1, m + 1)
    k = jnp.fft.fftfreq(n, 1.0 / n)
    J = material.compliance(-k * omega + whirl)
    if n % 2 == 0:
        J = J.at[n // 2].set(0.5 * (material.compliance(-0.5 * n * omega + whirl)
                                    + material.compliance(0.5 * n * omega + whirl)))
    S = R * J[:, None] * G[np.abs(np.fft.fftfreq(n, 1.0 / n)).astype(int)]   # (n, m + 1), full FFT order
    unit = jnp.eye(n * (m + 1), dtype=S.dtype).reshape(n * (m + 1), n, m + 1)
    u = jnp.fft.ifft(idct1(S * dct1(jnp.fft.fft(unit, axis=1), axis=2), axis=2), axis=1)   # (i l, a, b)
    return jnp.moveaxis(u.reshape(n, m + 1, n, m + 1), (0, 1), (2, 3))
