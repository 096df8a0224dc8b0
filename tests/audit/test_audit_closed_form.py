"""The audit in closed form (issue 16): one-segment catenaries on a flat seabed are audited
from their reported end positions and forces, without drawing a profile.

It must pass every certified result the profile audit passes (``solve(..., audit="full")``
runs both, in the scene hunts as here) and find each defect the profile audit exists for:
an end force off its line's plane or not carrying the line's weight, a horizontal tension
that changes without friction to change it, a span the catenary does not close, a grounded
line off the seabed, a hanging line through it.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import moorsolve
from moorsolve import load_case, solve
from moorsolve.model import BodyLoads
from moorsolve.audit import run as audit_module
from moorsolve.audit import AuditFailure, closed_form_audit
from moorsolve.audit.closed_form import closed_form_findings, covers
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.model.line_table import LINE_COLUMNS
from conftest import ROOT

CASES = ROOT / "cases"
COL = {name: k for k, name in enumerate(LINE_COLUMNS)}
COVERED = ["floating_dock", "oc4_semi", "volturnus_s", "oc3_spar", "buoy_vida", "ship_97m",
           "three_platforms", "turret_ship"]


def solved(name, **options):
    case = load_case(CASES / f"{name}.yaml")
    result = solve(case, **options)
    problem = get_problem(case)
    post = problem.post(result.state, problem.parameters(case, 1.0))
    return case, result, problem, np.atleast_2d(np.array(post["lines"], float))


@pytest.mark.parametrize("name", COVERED)
def test_shipped_cases_are_covered_and_pass(name):
    case, result, problem, table = solved(name, audit="full")
    assert covers(problem, case)
    findings, t_max = closed_form_findings(problem, case, table, 1e-6)
    assert findings == []
    assert t_max == pytest.approx(max(max(leg.fairlead_tension_N, leg.anchor_tension_N)
                                      for leg in result.legs), rel=1e-12)


@pytest.mark.parametrize("name", ["floating_dock_sloped", "dock_bathymetry",
                                  "chain_polyester_clump", "fpu_polyester_table",
                                  "ship_berth"])
def test_other_scenes_are_left_to_the_profile_audit(name):
    case = load_case(CASES / f"{name}.yaml")
    problem = get_problem(case)
    assert not covers(problem, case)


def findings_after(change, name="floating_dock", line=0):
    """The closed-form findings for ``name``'s solved table with ``change(row)`` applied
    to line ``line``'s row."""
    case, result, problem, table = solved(name)
    table = table.copy()
    change(table[line])
    return closed_form_findings(problem, case, table, 1e-6)[0]


def test_a_fairlead_force_short_of_the_weight_is_found():
    found = findings_after(lambda row: row.__setitem__(COL["FBz"], row[COL["FBz"]] * 1.001))
    assert any("do not carry the line's weight" in f for f in found), found


def test_a_fairlead_force_off_the_plane_is_found():
    def turn(row):
        fx, fy = row[COL["FBx"]], row[COL["FBy"]]
        c, s = np.cos(1e-3), np.sin(1e-3)
        row[COL["FBx"]], row[COL["FBy"]] = c * fx - s * fy, s * fx + c * fy
    found = findings_after(turn)
    assert any("leave the line's vertical plane" in f for f in found), found


def test_a_moved_fairlead_is_found():
    found = findings_after(lambda row: row.__setitem__(COL["bx"], row[COL["bx"]] + 0.05))
    assert any("the catenary from the lower end's force reaches" in f for f in found), found


def test_a_wrong_grounded_length_is_found():
    case, result, problem, table = solved("floating_dock")
    grounded = [i for i, leg in enumerate(result.legs) if leg.grounded_length_m > 1.0]
    assert grounded
    found = findings_after(lambda row: row.__setitem__(COL["grounded"],
                                                       row[COL["grounded"]] + 0.5),
                           line=grounded[0])
    assert found and all(f.startswith(f"leg {result.legs[grounded[0]].name}:")
                         for f in found)


def test_a_horizontal_tension_lost_without_friction_is_found():
    case, result, problem, table = solved("floating_dock")
    i = next(i for i, leg in enumerate(result.legs) if leg.grounded_length_m > 1.0)

    def weaker_anchor(row):
        row[COL["FAx"]] *= 0.9
        row[COL["FAy"]] *= 0.9
    found = findings_after(weaker_anchor, line=i)
    assert any("horizontal tension changes" in f for f in found), found


def test_a_grounded_line_off_the_seabed_is_found():
    case, result, problem, table = solved("floating_dock")
    i = next(i for i, leg in enumerate(result.legs) if leg.grounded_length_m > 1.0)

    def raise_both(row):           # the whole line 2 m up: its shape still closes
        row[COL["az"]] += 2.0
        row[COL["bz"]] += 2.0
    found = findings_after(raise_both, line=i)
    assert found and all("off the seabed" in f for f in found), found


def test_a_hanging_line_through_the_seabed_is_found():
    """A consistent catenary whose vertex is 1 m below the seabed: only the seabed check
    can see it (the forces balance and the span closes)."""
    case, result, problem, table = solved("floating_dock")
    row = table[0].copy()
    env = case.environment
    line = case.lines[0]
    w, L, c = line.line_type.weight_in_water, line.length, 1.0 / line.line_type.ea
    H, V0 = 2e5, -0.3 * w * L                  # leaves the lower end downwards
    s = -V0 / w
    vertex = (H / w * (np.hypot(1.0, (V0 + w * s) / H) - np.hypot(1.0, V0 / H))
              + c * s * (V0 + w * s / 2))
    a = np.array([row[COL["ax"]], row[COL["ay"]], -env.depth - vertex - 1.0])
    u = np.array([row[COL["bx"]] - row[COL["ax"]], row[COL["by"]] - row[COL["ay"]]])
    u /= np.linalg.norm(u)
    a1, a0 = (V0 + w * L) / H, V0 / H
    x = H / w * (np.arcsinh(a1) - np.arcsinh(a0)) + H * c * L
    z = H / w * (np.hypot(1.0, a1) - np.hypot(1.0, a0)) + c * L * (V0 + w * L / 2)
    b = a + np.array([u[0] * x, u[1] * x, z])
    row[[COL[k] for k in ("ax", "ay", "az")]] = a
    row[[COL[k] for k in ("bx", "by", "bz")]] = b
    row[[COL[k] for k in ("FAx", "FAy", "FAz")]] = [H * u[0], H * u[1], V0]
    row[[COL[k] for k in ("FBx", "FBy", "FBz")]] = [-H * u[0], -H * u[1], -(V0 + w * L)]
    row[COL["grounded"]] = 0.0
    table = table.copy()
    table[0] = row
    found = closed_form_findings(problem, case, table, 1e-6)[0]
    assert [f for f in found if f.startswith(f"leg {line.name}:")] == [
        f"leg {line.name}: the line passes 1 m below the seabed"]


def test_a_steep_line_is_left_to_the_profile_audit():
    case, result, problem, table = solved("floating_dock")
    table = table.copy()
    for k in ("FBx", "FBy", "FAx", "FAy"):
        table[0, COL[k]] = 0.0
    assert closed_form_findings(problem, case, table, 1e-6)[0] is None
    assert closed_form_audit(result, case, problem, {"lines": table}) is None


def test_a_line_off_the_seabed_touching_down_is_left_to_the_profile_audit():
    """A bridle or shared line (its lower end off the seabed) is audited here while it hangs
    clear; touching down between its ends it has two arcs, which the profile audit draws."""
    case, result, problem, table = solved("three_platforms")
    lifted = [i for i, k in enumerate(problem.kinds) if k.lifted or k.block.lifted]
    assert lifted and closed_form_findings(problem, case, table, 1e-6)[0] == []
    table = table.copy()
    table[lifted[0], COL["grounded"]] = 1.0
    assert closed_form_findings(problem, case, table, 1e-6)[0] is None


def test_the_solve_audits_covered_scenes_without_profiles(monkeypatch):
    """The default audit of a covered scene draws no profile; ``audit="full"`` runs the
    profile audit too, and an unbalanced body fails either way."""
    case = load_case(CASES / "floating_dock.yaml")
    drawn = []
    real = audit_module.audit_findings
    monkeypatch.setattr(audit_module, "audit_findings",
                        lambda *a, **k: drawn.append(1) or real(*a, **k))
    solve(case, solver="newton")
    assert drawn == []
    solve(case, solver="newton", audit="full")
    assert drawn == [1]
    result = solve(case, solver="newton", audit=False)
    problem = get_problem(case)
    post = problem.post(result.state, problem.parameters(case, 1.0))
    pushed = dataclasses.replace(result, loads={k: [v[0] + 1e4, v[1], v[2]]
                                                for k, v in result.loads.items()})
    with pytest.raises(AuditFailure, match="not in balance in surge"):
        audit_module.audit(pushed, case, problem, post)


def test_newton_and_ipopt_pass_over_random_loads():
    """Random loads on the dock: every certified result passes both audits."""
    base = load_case(CASES / "floating_dock.yaml")
    env = dataclasses.replace(base.environment, wind=None, current=None, waves=None)
    rng = np.random.default_rng(16)
    solved_count = 0
    for _ in range(8):
        f, a = rng.uniform(0.1, 1.0) * 6e6, rng.uniform(0, 2 * np.pi)
        body = dataclasses.replace(base.body, loads=BodyLoads(force=(
            f * np.cos(a), f * np.sin(a), rng.uniform(-3e7, 3e7))))
        case = dataclasses.replace(base, environment=env, bodies=(body,))
        for solver in ("newton", "ipopt"):
            try:
                solve(case, solver=solver, audit="full")
                solved_count += 1
            except moorsolve.ConvergenceError as exc:
                assert not isinstance(exc, AuditFailure), exc
    assert solved_count >= 8
