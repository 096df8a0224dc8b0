"""Wall tension versus effective tension of a sealed line (REFERENCE.md section 2).

Published tier: Sukhanov's illustration (A. A. Sukhanov, "Catenary in water", seed 000,
eq. (25); numbers as given in REFERENCE.md section 2), then physical properties.
"""

import math

import casadi
import numpy
import pytest

from moorsolve.constants import SEAWATER_DENSITY, STANDARD_GRAVITY
from moorsolve.physics.wall_tension import (outer_area, sukhanov_wall_tension,
                                            wall_tension)

KGF = STANDARD_GRAVITY  # [N]

# Sukhanov's illustration in kgf and m: weight in air q_c = 30 kgf/m, displaced water
# q_h = 5 kgf/m, catenary parameter a = 80 m, vertex 40 m below the surface.
Q_AIR = 30.0
Q_DISPLACED = 5.0
A = 80.0
VERTEX_DEPTH = 40.0
# The same line in SI: q_h = rho g A_o, so A_o = 5 kgf/m / (rho g).
OUTER_AREA = Q_DISPLACED * KGF / (SEAWATER_DENSITY * STANDARD_GRAVITY)
OUTER_DIAMETER = math.sqrt(4.0 * OUTER_AREA / math.pi)


def effective_tension_kgf(x):
    """T_eff = (q_c - q_h) a ch(x/a) along the catenary (Sukhanov eqs. (14), (24))."""
    return (Q_AIR - Q_DISPLACED) * A * numpy.cosh(numpy.asarray(x) / A)


def depth_m(x):
    """Depth of the catenary point below the surface, h - a (ch(x/a) - 1) (eq. (20))."""
    return VERTEX_DEPTH - A * (numpy.cosh(numpy.asarray(x) / A) - 1.0)


def wall_tension_kgf(x):
    return wall_tension(effective_tension_kgf(x) * KGF, depth_m(x), OUTER_DIAMETER,
                        SEAWATER_DENSITY, STANDARD_GRAVITY) / KGF


X_SURFACE = A * math.acosh(1.0 + VERTEX_DEPTH / A)  # where the catenary meets the surface


# ---- published ------------------------------------------------------------------------------

def test_sukhanov_illustration_at_vertex():
    # REFERENCE.md section 2 (Sukhanov, seed 000): T_eff(vertex) = 2000, T_wall(vertex) = 1800.
    assert effective_tension_kgf(0.0) == pytest.approx(2000.0, rel=1e-12)
    assert wall_tension_kgf(0.0) == pytest.approx(1800.0, rel=1e-12)
    assert sukhanov_wall_tension(Q_AIR, Q_DISPLACED, A, VERTEX_DEPTH, 0.0) == \
        pytest.approx(1800.0, rel=1e-12)


def test_sukhanov_illustration_at_surface():
    # Both tensions are 3000 where the line reaches the surface (depth 0, ch(x/a) = 1.5).
    assert depth_m(X_SURFACE) == pytest.approx(0.0, abs=1e-9)
    assert effective_tension_kgf(X_SURFACE) == pytest.approx(3000.0, rel=1e-12)
    assert wall_tension_kgf(X_SURFACE) == pytest.approx(3000.0, rel=1e-12)
    assert sukhanov_wall_tension(Q_AIR, Q_DISPLACED, A, VERTEX_DEPTH, X_SURFACE) == \
        pytest.approx(3000.0, rel=1e-12)


def test_matches_sukhanov_closed_form_along_the_line():
    x = numpy.linspace(-X_SURFACE, X_SURFACE, 41)
    closed = sukhanov_wall_tension(Q_AIR, Q_DISPLACED, A, VERTEX_DEPTH, x)
    numpy.testing.assert_allclose(wall_tension_kgf(x), closed, rtol=1e-12)


# ---- properties -----------------------------------------------------------------------------

def test_outer_area():
    assert outer_area(0.2) == pytest.approx(math.pi * 0.01, rel=1e-15)


def test_equal_at_surface_and_lower_by_hydrostatic_term_below():
    t_eff, d, rho, g = 5.0e5, 0.15, 1025.0, 9.81
    assert wall_tension(t_eff, 0.0, d, rho, g) == t_eff
    depth = 300.0
    expected = t_eff - rho * g * math.pi * d ** 2 / 4.0 * depth
    assert wall_tension(t_eff, depth, d, rho, g) == pytest.approx(expected, rel=1e-14)


def test_no_hydrostatic_term_above_the_water():
    assert wall_tension(1.0e4, -5.0, 0.2, 1025.0, 9.81) == 1.0e4


def test_compressive_at_depth_while_effective_tension_positive():
    # Sukhanov's warning: the same line with its vertex 500 m deep has a compressed wall there.
    deep = 500.0
    t_wall = sukhanov_wall_tension(Q_AIR, Q_DISPLACED, A, deep, 0.0)
    assert effective_tension_kgf(0.0) > 0.0
    assert t_wall == pytest.approx(Q_AIR * A - Q_DISPLACED * (deep + A), rel=1e-12)
    assert t_wall < 0.0
    t_wall_si = wall_tension(effective_tension_kgf(0.0) * KGF, deep, OUTER_DIAMETER,
                             SEAWATER_DENSITY, STANDARD_GRAVITY)
    assert t_wall_si / KGF == pytest.approx(t_wall, rel=1e-12)


def test_numpy_arrays_elementwise():
    t_eff = numpy.array([1.0e5, 2.0e5, 3.0e5])
    depth = numpy.array([0.0, 10.0, 20.0])
    out = wall_tension(t_eff, depth, 0.1, 1000.0, 10.0)
    assert isinstance(out, numpy.ndarray)
    numpy.testing.assert_allclose(out, t_eff - 1000.0 * 10.0 * math.pi * 0.01 / 4.0 * depth,
                                  rtol=1e-14)


def test_symbolic_equals_float():
    t_sym, d_sym = casadi.SX.sym("t"), casadi.SX.sym("d")
    f = casadi.Function("wall", [t_sym, d_sym],
                        [wall_tension(t_sym, d_sym, 0.3, 1025.0, 9.80665)])
    for t_eff, depth in [(1.0e6, 0.0), (1.0e6, 123.4), (2.0e5, -3.0)]:
        assert float(f(t_eff, depth)) == pytest.approx(
            wall_tension(t_eff, depth, 0.3, 1025.0, 9.80665), rel=1e-14)
