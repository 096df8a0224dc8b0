"""A current that turns and reverses with depth (issue 20): the profile form and the
lumped-node line drag that uses it.

Rows ``[z, speed]`` carry a signed speed along the current's heading (negative: the other
way); rows ``[z, speed, toward_deg]`` a heading each, the velocity vectors interpolated. A
taut line in a current reversing with depth bends into an S: its fairlead forces (from the
lumped-node line, Richardson on 40 and 80 elements) integrated back down the line's own ODE
(``tests/reference_ode.py``, no shared code) land on the anchor.
"""

from __future__ import annotations

import math


import numpy as np
import pytest
from reference_ode import integrate_in_current

from moorsolve import CaseError, load_case, solve

SIGNED = [[-50.0, -0.8], [-20.0, 0.0], [0.0, 1.2]]
HEADED = [[-50.0, 0.8, 180.0], [-20.0, 0.0, 0.0], [0.0, 1.2, 0.0]]


def line_in_current(profile, n=20, toward=0.0):
    return load_case({
        "environment": {"depth": 50.0,
                        "current": {"speed": 1.0, "toward_deg": toward, "profile": profile}},
        "line_types": {"riser": {"weight_in_water": 50.0, "ea": 1e6, "diameter": 0.05,
                                 "drag": {"normal": 1.2, "tangential": 0.02}}},
        # A tether stretched straight up from the anchor to a fixed point (2 kN pretension).
        "legs": [{"name": "R", "anchor": [0.0, 0.0], "fairlead": [0.0, 0.0, 0.0],
                  "segments": [{"type": "riser", "length": 49.9}]}],
        "solver": {"line_elements": n}})


def test_signed_rows_and_headed_rows_are_the_same_current():
    a = solve(line_in_current(SIGNED)).legs[0]
    b = solve(line_in_current(HEADED)).legs[0]
    assert a.fairlead_tension_N == pytest.approx(b.fairlead_tension_N, rel=1e-12)
    np.testing.assert_allclose(a.profile["x_m"], b.profile["x_m"], atol=1e-9)


def test_reversing_current_against_the_line_ode():
    def fairlead_forces(n):
        leg = solve(line_in_current(SIGNED, n)).legs[0]
        fx, _, fz = leg.fairlead_force            # the line's pull on the fairlead
        return np.array([-fx, -fz]), leg
    (coarse, _), (fine, leg) = fairlead_forces(40), fairlead_forces(80)
    H, V = fine + (fine - coarse) / 3            # second order (tests/solve/test_line_drag.py)
    # The S: the upper line pushed downstream (+x), the lower part upstream (-x).
    x, z = leg.profile["x_m"], leg.profile["z_m"]
    assert np.max(x[z > -15]) > 0.05 and np.min(x[z < -35]) < -0.02
    assert np.max(np.abs(leg.profile["y_m"])) < 1e-9

    def velocity(zz):
        return float(np.interp(zz, [r[0] for r in SIGNED], [r[1] for r in SIGNED]))
    ref = integrate_in_current(H=H, V=V, L=49.9, w=50.0, ea=1e6, diameter=0.05, rho=1025.0,
                               normal=1.2, tangential=0.02, velocity=velocity, z_fairlead=0.0)
    assert ref["X"] == pytest.approx(0.0, abs=2e-5)
    assert ref["Z"] == pytest.approx(50.0, abs=2e-5)


def test_a_current_turning_with_depth_pushes_each_part_its_way():
    """Toward +y at the surface, toward +x at the seabed: the line leaves every vertical
    plane, its upper part pushed toward +y, its lower part toward +x."""
    turning = [[-50.0, 0.8, 0.0], [0.0, 0.8, 90.0]]
    leg = solve(line_in_current(turning)).legs[0]
    x, y, z = (np.asarray(leg.profile[k]) for k in ("x_m", "y_m", "z_m"))
    upper, lower = z > -15.0, (z < -35.0) & (z > -49.0)
    # The deflection's heading turns from near +x low down to near +y high up.
    low = math.degrees(math.atan2(np.mean(y[lower]), np.mean(x[lower])))
    high = math.degrees(math.atan2(np.mean(y[upper]), np.mean(x[upper])))
    assert low < 45.0 < high and high - low > 20.0, (low, high)
    assert leg.fairlead_force[1] > 0               # the line pulls its top toward +y


def test_profile_forms_are_validated():
    with pytest.raises(CaseError, match=r"current.profile\[1\]"):
        line_in_current([[-50.0, 0.8, 0.0], [0.0, 0.8]])
    with pytest.raises(CaseError, match=r"profile\[0\]\[1\]"):
        line_in_current([[-50.0, -0.8, 0.0], [0.0, 0.8, 90.0]])
