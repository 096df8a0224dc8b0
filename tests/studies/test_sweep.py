"""moorsolve.sweep: every row equals an individual solve; failures are rows, not aborts."""

import itertools
import math

import numpy as np
import pytest

import moorsolve
from moorsolve.errors import CaseError, ConvergenceError
from moorsolve.model.paths import with_values
from moorsolve.studies.sweep_grid import snake_order
from conftest import ROOT

CASES = ROOT / "cases"


def _point(case, edits):
    return moorsolve.load_case(with_values(case.source, edits))


def _assert_row_equals_solve(row, result):
    scale = max(max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in result.legs)
    assert row["converged"]
    for leg in result.legs:
        assert abs(row[f"{leg.name}.fairlead_tension_N"] - leg.fairlead_tension_N) <= 1e-9 * scale
        assert abs(row[f"{leg.name}.anchor_tension_N"] - leg.anchor_tension_N) <= 1e-9 * scale
    if result.body is not None:
        assert row["x_m"] == pytest.approx(result.body["x_m"], abs=1e-7)
        assert row["y_m"] == pytest.approx(result.body["y_m"], abs=1e-7)
        assert row["yaw_deg"] == pytest.approx(result.body["yaw_deg"], abs=1e-7)
    assert row["residual_relative"] <= 1e-9


def test_every_row_equals_an_individual_solve_dock():
    case = moorsolve.load_case(CASES / "floating_dock.yaml")
    grid = {"environment.wind.toward_deg": [0, 45, 90, 135], "environment.wind.speed": [20, 45],
            "environment.current.speed": ["0.5 m/s", 1.5]}
    df = moorsolve.sweep(case, grid)
    assert len(df) == 16
    # Grid columns: SI numbers, the unit in the name ("0.5 m/s" is 0.5).
    columns = ["environment.wind.toward_deg [deg]", "environment.wind.speed [m/s]",
               "environment.current.speed [m/s]"]
    assert list(df.columns[:3]) == columns
    assert all(df[c].dtype == float for c in columns)
    for (_, row), values in zip(df.iterrows(), itertools.product(*grid.values())):
        edits = dict(zip(grid, values))
        si = [float(v.split()[0]) if isinstance(v, str) else v for v in values]
        assert [row[c] for c in columns] == si              # product order
        _assert_row_equals_solve(row, moorsolve.solve(_point(case, edits)))


def test_leg_paths_and_a_structure_change_take_the_slow_path_and_still_agree():
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    # Gravity is part of the problem's structure: one full solve per point.
    grid = {"legs[*].segments[0].length": [48.0, 50.0, "52 m"], "environment.gravity": [9.81, 9.7]}
    df = moorsolve.sweep(case, grid)
    assert set(df["solver"]) == {"ipopt"}
    for (_, row), values in zip(df.iterrows(), itertools.product(*grid.values())):
        _assert_row_equals_solve(row, moorsolve.solve(_point(case, dict(zip(grid, values)))))


def test_one_leg_by_name_and_ipopt_solver_agree_with_fast_path():
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    name = case.legs[0].name
    grid = {f"legs[{name}].segments[0].length": [47.0, 50.0, 55.0],
            "environment.wind.toward_deg": [0, 120, 240]}
    fast = moorsolve.sweep(case, grid)
    ref = moorsolve.sweep(case, grid, solver="ipopt")
    assert set(fast["solver"]) == {"newton"} and set(ref["solver"]) == {"ipopt"}
    cols = [c for c in fast.columns if c.endswith("_N") and "residual" not in c]
    np.testing.assert_allclose(fast[cols].to_numpy(), ref[cols].to_numpy(), rtol=1e-9,
                               atol=1e-9 * ref[cols].to_numpy().max())


def test_failed_points_are_rows_with_reasons():
    case = moorsolve.load_case(CASES / "ship_97m.yaml")
    grid = {"body.loads.force": [[0, 0, 0], [-2e5, 0, 0], [-5e6, 0, 0]]}
    df = moorsolve.sweep(case, grid)
    assert list(df["converged"]) == [True, True, False]
    with pytest.raises(ConvergenceError) as err:
        moorsolve.solve(_point(case, {"body.loads.force": [-5e6, 0, 0]}))
    reason = df["reason"].iloc[2]
    assert reason and reason.split(":")[0] == err.value.reason.split(":")[0]
    assert df["reason"].iloc[0] == ""


def test_parallel_and_serial_sweeps_are_identical():
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    grid = {"environment.wind.toward_deg": list(np.linspace(0, 350, 12)),
            "environment.wind.speed": list(np.linspace(5, 35, 8))}
    one = moorsolve.sweep(case, grid, workers=1)
    two = moorsolve.sweep(case, grid, workers=2)
    assert one["converged"].all() and two["converged"].all()
    cols = [c for c in one.columns if c.endswith("tension_N")] + ["x_m", "y_m"]
    np.testing.assert_allclose(one[cols].to_numpy(), two[cols].to_numpy(), rtol=1e-9, atol=1e-8)


@pytest.mark.parametrize("grid, field", [
    ({"environment.wind.sped": [1, 2]}, "grid['environment.wind.sped']"),
    ({"environment.wind.speed": []}, "grid['environment.wind.speed']"),
    ({"environment.wind.speed": "30"}, "grid['environment.wind.speed']"),
    ({"environment.wind.speed": [10, -5]}, "grid['environment.wind.speed']"),
    ({"legs[nope].segments[0].length": [50]}, "grid['legs[nope].segments[0].length']"),
    ({"legs[7].anchor": [[0, 0]]}, "grid['legs[7].anchor']"),
    ({"environment..depth": [20]}, "environment..depth"),
    ({}, "grid"),
])
def test_bad_grids_name_the_field(grid, field):
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    with pytest.raises(CaseError) as err:
        moorsolve.sweep(case, grid)
    assert err.value.field == field or str(err.value).startswith(field)


def test_sweep_needs_case_file_data():
    import dataclasses
    case = dataclasses.replace(moorsolve.load_case(CASES / "buoy_vida.yaml"), source=None)
    with pytest.raises(CaseError, match="load_case"):
        moorsolve.sweep(case, {"environment.wind.speed": [1]})


@pytest.mark.parametrize("shape", [(1,), (5,), (3, 4), (2, 3, 4), (4, 1, 3)])
def test_snake_order_visits_each_point_once_by_unit_steps(shape):
    order = snake_order(shape)
    assert sorted(order) == sorted(itertools.product(*[range(n) for n in shape]))
    for a, b in zip(order, order[1:]):
        assert sum(abs(i - j) for i, j in zip(a, b)) == 1


def test_with_values_leaves_the_source_untouched():
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    before = repr(case.source)
    edited = with_values(case.source, {"legs[*].segments[0].length": 60,
                                       "environment.current.speed": 1.0})
    assert repr(case.source) == before
    assert all(leg["segments"][0]["length"] == 60 for leg in edited["legs"])
    assert edited["environment"]["current"] == {"speed": 1.0}
    assert math.isclose(case.legs[0].length, moorsolve.load_case(case.source).legs[0].length)
