"""Sweep and load-table rows carry the stability of their equilibrium (``stable``,
``min_eigenvalue``) and its warnings; a certified but unstable row is never clean."""

from __future__ import annotations

import copy
import math
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
import yaml

import moorsolve
from moorsolve import load_case, solve

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "solve"))
from test_weathervane import angle_between, calm_case  # noqa: E402

def test_table_rows_carry_stability_and_equal_single_solves():
    data = calm_case(30.0, 150.0)
    case = load_case(data)
    pairs = [(30.0, 150.0), (200.0, 300.0), (120.0, 270.0)]
    table = pd.DataFrame({"environment.wind.toward_deg": [w for w, _ in pairs],
                          "environment.current.toward_deg": [c for _, c in pairs]})
    rows = moorsolve.sweep(case, table=table)
    for k, (w, c) in enumerate(pairs):
        single = solve(load_case(calm_case(w, c)), solver="newton")
        row = rows.iloc[k]
        assert row["converged"] and row["stable"] and row["reason"] == ""
        assert angle_between(row["tanker.yaw_deg"], single.bodies[1]["yaw_deg"]) < 1e-6
        assert row["min_eigenvalue"] == pytest.approx(single.stability.min_eigenvalue,
                                                      rel=1e-6)
        assert row["warnings"] == ""


def test_kernel_rows_carry_the_smallest_eigenvalue():
    """Rows the compiled kernel certifies: the smallest eigenvalue from its stiffness
    output equals the single solve's, grid and table alike."""
    case = load_case("cases/floating_dock.yaml")
    headings = [0.0, 70.0, 150.0, 260.0]
    grid = moorsolve.sweep(case, {"environment.wind.toward_deg": headings}, solver="newton")
    table = moorsolve.sweep(case, table=pd.DataFrame(
        {"environment.wind.toward_deg": headings}))
    for k, heading in enumerate(headings):
        data = copy.deepcopy(case.source)
        data["environment"]["wind"]["toward_deg"] = heading
        single = solve(load_case(data), solver="newton")
        for rows in (grid, table):
            assert rows.iloc[k]["stable"] and rows.iloc[k]["solver"] == "newton"
            assert rows.iloc[k]["min_eigenvalue"] == pytest.approx(
                single.stability.min_eigenvalue, rel=1e-7)


def _raft(moment: float) -> dict:
    """A raft free in yaw on a negative yaw spring, its lines through its centre: yaw 0 is
    its only equilibrium, unstable, whatever the force."""
    spring = [[0.0] * 6 for _ in range(6)]
    spring[5][5] = -2.0e6
    return {
        "environment": {"depth": 40.0},
        "line_types": {"chain": {"weight_in_water": 600.0, "ea": 3e8}},
        "bodies": [{"name": "raft", "free": ["surge", "sway", "yaw"], "stiffness": spring,
                    "loads": {"force": [moment, 0.0, 0.0]}}],
        "lines": [{"name": f"L{k}", "from": [110 * math.cos(a), 110 * math.sin(a)],
                   "to": {"body": "raft", "at": [0, 0, 0]},
                   "segments": [{"type": "chain", "length": 120}]}
                  for k, a in enumerate((0.0, 2.1, 4.2))]}


def test_unstable_rows_are_never_clean(tmp_path):
    case = load_case(_raft(1e3))
    rows = moorsolve.sweep(case, {"bodies[raft].loads.force": [[1e3, 0, 0], [2e3, 0, 0]]})
    assert rows["converged"].all() and not rows["stable"].any()
    assert (rows["min_eigenvalue"] < 0).all()
    assert rows["reason"].str.startswith("unstable equilibrium (unstable in raft.yaw)").all()
    # The file carries the same columns; the command says so and exits 1.
    path = tmp_path / "raft.yaml"
    path.write_text(yaml.safe_dump(_raft(1e3)))
    out = tmp_path / "raft.csv"
    run = subprocess.run([sys.executable, "-m", "moorsolve", "sweep", str(path), "--set",
                          "bodies[raft].loads.force=[1e3,0,0],[2e3,0,0]", "-o", str(out), "--quiet"],
                         capture_output=True, text=True)
    assert run.returncode == 1
    assert "2 of 2 points are unstable equilibria" in run.stderr
    written = pd.read_csv(out, index_col="point")
    assert list(written["stable"]) == [False, False]
    assert written["reason"].str.contains("unstable").all()
    assert {"min_eigenvalue", "warnings"} <= set(written.columns)
    parquet = tmp_path / "raft.parquet"
    frame = moorsolve.sweep(case, {"bodies[raft].loads.force": [[1e3, 0, 0], [2e3, 0, 0]]},
                            output=str(parquet))
    stored = pd.read_parquet(parquet)
    assert list(stored["stable"]) == list(frame["stable"]) == [False, False]
    assert list(stored["min_eigenvalue"]) == pytest.approx(list(frame["min_eigenvalue"]))
    assert list(stored["warnings"]) == ["", ""]


def _buoy() -> dict:
    """A buoy free in surge, sway and heave on three chains, its fairleads 1 m under the
    water at rest: an upward force lifts them out (an ``end_in_air`` warning)."""
    return {"environment": {"depth": 30.0},
            "line_types": {"chain": {"weight_in_water": 300.0, "ea": 3e8,
                                     "weight_in_air": 350.0}},
            "bodies": [{"name": "buoy", "free": ["surge", "sway", "heave"], "mass": 50000.0,
                        "centre_of_gravity": [0, 0, -1.0],
                        "hydrostatics": {"displaced_volume": 60.0, "metacentre": [0, 0, 0.0],
                                         "waterplane_area": 20.0},
                        "loads": {"force": [0.0] * 6}}],
            "lines": [{"name": f"L{k}", "from": [80 * math.cos(a), 80 * math.sin(a)],
                       "to": {"body": "buoy", "at": [2 * math.cos(a), 2 * math.sin(a), -1.0]},
                       "segments": [{"type": "chain", "length": 90}]}
                      for k, a in enumerate((0.0, 2.1, 4.2))]}


def test_rows_carry_the_warnings_of_a_single_solve():
    """Rows the kernel solves carry no Result; a row whose fairleads rise out of the water
    is solved in full and carries the same warnings as a single solve, grid and table."""
    case = load_case(_buoy())
    lifts = [0.0, 1e5, 4e5, 8e5]
    grid = moorsolve.sweep(case, {"bodies[buoy].loads.force": [[0, 0, f, 0, 0, 0]
                                                               for f in lifts]},
                           solver="newton")
    table = moorsolve.sweep(case, table=pd.DataFrame({"bodies[buoy].loads.force[2]": lifts}))
    for k, lift in enumerate(lifts):
        data = copy.deepcopy(case.source)
        data["bodies"][0]["loads"]["force"][2] = lift
        single = solve(load_case(data), solver="newton")
        expected = "; ".join(w["message"] for w in single.warnings)
        assert (k >= 2) == bool(expected)       # the lift takes the fairleads out at 4e5 N
        for rows in (grid, table):
            assert rows.iloc[k]["warnings"] == expected
            assert rows.iloc[k]["stable"]
            assert rows.iloc[k]["min_eigenvalue"] == pytest.approx(
                single.stability.min_eigenvalue, rel=1e-6)


def test_envelope_rows_say_unstable(tmp_path):
    """The offset envelope (a zipped sweep) says on each row that its equilibrium is
    unstable."""
    from moorsolve.studies.envelope import format_envelope

    data = _raft(1e3)
    data["environment"]["wind"] = {"speed": 20.0, "toward_deg": 0.0}
    data["bodies"][0]["loads"]["wind"] = {"model": "drag", "area_x": 10, "area_y": 10}
    envelope = moorsolve.offset_envelope(load_case(data), step_deg=90)
    rows = format_envelope(envelope).splitlines()[3:7]
    assert len(rows) == 4 and all("(unstable equilibrium (unstable in raft.yaw)" in r
                                  for r in rows)
    path = tmp_path / "raft.yaml"
    path.write_text(yaml.safe_dump(data))
    run = subprocess.run([sys.executable, "-m", "moorsolve", "envelope", str(path), "--step",
                          "90"], capture_output=True, text=True)
    assert run.returncode == 1
    assert "only an unstable equilibrium at 4 of 4 headings" in run.stderr
