"""MoorDyn import and export (issue 8): hand-written v1 and v2 files, round trips, the
exported equilibrium, malformed files."""

import math
import pathlib

import pytest
import yaml

import moorsolve
from moorsolve.cli import main
from moorsolve.io import case_to_moordyn, import_moordyn, moordyn_to_case_data, read_moordyn
from moorsolve.io.moordyn import MoorDynError
from conftest import TESTS


V2 = TESTS / "data" / "moordyn" / "semisub_v2.dat"
V1 = TESTS / "data" / "moordyn" / "spar_v1.dat"
CASES = TESTS.parent / "cases"


def _same(a: str, b: str) -> bool:
    """Two MoorDyn tokens agree: numbers to 6 significant digits, anything else exactly."""
    try:
        x, y = float(a), float(b)
    except ValueError:
        return a == b
    return abs(x - y) <= 1e-6 * max(abs(x), abs(y)) or abs(x - y) < 1e-9


def _compare_files(first: pathlib.Path, second: pathlib.Path):
    """Every table row, option, output and verbatim section of two MoorDyn files agrees."""
    a, b = read_moordyn(first), read_moordyn(second)
    assert a.version == b.version
    for key in set(a.tables) | set(b.tables):
        rows_a = {r.values[0]: r.values for r in a.tables[key]}
        rows_b = {r.values[0]: r.values for r in b.tables[key]}
        assert rows_a.keys() == rows_b.keys(), key
        for ident, values in rows_a.items():
            other = rows_b[ident]
            assert len(values) == len(other), (key, ident)
            for x, y in zip(values, other):
                assert _same(x, y), (key, ident, values, other)
    opts_a = {name.lower(): value for name, value, _ in a.options}
    opts_b = {name.lower(): value for name, value, _ in b.options}
    for name, value in opts_a.items():
        assert _same(value, opts_b[name]), name
    assert a.outputs == b.outputs
    assert a.sections == b.sections


# ---- import ------------------------------------------------------------------------------


def test_v2_sections_map_onto_the_case():
    md = read_moordyn(V2)
    assert md.version == 2
    data = moordyn_to_case_data(md)
    case = moorsolve.load_case(data)
    env = case.environment
    assert (env.depth, env.gravity, env.water_density) == (150.0, 9.80665, 1025.0)
    chain = case.line_types["chain"]
    # Submerged weight g (m - rho pi d^2 / 4) from the file's Diam and Mass/m.
    assert chain.weight_in_water == pytest.approx(9.80665 * (141.0 - 1025 * math.pi
                                                             * 0.1512 ** 2 / 4), rel=1e-14)
    assert chain.ea == 6.0e8 and chain.diameter == 0.1512
    assert case.line_types["rope"].ea == 1.5e8          # the static part of "1.5e8|3.0e8"
    assert [leg.name for leg in case.legs] == ["L1", "L2", "L5"]
    l2 = next(leg for leg in case.legs if leg.name == "L2")
    # Line 3 runs from joint 5 down to the clump 4: reversed into the leg's order.
    assert [s.line_type.name for s in l2.segments] == ["chain", "rope", "chain"]
    assert [s.length for s in l2.segments] == [250.0, 325.0, 90.0]
    assert l2.clumps[0].mass == 1.5e4 and l2.clumps[0].volume == 1.91
    assert l2.joint_clumps[1] is None
    assert l2.anchor == (5.0, 648.0, -150.0)
    # Body1 point (20, 34.64, -14) with the body at (5, -2, 0) turned 30 deg.
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    assert l2.fairlead == pytest.approx((5 + c * 20 - s * 34.64, -2 + s * 20 + c * 34.64, -14))
    l5 = next(leg for leg in case.legs if leg.name == "L5")
    assert l5.clumps[0].weight == pytest.approx(-9.80665 * 1025 * 5.0)     # a buoy
    # A Coupled body is held where the file puts it, as MoorDyn and MoorPy hold it in statics.
    assert case.body.free == () and case.body.loads.force is None
    block = case.moordyn
    assert block["line_types"]["rope"]["ea"] == "1.5e8|3.0e8"
    assert block["line_types"]["chain"]["cdax"] == "0.639"
    assert block["body"]["yaw_deg"] == 30.0 and block["body"]["columns"]["i"] == "1e10"
    assert ["FrictionCoefficient", "0.5"] in block["options"]
    assert block["outputs"] == ["FAIRTEN1", "ANCHTEN1", "BODY1PX", "POINT4PZ"]
    assert set(block["sections"]) == {"ROD TYPES", "RODS", "FAILURE"}


def test_v1_sections_map_onto_the_case():
    md = read_moordyn(V1)
    assert md.version == 1
    case = moorsolve.load_case(moordyn_to_case_data(md))
    env = case.environment
    assert env.depth == 320.0 and env.water_density == 1025.0
    assert env.gravity == 9.80665              # v1's default: the file gives no g
    main_type = case.line_types["main"]
    assert main_type.ea == 384.243e6
    assert main_type.weight_in_water == pytest.approx(
        9.80665 * (77.7066 - 1025 * math.pi * 0.09 ** 2 / 4), rel=1e-14)
    # Vessel points are fairleads on a body at the origin; Connect 6 joins lines 3 and 4.
    assert [leg.name for leg in case.legs] == ["L1", "L2", "L3"]
    assert case.legs[0].fairlead == (5.2, 0.0, -70.0)
    l3 = case.legs[2]
    assert [s.length for s in l3.segments] == [150.0, 752.2]
    assert l3.clumps[0].mass == 2.0e4
    # v1 names: Can -> ca, Cat -> caax, Cdn -> cd, Cdt -> cdax.
    assert case.moordyn["line_types"]["heavy"] == {"ba": "-1.0", "ca": "1.0", "caax": "0.0",
                                                   "cd": "2.4", "cdax": "0.4"}


def test_imported_cases_solve_and_the_spar_is_symmetric(tmp_path):
    for path in (V1, V2):
        import_moordyn(path, tmp_path / "c.yaml")
        result = moorsolve.solve(moorsolve.load_case(tmp_path / "c.yaml"))
        assert result.certificate.certified
    # The spar's first two legs are mirror images (120 deg apart, same line): equal tension.
    import_moordyn(V1, tmp_path / "spar.yaml")
    r = moorsolve.solve(moorsolve.load_case(tmp_path / "spar.yaml"))
    assert r.leg("L1").fairlead_tension_N == pytest.approx(r.leg("L2").fairlead_tension_N,
                                                           rel=1e-4)


def test_imported_yaml_is_a_case_file_with_the_block(tmp_path):
    out = tmp_path / "semi.yaml"
    import_moordyn(V2, out)
    text = out.read_text()
    assert text.startswith("# Imported from the MoorDyn v2 file semisub_v2.dat")
    data = yaml.safe_load(text)
    assert "moordyn" in data and "loads" not in data["body"]
    # The validator checks the block: a leg whose segments changed without it is refused.
    data["legs"][0]["segments"].append({"type": "chain", "length": 10.0})
    with pytest.raises(moorsolve.CaseError, match=r"moordyn\.legs\.L1\.lines"):
        moorsolve.load_case(data)
    data = yaml.safe_load(text)
    data["moordyn"]["colour"] = "red"
    with pytest.raises(moorsolve.CaseError, match="unknown key 'colour'"):
        moorsolve.load_case(data)
    data = yaml.safe_load(text)
    data["moordyn"]["line_types"]["nylon"] = {"cd": "1"}
    with pytest.raises(moorsolve.CaseError, match="nylon"):
        moorsolve.load_case(data)


# ---- round trips -------------------------------------------------------------------------


@pytest.mark.parametrize("path", [V2, V1], ids=["v2", "v1"])
def test_round_trip_reproduces_every_value(path, tmp_path):
    yaml_path = tmp_path / "case.yaml"
    import_moordyn(path, yaml_path)
    out = tmp_path / "again.dat"
    assert main(["export-moordyn", str(yaml_path), "-o", str(out)]) == 0
    _compare_files(path, out)
    # The front matter comes back too.
    assert read_moordyn(out).header == read_moordyn(path).header
    # And a second trip changes nothing.
    import_moordyn(out, tmp_path / "case2.yaml")
    assert yaml.safe_load((tmp_path / "case2.yaml").read_text())["legs"] == \
        yaml.safe_load(yaml_path.read_text())["legs"]


def test_v1_to_v2_and_back(tmp_path):
    import_moordyn(V1, tmp_path / "spar.yaml")
    case = moorsolve.load_case(tmp_path / "spar.yaml")
    (tmp_path / "spar_v2.dat").write_text(case_to_moordyn(case, version=2))
    md2 = read_moordyn(tmp_path / "spar_v2.dat")
    assert md2.version == 2
    heavy = next(r.values for r in md2.tables["line_types"] if r.values[0] == "heavy")
    # TypeName Diam Mass/m EA BA EI Cd Ca CdAx CaAx from v1's Can Cat Cdn Cdt.
    assert heavy[4:] == ["-1.0", "0", "2.4", "1.0", "0.4", "0.0"]
    import_moordyn(tmp_path / "spar_v2.dat", tmp_path / "spar2.yaml")
    case2 = moorsolve.load_case(tmp_path / "spar2.yaml")
    (tmp_path / "back_v1.dat").write_text(case_to_moordyn(case2, version=1))
    _compare_files(V1, tmp_path / "back_v1.dat")
    r1, r2 = moorsolve.solve(case), moorsolve.solve(case2)
    for a, b in zip(r1.legs, r2.legs):
        assert a.fairlead_tension_N == pytest.approx(b.fairlead_tension_N, rel=1e-9)


def test_export_a_case_that_did_not_come_from_moordyn(tmp_path):
    case = moorsolve.load_case(CASES / "chain_polyester_clump.yaml")
    text = case_to_moordyn(case)
    (tmp_path / "fpu.dat").write_text(text)
    md = read_moordyn(tmp_path / "fpu.dat")
    assert md.version == 2
    rows = {r.values[0]: r.values for r in md.tables["line_types"]}
    # Chain gets the chain coefficients, polyester the rope ones; Mass/m keeps the weight.
    assert rows["chain84"][6:10] == ["1.333", "1.0", "0.639", "0.5"]
    assert rows["polyester160"][6:10] == ["1.2", "1.0", "0.008", "0"]
    lt = case.line_types["chain84"]
    mass = float(rows["chain84"][2])
    assert 9.80665 * (mass - 1025 * math.pi * 0.084 ** 2 / 4) == pytest.approx(
        lt.weight_in_water, rel=1e-11)
    assert md.tables["bodies"][0].values[:2] == ["1", "Coupled"]
    clumps = [r.values for r in md.tables["points"] if r.values[1] == "Free"]
    assert len(clumps) == 8 and clumps[0][5:7] == ["15000", "1.91"]
    assert {n for n, _, _ in md.options} >= {"dtM", "WtrDpth", "g", "rho", "kBot"}
    # Import it back: the same statics (no loads travel through MoorDyn: add them back).
    data = moordyn_to_case_data(md)
    # A MoorDyn Coupled body comes in held; free it as the original case has it.
    assert data["body"]["free"] == []
    data["body"]["free"] = ["surge", "sway", "yaw"]
    data["body"]["loads"] = case.source["body"]["loads"]
    data["environment"].update({k: case.source["environment"][k]
                                for k in ("wind", "current")})
    back = moorsolve.load_case(data)
    r0, r1 = moorsolve.solve(case), moorsolve.solve(back)
    for key in ("x_m", "y_m", "yaw_deg"):
        assert r1.body[key] == pytest.approx(r0.body[key], abs=1e-7)
    for a, b in zip(r0.legs, r1.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-8)


def test_v1_export_of_a_case_with_a_body(tmp_path):
    case = moorsolve.load_case(CASES / "floating_dock.yaml")
    (tmp_path / "dock.dat").write_text(case_to_moordyn(case, version=1))
    md = read_moordyn(tmp_path / "dock.dat")
    kinds = {r.values[1] for r in md.tables["points"]}
    assert md.version == 1 and kinds == {"Fixed", "Vessel"}
    assert "rhoW" in {n for n, _, _ in md.options}


# ---- exported equilibrium ----------------------------------------------------------------


def _global_points(md):
    """Global positions of every point of a parsed v2 file (Body1 points placed by BODIES)."""
    body = md.tables.get("bodies")
    x0 = y0 = z0 = yaw = 0.0
    if body:
        v = body[0].values
        x0, y0, z0, yaw = float(v[2]), float(v[3]), float(v[4]), math.radians(float(v[7]))
    out = {}
    for r in md.tables["points"]:
        x, y, z = (float(t) for t in r.values[2:5])
        if r.values[1].startswith("Body"):
            x, y = (x0 + math.cos(yaw) * x - math.sin(yaw) * y,
                    y0 + math.sin(yaw) * x + math.cos(yaw) * y)
            z += z0
        out[int(r.values[0])] = (x, y, z)
    return out


@pytest.mark.parametrize("source", ["dock", "semisub"])
def test_equilibrium_positions_match_the_result(source, tmp_path):
    if source == "dock":
        case = moorsolve.load_case(CASES / "floating_dock.yaml")
        block_legs = None
    else:
        import_moordyn(V2, tmp_path / "semi.yaml")
        case = moorsolve.load_case(tmp_path / "semi.yaml")
        block_legs = case.moordyn["legs"]
    result = moorsolve.solve(case)
    out = tmp_path / "eq.dat"
    moorsolve.export_moordyn(case, out, equilibrium=True)
    md = read_moordyn(out)
    points = _global_points(md)
    lines = {int(r.values[0]): (int(r.values[2]), int(r.values[3])) for r in
             md.tables["lines"]}
    pid = 0
    for i, leg in enumerate(case.legs):
        lr = result.leg(leg.name)
        if block_legs is None:     # exported in leg order: anchor, joints, fairlead
            ids = list(range(pid + 1, pid + len(leg.segments) + 2))
            pid = ids[-1]
        else:
            ids = [p["id"] for p in block_legs[leg.name]["points"]]
        assert points[ids[-1]] == pytest.approx(lr.fairlead, abs=1e-8)
        for joint, j in zip(lr.joints, ids[1:-1]):
            assert points[j] == pytest.approx(tuple(joint["position_m"]), abs=1e-8)
        assert lines  # lines survive the equilibrium export
    # Imported again with the body held, the legs carry the equilibrium tensions.
    data = moordyn_to_case_data(md)
    data["body"]["free"] = []
    held = moorsolve.solve(moorsolve.load_case(data))
    for a, b in zip(result.legs, held.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, rel=1e-7)


def test_v1_equilibrium_moves_the_free_points_and_notes_the_platform(tmp_path):
    import_moordyn(V1, tmp_path / "spar.yaml")
    case = moorsolve.load_case(tmp_path / "spar.yaml")
    result = moorsolve.solve(case)
    text = case_to_moordyn(case, result=result)
    (tmp_path / "eq.dat").write_text(text)
    md = read_moordyn(tmp_path / "eq.dat")
    point6 = next(r.values for r in md.tables["points"] if r.values[0] == "6")
    assert [float(v) for v in point6[2:5]] == pytest.approx(
        result.leg("L3").joints[0]["position_m"], abs=1e-8)
    assert "moorsolve: positions are the static equilibrium" in text
    # Vessel points stay in the platform frame.
    point2 = next(r.values for r in md.tables["points"] if r.values[0] == "2")
    assert point2[2:5] == ["5.2", "0", "-70"]


# ---- malformed files ---------------------------------------------------------------------


def _broken(tmp_path, old, new, source=V2):
    text = source.read_text()
    assert old in text
    path = tmp_path / "lines.dat"
    path.write_text(text.replace(old, new, 1))
    return path


def _line_of(path, fragment):
    return next(i for i, line in enumerate(path.read_text().splitlines(), start=1)
                if fragment in line)


@pytest.mark.parametrize("old,new,message", [
    ("5     chain      7        8        420.0", "5     chain      7        8        abc",
     "column 'UnstrLen': 'abc' is not a number"),
    ("2     chain      3        4        250.0       25      -",
     "2     chain      3        4        250.0       25", "LINES row has 6 columns; expected 7"),
    ("6     rope       9        8", "6     nylon      9        8",
     "column 'LineType': unknown line type 'nylon'"),
    ("4     chain      5        6", "4     chain      5        66",
     "column 'AttachB': unknown point 66"),
    ("7     Fixed      568.0", "7     Glued      568.0", "column 'Attachment': unknown "
                                                          "attachment 'Glued'"),
    ("chain      0.1512  141.0", "chain      0.1512  heavy", "column 'Mass/m': 'heavy' is "
                                                              "not a number"),
    ("150           WtrDpth", "deep          WtrDpth", "option 'WtrDpth': 'deep' is not a "
                                                       "number"),
    ("1     Coupled    5.0", "1     Coupled    5.0x", "column 'X0': '5.0x' is not a number"),
])
def test_malformed_rows_name_file_line_and_column(old, new, message, tmp_path):
    path = _broken(tmp_path, old, new)
    with pytest.raises(MoorDynError) as err:
        import_moordyn(path, tmp_path / "out.yaml")
    line = _line_of(path, new)
    assert str(err.value) == f"lines.dat:{line}: {message}" or \
        str(err.value).startswith(f"lines.dat:{line}: {message}")
    assert not (tmp_path / "out.yaml").exists()


def test_missing_sections_and_unrepresentable_topology(tmp_path):
    path = _broken(tmp_path, "---------------------- LINES ------",
                   "---------------------- LINEZ --")
    with pytest.raises(MoorDynError, match=r"lines\.dat:\d+: unknown section 'LINEZ'"):
        read_moordyn(path)
    text = V2.read_text()
    start = text.index("---------------------- LINES ---")
    stop = text.index("---------------------- FAILURE")
    (tmp_path / "nolines.dat").write_text(text[:start] + text[stop:])
    with pytest.raises(MoorDynError, match=r"nolines\.dat: missing section LINES"):
        read_moordyn(tmp_path / "nolines.dat")
    # A free point joining three lines (a bridle) and a line onto a rod end are MoorDyn
    # topology: they import in the network form (tests/io/test_moordyn_corpus.py).
    path = _broken(tmp_path, "6     rope       9        8", "6     rope       5        8")
    assert moordyn_to_case_data(read_moordyn(path))["lines"][5]["from"] == "point5"
    # A points row of 8 columns (MoorDyn needs 9).
    path = _broken(tmp_path, "9     Body1      20    -34.64  -14     0      0       0      0",
                   "9     Body1      20    -34.64  -14     0      0       0")
    with pytest.raises(MoorDynError, match="POINTS row has 8 columns; expected 9 or more"):
        import_moordyn(path)


def test_cli_bad_input_exits_2_and_writes_nothing(tmp_path, capsys):
    path = _broken(tmp_path, "420.0", "4x0.0")
    out = tmp_path / "case.yaml"
    assert main(["import-moordyn", str(path), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("moorsolve: bad input: lines.dat:") and "Traceback" not in err
    assert err.count("\n") == 1 and not out.exists()
    assert main(["import-moordyn", str(tmp_path / "none.dat"), "-o", str(out)]) == 2
    assert "MoorDyn file not found" in capsys.readouterr().err
    # An inextensible line cannot be exported.
    data = yaml.safe_load((CASES / "floating_dock.yaml").read_text())
    del data["line_types"]["chain81"]["ea"]
    (tmp_path / "inext.yaml").write_text(yaml.safe_dump(data))
    target = tmp_path / "inext.dat"
    assert main(["export-moordyn", str(tmp_path / "inext.yaml"), "-o", str(target)]) == 2
    assert "line_types.chain81.ea" in capsys.readouterr().err and not target.exists()


def test_cli_import_export_round_trip(tmp_path, capsys):
    yaml_path = tmp_path / "spar.yaml"
    assert main(["import-moordyn", str(V1), "-o", str(yaml_path)]) == 0
    out = tmp_path / "spar.dat"
    assert main(["export-moordyn", str(yaml_path), "-o", str(out), "--version", "1",
                 "--equilibrium"]) == 0
    assert "wrote" in capsys.readouterr().out
    assert read_moordyn(out).version == 1


@pytest.mark.parametrize("mass, neutral", [(7.853982, True), (7.853981633974483, True),
                                           (7.86, False), (7.84, False)])
def test_a_line_within_a_millionth_of_neutral_imports_as_neutral(tmp_path, mass, neutral):
    """A 0.1 m line in fresh water displaces pi/4 0.01 1000 = 7.853981634 kg/m: a Mass/m
    within a millionth of it (MoorDyn's pendulum tests write 7.85398) is a neutral line, said
    in the report; a line visibly heavier or lighter keeps its weight."""
    text = f"""--------------------- MoorDyn Input File ---------------------------------
A bob hanging from a fixed point on a line about as dense as the water
----------------------- LINE TYPES ----------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
main       0.1     {mass}     1.0E9      -0.01       0          0.0    0.0    0.0     0.0
---------------------- POINTS --------------------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
1     Fixed     0       0       0       0      0       0      0
2     Free      10      0       -100    1E3    0       0      0
---------------------- LINES ---------------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1     main       1        2         100.5     20      -
---------------------- OPTIONS -------------------------------------------
1000.0        WtrDnsty      water density (kg/m^3)
500           WtrDpth       water depth (m)
------------------------- need this line ---------------------------------
"""
    path = tmp_path / "bob.dat"
    path.write_text(text)
    imported = moorsolve.io.moordyn.convert_moordyn(read_moordyn(path))
    weight = imported.data["line_types"]["main"]["weight_in_water"]
    said = any("a neutrally buoyant line, taken as 0" in c for c in imported.report.converted)
    assert (weight == 0.0) == neutral and said == neutral
    if not neutral:
        assert weight == pytest.approx(9.80665 * (mass - 2.5 * math.pi), rel=1e-9)
    result = moorsolve.solve(moorsolve.load_case(imported.data))
    assert result.converged
    bob = result.points[0]
    assert bob["x_m"] == pytest.approx(0.0, abs=1e-6)
