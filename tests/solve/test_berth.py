"""Berths end to end (issue 15): the shipped berth cases, sweeps through contact changes,
hawser pretension, the tide, the berth checks, the berth pictures, threads."""

from __future__ import annotations

import copy
import dataclasses
import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve import CaseError, load_case, solve
from moorsolve.checks import run_checks

from conftest import CASES
from test_contact import EA, F, berth

SHIP = CASES / "ship_berth.yaml"
DOCK = CASES / "dock_quay.yaml"
PONTOON = CASES / "pontoon_piles.yaml"


def away_case() -> dict:
    """The berth of tests/test_contact.py with two slack 8.5 m hawsers to bollards on the
    quay (chord 8 m at rest)."""
    points = [{"name": "B1", "position": [-5.0, 10.0, 2.0]},
              {"name": "B2", "position": [-5.0, -10.0, 2.0]}]
    lines = [{"name": f"H{i}", "from": f"B{i}", "to": {"body": "b", "at": [3.0, y, 2.0]},
              "segments": [{"type": "hawser", "length": 8.5}]}
             for i, y in ((1, 10.0), (2, -10.0))]
    return berth([0, 0, 0], free=("surge", "sway", "yaw"), points=points, lines=lines)


def test_a_sweep_through_contact_changes_never_fails():
    """The load runs from 2F onto the quay (fenders closed, hawsers slack) to 2F away from
    it (fenders open, hawsers taut): every point converges with the compiled kernel, each
    row equals its own solve, and the contacts open and close exactly where statics says:
    fenders carry F_onto/2 each, hawsers F_away/2 each. (At zero load the body may rest
    anywhere between the fenders and the hawsers' reach: not a point of this grid.)"""
    data = away_case()
    case = load_case(data)
    loads = [[fx, 0, 0] for fx in np.linspace(-2 * F, 2 * F, 8)]
    table = moorsolve.sweep(case, {"bodies[b].loads.force": loads})
    assert table["converged"].all()
    assert (table["solver"] == "newton").all()
    for (_, row), load in zip(table.iterrows(), loads):
        fx = load[0]
        onto, away = max(-fx, 0.0), max(fx, 0.0)
        assert row["F1.reaction_N"] == pytest.approx(onto / 2, rel=1e-6, abs=1e-6)
        assert row["F2.reaction_N"] == pytest.approx(onto / 2, rel=1e-6, abs=1e-6)
        assert row["H1.fairlead_tension_N"] == pytest.approx(away / 2, rel=1e-6, abs=1e-6)
        one = data.copy()
        one["bodies"] = copy.deepcopy(data["bodies"])
        one["bodies"][0]["loads"]["force"] = load
        single = solve(load_case(one), solver="ipopt")
        assert row["x_m"] == pytest.approx(single.body["x_m"], abs=1e-8)


def test_a_hawser_given_by_its_pretension_carries_it_at_the_case_pose():
    """Hand-derived: L = D / (1 + T0/EA) makes EA (D/L - 1) = T0 with the body held where
    the case places it (D = 8.0 m between bollard and fairlead)."""
    data = away_case()
    data["bodies"][0]["free"] = []
    for line in data["lines"]:
        line["segments"] = [{"type": "hawser", "pretension": "30 kN"}]
    result = solve(load_case(data))
    for h in result.hawsers:
        assert h["pretension_N"] == 30e3
        assert h["length_m"] == pytest.approx(8.0 / (1 + 30e3 / EA), rel=1e-12)
        assert h["tension_N"] == pytest.approx(30e3, rel=1e-9)


@pytest.mark.parametrize("segment, field, words", [
    ({"type": "hawser", "pretension": "30 kN", "length": 8}, "lines[0].segments[0].length",
     "unknown key"),
    ({"type": "chain", "pretension": "30 kN"}, "lines[0].segments[0].pretension",
     "weightless elastic"),
    ({"type": "hawser", "pretension": "-1 kN"}, "lines[0].segments[0].pretension", ">= 0"),
])
def test_bad_pretension_names_the_field(segment, field, words):
    data = away_case()
    data["line_types"]["chain"] = {"weight_in_water": 500.0, "ea": 1e8}
    data["lines"][0]["segments"] = [segment]
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == field and words in str(err.value)


def test_the_pontoon_rises_with_the_tide_and_its_piles_bend_more():
    """The pontoon floats at the still-water level whatever the tide (its hull and weight
    do not change): z = h. Its guides then sit h higher above the seabed, so each pile, a
    cantilever, carries the same guide force at a longer arm: moment = R (1 + h + 6) with
    the collar 1 m above the waterline and the seabed 6 m below the datum; the pile also
    gives more (3 E I / arm^3), so the pontoon moves further across."""
    case = load_case(PONTOON)
    offsets = []
    for h in (0.0, 2.0, 4.0):
        scene = dataclasses.replace(case, environment=dataclasses.replace(
            case.environment, water_level=h))
        r = solve(scene, solver="newton")
        assert r.bodies[0]["z_m"] == pytest.approx(h, abs=1e-3)
        for g in r.guides:
            arm = g["height_m"] + 6.0
            assert g["pile_moment_Nm"] == pytest.approx(g["reaction_N"] * arm, rel=1e-12)
            assert g["on_pile"]
        offsets.append(r.body["y_m"])
    assert offsets[0] < offsets[1] < offsets[2]


def test_a_collar_above_the_pile_top_is_reported():
    case = load_case(PONTOON)
    scene = dataclasses.replace(case, environment=dataclasses.replace(
        case.environment, water_level=5.5))
    r = solve(scene, solver="newton")
    assert not r.guide("G1")["on_pile"]
    assert any("come off the pile" in note for note in r.notes)
    report = run_checks(scene)
    assert not report.passed
    assert any("guide on pile" in failure for failure in report.failures)


def test_water_level_below_the_seabed_is_refused():
    data = yaml.safe_load(PONTOON.read_text())
    data["environment"]["water_level"] = -7.0
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "environment.water_level"


def test_berth_checks_use_meg4_for_hawsers_and_rated_deflection_for_fenders():
    """Every hawser of the ship is checked against 50 % of its MBL (MEG4's working load
    limit for synthetic lines), every fender against its rated deflection; a damaged
    condition (one line parted) re-solves the ship on the other seven."""
    report = run_checks(load_case(SHIP))
    intact = report.conditions[0]
    hawsers = [i for i in intact.items if i.check == "hawser tension"]
    fenders = [i for i in intact.items if i.check == "fender compression"]
    assert len(hawsers) == 8 and len(fenders) == 4
    result = intact.result
    for item in hawsers:
        leg = result.leg(item.leg)
        assert item.limit == pytest.approx(0.5 * 1.5e6)
        assert item.utilisation == pytest.approx(leg.fairlead_tension_N / (0.5 * 1.5e6))
        assert "MEG4" in item.criterion
    for item in fenders:
        assert item.limit == pytest.approx(1.01)       # the table's last deflection
    assert len(report.conditions) == 9                 # intact and each line parted


def test_a_wire_hawser_gets_meg4s_steel_wire_limit():
    from moorsolve.checks.berth import hawser_criterion
    wire = moorsolve.model.LineType(name="w", weight_in_water=0.0, ea=1e8, mbl=1e6,
                                    catalog="wire_iwrc")
    rope = moorsolve.model.LineType(name="r", weight_in_water=0.0, ea=1e8, mbl=1e6)
    assert hawser_criterion(wire).limit == 0.55
    assert hawser_criterion(rope).limit == 0.50


def test_the_dock_stays_on_its_fenders_with_a_hawser_parted():
    report = run_checks(load_case(DOCK))
    assert report.passed, report.failures
    for condition in report.conditions:
        assert all(f["in_contact"] for f in condition.result.fenders)


def test_berth_pictures_draw_headless(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    from moorsolve import plot
    for path in (SHIP, PONTOON):
        result = solve(load_case(path), solver="newton")
        ax = plot.plot_berth(result)
        assert ax.patches                       # piles, hull footprints, collars, walls
        assert len(ax.lines) == len(result.fenders) + (1 if result.fenders else 0)
        fig = plot.plot_equilibrium(result)
        fig.savefig(tmp_path / f"{path.stem}.png")
        assert (tmp_path / f"{path.stem}.png").stat().st_size > 10_000


def test_threads_solve_berths_as_serial_runs_do():
    """Eight threads solving the ship under different winds give the serial answers."""
    case = load_case(SHIP)

    def with_wind(speed):
        env = dataclasses.replace(case.environment,
                                  wind=dataclasses.replace(case.environment.wind, speed=speed))
        return dataclasses.replace(case, environment=env)

    speeds = [10.0 + 2 * k for k in range(8)]
    serial = [solve(with_wind(v), solver="newton") for v in speeds]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda v: solve(with_wind(v), solver="newton"), speeds))
    for a, b in zip(serial, threaded):
        assert [h["tension_N"] for h in a.hawsers] == [h["tension_N"] for h in b.hawsers]
        assert math.isclose(a.body["y_m"], b.body["y_m"], rel_tol=0, abs_tol=0)
