"""The audit's fast path: the one free body's balance screened with half the margin,
compiled with the closed-form line checks.

A screen that passes must mean the plain balance (``moorsolve.audit.bodies.body_findings``) passes;
a screen that fails hands the result to the plain balance, so a defect planted in the
reported pose, loads or body data is found and worded exactly as before.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from moorsolve import load_case, solve
from moorsolve.model import BodyLoads
from moorsolve.audit import run as audit_module
from moorsolve.audit import AuditFailure
from moorsolve.audit.bodies import body_findings, one_body_inputs
from moorsolve.audit.closed_form import closed_form_check, table_end_rows, wait_compiled
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.model.line_table import LINE_COLUMNS
from conftest import ROOT

CASES = ROOT / "cases"
COL = {name: k for k, name in enumerate(LINE_COLUMNS)}


def solved(name):
    """Solved and its report; ``oc3_spar`` without its extra springs (as the benchmarks
    solve it), ``oc3_spar_springs`` the shipped case with them."""
    case = load_case(CASES / f"{name.removesuffix('_springs')}.yaml")
    if name == "oc3_spar":
        case = dataclasses.replace(case, bodies=(dataclasses.replace(case.bodies[0],
                                                                     stiffness=None),))
    result = solve(case, solver="newton")
    problem = get_problem(case)
    post = problem.post(result.state, problem.parameters(case, 1.0))
    return case, result, problem, post, np.atleast_2d(np.array(post["lines"], float))


def screens(problem, result, case, table):
    """(compiled screen or None where it does not cover the scene, plain findings) of the
    bodies' balance."""
    tol_rel = max(audit_module.GEOMETRY_REL, 100.0 * result.certificate.tolerance)
    body = one_body_inputs(problem, result, case)
    _, t_lines, balanced = closed_form_check(problem, case, table, tol_rel, body)
    found = body_findings(result, case, *table_end_rows(table), max(t_lines, 1.0))
    return (balanced if body is not None else None), found


@pytest.mark.parametrize("name, covered", [
    ("floating_dock", True), ("oc4_semi", True), ("oc3_spar", True),
    ("oc3_spar_springs", True), ("ship_97m", True), ("three_platforms", False)])
def test_a_certified_result_passes_every_screen_that_covers_it(name, covered):
    case, result, problem, post, table = solved(name)
    assert wait_compiled(len(case.lines), 600)
    compiled, found = screens(problem, result, case, table)
    assert found == []
    assert compiled is (True if covered else None)   # three_platforms: free points


def _pushed(result, df):
    return dataclasses.replace(result, loads={k: [v[0] + df, *v[1:]]
                                              for k, v in result.loads.items()})


def _shifted(result, dx):
    """The reported origin moved along x, the line ends not: the lines' moment changes."""
    bodies = [dict(b, x_m=b["x_m"] + dx) for b in result.bodies]
    return dataclasses.replace(result, bodies=tuple(bodies))


def _sunk(result, dz):
    bodies = [dict(b, z_m=b["z_m"] + dz) for b in result.bodies]
    return dataclasses.replace(result, bodies=tuple(bodies))


def _nan_pose(result, _):
    bodies = [dict(b, x_m=math.nan) for b in result.bodies]
    return dataclasses.replace(result, bodies=tuple(bodies))


@pytest.mark.parametrize("name, plant, size, dof", [
    ("floating_dock", _pushed, 1e4, "surge"),
    ("floating_dock", _shifted, 1.0, "yaw"),
    ("oc3_spar", _shifted, 1.0, ""),
    ("oc3_spar", _sunk, 0.01, "heave"),
    ("oc3_spar_springs", _shifted, 1.0, ""),
    ("oc3_spar_springs", _sunk, 0.01, "heave"),
    ("oc4_semi", _pushed, 1e4, "surge"),
])
def test_a_planted_body_defect_fails_every_screen_and_the_audit(name, plant, size, dof):
    case, result, problem, post, table = solved(name)
    assert wait_compiled(len(case.lines), 600)
    bad = plant(result, size)
    compiled, found = screens(problem, bad, case, table)
    assert compiled is False
    assert any(f"not in balance in {dof}" in f for f in found), found   # "": any dof
    with pytest.raises(AuditFailure) as failure:
        audit_module.audit(bad, case, problem, post)
    for f in found:
        assert f in str(failure.value)


@pytest.mark.parametrize("name", ["floating_dock", "oc3_spar"])
def test_a_pose_not_a_number_fails_the_screen_and_the_plain_balance(name):
    """A NaN compares false with any tolerance: both must count it as unbalanced (the
    plain balance once wrote its test so that a NaN passed)."""
    case, result, problem, post, table = solved(name)
    assert wait_compiled(len(case.lines), 600)
    compiled, found = screens(problem, _nan_pose(result, 0), case, table)
    assert compiled is False
    # x enters the moments about the body's origin (the forces do not depend on it).
    assert any("not in balance in yaw: nan" in f for f in found), found


def test_a_planted_fairlead_force_fails_the_screens():
    """A force moved on the body's end (the line checks find it too)."""
    case, result, problem, post, table = solved("floating_dock")
    assert wait_compiled(len(case.lines), 600)
    table = table.copy()
    table[0, COL["FBx"]] += 1e4
    compiled, found = screens(problem, result, case, table)
    assert compiled is False and found


def test_the_screen_counts_a_body_s_extra_springs():
    """The shipped OC3 spar's springs (its crow's foot's yaw stiffness) are in the compiled
    balance: under a yaw moment they carry part of it, and the screen passes the certified
    result with them and fails it without them (as the plain balance does)."""
    case = load_case(CASES / "oc3_spar.yaml")
    body = case.bodies[0]
    case = dataclasses.replace(case, bodies=(dataclasses.replace(
        body, loads=BodyLoads(force=(3e5, 0.0, 0.0, 0.0, 0.0, 5e6))),))
    result = solve(case, solver="newton")
    assert abs(result.bodies[0]["yaw_deg"]) > 0.1
    problem = get_problem(case)
    post = problem.post(result.state, problem.parameters(case, 1.0))
    table = np.atleast_2d(np.array(post["lines"], float))
    assert wait_compiled(len(case.lines), 600)
    assert screens(problem, result, case, table) == (True, [])
    bare = dataclasses.replace(case, bodies=(dataclasses.replace(case.bodies[0],
                                                                 stiffness=None),))
    compiled, found = screens(problem, result, bare, table)
    assert compiled is False and any("in yaw" in f for f in found), found
