"""Batches of one structure take the fast paths and get the slow paths' answers.

Separately loaded cases of one scene share their equal parts (model/shared.py), so what a
solve derives from the lines is found again; each must still get, to 1e-9 of the largest
tension, what a case that shares nothing gets, a changed line must never be served the
structure of the unchanged one, and threads loading and solving at once agree.
"""

from __future__ import annotations

import copy
import json
import threading

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve.model import shared as shared_parts
from moorsolve.solve.assembly import prepared

from conftest import CASES

DOCK = CASES / "floating_dock.yaml"


def dock_data(force=(0.0, 0.0, 0.0)) -> dict:
    """The dock as case-file data with a constant force and no flows."""
    data = yaml.safe_load(DOCK.read_text())
    for flow in ("wind", "current", "waves"):
        data["environment"].pop(flow, None)
    data["body"]["loads"] = {"force": list(force)}
    return data


#: Answers reached from different starts agree to the certified tolerance: comparing them
#: to 1e-9 needs them certified tighter.
TIGHT = 1e-12

LOADS = [(1e6, 2e6, 1e7), (-3e6, 5e5, -2e7), (4e6, -1e6, 3e7), (0.0, 0.0, 0.0)]


def answers(result) -> np.ndarray:
    return np.array([result.body["x_m"], result.body["y_m"], result.body["yaw_deg"]]
                    + [leg.fairlead_tension_N for leg in result.legs]
                    + [leg.anchor_tension_N for leg in result.legs])


def assert_same(a, b, rtol=1e-9):
    """Poses to 1e-9 m (deg), tensions to ``rtol`` of the largest."""
    scale = max(np.abs(a[3:]).max(), 1.0)
    np.testing.assert_allclose(a[:3], b[:3], rtol=0, atol=1e-9)
    np.testing.assert_allclose(a[3:], b[3:], rtol=0, atol=rtol * scale)


def unshared(data):
    """A case that shares nothing with any earlier one: the slow path."""
    shared_parts.clear()
    prepared.clear()
    return moorsolve.load_case(copy.deepcopy(data))


def test_separately_loaded_cases_share_their_lines_and_get_the_unshared_answers():
    slow = [answers(moorsolve.solve(unshared(dock_data(f)), solver="newton")) for f in LOADS]
    cases = [moorsolve.load_case(dock_data(f)) for f in LOADS]
    assert all(c.lines is cases[0].lines and c.environment is cases[0].environment
               for c in cases)
    for case, expected in zip(cases, slow):
        assert_same(answers(moorsolve.solve(case, solver="newton")), expected)


def test_a_different_line_length_is_never_served_the_shared_structure():
    base = moorsolve.load_case(dock_data(LOADS[0]))
    moorsolve.solve(base, solver="newton")
    longer = dock_data(LOADS[0])
    longer["legs"][0]["segments"][0]["length"] *= 1.02
    changed = moorsolve.load_case(longer)
    assert changed.lines is not base.lines and changed.lines[0] != base.lines[0]
    assert not np.array_equal(prepared.case_parameters(changed),
                              prepared.case_parameters(base))
    got = answers(moorsolve.solve(changed, solver="newton"))
    assert_same(got, answers(moorsolve.solve(unshared(longer), solver="newton")))
    assert np.abs(got - answers(moorsolve.solve(base, solver="newton"))).max() > 1.0


def test_four_threads_loading_and_solving_one_structure_agree():
    forces = [(1e6 * (1 + k % 5), -5e5 * (k % 3), 1e7 * ((k % 7) - 3)) for k in range(24)]
    slow = {f: answers(moorsolve.solve(unshared(dock_data(f)), solver="newton"))
            for f in set(forces)}
    got, errors = {}, []

    def work(part):
        try:
            for f in part:
                got[(f, threading.get_ident())] = (f, answers(moorsolve.solve(
                    moorsolve.load_case(dock_data(f)), solver="newton")))
        except Exception as err:        # pragma: no cover - reported below
            errors.append(err)

    threads = [threading.Thread(target=work, args=(forces[k::4],)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert len(got) >= len(set(forces))
    for f, value in got.values():
        assert_same(value, slow[f])


# ---- grids: one vector axis of loads, validated by column ---------------------------------


def grid_answers(frame) -> np.ndarray:
    tensions = ([c for c in frame.columns if c.endswith(".fairlead_tension_N")]
                + [c for c in frame.columns if c.endswith(".anchor_tension_N")])
    return frame[["x_m", "y_m", "yaw_deg", *tensions]].to_numpy(dtype=float)


def random_forces(n, seed=3):
    rng = np.random.default_rng(seed)
    f, a = rng.uniform(0.1, 1.0, n) * 8e6, rng.uniform(0, 2 * np.pi, n)
    return [[float(x), float(y), float(m)] for x, y, m in
            zip(f * np.cos(a), f * np.sin(a), rng.uniform(-4e7, 4e7, n))]


def test_a_vector_axis_of_forces_is_the_table_of_the_same_loads_and_the_slow_grid(
        monkeypatch):
    import pandas as pd
    from moorsolve.studies import sweep_plan

    case = moorsolve.load_case(dock_data())
    forces = random_forces(80)
    grid = moorsolve.sweep(case, {"body.loads.force": forces}, tol=TIGHT)
    table = moorsolve.sweep(case, table=pd.DataFrame(
        {f"body.loads.force[{i}]": [f[i] for f in forces] for i in range(3)}), tol=TIGHT)
    assert grid["converged"].all() and (grid["solver"] == "newton").all()
    assert list(grid.columns[:3]) == [f"body.loads.force[{i}] [{u}]"
                                      for i, u in enumerate(("N", "N", "N m"))]
    fast = grid_answers(grid)
    for other in (grid_answers(table),):
        for row_a, row_b in zip(fast, other):
            assert_same(row_a, row_b)
    # The slow path: every value validated as a case, every point walked from its neighbour.
    monkeypatch.setattr(sweep_plan, "_axis_by_column", lambda *a: None)
    monkeypatch.setattr("moorsolve.studies.sweep_chunks._nearer_rest",
                        lambda P, loads, base: np.zeros(len(P), bool))
    slow = moorsolve.sweep(case, {"body.loads.force": forces}, tol=TIGHT)
    assert list(slow.columns) == list(grid.columns)
    np.testing.assert_array_equal(slow.iloc[:, :3].to_numpy(), grid.iloc[:, :3].to_numpy())
    for row_a, row_b in zip(fast, grid_answers(slow)):
        assert_same(row_a, row_b)
    single = answers(moorsolve.solve(case.with_values({"body.loads.force": forces[7]}),
                                     solver="newton", tol=TIGHT))
    assert_same(fast[7], single)


def test_a_bad_value_on_an_axis_of_numbers_is_named_by_the_grid():
    case = moorsolve.load_case(dock_data())
    with pytest.raises(moorsolve.CaseError, match=r"grid\['environment.water_density'\]"):
        moorsolve.sweep(case, {"environment.water_density": [1025.0, -3.0]})


def test_near_rest_start_depends_on_the_loads_alone():
    from moorsolve.studies.sweep_chunks import _nearer_rest

    loads = np.array([True, True, False])
    base = np.array([0.0, 0.0, 7.0])
    P = np.array([[1.0, 0.0, 7.0], [1.1, 0.0, 7.0], [-1.0, 0.0, 7.0], [0.1, 0.0, 8.0]])
    # row 1 is next to row 0; row 2 is nearer to no load; row 3 has another geometry.
    np.testing.assert_array_equal(_nearer_rest(P, loads, base), [False, False, True, False])


# ---- the command: a load table in, results out, CSV and Parquet -----------------------------


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_cli_table_round_trip(tmp_path, suffix, capsys):
    """``moorsolve sweep CASE --table LOADS -o OUT``: every row of the file read back is
    the in-memory sweep's row (same loads, same answers), with its columns' types."""
    import pandas as pd
    from moorsolve.cli import main

    case_file = tmp_path / "dock.yaml"
    case_file.write_text(yaml.safe_dump(dock_data()))
    forces = random_forces(90, seed=5)
    loads = pd.DataFrame({"body.loads.force[0] [kN]": [f[0] / 1e3 for f in forces],
                          "body.loads.force[1] [kN]": [f[1] / 1e3 for f in forces],
                          "body.loads.force[2]": [f[2] for f in forces]})
    table_file = tmp_path / f"loads{suffix}"
    if suffix == ".csv":
        loads.to_csv(table_file, index=False)
    else:
        loads.to_parquet(table_file, index=False)
    out = tmp_path / f"out{suffix}"
    assert main(["sweep", str(case_file), "--table", str(table_file), "-o", str(out),
                 "--quiet"]) == 0
    capsys.readouterr()
    got = pd.read_csv(out) if suffix == ".csv" else pd.read_parquet(out).reset_index()
    expected = moorsolve.sweep(moorsolve.load_case(case_file), table=loads)
    assert list(got["point"]) == list(range(90))
    assert got["converged"].dtype == bool and got["converged"].all()
    assert list(got["solver"]) == list(expected["solver"])
    for column in expected.columns:
        if expected[column].dtype.kind == "f":
            np.testing.assert_allclose(got[column].to_numpy(), expected[column].to_numpy(),
                                       rtol=1e-12, atol=0, err_msg=column)
    # The loads as given, in SI through the header's unit.
    np.testing.assert_allclose(got["body.loads.force[0] [kN]"], loads.iloc[:, 0])
    record = json.loads((out.parent / (out.name + ".sweep.json")).read_text())
    assert record["complete"] and record["grid"]["table"]["rows"] == 90


# ---- validation cached by structure -----------------------------------------------------


def test_legs_validated_once_are_never_served_for_other_data():
    good = dock_data(LOADS[0])
    first = moorsolve.load_case(good)
    again = moorsolve.load_case(dock_data(LOADS[1]))
    assert again.lines is first.lines                      # the legs validated once
    bad = dock_data(LOADS[1])
    bad["legs"][3]["segments"][0]["length"] = -5.0
    with pytest.raises(moorsolve.CaseError, match=r"legs\[3\]\.segments\[0\]\.length"):
        moorsolve.load_case(bad)
    heavier = dock_data(LOADS[1])
    heavier["environment"]["gravity"] = 9.7       # the chains' weights (t/m) depend on it
    changed = moorsolve.load_case(heavier)
    assert changed.lines is not first.lines
    fresh = unshared(heavier)
    assert changed.lines == fresh.lines and changed.line_types == fresh.line_types


def test_a_grid_of_repeated_leg_values_still_names_its_unit_column():
    case = moorsolve.load_case(dock_data((1e6, 0.0, 0.0)))
    frame = moorsolve.sweep(case, {"legs[*].segments[0].length": ["122.52 m", "12252 cm",
                                                                   "122.52 m"]})
    assert "legs[*].segments[0].length [m]" in frame.columns
    np.testing.assert_allclose(frame["legs[*].segments[0].length [m]"], 122.52)
    assert frame["converged"].all()
    assert_same(grid_answers(frame)[0], grid_answers(frame)[2], rtol=1e-9)


def test_a_scene_with_guides_sweeps_by_column_as_a_grid_and_a_table():
    """The point vector of a contact scene ends with its guides' limits: the load entries'
    mask must cover them (it stopped at the lines' limits and refused both forms)."""
    case = moorsolve.load_case(CASES / "pontoon_piles.yaml")
    levels = [0.0, 0.5, 1.0]
    grid = moorsolve.sweep(case, {"environment.water_level": levels})
    table = moorsolve.sweep(case, table={"environment.water_level": levels})
    assert list(grid["converged"]) == list(table["converged"])
    reactions = [c for c in grid.columns if c.endswith(".reaction_N")]
    assert reactions
    np.testing.assert_allclose(grid[reactions].to_numpy(), table[reactions].to_numpy(),
                               rtol=1e-6, atol=1e-3)


def test_edits_share_untouched_data_and_never_change_the_case_they_came_from():
    base = moorsolve.load_case(dock_data(LOADS[0]))
    before = copy.deepcopy(base.source)
    edited = base.with_values({"body.loads.force": list(LOADS[1])})
    longer = edited.with_values({"legs[0].segments[0].length": 130.0})
    assert base.source == before
    assert edited.source["body"]["loads"]["force"] == list(LOADS[1])
    assert edited.source["legs"][0]["segments"][0]["length"] == 122.52
    assert longer.source["legs"][0]["segments"][0]["length"] == 130.0
    assert edited.source["legs"] is base.source["legs"]     # shared, not copied
    assert longer.lines[0] != base.lines[0] and edited.lines is base.lines


def test_equal_grids_from_two_files_keep_their_own_source(tmp_path):
    """Two environments equal but for where their bathymetry grid was read from are not
    shared: each case reports its own file (equality leaves the source out)."""
    import yaml
    raw = yaml.safe_load((CASES / "dock_bathymetry.yaml").read_text())
    grid = moorsolve.load_case(CASES / "dock_bathymetry.yaml").environment.seabed.bathymetry
    inline = dict(raw)
    inline["environment"] = dict(raw["environment"])
    inline["environment"]["seabed"] = dict(raw["environment"]["seabed"],
                                           bathymetry={"x": list(grid.x), "y": list(grid.y),
                                                       "depth": [list(r) for r in grid.depth]})
    first = moorsolve.load_case(inline)
    second = moorsolve.load_case(CASES / "dock_bathymetry.yaml")
    assert first.environment.seabed.bathymetry == second.environment.seabed.bathymetry
    assert first.environment.seabed.bathymetry.source == "inline"
    assert second.environment.seabed.bathymetry.source.endswith("dock_bathymetry_seafloor.txt")
