"""A damaged condition that leaves a body held by nothing (a tanker on one hawser to a CALM
buoy): the check names the body that drifts off and why, in text, JSON and the HTML
report, and still checks the rest of the mooring; a plain solve says the same."""

from __future__ import annotations

import copy
import dataclasses
import json
import math

import pytest

import moorsolve
from moorsolve.checks import run_checks
from moorsolve.model.edit import without_line
from moorsolve.model.restraint import drifting_bodies
from moorsolve.report.check_html import render_html
from moorsolve.report.check_text import check_json, format_check_table

WIND, CURRENT = 20.0, 1.0                      # m/s, both toward +x
WIND_AREA_X, WIND_CX = 1000.0, 0.8              # tanker's frontal windage
CURRENT_AREA_X, CURRENT_CX = 900.0, 0.6         # and its frontal underwater area


def calm_case(n_chains: int = 6) -> dict:
    """A CALM buoy on ``n_chains`` chains (free in surge and sway) and a tanker free in
    surge, sway and yaw on one weightless hawser from the buoy to its bow; wind and current
    from astern of the tanker (it lies downwind of the buoy, bow toward it)."""
    points, lines = [], []
    for k in range(n_chains):
        a = 2 * math.pi * k / n_chains
        points.append({"name": f"A{k + 1}", "position": [300 * math.cos(a), 300 * math.sin(a)]})
        lines.append({"name": f"C{k + 1}", "from": f"A{k + 1}",
                      "to": {"body": "buoy", "at": [5 * math.cos(a), 5 * math.sin(a), -4.0]},
                      "segments": [{"type": "chain", "length": 320.0}]})
    lines.append({"name": "hawser", "from": {"body": "buoy", "at": [0.0, 0.0, 2.0]},
                  "to": {"body": "tanker", "at": [150.0, 0.0, 3.0]},
                  "segments": [{"type": "hawser", "length": 62.0}]})
    return {
        "name": "CALM buoy and tanker",
        "environment": {"depth": 50.0, "wind": {"speed": WIND, "toward_deg": 0.0},
                        "current": {"speed": CURRENT, "toward_deg": 0.0}},
        "line_types": {"chain": {"weight_in_water": 1200.0, "ea": 8.0e8, "mbl": 7.0e6},
                       "hawser": {"weight_in_water": 0.0, "ea": 1.5e8, "mbl": 4.0e6}},
        "bodies": [
            {"name": "buoy", "free": ["surge", "sway"]},
            {"name": "tanker", "position": [215.0, 0.0, 0.0], "orientation_deg": [0, 0, 180],
             "free": ["surge", "sway", "yaw"],
             "loads": {"wind": {"model": "drag", "area_x": WIND_AREA_X, "area_y": 4000,
                                "cx": WIND_CX, "cy": 0.9, "centre": [-20.0, 0.0]},
                       "current": {"model": "drag", "area_x": CURRENT_AREA_X, "area_y": 5000,
                                   "cx": CURRENT_CX, "cy": 0.8, "centre": [-10.0, 0.0]}}},
        ],
        "points": points, "lines": lines,
    }


def drag_on_tanker() -> float:
    """The wind and current drag on the tanker, head on (½ rho cx A V²) [N]."""
    return (0.5 * 1.225 * WIND_CX * WIND_AREA_X * WIND ** 2
            + 0.5 * 1025.0 * CURRENT_CX * CURRENT_AREA_X * CURRENT ** 2)


@pytest.fixture(scope="module")
def calm_report():
    return run_checks(moorsolve.load_case(calm_case()))


def test_only_the_hawser_leaves_a_body_held_by_nothing():
    case = moorsolve.load_case(calm_case())
    assert drifting_bodies(case) == []
    for line in case.lines:
        drifts = drifting_bodies(without_line(case, line.name))
        if line.name == "hawser":
            assert [(d.body, d.dofs, d.lines) for d in drifts] == [
                ("tanker", ("surge", "sway"), ())]
        else:
            assert drifts == []


def test_a_buoy_on_one_chain_drifts_with_its_tanker_when_the_chain_goes():
    case = moorsolve.load_case(calm_case(n_chains=1))
    drifts = drifting_bodies(without_line(case, "C1"))
    assert [d.body for d in drifts] == ["buoy", "tanker"]
    tanker = drifts[1]
    assert tanker.lines == ("hawser",) and tanker.group == ("body tanker", "body buoy")
    assert tanker.describe() == ("body tanker is held only by line hawser to body buoy, "
                                 "which drifts with it (no line path to an anchor)")


def test_a_spring_or_a_held_dof_holds_a_body():
    broken = without_line(moorsolve.load_case(calm_case()), "hawser")
    assert [d.body for d in drifting_bodies(broken)] == ["tanker"]

    def tanker(**change):
        bodies = tuple(dataclasses.replace(b, **change) if b.name == "tanker" else b
                       for b in broken.bodies)
        return dataclasses.replace(broken, bodies=bodies)
    assert drifting_bodies(tanker(free=("yaw",))) == []         # held in surge and sway
    k = [[0.0] * 6 for _ in range(6)]
    k[0][0] = k[1][1] = 1e5
    assert drifting_bodies(tanker(stiffness=tuple(map(tuple, k)))) == []
    k[1][1] = 0.0                                               # a spring in surge only
    (sway,) = drifting_bodies(tanker(stiffness=tuple(map(tuple, k))))
    assert sway.dofs == ("sway",)
    assert sway.restores == "nothing restores it in sway"


def test_check_names_the_tanker_that_drifts_off_with_its_load(calm_report):
    lost = next(c for c in calm_report.conditions if c.removed == "hawser")
    assert not lost.passed and lost.solved
    (drift,) = lost.drifting
    assert drift["body"] == "tanker" and drift["dofs"] == ["surge", "sway"]
    assert drift["load_N"] == pytest.approx(drag_on_tanker(), rel=1e-9)
    assert drift["toward_deg"] == pytest.approx(0.0, abs=1e-6)
    assert drift["message"] == (
        "body tanker is held by no line and drifts off: nothing restores it in surge and "
        f"sway, and the wind and the current push it {drag_on_tanker() / 1e3:.1f} kN toward "
        "0 deg")
    # The rest of the mooring is still checked: every chain, none of it the hawser.
    legs = {i.leg for i in lost.items if i.check == "tension"}
    assert legs == {f"C{k}" for k in range(1, 7)}
    assert all(i.passed for i in lost.items)
    # Every other condition keeps its tanker and passes.
    assert all(c.passed and not c.drifting for c in calm_report.conditions
               if c.removed != "hawser")


def test_the_lost_tanker_is_in_the_text_json_and_html(calm_report):
    case = moorsolve.load_case(calm_case())
    message = next(c for c in calm_report.conditions if c.removed == "hawser").drifting[0][
        "message"]
    text = format_check_table(calm_report)
    assert f"LOST: {message}" in text
    assert f"failed: damaged: hawser removed: {message}" in text
    data = json.loads(check_json(calm_report))
    cond = next(c for c in data["conditions"] if c["removed"] == "hawser")
    assert cond["passed"] is False and cond["drifting"][0]["message"] == message
    assert f"damaged: hawser removed: {message}" in data["failures"]
    page = render_html(calm_report, case, {})
    assert message in page and "body tanker" in page


def test_without_a_load_the_message_says_none_acts():
    data = calm_case()
    data["environment"].pop("wind")
    data["environment"].pop("current")
    report = run_checks(moorsolve.load_case(data))
    lost = next(c for c in report.conditions if c.removed == "hawser")
    assert not lost.passed
    assert lost.drifting[0]["load_N"] is None
    assert lost.drifting[0]["message"].endswith(
        "nothing restores it in surge and sway; it drifts off under any horizontal load "
        "(none acts on it in this condition)")


def test_solve_of_the_broken_scene_names_the_tanker_not_the_chains():
    case = without_line(moorsolve.load_case(calm_case()), "hawser")
    with pytest.raises(moorsolve.ConvergenceError) as exc:
        moorsolve.solve(case)
    assert "body tanker is held by no line: nothing restores it in surge and sway" in str(
        exc.value)
    assert "the legs could not balance" not in str(exc.value)


def test_a_ship_turning_about_its_turret_is_not_flagged_as_a_unit_slip():
    """The turret ship weathervanes half round: its origin swings past the water depth while
    the turret, where the chains hold it, moves a fraction of it. The modelling warning
    'displaced more than the water depth' is for slips of units or lengths, so it measures
    where the lines hold the body; a body that truly runs away is still flagged."""
    from conftest import CASES
    from moorsolve.checks.modelling import modelling_warnings
    case = moorsolve.load_case(CASES / "turret_ship.yaml")
    result = moorsolve.solve(case)
    ship = result.bodies[0]["offset"]
    assert math.hypot(ship["x_m"], ship["y_m"]) > case.environment.depth
    assert not [w for w in modelling_warnings(case, result) if w.code == "drift"]


def test_notebook_views_of_the_calm_scene(calm_report):
    """The notebook views: a network result's 6-long loads (once a crash) and the lost
    tanker under the check's table."""
    result = calm_report.conditions[0].result
    page = result._repr_html_()
    assert "load: tanker.wind" in page and "Fx 196.00 kN" in page
    assert "LOST: damaged: hawser removed: body tanker is held by no line" in \
        calm_report._repr_html_()
