"""Tests of moorsolve.io: loading, unit conversion and strict validation of case files."""

from __future__ import annotations

import copy
import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from moorsolve.errors import CaseError
from moorsolve.io import load_case
from moorsolve.model import (
    Body,
    BodyLoads,
    Case,
    DragLoad,
    DriftCoefficient,
    Flow,
    HuTangCurrent,
    HuTangDrift,
    HuTangWind,
    LineType,
    SolverOptions,
    Waves,
)

DEPTH = 20.85


def minimal_case() -> dict:
    """The smallest valid case: one elastic chain leg, no body."""
    return {
        "environment": {"depth": DEPTH},
        "line_types": {"chain81": {"weight_in_water": "0.13 t/m", "ea": 5.6e8}},
        "legs": [{"name": "L1", "anchor": [-240.0, -120.0], "fairlead": [-123.2, -25.5, 0.0],
                  "segments": [{"type": "chain81", "length": 123.7}]}],
    }


def full_case() -> dict:
    """A valid case that uses every section and every load model."""
    case = minimal_case()
    case["name"] = "full"
    case["environment"].update({
        "water_density": 1025, "air_density": "1.2 kg/m^3", "gravity": 9.81,
        "seabed": {"friction": 0.5},
        "wind": {"speed": "20 kn", "toward_deg": 30},
        "current": {"speed": 1.5, "toward_deg": "90 deg"},
        "waves": {"hs": 1.5, "toward_deg": 0},
    })
    case["line_types"]["rope"] = {"weight_in_water": "-2 kgf/m", "ea": "372 kN", "mbl": "5.6e8 N",
                                  "diameter": "81 mm", "sealed": True}
    case["line_types"]["wire"] = {"weight_in_water": "0.2 kN/m"}
    case["body"] = {
        "free": ["surge", "yaw"],
        "loads": {
            "force": [1000, "2 kN", "3 kN*m"],
            "wind": {"model": "drag", "area_x": 100, "area_y": "200 m^2",
                     "table": [[-180, 1, 0, 0], [0, 1, 0.5, 0.1], [90, 0, 1, 0]],
                     "length": 50, "centre": [1, 2]},
            "current": {"model": "hu_tang", "wetted_area": 500, "coefficient": 0.2},
            "wave_drift": {"model": "coefficient", "length_x": 10, "length_y": 30, "cx": 0.5},
        },
    }
    case["legs"].append({"name": "L2", "anchor": [240.0, 0.0, -10.0], "fairlead": [20, 0, -1],
                         "segments": [{"type": "wire", "length": 230}]})
    case["legs"].append({"name": "L3", "anchor": [0, 100], "fairlead": [0, 10, 0],
                         "segments": [{"type": "rope", "length": 80}]})
    case["solver"] = {"tol": "1e-8", "max_iter": 50, "max_time_s": "2 min"}
    return case


@pytest.fixture
def case_dict() -> dict:
    return minimal_case()


def load_error(data) -> CaseError:
    with pytest.raises(CaseError) as info:
        load_case(data)
    return info.value


# ---- valid input ------------------------------------------------------------------------


def test_minimal_case_loads(case_dict):
    case = load_case(case_dict)
    assert isinstance(case, Case)
    assert case.name == "case"
    assert case.body is None
    assert case.solver == SolverOptions()
    assert case.environment.depth == DEPTH
    assert case.environment.wind is None
    assert case.environment.seabed.friction == 0.0
    assert isinstance(case.line_types["chain81"], LineType)
    leg = case.legs[0]
    assert isinstance(case.legs, tuple) and isinstance(leg.segments, tuple)
    assert isinstance(leg.anchor, tuple) and isinstance(leg.fairlead, tuple)
    assert leg.line_type is case.line_types["chain81"]
    assert leg.length == 123.7


def test_two_element_anchor_gets_seabed_depth(case_dict):
    assert load_case(case_dict).legs[0].anchor == (-240.0, -120.0, -DEPTH)


def test_input_dict_is_not_modified(case_dict):
    before = copy.deepcopy(case_dict)
    load_case(case_dict)
    assert case_dict == before


def test_full_case_builds_every_dataclass():
    case = load_case(full_case())
    env = case.environment
    assert case.name == "full"
    assert env.air_density == 1.2 and env.gravity == 9.81 and env.seabed.friction == 0.5
    assert env.wind == Flow(speed=pytest.approx(20 * 1852 / 3600), toward_deg=30.0)
    assert env.current == Flow(speed=1.5, toward_deg=90.0)
    assert env.waves == Waves(hs=1.5, toward_deg=0.0)
    rope = case.line_types["rope"]
    assert rope.weight_in_water == pytest.approx(-2 * 9.80665)
    assert rope.ea == 372e3 and rope.mbl == 5.6e8 and rope.diameter == pytest.approx(0.081)
    assert rope.sealed and not case.line_types["wire"].elastic
    assert case.line_types["wire"].weight_in_water == pytest.approx(200.0)
    assert isinstance(case.body, Body)
    assert case.body.free == ("surge", "yaw")
    loads = case.body.loads
    assert isinstance(loads, BodyLoads)
    assert loads.force == (1000.0, 2000.0, 3000.0)
    assert isinstance(loads.wind, DragLoad)
    assert loads.wind.table == ((-180.0, 1.0, 0.0, 0.0), (0.0, 1.0, 0.5, 0.1),
                                (90.0, 0.0, 1.0, 0.0))
    assert loads.wind.area_y == 200.0 and loads.wind.centre == (1.0, 2.0)
    assert loads.current == HuTangCurrent(wetted_area=500.0, coefficient=0.2)
    assert loads.wave_drift == DriftCoefficient(length_x=10.0, length_y=30.0, cx=0.5)
    assert case.legs[1].anchor == (240.0, 0.0, -10.0)
    assert case.solver == SolverOptions(tol=1e-8, max_iter=50, max_time_s=120.0)


def test_hu_tang_models_and_defaults(case_dict):
    case_dict["body"] = {"loads": {
        "wind": {"model": "hu_tang", "superstructure_area": 300, "hull_area": 100,
                 "superstructure_area_lateral": 900, "hull_area_lateral": 400},
        "current": {"model": "drag", "area_x": 10, "area_y": 40},
        "wave_drift": {"model": "hu_tang", "beam": 20},
    }}
    body = load_case(case_dict).body
    assert body.free == ("surge", "sway", "yaw")
    assert body.loads.wind == HuTangWind(300.0, 100.0, 900.0, 400.0)
    assert body.loads.current == DragLoad(area_x=10.0, area_y=40.0)
    assert body.loads.wave_drift == HuTangDrift(beam=20.0, length=None, k=0.7)
    assert body.loads.force is None


def test_empty_free_list_and_null_means_none(case_dict):
    case_dict["body"] = {"free": [], "loads": {"wind": None}}
    case_dict["line_types"]["chain81"]["ea"] = None
    case_dict["legs"][0]["segments"][0]["length"] = 200.0
    case = load_case(case_dict)
    assert case.body.free == () and case.body.loads.wind is None
    assert case.line_types["chain81"].ea is None


def test_vertical_leg_is_allowed(case_dict):
    case_dict["line_types"]["chain81"].pop("ea")
    case_dict["legs"][0].update(anchor=[0, 0], fairlead=[0, 0, 0])
    case_dict["legs"][0]["segments"][0]["length"] = DEPTH
    assert load_case(case_dict).legs[0].anchor == (0.0, 0.0, -DEPTH)


# ---- units ------------------------------------------------------------------------------


def test_tonne_per_metre_uses_case_gravity(case_dict):
    case_dict["environment"]["gravity"] = 10
    assert load_case(case_dict).line_types["chain81"].weight_in_water == pytest.approx(1300.0)


def test_tonne_per_metre_default_gravity(case_dict):
    weight = load_case(case_dict).line_types["chain81"].weight_in_water
    assert weight == pytest.approx(1274.86, abs=0.01)


@pytest.mark.parametrize("text, expected", [
    ("22 kg/m", 22 * 9.80665),
    ("130 kgf/m", 130 * 9.80665),
    ("1.27 kN/m", 1270.0),
    ("0.13 tf/m", 0.13 * 1000 * 9.80665),
    (-50, -50.0),
    ("1.5e3", 1500.0),
])
def test_weight_per_length_forms(case_dict, text, expected):
    case_dict["line_types"]["chain81"]["weight_in_water"] = text
    weight = load_case(case_dict).line_types["chain81"].weight_in_water
    assert weight == pytest.approx(expected)


def test_unit_strings_convert(case_dict):
    case_dict["line_types"]["chain81"].update(diameter="81 mm", mbl="372 kN", ea="5.6e8 N")
    case_dict["environment"]["current"] = {"speed": "5 kn", "toward_deg": "30 deg"}
    case_dict["environment"]["water_density"] = "1.025 t/m^3"
    case_dict["legs"][0]["segments"][0]["length"] = "0.1237 km"
    case = load_case(case_dict)
    chain = case.line_types["chain81"]
    assert chain.diameter == pytest.approx(0.081)
    assert chain.mbl == pytest.approx(372e3)
    assert chain.ea == pytest.approx(5.6e8)
    assert case.environment.current.speed == pytest.approx(2.5722, abs=1e-4)
    assert case.environment.current.toward_deg == pytest.approx(30.0)
    assert case.environment.water_density == pytest.approx(1025.0)
    assert case.legs[0].length == pytest.approx(123.7)


def test_angle_in_radians_becomes_degrees(case_dict):
    case_dict["environment"]["waves"] = {"hs": 2, "toward_deg": f"{math.pi / 2} rad"}
    assert load_case(case_dict).environment.waves.toward_deg == pytest.approx(90.0)


# ---- files ------------------------------------------------------------------------------

YAML_CASE = """\
environment:
  depth: 20.85
line_types:
  chain81: {weight_in_water: "0.13 t/m", ea: 5.6e8}
legs:
  - name: L1
    anchor: [-240.0, -120.0]
    fairlead: [-123.2, -25.5, 0.0]
    segments:
      - {type: chain81, length: 123.7}
solver: {tol: 1e-10}
"""


def test_yaml_file_loads_with_stem_as_name(tmp_path):
    path = tmp_path / "floating_dock.yaml"
    path.write_text(YAML_CASE)
    for source in (path, str(path)):
        case = load_case(source)
        assert case.name == "floating_dock"
        # PyYAML reads 1e-10 as a string; it must still be taken as a number.
        assert case.solver.tol == 1e-10


def test_missing_file(tmp_path):
    err = load_error(tmp_path / "nope.yaml")
    assert "nope.yaml" in str(err) and "not found" in str(err)


@pytest.mark.parametrize("text, expected", [
    ("environment: {depth: 20\n", "invalid YAML"),
    ("- just\n- a list\n", "not a mapping"),
    ("", "not a mapping"),
    ("environment: {depth: 1}\nenvironment: {depth: 2}\n", "duplicate key"),
    ("name: 2020-13-45\n", "invalid YAML"),
    ("name: !!python/object:os.system x\n", "invalid YAML"),
])
def test_bad_yaml_files(tmp_path, text, expected):
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    err = load_error(path)
    assert err.field == str(path)
    assert expected in str(err)


def test_directory_and_binary_files(tmp_path):
    assert load_error(tmp_path).field == str(tmp_path)
    path = tmp_path / "binary.yaml"
    path.write_bytes(b"\xff\xfe\x00bad")
    assert load_error(path).field == str(path)


@pytest.mark.parametrize("source", [None, 42, ["a"], b"case.yaml", 3.5])
def test_bad_source_types(source):
    assert load_error(source).field == ""


# ---- validation errors ------------------------------------------------------------------


def _set(path, value):
    """A mutation that sets the value at ``path`` (a tuple of keys and indices)."""
    def mutate(case):
        target = case
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value
    return mutate


def _delete(path):
    def mutate(case):
        target = case
        for key in path[:-1]:
            target = target[key]
        del target[path[-1]]
    return mutate


SEG = ("legs", 0, "segments", 0)
LEG = ("legs", 0)
CHAIN = ("line_types", "chain81")


def _with_body(body):
    return _set(("body",), body)


def _clump_last(case):
    case["legs"][0]["segments"].append({"clump": {"mass": 1000}})


def _clump_first(case):
    case["legs"][0]["segments"].insert(0, {"clump": {"weight": -5e3}})


def _clump_both(case):
    case["legs"][0]["segments"] += [{"clump": {"weight": 1e3, "volume": 1.0}},
                                    {"type": "chain81", "length": 10}]


def _clump_no_mass(case):
    case["legs"][0]["segments"] += [{"clump": {"volume": 1.0}},
                                    {"type": "chain81", "length": 10}]


def _clump_negative_mass(case):
    case["legs"][0]["segments"] += [{"clump": {"mass": "-3 t"}},
                                    {"type": "chain81", "length": 10}]


def _clump_extra_key(case):
    case["legs"][0]["segments"] += [{"clump": {"mass": 10}, "type": "chain81"},
                                    {"type": "chain81", "length": 10}]


def _duplicate_leg(case):
    leg = copy.deepcopy(case["legs"][0])
    case["legs"].append(leg)


def _inextensible_short(case):
    del case["line_types"]["chain81"]["ea"]
    case["legs"][0]["segments"][0]["length"] = 100.0


ERROR_CASES = [
    # (mutation, field expected in the message, text expected in the message)
    (_set(SEG + ("length",), -5), "legs[0].segments[0].length", "-5 m must be > 0"),
    (_set(SEG + ("length",), 0), "legs[0].segments[0].length", "must be > 0"),
    (_set(SEG + ("length",), True), "legs[0].segments[0].length", "not a length"),
    (_set(SEG + ("length",), "abc"), "legs[0].segments[0].length", "not a length"),
    (_set(SEG + ("length",), "3 kg"), "legs[0].segments[0].length", "'3 kg' is not a length"),
    (_set(SEG + ("length",), "5 blorbs"), "legs[0].segments[0].length", "not a known unit"),
    (_set(SEG + ("length",), "2**9**9**9 m"), "legs[0].segments[0].length", "not a length"),
    (_set(SEG + ("length",), float("nan")), "legs[0].segments[0].length", "not finite"),
    (_set(SEG + ("length",), float("inf")), "legs[0].segments[0].length", "not finite"),
    (_set(SEG + ("length",), "1e999 m"), "legs[0].segments[0].length", "not finite"),
    (_set(SEG + ("length",), 10**400), "legs[0].segments[0].length", "too large"),
    (_set(SEG + ("length",), [1]), "legs[0].segments[0].length", "not a length"),
    (_set(SEG + ("type",), "chain82"), "legs[0].segments[0].type", "chain81"),
    (_set(SEG + ("type",), ["chain81"]), "legs[0].segments[0].type", "unknown line type"),
    (_delete(SEG + ("type",)), "legs[0].segments[0].type", "missing"),
    (_clump_last, "legs[0].segments[1]", "ends the leg"),
    (_clump_first, "legs[0].segments[0]", "between two segments"),
    (_clump_both, "legs[0].segments[1].clump.volume", "not used with weight"),
    (_clump_no_mass, "legs[0].segments[1].clump.mass", "needs mass"),
    (_clump_negative_mass, "legs[0].segments[1].clump.mass", "must be >= 0"),
    (_clump_extra_key, "legs[0].segments[1].type", "unknown key"),
    (_set(LEG + ("segments",), []), "legs[0].segments", "no segments"),
    (_set(LEG + ("segments",), {"type": "chain81"}), "legs[0].segments", "not a list"),
    (_inextensible_short, "legs[0].segments", "cannot reach"),
    (_duplicate_leg, "legs[1].name", "duplicate leg name 'L1'"),
    (_set(LEG + ("name",), None), "legs[0].name", "non-empty string"),
    (_set(LEG + ("name",), ""), "legs[0].name", "non-empty string"),
    (_delete(LEG + ("name",)), "legs[0].name", "missing"),
    (_set(LEG + ("anchor",), [0, 0, -30]), "legs[0].anchor", "below the seabed"),
    (_set(LEG + ("anchor",), [-240, -120, 5]), "legs[0].anchor", "above the still-water"),
    (_set(LEG + ("anchor",), [1]), "legs[0].anchor", "[x, y] or [x, y, z]"),
    (_set(LEG + ("anchor",), "0, 0"), "legs[0].anchor", "not a list"),
    (_set(LEG + ("fairlead",), [0, 0, -25]), "legs[0].fairlead", "below the seabed"),
    (_set(LEG + ("fairlead",), [0, 0, "5 parsecs"]), "legs[0].fairlead", "must be <="),
    (_set(LEG + ("fairlead",), [0, 0]), "legs[0].fairlead", "[x, y, z]"),
    (_set(("legs",), []), "legs", "at least one leg"),
    (_set(("legs",), {"L1": {}}), "legs", "not a list"),
    (_delete(("legs",)), "legs", "missing"),
    (_set(("environment",), []), "environment", "not a mapping"),
    (_set(("environment",), None), "environment", "not a mapping"),
    (_delete(("environment", "depth")), "environment.depth", "missing"),
    (_set(("environment", "depth"), None), "environment.depth", "None is not a length"),
    (_set(("environment", "depth"), -20), "environment.depth", "must be > 0"),
    (_set(("environment", "water_density"), 0), "environment.water_density", "must be > 0"),
    (_set(("environment", "air_density"), "1 kg"), "environment.air_density", "not a density"),
    (_set(("environment", "gravity"), "9.8 m"), "environment.gravity", "not an acceleration"),
    (_set(("environment", "seabed"), {"friction": -0.1}), "environment.seabed.friction",
     "must be >= 0"),
    (_set(("environment", "seabed"), {"friction": "0.5 m"}), "environment.seabed.friction",
     "without a unit"),
    (_set(("environment", "wind"), {"speed": -1}), "environment.wind.speed", "must be >= 0"),
    (_set(("environment", "wind"), {"speed": "5 parsecs"}), "environment.wind.speed",
     "not a speed"),
    (_set(("environment", "wind"), {"toward_deg": 0}), "environment.wind.speed", "missing"),
    (_set(("environment", "current"), {"speed": 1, "toward_deg": "nan"}),
     "environment.current.toward_deg", "not an angle"),
    (_set(("environment", "current"), {"speed": 1, "toward_deg": "3 m"}),
     "environment.current.toward_deg", "not an angle"),
    (_set(("environment", "waves"), {"hs": "2 s"}), "environment.waves.hs", "not a length"),
    (_set(("line_types",), {}), "line_types", "at least one"),
    (_set(("line_types",), ["chain81"]), "line_types", "not a mapping"),
    (_set(("line_types", 7), {"weight_in_water": 1}), "line_types", "not a non-empty string"),
    (_delete(CHAIN + ("weight_in_water",)), "line_types.chain81.weight_in_water", "missing"),
    (_set(CHAIN + ("weight_in_water",), "5 m"), "line_types.chain81.weight_in_water",
     "not a force per length"),
    (_set(CHAIN + ("weight_in_water",), float("-inf")), "line_types.chain81.weight_in_water",
     "not finite"),
    (_set(CHAIN + ("ea",), -1), "line_types.chain81.ea", "must be > 0"),
    (_set(CHAIN + ("ea",), "5 kN/m"), "line_types.chain81.ea", "not a force"),
    (_set(CHAIN + ("mbl",), 0), "line_types.chain81.mbl", "must be > 0"),
    (_set(CHAIN + ("diameter",), "-81 mm"), "line_types.chain81.diameter", "must be > 0"),
    (_set(CHAIN + ("sealed",), "yes"), "line_types.chain81.sealed", "not true or false"),
    (_set(CHAIN + ("sealed",), True), "line_types.chain81.diameter",
     "sealed line needs a diameter"),
    (_set(("name",), 12), "name", "non-empty string"),
    (_set(("solver",), {"tol": 0}), "solver.tol", "must be > 0"),
    (_set(("solver",), {"tol": 1}), "solver.tol", "must be < 1"),
    (_set(("solver",), {"max_iter": 0}), "solver.max_iter", "from 1"),
    (_set(("solver",), {"max_iter": True}), "solver.max_iter", "not an integer"),
    (_set(("solver",), {"max_iter": 20.5}), "solver.max_iter", "not an integer"),
    (_set(("solver",), {"max_time_s": "5 m"}), "solver.max_time_s", "not a time"),
    (_set(("solver",), None), "solver", "not a mapping"),
    (_with_body([]), "body", "not a mapping"),
    (_with_body({"free": ["surge", "heave"]}), "body.free[1]", "surge, sway, yaw"),
    (_with_body({"free": ["surge", "surge"]}), "body.free[1]", "twice"),
    (_with_body({"free": "surge"}), "body.free", "not a list"),
    (_with_body({"loads": {"force": [0, 0]}}), "body.loads.force", "[Fx N, Fy N, Mz N m]"),
    (_with_body({"loads": {"force": [0, 0, "5 kN"]}}), "body.loads.force[2]", "not a moment"),
    (_with_body({"loads": {"wind": {"area_x": 1, "area_y": 1}}}), "body.loads.wind.model",
     "drag, hu_tang"),
    (_with_body({"loads": {"wind": {"model": "Drag", "area_x": 1, "area_y": 1}}}),
     "body.loads.wind.model", "drag, hu_tang"),
    (_with_body({"loads": {"wind": "drag"}}), "body.loads.wind", "not a mapping"),
    (_with_body({"loads": {"current": {"model": "hu_tang", "wetted_area": 0}}}),
     "body.loads.current.wetted_area", "must be > 0"),
    (_with_body({"loads": {"current": {"model": "hu_tang", "wetted_area": 1, "area_x": 1}}}),
     "body.loads.current.area_x", "unknown key"),
    (_with_body({"loads": {"current": {"model": "drag", "area_x": -1, "area_y": 1}}}),
     "body.loads.current.area_x", "must be >= 0"),
    (_with_body({"loads": {"wave_drift": {"model": "drag"}}}), "body.loads.wave_drift.model",
     "hu_tang, coefficient"),
    (_with_body({"loads": {"wave_drift": {"model": "hu_tang", "beam": 20, "k": 0}}}),
     "body.loads.wave_drift.k", "must be > 0"),
    (_with_body({"loads": {"wave_drift": {"model": "coefficient", "length_x": 1}}}),
     "body.loads.wave_drift.length_y", "missing"),
    (_with_body({"loads": {"wind": {"model": "hu_tang", "superstructure_area": 1,
                                    "hull_area": 1, "hull_area_lateral": 3}}}),
     "body.loads.wind.superstructure_area_lateral", "both or neither"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "centre": [0, 0, 0, 0]}}}),
     "body.loads.wind.centre", "[x, y]"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[0, 1, 1, 0]]}}}),
     "body.loads.wind.table", "at least 2 rows"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[0, 1, 1, 0], [0, 1, 1, 0]]}}}),
     "body.loads.wind.table[1][0]", "strictly increasing"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[-190, 1, 1, 0], [0, 1, 1, 0]]}}}),
     "body.loads.wind.table[0][0]", "must be >= -180"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[0, 1, 1, 0], [360, 1, 1, 0]]}}}),
     "body.loads.wind.table[1][0]", "must be < 360"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[-180, 1, 1, 0], [180, 1, 1, 0]]}}}),
     "body.loads.wind.table[1][0]", "span"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[0, 1, 1, 0], [90, 1, 1]]}}}),
     "body.loads.wind.table[1]", "[heading_deg, cx, cy, cmz]"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1,
                                    "table": [[0, 1, 1, 0.2], [90, 1, 1, 0]]}}}),
     "body.loads.wind.length", "non-zero cmz"),
    (_with_body({"loads": {"wind": {"model": "drag", "area_x": 1, "area_y": 1, "cx": 2,
                                    "table": [[0, 1, 1, 0], [90, 1, 1, 0]]}}}),
     "body.loads.wind.cx", "not used with a table"),
]


@pytest.mark.parametrize("mutate, field, text", ERROR_CASES)
def test_errors_name_the_field(case_dict, mutate, field, text):
    mutate(case_dict)
    err = load_error(case_dict)
    assert field in err.field
    assert field in str(err) and text in str(err)


def _mapping_paths(node, path=()):
    """Every path in ``node`` that leads to a mapping of case-file keys."""
    if isinstance(node, dict):
        # line_types maps user names, not keys: an extra entry there is a new line type.
        if path != ("line_types",):
            yield path
        for key, value in node.items():
            yield from _mapping_paths(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _mapping_paths(value, path + (i,))


def _dotted(path):
    text = ""
    for key in path:
        text += f"[{key}]" if isinstance(key, int) else (f".{key}" if text else key)
    return text


FULL_MAPPINGS = list(_mapping_paths(full_case()))


@pytest.mark.parametrize("path", FULL_MAPPINGS, ids=[_dotted(p) or "top" for p in FULL_MAPPINGS])
def test_unknown_keys_are_errors_at_every_level(path):
    case = full_case()
    target = case
    for key in path:
        target = target[key]
    target["bogus"] = 1
    err = load_error(case)
    expected = _dotted(path + ("bogus",))
    assert err.field == expected
    assert "unknown key 'bogus'" in str(err) and "allowed keys" in str(err)


def test_full_case_covers_every_section():
    # Guard for the test above: the mapping list must reach every level of the schema.
    dotted = {_dotted(p) for p in FULL_MAPPINGS}
    for expected in ("", "environment", "environment.seabed", "environment.wind",
                     "environment.waves", "line_types.rope", "body", "body.loads",
                     "body.loads.wind", "body.loads.current", "body.loads.wave_drift",
                     "legs[0]", "legs[0].segments[0]", "solver"):
        assert expected in dotted


# ---- property: junk never escapes as anything but CaseError -----------------------------

JUNK = [None, "abc", -1, 0, float("nan"), float("inf"), [], {}, True, "5 parsecs", "",
        [1, 2, 3], {"model": "drag"}, "1e999 m", -1e300, "0.13 t/m", 10**400]


def _all_paths(node, path=()):
    """Every path in ``node`` to a value (mapping entries and list items)."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield path + (key,)
            yield from _all_paths(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield path + (i,)
            yield from _all_paths(value, path + (i,))


FULL_PATHS = list(_all_paths(full_case()))

mutations = st.lists(
    st.tuples(st.sampled_from(FULL_PATHS), st.sampled_from(["set", "delete"]),
              st.sampled_from(JUNK)),
    min_size=1, max_size=3)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutations)
def test_junk_yields_case_or_case_error(changes):
    case = full_case()
    for path, action, junk in changes:
        target = case
        try:
            for key in path[:-1]:
                target = target[key]
            if action == "delete":
                del target[path[-1]]
            else:
                target[path[-1]] = copy.deepcopy(junk)
        except (KeyError, IndexError, TypeError):
            continue  # an earlier change removed or replaced this path
    try:
        result = load_case(case)
    except CaseError as err:
        assert isinstance(err.field, str)
    else:
        assert isinstance(result, Case)


def test_free_yaw_without_any_lever_arm_is_solved_and_reported_neutral():
    """Issue 14: every fairlead at the body origin leaves yaw unrestrained and unloaded: not
    an error; the solve keeps yaw at its given value and reports it as neutral."""
    from moorsolve import load_case, solve
    data = {
        "environment": {"depth": 22.0},
        "line_types": {"c": {"weight_in_water": 200.0}},
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": [1000.0, 0.0, 0.0]}},
        "legs": [{"name": n, "anchor": [x, y], "fairlead": [0.0, 0.0, 0.0],
                  "segments": [{"type": "c", "length": 50.0}]}
                 for n, x, y in (("a", 33.0, 0.0), ("b", -16.5, 28.6), ("c", -16.5, -28.6))]}
    result = solve(load_case(data))
    assert result.body["yaw_deg"] == 0.0
    assert result.stability.stable and result.stability.neutral_dofs == ("body.yaw",)
    assert result.body["x_m"] > 0
