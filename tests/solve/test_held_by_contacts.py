"""A body held by its contacts alone: pile guides or fenders, no line.

Hand statics (as in tests/solve/test_contact.py): a pontoon on two rigid guide piles
10 m either side of its centre, pushed sideways by F through the centre, free in sway and
yaw, crosses the collars' clearance c and bears on one pad of each: each guide takes F/2.
"""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml

import moorsolve
from moorsolve import CaseError, load_case, solve
from moorsolve.checks.modelling import modelling_warnings

CASES = Path(__file__).resolve().parents[2] / "cases"
F = 2.0e5
SOLVERS = ("ipopt", "newton")


def pontoon(force, free=("sway", "yaw")) -> dict:
    """A pontoon on two rigid guide piles at (+-10, 0), collars 1 m above the water with
    5 cm of play; no lines and no line types."""
    return {
        "name": "pontoon on guides alone", "environment": {"depth": 8.0},
        "bodies": [{"name": "p", "free": list(free), "loads": {"force": list(force)}}],
        "piles": [{"name": "P1", "position": [10.0, 0.0], "radius": 0.4},
                  {"name": "P2", "position": [-10.0, 0.0], "radius": 0.4}],
        "guides": [{"name": "G1", "body": "p", "at": [10.0, 0.0, 1.0], "pile": "P1",
                    "clearance": 0.05},
                   {"name": "G2", "body": "p", "at": [-10.0, 0.0, 1.0], "pile": "P2",
                    "clearance": 0.05}],
    }


@pytest.mark.parametrize("solver", SOLVERS)
def test_guides_alone_hold_a_pontoon(solver):
    r = solve(load_case(pontoon([0.0, F, 0.0])), solver=solver)
    assert r.converged and r.legs == ()
    assert r.body["y_m"] == pytest.approx(0.05, rel=1e-9)
    for name in ("G1", "G2"):
        assert r.guide(name)["reaction_N"] == pytest.approx(F / 2, rel=1e-9)
    assert r.warnings == ()
    assert not [w for w in modelling_warnings(r.case, r) if w.code == "all_slack"]
    d = r.to_dict(profiles=False)
    assert d["legs"] == [] and len(d["guides"]) == 2


def test_a_slack_line_added_changes_nothing():
    """The same pontoon with an idle slack rope to the shore (what a line-less berth
    needed before): the same equilibrium, to the solver's tolerance."""
    alone = solve(load_case(pontoon([0.0, F, 0.0])), solver="newton")
    data = pontoon([0.0, F, 0.0])
    data["line_types"] = {"rope": {"weight_in_water": 0, "ea": 1e7}}
    data["lines"] = [{"name": "idle", "from": [0.0, 50.0, 0.0], "to": {"body": "p",
                                                                      "at": [0, 0, 0]},
                      "segments": [{"type": "rope", "length": 60.0}]}]
    roped = solve(load_case(data), solver="newton")
    assert roped.legs[0].slack
    for name in ("G1", "G2"):
        assert alone.guide(name)["reaction_N"] == pytest.approx(
            roped.guide(name)["reaction_N"], rel=1e-9)


def test_the_shipped_pontoon_has_no_line_and_no_slack_warning():
    """cases/pontoon_piles.yaml: the guides hold the pontoon; its old slack gangway rope
    is gone, and with it the warning that all its lines are slack. The answer is the one
    the case gave with the rope (G1 16.35 kN, G2 18.35 kN, the pontoon 5 cm across)."""
    case = load_case(CASES / "pontoon_piles.yaml")
    assert case.lines == ()
    r = solve(case, solver="newton")
    assert r.solver == "newton"
    assert r.guide("G1")["reaction_N"] == pytest.approx(16352.72, rel=1e-6)
    assert r.guide("G2")["reaction_N"] == pytest.approx(18345.96, rel=1e-6)
    assert r.body["y_m"] == pytest.approx(0.0501272, rel=1e-5)
    assert not modelling_warnings(case, r)


def test_nothing_to_hold_is_refused():
    data = pontoon([0.0, F, 0.0])
    del data["guides"]
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "lines" and "fenders or pile guides" in str(err.value)


def test_a_body_no_contact_holds_is_refused():
    """Two bodies, guides on one: the other, free in surge, is held by nothing."""
    data = pontoon([0.0, F, 0.0])
    data["bodies"].append({"name": "q", "position": [0.0, 30.0, 0.0], "free": ["surge"]})
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "bodies[1].free" and "fender, pile guide" in str(err.value)


def test_lines_still_need_their_types():
    data = pontoon([0.0, F, 0.0])
    data["lines"] = [{"name": "L", "from": [0.0, 50.0, 0.0], "to": {"body": "p",
                                                                  "at": [0, 0, 0]},
                      "segments": [{"type": "rope", "length": 60.0}]}]
    with pytest.raises(CaseError) as err:
        load_case(copy.deepcopy(data))
    assert err.value.field == "line_types"


@pytest.mark.parametrize("command", ["envelope", "accuracy"])
def test_line_studies_refuse_a_scene_without_lines(command, capsys):
    """The studies about line tensions say why they cannot run, exit status 2."""
    from moorsolve.cli import main
    assert main([command, str(CASES / "pontoon_piles.yaml")]) == 2
    err = capsys.readouterr().err
    assert "lines:" in err and "no lines" in err and "Traceback" not in err


def test_plot_and_check_take_a_scene_without_lines(tmp_path, capsys):
    import matplotlib
    matplotlib.use("Agg")
    from moorsolve.cli import main
    assert main(["plot", str(CASES / "pontoon_piles.yaml"), "-o", str(tmp_path / "p.png")]) == 0
    assert (tmp_path / "p.png").stat().st_size > 10_000
    assert main(["check", str(CASES / "pontoon_piles.yaml")]) == 0
    out = capsys.readouterr().out
    assert "nan" not in out and "PASS" in out
