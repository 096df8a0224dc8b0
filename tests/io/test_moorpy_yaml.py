"""MoorPy's mooring YAML as a second door in and out (issue 19): MoorPy's own spelling, the
windIO/RAFT spelling, MoorPy's ``file:`` key, bridles in the network form, and a round trip
through export-moorpy."""

import math

import pytest
import yaml

import moorsolve
from moorsolve.cli import main
from moorsolve.io import read_import, read_moorpy
from conftest import TESTS


DATA = TESTS / "data" / "moorpy"
MOORDYN = TESTS / "data" / "moordyn"


def test_moorpy_spelling():
    imp = read_moorpy(DATA / "spread_moorpy.yaml")
    data = imp.data
    assert imp.form == "legs" and [leg["name"] for leg in data["legs"]] == ["line1", "line2",
                                                                           "line3"]
    env = data["environment"]
    assert (env["depth"], env["water_density"], env["gravity"]) == (180, 1025, 9.81)
    chain = data["line_types"]["chain"]
    # MoorPy's weight in water: g (mass_density - rho pi d^2 / 4), its g = 9.81.
    assert chain["weight_in_water"] == pytest.approx(
        9.81 * (126.0 - 1025 * math.pi * 0.1458 ** 2 / 4), rel=1e-14)
    assert chain["mbl"] == 7.2e6 and chain["ea"] == 6.4e8
    text = imp.report.text()
    assert "gravity 9.81 m/s^2 (MoorPy's default: its YAML has none)" in text
    assert "line_types[0] (chain): cost: not used by the statics" in text
    assert data["legs"][1]["anchor"] == [-380.0, 658.179, -180.0]   # type: anchor
    assert data["body"] == {"free": []}                              # vessel / fairlead
    result = moorsolve.solve(moorsolve.load_case(data))
    t = [leg.fairlead_tension_N for leg in result.legs]
    assert max(t) - min(t) < 1e-5 * max(t)                           # 120 deg symmetric


def test_windio_spelling_in_a_raft_file():
    imp = read_moorpy(DATA / "raft_mooring_windio.yaml")
    data = imp.data
    assert data["name"] == "windIO three-leg semi"
    assert data["legs"][0]["anchor"] == [837.0, 0.0, -200.0]         # location z: seabed
    assert data["line_types"]["main"]["mbl"] == 5.6e6
    assert "anchor_types: MoorPy's YAML reader does not read them either" in imp.report.text()
    assert moorsolve.solve(moorsolve.load_case(data)).certificate.certified


def test_bridle_takes_the_network_form_with_the_file_names():
    imp = read_moorpy(DATA / "bridle_buoy_moorpy.yaml")
    assert imp.form == "network" and "free point apex joins 3 lines (bridleA, bridleB, main)" \
        in imp.form_reason
    data = imp.data
    points = {p["name"]: p for p in data["points"]}
    assert points["apex"] == {"name": "apex", "position": [60.0, 0.0, -25.0], "free": True,
                              "mass": 800.0, "volume": 4.0}
    lines = {ln["name"]: ln for ln in data["lines"]}
    assert lines["main"]["from"] == "anchor" and lines["main"]["to"] == "apex"
    assert lines["bridleA"]["to"] == {"body": "vessel", "at": [30.0, 8.0, -6.0]}
    assert data["bodies"] == [{"name": "vessel", "position": [0.0, 0.0, 0.0], "free": []}]


def test_file_key_loads_the_moordyn_file():
    imp = read_moorpy(DATA / "moordyn_file_moorpy.yaml")
    assert imp.data == read_import(MOORDYN / "openfast_v2_seabed.dat").data
    assert "which MoorPy loads instead" in imp.report.text()


def test_round_trip_through_moorpy_yaml(tmp_path):
    """A MoorDyn import (clump, buoy, multi-segment legs) out to MoorPy's YAML and back:
    the same lines, the same tensions."""
    case = moorsolve.load_case(read_import(MOORDYN / "semisub_v2.dat").data)
    out = tmp_path / "semi_moorpy.yaml"
    moorsolve.export_moorpy(case, out)
    text = out.read_text()
    assert "create the System with g=9.80665" in text
    written = yaml.safe_load(text)
    assert [p["type"] for p in written["points"]][:2] == ["fixed", "vessel"]
    back = moorsolve.import_moorpy(out)
    assert back["environment"]["gravity"] == 9.80665               # our gravity key
    r0, r1 = moorsolve.solve(case), moorsolve.solve(moorsolve.load_case(back))
    assert len(r0.legs) == len(r1.legs)
    for a, b in zip(r0.legs, r1.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-9)
        assert b.anchor_tension_N == pytest.approx(a.anchor_tension_N, rel=1e-9)


@pytest.mark.parametrize("edit,message", [
    (lambda d: d.pop("water_depth"), "spread_moorpy.yaml: water_depth: missing 'water_depth'"),
    (lambda d: d["lines"][1].update(endB="fair9"), "lines[1].endB: unknown point 'fair9'"),
    (lambda d: d["points"][0].update(type="hovering"), "points[0].type: unknown point type"),
    (lambda d: d["line_types"][0].update(stiffness="stiff"),
     "line_types[0].stiffness: 'stiff' is not a number"),
])
def test_bad_moorpy_yaml_names_the_entry(edit, message, tmp_path):
    data = yaml.safe_load((DATA / "spread_moorpy.yaml").read_text())
    edit(data)
    path = tmp_path / "spread_moorpy.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(moorsolve.CaseError) as err:
        read_moorpy(path)
    assert message in str(err.value)


def test_commands(tmp_path, capsys):
    case = tmp_path / "spread.yaml"
    assert main(["import-moorpy", str(DATA / "spread_moorpy.yaml"), "-o", str(case)]) == 0
    out = capsys.readouterr().out
    assert "  converted:" in out and "solved at rest" in out
    assert case.read_text().startswith("# Imported from the MoorPy YAML spread_moorpy.yaml")
    back = tmp_path / "again.yaml"
    assert main(["export-moorpy", str(case), "-o", str(back)]) == 0
    assert yaml.safe_load(back.read_text())["water_depth"] == 180
    bad = tmp_path / "bad.yaml"
    bad.write_text("water_depth: 10\nline_types: []\npoints: []\nlines: []\n")
    assert main(["import-moorpy", str(bad), "-o", str(tmp_path / "x.yaml")]) == 2
    assert "bad.yaml: line_types: no line types" in capsys.readouterr().err
    assert not (tmp_path / "x.yaml").exists()


def test_network_case_out_to_moorpy_yaml_and_back(tmp_path):
    """The bridle (a free apex joining three lines, a held body) through MoorPy's YAML:
    the same lines by name, the same tensions; MoorDyn export writes it as v2 only."""
    case = moorsolve.load_case(read_import(MOORDYN / "bridle_v2.dat").data)
    out = tmp_path / "bridle.yaml"
    moorsolve.export_moorpy(case, out)
    written = yaml.safe_load(out.read_text())
    types = {p["name"]: p["type"] for p in written["points"]}
    assert types["point3"] == "free" and types["point4"] == "fixed"
    assert types["line1_B"] == "vessel"
    back = read_moorpy(out)
    assert back.form == "network"
    r0, r1 = moorsolve.solve(case), moorsolve.solve(moorsolve.load_case(back.data))
    for leg in r0.legs:
        other = r1.leg(leg.name)
        assert other.fairlead_tension_N == pytest.approx(leg.fairlead_tension_N, rel=1e-9)
        assert other.anchor_tension_N == pytest.approx(leg.anchor_tension_N, rel=1e-9)
    assert "BODIES" in moorsolve.case_to_moordyn(case)
    with pytest.raises(moorsolve.CaseError, match="v2 only"):
        moorsolve.case_to_moordyn(case, version=1)
    two = moorsolve.load_case(read_import(MOORDYN / "shared_line_two_bodies_v2.dat").data)
    with pytest.raises(moorsolve.CaseError, match="2 bodies .*one vessel"):
        moorsolve.export_moorpy(two, tmp_path / "two.yaml")
