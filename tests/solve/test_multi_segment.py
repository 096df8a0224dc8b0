"""Multi-segment legs with clump weights and buoys at the joints (issue 4).

Theory: Merkin 1980 (seed 004) section 2.2 (a thread of piecewise constant weight: the
horizontal tension is the same in every part, the vertical tension grows by w per metre)
and section 3.3 (a concentrated force makes the vertical tension jump by that force). The
independent checks below integrate those equations numerically (scipy) from the solved
end forces and require the line to land on its fairlead.
"""

import copy
import math

import numpy as np
import pytest
import yaml
from scipy.integrate import solve_ivp

from moorsolve import load_case, solve
from moorsolve.physics.catenary import LegKind
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.solve.assembly.layout import ENV_PARAMS, LEG_PARAMS, SEABED_PARAMS, BODY_PARAMS
from moorsolve.solve.assembly.prepared import parameter_vector
from moorsolve.solve.lines.line_kinds import MultiLegKind
from conftest import ROOT

CASES = ROOT / "cases"


def vida():
    return yaml.safe_load((CASES / "buoy_vida.yaml").read_text())


def with_segments(data, segments):
    data = copy.deepcopy(data)
    for leg in data["legs"]:
        leg["segments"] = copy.deepcopy(segments)
    return data


def single_leg(segments, *, depth=100.0, fairlead=(400.0, 0.0, -5.0), friction=0.0):
    return {"environment": {"depth": depth, "seabed": {"friction": friction}},
            "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5e8},
                           "poly": {"weight_in_water": 50.0, "ea": 5e7},
                           "rope": {"weight_in_water": 0.0, "ea": 2e7}},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": list(fairlead),
                      "segments": segments}]}


def chain_poly_chain(weight):
    return single_leg([{"type": "chain", "length": 150}, {"clump": {"weight": weight}},
                       {"type": "poly", "length": 250}, {"type": "chain", "length": 60}])


# ---- a split leg is the same leg ------------------------------------------------------


@pytest.mark.parametrize("split", [(20.0, 30.0), (40.0, 10.0), (10.0, 25.0, 15.0)])
def test_split_leg_equals_single_segment_leg(split):
    """Vida under bora: chains cut in 2 or 3 identical pieces give the one-piece answer."""
    one = solve(load_case(vida()))
    segments = [{"type": "chain", "length": s} for s in split]
    many = solve(load_case(with_segments(vida(), segments)))
    assert many.converged
    # Both are certified to 1e-9 of the largest tension: agree to a few times that.
    scale = max(leg.fairlead_tension_N for leg in one.legs)
    for a, b in zip(one.legs, many.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, abs=3e-9 * scale)
        assert b.anchor_tension_N == pytest.approx(a.anchor_tension_N, abs=3e-9 * scale)
        assert b.grounded_length_m == pytest.approx(a.grounded_length_m, abs=1e-6)
        assert b.touchdown_from_anchor_m == pytest.approx(a.touchdown_from_anchor_m,
                                                          abs=1e-6)
        assert b.slack == a.slack
        assert len(b.segments) == len(split) and len(b.joints) == len(split) - 1
    assert many.body["x_m"] == pytest.approx(one.body["x_m"], abs=1e-7)
    assert many.body["y_m"] == pytest.approx(one.body["y_m"], abs=1e-7)
    assert "multi_segment" in many.effects


def test_split_leg_with_friction_equals_single_segment_leg():
    """Friction on the anchor segment: touchdown inside it gives the one-piece answer."""
    one = solve(load_case(single_leg([{"type": "chain", "length": 460}], friction=0.6)))
    two = solve(load_case(single_leg([{"type": "chain", "length": 360},
                                      {"type": "chain", "length": 100}], friction=0.6)))
    a, b = one.legs[0], two.legs[0]
    assert 0 < a.grounded_length_m < 360  # the touchdown is in the anchor segment
    assert b.anchor_tension_N == pytest.approx(a.anchor_tension_N, rel=1e-9)
    assert b.anchor_tension_N < 0.9 * b.horizontal_tension_N
    assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-9)


def test_zero_clump_changes_nothing():
    plain = solve(load_case(with_segments(vida(), [{"type": "chain", "length": 20},
                                                   {"type": "chain", "length": 30}])))
    zero = solve(load_case(with_segments(vida(), [{"type": "chain", "length": 20},
                                                  {"clump": {"mass": 0.0, "volume": 0.0}},
                                                  {"type": "chain", "length": 30}])))
    for a, b in zip(plain.legs, zero.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-12)
        assert b.joints[0]["position_m"] == pytest.approx(a.joints[0]["position_m"],
                                                          rel=1e-9, abs=1e-9)
    assert "clump_weight" not in zero.effects and "buoy" not in zero.effects


# ---- clumps and buoys -------------------------------------------------------------------


def test_clump_resting_on_the_seabed_is_carried_by_it():
    """A clump on a grounded joint: the seabed carries exactly its weight, tensions unchanged."""
    bare = solve(load_case(chain_poly_chain(0.0))).legs[0]
    heavy = solve(load_case(chain_poly_chain(1e5)))
    leg = heavy.legs[0]
    joint = leg.joints[0]
    assert joint["on_seabed"] and joint["height_above_seabed_m"] == 0.0
    assert joint["seabed_reaction_N"] == pytest.approx(1e5, rel=1e-9)
    assert leg.fairlead_tension_N == pytest.approx(bare.fairlead_tension_N, rel=1e-9)
    assert "clump_weight" in heavy.effects


def test_buoy_lifts_the_joint_and_the_grounded_length_responds():
    grounded, heights, tensions = [], [], []
    for weight in (0.0, -2e4, -6e4, -1.5e5):
        res = solve(load_case(chain_poly_chain(weight)))
        leg = res.legs[0]
        grounded.append(leg.grounded_length_m)
        heights.append(leg.joints[0]["height_above_seabed_m"])
        tensions.append(leg.fairlead_tension_N)
        # The joint's vertical balance: what the segments pull plus the buoy's lift.
        below, above = leg.segments[0], leg.segments[1]
        assert above["bottom_vertical_N"] - below["top_vertical_N"] - weight \
            + leg.joints[0]["seabed_reaction_N"] == pytest.approx(0.0, abs=1e-6 * 1e5)
    assert heights[0] == 0.0 and heights[1] > 0.0
    assert np.all(np.diff(heights) > 0)
    assert np.all(np.diff(grounded) < 0)
    assert np.all(np.diff(tensions) > 0)  # lifting the chain off the seabed stiffens the leg
    assert "buoy" in res.effects


def _shoot(leg_result, segments, clumps, H, VA, ea):
    """Integrate the thread equations from the anchor (Merkin 2.2, 3.3); suspended legs."""
    x, z, V = 0.0, 0.0, VA
    for k, (L, w) in enumerate(segments):
        def rhs(s, y, w=w):
            T = math.hypot(H, y[2])
            stretch = 1 + T / ea
            return [H / T * stretch, y[2] / T * stretch, w]
        sol = solve_ivp(rhs, (0, L), [x, z, V], rtol=1e-11, atol=1e-9)
        x, z, V = sol.y[:, -1]
        if k < len(clumps):
            V += clumps[k]  # the line above carries the clump (a buoy, negative, relieves it)
    return x, z, V


def test_suspended_leg_with_buoy_and_clump_matches_integrated_thread():
    """Anchor uplift, a buoy and a clump: the thread equations land on the fairlead."""
    data = single_leg([{"type": "chain", "length": 60}, {"clump": {"weight": -9e4}},
                       {"type": "chain", "length": 80}, {"clump": {"weight": 2e4}},
                       {"type": "chain", "length": 30}], depth=100.0,
                      fairlead=(150.0, 0.0, -5.0))
    res = solve(load_case(data))
    leg = res.legs[0]
    assert leg.uplift and leg.grounded_length_m == 0.0
    x, z, V = _shoot(leg, [(60, 1000.0), (80, 1000.0), (30, 1000.0)], [-9e4, 2e4],
                     leg.horizontal_tension_N, leg.anchor_vertical_N, 5e8)
    assert x == pytest.approx(150.0, abs=1e-6)
    assert z == pytest.approx(95.0, abs=1e-6)
    assert V == pytest.approx(leg.fairlead_vertical_N, rel=1e-8)


def test_s_shape_buoy_then_touchdown_again():
    """A buoy lifts the line, which sags back onto the seabed and rises to the fairlead."""
    data = single_leg([{"type": "chain", "length": 100}, {"clump": {"weight": -1.2e5}},
                       {"type": "chain", "length": 250}], depth=50.0,
                      fairlead=(300.0, 0.0, 0.0))
    leg = solve(load_case(data)).legs[0]
    assert leg.joints[0]["height_above_seabed_m"] > 10.0
    assert leg.segments[1]["grounded_length_m"] > 50.0  # the U under the buoy
    z = leg.profile["z_m"]
    assert np.min(z) >= -50.0 - 1e-9
    # The profile is continuous and reaches the fairlead.
    assert leg.profile["x_m"][-1] == pytest.approx(300.0, abs=1e-6)
    assert z[-1] == pytest.approx(0.0, abs=1e-6)
    assert np.max(np.hypot(np.diff(leg.profile["x_m"]), np.diff(z))) < 10.0


@pytest.mark.parametrize("buoy", [-1e5, -3e4])
def test_both_ends_on_the_seabed_buoy_arch(buoy):
    """Anchor and fairlead both on the seabed; a buoy arches the middle of the leg."""
    data = single_leg([{"type": "chain", "length": 100}, {"clump": {"weight": buoy}},
                       {"type": "chain", "length": 250}], depth=50.0,
                      fairlead=(300.0, 0.0, -50.0))
    res = solve(load_case(data))
    leg = res.legs[0]
    assert res.certificate.relative < 1e-9
    h = leg.joints[0]["height_above_seabed_m"]
    assert h > 0
    # The lifted chain hangs symmetric-ish: its weight equals the buoy's lift.
    suspended = 350.0 - leg.grounded_length_m
    assert suspended * 1000.0 == pytest.approx(-buoy, rel=1e-6)
    assert np.min(leg.profile["z_m"]) >= -50.0 - 1e-9
    assert leg.profile["z_m"][-1] == pytest.approx(-50.0, abs=1e-6)


def test_weightless_rope_segment_is_straight():
    """A neutral rope between a buoyed joint and the fairlead stays straight."""
    data = single_leg([{"type": "chain", "length": 120}, {"clump": {"weight": -3e4}},
                       {"type": "rope", "length": 300}], depth=100.0)
    leg = solve(load_case(data)).legs[0]
    seg = leg.segments[1]
    assert seg["top_tension_N"] == pytest.approx(seg["bottom_tension_N"], rel=1e-9)
    assert "neutral_line" in solve(load_case(data)).effects


# ---- the core problem is untouched ------------------------------------------------------


@pytest.mark.parametrize("name", ["floating_dock", "buoy_vida", "ship_97m"])
def test_scenes_without_joints_build_the_core_problem(name):
    case = load_case(str(CASES / f"{name}.yaml"))
    problem = get_problem(case)
    assert problem.n_x == problem.n_q + 2 * len(case.legs)
    # Environment, lines, the seabed and the body: no segment parameters.
    n_body = len(BODY_PARAMS) * len(case.bodies)
    assert problem.n_p == (len(ENV_PARAMS) + len(LEG_PARAMS) * len(case.legs)
                           + len(SEABED_PARAMS) + n_body)
    assert all(isinstance(k.block, LegKind) for k in problem.kinds)
    assert problem.leg_offsets == [problem.n_q + 2 * i for i in range(len(case.legs))]
    assert len(parameter_vector(case)) == problem.n_p
    assert problem.residual.size1_out(0) == problem.n_x
    assert "multi_segment" not in problem.effects


def test_multi_segment_problem_layout():
    case = load_case(with_segments(vida(), [{"type": "chain", "length": 20},
                                            {"clump": {"weight": 500}},
                                            {"type": "chain", "length": 30}]))
    problem = get_problem(case)
    kind = problem.kinds[0].block
    assert isinstance(kind, MultiLegKind) and kind.n_joints == 1
    # Per leg: u, V, and per joint its distance and signed force.
    assert problem.n_x == problem.n_q + 3 * 4
    assert problem.residual.size1_out(0) == problem.n_x
    assert len(parameter_vector(case)) == problem.n_p


def test_newton_fast_path_solves_multi_segment_legs():
    case = load_case(chain_poly_chain(-6e4))
    ref = solve(case)
    fast = solve(case, solver="newton")
    assert fast.legs[0].fairlead_tension_N == pytest.approx(ref.legs[0].fairlead_tension_N,
                                                            rel=1e-9)
