"""Mooring checks (issue 5): criteria table, each criterion passing and failing, damaged
conditions, the dock case, the CLI and the HTML report."""

from __future__ import annotations

import copy
import json
import math

import pytest

import moorsolve
from moorsolve.checks import criteria_table, criterion, run_checks
from moorsolve.cli import main
from moorsolve.errors import CaseError
from moorsolve.report.check_text import format_check_table
from moorsolve.report.text import format_table, to_json
from conftest import ROOT

DOCK = ROOT / "cases" / "floating_dock.yaml"
SMALL = ROOT / "cases" / "check_failures.yaml"


def small(**checks) -> dict:
    """Four chains on a square body pushed toward +x; ``checks`` fills the checks section."""
    legs = []
    for name, (ux, uy) in {"E": (1, 0), "N": (0, 1), "W": (-1, 0), "S": (0, -1)}.items():
        legs.append({"name": name, "anchor": [100.0 * ux, 100.0 * uy],
                     "fairlead": [10.0 * ux, 10.0 * uy, 0.0],
                     "segments": [{"type": "chain", "length": 100.0}]})
    data = {
        "name": "small",
        "environment": {"depth": 20.0},
        "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5e8, "mbl": "2000 kN"}},
        "body": {"free": ["surge", "sway"], "loads": {"force": ["100 kN", 0, 0]}},
        "legs": legs,
    }
    if checks:
        data["checks"] = checks
    return data


def check(data, **kw):
    return run_checks(moorsolve.load_case(data), **kw)


def items(report, check_name, condition="intact"):
    c = next(c for c in report.conditions if c.name == condition)
    return [i for i in c.items if i.check == check_name]


# ---- criteria data ------------------------------------------------------------------------


def test_criteria_table_has_cited_rows_for_both_standards():
    rows = criteria_table()
    assert {r.standard for r in rows} == {"api-rp-2sk", "dnv-os-e301"}
    assert all(r.source and r.verified for r in rows)
    # API RP 2SK line tension safety factors (quasi-static and dynamic, intact and damaged).
    assert criterion("api-rp-2sk", "intact").factor == 2.00
    assert criterion("api-rp-2sk", "damaged").factor == 1.43
    assert criterion("api-rp-2sk", "intact", analysis="dynamic").factor == 1.67
    assert criterion("api-rp-2sk", "damaged", analysis="dynamic").factor == 1.25
    # DNV-OS-E301: gamma_mean against 0.95 MBL, consequence classes 1 and 2.
    uls1 = criterion("dnv-os-e301", "intact", 1)
    assert (uls1.factor, uls1.gamma_dyn, uls1.capacity_factor) == (1.10, 1.50, 0.95)
    assert criterion("dnv-os-e301", "intact", 2).factor == 1.40
    assert criterion("dnv-os-e301", "damaged", 2).gamma_dyn == 1.25
    with pytest.raises(KeyError):
        criterion("api-rp-2sk", "transient")


# ---- each criterion, passing and failing -----------------------------------------------------


def test_small_case_passes_every_criterion():
    report = check(small(anchor={"type": "deadweight", "allowed_uplift": "500 kN"},
                         offset_limit="10 m", offset_limit_damaged="40 m",
                         min_grounded_length="1 m", min_grounded_length_damaged=0))
    assert report.passed, report.failures
    assert len(report.conditions) == 5
    t = items(report, "tension")
    assert all(i.passed and i.utilisation < 1 for i in t)
    # The windward leg W carries the most; its safety factor is MBL / T.
    w = max(t, key=lambda i: i.value)
    assert w.leg == "W"
    assert w.limit == pytest.approx(2000e3 / 2.0)


def test_tension_fails_below_the_safety_factor_and_damaged_uses_its_own():
    data = small()
    result = moorsolve.solve(moorsolve.load_case(data))
    T = max(result.leg("W").fairlead_tension_N, result.leg("W").anchor_tension_N)
    # MBL between 1.43 T and 2.0 T: the intact check fails on W.
    data["line_types"]["chain"]["mbl"] = 1.7 * T
    report = check(data, damaged=False)
    (w,) = [i for i in items(report, "tension") if i.leg == "W"]
    assert not w.passed and w.utilisation == pytest.approx(2.0 / 1.7, rel=1e-9)
    assert not report.passed
    # Under DNV-OS-E301 class 1 (1.10 T <= 0.95 MBL) the same line passes.
    report = check(data, damaged=False, standard="dnv-os-e301")
    (w,) = [i for i in items(report, "tension") if i.leg == "W"]
    assert w.passed and w.utilisation == pytest.approx(1.10 / (0.95 * 1.7), rel=1e-9)


def test_missing_mbl_fails_the_tension_check():
    data = small()
    del data["line_types"]["chain"]["mbl"]
    report = check(data, damaged=False)
    assert not any(i.passed for i in items(report, "tension"))
    assert "no MBL" in items(report, "tension")[0].criterion


@pytest.fixture(scope="module")
def lifting():
    """A load that lifts the windward anchor."""
    data = small()
    data["body"]["loads"]["force"] = ["600 kN", 0, 0]
    data["line_types"]["chain"]["mbl"] = "20000 kN"
    result = moorsolve.solve(moorsolve.load_case(data))
    W = result.leg("W")
    assert W.uplift and W.anchor_vertical_N > 0
    return data, W


def test_drag_anchor_fails_on_any_uplift(lifting):
    data, W = lifting
    report = check(dict(data, checks={"anchor": {"type": "drag"}}), damaged=False)
    (u,) = [i for i in items(report, "anchor uplift") if i.leg == "W"]
    assert not u.passed and u.value == pytest.approx(W.anchor_vertical_N)
    # The leeward anchors stay on the seabed: no uplift, pass.
    assert all(i.passed for i in items(report, "anchor uplift") if i.leg != "W")


def test_deadweight_anchor_allows_uplift_up_to_its_limit(lifting):
    data, W = lifting
    for factor, ok in ((1.01, True), (0.99, False)):
        anchor = {"type": "deadweight", "allowed_uplift": factor * W.anchor_vertical_N}
        report = check(dict(data, checks={"anchor": anchor}), damaged=False)
        (u,) = [i for i in items(report, "anchor uplift") if i.leg == "W"]
        assert u.passed is ok


def test_pile_anchor_checks_the_uplift_angle_and_leg_overrides_default(lifting):
    data, W = lifting
    data = copy.deepcopy(data)
    data["legs"][2]["anchor_type"] = {"type": "pile",
                                      "allowed_uplift_angle_deg": W.uplift_angle_deg - 0.1}
    report = check(dict(data, checks={"anchor": {"type": "drag"}}), damaged=False)
    (u,) = [i for i in items(report, "anchor uplift angle") if i.leg == "W"]
    assert not u.passed and u.value == pytest.approx(W.uplift_angle_deg)
    data["legs"][2]["anchor_type"]["allowed_uplift_angle_deg"] = W.uplift_angle_deg + 0.1
    report = check(dict(data, checks={"anchor": {"type": "drag"}}), damaged=False)
    assert report.passed


def test_grounded_length_and_offset_limits():
    report = check(small(min_grounded_length="40 m"), damaged=False)
    g = {i.leg: i for i in items(report, "grounded length")}
    result = report.conditions[0].result
    for leg in result.legs:
        assert g[leg.name].value == pytest.approx(leg.grounded_length_m)
        assert g[leg.name].passed is (leg.grounded_length_m >= 40.0)
    assert not g["W"].passed and g["E"].passed
    offset = report.conditions[0].offset_m
    assert offset == pytest.approx(math.hypot(result.body["x_m"], result.body["y_m"]))
    for limit, ok in ((offset * 1.01, True), (offset * 0.99, False)):
        (o,) = items(check(small(offset_limit=limit), damaged=False), "offset")
        assert o.passed is ok


def test_damaged_condition_without_equilibrium_is_a_failed_check_not_a_crash(monkeypatch):
    import moorsolve.checks.run as run_module
    from moorsolve.errors import ConvergenceError

    real_solve = run_module.solve

    def solve(scene, **kw):          # no certified equilibrium once W is gone
        if "W" not in [leg.name for leg in scene.legs]:
            raise ConvergenceError("the legs could not balance the body load",
                                   residual_N=1e5, status="Maximum_Iterations_Exceeded")
        return real_solve(scene, **kw)

    monkeypatch.setattr(run_module, "solve", solve)
    report = check(small())
    by_name = {c.name: c for c in report.conditions}
    assert by_name["intact"].solved
    lost = by_name["damaged: W removed"]
    assert not lost.solved and not lost.passed and "could not balance" in lost.reason
    assert not report.passed
    assert any("no equilibrium" in f for f in report.failures)
    assert all(c.solved for name, c in by_name.items() if name != "damaged: W removed")


def test_damaged_conditions_remove_each_leg_and_resolve():
    report = check(small())
    assert [c.name for c in report.conditions] == [
        "intact", "damaged: E removed", "damaged: N removed", "damaged: W removed",
        "damaged: S removed"]
    for c in report.conditions[1:]:
        assert [leg.name for leg in c.result.legs] == [
            n for n in ("E", "N", "W", "S") if n != c.removed]
        assert c.criterion.condition == "damaged"
    # E pulls the body toward +x with the load; without it the windward W carries less.
    intact_W = report.conditions[0].result.leg("W").fairlead_tension_N
    assert report.conditions[1].result.leg("W").fairlead_tension_N < intact_W


def test_checks_section_validation():
    for checks, field in (({"standard": "iso"}, "checks.standard"),
                          ({"bogus": 1}, "checks.bogus"),
                          ({"consequence_class": 3}, "checks.consequence_class"),
                          ({"offset_limit": -1}, "checks.offset_limit"),
                          ({"min_grounded_length": "200 m"}, "checks.min_grounded_length"),
                          ({"anchor": {"type": "vla"}}, "checks.anchor.type"),
                          ({"anchor": {"type": "deadweight"}},
                           "checks.anchor.allowed_uplift"),
                          ({"anchor": {"type": "drag", "allowed_uplift": 5}},
                           "checks.anchor.allowed_uplift"),
                          ({"damaged": "yes"}, "checks.damaged")):
        with pytest.raises(CaseError) as err:
            moorsolve.load_case(small(**checks))
        assert err.value.field == field


# ---- the shipped cases -------------------------------------------------------------------


def test_dock_intact_and_12_damaged_conditions():
    report = run_checks(moorsolve.load_case(DOCK))
    assert len(report.conditions) == 13 and all(c.solved for c in report.conditions)
    intact = report.conditions[0]
    assert intact.passed
    # Intact worst chain L3 at about 1511 kN against the U3 catalogue MBL 4827 kN.
    worst = intact.worst()
    assert worst.leg == "L3" and 4827e3 / worst.value > 3.0
    # Breaking L4 overloads L3's sinker beyond the case's 281 kN: the honest failure.
    assert [c.name for c in report.conditions if not c.passed] == ["damaged: L4 removed"]


def test_small_failing_case_file_fails_each_criterion():
    report = run_checks(moorsolve.load_case(SMALL))
    failed = {(i.check, i.condition) for c in report.conditions for i in c.items
              if not i.passed}
    checks_failed = {name for name, _ in failed}
    assert {"tension", "anchor uplift", "grounded length", "offset"} <= checks_failed
    # Without W only E holds the pontoon: either no equilibrium is found or the pontoon
    # drifts past E's anchor (a true but useless equilibrium): failed either way.
    lost = next(c for c in report.conditions if c.removed == "W")
    assert not lost.passed
    assert not lost.solved or lost.offset_m > 90.0


# ---- command line and report ---------------------------------------------------------------


def test_cli_check_exit_status_json_and_report(tmp_path, capsys):
    out = tmp_path / "dock.html"
    assert main(["check", str(DOCK), "--report", str(out)]) == 1
    text = capsys.readouterr().out
    assert "damaged: L12 removed" in text and "FAIL" in text
    html = out.read_text()
    for section in ("1. Case", "2. Plan, elevation and 3-D view", "3. Tension utilisation",
                    "4. Checks", "5. Criteria", "API RP 2SK"):
        assert section in html
    assert html.count("data:image/png;base64,") == 3
    assert not [p for p in tmp_path.iterdir() if p != out]       # no temporary left
    assert main(["check", str(DOCK), "--json", "--no-damaged"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["passed"] and len(data["conditions"]) == 1


def test_cli_check_bad_input_is_status_2_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "r.html"
    assert main(["check", str(DOCK), "--report", str(tmp_path / "nope" / "r.html")]) == 2
    assert main(["check", str(DOCK), "--report", str(tmp_path / "r.txt")]) == 2
    assert main(["check", str(tmp_path / "missing.yaml"), "--report", str(out)]) == 2
    with pytest.raises(SystemExit) as exc:
        main(["check", str(DOCK), "--standard", "iso-19901"])
    assert exc.value.code == 2
    assert not out.exists()
    capsys.readouterr()


def test_utilisation_has_one_meaning_and_t_over_mbl_is_named_apart():
    """``utilisation`` is the design tension over the standard's allowable tension (the
    check's); solve reports the tension over MBL as ``t_over_mbl`` (T/MBL), never as a
    utilisation. For one leg: utilisation = T/MBL x factor / capacity_factor."""
    case = moorsolve.load_case(small())
    result = moorsolve.solve(case)
    legs = json.loads(to_json(result, profiles=False))["legs"]
    assert all("utilisation" not in leg and "t_over_mbl" in leg for leg in legs)
    assert "T/MBL" in format_table(result)
    for standard, factor, capacity in (("api-rp-2sk", 2.00, 1.0), ("dnv-os-e301", 1.10, 0.95)):
        report = run_checks(case, standard=standard, damaged=False)
        for item in items(report, "tension"):
            leg = result.leg(item.leg)
            assert item.utilisation == pytest.approx(leg.t_over_mbl * factor / capacity,
                                                     rel=1e-9)
        assert "util = tension / the standard's allowable tension" in \
            format_check_table(report)
    with pytest.warns(DeprecationWarning, match="t_over_mbl"):
        assert result.legs[0].utilisation == result.legs[0].t_over_mbl


def test_checks_of_a_scene_without_legs():
    """A berth of fenders and piles alone takes a checks block; a grounded-length limit there
    is refused by name instead of failing on an empty list."""
    import yaml
    raw = yaml.safe_load(open(ROOT / "cases" / "pontoon_piles.yaml"))
    raw["checks"] = {"standard": "api-rp-2sk"}
    assert moorsolve.load_case(raw).checks.standard == "api-rp-2sk"
    raw["checks"] = {"min_grounded_length": 5}
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(raw)
    assert err.value.field == "checks.min_grounded_length"
    assert "no mooring legs" in str(err.value)
