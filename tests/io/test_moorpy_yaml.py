"""MoorPy's mooring YAML as a second door in and out (issue 19): MoorPy's own spelling, the
windIO/RAFT spelling, MoorPy's ``file:`` key, bridles in the network form, and a round trip
through export-moorpy."""

import math
import re

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


# ---- bodies: mass, hydrostatics, springs, constant force -----------------------------------

SPAR = TESTS.parent / "cases" / "oc3_spar.yaml"
SURGE_FORCE = 8.0e5          # N, a constant force along x (of the order of rated thrust)


def _spar_with_force():
    import dataclasses
    case = moorsolve.load_case(SPAR)
    (spar,) = case.bodies
    loads = dataclasses.replace(spar.loads, force=(SURGE_FORCE, 0.0, 0.0, 0.0, 0.0, 0.0))
    return dataclasses.replace(case, bodies=(dataclasses.replace(spar, loads=loads),))


def test_export_writes_the_body_and_import_reads_it_back(tmp_path):
    case = _spar_with_force()
    out = tmp_path / "spar.yaml"
    data = moorsolve.export_moorpy(case, out)
    (body,) = data["bodies"]
    spar = case.bodies[0]
    assert body["type"] == 0 and body["DOFs"] == [0, 1, 2, 3, 4, 5]
    assert body["m"] == spar.mass and body["rCG"] == list(spar.centre_of_gravity)
    assert body["v"] == spar.hydrostatics.displaced_volume
    assert body["rM"] == list(spar.hydrostatics.metacentre)
    assert body["AWP"] == spar.hydrostatics.waterplane_area
    assert body["f6Ext"] == [SURGE_FORCE, 0, 0, 0, 0, 0]
    assert body["stiffness"][5][5] == 98.34e6
    text = out.read_text()
    assert "MoorPy solves without it" in text and "ms.parseYAML(d)" in text
    back = moorsolve.load_case(read_moorpy(out).data)
    (again,) = back.bodies
    for key in ("free", "position", "orientation_deg", "mass", "centre_of_gravity",
                "hydrostatics", "stiffness"):
        assert getattr(again, key) == getattr(spar, key), key
    assert again.loads.force == (SURGE_FORCE, 0, 0, 0, 0, 0)
    a, b = moorsolve.solve(case), moorsolve.solve(back)
    for la, lb in zip(a.legs, b.legs):
        assert lb.fairlead_tension_N == pytest.approx(la.fairlead_tension_N, rel=1e-9)


def test_a_posed_body_keeps_its_frame(tmp_path):
    """A body away from the origin and turned: its vessel points stay in its frame and the
    pose goes in r6, so the scene read back is the same scene."""
    import dataclasses
    case = moorsolve.load_case(TESTS.parent / "cases" / "oc4_semi.yaml")
    data = moorsolve.io.case_to_moorpy(case)
    assert data["bodies"][0]["DOFs"] == [0, 1, 5]
    assert data["bodies"][0]["f6Ext"] == [8.0e5, 0.0, 0.0, 0.0, 0.0, 0.0]
    (body,) = case.bodies
    moved = dataclasses.replace(case, bodies=(dataclasses.replace(
        body, position=(30.0, -20.0, 0.0), orientation_deg=(0.0, 0.0, 25.0)),), form="network")
    moorsolve.export_moorpy(moved, tmp_path / "moved.yaml")
    back = moorsolve.load_case(read_moorpy(tmp_path / "moved.yaml").data)
    assert back.bodies[0].position == (30.0, -20.0, 0.0)
    assert back.bodies[0].orientation_deg == pytest.approx((0.0, 0.0, 25.0), abs=1e-12)
    a, b = moorsolve.solve(moved), moorsolve.solve(back)
    assert b.bodies[0]["x_m"] == pytest.approx(a.bodies[0]["x_m"], rel=1e-9)
    for la, lb in zip(a.legs, b.legs):
        assert lb.fairlead_tension_N == pytest.approx(la.fairlead_tension_N, rel=1e-9)


def test_moorpy_solves_the_exported_spar_to_our_equilibrium(tmp_path):
    """MoorPy 1.3.0 loads the exported file (the body from 'bodies' by addBody, the rest by
    parseYAML, as the file's header says) and finds the same 6-DOF equilibrium: offsets and
    tensions to 1e-6 (seen: 3e-13 in tension, surge 24.463566 m, heave -0.266093 m, pitch
    2.435899 deg in both). The spar's yaw spring, which MoorPy cannot take, is inert here: the
    force along the symmetry plane of the lines leaves yaw at zero."""
    mp = pytest.importorskip("moorpy")
    import contextlib
    import io
    import warnings
    import numpy as np
    case = _spar_with_force()
    out = tmp_path / "spar.yaml"
    moorsolve.export_moorpy(case, out)
    d = yaml.safe_load(out.read_text())
    ms = mp.System(depth=d["water_depth"], rho=d["rho"], g=d["gravity"])
    b = d["bodies"][0]
    ms.addBody(b["type"], np.array(b["r6"]), m=b.get("m", 0), v=b.get("v", 0),
               rCG=np.array(b.get("rCG", [0, 0, 0])), AWP=b.get("AWP", 0),
               rM=np.array(b.get("rM", [0, 0, 0])), f6Ext=np.array(b.get("f6Ext", [0] * 6)),
               DOFs=b["DOFs"])
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ms.parseYAML(d)
        ms.initialize()
        ms.solveEquilibrium(tol=1e-6, maxIter=500)
    ours = moorsolve.solve(case)
    spar = ours.bodies[0]
    assert abs(spar["yaw_deg"]) < 1e-9               # the spring carries nothing
    r6 = ms.bodyList[0].r6
    assert r6[0] == pytest.approx(spar["x_m"], rel=1e-6)
    assert r6[2] == pytest.approx(spar["z_m"], rel=1e-6)
    assert math.degrees(r6[4]) == pytest.approx(spar["pitch_deg"], rel=1e-6)
    assert abs(r6[1]) < 1e-6 * abs(r6[0]) and abs(r6[5]) < 1e-6
    for line, leg in zip(ms.lineList, ours.legs):
        assert line.TB == pytest.approx(leg.fairlead_tension_N, rel=1e-6)
        assert line.TA == pytest.approx(leg.anchor_tension_N, rel=1e-6)


@pytest.mark.parametrize("edit, message", [
    (lambda b: b.update(type=2), "bodies[0].type: 2 must be 0 (free), 1 (fixed) or -1"),
    (lambda b: b.update(r6=[0, 0, 0]), "bodies[0].r6: [0, 0, 0] must be a list of 6 numbers"),
    (lambda b: b.update(DOFs=[0, 7]), "bodies[0].DOFs: [0, 7] must list DOF indices"),
    (lambda b: b.update(m=-1), "bodies[0].m: -1 must be >= 0"),
    (lambda b: b.update(mass=1), "bodies[0].mass: unknown key"),
    (lambda b: b.update(stiffness=[[0] * 6] * 5), "bodies[0].stiffness: must be a 6x6"),
])
def test_bad_body_entry_is_named(edit, message, tmp_path):
    data = moorsolve.io.case_to_moorpy(_spar_with_force())
    edit(data["bodies"][0])
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(moorsolve.CaseError, match=re.escape(message)):
        read_moorpy(path)
