"""Directions given as ``from_deg`` or as compass bearings (``environment.directions:
nautical``) mean the same scene as the contract's ``toward_deg`` (counter-clockwise from +x),
and the tools that turn a case's flows write the file's own terms."""

from __future__ import annotations

import copy
import itertools

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve import CaseError
from moorsolve.model.directions import Compass, direction_edit
from moorsolve.model.paths import with_values

from conftest import CASES

FLOWS = ("wind", "current", "waves")


def dock() -> dict:
    with open(CASES / "floating_dock.yaml", encoding="utf-8") as f:
        return yaml.safe_load(f)


def restated(data: dict, key: str, nautical: bool, north_deg: float = 90.0) -> dict:
    """``data`` with every flow's direction given under ``key`` in the chosen convention."""
    out = copy.deepcopy(data)
    env = out["environment"]
    if nautical:
        env["directions"] = "nautical"
        if north_deg != 90.0:
            env["north_deg"] = north_deg
    compass = Compass("nautical" if nautical else "mathematical", north_deg)
    for f in FLOWS:
        toward = float(env[f].pop("toward_deg"))
        env[f][key] = compass.file_value(toward, key)
    return out


@pytest.mark.parametrize("north", [90.0, 0.0, 33.0])
def test_compass_round_trip(north):
    for convention, key in itertools.product(("mathematical", "nautical"),
                                             ("toward_deg", "from_deg")):
        compass = Compass(convention, north)
        for toward in np.arange(0.0, 360.0, 7.5):
            value = compass.file_value(toward, key)
            assert 0.0 <= value < 360.0
            assert compass.toward_deg(value, key) % 360.0 == pytest.approx(toward, abs=1e-9)


def test_known_bearings():
    # North along +y (x east): a wind from 060 (ENE) travels toward 240, i.e. 210 deg
    # counter-clockwise from +x; from the north (000) it travels toward -y (270).
    north_up = Compass("nautical", 90.0)
    assert north_up.toward_deg(60.0, "from_deg") == pytest.approx(210.0)
    assert north_up.toward_deg(0.0, "from_deg") == pytest.approx(270.0)
    assert north_up.toward_deg(90.0, "toward_deg") == pytest.approx(0.0)    # toward east = +x
    assert Compass().toward_deg(250.0, "from_deg") == pytest.approx(70.0)
    # North along +x: a current setting toward 090 (east) travels toward -y.
    assert Compass("nautical", 0.0).toward_deg(90.0, "toward_deg") == pytest.approx(270.0)


@pytest.mark.parametrize("key,nautical,north", [("from_deg", False, 90.0),
                                                ("from_deg", True, 90.0),
                                                ("toward_deg", True, 90.0),
                                                ("from_deg", True, -30.0)])
def test_every_form_is_the_same_scene(key, nautical, north):
    reference = moorsolve.load_case(dock())
    case = moorsolve.load_case(restated(dock(), key, nautical, north))
    for f in FLOWS:
        assert getattr(case.environment, f).toward_deg % 360 == pytest.approx(
            getattr(reference.environment, f).toward_deg % 360, abs=1e-9)
    a, b = moorsolve.solve(reference), moorsolve.solve(case)
    assert b.body["x_m"] == pytest.approx(a.body["x_m"], abs=1e-9)
    assert b.body["y_m"] == pytest.approx(a.body["y_m"], abs=1e-9)
    assert b.body["yaw_deg"] == pytest.approx(a.body["yaw_deg"], abs=1e-9)


@pytest.mark.parametrize("edit,field,words", [
    (lambda e: e["wind"].update(from_deg=10), "environment.wind.from_deg", "not both"),
    (lambda e: e.update(directions="nautical") or e["wind"].pop("toward_deg"),
     "environment.wind.from_deg", "bearing"),
    (lambda e: e.update(north_deg=10), "environment.north_deg", "nautical"),
    (lambda e: e.update(directions="compass"), "environment.directions", "nautical"),
])
def test_direction_errors_name_the_field(edit, field, words):
    data = dock()
    edit(data["environment"])
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(data)
    assert err.value.field == field and words in str(err.value)


def test_a_path_edit_replaces_the_other_direction_key():
    data = restated(dock(), "from_deg", True)
    edited = with_values(data, {"environment.wind.toward_deg": 90.0})
    assert edited["environment"]["wind"] == {"speed": data["environment"]["wind"]["speed"],
                                             "toward_deg": 90.0}
    assert "from_deg" in data["environment"]["wind"]              # the original untouched
    # Nautical: toward 090 is toward east, +x.
    assert moorsolve.load_case(edited).environment.wind.toward_deg == pytest.approx(0.0)


def test_direction_edit_writes_the_files_terms():
    case = moorsolve.load_case(restated(dock(), "from_deg", True))
    path, value = direction_edit(case, "wind", 0.0)           # toward +x = toward east
    assert path == "environment.wind.from_deg" and value == pytest.approx(270.0)  # from west
    plain = moorsolve.load_case(dock())
    assert direction_edit(plain, "current", 123.0) == ("environment.current.toward_deg", 123.0)


def test_envelope_of_a_nautical_case_equals_the_plain_one():
    plain = moorsolve.offset_envelope(moorsolve.load_case(dock()), step_deg=45)
    nautical = moorsolve.offset_envelope(
        moorsolve.load_case(restated(dock(), "from_deg", True)), step_deg=45)
    np.testing.assert_allclose(nautical.heading_deg, plain.heading_deg)
    np.testing.assert_allclose(nautical.offset_m, plain.offset_m, atol=1e-9)
    np.testing.assert_allclose(nautical.worst_tension_N, plain.worst_tension_N, rtol=1e-9)


def test_study_headings_turn_the_flows_in_the_files_terms():
    from moorsolve.io.study_file import load_case_variant, load_study
    study_data = {"line_types": {"chain81": {"mass_per_length": "149.5 kg/m"}},
                  "variables": {"all": {"type": "length", "legs": "*", "lower": "120.6 m",
                                        "upper": "135 m"}},
                  "load_cases": [{"name": "turn", "headings": [0, 90]}]}
    plain = moorsolve.load_case(dock())
    nautical = moorsolve.load_case(restated(dock(), "from_deg", True))
    for a, b in zip(load_study(study_data, plain).load_cases,
                    load_study(study_data, nautical).load_cases):
        assert "environment.wind.from_deg" in b.edits and a.name == b.name
        ca, cb = load_case_variant(plain, a.edits), load_case_variant(nautical, b.edits)
        for f in FLOWS:
            assert getattr(cb.environment, f).toward_deg % 360 == pytest.approx(
                getattr(ca.environment, f).toward_deg % 360, abs=1e-9)
