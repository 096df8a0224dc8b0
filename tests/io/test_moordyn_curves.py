"""MoorDyn line types whose EA is a tension-strain curve file, in and out.

MoorDyn reads an EA that is not a number as the name of a file (MoorDyn-C: a token that does
not parse as a number; MoorDyn-F: one with a letter other than e/E): three header lines,
then ``strain tension`` rows, at most 30. Import makes it a table law; export writes the
table (a Baranov law sampled) beside the ``.dat``; MoorDyn itself (the optional peer) reads
the exported curve and holds the exported equilibrium.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import yaml
from conftest import CASES, DATA

import moorsolve
from moorsolve.errors import CaseError

FPU = CASES / "fpu_polyester_table.yaml"
MOORDYN = DATA / "moordyn_curves"


# ---- MoorDyn curve files ---------------------------------------------------------------------


CURVE_STRAIN = [0.0, 0.004, 0.009, 0.015, 0.022, 0.030]
CURVE_TENSION = [0.0, 0.5e5, 1.4e5, 2.8e5, 4.9e5, 7.8e5]


@pytest.mark.parametrize("name", ["taut_polyester_v2.dat", "taut_polyester_v1.dat"])
def test_moordyn_ea_curve_file_becomes_a_table_law(name):
    data = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(MOORDYN / name))
    poly = data["line_types"]["poly"]
    assert "ea" not in poly
    assert poly["stretch"] == {"model": "table", "strain": CURVE_STRAIN,
                               "tension": CURVE_TENSION, "interpolation": "linear"}
    assert moorsolve.solve(moorsolve.load_case(data)).converged


def test_moordyn_curve_errors_name_the_file_and_line(tmp_path):
    text = (MOORDYN / "taut_polyester_v2.dat").read_text()
    (tmp_path / "line.dat").write_text(text)
    with pytest.raises(CaseError, match=r"line.dat:8.*polyester_curve.txt.*not found"):
        moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(tmp_path / "line.dat"))
    rows = "\n".join(f"{0.001 * i} {1e4 * i}" for i in range(31))
    (tmp_path / "polyester_curve.txt").write_text(f"a\nb\nc\n{rows}")
    with pytest.raises(CaseError, match="31 rows; MoorDyn reads at most 30"):
        moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(tmp_path / "line.dat"))
    (tmp_path / "polyester_curve.txt").write_text("a\nb\nc\n0 0\n0.01 abc")
    with pytest.raises(CaseError, match=r"polyester_curve.txt:5"):
        moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(tmp_path / "line.dat"))


@pytest.mark.parametrize("version", [1, 2])
def test_export_writes_the_curve_file_and_reads_back(tmp_path, version):
    """The FPU's 9-row monotone-cubic table goes out as 30 rows of its cubic (its own rows
    among them), so that MoorDyn's chords stay within 2.2e-4 of its top tension (3.7e-3
    with the 9 rows alone, measured); read back, it is those rows joined by chords."""
    from moorsolve.io.moordyn_curves import chord_departure
    case = moorsolve.load_case(str(FPU))
    out = tmp_path / "fpu.dat"
    moorsolve.export_moordyn(case, out, version=version)
    curve = tmp_path / "fpu_polyester160_ea.txt"
    text = curve.read_text()
    assert not text.endswith("\n")                 # MoorDyn-C rejects an empty last line
    assert "fpu_polyester160_ea.txt" in out.read_text()
    lines = text.split("\n")
    assert len(lines) == 3 + 30 and "monotone cubic sampled at 30 rows" in lines[0]
    law = case.line_types["polyester160"].stretch
    back = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(out))
    table = back["line_types"]["polyester160"]["stretch"]
    assert table["interpolation"] == "linear"
    strain, tension = table["strain"], table["tension"]
    assert set(law.tension) <= set(tension)
    assert np.allclose(law.strains(tension), strain, rtol=1e-15, atol=0)
    assert chord_departure(law, law.strain, law.tension) > 3e-3
    assert chord_departure(law, strain, tension) < 2.5e-4


def test_export_of_a_linear_table_is_its_rows_and_warns_for_a_coarse_cubic(tmp_path, caplog):
    """A table of chords is MoorDyn's own law: its rows go out as they are and come back
    equal. A cubic table whose 30 sampled rows still miss it by more than 1e-3 of its top
    tension (a kink of a curve in three rows: 1.2e-3 measured) is written with a warning."""
    data = yaml.safe_load(FPU.read_text())
    stretch = data["line_types"]["polyester160"]["stretch"]
    stretch["interpolation"] = "linear"
    moorsolve.export_moordyn(moorsolve.load_case(data), tmp_path / "lin.dat")
    back = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(tmp_path / "lin.dat"))
    law = moorsolve.load_case(data).line_types["polyester160"].stretch
    assert back["line_types"]["polyester160"]["stretch"] == {
        "model": "table", "strain": list(law.strain), "tension": list(law.tension),
        "interpolation": "linear"}
    assert not any("departs" in r.message for r in caplog.records)
    data["line_types"]["polyester160"]["stretch"] = {
        "model": "table", "strain": [0.001, 0.1], "tension": ["3000 kN", "3300 kN"]}
    with caplog.at_level("WARNING"):
        moorsolve.export_moordyn(moorsolve.load_case(data), tmp_path / "kink.dat")
    assert any("polyester160" in r.getMessage() and "departs from the monotone-cubic"
               in r.getMessage() for r in caplog.records)


def test_table_interpolation_is_checked():
    data = yaml.safe_load(FPU.read_text())
    data["line_types"]["polyester160"]["stretch"]["interpolation"] = "spline"
    with pytest.raises(CaseError, match=r"polyester160\.stretch\.interpolation.*linear"):
        moorsolve.load_case(data)


def test_network_export_writes_the_curve_too(tmp_path):
    data = yaml.safe_load((CASES / "three_platforms.yaml").read_text())
    lt = data["line_types"]["shared"]
    ea = float(lt.pop("ea"))
    lt["stretch"] = {"model": "table", "strain": [0.001, 0.002, 0.004],
                     "tension": [ea * 0.001, ea * 0.002, ea * 0.005],
                     "interpolation": "linear"}
    moorsolve.export_moordyn(moorsolve.load_case(data), tmp_path / "three.dat")
    assert (tmp_path / "three_shared_ea.txt").exists()
    back = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(tmp_path / "three.dat"))
    assert back["line_types"]["shared"]["stretch"]["tension"] == [
        0.0, ea * 0.001, ea * 0.002, ea * 0.005]


def test_export_samples_a_baranov_law_for_moordyn(tmp_path):
    data = {"environment": {"depth": 30.0},
            "line_types": {"hemp": {"weight_in_water": 25.0, "mbl": 2e5, "diameter": 0.05,
                                    "stretch": {"model": "baranov", "n": 4e-4}}},
            "legs": [{"name": "R", "anchor": [0.0, 0.0], "fairlead": [60.0, 0.0, -5.0],
                      "segments": [{"type": "hemp", "length": 70.0}]}]}
    moorsolve.export_moordyn(moorsolve.load_case(data), tmp_path / "rope.dat")
    rows = [tuple(map(float, line.split())) for line in
            (tmp_path / "rope_hemp_ea.txt").read_text().split("\n")[3:]]
    assert len(rows) == 30 and rows[0] == (0.0, 0.0)
    n, mbl = 4e-4, 2e5
    assert rows[-1][1] == pytest.approx(mbl, rel=1e-12)          # up to the MBL
    assert all(t == pytest.approx((e / n) ** 2, rel=1e-12) for e, t in rows[1:])


@pytest.mark.parametrize("quadratic, bound", [(0.0, 3e-3), (1.2e8, 1e-2)])
def test_moordyn_reads_the_exported_curve(tmp_path, quadratic, bound):
    """MoorDyn (the optional peer) loads the exported curve file and holds the exported
    equilibrium with our mooring force. A linear curve: as close as a Hooke line (1.3e-5
    measured). A stiffening curve: MoorDyn's dynamic relaxation leaves 0.1 m/s^2 of
    unbalanced acceleration and 0.4 % of the force (measured), inside 1 %; reading the
    columns swapped or in kN would be off by far more."""
    pytest.importorskip("moordyn")
    from moorsolve.studies.stiffness import mooring_force
    data = yaml.safe_load(FPU.read_text())
    strain = np.linspace(0.0, 0.06, 30)
    data["line_types"]["polyester160"]["stretch"] = {
        "model": "table", "strain": strain[1:].tolist(),
        "tension": (8 * 7.89e6 * strain[1:] + quadratic * strain[1:] ** 2).tolist()}
    data["line_types"]["polyester160"].pop("stiffness_bounds")
    case = moorsolve.load_case(data)
    path = tmp_path / "fpu.dat"
    result = moorsolve.export_moordyn(case, path, equilibrium=True)
    text = re.sub(r"\n60(\s+)TmaxIC", r"\n600\1TmaxIC", path.read_text())
    path.write_text(text)
    pose = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
    ours = np.array(mooring_force(case, pose)[0])[:2]
    from test_moordyn_peer import _moordyn_body_force
    theirs = _moordyn_body_force(path, pose)[:2]
    assert np.max(np.abs(theirs - ours)) < bound * np.hypot(*ours)


# ---- MoorDyn's own physics of a curve file ----------------------------------------------------

#: A coarse stiffening polyester curve (strain, tension [N]): chords and cubic differ by
#: percent between its rows.
COARSE = [(0.0, 0.0), (0.01, 1.0e5), (0.02, 3.0e5), (0.04, 9.0e5), (0.08, 2.5e6)]

TAUT_NETWORK = """--------------------- MoorDyn Input File ------------------------------------
Two taut polyester lines from fixed points up to a free buoyant point, clear of the seabed
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m   EA          BA/-zeta  EI   Cd   Ca   CdAx   CaAx
(name)     (m)     (kg/m)   (N)         (N-s/-)   (-)  (-)  (-)  (-)    (-)
poly       0.13    20.0     coarse.txt  -1.0      0    1.2  1.0  0.008  0.0
---------------------- POINTS --------------------------------
ID   Attachment  X       Y     Z       Mass   Volume  CdA   Ca
(#)  (-)         (m)     (m)   (m)     (kg)   (m^3)   (m^2) (-)
1    Fixed       0.0     0.0   -150.0  0      0       0     0
2    Free        150.0   0.0   -60.0   0      60      0     0
3    Fixed       300.0   0.0   -150.0  0      0       0     0
---------------------- LINES --------------------------------
ID   LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)  (name)    (#)      (#)      (m)       (-)      (-)
1    poly      1        2        168.0     20       -
2    poly      2        3        168.0     20       -
---------------------- OPTIONS -----------------------------------------
200.0    WtrDpth
9.80665  g
1025.0   rho
0.001    dtM
0.5      dtIC
2000     TmaxIC
1e-9     threshIC
------------------------- need this line -------------------------------"""


def _segment_tensions(result, weight, segments):
    """Our tension at the middle of each line's first and last MoorDyn segment: along a
    catenary clear of the seabed the vertical tension grows by ``w`` per unstretched metre
    (``V(s) = V_A + w s``), the horizontal one is constant."""
    out = []
    for line in result.lines:
        L = line.profile["s_m"][-1]
        for s in (L / (2 * segments), L - L / (2 * segments)):
            out.append(math.hypot(line.horizontal_tension_N,
                                  line.anchor_vertical_N + weight * s))
    return np.array(out)


def test_a_moordyn_curve_file_solves_to_moordyns_own_physics(tmp_path):
    """A curve file means MoorDyn's chords between its rows. MoorDyn 2.7.2 (the optional
    peer) relaxes two taut polyester lines of 20 segments each to 3e-8 m/s^2 on the coarse
    5-row curve; the imported file (``interpolation: linear``) solves to the same free
    point within 1e-6 of the line length and the same segment tensions within 1e-4
    (measured 2.3e-8 and 4.9e-8: on a taut line clear of the seabed the lumped-mass tension
    of a segment is the catenary's at its middle). The same rows read by the monotone cubic
    are off by 2.6e-3 in tension and 1.7e-3 of the length (0.29 m; measured), so the test
    tells the two laws apart."""
    moordyn = pytest.importorskip("moordyn")
    rows = "\n".join(f"{e!r} {t!r}" for e, t in COARSE)
    (tmp_path / "coarse.txt").write_text(f"---- coarse ----\nStrain Tension\n(-) (N)\n{rows}")
    path = tmp_path / "taut.dat"
    path.write_text(TAUT_NETWORK)
    system = moordyn.Create(str(path))
    try:
        moordyn.Init(system, np.zeros(0), np.zeros(0))
        theirs_point = np.array(moordyn.GetPointPos(moordyn.GetPoint(system, 2)))
        theirs = []
        for i in (1, 2):
            line = moordyn.GetLine(system, i)
            n = moordyn.GetLineNumberNodes(line)
            theirs += [np.linalg.norm(moordyn.GetLineNodeTen(line, 0)),
                       np.linalg.norm(moordyn.GetLineNodeTen(line, n - 1))]
    finally:
        moordyn.Close(system)
    data = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(path))
    assert data["line_types"]["poly"]["stretch"]["interpolation"] == "linear"
    weight = data["line_types"]["poly"]["weight_in_water"]
    errors = {}
    for interpolation in ("linear", "monotone_cubic"):
        data["line_types"]["poly"]["stretch"]["interpolation"] = interpolation
        result = moorsolve.solve(moorsolve.load_case(data))
        assert result.converged
        point = result.points[0]
        ours_point = np.array([point["x_m"], point["y_m"], point["z_m"]])
        ours = _segment_tensions(result, weight, 20)
        errors[interpolation] = (np.max(np.abs(ours - np.array(theirs)) / ours),
                                 np.max(np.abs(ours_point - theirs_point)) / 168.0)
    assert errors["linear"][0] < 1e-4 and errors["linear"][1] < 1e-6, errors
    assert errors["monotone_cubic"][0] > 1e-3 and errors["monotone_cubic"][1] > 1e-3, errors
