"""The case-file schema (moorsolve.model.schema) and the validators are one list.

Walked both ways: every mapping a validator checks names its schema section (the keys it
accepts are the section's keys), every section is checked by some validator and reachable
from a top-level form, every key a validator accepts is read (a documented key the
validator ignored would be a silent drop), the unit of every quantity converted is the unit
the schema documents, and the defaults the schema documents are the defaults the model
takes. The reference page generated from the schema is up to date.
"""

from __future__ import annotations

import ast
import copy
import importlib
import pkgutil
import sys

import pytest
import yaml

import moorsolve
import moorsolve.model as model_pkg
from moorsolve.errors import CaseError
from moorsolve.model import schema
from moorsolve.model.units import recording

from conftest import CASES, ROOT

MODEL = ROOT / "moorsolve" / "model"
VALIDATORS = sorted(p for p in MODEL.glob("*.py"))
TOP = ("case", "network")


def _calls(tree, name):
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            f = node.func
            if (isinstance(f, ast.Name) and f.id == name) or \
                    (isinstance(f, ast.Attribute) and f.attr == name):
                yield node


def test_every_check_of_a_case_mapping_names_its_schema_section():
    for path in VALIDATORS:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for call in _calls(tree, "check_mapping"):
            if path.name == "fields.py":
                continue
            words = {k.arg for k in call.keywords}
            assert "section" in words, f"{path.name}:{call.lineno} checks a mapping without " \
                                       "its schema section"
            assert not words & {"required", "optional"}, f"{path.name}:{call.lineno}"


def test_every_section_is_checked_by_a_validator_and_reachable():
    literals = set()
    for path in VALIDATORS:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                literals.add(node.value)
    unchecked = sorted(set(schema.SECTIONS) - literals)
    assert not unchecked, f"sections no validator names: {unchecked}"
    named = {n for s in schema.SECTIONS.values() for k in s.keys.values()
             for n in k.section.split("|") if n}
    assert named <= set(schema.SECTIONS), sorted(named - set(schema.SECTIONS))
    assert set(schema.SECTIONS) - named == set(TOP)


def test_every_key_is_documented_with_a_known_kind():
    for sec in schema.SECTIONS.values():
        assert sec.doc and sec.where, sec.name
        for key, spec in sec.keys.items():
            assert spec.doc and spec.doc[0].islower() or spec.doc[0].isupper(), (sec.name, key)
            assert spec.kind in schema.TYPES or spec.unit is not None
            if spec.kind == "choice" and spec.choices and spec.default not in (
                    schema.REQUIRED, schema.NONE):
                assert spec.default in spec.choices, (sec.name, key)
    with pytest.raises(ValueError, match="declared twice"):
        schema.section("case", "x", "x", {})
    with pytest.raises(ValueError, match="unknown kind"):
        schema.Key("x", "furlongs")


# ---- walking the validators -------------------------------------------------------------


class _Tracked(dict):
    """A checked mapping that remembers which keys the validator read."""

    def __init__(self, raw, record):
        super().__init__(raw)
        self.read = record

    def __getitem__(self, key):
        self.read.add(key)
        return super().__getitem__(key)

    def get(self, key, default=None):
        self.read.add(key)
        return super().get(key, default)

    def items(self):
        self.read.update(self.keys())
        return super().items()


@pytest.fixture
def walk(monkeypatch):
    """Build cases while recording each checked mapping: ``(path, section, given keys,
    keys read)``, and each quantity converted: ``{field: (value, kind)}``."""
    from moorsolve.model import fields
    seen = []
    original = fields.check_mapping

    def check_mapping(raw, path, required=(), optional=(), *, section=""):
        checked = original(raw, path, required, optional, section=section)
        read: set = set()
        seen.append((path, section, set(checked), read))
        return _Tracked(checked, read)

    for info in pkgutil.iter_modules(model_pkg.__path__):
        module = importlib.import_module(f"moorsolve.model.{info.name}")
        if getattr(module, "check_mapping", None) is original:
            monkeypatch.setattr(module, "check_mapping", check_mapping)

    def build(source):
        with recording() as quantities:
            if isinstance(source, dict):
                moorsolve.load_case(copy.deepcopy(source))
            else:
                moorsolve.load_case(source)
        return seen, quantities
    return build


_DOCK = {
    "environment": {"depth": 50.0},
    "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 1e9, "mbl": 5e6}},
    "legs": [{"name": "L1", "anchor": [400.0, 0.0], "fairlead": [10.0, 0.0, -5.0],
              "segments": [{"type": "chain", "length": 420.0}]}],
}
#: Small cases reaching the sections the shipped cases leave out.
EXTRA = {
    "sea state and seabed": dict(_DOCK, environment={
        "depth": 50.0, "waves": {"hs": 3.0, "tp": 9.0, "toward_deg": 10,
                                 "spectrum": {"model": "jonswap", "gamma": 2.0},
                                 "duration": "3 h"},
        "seabed": {"friction": 0.5, "gradient": [0.01, 0.0]},
        "gravity": 9.81, "air_density": 1.2, "water_level": 1.0}),
    "tabulated spectrum": dict(_DOCK, environment={
        "depth": 50.0, "waves": {"hs": 4 * 0.6 ** 0.5, "from_deg": 0,
                                 "spectrum": {"table": [[0.2, 0.0], [0.5, 1.0], [0.8, 1.0],
                                                        [1.1, 0.0]]}}}),
    "grid seabed": dict(_DOCK, environment={
        "depth": 50.0, "seabed": {"bathymetry": {"x": [-100, 500], "y": [-100, 100],
                                                 "depth": [[50, 50], [50, 50]],
                                                 "source": "inline"},
                                  "tolerance": 0.2}}),
    "line type variants": dict(_DOCK, line_types={
        "chain": {"catalog": "studless_r3", "diameter": "76 mm",
                  "corrosion_allowance": "2 mm",
                  "drag": {"normal": 2.4, "tangential": 1.15, "side": 0.0},
                  "stiffness_bounds": {"lower": {"model": "hooke", "ea": 5e8},
                                       "upper": {"model": "dynamic", "alpha": 20,
                                                 "beta": 25}}},
        "rope": {"weight_in_water": 50.0, "mbl": 5e6, "diameter": 0.15, "fibre": True,
                 "min_tension": 0, "sealed": False, "weight_in_air": 60.0,
                 "stretch": {"model": "table", "strain": [0, 0.01, 0.02],
                             "tension": [0, 1e6, 3e6], "interpolation": "linear"}},
        "fibre": {"weight_in_water": 50.0, "stretch": {"model": "baranov", "n": 1e-5}}},
        legs=[{"name": "L1", "anchor": [400.0, 0.0], "fairlead": [10.0, 0.0, -5.0],
               "anchor_type": {"type": "pile", "allowed_uplift_angle_deg": 10},
               "segments": [{"type": "chain", "length": 200.0},
                            {"clump": {"weight": -1000.0}},
                            {"type": "rope", "length": 110.0},
                            {"clump": {"mass": 100.0, "volume": 0.01}},
                            {"type": "fibre", "length": 110.0}]}],
        solver={"tol": 1e-8, "max_iter": 100, "max_time_s": 10, "line_elements": 10},
        checks={"standard": "dnv-os-e301", "consequence_class": 2, "offset_limit": 30,
                "offset_limit_damaged": 40, "min_grounded_length": 10,
                "min_grounded_length_damaged": 5, "damaged": False,
                "anchor": {"type": "deadweight", "allowed_uplift": 1e5}}),
    "load models": dict(_DOCK, body={
        "free": ["surge", "sway", "yaw"], "fixed_to": "water",
        "outline": {"length": 100, "beam": 20, "draft": 5, "freeboard": 4,
                    "centre": [0, 0], "heading_deg": 0},
        "loads": {"force": [1e4, 0, 0],
                  "wind": {"model": "hu_tang", "superstructure_area": 100, "hull_area": 50,
                           "superstructure_area_lateral": 300,
                           "hull_area_lateral": 200, "centre": [0, 0]},
                  "current": {"model": "drag", "area_x": 10, "area_y": 20, "length": 10,
                              "table": [[0, 1, 0, 0], [90, 0, 1, 0.1]], "centre": [0, 0]},
                  "wave_drift": {"model": "coefficient", "length_x": 10, "length_y": 20,
                                 "cx": 1, "cy": 1, "centre": [0, 0]}}},
        environment={"depth": 50.0, "wind": {"speed": 10, "toward_deg": 0},
                     "current": {"speed": 0.5, "toward_deg": 0,
                                 "profile": [[-50, 0.2], [0, 0.5]]},
                     "waves": {"hs": 1.0, "toward_deg": 0}}),
    "ship loads": dict(_DOCK, body={"loads": {
        "current": {"model": "hu_tang", "wetted_area": 1000, "coefficient": 0.2,
                    "centre": [0, 0]},
        "wave_drift": {"model": "hu_tang", "beam": 20, "length": 100, "k": 0.7,
                       "centre": [0, 0]},
        "wind": {"model": "drag", "area_x": 10, "area_y": 20, "cx": 1, "cy": 1}}},
        environment={"depth": 50.0, "directions": "nautical", "north_deg": 90,
                     "wind": {"speed": 10, "from_deg": 0},
                     "current": {"speed": 0.5, "from_deg": 0},
                     "waves": {"hs": 1.0, "from_deg": 0}}),
    "life of a mooring": dict(
        _DOCK,
        line_types={"chain": {"weight_in_water": 1000.0, "ea": 1e9, "mbl": 5e6,
                              "diameter": "76 mm"},
                    "rope": {"weight_in_water": 50.0, "ea": 1e8, "mbl": 5e6, "fibre": True,
                             "diameter": 0.15}},
        legs=[{"name": "L1", "anchor": [400.0, 0.0], "fairlead": [10.0, 0.0, -5.0],
               "anchor_type": {"type": "suction"},
               "segments": [{"type": "chain", "length": 300.0},
                            {"type": "rope", "length": 120.0}]}],
        analysis={"lines": "quasi_static"},
        checks={"method": "quasi_static", "design_life": "20 y",
                "corrosion": {"rate": {"splash": "0.4 mm/y", "catenary": "0.3 mm/y",
                                       "bottom": "0.4 mm/y"},
                              "splash_depth": "4 m",
                              "line_types": {"chain": {"rate": "0.2 mm/y"}},
                              "segments": [{"line": "L1", "segment": 0,
                                            "rate": "0.5 mm/y"}]},
                "creep": {"rate": "0.1 %/y", "line_types": {"rope": {"rate": 0.002}}},
                "anchors": {
                    "drag": {"fluke_weight": "10 t", "soil": "soft_clay", "mass": "12 t",
                             "embedment": {"padeye_depth": 10, "su0": "2 kPa",
                                           "su_gradient": "1.5 kPa/m",
                                           "line_diameter": "76 mm", "bearing_factor": 8.5,
                                           "bearing_width": 2.5, "friction": 0.4}},
                    "suction": {"h_max": "5 MN", "v_max": "4 MN", "length": 15,
                                "diameter": 5, "mass": "80 t"},
                    "pile": {"h_max": "6 MN", "v_max": "5 MN", "mass": "60 t"},
                    "deadweight": {"mass": "50 t"}},
                "fatigue": {"sea_states": {"table": [[2.0, 8.0, 0, 1.0]]},
                            "spectrum": {"model": "jonswap", "gamma": 2.0},
                            "curve": {"catalog": "dnv_studless"},
                            "curves": {"rope": {"m": 3, "a_d": 6e10,
                                                "basis": "stress_chain"}},
                            "design_fatigue_factor": 5, "method": "dirlik"}}),
}


def _network_extras():
    body = {
        "name": "b", "position": [0, 0, 0], "orientation_deg": [0, 0, 0],
        "free": ["surge", "sway", "heave", "roll", "pitch", "yaw"], "mass": 1e6,
        "centre_of_gravity": [0, 0, -2],
        "hull": [{"shape": "cylinder", "bottom": -10, "top": 5, "radius": 6,
                  "centre": [0, 0]},
                 {"shape": "box", "bottom": -12, "top": -10, "length": 20, "width": 20,
                  "centre": [0, 0]}],
        "stiffness": [[0] * 6 for _ in range(6)], "added_mass": [[0] * 6 for _ in range(6)],
        "inertia": [1e8, 1e8, 1e8], "fixed_to": "water",
        "outline": {"length": 30, "beam": 12},
        "hydrodynamics": {
            "source": "table", "omega": [0.5, 1.0],
            "added_mass": [[[0] * 6] * 6] * 2, "damping": [[[0] * 6] * 6] * 2,
            "excitation": [{"heading_deg": 0, "re": [[0] * 6] * 2, "im": [[0] * 6] * 2}],
            "mean_drift": [{"heading_deg": 0, "values": [[0] * 6] * 2}]},
        "damping": {"linear": [0] * 6, "critical_fraction": {"surge": 0.05, "yaw": 0.02}},
    }
    return {
        "environment": {"depth": 60.0},
        "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 1e9},
                       "hawser": {"weight_in_water": 0, "ea": 1e7}},
        "bodies": [body, {"name": "s", "position": [200, 0, 0],
                          "hydrostatics": {"displaced_volume": 1000, "metacentre": [0, 0, 1],
                                           "waterplane_area": 100}, "mass": 1.025e6,
                          "free": ["surge", "sway", "heave", "yaw"]}],
        "points": [{"name": "A", "position": [400, 0]},
                   {"name": "P", "position": [100, 0, -20], "free": True, "mass": 10,
                    "volume": 0.1}],
        "lines": [{"name": "L1", "from": "A", "to": {"body": "s", "at": [5, 0, 0]},
                   "segments": [{"type": "chain", "length": 215}],
                   "anchor_type": {"type": "drag"}},
                  {"name": "L2", "from": {"body": "b", "at": [6, 0, 0]}, "to": "P",
                   "segments": [{"type": "chain", "length": 100}]},
                  {"name": "L3", "from": "P", "to": {"body": "s", "at": [-5, 0, 0]},
                   "segments": [{"type": "chain", "length": 100}]},
                  {"name": "L4", "from": [-300, 0], "to": {"body": "b", "at": [-6, 0, 0]},
                   "segments": [{"type": "hawser", "pretension": 1e4}]}],
        "walls": [{"name": "quay", "point": [0, -6, 0], "normal": [0, 1, 0],
                   "friction": 0.1, "friction_slip": 0.01}],
        "piles": [{"name": "p1", "position": [0, 20], "radius": 1.0, "top": 5,
                   "friction": 0.1, "friction_slip": 0.01, "bending_stiffness": 1e10},
                  {"name": "p2", "position": [20, 0], "radius": 1.0}],
        "fenders": [{"name": "F", "body": "b", "at": [0, -6, 0], "wall": "quay",
                     "reaction": {"stiffness": 1e6}, "rated_deflection": 0.5,
                     "mounted": "body", "height": 1.0}],
        "guides": [{"name": "G", "body": "b", "at": [0, 20, 0], "pile": "p1",
                    "clearance": 0.5, "pads": 8}],
    }


SOURCES = ([pytest.param(p, id=p.name) for p in sorted(CASES.glob("*.yaml"))]
           + [pytest.param(v, id=k) for k, v in EXTRA.items()])


def _key_of(field: str, by_path: dict):
    """``(section, key)`` of a quantity's field path: the innermost checked mapping that
    holds it (list indices of rows and points stripped)."""
    path = field
    while path:
        cut = max(path.rfind("."), path.rfind("["))
        if cut < 0:
            parent, key = "", path
        else:
            parent, key = path[:cut], path[cut:].lstrip(".")
        if not key.startswith("[") and parent in by_path:
            return by_path[parent], key
        path = parent
    return None, None


#: Sections that are one variant of several (a load model, an anchor kind): their
#: discriminating key was read before the mapping was checked, to choose the section.
VARIANTS = {n for s in schema.SECTIONS.values() for k in s.keys.values()
            if "|" in k.section for n in k.section.split("|")}


def _walk_checks(seen, quantities):
    by_path = {path: section for path, section, _, _ in seen}
    for path, section, given, read in seen:
        ignored = given - read
        if section in VARIANTS:
            ignored -= {"model", "type", "shape", "source"}
        assert not ignored, f"{path or 'the case'} ({section}): {sorted(ignored)} accepted " \
                            "but never read"
        assert given <= set(schema.get(section).keys)
    for field, (_, kind) in quantities.items():
        section, key = _key_of(field, by_path)
        assert section is not None, field
        spec = schema.get(section).keys[key]
        expected = set(spec.kinds) | ({"force_per_length"} if spec.kind == "weight" else set())
        assert kind in expected, f"{field}: converted as {kind}, documented as {expected}"


@pytest.mark.parametrize("source", SOURCES)
def test_what_the_validators_accept_read_and_convert_is_what_the_schema_says(walk, source):
    seen, quantities = walk(source)
    assert seen
    _walk_checks(seen, quantities)


def test_the_walk_reaches_every_section(walk):
    reached = set()
    for source in [p.values[0] for p in SOURCES] + [_network_extras()]:
        seen, quantities = walk(source)
        _walk_checks(seen, quantities)
        reached |= {section for _, section, _, _ in seen}
        seen.clear()
    # WAMIT coefficients come from files (tests/dynamics reads them), Capytaine's from a
    # panel solve; every other section is built here.
    assert set(schema.SECTIONS) - reached <= {"hydro_wamit", "hydro_capytaine"}
    assert {"case", "network", "outline", "hull_box", "guide", "fender"} <= reached


def test_an_unknown_key_is_refused_in_every_checked_mapping_of_a_case():
    data = yaml.safe_load((CASES / "floating_dock.yaml").read_text(encoding="utf-8"))
    data["environment"]["depht"] = 50
    with pytest.raises(CaseError, match="unknown key 'depht'.*allowed keys: depth, "
                                        "water_density"):
        moorsolve.load_case(data)


def test_the_documented_defaults_are_the_models_defaults():
    from moorsolve.model.environment import Environment, Seabed
    from moorsolve.model.lines import LineDrag
    from moorsolve.model.scene import Checks, SolverOptions
    from moorsolve.model.sea import DEFAULT_DURATION
    from moorsolve.model.stretch import INTERPOLATIONS
    env = Environment(depth=1.0)
    assert schema.default("environment", "water_density") == env.water_density
    assert schema.default("environment", "air_density") == env.air_density
    assert schema.default("environment", "gravity") == env.gravity
    assert schema.default("environment", "water_level") == env.water_level
    assert schema.default("environment", "north_deg") == env.compass.north_deg
    assert schema.default("environment", "directions") == env.compass.convention
    assert schema.default("seabed", "friction") == Seabed().friction
    assert schema.default("seabed", "tolerance") == Seabed().tolerance
    assert schema.default("seabed", "gradient") == tuple(Seabed().gradient)
    assert schema.default("waves", "duration") == DEFAULT_DURATION
    solver = SolverOptions()
    for key in ("tol", "max_iter", "max_time_s", "line_elements"):
        assert schema.default("solver", key) == getattr(solver, key), key
    checks = Checks()
    assert schema.default("checks", "standard") == checks.standard
    assert schema.default("checks", "consequence_class") == checks.consequence_class
    assert schema.default("stretch_table", "interpolation") == INTERPOLATIONS[0]
    assert schema.default("line_drag", "tangential") == LineDrag(normal=1.0).tangential
    # And a case that gives none of them gets them.
    case = moorsolve.load_case(copy.deepcopy(_DOCK))
    assert case.solver == solver
    assert case.environment.water_density == env.water_density


# ---- the reference page -----------------------------------------------------------------


def test_the_case_file_reference_page_is_generated_from_the_schema():
    sys.path.insert(0, str(ROOT / "docs"))
    import make_case_reference
    page = ROOT / "docs" / "case-file-reference.md"
    assert page.read_text(encoding="utf-8") == make_case_reference.render(), \
        "docs/case-file-reference.md is stale: run python docs/make_case_reference.py"
    text = page.read_text(encoding="utf-8")
    for sec in schema.SECTIONS.values():
        assert f"`{sec.where}`" in text or sec.where in text, sec.name
        for key in sec.keys:
            assert f"`{key}`" in text


@pytest.mark.parametrize("outline, field, message", [
    ({"length": 97}, "body.outline.beam", "required key 'beam' is missing"),
    ({"length": 97, "beam": 120}, "body.outline.beam", "must be <= 97 m"),
    ({"length": 97, "beam": 15.8, "draft": -1}, "body.outline.draft", "must be >= 0"),
    ({"length": 97, "beam": 15.8, "keel": 1}, "body.outline.keel", "unknown key 'keel'"),
])
def test_a_bad_ship_outline_names_its_field(outline, field, message):
    data = dict(copy.deepcopy(_DOCK), body={"outline": outline})
    with pytest.raises(CaseError, match=message) as err:
        moorsolve.load_case(data)
    assert err.value.field == field


def test_an_outline_draws_only():
    """The same equilibrium with and without a drawn outline, which the Body carries."""
    bare = moorsolve.solve(moorsolve.load_case(copy.deepcopy(_DOCK) | {"body": {}}))
    drawn = moorsolve.load_case(copy.deepcopy(_DOCK) | {"body": {
        "outline": {"length": "97 m", "beam": 15.8, "draft": 3.8, "heading_deg": 10}}})
    assert drawn.bodies[0].outline.heading_deg == 10.0
    assert moorsolve.solve(drawn).body == bare.body
