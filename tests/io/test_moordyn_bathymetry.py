"""MoorDyn's SeafloorFile (issue 19, item 3): imported as the case's bathymetry (anchors put
on its surface, listed as converted), exported beside the written file, and the imported
scene checked against MoorPy's grid seabed where it is planar between anchor and fairlead."""

import contextlib
import io
import warnings

import pytest
import yaml

import moorsolve
from moorsolve.io import read_import
from moorsolve.io.bathymetry import read_bathymetry
from moorsolve.io.moordyn import MoorDynError
from moorsolve.io.moordyn_write import export_moordyn
from moorsolve.audit import AuditFailure
from conftest import DATA

FOLDER = DATA / "moordyn_bathymetry"
FILE = FOLDER / "three_legs_seafloor_v2.dat"


def test_seafloor_file_becomes_the_case_bathymetry():
    imp = read_import(FILE)
    seabed = imp.data["environment"]["seabed"]
    assert seabed["bathymetry"] == str((FOLDER / "seafloor.txt").resolve())
    converted = " | ".join(imp.report.converted)
    assert "SeafloorFile 'seafloor.txt': a bathymetry grid of 3 x 3 depths" in converted
    assert not any("SeafloorFile" in entry for entry in imp.report.ignored)
    case = moorsolve.load_case(imp.data)
    grid = case.environment.seabed.bathymetry
    # Anchors at WtrDpth (-100 m) are put on the grid: 97.6 m deep at x = 600, 101.2 m at -300.
    assert [line.a.position[2] for line in case.lines] == pytest.approx([-97.6, -101.2, -101.2],
                                                                        abs=1e-12)
    assert "point 1 (line 15): z = -100 m is put on the bathymetry's surface" in converted
    res = moorsolve.solve(case)
    assert "bathymetry" in res.effects
    # Legs 2 and 3 mirror each other across y = 0 (the grid does not change with y).
    assert res.legs[1].fairlead_tension_N == pytest.approx(res.legs[2].fairlead_tension_N,
                                                           rel=1e-9)
    assert grid.height(0.0, 0.0) == -100.0


def test_a_missing_seafloor_file_is_reported_and_a_bad_one_refused(tmp_path):
    text = FILE.read_text()
    bad = tmp_path / "bad.dat"
    bad.write_text(text.replace("seafloor.txt  SeafloorFile", "nowhere.txt  SeafloorFile"))
    imp = read_import(bad)          # a file shared without its grid: reported, seabed flat
    assert any("line 30: SeafloorFile 'nowhere.txt': no such file" in entry
               for entry in imp.report.ignored)
    assert "seabed" not in imp.data["environment"]
    (tmp_path / "seafloor.txt").write_text("header\nnGridX 2\nnGridY 1\n0 1\n")
    bad.write_text(text)
    with pytest.raises(MoorDynError, match="SeafloorFile 'seafloor.txt'"):
        read_import(bad)


def test_export_writes_the_grid_beside_the_file_and_reimports(tmp_path):
    case = moorsolve.load_case(read_import(FILE).data)
    out = tmp_path / "exported.dat"
    export_moordyn(case, out)
    written = tmp_path / "exported_seafloor.txt"
    assert "exported_seafloor.txt  SeafloorFile" in out.read_text()
    grid = case.environment.seabed.bathymetry
    assert read_bathymetry(written) == {"x": list(grid.x), "y": list(grid.y),
                                        "depth": [list(r) for r in grid.depth]}
    again = moorsolve.load_case(read_import(out).data)
    assert again.environment.seabed.bathymetry == grid
    a, b = moorsolve.solve(case), moorsolve.solve(again)
    for la, lb in zip(a.legs, b.legs):
        assert lb.fairlead_tension_N == pytest.approx(la.fairlead_tension_N, rel=1e-9)


def test_imported_case_yaml_names_the_grid(tmp_path):
    from moorsolve.io import import_moordyn
    out = tmp_path / "case.yaml"
    import_moordyn(FILE, out)
    data = yaml.safe_load(out.read_text())
    assert data["environment"]["seabed"]["bathymetry"].endswith("seafloor.txt")
    assert moorsolve.load_case(out).environment.seabed.bathymetry is not None


def test_agrees_with_moorpy_on_a_planar_grid():
    """MoorPy slopes each line by the chord between the seabed under its two ends; on this
    grid (planar between every anchor and fairlead) that is the seabed under the chain, so
    the two must agree."""
    mp = pytest.importorskip("moorpy")
    case = moorsolve.load_case(read_import(FILE).data)
    res = moorsolve.solve(case)
    env = case.environment
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ms = mp.System(file=str(FILE), bathymetry=str(FOLDER / "seafloor.txt"))
        ms.g, ms.rho, ms.depth = env.gravity, env.water_density, env.depth
        for point in ms.pointList[:3]:
            # MoorPy's own surface height (ours differs in the last bit; MoorPy would then
            # take the anchor as lifted off the seabed).
            point.r[2] = -ms.getDepthFromBathymetry(point.r[0], point.r[1])[0]
        for body in ms.bodyList:
            body.type = 1                                  # held, as the import holds it
        ms.initialize()
        assert ms.solveEquilibrium(DOFtype="free", tol=1e-7, maxIter=500, no_fail=True)
        for line in ms.lineList:
            line.staticSolve(tol=1e-10)
    for line, leg in zip(ms.lineList, res.legs):
        assert leg.anchor_tension_N == pytest.approx(line.TA, rel=1e-7)
        assert leg.fairlead_tension_N == pytest.approx(line.TB, rel=1e-7)


def test_wtrdpth_naming_the_grid_is_moordyn_f_bathymetry(tmp_path):
    text = FILE.read_text()
    text = text.replace("100           WtrDpth", "seafloor.txt  WtrDpth")
    text = text.replace("seafloor.txt  SeafloorFile  bathymetry\n", "")
    (tmp_path / "seafloor.txt").write_text((FOLDER / "seafloor.txt").read_text())
    # Anchors on the seabed by MoorDyn-F's word: put on the grid's surface.
    path = tmp_path / "wtrdpth.dat"
    path.write_text(text.replace(" -100    0 ", " seabed  0 "))
    imp = read_import(path)
    assert imp.data["environment"]["depth"] == 104.0          # the grid's deepest node
    assert imp.data["environment"]["seabed"]["bathymetry"] == str(tmp_path / "seafloor.txt")
    assert any("WtrDpth 'seafloor.txt' names the grid" in e for e in imp.report.converted)
    case = moorsolve.load_case(imp.data)
    assert [line.a.position[2] for line in case.lines] == pytest.approx([-97.6, -101.2, -101.2])
    assert moorsolve.solve(case).certificate.certified
    # Written at z = -100, two anchors lie 1.2 m above this grid: MoorDyn-F keeps them there,
    # so does the import. Their chains reach the seabed from a fixed point above it, which
    # is modelled on a flat seabed at the height under that point; here the seabed rises
    # under them, and the audit refuses the answer rather than certify a line through it.
    path.write_text(text)
    case = moorsolve.load_case(read_import(path).data)
    assert [line.a.position[2] for line in case.lines] == pytest.approx([-97.6, -100, -100])
    with pytest.raises(AuditFailure, match="L2: the line passes 1.06 m below its seabed plane"):
        moorsolve.solve(case)
