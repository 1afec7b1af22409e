"""vjax.materials.lubricant: each viscosity law through its defining points and against an
independent implementation or tabulated data (ASTM D341's full formula, IAPWS water, Cragoe's
oil correlations), derivatives against central differences, jit / vmap, float32, bad input;
and fitting.torque's viscosity functions, which now delegate to it, unchanged in value."""
import dataclasses
import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax.materials.lubricant import ISO_VG, Lubricant, as_lubricant

VG32 = dict(nu_1=32.0, nu_2=5.34, rho=874.0)


def astm_d341(nu_1, T_1, nu_2, T_2, T):
    """The standard's full form (ASTM D341-09, with its terms for low viscosities), written
    from the standard: Z = nu + 0.7 + exp(-1.47 - 1.84 nu - 0.51 nu^2),
    log10 log10 Z = A - B log10 T_K, and back nu = (Z - 0.7) - exp(-0.7487 - 3.295 (Z - 0.7)
    + 0.6119 (Z - 0.7)^2 - 0.3193 (Z - 0.7)^3), in cSt."""
    Z = lambda nu: nu + 0.7 + math.exp(-1.47 - 1.84 * nu - 0.51 * nu ** 2)      # noqa: E731
    M = np.array([[1.0, -math.log10(T_1 + 273.15)], [1.0, -math.log10(T_2 + 273.15)]])
    A, B = np.linalg.solve(M, [math.log10(math.log10(Z(nu_1))), math.log10(math.log10(Z(nu_2)))])
    x = 10.0 ** 10.0 ** (A - B * np.log10(np.asarray(T) + 273.15)) - 0.7
    return x - np.exp(-0.7487 - 3.295 * x + 0.6119 * x ** 2 - 0.3193 * x ** 3)


# ---- the laws through their points ------------------------------------------------------
def test_walther_through_its_points_and_against_astm_d341():
    """Through the two points exactly (any two temperatures), dynamic = rho nu; between and
    beyond them the standard's full form agrees to 2e-5 while nu >= 3 cSt (its low-viscosity
    terms, which vjax leaves out, matter only below that)."""
    for nu_1, T_1, nu_2, T_2 in ((32.0, 40.0, 5.34, 100.0), (220.0, 20.0, 14.0, 90.0)):
        oil = Lubricant.walther(nu_1, nu_2, T_1, T_2, rho=874.0)
        np.testing.assert_allclose(oil.viscosity(np.array([T_1, T_2])), [874e-6 * nu_1, 874e-6 * nu_2], rtol=1e-12)
        T = np.linspace(-20.0, 120.0, 15)
        ref = astm_d341(nu_1, T_1, nu_2, T_2, T)
        assert ref.min() > 3.0
        np.testing.assert_allclose(oil.kinematic_viscosity(T) * 1e6, ref, rtol=2e-5)
        np.testing.assert_allclose(oil.viscosity(T), 874e-6 * ref, rtol=2e-5)


def test_iso_vg_presets():
    """ISO VG 32 is the thermal cases' oil (32.0 and 5.34 cSt, 874 kg/m^3, 1949 J/(kg K)); every
    grade runs through its grade at 40 C (ISO 3448 midpoint) and its table's nu at 100 C, and
    its c_p and k agree with Cragoe's correlations for petroleum oils at 40 C (written here in
    their original units, Btu, lb, ft, h, F)."""
    oil = Lubricant.iso_vg(32)
    assert (oil.rho, oil.c_p, oil.name) == (874.0, 1949.0, "ISO VG 32")
    np.testing.assert_allclose([oil.viscosity(40.0), oil.viscosity(100.0)], [874e-6 * 32.0, 874e-6 * 5.34], rtol=1e-12)
    nu100 = []
    for grade in ISO_VG:
        oil = Lubricant.iso_vg(grade)
        nu100.append(float(oil.kinematic_viscosity(100.0)) * 1e6)
        np.testing.assert_allclose(oil.kinematic_viscosity(40.0) * 1e6, grade, rtol=1e-12)
        s, t_F = oil.rho / 999.0, 40.0 * 1.8 + 32.0
        np.testing.assert_allclose(oil.c_p, (0.388 + 0.00045 * t_F) / math.sqrt(s) * 4186.8, rtol=2e-3)
        np.testing.assert_allclose(oil.k, 0.0677 * (1.0 - 0.0003 * (t_F - 32.0)) / s * 1.730735, rtol=2e-3)
    assert np.all(np.diff(nu100) > 0)
    # the data sheet's own values replace the table's
    mine = Lubricant.iso_vg(46, nu100=6.9, rho=870.0)
    np.testing.assert_allclose(mine.viscosity(100.0), 870e-6 * 6.9, rtol=1e-12)


def test_density_constant_by_default_or_linear():
    oil = Lubricant.walther(**VG32)
    np.testing.assert_allclose(oil.density(np.array([0.0, 40.0, 150.0])), 874.0, rtol=0)
    hot = Lubricant.walther(**VG32, expansion=6.5e-4, T_rho=15.0)
    np.testing.assert_allclose(hot.density(40.0), 874.0 * (1 - 6.5e-4 * 25.0), rtol=1e-14)
    # the data sheet's kinematic viscosities stay the anchors; the dynamic one follows rho(T)
    np.testing.assert_allclose(hot.viscosity(100.0), 874.0 * (1 - 6.5e-4 * 85.0) * 5.34e-6, rtol=1e-12)


def test_vogel_through_three_points():
    """From three points of a known Vogel law: its parameters back; from three points of VG 32's
    Walther curve: through them exactly, and close to it between them."""
    A, B, C = 5e-5, 900.0, -95.0
    T = np.array([30.0, 60.0, 110.0])
    fit = Lubricant.vogel_points(T, A * np.exp(B / (T - C)))
    np.testing.assert_allclose([fit.params[n] for n in "ABC"], [A, B, C], rtol=1e-9)
    oil = Lubricant.iso_vg(32)
    T = np.array([40.0, 70.0, 100.0])
    fit = Lubricant.vogel_points(T, oil.viscosity(T), rho=874.0)
    np.testing.assert_allclose(fit.viscosity(T), oil.viscosity(T), rtol=1e-12)
    assert fit.params["C"] < 40.0 and fit.rho == 874.0
    np.testing.assert_allclose(fit.viscosity(np.array([55.0, 85.0])), oil.viscosity(np.array([55.0, 85.0])), rtol=0.02)


def test_exponential_and_constant():
    lub = Lubricant.exponential(0.03, 0.04, 40.0)
    np.testing.assert_allclose(lub.viscosity(np.array([40.0, 65.0])), [0.03, 0.03 / math.e], rtol=1e-14)
    c = Lubricant.constant(0.01)
    assert np.shape(c.viscosity(np.zeros(3))) == (3,)
    np.testing.assert_allclose(c.viscosity(np.array([0.0, 99.0])), 0.01, rtol=0)


def test_water_against_iapws():
    """Water's law (fitting.torque's before) against the IAPWS 2008 viscosity of liquid water at
    0.1 MPa (100 C: saturated), which the CRC Handbook tabulates to the digits given: within
    the 1 % the law states from 10 to 100 C; its thermal properties are IAPWS's at 40 C."""
    T = np.array([10.0, 20.0, 40.0, 60.0, 80.0, 100.0])
    mu = np.array([1.3059, 1.0016, 0.6527, 0.4660, 0.3541, 0.2817]) * 1e-3
    water = Lubricant.water()
    np.testing.assert_allclose(water.viscosity(T), mu, rtol=0.01)
    np.testing.assert_allclose([water.rho, water.c_p, water.k], [992.22, 4179.4, 0.6285], rtol=2e-3)
    assert water.T_max == 100.0


def test_torque_viscosity_functions_unchanged():
    """fitting.torque's oil_viscosity and water_viscosity delegate to Lubricant: the numbers
    their docstrings state, and their closed forms as they were before (rtol 1e-13)."""
    from fitting import torque as ft
    eta = ft.oil_viscosity(32, 5.4)
    np.testing.assert_allclose([eta(40.0), eta(70.0)], [0.0275, 0.0096], atol=5e-5)
    assert eta.__name__ == "oil_viscosity(32, 5.4, 860)" and isinstance(eta.lubricant, Lubricant)
    T = np.array([0.0, 40.0, 70.0, 100.0, 150.0])
    z40, z100 = (math.log10(math.log10(v + 0.7)) for v in (32.0, 5.4))
    before = 860e-6 * (10.0 ** (10.0 ** (z40 - (z40 - z100) / math.log10(373.15 / 313.15)
                                         * np.log10((T + 273.15) / 313.15))) - 0.7)
    np.testing.assert_allclose(eta(T), before, rtol=1e-13)
    np.testing.assert_allclose([ft.water_viscosity(t) for t in (20.0, 40.0, 70.0)], [1.00e-3, 0.65e-3, 0.40e-3],
                               atol=5e-6)
    np.testing.assert_allclose(ft.water_viscosity(T), 2.414e-5 * 10.0 ** (247.8 / (T + 273.15 - 140.0)), rtol=1e-13)


# ---- derivatives, jit, vmap, float32 ----------------------------------------------------------
LAWS = {
    "walther": Lubricant.walther(**VG32, expansion=6.5e-4),
    "vogel": Lubricant.water(),
    "exponential": Lubricant.exponential(0.03, 0.04, 40.0),
    "constant": Lubricant.constant(0.01),
}


def central(f, x, h):
    return (f(x + h) - f(x - h)) / (2 * h)


@pytest.mark.parametrize("law", LAWS)
def test_derivatives_vs_central_differences(law):
    """d eta / d T and d eta / d each of the law's parameters and rho, by jax.grad, against
    central differences (step 1e-5 relative: truncation and round-off both near 1e-10)."""
    lub = LAWS[law]
    for T in (20.0, 60.0, 95.0):
        np.testing.assert_allclose(jax.grad(lub.viscosity)(T), central(lub.viscosity, T, 1e-4),
                                   rtol=1e-7, atol=1e-16)
        g = jax.grad(lambda l: l.viscosity(T), allow_int=True)(lub)
        for name, value in lub.params.items():
            with_p = lambda v: dataclasses.replace(lub, params={**lub.params, name: v}).viscosity(T)  # noqa: E731
            h = 1e-5 * max(abs(value), 1.0)
            np.testing.assert_allclose(g.params[name], central(with_p, value, h), rtol=1e-6, atol=1e-14)
        if law == "walther":
            np.testing.assert_allclose(g.rho, lub.viscosity(T) / lub.density(T) * (1 - 6.5e-4 * (T - 15.0)),
                                       rtol=1e-12)


def test_derivatives_through_the_constructors():
    """The viscosity at 70 C with respect to the data-sheet points (Walther: nu_1, nu_2; Vogel:
    its three viscosities), through the constructors, against central differences."""
    def walther(nu):
        return Lubricant.walther(nu[0], nu[1], rho=874.0).viscosity(70.0)
    nu = jnp.array([32.0, 5.34])
    g = jax.grad(walther)(nu)
    for i in range(2):
        e = np.eye(2)[i] * 1e-5 * nu[i]
        np.testing.assert_allclose(g[i], (walther(nu + e) - walther(nu - e)) / (2e-5 * nu[i]), rtol=1e-7)
    T = jnp.array([40.0, 70.0, 100.0])
    eta = Lubricant.iso_vg(32).viscosity(T)

    def vogel(eta):
        return Lubricant.vogel_points(T, eta).viscosity(55.0)
    g = jax.grad(vogel)(eta)
    for i in range(3):
        e = np.eye(3)[i] * 1e-6 * eta[i]
        np.testing.assert_allclose(g[i], (vogel(eta + e) - vogel(eta - e)) / (2e-6 * eta[i]), rtol=1e-6)


@pytest.mark.parametrize("law", LAWS)
def test_jit_and_vmap(law):
    """The Lubricant is a PyTree: a jitted function takes it as an argument; vmap over
    temperatures and over a batch of lubricants (here: their parameters scaled)."""
    lub = LAWS[law]
    T = jnp.linspace(10.0, 100.0, 7)
    eager = np.array([lub.viscosity(t) for t in T])
    np.testing.assert_allclose(jax.jit(lambda l, t: l.viscosity(t))(lub, T), eager, rtol=1e-13)
    np.testing.assert_allclose(jax.vmap(lub.viscosity)(T), eager, rtol=1e-13)
    np.testing.assert_allclose(jax.vmap(jax.grad(lub.viscosity))(T),
                               [jax.grad(lub.viscosity)(t) for t in T], rtol=1e-13)
    batch = jax.tree.map(lambda x: jnp.stack([jnp.asarray(x, float)] * 3), lub)
    out = jax.vmap(lambda l: l.viscosity(50.0))(batch)
    np.testing.assert_allclose(out, lub.viscosity(50.0), rtol=1e-14)


@pytest.mark.parametrize("law", LAWS)
def test_float32_runs_without_nan(law):
    """float32 parameters and temperatures: float32 viscosity and derivative, finite from -20 to
    250 C, and within 1e-4 of float64 (the Walther law's log log loses the most)."""
    lub = LAWS[law]
    lub32 = jax.tree.map(lambda x: jnp.asarray(x, jnp.float32), lub)
    T = jnp.linspace(-20.0, 250.0, 28, dtype=jnp.float32)
    eta = lub32.viscosity(T)
    d = jax.vmap(jax.grad(lub32.viscosity))(T)
    assert eta.dtype == jnp.float32 and d.dtype == jnp.float32
    assert bool(jnp.all(jnp.isfinite(eta))) and bool(jnp.all(jnp.isfinite(d))) and bool(jnp.all(eta > 0))
    np.testing.assert_allclose(eta, lub.viscosity(np.asarray(T, np.float64)), rtol=1e-4)


# ---- conversion and bad input -----------------------------------------------------------------
def test_as_lubricant():
    oil = Lubricant.iso_vg(32)
    assert as_lubricant(oil) is oil
    np.testing.assert_allclose(oil(55.0), oil.viscosity(55.0), rtol=0)       # a Lubricant is a function of T
    c = as_lubricant(0.02)
    assert c.law == "constant" and float(c.viscosity(80.0)) == 0.02
    f = as_lubricant(lambda T: 1e-3 * (1 + T))
    assert f.law == "function"
    np.testing.assert_allclose(f.viscosity(np.array([0.0, 9.0])), [1e-3, 1e-2], rtol=1e-15)
    # a traced number inside jit
    np.testing.assert_allclose(jax.jit(lambda e: as_lubricant(e).viscosity(30.0))(0.05), 0.05, rtol=0)


def test_bad_input_names_the_argument():
    cases = [
        (lambda: Lubricant.walther(-1.0, 5.0, rho=870.0), "nu_1"),
        (lambda: Lubricant.walther(5.0, 32.0, rho=870.0), "nu_2 must be below nu_1"),
        (lambda: Lubricant.walther(32.0, 5.0, 100.0, 40.0, rho=870.0), "T_1 must be below T_2"),
        (lambda: Lubricant.walther(32.0, 5.0, rho=0.0), "rho"),
        (lambda: Lubricant.walther(32.0, 5.0, rho=870.0, c_p=-1.0), "c_p"),
        (lambda: Lubricant.walther(32.0, 5.0, rho=870.0, expansion=-1e-3), "expansion"),
        (lambda: Lubricant.iso_vg(33), "grade"),
        (lambda: Lubricant.vogel(1e-4, 0.0, -100.0), "B"),
        (lambda: Lubricant.vogel(1e-4, 800.0, -100.0).viscosity(-120.0), "pole"),
        (lambda: Lubricant.vogel_points([40.0, 70.0, 100.0], [0.03, 0.01, 0.001]), "eta must fall"),
        (lambda: Lubricant.vogel_points([40.0, 30.0, 100.0], [0.03, 0.01, 0.005]), "T must be increasing"),
        (lambda: Lubricant.vogel_points([40.0, 100.0], [0.03, 0.01]), "T must hold 3"),
        (lambda: Lubricant.exponential(0.03, -0.01, 40.0), "beta"),
        (lambda: Lubricant.constant(0.0), "eta"),
        (lambda: Lubricant.iso_vg(32).viscosity(-300.0), "absolute zero"),
        (lambda: as_lubricant(-0.01), "viscosity must be > 0"),
        (lambda: as_lubricant(None), "viscosity must be"),
        (lambda: as_lubricant("oil"), "viscosity must be"),
        (lambda: as_lubricant(np.ones(3)), "viscosity must be a scalar"),
        (lambda: Lubricant.constant(0.01).require("rho", "c_p"), "no rho .*, c_p"),
        (lambda: Lubricant.from_function(3.0), "function must be callable"),
    ]
    for make, message in cases:
        with pytest.raises(ValueError, match=message):
            make()
    Lubricant.iso_vg(32).require("rho", "c_p", "k")       # all known: no error


def test_journal_bearing_takes_a_lubricant_at_its_temperature():
    """A Lubricant (or a function of T) in place of the viscosity: the bearing at
    eta(temperature), long and finite; without a temperature it is refused by name."""
    oil = vjax.Lubricant.iso_vg(32)
    eta = float(oil.viscosity(60.0))
    for kw, load in (({}, 2e4), (dict(length=0.05, options=vjax.FiniteJournalOptions(n=32, m=8)), 2e3)):
        a = vjax.journal_bearing(0.05, 5e-5, oil, load, omega_shaft=100.0, temperature=60.0, **kw)
        b = vjax.journal_bearing(0.05, 5e-5, eta, load, omega_shaft=100.0, **kw)
        c = vjax.journal_bearing(0.05, 5e-5, oil.viscosity, load, omega_shaft=100.0, temperature=60.0, **kw)
        assert float(a.eccentricity) == float(b.eccentricity) == float(c.eccentricity)
    with pytest.raises(ValueError, match="viscosity.*temperature="):
        vjax.journal_bearing(0.05, 5e-5, oil, 2e4, omega_shaft=100.0)
