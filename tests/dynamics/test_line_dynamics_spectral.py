"""The spectral driver of the line dynamics (moorsolve.dynamics.line_spectral): moments,
the characteristic dynamic tension by hand, and the response against independent paths."""

from __future__ import annotations

import math

import numpy as np
import pytest

import moorsolve
from moorsolve.dynamics.line_dynamics import line_response
from moorsolve.dynamics.line_model import line_model
from moorsolve.dynamics.line_spectral import (characteristic_dynamic_tension,
                                              spectral_statistics, tension_statistics)
from moorsolve.errors import CaseError
from test_line_dynamics import AZIMUTH, FAIRLEAD, chain_case

OUTWARD = np.array([math.cos(AZIMUTH), math.sin(AZIMUTH), 0.0])


def pierson_moskowitz(omega, hs, tp):
    """S(omega) = 5/16 Hs^2 wp^4 omega^-5 exp(-5/4 (wp/omega)^4) [m^2 s/rad]
    (DNV-RP-C205 (2010) eq. 3.5.5.1)."""
    wp = 2 * math.pi / tp
    return 5 / 16 * hs ** 2 * wp ** 4 / omega ** 5 * np.exp(-1.25 * (wp / omega) ** 4)


def test_moments_of_a_pierson_moskowitz_sea_match_the_closed_form():
    """For S = A w^-5 exp(-B w^-4): m0 = A/(4B) = Hs^2/16 and m2 = A sqrt(pi)/(4 sqrt B),
    so sigma = Hs/4 and T_z = Tp (5 pi / 4)^(-1/4) = 0.7104 Tp."""
    omega = np.linspace(0.05, 60.0, 400_000)
    sigma, tz = spectral_statistics(omega, pierson_moskowitz(omega, 3.0, 12.0))
    assert sigma == pytest.approx(3.0 / 4, rel=1e-4)
    assert tz == pytest.approx(12.0 * (1.25 * math.pi) ** -0.25, rel=1e-3)


def test_characteristic_dynamic_tension_by_hand():
    """sigma 100 kN, T_z 10 s, 3 hours: N = 1080, ln N = 6.984716, T_dyn = 1e5 x
    sqrt(13.969432) = 373.757 kN."""
    t_dyn, cycles = characteristic_dynamic_tension(1.0e5, 10.0, 10800.0)
    assert cycles == pytest.approx(1080.0, rel=1e-12)
    assert t_dyn == pytest.approx(373_757.0, rel=2e-6)
    assert characteristic_dynamic_tension(0.0, float("nan")) == (0.0, 0.0)
    with pytest.raises(CaseError, match="duration"):
        characteristic_dynamic_tension(1.0e5, 10.0, 15.0)


@pytest.fixture(scope="module")
def chain():
    case = moorsolve.load_case(chain_case(FAIRLEAD, span=300.0, length=320.0))
    return case, moorsolve.solve(case)


def test_without_drag_the_statistics_are_those_of_the_harmonic_transfer_function(chain):
    """Without drag the line is linear: sigma and T_z of the end tensions equal those of
    the transfer functions solved one frequency at a time (an independent path through
    the solver) times the wave spectrum, integrated here by hand."""
    case, result = chain
    model = line_model(case, result, "L1", n_elements=40, drag_normal=0.0)
    omega = np.linspace(0.25, 1.5, 26)
    S = pierson_moskowitz(omega, 2.0, 10.0)
    rao = np.outer(0.5 * OUTWARD, np.ones_like(omega)) + 0j
    stats = tension_statistics(model, omega, rao, S)
    H = np.array([line_response(model, [w], rao[:, [i]]).tension_b[0]
                  for i, w in enumerate(omega)])
    ST = np.abs(H) ** 2 * S
    m0 = np.sum(0.5 * (ST[1:] + ST[:-1]) * np.diff(omega))
    m2 = np.sum(0.5 * ((omega ** 2 * ST)[1:] + (omega ** 2 * ST)[:-1]) * np.diff(omega))
    assert stats.fairlead.sigma_N == pytest.approx(math.sqrt(m0), rel=1e-9)
    assert stats.fairlead.tz_s == pytest.approx(2 * math.pi * math.sqrt(m0 / m2), rel=1e-9)
    N = 10800.0 / stats.fairlead.tz_s
    assert stats.fairlead.t_dyn_N == pytest.approx(math.sqrt(m0 * 2 * math.log(N)),
                                                   rel=1e-9)


def test_converged_drag_is_borgmans_linearisation_of_the_returned_motion(chain):
    """Recomputed from the returned node motions, sqrt(8/pi) sigma_v 0.5 rho Cd d l equals
    the damping the solve converged to (the fixed point of the iteration)."""
    case, result = chain
    model = line_model(case, result, "L1", n_elements=40)
    omega = np.linspace(0.25, 1.5, 26)
    S = pierson_moskowitz(omega, 2.0, 10.0)
    rao = np.outer(0.5 * OUTWARD, np.ones_like(omega)) + 0j
    stats = tension_statistics(model, omega, rao, S, tolerance=1e-8)
    r = stats.response
    v = 1j * omega[:, None, None] * r.motion
    t = model.tangent
    vn = v - np.einsum("wni,ni->wn", v, t)[..., None] * t
    var = np.trapezoid(np.sum(np.abs(vn) ** 2, -1) * S[:, None], omega, axis=0)
    expected = math.sqrt(8 / math.pi) * np.sqrt(var) * model.drag_normal
    np.testing.assert_allclose(r.damping_normal, expected, rtol=1e-6,
                               atol=1e-9 * expected.max())
    assert expected.max() > 0
