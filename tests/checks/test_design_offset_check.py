"""``moorsolve check`` with a sea state and ``method: quasi_static``: API RP 2SK's quasi-static method (3rd ed., 2005,
section 6.4.2 design offset, section 7.4 safety factors 2.00 intact / 1.43 damaged), each
body held at its design offset and the lines re-solved; without a sea state the check covers
the mean tension only and says so."""

from __future__ import annotations

import dataclasses
import json
import math
import re

import numpy as np
import pytest

import moorsolve
from moorsolve.checks import run_checks
from moorsolve.checks.design_offset import MEAN_ONLY
from moorsolve.checks.design_offset import METHOD_DESIGN_OFFSET as _SHOWN

from moorsolve.cli import main
from moorsolve.model.edit import without_line
from conftest import ROOT

BUOY = ROOT / "cases" / "buoy_sea.yaml"
#: The chain's MBL in the case file [N].
MBL = 1.5e6
METHOD_DESIGN_OFFSET = _SHOWN["api-rp-2sk"]


@pytest.fixture(scope="module")
def buoy():
    return moorsolve.load_case(BUOY)


@pytest.fixture(scope="module")
def report(buoy):
    return run_checks(buoy, method="quasi_static")


def _held_tensions(scene) -> tuple:
    """An independent design-offset solve: the motions about the scene's equilibrium, the
    buoy's mean pose moved horizontally along its mean offset to the design offset, the
    buoy replaced by a body held there (no free DOF) and the case solved."""
    m = moorsolve.motions(scene)
    mean = m.result.body_named("buoy")
    design = m.body("buoy").design_offset_m
    off = np.array([mean["offset"]["x_m"], mean["offset"]["y_m"]])
    u = off / np.linalg.norm(off)
    body = scene.body_named("buoy")
    ref = np.array(body.position[:2])          # the case pose (water level 0)
    xy = ref + design * u
    held = dataclasses.replace(body, free=(), position=(xy[0], xy[1], mean["z_m"]),
                               orientation_deg=(mean["roll_deg"], mean["pitch_deg"],
                                                mean["yaw_deg"]))
    case = dataclasses.replace(scene, bodies=(held,))
    res = moorsolve.solve(case, allow_overload=True)
    return design, {lr.name: max(lr.fairlead_tension_N, lr.anchor_tension_N)
                    for lr in res.legs}, m.result


@pytest.mark.parametrize("removed", [None, "L3"])
def test_tension_at_design_offset_equals_an_independent_held_solve(buoy, report, removed):
    scene = buoy if removed is None else without_line(buoy, removed)
    design, tensions, mean = _held_tensions(scene)
    cond = report.conditions[0] if removed is None else next(
        c for c in report.conditions if c.removed == removed)
    assert cond.method == "design offset"
    assert cond.design_offset_m["buoy"] == pytest.approx(design, rel=1e-9)
    # The mean offset is part of the design offset, and the dynamic part adds to it.
    mean_offset = math.hypot(mean.body_named("buoy")["offset"]["x_m"],
                             mean.body_named("buoy")["offset"]["y_m"])
    assert design > mean_offset
    # The body is held at the design offset from the case pose (origin), along the mean
    # offset, with heave and the rotations at their mean values.
    held = cond.held.body_named("buoy")
    m = mean.body_named("buoy")
    assert math.hypot(held["x_m"], held["y_m"]) == pytest.approx(design, rel=1e-12)
    cross = held["x_m"] * m["offset"]["y_m"] - held["y_m"] * m["offset"]["x_m"]
    assert abs(cross) <= 1e-12 * design * mean_offset
    assert held["x_m"] * m["offset"]["x_m"] + held["y_m"] * m["offset"]["y_m"] > 0
    for key in ("z_m", "roll_deg", "pitch_deg", "yaw_deg"):
        assert held[key] == pytest.approx(m[key], rel=1e-12, abs=1e-12)
    lines = {line["leg"]: line for line in cond.lines}
    assert set(lines) == set(tensions)
    for name, t in tensions.items():
        lr = next(lr for lr in mean.legs if lr.name == name)
        end = lines[name]["end"]
        t_mean = lr.fairlead_tension_N if end == "fairlead" else lr.anchor_tension_N
        assert lines[name]["t_mean_N"] == pytest.approx(t_mean, rel=1e-9)
        # At the design offset, or at its mean where the line slackens there.
        assert lines[name]["t_max_N"] == pytest.approx(max(t, t_mean), rel=1e-6)
        item = next(i for i in cond.items if i.check == "tension" and i.leg == name)
        assert item.value == pytest.approx(max(t, t_mean), rel=1e-6)
    offset_item = next(i for i in cond.items if i.check == "offset") \
        if any(i.check == "offset" for i in cond.items) else None
    assert offset_item is None or offset_item.value == pytest.approx(design)


def test_intact_windward_line_tightens_at_the_design_offset(report):
    # The sea runs toward 20 deg: the line anchored against it (L3, anchor at -120 deg)
    # tightens, the one it runs toward (L1, anchor at 0 deg) slackens.
    lines = {line["leg"]: line for line in report.conditions[0].lines}
    assert lines["L3"]["t_max_N"] > lines["L3"]["t_mean_N"]
    # L1 slackens at the design offset: it is checked at its mean tension, no less.
    assert lines["L1"]["t_max_N"] == lines["L1"]["t_mean_N"]
    assert lines["L1"]["t_dyn_N"] == 0.0


def test_utilisation_is_the_tension_over_mbl_by_the_safety_factor(report):
    for cond in report.conditions:
        sf = 2.00 if cond.kind == "intact" else 1.43
        for line in cond.lines:
            T = line["t_max_N"]
            assert line["utilisation"] == pytest.approx(T / (MBL / sf), rel=1e-9)
            assert line["design_N"] == pytest.approx(sf * T, rel=1e-12)
            assert line["capacity_N"] == MBL
            assert line["t_dyn_N"] == pytest.approx(T - line["t_mean_N"], rel=1e-12, abs=1e-9)
            item = next(i for i in cond.items if i.check == "tension" and i.leg == line["leg"])
            assert item.utilisation == pytest.approx(T / (MBL / sf), rel=1e-9)
            assert "at the design offset" in item.criterion
    assert report.method == METHOD_DESIGN_OFFSET


def _strip_times(text: str) -> str:
    return re.sub(r"\(\d+\.\d+ s\)", "(t s)", text)


def _variant(tmp_path, name: str, drop) -> str:
    text = BUOY.read_text()
    lines = text.splitlines()
    start = lines.index("  waves:")
    block = lines[start:start + 6]
    assert block[2].strip().startswith("tp:")
    keep = [line for line in block if not drop(line)]
    out = tmp_path / name
    out.write_text("\n".join(lines[:start] + keep + lines[start + 6:]) + "\n")
    return str(out)


def test_without_a_period_the_check_is_the_mean_only_one(tmp_path, capsys):
    no_tp = _variant(tmp_path, "no_tp.yaml", lambda l: l.strip().split(":")[0] in
                     ("tp", "spectrum"))
    no_sea = _variant(tmp_path, "no_sea.yaml", lambda l: True)
    outputs = {}
    for path in (no_tp, no_sea):
        assert main(["check", path]) == 0
        text = capsys.readouterr().out
        assert main(["check", path, "--json"]) == 0
        data = json.loads(capsys.readouterr().out)
        data.pop("time_s")
        outputs[path] = (_strip_times(text), data)
    assert outputs[no_tp] == outputs[no_sea]
    text, data = outputs[no_tp]
    assert f"method       {MEAN_ONLY}" in text
    assert data["method"] == MEAN_ONLY
    assert "design offset" not in text
    # The figures are the static solve's: the larger end tension, the factors on it.
    case = moorsolve.load_case(no_tp)
    res = moorsolve.solve(case)
    intact = data["conditions"][0]
    assert intact["method"] == "mean"
    for lr in res.legs:
        T = max(lr.fairlead_tension_N, lr.anchor_tension_N)
        line = next(x for x in intact["lines"] if x["leg"] == lr.name)
        assert line["t_max_N"] == pytest.approx(T, rel=1e-9)
        assert line["t_dyn_N"] == 0.0
        assert line["utilisation"] == pytest.approx(T / (MBL / 2.00), rel=1e-9)


def test_cli_text_and_json_carry_the_method(capsys, tmp_path):
    assert main(["check", str(BUOY), "--no-damaged", "--method", "quasi_static"]) == 0
    text = capsys.readouterr().out
    assert f"method       {METHOD_DESIGN_OFFSET}" in text
    # Every line's figures in the per-line table, as the JSON has them.
    report = run_checks(moorsolve.load_case(BUOY), damaged=False, method="quasi_static")
    for line in report.conditions[0].lines:
        row = (f"{line['leg']:>6}{line['end']:>9}{line['t_mean_N'] / 1e3:11.1f}"
               f"{line['t_dyn_N'] / 1e3:10.1f}{line['t_max_N'] / 1e3:10.1f}"
               f"{line['design_N'] / 1e3:11.1f}{line['capacity_N'] / 1e3:13.1f}"
               f"{line['utilisation']:7.3f}")
        assert row in text
    assert f"design offset: buoy {report.conditions[0].design_offset_m['buoy']:.2f} m" in text
    assert main(["check", str(BUOY), "--no-damaged", "--json", "--method", "quasi_static"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["method"] == METHOD_DESIGN_OFFSET
    intact = data["conditions"][0]
    assert intact["method"] == "design offset"
    assert intact["design_offset_m"]["buoy"] > 0
    for line in intact["lines"]:
        assert {"t_mean_N", "t_max_N", "design_N", "capacity_N", "utilisation"} <= set(line)
    html = tmp_path / "r.html"
    assert main(["check", str(BUOY), "--no-damaged", "--report", str(html), "--method",
                 "quasi_static"]) == 0
    capsys.readouterr()
    assert METHOD_DESIGN_OFFSET in html.read_text()


def test_dnv_quasi_static_factors_the_tension_at_the_design_offset(buoy, report):
    # DNV-OS-E301 ULS CC1 with the quasi-static line tension: T_dyn = T(design offset) -
    # T_mean, 1.10 T_mean + 1.50 T_dyn <= 0.95 MBS, on the same held solve as API's.
    dnv = run_checks(buoy, standard="dnv-os-e301", damaged=False, method="quasi_static")
    assert dnv.conditions[0].method == "design offset"
    api = {x["leg"]: x for x in report.conditions[0].lines}
    for line in dnv.conditions[0].lines:
        ref = api[line["leg"]]
        assert line["t_max_N"] == pytest.approx(ref["t_max_N"], rel=1e-9)
        t_dyn = ref["t_max_N"] - ref["t_mean_N"]
        assert line["design_N"] == pytest.approx(1.10 * ref["t_mean_N"] + 1.50 * t_dyn,
                                                 rel=1e-9)
        assert line["utilisation"] == pytest.approx(line["design_N"] / (0.95 * MBL), rel=1e-12)


def test_offset_uplift_and_grounded_length_are_checked_at_the_design_offset(buoy):
    # A 2 m offset limit: the mean offset (under 0.1 m) passes it, the design offset
    # (about 2.5 m) does not; grounded length and uplift from the held solve.
    from moorsolve.model import Checks
    case = dataclasses.replace(buoy, checks=Checks(offset_limit=2.0, min_grounded_length=1.0,
                                                   damaged=False, method="quasi_static"))
    report = run_checks(case)
    cond = report.conditions[0]
    design, _, mean = _held_tensions(case)
    mean_offset = math.hypot(mean.body_named("buoy")["offset"]["x_m"],
                             mean.body_named("buoy")["offset"]["y_m"])
    assert mean_offset < 2.0 < design
    offset = next(i for i in cond.items if i.check == "offset")
    assert offset.value == pytest.approx(design, rel=1e-12)
    assert not offset.passed and not report.passed
    assert "design offset" in offset.criterion
    held = {lr.name: lr for lr in cond.held.legs}
    for item in cond.items:
        if item.check == "grounded length":
            assert item.value == pytest.approx(held[item.leg].grounded_length_m, rel=1e-12)
        if item.check == "anchor uplift":
            assert item.value == (held[item.leg].anchor_vertical_N
                                  if held[item.leg].anchor_vertical_N > max(
                                      1e-6 * held[item.leg].anchor_tension_N, 1.0) else 0.0)
    # The slackening line (L1) has more chain on the seabed at the offset than at the mean.
    mean_legs = {lr.name: lr for lr in mean.legs}
    assert held["L1"].grounded_length_m > mean_legs["L1"].grounded_length_m
    assert held["L3"].grounded_length_m < mean_legs["L3"].grounded_length_m


def test_a_free_floating_body_without_hydrodynamics_in_a_sea_is_refused(tmp_path, capsys):
    import yaml
    data = yaml.safe_load(BUOY.read_text())
    del data["bodies"][0]["hydrodynamics"]
    path = tmp_path / "no_hydro.yaml"
    path.write_text(yaml.safe_dump(data))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "bodies[0].hydrodynamics" in err and "Traceback" not in err


def test_a_damaged_condition_whose_motions_fail_is_a_failed_condition(buoy, monkeypatch):
    from moorsolve.checks import run as run_module
    from moorsolve.errors import CaseError
    real = run_module.design_offset_solve

    def refuse_damaged(result, *, tol=None):
        if len(result.legs) < 3:
            raise CaseError("bodies[0].damping", "an undamped slow-drift mode")
        return real(result, tol=tol)

    monkeypatch.setattr(run_module, "design_offset_solve", refuse_damaged)
    report = run_checks(buoy, method="quasi_static")
    assert report.conditions[0].passed
    for cond in report.conditions[1:]:
        assert not cond.solved and not cond.passed
        assert "an undamped slow-drift mode" in cond.reason
    assert not report.passed
