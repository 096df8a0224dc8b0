"""Physical properties of the coupled equilibrium, and the certificate on every shipped case."""

import copy
import math

import numpy as np
import pytest
import yaml

from moorsolve import load_case, solve
from moorsolve.solve.assembly.cache import get_problem
from conftest import ROOT

CASES = ROOT / "cases"
SHIPPED = sorted(CASES.glob("*.yaml"))


def dock_data():
    return yaml.safe_load((CASES / "floating_dock.yaml").read_text())


def max_tension(result):
    return max((max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in result.legs),
               default=0.0)


@pytest.mark.parametrize("path", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_certificate_holds_on_every_shipped_case(path):
    result = solve(load_case(str(path)))
    assert result.converged and result.certificate.certified
    # The largest force carried: a line's tension or a contact's reaction (issue 15).
    scale = max([max_tension(result)] + [c["reaction_N"] for c in
                                         result.fenders + result.guides])
    assert result.certificate.force_N <= 1e-9 * scale
    # Recompute the body balance independently from the reported leg forces and loads.
    if result.body is not None:
        fx = sum(v[0] for v in result.loads.values())
        fy = sum(v[1] for v in result.loads.values())
        for leg in result.legs:
            dx, dy = (leg.fairlead[0] - leg.anchor[0], leg.fairlead[1] - leg.anchor[1])
            X = math.hypot(dx, dy)
            if "line_drag" in result.effects:
                # A line in a current also pulls its fairlead sideways (issue 4).
                fx += leg.fairlead_force[0]
                fy += leg.fairlead_force[1]
            else:
                fx -= leg.horizontal_tension_N * dx / X
                fy -= leg.horizontal_tension_N * dy / X
        # Fenders and pile guides push on the body (reaction and friction; issue 15).
        for contact in result.fenders + result.guides:
            fx += contact["force_N"][0]
            fy += contact["force_N"][1]
        case = load_case(str(path))
        if "surge" in case.body.free:
            assert abs(fx) <= 1e-8 * scale
        if "sway" in case.body.free:
            assert abs(fy) <= 1e-8 * scale


def test_dock_effects_are_what_the_case_declares():
    result = solve(load_case(str(CASES / "floating_dock.yaml")))
    assert result.effects == ["elastic", "seabed_contact", "wind", "current", "wave_drift"]
    data = dock_data()
    del data["environment"]["current"], data["environment"]["waves"]
    result = solve(load_case(data))
    assert result.effects == ["elastic", "seabed_contact", "wind"]
    assert set(result.loads) == {"wind"}


def test_scene_without_loads_builds_no_load_terms():
    data = dock_data()
    del data["body"]["loads"]
    case = load_case(data)
    problem = get_problem(case)
    assert problem.load_names == []
    assert "wind" not in problem.effects


def test_symmetric_layout_under_symmetric_load_stays_symmetric():
    data = dock_data()
    for key in ("wind", "current", "waves"):
        data["environment"][key]["toward_deg"] = 90.0     # straight across the dock
    data["body"]["loads"]["wind"]["centre"] = [0.0, 0.0]
    result = solve(load_case(data))
    assert result.body["x_m"] == pytest.approx(0.0, abs=1e-9)
    assert result.body["yaw_deg"] == pytest.approx(0.0, abs=1e-9)
    assert result.body["y_m"] > 0
    t = {leg.name: leg.fairlead_tension_N for leg in result.legs}
    # The layout is mirror-symmetric about x = 0: L1<->L4, L2<->L3, L5<->L12, ...
    for a, b in [("L1", "L4"), ("L2", "L3"), ("L5", "L12"), ("L6", "L11"),
                 ("L7", "L10"), ("L8", "L9")]:
        assert t[a] == pytest.approx(t[b], rel=1e-7)


def test_zero_load_on_symmetric_layout_gives_zero_offset():
    data = dock_data()
    for key in ("wind", "current", "waves"):
        del data["environment"][key]
    result = solve(load_case(data))
    assert math.hypot(result.body["x_m"], result.body["y_m"]) < 1e-9
    assert abs(result.body["yaw_deg"]) < 1e-9
    h = [leg.horizontal_tension_N for leg in result.legs]
    # Anchors are written to 0.1 mm; the stiff chains turn that into up to 3e-5 of H.
    assert np.ptp(h) <= 1e-4 * np.mean(h)
    # The chain length was chosen for about 372 kN of horizontal pretension (Hu & Tang).
    assert np.mean(h) == pytest.approx(372e3, rel=0.01)


def rotate(point, angle):
    c, s = math.cos(angle), math.sin(angle)
    x, y = point[0], point[1]
    return [c * x - s * y, s * x + c * y] + list(point[2:])


@pytest.mark.parametrize("angle_deg", [37.0, 90.0, -150.0])
def test_rotating_the_whole_case_rotates_the_result(angle_deg):
    # Loads that turn with the scene: a constant force, and a current load that acts
    # along the flow whatever the heading (Hu & Tang's form). The drag-area forms are tied
    # to the body axes, which a rotation of the coordinates does not carry.
    data = dock_data()
    for key in ("wind", "waves"):
        del data["environment"][key]
    data["environment"]["current"] = {"speed": 2.0, "toward_deg": 20.0}
    data["body"]["loads"] = {
        "current": {"model": "hu_tang", "wetted_area": 15000, "centre": [15.0, -4.0]},
        "force": [3.0e5, -1.0e5, 2.0e6]}
    base = solve(load_case(data))

    a = math.radians(angle_deg)
    turned = copy.deepcopy(data)
    for leg in turned["legs"]:
        leg["anchor"] = rotate(leg["anchor"], a)
        leg["fairlead"] = rotate(leg["fairlead"], a)
    turned["environment"]["current"]["toward_deg"] += angle_deg
    turned["body"]["loads"]["current"]["centre"] = rotate([15.0, -4.0], a)
    fx, fy, mz = data["body"]["loads"]["force"]
    turned["body"]["loads"]["force"] = rotate([fx, fy], a) + [mz]
    result = solve(load_case(turned))

    expected = rotate([base.body["x_m"], base.body["y_m"]], a)
    assert result.body["x_m"] == pytest.approx(expected[0], abs=1e-8)
    assert result.body["y_m"] == pytest.approx(expected[1], abs=1e-8)
    assert result.body["yaw_deg"] == pytest.approx(base.body["yaw_deg"], abs=1e-9)
    for a_leg, b_leg in zip(base.legs, result.legs):
        assert b_leg.fairlead_tension_N == pytest.approx(a_leg.fairlead_tension_N, rel=1e-8)


def test_renumbering_legs_changes_nothing():
    data = dock_data()
    base = solve(load_case(data))
    data["legs"] = data["legs"][::-1]
    result = solve(load_case(data))
    for name in ("L1", "L3", "L7", "L12"):
        assert result.leg(name).fairlead_tension_N == pytest.approx(
            base.leg(name).fairlead_tension_N, rel=1e-9)
    assert result.body["y_m"] == pytest.approx(base.body["y_m"], abs=1e-9)


def test_load_sharing_sums_to_the_applied_load():
    result = solve(load_case(str(CASES / "floating_dock.yaml")))
    total = np.sum([v[:2] for v in result.loads.values()], axis=0)
    pull = np.zeros(2)
    for leg in result.legs:
        d = np.subtract(leg.anchor[:2], leg.fairlead[:2])
        pull += leg.horizontal_tension_N * d / np.linalg.norm(d)
    assert pull == pytest.approx(-total, rel=1e-9)


def test_stiffer_lines_move_the_body_less():
    soft, stiff = dock_data(), dock_data()
    soft["line_types"]["chain81"]["ea"] = 2.0e8
    offset_soft = solve(load_case(soft)).body["y_m"]
    offset_stiff = solve(load_case(stiff)).body["y_m"]
    data = dock_data()
    del data["line_types"]["chain81"]["ea"]
    offset_rigid = solve(load_case(data)).body["y_m"]
    assert offset_soft > offset_stiff > offset_rigid > 0


def test_friction_relieves_the_anchor_not_the_fairlead_of_an_inextensible_line():
    data = dock_data()
    del data["line_types"]["chain81"]["ea"]
    plain = solve(load_case(data))
    data["environment"]["seabed"]["friction"] = 0.5
    rough = solve(load_case(data))
    assert "seabed_friction" in rough.effects
    for a, b in zip(plain.legs, rough.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-9)
        if a.grounded_length_m > 0:
            w = 0.13e3 * 9.80665
            expected = max(a.horizontal_tension_N - 0.5 * w * a.grounded_length_m, 0.0)
            assert b.anchor_horizontal_N == pytest.approx(expected, rel=1e-9, abs=1e-6)


def test_friction_shortens_the_elastic_stretch_on_the_seabed():
    data = dock_data()
    for key in ("wind", "current", "waves"):
        del data["environment"][key]
    data["line_types"]["chain81"]["ea"] = 5.0e7          # soft, so stretch matters
    plain = solve(load_case(data)).legs[0]
    data["environment"]["seabed"]["friction"] = 1.0
    rough = solve(load_case(data)).legs[0]
    # Less stretch on the seabed needs more tension to span the same distance.
    assert rough.horizontal_tension_N > plain.horizontal_tension_N
    assert rough.anchor_horizontal_N < plain.anchor_horizontal_N


def test_profile_ends_at_the_fairlead_and_starts_at_the_anchor():
    result = solve(load_case(str(CASES / "floating_dock.yaml")))
    for leg in result.legs:
        p = leg.profile
        assert (p["x_m"][0], p["y_m"][0], p["z_m"][0]) == pytest.approx(leg.anchor, abs=1e-9)
        assert (p["x_m"][-1], p["y_m"][-1], p["z_m"][-1]) == pytest.approx(
            leg.fairlead, abs=1e-6)
        assert p["tension_N"][-1] == pytest.approx(leg.fairlead_tension_N, rel=1e-9)
        if leg.touchdown_point is not None:
            assert leg.touchdown_from_anchor_m == pytest.approx(
                math.dist(leg.anchor, leg.touchdown_point), abs=1e-9)


def test_sealed_line_reports_wall_tension_and_flags_compression():
    # A deep sealed cable (Sukhanov, seed 000): light in water, large displaced weight.
    case = load_case({
        "environment": {"depth": 1000.0},
        "line_types": {"cable": {"weight_in_water": 50.0, "diameter": 0.3, "sealed": True,
                                 "ea": 1e9}},
        "legs": [{"name": "C", "anchor": [0, 0], "fairlead": [300.0, 0.0, 0.0],
                  "segments": [{"type": "cable", "length": 1200.0}]}]})
    result = solve(case)
    leg = result.legs[0]
    p = leg.profile
    rho_g_area = 1025 * 9.80665 * math.pi * 0.3**2 / 4
    depth_below = -np.asarray(p["z_m"])
    assert np.asarray(p["wall_tension_N"]) == pytest.approx(
        np.asarray(p["tension_N"]) - rho_g_area * depth_below, rel=1e-12, abs=1e-6)
    assert p["compression"] is True
    assert "wall_tension" in result.effects


def test_warm_start_reproduces_the_cold_solution():
    case = load_case(str(CASES / "floating_dock.yaml"))
    cold = solve(case)
    warm = solve(case, start=cold.state)
    assert warm.body["y_m"] == pytest.approx(cold.body["y_m"], abs=1e-10)
    assert warm.iterations <= cold.iterations
