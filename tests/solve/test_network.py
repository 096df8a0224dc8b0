"""The scene as a network: bodies in six DOFs, free points and bridles, several bodies,
stability and weathervaning, threads (issue 14).

Published values first (the OC3 spar's mooring stiffness), then the peer (MoorPy, where
installed) on six-DOF, bridled and multi-body scenes, then physical properties.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import moorsolve
import moorsolve.checks
from moorsolve import CaseError, load_case, solve
from moorsolve.model import BodyLoads
from moorsolve.model.build_network import rotation
from moorsolve.studies.stiffness import mooring_force

from conftest import CASES

SPAR = CASES / "oc3_spar.yaml"
SHIP = CASES / "turret_ship.yaml"


def spar_with_force(force6):
    case = load_case(SPAR)
    body = dataclasses.replace(case.bodies[0], loads=BodyLoads(force=tuple(force6)))
    return dataclasses.replace(case, bodies=(body,))


# ---- published: OC3 Hywind mooring stiffness ------------------------------------------


def test_oc3_spar_mooring_stiffness_matches_the_oc3_definition():
    """Jonkman (2010), "Definition of the Floating System for Phase IV of OC3",
    NREL/TP-500-47535, section 5 (mooring system): linearized mooring restoring about the
    undisplaced position, without the crow's-foot yaw spring: K11 = 41,180 N/m,
    K15 = -2,821,000 N, K33 = 11,940 N/m, K44 = K55 = 311,100,000 N m/rad,
    K66 = 11,560,000 N m/rad. The report's own linearization (FAST) agrees with the exact
    derivative to 0.2 %; MoorPy's analytic stiffness agrees with ours to 1e-5 (below)."""
    K = moorsolve.stiffness(solve(load_case(SPAR), tol=1e-12))
    assert K[0, 0] == pytest.approx(41_180, rel=1e-3)
    assert K[1, 1] == pytest.approx(41_180, rel=1e-3)
    assert K[2, 2] == pytest.approx(11_940, rel=1e-3)
    assert K[5, 5] == pytest.approx(11_560_000, rel=1e-3)
    assert K[3, 3] == pytest.approx(311_100_000, rel=2e-3)
    assert K[4, 4] == pytest.approx(311_100_000, rel=2e-3)
    assert K[0, 4] == pytest.approx(-2_821_000, rel=3e-3)
    # A spar's mooring couples surge with pitch (REFERENCE.md section 7): K15 < 0, K24 > 0.
    assert K[0, 4] < 0 < K[1, 3]
    assert np.max(np.abs(K - K.T)) < 1e-6 * np.max(np.abs(K))


def test_six_dof_stiffness_matches_finite_differences_of_the_mooring_force():
    case = spar_with_force((6e5, -2e5, 0, 0, 0, 1e6))
    result = solve(case, tol=1e-12)
    K = moorsolve.stiffness(result)
    off = result.bodies[0]["offset"]
    base = np.array([off["x_m"], off["y_m"], off["z_m"], off["roll_deg"], off["pitch_deg"],
                     off["yaw_deg"]])
    R0 = rotation(*np.radians(base[3:]))

    def turned(axis, angle):
        """The offset with the body turned by ``angle`` [rad] about a global axis."""
        c, s = math.cos(angle), math.sin(angle)
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        G = np.eye(3)
        G[i, i] = G[j, j] = c
        G[i, j], G[j, i] = -s, s
        R = G @ R0
        euler = (math.atan2(R[2, 1], R[2, 2]), -math.asin(R[2, 0]), math.atan2(R[1, 0], R[0, 0]))
        return np.concatenate([base[:3], np.degrees(euler)])

    fd = np.zeros((6, 6))
    for j in range(6):
        if j < 3:
            h = 1e-3                          # m
            e = np.zeros(6)
            e[j] = h
            plus, minus = base + e, base - e
        else:
            h = 1e-6                          # rad about the global axes
            plus, minus = turned(j - 3, h), turned(j - 3, -h)
        fp, _ = mooring_force(case, plus)
        fm, _ = mooring_force(case, minus)
        fd[:, j] = -(fp - fm) / (2 * h)
    scale = np.sqrt(np.outer(np.abs(np.diag(K)), np.abs(np.diag(K))))
    assert np.max(np.abs(K - fd) / scale) < 1e-5


# ---- peer: MoorPy on six-DOF, bridled and multi-body scenes ------------------------------


def _peer():
    pytest.importorskip("moorpy")
    import importlib.util
    import sys
    from conftest import ROOT
    sys.path.insert(0, str(ROOT / "benchmarks"))
    spec = importlib.util.spec_from_file_location(
        "peer_moorpy_network", ROOT / "benchmarks" / "peer_moorpy_network.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _compare_with_moorpy(case, pos_tol=1e-6, t_rel=1e-7):
    peer = _peer()
    result = solve(case, tol=1e-12)
    scene = peer.NetworkScene(case)
    assert scene.solve(tol=1e-9)
    for body in result.bodies:
        r6 = scene.poses()[body["name"]]
        ours = [body["x_m"], body["y_m"], body["z_m"]] + [
            math.radians(body[k]) for k in ("roll_deg", "pitch_deg", "yaw_deg")]
        assert np.max(np.abs(np.array(ours) - r6)) < pos_tol, (ours, r6)
    for pt in result.points:
        r = scene.point_positions()[pt["name"]]
        assert np.max(np.abs(np.array([pt["x_m"], pt["y_m"], pt["z_m"]]) - r)) < pos_tol
    t_max = max(max(lr.fairlead_tension_N, lr.anchor_tension_N) for lr in result.legs)
    for lr, (ta, tb) in zip(result.legs, scene.tensions()):
        assert abs(lr.anchor_tension_N - ta) < t_rel * t_max, lr.name
        assert abs(lr.fairlead_tension_N - tb) < t_rel * t_max, lr.name
    return result


def test_spar_under_thrust_and_moment_agrees_with_moorpy():
    peer = _peer()
    case = peer.without_extras(spar_with_force((8e5, 2e5, 0, 0, 0, 0)))
    result = _compare_with_moorpy(case)
    assert result.bodies[0]["x_m"] > 20 and result.bodies[0]["pitch_deg"] > 1


BRIDLE = {
    "name": "buoy on a bridle",
    "environment": {"depth": 50.0},
    "line_types": {"chain": {"weight_in_water": 800.0, "ea": 5e8},
                   "rope": {"weight_in_water": 30.0, "ea": 5e7}},
    "bodies": [{"name": "buoy", "free": ["surge", "sway", "yaw"],
                "loads": {"force": [4e4, 1e4, 0.0]}}],
    "points": [{"name": "apex", "position": [-30.0, 0.0, -15.0], "free": True,
                "mass": 500.0, "volume": 0.1},
               {"name": "A1", "position": [-250.0, 0.0]},
               {"name": "A2", "position": [150.0, 200.0]},
               {"name": "A3", "position": [150.0, -200.0]}],
    "lines": [
        {"name": "B1", "from": "apex", "to": {"body": "buoy", "at": [-2.0, 3.0, -2.0]},
         "segments": [{"type": "rope", "length": 32.0}]},
        {"name": "B2", "from": "apex", "to": {"body": "buoy", "at": [-2.0, -3.0, -2.0]},
         "segments": [{"type": "rope", "length": 32.0}]},
        {"name": "M1", "from": "A1", "to": "apex", "segments": [{"type": "chain",
                                                                "length": 240.0}]},
        {"name": "M2", "from": "A2", "to": {"body": "buoy", "at": [1.0, 1.0, -2.0]},
         "segments": [{"type": "chain", "length": 255.0}]},
        {"name": "M3", "from": "A3", "to": {"body": "buoy", "at": [1.0, -1.0, -2.0]},
         "segments": [{"type": "chain", "length": 255.0}]},
    ],
}


def test_bridle_and_free_point_agree_with_moorpy():
    result = _compare_with_moorpy(load_case(copy.deepcopy(BRIDLE)))
    assert "free_points" in result.effects
    assert result.stability.stable


def test_bridle_apex_is_in_balance():
    """The apex's lines and its net weight balance (an independent sum over the result's
    end forces)."""
    result = solve(load_case(copy.deepcopy(BRIDLE)), tol=1e-12)
    apex = result.points[0]
    where = np.array([apex["x_m"], apex["y_m"], apex["z_m"]])
    net = 9.80665 * (500.0 - 1025.0 * 0.1)
    force = np.array([0.0, 0.0, -net])
    for lr in result.legs:
        if np.allclose(lr.anchor, where, atol=1e-9):
            force += lr.anchor_force
        if np.allclose(lr.fairlead, where, atol=1e-9):
            force += lr.fairlead_force
    assert np.max(np.abs(force)) < 1e-9 * max(lr.fairlead_tension_N for lr in result.legs)


TWO_PONTOONS = {
    "name": "two pontoons joined by a shared line",
    "environment": {"depth": 30.0},
    "line_types": {"chain": {"weight_in_water": 600.0, "ea": 3e8},
                   "hawser": {"weight_in_water": 20.0, "ea": 2e7}},
    "bodies": [{"name": "west", "free": ["surge", "sway", "yaw"], "position": [-40, 0, 0],
                "loads": {"force": [3e4, 2e4, 1e5]}},
               {"name": "east", "free": ["surge", "sway", "yaw"], "position": [40, 0, 0],
                "loads": {"force": [3e4, -1e4, 0.0]}}],
    "lines": [
        {"name": "W1", "from": [-200, 60], "to": {"body": "west", "at": [-10, 5, -1]},
         "segments": [{"type": "chain", "length": 160}]},
        {"name": "W2", "from": [-200, -60], "to": {"body": "west", "at": [-10, -5, -1]},
         "segments": [{"type": "chain", "length": 160}]},
        {"name": "E1", "from": [200, 60], "to": {"body": "east", "at": [10, 5, -1]},
         "segments": [{"type": "chain", "length": 160}]},
        {"name": "E2", "from": [200, -60], "to": {"body": "east", "at": [10, -5, -1]},
         "segments": [{"type": "chain", "length": 160}]},
        {"name": "S1", "from": {"body": "west", "at": [10, 4, -0.5]},
         "to": {"body": "east", "at": [-10, 4, -0.5]}, "segments": [{"type": "hawser",
                                                                      "length": 60.2}]},
        {"name": "S2", "from": {"body": "west", "at": [10, -4, -0.5]},
         "to": {"body": "east", "at": [-10, -4, -0.5]}, "segments": [{"type": "hawser",
                                                                       "length": 60.2}]},
    ],
}


def test_two_bodies_with_shared_lines_agree_with_moorpy():
    result = _compare_with_moorpy(load_case(copy.deepcopy(TWO_PONTOONS)))
    assert "several_bodies" in result.effects and len(result.bodies) == 2


def test_shared_line_pulls_both_bodies_equally_and_oppositely():
    """Newton's third law across a shared line: the resultant of every body's loads and
    line forces is zero, so the sum over both bodies of the external loads equals the
    pull of the anchored lines."""
    result = solve(load_case(copy.deepcopy(TWO_PONTOONS)), tol=1e-12)
    anchored = np.zeros(2)
    for lr in result.legs:
        if lr.name[0] in "WE":
            anchored += np.array(lr.fairlead_force[:2])
    loads = np.array([3e4 + 3e4, 2e4 - 1e4])
    assert np.allclose(anchored + loads, 0.0, atol=1e-6 * np.max(np.abs(loads)))


# ---- six DOFs, hydrostatics, free points --------------------------------------------------


def test_spar_floats_at_its_hydrostatic_balance_under_its_lines():
    """Heave equilibrium: buoyancy minus weight minus the heave spring carries the lines'
    downward pull; roll and pitch stay zero in the symmetric scene."""
    case = load_case(SPAR)
    result = solve(case, tol=1e-12)
    b = result.bodies[0]
    rho_g = 1025 * 9.80665
    body = case.bodies[0]
    net = rho_g * body.hydrostatics.displaced_volume - body.mass * 9.80665 \
        - rho_g * body.hydrostatics.waterplane_area * b["z_m"]
    pull = sum(lr.fairlead_vertical_N for lr in result.legs)
    assert net == pytest.approx(pull, rel=1e-9)
    assert abs(b["roll_deg"]) < 1e-8 and abs(b["pitch_deg"]) < 1e-6
    assert result.stability.stable


def test_exact_cylinder_hull_matches_the_linear_model_at_small_angles():
    """A vertical cylinder's exact buoyancy has the linear model's stiffness for small
    heel: rho g V z_B + rho g I_wp - m g z_G (REFERENCE.md section 7)."""
    data = {
        "environment": {"depth": 200.0},
        "line_types": {"chain": {"weight_in_water": 700.0, "ea": 4e8}},
        "bodies": [{"name": "can", "mass": 2.0e6, "centre_of_gravity": [0, 0, -20.0],
                    "hull": [{"shape": "cylinder", "radius": 5.0, "bottom": -40.0,
                              "top": 10.0}],
                    "loads": {"force": [0, 0, 0, 0, 2e6, 0]}}],
        "lines": [{"name": f"L{k}", "from": [300 * math.cos(a), 300 * math.sin(a)],
                   "to": {"body": "can", "at": [5 * math.cos(a), 5 * math.sin(a), -20]},
                   "segments": [{"type": "chain", "length": 330}]}
                  for k, a in enumerate((0.0, 2 * math.pi / 3, 4 * math.pi / 3))]}
    result = solve(load_case(data), tol=1e-12)
    assert "exact_hydrostatics" in result.effects
    K, dofs = moorsolve.coupled_stiffness(result)
    pitch = dofs.index("can.pitch")
    b = result.bodies[0]
    draft = 40.0 + b["z_m"]
    V = math.pi * 25 * draft
    z_B = -40.0 + draft / 2
    rho_g = 1025 * 9.80665
    hydro = rho_g * (V * z_B + math.pi * 5**4 / 4) - 2.0e6 * 9.80665 * (-20.0)
    moor = moorsolve.stiffness(result)[4, 4]
    # The pitched pose (about 1 deg) moves the values at second order.
    assert K[pitch, pitch] == pytest.approx(hydro + moor, rel=2e-3)


def test_free_clump_point_rests_on_the_seabed_with_its_reaction():
    data = {
        "environment": {"depth": 30.0},
        "line_types": {"chain": {"weight_in_water": 500.0, "ea": 3e8}},
        "bodies": [{"name": "buoy", "free": ["surge", "sway"]}],
        "points": [{"name": "clump", "position": [-60.0, 0.0, -29.0], "free": True,
                    "mass": 8000.0, "volume": 1.0},
                   {"name": "A", "position": [-150.0, 0.0]}],
        "lines": [{"name": "up", "from": "clump", "to": {"body": "buoy", "at": [0, 0, 0]},
                   "segments": [{"type": "chain", "length": 80.0}]},
                  {"name": "ground", "from": "A", "to": "clump",
                   "segments": [{"type": "chain", "length": 95.0}]},
                  {"name": "back", "from": [150.0, 0.0], "to": {"body": "buoy",
                                                                "at": [0, 0, 0]},
                   "segments": [{"type": "chain", "length": 160.0}]}]}
    # The chain lying flat from the anchor to the clump has zero vertical tension at both
    # ends, a double root of its height equation (Z ~ V|V|): its vertical force is resolved
    # to about sqrt(eps) of the tension scale, so this scene is certified at 1e-8.
    result = solve(load_case(data), tol=1e-8)
    clump = result.points[0]
    assert clump["z_m"] == pytest.approx(-30.0, abs=1e-9)
    net = 9.80665 * (8000.0 - 1025.0)
    up = result.leg("up")
    ground = result.leg("ground")
    # Vertical balance of the clump: the seabed carries what the lines do not.
    lifted = up.anchor_vertical_N + ground.fairlead_force[2]
    assert clump["seabed_reaction_N"] == pytest.approx(net - lifted, rel=1e-6)
    assert clump["seabed_reaction_N"] > 0


# ---- stability and weathervaning --------------------------------------------------------


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
@pytest.mark.parametrize("toward", [0.0, 45.0, 100.0, 180.0, 270.0])
@pytest.mark.parametrize("model", [
    {"model": "drag", "area_x": 600, "area_y": 2400, "cx": 0.8, "cy": 1.0,
     "centre": [-15.0, 0.0]},
    {"model": "hu_tang", "superstructure_area": 300, "hull_area": 200,
     "centre": [-15.0, 0.0]},
    {"model": "drag", "area_x": 600, "area_y": 2400, "length": 150, "centre": [-15.0, 0.0],
     "table": [[0, 0.8, 0, 0], [90, 0, 1.0, 0.05], [180, -0.7, 0, 0],
               [270, 0, -1.0, -0.05]]},
], ids=["drag", "hu_tang", "table"])
def test_turret_ship_weathervanes_with_its_load_centre_downwind(model, toward, solver):
    """REFERENCE.md section 7: on a turret the lines exert no yaw moment about it; the ship
    is stable with its load centre downwind of the turret, i.e. heading ``toward + 180``
    (bow into the wind), whatever heading the wind comes from and the case starts at."""
    case = load_case(SHIP)
    data = copy.deepcopy(case.source)
    data["environment"]["wind"]["toward_deg"] = toward
    data["bodies"][0]["loads"]["wind"] = model
    result = solve(load_case(data), solver=solver)
    assert result.stability.stable and not result.stability.unstable_dofs
    yaw = result.bodies[0]["yaw_deg"]
    assert math.cos(math.radians(yaw - (toward + 180.0))) == pytest.approx(1.0, abs=1e-9)


def test_unstable_equilibrium_alone_is_reported(caplog):
    """A raft free in yaw on a negative yaw spring and lines through its centre: yaw 0 is
    the only equilibrium and it is unstable; the solve returns it, stable false, and says
    so in the notes and on the log (stderr in the CLI)."""
    spring = [[0.0] * 6 for _ in range(6)]
    spring[5][5] = -2.0e6
    data = {
        "environment": {"depth": 40.0},
        "line_types": {"chain": {"weight_in_water": 600.0, "ea": 3e8}},
        "bodies": [{"name": "raft", "free": ["surge", "sway", "yaw"], "stiffness": spring}],
        "lines": [{"name": f"L{k}", "from": [110 * math.cos(a), 110 * math.sin(a)],
                   "to": {"body": "raft", "at": [0, 0, 0]},
                   "segments": [{"type": "chain", "length": 120}]}
                  for k, a in enumerate((0.0, 2.1, 4.2))]}
    with caplog.at_level("WARNING"):
        result = solve(load_case(data))
    assert not result.stability.stable
    assert result.stability.unstable_dofs == ("raft.yaw",)
    assert result.stability.min_eigenvalue < 0
    assert any("only an unstable equilibrium" in n for n in result.notes)
    assert "unstable" in caplog.text


def test_indifferent_yaw_keeps_its_value_and_is_reported_neutral():
    data = {
        "environment": {"depth": 22.0},
        "line_types": {"c": {"weight_in_water": 200.0}},
        "bodies": [{"name": "buoy", "free": ["surge", "sway", "yaw"],
                    "orientation_deg": [0, 0, 30.0], "loads": {"force": [500.0, 0, 0]}}],
        "lines": [{"name": n, "from": [x, y], "to": {"body": "buoy", "at": [0, 0, 0]},
                   "segments": [{"type": "c", "length": 50.0}]}
                  for n, x, y in (("a", 33.0, 0.0), ("b", -16.5, 28.6), ("c", -16.5, -28.6))]}
    result = solve(load_case(data))
    assert result.bodies[0]["yaw_deg"] == pytest.approx(30.0, abs=1e-12)
    assert result.stability.neutral_dofs == ("buoy.yaw",)


# ---- bad input ------------------------------------------------------------------------------


def _bad(mutate, field, text):
    data = copy.deepcopy(BRIDLE)
    mutate(data)
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == field
    assert text in str(err.value)


def test_unknown_body_and_point_are_named():
    _bad(lambda d: d["lines"][0].update({"to": {"body": "boat", "at": [0, 0, 0]}}),
         "lines[0].to.body", "unknown body 'boat'")
    _bad(lambda d: d["lines"][2].update({"to": "apx"}), "lines[2].to", "unknown point 'apx'")


def test_duplicate_names_are_refused():
    _bad(lambda d: d["lines"][1].update({"name": "B1"}), "lines[1].name",
         "duplicate line name 'B1'")
    _bad(lambda d: d["points"][1].update({"name": "apex"}), "points[1].name",
         "duplicate point name 'apex'")


def test_free_point_nothing_holds_is_refused():
    def mutate(d):
        d["points"].append({"name": "loose", "position": [0, 0, -10], "free": True})
    _bad(mutate, "points[4].free", "not attached to any line")


def test_heave_without_mass_or_hydrostatics_names_the_body_and_field():
    _bad(lambda d: d["bodies"][0].update({"free": ["surge", "heave"]}), "bodies[0].free",
         "body 'buoy' is free in heave but has no mass and no hydrostatics")


def test_body_nothing_holds_is_refused():
    def mutate(d):
        d["bodies"].append({"name": "drifter", "free": ["surge"]})
    _bad(mutate, "bodies[1].free", "no line, fender, pile guide or spring holds it")


# ---- threads ---------------------------------------------------------------------------


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_eight_threads_give_the_serial_answers(solver):
    dock = load_case(CASES / "floating_dock.yaml")
    cases = [load_case({**copy.deepcopy(dock.source), "environment": {
        **dock.source["environment"], "wind": {"speed": 30.0, "toward_deg": a}}})
        for a in range(0, 360, 45)] + [load_case(SPAR), load_case(SHIP),
                                       load_case(copy.deepcopy(BRIDLE))]
    serial = [solve(c, solver=solver) for c in cases]
    with ThreadPoolExecutor(8) as pool:
        parallel = list(pool.map(lambda c: solve(c, solver=solver), cases * 3))
    for a, b in zip(serial * 3, parallel):
        assert a.state.tolist() == b.state.tolist()
        assert [leg.fairlead_tension_N for leg in a.legs] == \
            [leg.fairlead_tension_N for leg in b.legs]


# ---- studies and checks on the network -----------------------------------------------------


def test_damaged_conditions_remove_every_line_of_a_network():
    data = copy.deepcopy(BRIDLE)
    data["checks"] = {"offset_limit": 40.0}
    for lt in data["line_types"].values():
        lt["mbl"] = 2e6
    report = moorsolve.checks.run_checks(load_case(data))
    removed = [c.removed for c in report.conditions]
    assert removed == [None] + [line["name"] for line in BRIDLE["lines"]]
    assert all(c.solved for c in report.conditions)
    # Uplift is checked at anchors only (end A on the seabed), not on the bridle legs.
    intact = report.conditions[0]
    uplift = {i.leg for i in intact.items if i.check.startswith("anchor uplift")}
    assert uplift == {"M1", "M2", "M3"}


def test_removing_a_line_drops_the_free_points_it_alone_held():
    from moorsolve.model.edit import without_line
    data = copy.deepcopy(BRIDLE)
    data["points"].append({"name": "float", "position": [-100.0, 0.0, -10.0], "free": True,
                           "volume": 1.0})
    data["lines"].append({"name": "F", "from": "apex", "to": "float",
                          "segments": [{"type": "rope", "length": 75.0}]})
    case = load_case(data)
    damaged = without_line(case, "F")
    assert [p.name for p in damaged.points if p.free] == ["apex"]
    assert "F" not in [line.name for line in damaged.lines]


def test_sweep_reports_every_body_and_envelope_names_its_body():
    data = copy.deepcopy(TWO_PONTOONS)
    data["environment"]["wind"] = {"speed": 20.0, "toward_deg": 0.0}
    for body in data["bodies"]:
        body["loads"]["wind"] = {"model": "drag", "area_x": 100.0, "area_y": 300.0}
    case = load_case(data)
    table = moorsolve.sweep(case, {"environment.wind.toward_deg": [0.0, 90.0]})
    for name in ("west", "east"):
        for field in ("x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg"):
            assert f"{name}.{field}" in table.columns
    for k, toward in enumerate((0.0, 90.0)):
        single = solve(load_case({**copy.deepcopy(data), "environment": {
            **data["environment"], "wind": {"speed": 20.0, "toward_deg": toward}}}))
        east = single.body_named("east")
        assert table["east.x_m"].iloc[k] == pytest.approx(east["x_m"], abs=1e-6)
        assert table["east.yaw_deg"].iloc[k] == pytest.approx(east["yaw_deg"], abs=1e-6)
    with pytest.raises(CaseError, match="name the one"):
        moorsolve.offset_envelope(case, step_deg=90)
    env = moorsolve.offset_envelope(case, step_deg=90, body="east")
    assert np.all(np.isfinite(env.offset_m)) and len(env.offset_m) == 4


def test_box_hull_heave_and_a_hull_pushed_out_of_its_exact_range():
    """A floating box: its exact buoyancy balances the weight at the draft m / (rho L W);
    pushed down and heeled until its deck edge goes under, the solve refuses with the
    reason."""
    data = {
        "environment": {"depth": 100.0},
        "line_types": {"rope": {"weight_in_water": 0.0, "ea": 1e8}},
        "bodies": [{"name": "barge", "mass": 1.0e6, "free": ["heave", "roll", "pitch"],
                    "centre_of_gravity": [0, 0, -1.0],
                    "hull": [{"shape": "box", "length": 40.0, "width": 10.0,
                              "bottom": -5.0, "top": 3.0}]}],
        "lines": [{"name": "L", "from": [0, 0, -100], "to": {"body": "barge",
                                                              "at": [0, 0, -5]},
                   "segments": [{"type": "rope", "length": 200.0}]}]}
    result = solve(load_case(data), tol=1e-12)
    draft = 1.0e6 / (1025.0 * 400.0)
    # The bottom (body z = -5) sits at the draft below the water: origin at 5 - draft.
    assert result.bodies[0]["z_m"] == pytest.approx(5.0 - draft, rel=1e-9)
    data["bodies"][0]["loads"] = {"force": [0, 0, -2.0e7, 4.0e7, 0, 0]}
    with pytest.raises(moorsolve.ConvergenceError, match="hull member 0"):
        solve(load_case(data))


def test_three_platforms_with_bridles_and_shared_lines_agree_with_moorpy():
    """The shipped multi-body case (15 lines, three bridles, six-DOF bodies on linear
    hydrostatics) against MoorPy."""
    result = _compare_with_moorpy(load_case(CASES / "three_platforms.yaml"))
    assert len(result.bodies) == 3 and len(result.points) == 3
    assert result.stability.stable


# ---- MoorDyn export of a network, and back ------------------------------------------------


def _roundtrip(case, tmp_path):
    path = tmp_path / "scene.dat"
    path.write_text(moorsolve.case_to_moordyn(case))
    back = load_case(moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(path)))
    return solve(case, tol=1e-12), solve(back, tol=1e-12)


def test_network_export_to_moordyn_and_back_keeps_the_equilibrium(tmp_path):
    """A held body on a bridle with a free apex: MoorDyn v2 out, our reader in, the same
    apex position and tensions."""
    data = copy.deepcopy(BRIDLE)
    data["bodies"][0]["free"] = []
    ours, back = _roundtrip(load_case(data), tmp_path)
    apex, again = ours.points[0], back.points[0]
    for key in ("x_m", "y_m", "z_m"):
        assert again[key] == pytest.approx(apex[key], abs=1e-9)
    for a, b in zip(ours.legs, back.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-9)


def test_network_export_of_a_free_six_dof_buoy_and_back(tmp_path):
    """A submerged buoy free in six DOFs on three taut lines: mass and buoyancy at its centre
    of gravity (MoorDyn's convention, no waterplane), so the file holds the whole model."""
    data = {
        "environment": {"depth": 100.0},
        "line_types": {"rope": {"weight_in_water": 20.0, "ea": 5e7, "diameter": 0.05}},
        "bodies": [{"name": "buoy", "position": [0, 0, -30], "mass": 5000.0,
                    "centre_of_gravity": [0, 0, -0.5], "inertia": [8e3, 8e3, 6e3],
                    "hydrostatics": {"displaced_volume": 12.0,
                                     "metacentre": [0, 0, -0.5]}}],
        "lines": [{"name": f"T{k}", "from": [40 * math.cos(a), 40 * math.sin(a)],
                   "to": {"body": "buoy", "at": [1.5 * math.cos(a), 1.5 * math.sin(a), -1.5]},
                   "segments": [{"type": "rope", "length": 80.0}]}
                  for k, a in enumerate((0.0, 2.0944, 4.1888))]}
    case = load_case(data)
    text = moorsolve.case_to_moordyn(case)
    assert "Free" in text.split("BODIES")[1].splitlines()[3]
    ours, back = _roundtrip(case, tmp_path)
    for key in ("x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg"):
        assert back.bodies[0][key] == pytest.approx(ours.bodies[0][key], abs=1e-8)
    for a, b in zip(ours.legs, back.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-8)


def test_network_export_says_what_moordyn_cannot_hold():
    text = moorsolve.case_to_moordyn(load_case(SPAR))
    assert "metacentre and heave restoring" in text and "extra springs" in text
    with pytest.raises(CaseError, match="v2 only"):
        moorsolve.case_to_moordyn(load_case(SPAR), version=1)
