"""Lubricants: a liquid's viscosity law and its thermal properties, in one JAX PyTree.

:class:`Lubricant` holds a viscosity law of the temperature T (C) and the density rho
(kg/m^3), specific heat c_p (J/(kg K)), thermal conductivity k (W/(m K)) and an optional
maximum temperature T_max (C). Its numbers are PyTree leaves (jit, vmap and grad see them);
the law's name is static. :func:`as_lubricant` turns what the scenes accepted before (a
viscosity in Pa s, or a function of T) into one.

>>> oil = Lubricant.iso_vg(32)                     # 32.0 cSt at 40 C, 5.34 at 100 C, 874 kg/m^3
>>> round(float(oil.viscosity(40.0)), 6)           # Pa s: 874e-6 * 32.0
0.027968
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable

import jax
import jax.numpy as jnp
import numpy as np

from .._core import checks

KELVIN = 273.15
LAWS = ("walther", "vogel", "exponential", "constant", "function")

# ISO VG mineral oils (ISO 3448: the grade is the midpoint kinematic viscosity at 40 C, cSt).
# grade: (nu at 100 C in cSt, rho at 15 C in kg/m^3, c_p at 40 C in J/(kg K), k at 40 C in W/(m K)).
# nu100: a viscosity index of 100 by ASTM D2270 (a paraffinic mineral oil's, typical of
# circulating, turbine and hydraulic oils), except VG 32: 5.34 cSt and c_p 1949 J/(kg K), the
# oil of the thermal bearing cases (VI 98.5). rho: typical of such oils' data sheets (0.86-0.90
# g/ml, heavier grades denser; +-1 %: give the oil's own). c_p and k at 40 C from Cragoe's
# correlations for petroleum oils (US Bureau of Standards Misc. Publ. 97, 1929) at that density:
# c_p = (0.388 + 0.00045 t_F) / sqrt(s) Btu/(lb F), k = 0.0677 (1 - 0.0003 (t_F - 32)) / s
# Btu/(h ft F), s = rho / 999 kg/m^3 the specific gravity (both within a few % for mineral oils).
ISO_VG = {
    22: (4.29, 865.0, 1956.0, 0.1324),
    32: (5.34, 874.0, 1949.0, 0.1310),
    46: (6.76, 879.0, 1941.0, 0.1303),
    68: (8.73, 882.0, 1937.0, 0.1298),
    100: (11.38, 886.0, 1933.0, 0.1293),
    150: (15.02, 889.0, 1930.0, 0.1288),
    220: (19.44, 892.0, 1927.0, 0.1284),
    320: (24.95, 895.0, 1923.0, 0.1280),
}

# Water: Vogel's law eta = 2.414e-5 * 10^(247.8 / (T_K - 140)) Pa s, within 1 % of the IAPWS 2008
# viscosity from 10 to 100 C and 2.2 % at 0 C (IAPWS at 0.1 MPa: 1.0016 mPa s at 20 C, 0.6527 at
# 40, 0.4660 at 60, 0.3541 at 80, 0.2817 at 100). rho, c_p, k at 40 C and 0.1 MPa (IAPWS-95;
# IAPWS 2011 conductivity).
_WATER_VOGEL = dict(A=2.414e-5, B=247.8 * math.log(10.0), C=140.0 - KELVIN)
_WATER_PROPERTIES = dict(rho=992.2, c_p=4179.0, k=0.629)


def _concrete(*xs):
    return all(checks.values("x", x) is not None for x in xs)


def _check_properties(rho, c_p, k, expansion, T_rho, T_max):
    for name, v in (("rho", rho), ("c_p", c_p), ("k", k)):
        if v is not None:
            checks.positive(name, v)
    checks.nonnegative("expansion", expansion)
    checks.finite("T_rho", T_rho)
    if T_max is not None:
        checks.finite("T_max", T_max)


def _scalar_name(fmt, *xs):
    """A readable name when the numbers are concrete (not under a trace)."""
    return fmt.format(*map(float, xs)) if _concrete(*xs) else fmt.split("(")[0]


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Lubricant:
    """A lubricant: viscosity law and thermal properties (build it with a classmethod).

    ``params``: the law's parameters (a dict of numbers, PyTree leaves). ``law`` (static):
    "walther" (A, B: log10 log10(nu + 0.7) = A - B log10 T_K, nu in cSt; dynamic viscosity
    rho(T) nu), "vogel" (A in Pa s, B in K, C in C: eta = A exp(B / (T - C))), "exponential"
    (eta0 in Pa s, beta in 1/K, T0 in C: eta = eta0 exp(-beta (T - T0))), "constant" (eta,
    Pa s), "function" (``function(T)`` in Pa s, a user's callable: static).

    ``rho`` (kg/m^3, at ``T_rho`` C, changing linearly by the volumetric ``expansion``
    coefficient (1/K): rho(T) = rho (1 - expansion (T - T_rho)); default 0: constant),
    ``c_p`` (J/(kg K)), ``k`` (W/(m K)): None when not known (a plain viscosity); a thermal
    computation asks for them with :meth:`require`. ``T_max`` (C): the oil's stated maximum
    temperature, or None. ``name`` (static): for messages and tables.

    A Lubricant is also a function of T: ``lubricant(T) == lubricant.viscosity(T)``.
    """

    params: dict
    rho: jax.Array | None = None
    c_p: jax.Array | None = None
    k: jax.Array | None = None
    expansion: jax.Array = 0.0
    T_rho: jax.Array = 15.0
    T_max: jax.Array | None = None
    law: str = dataclasses.field(default="constant", metadata=dict(static=True))
    name: str = dataclasses.field(default="", metadata=dict(static=True))
    function: Callable | None = dataclasses.field(default=None, metadata=dict(static=True))

    # ---- evaluation ------------------------------------------------------------------------
    def viscosity(self, T):
        """Dynamic viscosity (Pa s) at the temperature ``T`` (C), elementwise; differentiable in
        T and in the parameters. Concrete T is checked against the law's domain (above
        absolute zero; above the pole C for Vogel's law)."""
        p = self.params
        if checks.values("T", T) is not None:
            if not np.all(np.asarray(T) > -KELVIN):
                raise ValueError(f"T must be above absolute zero (-273.15 C), got {T!r}")
            if self.law == "vogel" and _concrete(p["C"]) and not np.all(np.asarray(T) > float(p["C"])):
                raise ValueError(f"T must be above the Vogel law's pole C = {float(p['C']):g} C "
                                 f"(the viscosity diverges there), got {T!r}")
        if self.law == "walther":
            nu = 10.0 ** (10.0 ** (p["A"] - p["B"] * jnp.log10(T + KELVIN))) - 0.7      # cSt
            return self.density(T) * 1e-6 * nu
        if self.law == "vogel":
            return p["A"] * jnp.exp(p["B"] / (T - p["C"]))
        if self.law == "exponential":
            return p["eta0"] * jnp.exp(-p["beta"] * (T - p["T0"]))
        if self.law == "constant":
            return p["eta"] * jnp.ones_like(T)
        return self.function(T)

    __call__ = viscosity

    def density(self, T):
        """Density (kg/m^3) at ``T`` (C)."""
        self.require("rho")
        return self.rho * (1.0 - self.expansion * (T - self.T_rho))

    def kinematic_viscosity(self, T):
        """Kinematic viscosity (m^2/s) at ``T`` (C): viscosity / density."""
        return self.viscosity(T) / self.density(T)

    def require(self, *names):
        """Raise a ValueError naming the thermal properties (of "rho", "c_p", "k", "T_max")
        this lubricant lacks; a thermal scene calls it before using them."""
        missing = [n for n in names if getattr(self, n) is None]
        if missing:
            units = dict(rho="kg/m^3", c_p="J/(kg K)", k="W/(m K)", T_max="C")
            raise ValueError(f"the lubricant {self.name or self.law!r} has no "
                             + ", ".join(f"{n} ({units[n]})" for n in missing)
                             + ": give " + ", ".join(f"{n}=..." for n in missing) + " when building it")

    # ---- constructors ----------------------------------------------------------------------
    @classmethod
    def walther(cls, nu_1, nu_2, T_1=40.0, T_2=100.0, *, rho, c_p=None, k=None, expansion=0.0,
                T_rho=15.0, T_max=None, name=None):
        """Walther's equation (ASTM D341): log10 log10(nu + 0.7) = A - B log10 T_K (nu in cSt =
        mm^2/s, T_K in K) through the kinematic viscosities ``nu_1`` at ``T_1`` and ``nu_2`` at
        ``T_2`` (C; a data sheet's 40 and 100 C by default). Dynamic viscosity rho(T) nu(T)
        with ``rho`` in kg/m^3 (constant unless ``expansion`` is given, see the class).

        The form nu + 0.7 is the standard's for nu >= 2 cSt (its correction terms below 2 cSt,
        a thin oil well above 100 C, are not included). Traceable: the viscosity is
        differentiable with respect to nu_1, nu_2, T_1, T_2 too."""
        for n, v in (("nu_1", nu_1), ("nu_2", nu_2)):
            checks.positive(n, v)
        for n, v in (("T_1", T_1), ("T_2", T_2)):
            checks.finite(n, v)
        checks.positive("rho", rho)
        _check_properties(rho, c_p, k, expansion, T_rho, T_max)
        if _concrete(T_1, T_2) and not T_1 < T_2:
            raise ValueError(f"T_1 must be below T_2, got T_1={T_1}, T_2={T_2}")
        if _concrete(nu_1, nu_2) and not nu_2 < nu_1:
            raise ValueError(f"nu_2 must be below nu_1 (an oil thins when heated), got nu_1={nu_1}, nu_2={nu_2}")
        z1, z2 = (jnp.log10(jnp.log10(nu + 0.7)) for nu in (nu_1, nu_2))
        x1, x2 = (jnp.log10(T + KELVIN) for T in (T_1, T_2))
        B = (z1 - z2) / (x2 - x1)
        name = name or _scalar_name("walther({:g} cSt at {:g} C, {:g} cSt at {:g} C)", nu_1, T_1, nu_2, T_2)
        return cls(dict(A=z1 + B * x1, B=B), rho, c_p, k, expansion, T_rho, T_max, "walther", name)

    @classmethod
    def iso_vg(cls, grade, *, nu100=None, rho=None, c_p=None, k=None, expansion=0.0, T_max=None):
        """A mineral oil of ISO VG ``grade`` (22, 32, 46, 68, 100, 150, 220, 320) by Walther
        through ``grade`` cSt at 40 C and ``nu100`` at 100 C, with rho, c_p, k from the table
        :data:`ISO_VG` (typical values and their sources there); any of them can be replaced by
        the oil's own data sheet."""
        if grade not in ISO_VG:
            raise ValueError(f"grade must be one of the ISO VG grades {sorted(ISO_VG)}, got {grade!r}")
        d_nu100, d_rho, d_cp, d_k = ISO_VG[grade]
        pick = lambda v, default: default if v is None else v     # noqa: E731
        return cls.walther(float(grade), pick(nu100, d_nu100), 40.0, 100.0, rho=pick(rho, d_rho),
                           c_p=pick(c_p, d_cp), k=pick(k, d_k), expansion=expansion, T_max=T_max,
                           name=f"ISO VG {grade}")

    @classmethod
    def vogel(cls, A, B, C, *, rho=None, c_p=None, k=None, expansion=0.0, T_rho=15.0, T_max=None, name="vogel"):
        """Vogel's law eta = A exp(B / (T - C)) (Pa s): ``A`` (Pa s) > 0, ``B`` (K) > 0, pole
        ``C`` (C); valid for T > C."""
        checks.positive("A", A)
        checks.positive("B", B)
        checks.finite("C", C)
        _check_properties(rho, c_p, k, expansion, T_rho, T_max)
        return cls(dict(A=A, B=B, C=C), rho, c_p, k, expansion, T_rho, T_max, "vogel", name)

    @classmethod
    def vogel_points(cls, T, eta, **properties):
        """Vogel's law through three points: viscosities ``eta`` (Pa s) at temperatures ``T``
        (C), both of length 3, T increasing. ln eta must be convex and decreasing in T (it
        falls faster per degree between the first two points than between the last two),
        which puts the pole below T[0]; straight: use :meth:`exponential`. Other keywords as
        :meth:`vogel`. Traceable in T and eta."""
        for n, v in (("T", T), ("eta", eta)):
            if np.shape(v) != (3,):
                raise ValueError(f"{n} must hold 3 values, got shape {np.shape(v)}")
        checks.finite("T", T)
        checks.positive("eta", eta)
        T, y = jnp.asarray(T), jnp.log(jnp.asarray(eta))
        if _concrete(T) and not np.all(np.diff(np.asarray(T)) > 0):
            raise ValueError(f"T must be increasing, got {T}")
        s1, s2 = (y[0] - y[1]) / (T[1] - T[0]), (y[1] - y[2]) / (T[2] - T[1])   # falls per degree
        if _concrete(s1, s2) and not (float(s1) > float(s2) > 0):
            raise ValueError(f"eta must fall with T, faster between the first two points than between the "
                             f"last two, for a Vogel law with its pole below T; got ln eta falling "
                             f"{float(s1):.4g} then {float(s2):.4g} per K (use Lubricant.exponential for a "
                             f"straight ln eta)")
        C = T[0] - (T[2] - T[0]) / (s1 / s2 - 1.0)
        B = (y[0] - y[1]) * (T[0] - C) * (T[1] - C) / (T[1] - T[0])
        return cls.vogel(jnp.exp(y[0] - B / (T[0] - C)), B, C, **properties)

    @classmethod
    def exponential(cls, eta0, beta, T0, *, rho=None, c_p=None, k=None, expansion=0.0, T_rho=15.0, T_max=None,
                    name="exponential"):
        """Reynolds' exponential law eta = ``eta0`` exp(-``beta`` (T - ``T0``)): eta0 (Pa s) at T0
        (C), beta (1/K) >= 0. (Through a mineral oil's two data-sheet points it overestimates
        the viscosity between them: prefer :meth:`walther` for oils.)"""
        checks.positive("eta0", eta0)
        checks.nonnegative("beta", beta)
        checks.finite("T0", T0)
        _check_properties(rho, c_p, k, expansion, T_rho, T_max)
        return cls(dict(eta0=eta0, beta=beta, T0=T0), rho, c_p, k, expansion, T_rho, T_max, "exponential", name)

    @classmethod
    def water(cls, *, rho=_WATER_PROPERTIES["rho"], c_p=_WATER_PROPERTIES["c_p"], k=_WATER_PROPERTIES["k"],
              expansion=0.0, T_max=100.0):
        """Water: Vogel's law eta = 2.414e-5 * 10^(247.8 / (T_K - 140)) Pa s (within 1 % of
        IAPWS 2008 from 10 to 100 C); rho 992.2 kg/m^3, c_p 4179 J/(kg K), k 0.629 W/(m K), its
        values at 40 C (IAPWS; rho falls 4 % and k rises 13 % from 20 to 100 C: give them at the
        film's temperature if it matters); T_max 100 C (boiling at atmospheric pressure)."""
        _check_properties(rho, c_p, k, expansion, 40.0, T_max)
        return cls(dict(_WATER_VOGEL), rho, c_p, k, expansion, 40.0, T_max, "vogel", "water")

    @classmethod
    def constant(cls, eta, *, rho=None, c_p=None, k=None, T_max=None, name=None, argument="eta"):
        """A temperature-independent viscosity ``eta`` (Pa s) > 0 (``argument``: the name the
        error message gives it)."""
        checks.positive(argument, eta)
        _check_properties(rho, c_p, k, 0.0, 15.0, T_max)
        name = name or _scalar_name("constant({:g} Pa s)", eta)
        return cls(dict(eta=eta), rho, c_p, k, 0.0, 15.0, T_max, "constant", name)

    @classmethod
    def from_function(cls, function, *, rho=None, c_p=None, k=None, T_max=None, name=None):
        """A viscosity given as a function of T (C) returning Pa s (how the scenes took a
        temperature-dependent viscosity before this class). It is static: jit retraces for a
        new function, and grad sees only what the function closes over as constants."""
        if not callable(function):
            raise ValueError(f"function must be callable, got {function!r}")
        _check_properties(rho, c_p, k, 0.0, 15.0, T_max)
        name = name or getattr(function, "__name__", "function")
        return cls({}, rho, c_p, k, 0.0, 15.0, T_max, "function", name, function)


def as_lubricant(x, argument="viscosity") -> Lubricant:
    """``x`` as a :class:`Lubricant`: a Lubricant as it is, a callable of T (C) by
    :meth:`Lubricant.from_function`, a number (Pa s, may be traced) by
    :meth:`Lubricant.constant`. ``argument``: the name the error message gives x."""
    if isinstance(x, Lubricant):
        return x
    if callable(x):
        return Lubricant.from_function(x)
    if x is None or isinstance(x, (str, bytes)):
        raise ValueError(f"{argument} must be a viscosity (Pa s), a function of the temperature (C) "
                         f"or a Lubricant, got {x!r}")
    checks.scalar(argument, x)
    return Lubricant.constant(x, argument=argument)
