"""Load tables (issue 16): sweep(case, table=...) and moorsolve sweep --table.

Every row must equal the single solve of the case that row describes; the columns are
validated once (by probes), and a bad cell is named by its column and row.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import moorsolve
from moorsolve.cli import main
from moorsolve.model.paths import with_values
from moorsolve.studies.load_table import TableAxis, parse_header
from moorsolve.studies.sweep_plan import SweepPlan

from conftest import CASES

DOCK = CASES / "floating_dock.yaml"
SPAR = CASES / "oc3_spar.yaml"
KNOT = 1852.0 / 3600.0


def dock_table(n, seed=5):
    rng = np.random.default_rng(seed)
    return pd.DataFrame({"environment.wind.speed [kn]": rng.uniform(10, 70, n),
                         "environment.wind.toward_deg": rng.uniform(0, 360, n),
                         "environment.current.speed": rng.uniform(0, 1.5, n),
                         "environment.waves.hs [m]": rng.uniform(0, 3, n)})


def row_case(case, table, i):
    """The case of row ``i``, made and validated the slow way: as a case file."""
    edits = {}
    for header in table.columns:
        path, unit = parse_header(header)
        value = table[header].iloc[i]
        value = value.item() if hasattr(value, "item") else value
        edits[path] = value if unit is None else f"{value!r} {unit}"
    return moorsolve.load_case(with_values(case.source, edits))


def assert_row_is_the_solve(result_row, solved, tol=1e-9):
    t_max = max(max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in solved.legs)
    for leg in solved.legs:
        assert abs(result_row[f"{leg.name}.fairlead_tension_N"] - leg.fairlead_tension_N) \
            <= tol * t_max
        assert abs(result_row[f"{leg.name}.anchor_tension_N"] - leg.anchor_tension_N) \
            <= tol * t_max
    if solved.body is not None:
        for key in ("x_m", "y_m", "yaw_deg"):
            assert result_row[key] == pytest.approx(solved.body[key], abs=1e-9)


def test_every_row_is_the_solve_of_its_case():
    case = moorsolve.load_case(DOCK)
    table = dock_table(40)
    result = moorsolve.sweep(case, table=table)
    assert list(result.columns[:4]) == list(table.columns)
    assert result["converged"].all() and (result["solver"] == "newton").all()
    for i in (0, 13, 39):
        assert_row_is_the_solve(result.iloc[i], moorsolve.solve(row_case(case, table, i),
                                                                solver="newton"))
    # Rows are solved as single solves are: from rest, so a row's answer does not depend
    # on the rows before it.
    again = moorsolve.sweep(case, table=table.iloc[::-1].reset_index(drop=True))
    np.testing.assert_allclose(again["L3.fairlead_tension_N"].to_numpy()[::-1],
                               result["L3.fairlead_tension_N"].to_numpy(), rtol=1e-12)


def test_a_unit_in_the_header_is_the_same_load_in_si():
    case = moorsolve.load_case(DOCK)
    knots = pd.DataFrame({"environment.wind.speed [kn]": [20.0, 40.0, 60.0]})
    si = pd.DataFrame({"environment.wind.speed": [20.0 * KNOT, 40.0 * KNOT, 60.0 * KNOT]})
    a, b = moorsolve.sweep(case, table=knots), moorsolve.sweep(case, table=si)
    for column in ("x_m", "y_m", "L3.fairlead_tension_N"):
        np.testing.assert_allclose(a[column], b[column], rtol=1e-12)


def test_columns_are_validated_once_by_probes_not_row_by_row():
    """A column of load entries is validated at its smallest, largest and median value:
    three case files, whatever the number of rows."""
    case = moorsolve.load_case(DOCK)
    table = dock_table(500)
    calls = []
    import moorsolve.io as io_package
    real = io_package.load_case

    def counting(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    io_package.load_case = counting
    try:
        plan = SweepPlan(case, table=table)
    finally:
        io_package.load_case = real
    assert plan.fast
    assert len(calls) <= 3 * len(table.columns)


def test_a_column_of_lengths_is_validated_per_value():
    """Not a load (it moves the geometry): each distinct value is its own case file, and
    the rows still equal their single solves."""
    case = moorsolve.load_case(DOCK)
    table = pd.DataFrame({"legs[L3].segments[0].length": [122.52, 123.0, 122.52, 124.0],
                          "environment.wind.speed": [30.0, 35.0, 40.0, 45.0]})
    result = moorsolve.sweep(case, table=table)
    for i in range(len(table)):
        assert_row_is_the_solve(result.iloc[i], moorsolve.solve(row_case(case, table, i),
                                                                solver="newton"))


def test_network_force_components_with_units():
    case = moorsolve.load_case(SPAR)
    table = pd.DataFrame({"bodies[spar].loads.force[0] [kN]": [200.0, 800.0, 1200.0],
                          "bodies[spar].loads.force[5] [kN*m]": [-2e3, 0.0, 3e3]})
    data = dict(case.source)
    data["bodies"] = [dict(data["bodies"][0], loads={"force": [0, 0, 0, 0, 0, 0]})]
    base = moorsolve.load_case(data)
    result = moorsolve.sweep(base, table=table)
    assert result["converged"].all()
    for i in range(len(table)):
        assert_row_is_the_solve(result.iloc[i], moorsolve.solve(row_case(base, table, i),
                                                                solver="newton"), 1e-8)
        assert result.iloc[i]["spar.x_m"] > 0


def test_rows_that_turn_far_are_solved_as_single_solves():
    """Rows whose moment turns the spar (without its yaw spring) past a Newton step's
    reach, and every other row, are their single solves: the batch leaves the far turns to
    the solve's continuation."""
    data = dict(moorsolve.load_case(SPAR).source)
    body = {k: v for k, v in data["bodies"][0].items() if k != "stiffness"}
    data["bodies"] = [dict(body, loads={"force": [0, 0, 0, 0, 0, 0]})]
    base = moorsolve.load_case(data)
    table = pd.DataFrame({"bodies[spar].loads.force[0] [kN]": [300.0, 300.0, 600.0, 100.0],
                          "bodies[spar].loads.force[5] [kN*m]": [1e3, 5e3, -1e4, 2e2]})
    result = moorsolve.sweep(base, table=table)
    assert result["converged"].all() and (result["solver"] == "newton").all()
    turned = 0
    for i in range(len(table)):
        solved = moorsolve.solve(row_case(base, table, i), solver="newton")
        assert_row_is_the_solve(result.iloc[i], solved, 1e-8)
        assert result.iloc[i]["spar.yaw_deg"] == pytest.approx(solved.bodies[0]["yaw_deg"],
                                                               abs=1e-7)
        turned += abs(solved.bodies[0]["yaw_deg"]) > 20
    assert turned >= 2


@pytest.mark.parametrize("column,values,words", [
    ("environment.wind.speed", [10.0, 500.0], ["environment.wind.speed", "row 1", "500"]),
    ("environment.wind.speed [furlong]", [10.0, 20.0], ["furlong"]),
    ("environment.wind.speedy", [10.0], ["speedy"]),
    ("environment.wind.speed", [10.0, float("nan")], ["row 1"]),
    ("legs[L99].anchor", [1.0], ["L99"]),
])
def test_a_bad_column_or_cell_is_named(column, values, words):
    case = moorsolve.load_case(DOCK)
    with pytest.raises(moorsolve.CaseError) as err:
        moorsolve.sweep(case, table=pd.DataFrame({column: values}))
    for word in words:
        assert word in str(err.value)


def test_a_table_or_a_grid_not_both():
    case = moorsolve.load_case(DOCK)
    with pytest.raises(moorsolve.CaseError):
        moorsolve.sweep(case, {"environment.wind.speed": [10]},
                        table=pd.DataFrame({"environment.wind.speed": [20.0]}))
    with pytest.raises(moorsolve.CaseError):
        moorsolve.sweep(case)


def test_the_plan_travels_to_a_worker():
    """A Dask worker rebuilds the plan from plain data: the same parameter vectors."""
    case = moorsolve.load_case(DOCK)
    plan = SweepPlan(case, table=dock_table(20))
    again = SweepPlan.from_spec(plan.spec())
    np.testing.assert_array_equal(again.vectors(), plan.vectors())
    assert again.grid_columns() == plan.grid_columns()


def test_header_parsing():
    assert parse_header("environment.wind.speed [kn]") == ("environment.wind.speed", "kn")
    assert parse_header("legs[L3].anchor") == ("legs[L3].anchor", None)
    assert parse_header("bodies[hull].loads.force[5] [kN m]") == \
        ("bodies[hull].loads.force[5]", "kN m")
    with pytest.raises(moorsolve.CaseError):
        TableAxis(pd.DataFrame({"a.b": [1.0], "a.b [m]": [2.0]}))


def test_command_line_table(tmp_path, capsys):
    table = dock_table(12)
    path = tmp_path / "loads.csv"
    table.to_csv(path, index=False)
    out = tmp_path / "results.csv"
    assert main(["sweep", str(DOCK), "--table", str(path), "-o", str(out), "--quiet"]) == 0
    written = pd.read_csv(out)
    assert len(written) == 12 and written["converged"].all()
    np.testing.assert_allclose(written["environment.wind.speed [kn]"],
                               table["environment.wind.speed [kn]"])
    bad = tmp_path / "bad.csv"
    pd.DataFrame({"environment.wind.speed": [10.0, 900.0]}).to_csv(bad, index=False)
    assert main(["sweep", str(DOCK), "--table", str(bad), "-o",
                 str(tmp_path / "r2.csv")]) == 2
    err = capsys.readouterr().err
    assert "--table" in err and "row 1" in err and not (tmp_path / "r2.csv").exists()
    assert main(["sweep", str(DOCK), "--table", str(path), "--set",
                 "environment.wind.speed=10", "-o", str(tmp_path / "r3.csv")]) == 2
