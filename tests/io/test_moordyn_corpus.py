"""MoorDyn files as they are found (issue 19): a corpus of hand-written files in every
layout the parsers meet (tests/data/moordyn/), each quirk checked where it shows, every file
imported, the legs-form ones solved, the network-form ones checked against the contract's
shape (CONTRACT.md, "The scene as a network"), and what MoorDyn refuses refused with the
line, the reason and the version guess."""

import math

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve.cli import main
from moorsolve.io import convert_moordyn, read_import, read_moordyn
from moorsolve.io.moordyn import MoorDynError
from moorsolve.io.moordyn_parse import parse_moordyn_text
from conftest import DATA, ROOT

DATA = DATA / "moordyn"
CASES = ROOT / "cases"
G, RHO = 9.80665, 1025.0

#: The case form each corpus file takes, and why (a fragment of the reason).
FORMS = {
    "semisub_v2.dat": ("legs", ""),
    "spar_v1.dat": ("legs", ""),
    "semi_openfast_v1.dat": ("legs", ""),
    "lines_c_v1.txt": ("legs", ""),
    "semitaut_v2_quirks.dat": ("legs", ""),
    "buoy_single_fairlead_v2.dat": ("legs", ""),
    "windows_crlf_v2.dat": ("legs", ""),
    "no_depth_v2.dat": ("legs", ""),
    "openfast_v2_seabed.dat": ("legs", ""),
    "bridle_v2.dat": ("network", "free point 3 joins 3 lines (1, 2, 3)"),
    "free_buoy_six_dof_v2.dat": ("network", "body 1 is Free"),
    "coupled_pinned_v2.dat": ("network", "body 1 is CoupledPinned"),
    "shared_line_two_bodies_v2.dat": ("network", "several carriers"),
    "rods_v2.dat": ("network", "rod 2 is Pinned"),
    "hub_v2.dat": ("network", "free point 4 joins 4 lines"),
    "dangling_buoys_v2.dat": ("network", "no body carries the lines"),
    "farm_turbines_v2.dat": ("network", "several carriers"),
    "stale_names_v2.dat": ("network", "no body carries the lines"),
    "connectors_v2.dat": ("network", "line(s) attach to rod 1 (zero length)"),
    "weightless_dry_v2.dat": ("network", "body 1 is free"),
    "tilted_body_v2.dat": ("network", "body 1 is Free"),
}


def test_the_corpus_is_listed_here():
    assert sorted(p.name for p in DATA.iterdir()) == sorted(FORMS)


@pytest.mark.parametrize("name", sorted(FORMS))
def test_every_file_imports_in_its_form(name):
    imp = read_import(DATA / name)
    form, reason = FORMS[name]
    assert imp.form == form and reason in imp.form_reason
    assert imp.report.read[0].startswith(f"MoorDyn v{imp.file.version} file (")
    data = imp.data
    if name == "farm_turbines_v2.dat":
        # FAST.Farm's turbine positions are not in the file: put turbine 2 where the file's
        # anchors and shared line say it is, as a user would.
        next(b for b in data["bodies"] if b["name"] == "turbine2")["position"] = [1000.0, 0, 0]
    result = moorsolve.solve(moorsolve.load_case(data))
    assert result.certificate.certified
    # Every line carries tension (no empty answer) and no body was lost far away.
    assert all(leg.fairlead_tension_N > 0 for leg in result.legs)
    assert not [w for w in result.warnings if "unstable" in str(w)]


@pytest.mark.parametrize("name", sorted(n for n, (f, _) in FORMS.items() if f == "network"))
def test_network_cases_have_the_contract_shape(name):
    imp = read_import(DATA / name)
    data, scene = imp.data, imp.file
    assert set(data) <= {"name", "environment", "line_types", "bodies", "points", "lines",
                         "moordyn"}
    bodies = {b["name"]: b for b in data.get("bodies", [])}
    points = {p["name"]: p for p in data.get("points", [])}
    body_keys = {"name", "position", "orientation_deg", "free", "mass", "centre_of_gravity",
                 "hydrostatics", "hull"}
    dofs = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    for b in bodies.values():
        assert set(b) <= body_keys and len(b["position"]) == 3
        assert all(d in dofs for d in b["free"])
        if b["free"] and set(b["free"]) & {"heave", "roll", "pitch"}:
            assert b["mass"] > 0                  # the contract needs it
        if "hydrostatics" in b:
            assert set(b["hydrostatics"]) == {"displaced_volume", "metacentre",
                                              "waterplane_area"}
            assert "hull" not in b
    for p in points.values():
        assert set(p) <= {"name", "position", "free", "mass", "volume"}
        assert ("mass" in p) == ("volume" in p) == bool(p.get("free"))

    def check_end(end):
        if isinstance(end, str):
            assert end in points
        else:
            assert set(end) == {"body", "at"} and end["body"] in bodies and len(end["at"]) == 3

    # Every MoorDyn line is line<N>, end A at its AttachA, one segment of its type and length.
    rows = {int(r.values[0]): r.values for r in scene.tables["lines"]}
    assert [ln["name"] for ln in data["lines"]] == [f"line{i}" for i in sorted(rows)]
    for ln in data["lines"]:
        v = rows[int(ln["name"][4:])]
        check_end(ln["from"])
        check_end(ln["to"])
        assert ln["segments"] == [{"type": v[1], "length": float(v[4])}]
        token = v[2].upper().lstrip("POINTC")
        if isinstance(ln["from"], str) and token.isdigit():
            assert ln["from"] == f"point{int(token)}"
    # The block maps every case line and point back to its MoorDyn row.
    net = data["moordyn"]["network"]
    assert set(net["lines"]) == {ln["name"] for ln in data["lines"]}
    assert all(net["lines"][f"line{i}"]["id"] == i for i in rows)
    for name in points:
        if name.startswith("point"):
            assert net["points"][name]["id"] == int(name[5:])
    moorsolve.model.moordyn_block.validate_moordyn_block(
        data["moordyn"], "moordyn", data["line_types"], (),
        {"lines": [ln["name"] for ln in data["lines"]], "points": list(points),
         "bodies": list(bodies)})


def _everything_accounted_for(imp):
    """Every entry of the file is in the case, the block or the report."""
    data, scene = imp.data, imp.file
    text = yaml.safe_dump(data) + imp.report.text()
    for row in scene.tables["line_types"]:
        assert row.values[0] in data["line_types"]
    for kind, word in (("points", "point"), ("lines", "line"), ("bodies", "body"),
                       ("rods", "rod")):
        for row in scene.tables.get(kind, []):
            ident = int(row.values[0])
            assert (f"{word}{ident}" in text or f"{word} {ident}" in text
                    or f"id: {ident}" in text), (kind, ident)
    for name, value, _ in scene.options:
        assert name in text
    return text


@pytest.mark.parametrize("name", sorted(FORMS))
def test_everything_in_the_file_is_in_the_case_or_the_report(name):
    _everything_accounted_for(read_import(DATA / name))


# ---- the quirks, file by file -----------------------------------------------------------


def test_openfast_v1_count_rows_fortran_exponents_and_defaults():
    imp = read_import(DATA / "semi_openfast_v1.dat")
    md = imp.file
    assert md.version == 1 and "in column 3, as v1 does" in md.version_reason
    assert {k: c[0] for k, c in md.counts.items() if c} == {"line_types": 1, "points": 6,
                                                             "lines": 3}
    assert "FALSE    Echo      - echo the input file data (flag)" in md.header
    case = moorsolve.load_case(imp.data)
    assert case.line_types["main"].ea == 6.11e8                 # 6.11D8
    env = case.environment
    # No WtrDpth: the deepest point; no g or rho: OpenFAST's 9.80665 and 1025.
    assert (env.depth, env.gravity, env.water_density) == (180.0, G, RHO)
    result = moorsolve.solve(case)
    # Three legs 120 deg apart, same line and geometry: equal tensions.
    t = [leg.fairlead_tension_N for leg in result.legs]
    assert max(t) - min(t) < 1e-6 * max(t)
    assert case.moordyn["outputs"][:1] == ["FairTen1"]


def test_moordyn_c_v1_tabs_free_numbering_and_a_sinker():
    imp = read_import(DATA / "lines_c_v1.txt")
    case = moorsolve.load_case(imp.data)
    assert imp.file.version == 1 and case.environment.depth == 95.0
    l2 = next(leg for leg in case.legs if leg.name == "L2")
    assert [s.line_type.name for s in l2.segments] == ["chain", "wire"]
    assert (l2.clumps[0].mass, l2.clumps[0].volume) == (4500.0, 0.3)
    assert l2.anchor == (-155.0, 268.468, -95.0) and l2.fairlead == (-3.0, 5.196, -8.0)
    assert imp.data["moordyn"]["legs"]["L2"]["points"][1]["id"] == 25
    assert imp.data["moordyn"]["outputs"] == ["FairTen1 FairTen2 FairTen3 FairTen4",
                                              "AnchTen1 AnchTen4"]


def test_semitaut_quirks():
    imp = read_import(DATA / "semitaut_v2_quirks.dat")
    md, data = imp.file, imp.data
    assert md.version == 2
    types = data["line_types"]
    assert types["poly"]["ea"] == 1.10e8 and types["topchain"]["ea"] == 7.54e8
    block_types = data["moordyn"]["line_types"]
    assert block_types["chain84"]["cf"] == "0.18" and block_types["poly"]["ea"] == "1.10e8|3.30e8"
    assert block_types["topchain"]["cl"] == "0.9" and block_types["poly"]["ba"] == "-0.8|-0.5"
    assert types["chain84"]["weight_in_water"] == pytest.approx(
        G * (141.1 - RHO * math.pi * 0.1512 ** 2 / 4), rel=1e-14)
    # The lower-case 'bodies' header, CG and inertia with bars.
    assert data["moordyn"]["body"]["columns"]["cg"] == "0|0|-8.5"
    env = data["environment"]
    assert (env["depth"], env["gravity"], env["water_density"]) == (300.0, G, RHO)
    text = imp.report.text()
    assert "no g: MoorDyn's default gravity 9.80665" in text
    assert "option row '0.5' has no name; skipped" in text
    assert "options MoorDyn does not know (it warns and ignores them): ICgenQuick" in text
    # Leg 4 carries the 9 m^3 buoy of the Point-keyword point 6.
    l4 = next(leg for leg in data["legs"] if leg["name"] == "L4")
    assert l4["segments"][1] == {"clump": {"mass": 2000.0, "volume": 9.0}}
    result = moorsolve.solve(moorsolve.load_case(data))
    # Legs 1 and 7 are the same leg turned 240 deg (to the file's 4 decimals: a stiff
    # polyester turns 1e-4 m into a few newtons).
    assert result.leg("L1").fairlead_tension_N == pytest.approx(
        result.leg("L7").fairlead_tension_N, rel=1e-4)


def test_single_fairlead_at_the_body_origin_imports_and_solves():
    imp = read_import(DATA / "buoy_single_fairlead_v2.dat")
    case = moorsolve.load_case(imp.data)
    assert case.body.free == ()
    (leg,) = case.legs
    assert leg.fairlead == (10.0, -5.0, 0.0)          # the body origin, placed by X0 Y0
    result = moorsolve.solve(case)
    assert result.certificate.certified and result.leg("L1").fairlead_tension_N > 0


def test_windows_file_crlf_latin1_sections_and_forces():
    md = read_moordyn(DATA / "windows_crlf_v2.dat")
    assert set(md.sections) == {"FAILURE", "EXTERNAL LOADS"}
    imp = convert_moordyn(md)
    text = imp.report.text()
    # The file names a grid it was not shipped with: reported, the seabed flat.
    assert "SeafloorFile 'bathymetry.txt': no such file beside the input file" in text
    assert "seabed" not in imp.data["environment"]
    assert "FAILURE (line" in text and "EXTERNAL LOADS (line" in text
    assert "OUTPUTS (line" in text and "6 output channel(s)" in text
    legs = imp.data["moordyn"]["legs"]
    assert legs["L1"]["points"][0]["columns"]["fx"] == "0"      # 12-column points
    assert ["kBot", "5.0D5"] in imp.data["moordyn"]["options"]


def test_openfast_v2_seabed_keyword_and_bang_comments():
    imp = read_import(DATA / "openfast_v2_seabed.dat")
    case = moorsolve.load_case(imp.data)
    assert [leg.anchor[2] for leg in case.legs] == [-200.0] * 3
    assert case.environment.water_density == RHO                # rhoW
    assert "Z 'seabed' is z = -200 m" in imp.report.text()


def test_no_depth_and_the_modelling_warnings():
    from moorsolve.checks.modelling import modelling_warnings
    imp = read_import(DATA / "no_depth_v2.dat")
    case = moorsolve.load_case(imp.data)
    assert case.environment.depth == 85.0
    assert "no WtrDpth: water depth 85 m, that of the deepest point" in imp.report.text()
    result = moorsolve.solve(case)
    warnings = modelling_warnings(case, result)
    assert [(w.code, w.subject) for w in warnings] == [("anchor_above_seabed", "L2")]
    assert warnings[0].value == pytest.approx(7.0)
    assert "line L2: its fixed end is 7 m above the seabed" in str(warnings[0])
    # Read against a seabed 10 m shallower, the chains run through it: flagged with the
    # depth they reach (the lines rest on the solved seabed at z = -85 m).
    shallow = dict(imp.data, environment=dict(imp.data["environment"], depth=75.0))
    shallow["legs"] = [dict(leg, anchor=leg["anchor"][:2]) for leg in shallow["legs"]]
    below = [w for w in modelling_warnings(moorsolve.load_case(shallow), result)
             if w.code == "below_seabed"]
    assert [w.subject for w in below] == ["L1", "L2", "L3"]
    assert all(w.value == pytest.approx(10.0) for w in below)


def test_slack_and_drift_warnings():
    from moorsolve.checks.modelling import modelling_warnings
    data = read_import(DATA / "semi_openfast_v1.dat").data
    # Lines far longer than their span lie slack on the seabed.
    data["legs"] = [dict(leg, segments=[{"type": "main", "length": 1500.0}])
                    for leg in data["legs"]]
    case = moorsolve.load_case(data)
    warnings = modelling_warnings(case, moorsolve.solve(case))
    assert [w.code for w in warnings] == ["all_slack"]
    assert "all 3 lines are slack" in str(warnings[0])
    # The floating dock (20.85 m of water) with its chain stiffness slipped to 2e6 N (kN
    # read as N would be 5.6e5): the typhoon stretches the chains and it drifts 50 m.
    data = yaml.safe_load((CASES / "floating_dock.yaml").read_text())
    data["line_types"]["chain81"]["ea"] = 2.0e6
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case)
    drift = [w for w in modelling_warnings(case, result) if w.code == "drift"]
    offset = math.hypot(result.body["x_m"], result.body["y_m"])
    assert offset > 40.0 and drift[0].value == pytest.approx(offset)
    assert "more than the water depth 20.85 m" in str(drift[0])


# ---- network cases: the mapping ------------------------------------------------------------


def _network(name):
    imp = read_import(DATA / name)
    return imp, {b["name"]: b for b in imp.data.get("bodies", [])}, \
        {p["name"]: p for p in imp.data.get("points", [])}, \
        {ln["name"]: ln for ln in imp.data["lines"]}


def test_bridle():
    imp, bodies, points, lines = _network("bridle_v2.dat")
    assert bodies == {"body1": {"name": "body1", "position": [0.0, 0.0, 0.0], "free": []}}
    assert points["point3"] == {"name": "point3", "position": [150.0, 0.0, -30.0], "free": True,
                                "mass": 0.0, "volume": 0.0}
    assert lines["line1"] == {"name": "line1", "from": "point3",
                              "to": {"body": "body1", "at": [120.0, 9.0, -8.0]},
                              "segments": [{"type": "wire", "length": 40.0}]}
    assert lines["line3"]["from"] == "point4" and lines["line3"]["to"] == "point3"


def test_free_body_six_dof_with_moordyn_buoyancy_at_the_cg():
    imp, bodies, points, lines = _network("free_buoy_six_dof_v2.dat")
    b = bodies["body1"]
    assert b["free"] == ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    assert b["position"] == [0.0, 0.0, -20.0] and b["mass"] == 2.0e4
    assert b["centre_of_gravity"] == [0.0, 0.0, -1.0]
    assert b["hydrostatics"] == {"displaced_volume": 60.0, "metacentre": [0.0, 0.0, -1.0],
                                 "waterplane_area": 0.0}


def test_coupled_pinned_body_turns_but_stays():
    imp, bodies, points, lines = _network("coupled_pinned_v2.dat")
    assert bodies["body1"]["free"] == ["roll", "pitch", "yaw"]
    assert bodies["body1"]["centre_of_gravity"] == [0.0, 0.0, -60.0]


def test_shared_line_between_two_held_bodies():
    imp, bodies, points, lines = _network("shared_line_two_bodies_v2.dat")
    assert bodies["body2"]["orientation_deg"] == [0.0, 0.0, 180.0]
    assert bodies["body2"]["free"] == [] and bodies["body1"]["free"] == []
    assert lines["line5"]["from"] == {"body": "body1", "at": [30.0, 0.0, -15.0]}
    assert lines["line5"]["to"] == {"body": "body2", "at": [30.0, 0.0, -15.0]}


def test_hub_and_dangling_buoys():
    imp, bodies, points, lines = _network("hub_v2.dat")
    assert points["point4"]["free"] and points["point4"]["mass"] == 1500.0
    assert sum(ln["to"] == "point4" for ln in lines.values()) == 3
    assert lines["line4"]["to"] == {"body": "vessel", "at": [0.0, 0.0, -10.0]}
    assert bodies == {"vessel": {"name": "vessel", "position": [0.0, 0.0, 0.0], "free": []}}
    imp, bodies, points, lines = _network("dangling_buoys_v2.dat")
    assert bodies == {} and "bodies" not in imp.data
    assert points["point2"]["volume"] == 0.6 and lines["line1"]["to"] == "point2"


def test_turbines_are_held_and_their_reference_is_reported():
    imp, bodies, points, lines = _network("farm_turbines_v2.dat")
    assert set(bodies) == {"turbine1", "turbine2"}
    assert "FAST.Farm gives each turbine's reference position" in imp.report.text()


def test_rods():
    imp, bodies, points, lines = _network("rods_v2.dat")
    float_, tower, hull = bodies["rod1"], bodies["rod2"], bodies["body1"]
    # The free horizontal float: x along it from end A, free but for its spin (roll).
    assert float_["position"] == [-30.0, 0.0, -40.0] and "orientation_deg" not in float_
    assert float_["free"] == ["surge", "sway", "heave", "pitch", "yaw"]
    assert float_["mass"] == pytest.approx(60 * 800.0)
    assert float_["centre_of_gravity"] == [30.0, 0.0, 0.0]
    # Submerged, so its buoyancy is constant at its middle: V = pi d^2/4 L.
    assert float_["hydrostatics"] == {"displaced_volume": pytest.approx(60 * math.pi),
                                      "metacentre": [30.0, 0.0, 0.0], "waterplane_area": 0.0}
    assert lines["line2"]["to"] == {"body": "rod1", "at": [0.0, 0.0, 0.0]}
    assert lines["line3"]["to"] == {"body": "rod1", "at": [60.0, 0.0, 0.0]}
    # The tower pinned at the seabed: origin at the pin, z up along it, free to tilt only;
    # an upright cylinder, so its buoyancy is integrated exactly.
    assert tower["position"] == [300.0, 0.0, -150.0] and tower["free"] == ["roll", "pitch"]
    assert tower["hull"] == [{"shape": "cylinder", "radius": 1.0, "bottom": 0.0, "top": 40.0,
                              "centre": [0.0, 0.0]}]
    assert lines["line1"]["from"] == {"body": "rod2", "at": [0.0, 0.0, 40.0]}
    # The fixed frame's end B is a fixed point, the coupled rod's end A a vessel point.
    assert points["rod3B"] == {"name": "rod3B", "position": [-750.0, 259.8, -146.0]}
    assert lines["line4"]["to"] == {"body": "vessel", "at": [-20.0, -300.0, -10.0]}
    # The free hull: its own mass plus the column rod's weight; the column as its hull.
    assert hull["mass"] == pytest.approx(1.0e5 + 26 * 2.0e4)
    assert hull["centre_of_gravity"][2] == pytest.approx((1.0e5 * -15 + 5.2e5 * -7) / 6.2e5)
    assert hull["hull"] == [{"shape": "cylinder", "radius": 3.0, "bottom": -20.0, "top": 6.0,
                             "centre": [0.0, 0.0]}]
    # Every chain meets the column's foot, on the body's axis: yaw is left out.
    assert hull["free"] == ["surge", "sway", "heave", "roll", "pitch"]
    assert "point 6 (line 37, Body1): no line uses it" in imp.report.text()


def test_a_steep_rod_gets_z_along_it_and_a_flat_one_x(tmp_path):
    """Both frames put the rod's ends where the file has them, with |pitch| <= 45 deg."""
    from moorsolve.model.build_network import rotation
    text = (DATA / "rods_v2.dat").read_text()
    for a, b in (("-30     0      -40    30     0      -40", "flat"),
                 ("-30     0      -40    -10    8      -10", "steep")):
        path = _text(tmp_path, text.replace("-30     0      -40    30     0      -40", a))
        data = read_import(path).data
        rod = next(x for x in data["bodies"] if x["name"] == "rod1")
        ends = [ln["to"]["at"] for ln in data["lines"] if ln["name"] in ("line2", "line3")]
        R = rotation(*(math.radians(v) for v in rod.get("orientation_deg", [0, 0, 0])))
        world = [np.asarray(rod["position"]) + R @ np.asarray(e) for e in ends]
        coords = [float(v) for v in a.split()]
        assert world[0] == pytest.approx(coords[:3], abs=1e-9)
        assert world[1] == pytest.approx(coords[3:], abs=1e-9)
        assert abs(rod.get("orientation_deg", [0, 0, 0])[1]) <= 45.0
        if b == "steep":
            assert rod["free"] == ["surge", "sway", "heave", "roll", "pitch"]
            assert ends[0][:2] == [0.0, 0.0] and ends[1][:2] == pytest.approx([0.0, 0.0])


def test_yaw_is_left_out_when_every_line_meets_a_free_body_on_its_axis(tmp_path):
    text = (DATA / "free_buoy_six_dof_v2.dat").read_text()
    for old in ("3.0       0.0        -2.0", "-1.5      2.598      -2.0",
                "-1.5      -2.598     -2.0"):
        text = text.replace(old, "0.0       0.0        -2.0")
    (tmp_path / "axis.dat").write_text(text)
    imp = read_import(tmp_path / "axis.dat")
    assert imp.data["bodies"][0]["free"] == ["surge", "sway", "heave", "roll", "pitch"]
    assert "nothing holds its yaw" in imp.report.text()


def test_rotation_conventions_of_a_tilted_held_body(tmp_path):
    """MoorDyn-C turns a body by Rx(r0) Ry(p0) Rz(y0); the case's angles are z-y-x. The
    fairlead of a held body with roll, pitch and yaw lands where MoorDyn puts it, and the
    export gives the body-frame point back."""
    text = (DATA / "buoy_single_fairlead_v2.dat").read_text()
    text = text.replace("10.0   -5.0  0.0    0       0      15",
                        "10.0   -5.0  0.0    10      20     15")
    text = text.replace("2     Body1      0.0     0.0   0.0",
                        "2     Body1      2.0     1.0   -3.0")
    (tmp_path / "tilted.dat").write_text(text)
    data = read_import(tmp_path / "tilted.dat").data
    r, p, y = (math.radians(a) for a in (10, 20, 15))
    c, s = math.cos, math.sin
    rx = np.array([[1, 0, 0], [0, c(r), -s(r)], [0, s(r), c(r)]])
    ry = np.array([[c(p), 0, s(p)], [0, 1, 0], [-s(p), 0, c(p)]])
    rz = np.array([[c(y), -s(y), 0], [s(y), c(y), 0], [0, 0, 1]])
    expected = np.array([10.0, -5.0, 0.0]) + rx @ ry @ rz @ np.array([2.0, 1.0, -3.0])
    assert data["legs"][0]["fairlead"] == pytest.approx(expected, abs=1e-12)
    assert data["moordyn"]["body"]["r0_deg"] == 10.0
    out = tmp_path / "back.dat"
    moorsolve.export_moordyn(moorsolve.load_case(data), out)
    row = next(r.values for r in read_moordyn(out).tables["points"] if r.values[0] == "2")
    assert [float(v) for v in row[2:5]] == pytest.approx([2.0, 1.0, -3.0], abs=1e-9)
    body = read_moordyn(out).tables["bodies"][0].values
    assert [float(v) for v in body[5:8]] == [10.0, 20.0, 15.0]


# ---- the version, and what MoorDyn refuses ----------------------------------------------------

_V2 = """---- MoorDyn Input File ----
---------------------- LINE TYPES -----------------
TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx
(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)
chain 0.1 90 5e8 -1 0 1.3 1 0.6 0.5
---------------------- POINTS ---------------------
ID Attachment X Y Z Mass Volume CdA Ca
(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)
1 Fixed 400 0 -100 0 0 0 0
2 Coupled 10 0 -10 0 0 0 0
---------------------- LINES ----------------------
ID LineType AttachA AttachB UnstrLen NumSegs Outputs
(#) (name) (#) (#) (m) (-) (-)
1 chain 1 2 420 20 -
---------------------- OPTIONS --------------------
100 WtrDpth
--------------------- need this line --------------
"""


def _text(tmp_path, text, name="f.dat"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_version_and_why():
    md = parse_moordyn_text(_V2)
    assert md.version == 2 and "length (420) in column 5" not in md.version_reason
    assert md.version_reason.startswith("the LINES column names (line 12) are v2's")
    v1 = _V2.replace("ID LineType AttachA AttachB UnstrLen NumSegs Outputs",
                     "Line LineType UnstrLen NumSegs NodeAnch NodeFair Outputs") \
        .replace("1 chain 1 2 420 20 -", "1 chain 420.0 20 1 2 -")
    md = parse_moordyn_text(v1)
    assert md.version == 1 and "column 3, as v1 does" in md.version_reason
    bare = _V2.replace("ID LineType AttachA AttachB UnstrLen NumSegs Outputs", "a b c d e f g")
    md = parse_moordyn_text(bare)
    assert md.version == 2 and "LINE TYPES rows have 10 columns" in md.version_reason
    md = parse_moordyn_text(bare.replace("chain 0.1 90 5e8 -1 0 1.3 1 0.6 0.5",
                                         "chain 0.1 90 5e8 -1 1 0 1.3 0.6"))
    assert md.version == 1 and "9 columns" in md.version_reason
    # An unknown section is skipped as MoorDyn skips it, with a note.
    md = parse_moordyn_text(_V2.replace("--------------------- need this line",
                                        "------- CURRENT PROFILE -----\n0 1.0\n---- end"))
    assert any("'CURRENT PROFILE' names no section MoorDyn knows" in n for n in md.notes)


@pytest.mark.parametrize("old,new,message", [
    ("2 Coupled 10 0 -10 0 0 0 0", "3 Coupled 10 0 -10 0 0 0 0",
     "point ID 3 out of order: MoorDyn v2 needs the IDs 1, 2, 3"),
    ("chain 0.1 90 5e8 -1 0 1.3 1 0.6 0.5", "chain 0.1 90 5e8 -1 0 1.3 1 0.6 0.5 1 2",
     "LINE TYPES row has 12 columns"),
    ("(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)\n", "",
     "POINTS: expected the units row here, found a row of values"),
    ("1 chain 1 2 420 20 -", "1 chain 1 2 420 20",
     "LINES row has 6 columns; expected 7 or more"),
    ("1 chain 1 2 420 20 -", "1 chain 1 R1A 420 20 -", "'R1A': unknown rod 1"),
    ("2 Coupled 10 0 -10 0 0 0 0", "2 Glued 10 0 -10 0 0 0 0",
     "column 'Attachment': unknown attachment 'Glued'"),
    ("chain 0.1 90 5e8", "chain 0.1 90 ea.txt", "curve file 'ea.txt' not found"),
    ("chain 0.1 90 5e8", "chain 0.1 90 SYROPE:a|1|2", "SYROPE"),
    ("2 Coupled 10 0 -10 0 0 0 0", "2 Free 10 0 -10 0 0 5 0 0 0 0 0",
     "a steady horizontal force (FX 5, FY 0 N)"),
])
def test_what_moordyn_refuses_is_refused_with_line_reason_and_version(old, new, message,
                                                                       tmp_path):
    assert old in _V2
    path = _text(tmp_path, _V2.replace(old, new))
    with pytest.raises(MoorDynError) as err:
        read_import(path)
    text = str(err.value)
    assert message in text and text.startswith("f.dat:")
    if "units row" not in message:
        assert "(read as MoorDyn v2:" in text


def test_count_rows_must_match_and_versions_must_not_mix(tmp_path):
    text = (DATA / "semi_openfast_v1.dat").read_text().replace("3        NLines", "4        NLines")
    with pytest.raises(MoorDynError, match=r"f\.dat:\d+: NLines is 4 but the LINES section has "
                                           r"3 row\(s\).*read as MoorDyn v1"):
        read_import(_text(tmp_path, text))
    # Column names of one version over rows of the other: MoorDyn reads by position, so do
    # we (MoorPy's own test files carry v1 names over v2 rows).
    mixed = _V2.replace("1 chain 1 2 420 20 -", "1 chain 420.5 20 1 2 -")
    md = read_moordyn(_text(tmp_path, mixed))
    assert md.version == 1 and "MoorDyn reads the columns by position" in md.version_reason
    rows = _V2.replace("1 chain 1 R1A", "1 chain 1 2").replace(
        "ID LineType AttachA AttachB UnstrLen NumSegs Outputs",
        "Line LineType NodeAnch NodeFair UnstrLen NumSegs Outputs").replace(
        "1 chain 1 2 420 20 -", "1 chain 1 2 420.0 20 -")
    assert read_moordyn(_text(tmp_path, rows)).version == 2
    twice = _V2.replace("---------------------- OPTIONS", "---- POINTS ----\na\nb\n"
                                                          "---------------------- OPTIONS")
    with pytest.raises(MoorDynError, match="a second POINTS section"):
        read_moordyn(_text(tmp_path, twice))


def test_lenient_where_moordyn_is(tmp_path):
    text = _V2.replace("1 chain 1 2 420 20 -", "1 chain P1 Point2 420 20 - extra words")
    text = text.replace("100 WtrDpth", "100 WtrDpth\n90 WtrDpth   the last one counts")
    imp = read_import(_text(tmp_path, text))
    assert imp.data["environment"]["depth"] == 100.0       # point 1 at -100 deepens it
    assert "replaces the depth given at line" in imp.report.text()
    body = _V2.replace("---------------------- POINTS", "---- BODIES ----\nID A\n(#) (-)\n"
                       "1 Floating 0 0 0 0 0 0 1e3 0 0 1 0 0\n---------------------- POINTS")
    body = body.replace("2 Coupled", "2 Body1")
    imp = read_import(_text(tmp_path, body))
    assert imp.data["bodies"][0]["free"][:3] == ["surge", "sway", "heave"]
    assert "MoorDyn-C takes any such word as Free" in imp.report.text()


# ---- the command -------------------------------------------------------------------------


def test_import_command_prints_the_report_and_keeps_it(tmp_path, capsys):
    out = tmp_path / "case.yaml"
    assert main(["import-moordyn", str(DATA / "no_depth_v2.dat"), "-o", str(out)]) == 0
    captured = capsys.readouterr()
    assert "  read:" in captured.out and "  converted:" in captured.out
    assert "  ignored:" in captured.out and "solved at rest: largest tension" in captured.out
    assert "warning: line L2: its fixed end is 7 m above the seabed" in captured.err
    text = out.read_text()
    assert text.startswith("# Imported from the MoorDyn v2 file no_depth_v2.dat")
    assert "#     - no WtrDpth: water depth 85 m" in text
    assert moorsolve.load_case(out).environment.depth == 85.0
    assert main(["solve", str(out)]) == 0
    assert "fixed end is 7 m above the seabed" in capsys.readouterr().err


def test_stale_column_names_give_way_to_the_rows():
    imp = read_import(DATA / "stale_names_v2.dat")
    assert imp.file.version == 2
    assert "its column names (line 15) are v1's" in imp.file.version_reason
    assert "MoorDyn reads the columns by position" in imp.file.version_reason
    lines = {ln["name"]: ln for ln in imp.data["lines"]}
    assert lines["line2"] == {"name": "line2", "from": "point2", "to": "point3",
                              "segments": [{"type": "chain", "length": 330.0}]}


def test_zero_length_rods_are_connectors():
    imp, bodies, points, lines = _network("connectors_v2.dat")
    assert points["rod1"] == {"name": "rod1", "position": [120.0, 0.0, -260.0], "free": True,
                              "mass": 0.0, "volume": 0.0}
    assert lines["line1"]["to"] == "rod1" and lines["line2"]["from"] == "rod1"
    assert lines["line2"]["to"] == "rod2" and lines["line3"]["from"] == "rod2"
    result = moorsolve.solve(moorsolve.load_case(imp.data))
    # A massless connector passes the tension on: both sides carry the same force there.
    t = {leg.name: leg for leg in result.legs}
    assert t["line1"].fairlead_tension_N == pytest.approx(t["line2"].anchor_tension_N,
                                                          rel=1e-8)


def test_weightless_and_dry():
    """g 0 and WtrDnsty 0 (a MoorDyn test file): nothing weighs or floats; the body sits
    where the lines' elastic forces balance, which this test finds on its own."""
    from scipy.optimize import brentq
    imp, bodies, points, lines = _network("weightless_dry_v2.dat")
    data = imp.data
    assert data["line_types"]["nylon"]["weight_in_water"] == 0.0
    assert bodies["body1"]["hydrostatics"]["displaced_volume"] == 0.0
    assert bodies["body1"]["mass"] == 1e-9
    text = imp.report.text()
    assert "gravity 0 (weightless" in text and "water density 0 (dry" in text
    result = moorsolve.solve(moorsolve.load_case(data))
    ea = 25152.0

    def force(d):            # along x on the body at x = d; lines 1-6 of 0.9 m, line 7 1.4 m
        f = ea * ((1 - d) / 0.9 - 1) - ea * ((1 + d) / 0.9 - 1)
        f += ea * ((1.5 - d) / 1.4 - 1)
        for dz in (1.0, 1.0, 1.0, 1.0):                 # lines 3-6, across x
            r = math.hypot(d, dz)
            f -= ea * (r / 0.9 - 1) * d / r
        return f

    d = brentq(force, 0.0, 0.2)
    body = result.bodies[0]
    assert body["x_m"] == pytest.approx(d, rel=1e-6)
    assert abs(body["y_m"]) < 1e-9 and body["z_m"] == pytest.approx(-5.0, abs=1e-9)


def test_a_body_given_on_its_side_is_the_same_body():
    """MoorDyn's p0 = -90 deg (the z-y-x angles' singular pitch): the body's frame is taken
    parallel to the scene's axes with its points turned into it; given so, the buoy of
    free_buoy_six_dof_v2.dat finds the same equilibrium."""
    imp, bodies, points, lines = _network("tilted_body_v2.dat")
    assert "orientation_deg" not in bodies["body1"]
    assert lines["line1"]["to"]["at"] == pytest.approx([3.0, 0.0, -2.0], abs=1e-6)
    tilted = moorsolve.solve(moorsolve.load_case(imp.data))
    plain = moorsolve.solve(moorsolve.load_case(read_import(
        DATA / "free_buoy_six_dof_v2.dat").data))
    for a, b in zip(tilted.legs, plain.legs):
        assert a.fairlead_tension_N == pytest.approx(b.fairlead_tension_N, rel=1e-6)
    assert tilted.bodies[0]["z_m"] == pytest.approx(plain.bodies[0]["z_m"], abs=1e-6)
