"""Steady-state viscoelastic ring operator sigma -> u, applied by FFT (docs/theory.md §2-§3).

A ring of radius R is cut into N equal elements (centres theta_i = 2 pi i / N, half-width
alpha = pi / N, constant pressure per element). Eq. 2.18 couples them through the
circulant matrix L(theta_i - theta_k), so it is diagonal in Fourier space. For a pressure
pattern rotating rigidly at angular velocity ``omega`` (rad/s) relative to the body, mode
n is seen by a material point as a harmonic at frequency -n*omega, so

    u^_n = R * L^_n * Jeff_n(omega) * sigma^_n.

**Sign convention of omega.** ``omega > 0`` means the pressure pattern moves towards
increasing theta (counter-clockwise). Its leading edge is then the one at larger theta,
and the material, still relaxing behind the load, shows the larger displacement at the
trailing edge (smaller theta).

Memory models (``memory=``):

- ``"periodic"`` (default): the exact periodic steady state, Jeff_n = 1/E*(-n omega).
  Mode 0 (the mean load) is static and always sees the rubbery compliance 1/E0.
- ``"thesis"``: Eq. 2.14/2.16, the load history truncated to one revolution:
  Jeff_n = J0 + sum_k C_k (1 - exp(-2 pi/(|omega| lambda_k))) / (1 - i n omega lambda_k),
  with (J0, C_k, lambda_k) the creep spectrum.
- a number m > 0 of revolutions since the rolling started: the same with 2 pi m; m = 1 is
  the thesis, m -> inf the periodic steady state (t_run = 2 pi m / omega).

The two differ where omega*lambda_k is not small (docs/theory.md §3: a factor 2 in pin friction
torque at omega*tau = 1). The periodic model is what a machine sees after running in;
the thesis model reproduces the thesis's figures. Elastic materials skip all of this.

The Nyquist mode (N even) uses Re Jeff, as the real FFT keeps only its real part; this
keeps the operator real and equal to its dense matrix.
"""
from __future__ import annotations

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks
from . import green
from ..materials.viscoelastic import Material


def memory_revolutions(memory) -> float:
    """Number of revolutions of load history: inf for "periodic", 1 for "thesis". A traced
    number (revolutions, inf for periodic) is returned as it is: a program that takes the
    memory as an argument serves every memory model (:func:`effective_compliance`)."""
    if not checks.is_concrete(memory):
        return memory
    if isinstance(memory, str):
        checks.one_of("memory", memory, ("periodic", "thesis"))
        return np.inf if memory == "periodic" else 1.0
    try:
        m = float(memory)
    except (TypeError, ValueError):
        raise ValueError(f"memory must be 'periodic', 'thesis' or a number of revolutions > 0, got {memory!r}")
    if not m > 0:
        raise ValueError(f"memory (number of revolutions) must be > 0, got {memory!r}")
    return m


def effective_compliance(material: Material, modes, omega, memory="periodic"):
    """Jeff_n (1/Pa) of Fourier modes ``modes`` (signed integers) for a pattern at ``omega`` (rad/s).
    ``memory``: "periodic", "thesis", a number of revolutions, or a traced one (inf: periodic),
    for which both models are compiled and the value picks one when the program runs."""
    modes = jnp.asarray(modes)
    if material.is_elastic:  # no memory terms at all
        return jnp.broadcast_to(1.0 / material.E0, modes.shape)
    m = memory_revolutions(memory)
    periodic = lambda: material.compliance(-modes * omega)     # noqa: E731
    if checks.is_concrete(m):
        return periodic() if np.isinf(m) else _truncated(material, modes, omega, m)
    # the truncated branch at a finite m whatever m is, so that its derivatives stay finite
    return jax.lax.cond(jnp.isinf(m), periodic,
                        lambda: _truncated(material, modes, omega, jnp.where(jnp.isinf(m), 1.0, m)))


def _truncated(material: Material, modes, omega, m):
    """Eq. 2.14/2.16: the load history truncated to m revolutions (module docstring)."""
    spec = material.creep_spectrum()
    speed = jnp.abs(omega)
    moving = speed > 0
    # exp(-2 pi m / (|omega| lambda)) -> 0 as omega -> 0; double where keeps grads finite.
    decay = jnp.where(moving, jnp.exp(-2.0 * jnp.pi * m / (jnp.where(moving, speed, 1.0)
                                                         * spec.retardation_times)), 0.0)
    w = (modes * omega)[..., None]
    terms = spec.C * (1.0 - decay) / (1.0 - 1j * w * spec.retardation_times)
    return spec.J0 + jnp.sum(terms, axis=-1)


def grid(n: int):
    """Element centres theta_i = 2 pi i / n (rad) and half-width alpha = pi / n."""
    return 2.0 * jnp.pi * jnp.arange(n) / n, jnp.pi / n


def element_symbol(kind: str, n: int, R, nu, ref_length=1.0, thickness=None):
    """Real FFT of the first column L(theta_i) of the circulant element matrix (modes 0..n/2).

    The kernels are even, so the symbol is real. Multiply by R * Jeff_n to get the operator.
    "liner" and "sleeve" (bonded layers of ``thickness`` m) are built from their modal
    compliances (:func:`vjax.bodies.green.layer_element_symbol`).
    """
    if kind in green.LAYERS:
        return green.layer_element_symbol(kind, n, R, nu, thickness)
    green._check_kind(kind)
    if kind != "half_plane":
        weights = green._coefficients("cylinder" if kind == "diametral" else kind, R, nu, ref_length)
        return sum(w * b for w, b in zip(weights, green.element_basis_symbols(n, kind == "diametral")))
    theta, alpha = grid(n)
    return jnp.fft.rfft(green.element_kernel(kind, theta, alpha, R, nu, ref_length)).real


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class RingOperator:
    """u = L sigma on a ring of ``n`` elements; u, sigma positive into the body (m, Pa).

    ``symbol[k]`` (m/Pa) multiplies mode k = 0..n/2 of the real FFT. Calling the operator
    costs one rfft and one irfft: O(n log n).
    """

    symbol: jax.Array
    n: int = dataclasses.field(metadata=dict(static=True))

    def __call__(self, sigma):
        return jnp.fft.irfft(self.symbol * jnp.fft.rfft(sigma, axis=-1), self.n, axis=-1)

    def apply_theta_modes(self, P):
        """Displacement (n, m + 1) (m) of the axial slices of a finite bearing's land, each as
        this ring, from their pressures' real FFT in theta ``P`` (n // 2 + 1, m + 1) (rows)."""
        return jnp.fft.irfft(self.symbol[:, None] * P, self.n, axis=0)

    @property
    def plane_symbol(self):
        """The symbol (n // 2 + 1,) (m/Pa) for a pressure uniform along the axis: this one."""
        return self.symbol

    @property
    def kernel(self):
        """First column c: the dense matrix is M[i, j] = c[(i - j) mod n]."""
        return jnp.fft.irfft(self.symbol, self.n)

    def dense(self):
        """The dense n x n matrix (for small n and for tests)."""
        c = self.kernel
        idx = (jnp.arange(self.n)[:, None] - jnp.arange(self.n)[None, :]) % self.n
        return c[idx]


def ring_operator(kind: str, material: Material, R, n: int, omega=0.0, memory="periodic",
                  ref_length=1.0, thickness=None) -> RingOperator:
    """Steady-state operator of a ring of radius ``R`` (m) on ``n`` elements.

    Args:
      kind: Green's function, "hole", "cylinder", "diametral", "half_plane", or a bonded
        layer "liner" / "sleeve" (see :mod:`vjax.bodies.green`).
      material: the body's :class:`~vjax.Material`.
      R: ring radius (m).
      n: number of elements (static).
      omega: angular velocity of the pressure pattern relative to the body (rad/s).
      memory: "periodic", "thesis" or a number of revolutions (see module docstring).
      ref_length: reference length of the log terms (m), default 1 m as the thesis.
      thickness: a layer's thickness (m), 0 < thickness (< R for a sleeve); layers only.

    >>> import jax.numpy as jnp
    >>> op = ring_operator("hole", Material.elastic(1e6, 0.3), R=0.05, n=64)
    >>> u = op(jnp.full(64, 1e3))   # uniform pressure: Lame, u = p R (1 + nu) / E
    >>> round(float(u[0]) / (1e3 * 0.05 * 1.3 / 1e6), 6)
    1.0
    """
    if kind in green.LAYERS:
        checks.positive("thickness", thickness)
        checks.scalar("thickness", thickness)
        t, r = checks.values("thickness", thickness), checks.values("R", R)
        if t is not None and r is not None and not (t >= 1e-3 * r and (kind == "liner" or t < r)):
            raise ValueError(f"thickness must be at least 1e-3 R{'' if kind == 'liner' else ' and below R'} for a "
                             f"{kind}, got thickness={thickness!r} with R={R!r}")
    else:
        green._check_kind(kind)
    if not isinstance(n, (int, np.integer)) or n < 4:
        raise ValueError(f"n (number of elements) must be an integer >= 4, got {n!r}")
    checks.instance("material", material, Material, "a vjax.Material")
    checks.positive("R", R)
    checks.positive("ref_length", ref_length)
    checks.finite("omega", omega)
    for name, val in (("R", R), ("ref_length", ref_length), ("omega", omega)):
        checks.scalar(name, val)
    m = memory_revolutions(memory)
    # a concrete memory is static (a program holds its own model); a traced one (revolutions,
    # inf: periodic) serves every model in one program (:func:`effective_compliance`)
    symbol = _symbol if checks.is_concrete(m) else _symbol_traced
    return RingOperator(symbol(kind, material, R, int(n), omega, m, ref_length, thickness), int(n))


def _symbol_fn(kind, material, R, n, omega, memory, ref_length, thickness):
    """R L^_n Jeff_n for modes 0..n/2; compiled once per (kind, n, memory, material shape)."""
    modes = jnp.arange(n // 2 + 1, dtype=jnp.result_type(float))
    return R * element_symbol(kind, n, R, material.nu, ref_length, thickness) * effective_compliance(
        material, modes, omega, memory)


_symbol = jax.jit(_symbol_fn, static_argnums=(0, 3, 5))
_symbol_traced = jax.jit(_symbol_fn, static_argnums=(0, 3))


def whirl_symbol(kind: str, material: Material, R, n: int, omega, whirl, ref_length=1.0, thickness=None):
    """Operator of a small perturbation sigma(theta) e^{i whirl t} of a pressure pattern that
    moves at ``omega`` (rad/s) relative to the body, on the full FFT (modes in
    ``jnp.fft.fftfreq`` order): u^_m = R L^_|m| J*(-m omega + whirl) sigma^_m.

    A material point sees mode m at -m omega + whirl (rad/s), so modes m and -m respond at
    different frequencies and the operator is not Hermitian (the real FFT of
    :func:`ring_operator` does not apply). At ``whirl = 0`` it equals the periodic steady
    operator (the Nyquist mode takes the mean of its two frequencies, Re J* at whirl 0).
    """
    m = jnp.fft.fftfreq(n, 1.0 / n)
    L = element_symbol(kind, n, R, material.nu, ref_length, thickness)[jnp.abs(m).astype(int)]
    return R * L * whirl_compliance(material, n, omega, whirl)


def whirl_compliance(material: Material, n: int, omega, whirl):
    """Compliance J*(-m omega + whirl) (1/Pa, complex (n,)) of each full-FFT mode m (``fftfreq``
    order) of a perturbation at ``whirl`` (rad/s) on a pattern moving at ``omega`` relative to the
    body; the Nyquist mode takes the mean of its two frequencies (:func:`whirl_symbol`)."""
    m = jnp.fft.fftfreq(n, 1.0 / n)
    J = material.compliance(-m * omega + whirl)
    if n % 2 == 0:
        J = J.at[n // 2].set(0.5 * (material.compliance(-0.5 * n * omega + whirl)
                                    + material.compliance(0.5 * n * omega + whirl)))
    return J


def circulant(symbol):
    """Dense (n, n) matrix of the circulant operator with full-FFT ``symbol`` (n,) (e.g. a
    :func:`whirl_symbol`): column k is the operator applied to the unit vector e_k."""
    n = symbol.shape[0]
    col = jnp.fft.ifft(symbol)
    return col[(jnp.arange(n)[:, None] - jnp.arange(n)[None, :]) % n]


def spectral_derivative(u):
    """du/dtheta of a periodic sampled field (Nyquist mode dropped)."""
    n = u.shape[-1]
    k = jnp.arange(n // 2 + 1)
    k = jnp.where(k == n // 2, 0, k) if n % 2 == 0 else k
    return jnp.fft.irfft(1j * k * jnp.fft.rfft(u), n)
