"""MoorDyn line types whose EA is a tension-strain curve file, in and out.

MoorDyn reads an EA that is not a number as the name of a file (MoorDyn-C: a token that does
not parse as a number; MoorDyn-F: one with a letter other than e/E): three header lines,
then ``strain tension`` rows, at most 30. Import makes it a table law; export writes the
table (a Baranov law sampled) beside the ``.dat``; MoorDyn itself (the optional peer) reads
the exported curve and holds the exported equilibrium.
"""

from __future__ import annotations

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
                               "tension": CURVE_TENSION}
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
    case = moorsolve.load_case(str(FPU))
    out = tmp_path / "fpu.dat"
    moorsolve.export_moordyn(case, out, version=version)
    curve = tmp_path / "fpu_polyester160_ea.txt"
    text = curve.read_text()
    assert not text.endswith("\n")                 # MoorDyn-C rejects an empty last line
    assert "fpu_polyester160_ea.txt" in out.read_text()
    lines = text.split("\n")
    assert len(lines) == 3 + 9
    back = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(out))
    law = case.line_types["polyester160"].stretch
    assert back["line_types"]["polyester160"]["stretch"] == {
        "model": "table", "strain": list(law.strain), "tension": list(law.tension)}


def test_network_export_writes_the_curve_too(tmp_path):
    data = yaml.safe_load((CASES / "three_platforms.yaml").read_text())
    lt = data["line_types"]["shared"]
    ea = float(lt.pop("ea"))
    lt["stretch"] = {"model": "table", "strain": [0.001, 0.002, 0.004],
                     "tension": [ea * 0.001, ea * 0.002, ea * 0.005]}
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
