"""Closure laws: porous resistance (seed eqs. 5-7) and stone drag (seed eqs. 16-18)."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vofdem

NU = vofdem.Medium().nu_water  # m^2/s, the helpers' default water (the core's medium)
RHO = vofdem.Medium().rho_water  # kg/m^3
REF_NU, REF_RHO = 1.0e-6, 1000.0  # the water of the settling velocities in REFERENCES.md
G = 9.81  # m/s^2


# ---------------------------------------------------------------- porous resistance, unit values
def test_permeability_and_forchheimer_coefficient_of_the_paper():
    # hand-computed: K = 0.41^3 0.048^2 / (200 0.59^2) = 2.281e-6 m^2, C = 2.8 / sqrt(200 0.41^3) = 0.754
    assert vofdem.permeability(0.41, 0.048, 200.0) == pytest.approx(2.281e-6, rel=5e-4)
    assert vofdem.forchheimer_coefficient(0.41, 200.0, 2.8) == pytest.approx(0.754, rel=5e-4)


def test_resistance_matches_the_coefficients_of_eq7():
    n, d, u = 0.41, 0.048, 0.1
    k = vofdem.permeability(n, d)
    c = vofdem.forchheimer_coefficient(n)
    rx, rz = vofdem.porous_resistance(u, 0.0, n, d)
    assert rx == pytest.approx(-u * (NU / k + c / math.sqrt(k) * abs(u)), rel=1e-12)
    assert rz == 0.0


def ergun_pressure_gradient(u, n, d, nu=NU, rho=RHO):
    """-dp/dx of Ergun (1952) in the superficial velocity u, written independently of eq. (7)."""
    return rho * u * (150.0 * nu * (1 - n) ** 2 / (n**3 * d**2) + 1.75 * (1 - n) / (n**3 * d) * abs(u))


@pytest.mark.parametrize("u", [1e-4, 0.01, 0.3, -0.2])
@pytest.mark.parametrize("n", [0.3, 0.41, 0.6])
def test_k1_k2_150_175_is_the_ergun_equation(u, n):
    d = 0.048
    rx, _ = vofdem.porous_resistance(u, 0.0, n, d, k1=vofdem.ERGUN_K1, k2=vofdem.ERGUN_K2)
    # steady uniform flow: the pressure gradient balances the resistance, -dp/dx = -rho R_x
    assert -RHO * rx == pytest.approx(ergun_pressure_gradient(u, n, d), rel=1e-12)


def test_papers_coefficients_are_133_and_160_times_ergun():
    n, d = 0.41, 0.048
    # the linear term alone (k2 = 0) and the quadratic term alone (nu = 0)
    def lin(k1):
        return vofdem.porous_resistance(0.1, 0, n, d, k1=k1, k2=0.0)[0]

    def quad(k1, k2):
        return vofdem.porous_resistance(0.1, 0, n, d, nu=0.0, k1=k1, k2=k2)[0]

    assert lin(200) / lin(150) == pytest.approx(200 / 150, rel=1e-12)
    assert quad(200, 2.8) / quad(150, 1.75) == pytest.approx(2.8 / 1.75, rel=1e-12)


def test_resistance_points_against_the_flow():
    for u, w in [(0.3, 0.0), (-0.3, 0.1), (0.05, -0.2), (0.0, 1.0)]:
        rx, rz = vofdem.porous_resistance(u, w, 0.41, 0.048)
        assert rx * u + rz * w < 0
        # parallel to (u, w): the cross product vanishes
        assert rx * w - rz * u == pytest.approx(0.0, abs=1e-12)


def test_clear_water_n_equal_1_has_no_resistance():
    assert vofdem.porous_resistance(0.7, -0.4, 1.0, 0.048) == (0.0, 0.0)
    assert vofdem.permeability(1.0, 0.048) == math.inf


def test_vectorised_forms_broadcast():
    u = np.linspace(-0.5, 0.5, 4)
    n = np.array([[0.35], [0.41], [1.0]])
    rx, rz = vofdem.porous_resistance(u, 0.0, n, 0.048)
    assert rx.shape == rz.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            assert rx[i, j] == vofdem.porous_resistance(float(u[j]), 0.0, float(n[i, 0]), 0.048)[0]
    assert isinstance(vofdem.porous_resistance(0.1, 0.0, 0.41, 0.048)[0], float)
    fx, fz = vofdem.drag_force(u[:, None], 0.0, 0.0, np.array([0.0, 0.1]), 0.048)
    assert fx.shape == fz.shape == (4, 2)


# ---------------------------------------------------------------- drag, unit values
def test_drag_coefficient_of_both_laws():
    for re in [0.1, 1.0, 100.0, 1e4]:
        assert vofdem.drag_coefficient(re) == pytest.approx(0.4 + 24 / re, rel=1e-14)
    law = vofdem.DragLaw.SCHILLER_NAUMANN
    for re in [0.1, 1.0, 100.0, 999.0]:
        assert vofdem.drag_coefficient(re, law) == pytest.approx(24 / re * (1 + 0.15 * re**0.687), rel=1e-14)
    assert vofdem.drag_coefficient(5e4, law) == pytest.approx(0.44, rel=1e-14)
    # the two branches meet at Re = 1000 within 0.4 %
    assert vofdem.drag_coefficient(999.999, law) == pytest.approx(0.44, rel=4e-3)


def test_drag_force_value_and_direction():
    d, u, up = 0.048, 0.5, 0.1
    fx, fz = vofdem.drag_force(u, 0.0, up, 0.0, d)
    v = u - up
    re = v * d / NU
    assert fx == pytest.approx(0.5 * RHO * (0.4 + 24 / re) * math.pi * d**2 / 4 * v * v, rel=1e-12)
    assert fz == 0.0
    fx, fz = vofdem.drag_force(0.2, 0.3, -0.1, 0.1, d, law=vofdem.DragLaw.SCHILLER_NAUMANN)
    assert fx > 0 and fz > 0 and fx * 0.2 - fz * 0.3 == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("law", [vofdem.DragLaw.PAPER, vofdem.DragLaw.SCHILLER_NAUMANN])
def test_zero_relative_velocity_gives_exactly_zero_force(law):
    assert vofdem.drag_force(0.3, -0.2, 0.3, -0.2, 0.048, law=law) == (0.0, 0.0)
    assert vofdem.drag_force(0.0, 0.0, 0.0, 0.0, 0.048, law=law) == (0.0, 0.0)


def brentq(f, a, b, tol=1e-12):
    """Bisection refined to tol: the slow obvious root finder."""
    fa = f(a)
    assert fa * f(b) < 0
    while b - a > tol:
        c = 0.5 * (a + b)
        if fa * f(c) <= 0:
            b = c
        else:
            a, fa = c, f(c)
    return 0.5 * (a + b)


def settling_velocity(d, rho_s, law):
    weight = (rho_s - REF_RHO) * G * math.pi * d**3 / 6  # submerged weight [N]
    # a stone sinking at speed v in still water: the drag on it points up
    return brentq(lambda v: vofdem.drag_force(0.0, 0.0, 0.0, -v, d, rho=REF_RHO, nu=REF_NU, law=law)[1] - weight,
                  1e-6, 20.0)


@pytest.mark.parametrize(
    "d, law, expected",
    [
        (0.048, vofdem.DragLaw.PAPER, 1.61),
        (0.048, vofdem.DragLaw.SCHILLER_NAUMANN, 1.53),
        (0.0159, vofdem.DragLaw.PAPER, 0.924),
        (0.0159, vofdem.DragLaw.SCHILLER_NAUMANN, 0.883),
        (0.001, vofdem.DragLaw.PAPER, 0.204),
        (0.001, vofdem.DragLaw.SCHILLER_NAUMANN, 0.155),
    ],
)
def test_settling_velocity_of_a_stone(d, law, expected):
    # REFERENCES.md gives 3 significant digits: agree to half a unit of the last one
    v = settling_velocity(d, 2650.0, law)
    assert v == pytest.approx(expected, abs=0.5 * 10 ** (math.floor(math.log10(expected)) - 2))


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "kwargs, pattern",
    [
        (dict(n=0.41, d=0.0), r"d = 0 is outside the allowed range \(0, inf\)"),
        (dict(n=0.41, d=-0.048), r"d = -0.048 is outside the allowed range \(0, inf\)"),
        (dict(n=0.0, d=0.048), r"n = 0 is outside the allowed range \(0, 1\]"),
        (dict(n=1.2, d=0.048), r"n = 1.2 is outside the allowed range \(0, 1\]"),
        (dict(n=-0.1, d=0.048), r"n = -0.1 is outside the allowed range \(0, 1\]"),
        (dict(n=float("nan"), d=0.048), r"n = nan is outside the allowed range \(0, 1\]"),
        (dict(n=0.41, d=float("nan")), r"d = nan is outside the allowed range \(0, inf\)"),
    ],
)
def test_porous_resistance_refuses_bad_input(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        vofdem.porous_resistance(0.1, 0.0, **kwargs)


def test_other_closures_refuse_bad_input():
    with pytest.raises(ValueError, match=r"u = nan is outside the allowed range \(finite values\)"):
        vofdem.porous_resistance(float("nan"), 0.0, 0.41, 0.048)
    with pytest.raises(ValueError, match=r"d = 0 is outside the allowed range \(0, inf\)"):
        vofdem.drag_force(0.1, 0.0, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match=r"d = -0.01 is outside the allowed range \(0, inf\)"):
        vofdem.drag_force(0.1, 0.0, 0.0, 0.0, -0.01)
    with pytest.raises(ValueError, match=r"wp = nan is outside"):
        vofdem.drag_force(0.1, 0.0, 0.0, float("nan"), 0.048)
    with pytest.raises(ValueError, match=r"re = 0 is outside the allowed range \(0, inf\)"):
        vofdem.drag_coefficient(0.0)
    with pytest.raises(ValueError, match=r"n = 1.5 is outside the allowed range \(0, 1\]"):
        vofdem.permeability(1.5, 0.048)
    # an array with one bad entry is refused as a whole
    with pytest.raises(ValueError, match=r"n = 0 is outside"):
        vofdem.porous_resistance(0.1, 0.0, np.array([0.4, 0.0]), 0.048)


# ---------------------------------------------------------------- properties
speeds = st.floats(-3.0, 3.0, allow_nan=False)
porosities = st.floats(0.05, 1.0)
diameters = st.floats(1e-3, 0.2)


@settings(max_examples=200, deadline=None)
@given(u=speeds, w=speeds, n=porosities, d=diameters)
def test_resistance_dissipates_and_is_odd(u, w, n, d):
    rx, rz = vofdem.porous_resistance(u, w, n, d)
    assert rx * u + rz * w <= 0.0
    mx, mz = vofdem.porous_resistance(-u, -w, n, d)
    assert (mx, mz) == (-rx, -rz)


@settings(max_examples=200, deadline=None)
@given(u=st.floats(1e-3, 3.0), n1=st.floats(0.05, 0.99), n2=st.floats(0.05, 0.99), d=diameters)
def test_resistance_falls_as_porosity_rises(u, n1, n2, d):
    lo, hi = sorted((n1, n2))
    # a looser matrix resists less
    assert -vofdem.porous_resistance(u, 0, hi, d)[0] <= -vofdem.porous_resistance(u, 0, lo, d)[0]


@settings(max_examples=200, deadline=None)
@given(u=speeds, w=speeds, up=speeds, wp=speeds, c=speeds, d=diameters,
       law=st.sampled_from([vofdem.DragLaw.PAPER, vofdem.DragLaw.SCHILLER_NAUMANN]))
def test_drag_depends_on_relative_velocity_along_it(u, w, up, wp, c, d, law):
    fx, fz = vofdem.drag_force(u, w, up, wp, d, law=law)
    vx, vz = u - up, w - wp
    assert fx * vx + fz * vz >= 0.0
    # same relative velocity, same force (to round-off of the subtraction)
    gx, gz = vofdem.drag_force(u + c, w, up + c, wp, d, law=law)
    scale = abs(fx) + abs(fz) + 1e-300
    assert abs(gx - fx) + abs(gz - fz) <= 1e-6 * scale + 1e-9
