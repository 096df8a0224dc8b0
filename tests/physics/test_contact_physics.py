"""The contact law on floats (moorsolve.physics.contact): complementarity, the fender curve and
its energy, Coulomb friction with an elastic stick."""

from __future__ import annotations


import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from moorsolve.physics.contact import (fender_energy, fender_reaction, fischer_burmeister,
                                       friction_force, natural_residual)

from hypothesis_budget import examples

TABLE = ([0.1, 0.3, 0.5, 0.6], [150e3, 600e3, 1000e3, 1300e3])


@settings(max_examples=examples(200), deadline=None)
@given(a=st.floats(-1e3, 1e3), b=st.floats(-1e3, 1e3))
def test_fischer_burmeister_marks_the_complementarity_set(a, b):
    """phi(a, b) = 0 iff a >= 0, b >= 0, a b = 0: between 0 and min(a, b) where both are
    non-negative (so zero exactly when one is), at most min(a, b) where either is negative
    (to round-off, and the 1e-150 floor under its square root)."""
    phi = float(fischer_burmeister(a, b))
    tiny = 1e-15 * max(abs(a), abs(b)) + 1e-150
    if a >= 0 and b >= 0:
        assert -tiny <= phi <= min(a, b) + tiny
    else:
        assert phi <= min(a, b) + tiny


def test_natural_residual():
    assert float(natural_residual(0.0, 0.3, 1e4)) == 0.0          # open, no reaction
    assert float(natural_residual(5e3, 0.0, 1e4)) == 0.0          # closed, pushing
    assert float(natural_residual(5e3, 0.1, 1e4)) == 1e3          # a reaction across a gap
    assert float(natural_residual(-2e3, 0.0, 1e4)) == 2e3         # a pulling contact


@pytest.mark.parametrize("d", [0.0, 0.05, 0.1, 0.2, 0.45, 0.6, 0.7])
def test_fender_reaction_interpolates_the_makers_rows(d):
    """Linear between (0, 0) and the rows; beyond the last row the last slope continues."""
    ds, rs = [0.0] + TABLE[0], [0.0] + TABLE[1]
    expected = np.interp(d, ds, rs) if d <= ds[-1] else rs[-1] + (d - ds[-1]) * (
        (rs[-1] - rs[-2]) / (ds[-1] - ds[-2]))
    assert float(fender_reaction(d, *TABLE)) == pytest.approx(expected, rel=1e-14)
    assert float(fender_reaction(-0.2, *TABLE)) == 0.0                # not compressed


@pytest.mark.parametrize("d", [0.05, 0.3, 0.45, 0.65])
def test_fender_energy_is_the_area_under_the_curve(d):
    grid = np.linspace(0.0, d, 20001)
    area = np.trapezoid([float(fender_reaction(x, *TABLE)) for x in grid], grid)
    assert float(fender_energy(d, *TABLE)) == pytest.approx(area, rel=1e-7)


def test_friction_sticks_elastically_then_slips_against_the_slip():
    mu, lam, delta = 0.3, 1e5, 1e-3
    stick = np.asarray(friction_force(np.array([0.0, 4e-4, 0.0]), lam, mu, delta)).ravel()
    assert stick == pytest.approx([0.0, -mu * lam * 0.4, 0.0], rel=1e-14)
    slip = np.asarray(friction_force(np.array([3e-3, 4e-3, 0.0]), lam, mu, delta)).ravel()
    assert np.linalg.norm(slip) == pytest.approx(mu * lam, rel=1e-14)
    assert slip == pytest.approx(-mu * lam * np.array([0.6, 0.8, 0.0]), rel=1e-14)
    # No reaction, no friction, whatever the slip.
    assert np.all(np.asarray(friction_force(np.array([1.0, 0.0, 0.0]), -5.0, mu,
                                            delta)) == 0)
