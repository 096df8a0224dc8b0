"""The independent audit of every result, and the warnings nobody may miss (issue 20).

The audit (``moorsolve.audit``) recomputes from the reported profile, end forces and
loads alone. These tests feed it the defects issue 20 found (a buoyant line drawn in the
air, a folded line's profile ending at the wrong point, an end force not along its line,
unbalanced body forces) and check each is an error, not a note; and that the warnings reach
the text, the JSON with and without profiles, and the check report.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

import moorsolve

from moorsolve import ConvergenceError, load_case, solve
from moorsolve.cli import main
from moorsolve.report.text import format_table
from moorsolve.solve.result import leg_results
from moorsolve.audit import AuditFailure, audit
from moorsolve.solve.result.profile_batch import ProfileBatch
from conftest import ROOT

CASES = ROOT / "cases"


def one_leg(w, anchor, fairlead, L, ea=1e8, depth=50.0, **line):
    return load_case({
        "environment": {"depth": depth},
        "line_types": {"line": {"weight_in_water": w, "ea": ea, **line}},
        "legs": [{"name": "A", "anchor": anchor, "fairlead": fairlead,
                  "segments": [{"type": "line", "length": L}]}]})


def with_profile(result, leg_index=0, **changes):
    legs = list(result.legs)
    profile = dict(legs[leg_index].profile)
    for key, value in changes.items():
        profile[key] = value(np.asarray(profile[key], float)) if callable(value) else value
    legs[leg_index] = dataclasses.replace(legs[leg_index], profile=profile)
    return dataclasses.replace(result, legs=legs)


@pytest.mark.parametrize("name", sorted(p.name for p in CASES.glob("*.yaml")))
def test_every_shipped_case_passes_the_audit(name):
    case = load_case(CASES / name)
    try:
        result = solve(case)
    except ConvergenceError as exc:
        # cases/check_failures.yaml is built to fail the checks, not the solve.
        pytest.fail(f"{name}: {exc}")
    assert audit(result, case) == [leg.name for leg in result.legs]


def test_a_buoyant_line_drawn_in_the_air_fails():
    """Issue 20: a buoyant line's profile several metres in the air was certified."""
    case = one_leg(-100.0, [0, 0], [100.0, 0, 0.0], 120.0)
    result = solve(case)
    assert result.legs[0].floating_length_m > 0
    lifted = with_profile(result, z_m=lambda z: np.where(z > -30, z + 20.0 * (z + 30) / 30, z))
    with pytest.raises(AuditFailure, match="above the surface"):
        audit(lifted, case)


def test_the_old_folded_profile_fails():
    """Issue 20: a folded line (H = 0) was drawn through the seabed and ended elsewhere.

    The old formula multiplied the fold's height by sgn(T_v); the audit sees the end missed.
    """
    case = one_leg(100.0, [0, 0, -30.0], [0, 0, -10.0], 30.0)
    result = solve(case)
    leg = result.legs[0]
    assert leg.horizontal_tension_N == pytest.approx(0.0, abs=1e-6)
    # The fold: 25 m down from the fairlead, 5 m down from the anchor (with stretch).
    assert np.min(leg.profile["z_m"]) == pytest.approx(-35.0, abs=1e-3)
    assert leg.profile["z_m"][-1] == pytest.approx(-10.0, abs=1e-9)
    s = np.asarray(leg.profile["s_m"])
    Tv = leg.anchor_vertical_N + 100.0 * s
    old_z = -30.0 + (np.abs(Tv) - abs(leg.anchor_vertical_N)) / 100.0 * np.sign(Tv)
    with pytest.raises(AuditFailure, match="ends .* from the fairlead"):
        audit(with_profile(result, z_m=old_z), case)


def test_a_discontinuous_profile_fails():
    case = one_leg(100.0, [0, 0], [80.0, 0, 0.0], 100.0)
    result = solve(case)
    n = len(result.legs[0].profile["x_m"])
    jump = np.zeros(n)
    jump[n // 2:] = 3.0
    # Shifted along the chord from the middle on, and back at the end: a gap, ends kept.
    jump[-1] = 0.0
    with pytest.raises(AuditFailure, match="not continuous"):
        audit(with_profile(result, x_m=lambda x: x + jump), case)


def test_a_profile_through_the_seabed_fails():
    case = one_leg(100.0, [0, 0], [80.0, 0, 0.0], 100.0)
    result = solve(case)
    sag = -2.0 * np.sin(np.linspace(0, np.pi, len(result.legs[0].profile["z_m"])))
    with pytest.raises(AuditFailure, match="below the seabed"):
        audit(with_profile(result, z_m=lambda z: z + sag), case)


def test_an_end_force_off_the_line_fails():
    case = one_leg(100.0, [0, 0], [80.0, 0, 0.0], 100.0)
    result = solve(case)
    leg = result.legs[0]
    wrong = dataclasses.replace(leg, fairlead_vertical_N=0.5 * leg.fairlead_vertical_N,
                                fairlead_tension_N=np.hypot(leg.horizontal_tension_N,
                                                            0.5 * leg.fairlead_vertical_N))
    wrong = dataclasses.replace(wrong, profile=dict(
        wrong.profile, tension_N=np.concatenate([leg.profile["tension_N"][:-1],
                                                 [wrong.fairlead_tension_N]])))
    with pytest.raises(AuditFailure, match="points .* away from the line"):
        audit(dataclasses.replace(result, legs=[wrong]), case)


def test_a_tension_that_does_not_carry_the_weight_fails():
    """The vertical forces are checked against the weight the profile says hangs."""
    case = one_leg(-100.0, [0, 0], [40.0, 0, -20.0], 60.0)
    result = solve(case)
    leg = result.legs[0]
    assert leg.floating_length_m == 0.0
    wrong = dataclasses.replace(leg, anchor_vertical_N=leg.anchor_vertical_N * 1.01)
    with pytest.raises(AuditFailure, match="weight"):
        audit(dataclasses.replace(result, legs=[wrong]), case)


def test_an_unbalanced_body_fails():
    case = load_case(CASES / "buoy_vida.yaml")
    result = solve(case)
    loads = {k: [v[0] + 1e3, v[1], v[2]] for k, v in result.loads.items()}
    with pytest.raises(AuditFailure, match="not in balance in surge"):
        audit(dataclasses.replace(result, loads=loads), case)


def test_solve_raises_when_the_reported_profile_is_wrong(monkeypatch):
    """An audit failure inside ``solve`` is a ConvergenceError with the reason."""
    real = leg_results.leg_profile

    def broken(*args, **kwargs):
        prof = real(*args, **kwargs)
        return dict(prof, z=prof["z"] + 1.0)
    monkeypatch.setattr(leg_results, "leg_profile", broken)
    # Each line drawn by its own (broken) drawing, not with the others (profile_batch).
    monkeypatch.setattr(ProfileBatch, "add", lambda self, params, fallback, finish: fallback)
    case = one_leg(100.0, [0, 0], [80.0, 0, 0.0], 100.0)
    message = ("the solution certified but leg A's profile drawn from it fails the "
               "independent audit: the profile starts 1 m from end A")
    with pytest.raises(ConvergenceError, match=message):
        solve(case, audit="full")
    # Audited in closed form, the solve draws no profile; the profile, when it is read, is
    # checked against the reported ends and tensions.
    result = solve(case)
    with pytest.raises(AuditFailure, match=message) as caught:
        result.legs[0].profile["z_m"]
    assert "a certified equilibrium" in str(caught.value)


# ---- warnings -----------------------------------------------------------------------------


def deep_sealed_cable():
    """Sukhanov's situation: a sealed cable hanging deep, its wall compressive at depth.

    3000 m of water, a cable of 0.2 m with 60 N/m in water hanging from a surface buoy
    nearly straight down: the hydrostatic term rho g A d = 1025 * 9.80665 * 0.0314 * 3000
    = 947 kN exceeds the effective tension at depth (about 60 N/m times the height).
    """
    return one_leg(60.0, [0, 0], [500.0, 0, 0.0], 3300.0, ea=1e9, depth=3000.0,
                   diameter=0.2, sealed=True)


def test_wall_compression_is_a_warning_everywhere():
    case = deep_sealed_cable()
    result = solve(case)
    codes = [w["code"] for w in result.warnings]
    assert "wall_compression" in codes
    data = result.to_dict(profiles=False)
    assert "profile" not in data["legs"][0]
    assert any(w["code"] == "wall_compression" for w in data["warnings"])
    assert "WARNING: leg A: the wall tension" in format_table(result)


def test_warnings_in_the_cli_with_and_without_profiles(tmp_path, capsys):
    path = tmp_path / "hose.yaml"
    path.write_text(json.dumps({
        "environment": {"depth": 50},
        "line_types": {"hose": {"weight_in_water": -100.0, "ea": 1e8}},
        "legs": [{"name": "H1", "anchor": [0, 0], "fairlead": [100, 0, 0],
                  "segments": [{"type": "hose", "length": 120}]}]}))
    assert main(["solve", str(path), "--json", "--no-profiles"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [w["code"] for w in data["warnings"]] == ["floating"]
    assert data["legs"][0]["floating_length_m"] > 0
    assert main(["solve", str(path)]) == 0
    out = capsys.readouterr().out
    assert "WARNING: leg H1:" in out and "floats on the surface" in out


def test_warnings_in_the_check_report(tmp_path, capsys):
    path = tmp_path / "hose.yaml"
    path.write_text(json.dumps({
        "environment": {"depth": 50},
        "line_types": {"hose": {"weight_in_water": -100.0, "ea": 1e8, "mbl": 1e6}},
        "legs": [{"name": "H1", "anchor": [0, 0], "fairlead": [100, 0, 0],
                  "segments": [{"type": "hose", "length": 120}]}]}))
    main(["check", str(path), "--json", "--no-damaged"])
    data = json.loads(capsys.readouterr().out)
    assert any(w["code"] == "floating" for w in data["warnings"])
    main(["check", str(path), "--no-damaged"])
    assert "WARNING: intact: leg H1:" in capsys.readouterr().out


def test_audit_checks_every_free_dof_of_a_six_dof_body_with_its_hydrostatics():
    """The OC3 spar: the audit recomputes weight, linear buoyancy and springs itself; a
    reported fairlead force moved down by 1 kN (or a buoyancy the case does not have) shows
    as an imbalance in heave."""
    import dataclasses as dc

    from conftest import CASES
    from moorsolve.audit import audit_findings
    case = moorsolve.load_case(CASES / "oc3_spar.yaml")
    result = moorsolve.solve(case)
    assert audit_findings(result, case) == []
    leg = result.legs[0]
    wrong = dc.replace(leg, fairlead_force=tuple(leg.fairlead_force[:2])
                       + (leg.fairlead_force[2] - 1e3,))
    bad = dc.replace(result, legs=[wrong] + list(result.legs[1:]))
    found = audit_findings(bad, case)
    assert any("heave" in f for f in found)
    lighter = dc.replace(case.bodies[0], mass=case.bodies[0].mass * 0.999)
    assert any("heave" in f for f in audit_findings(
        result, dc.replace(case, bodies=(lighter,))))


def test_audit_integrates_hull_members_by_quadrature():
    """A floating box solved with the exact (closed-form) buoyancy passes the audit, which
    integrates the submerged volume by Gauss quadrature instead; heeled as well."""
    from moorsolve.audit import audit_findings
    data = {
        "environment": {"depth": 100.0},
        "line_types": {"rope": {"weight_in_water": 0.0, "ea": 1e8}},
        "bodies": [{"name": "barge", "mass": 1.0e6, "free": ["heave", "roll", "pitch"],
                    "centre_of_gravity": [0, 0, -1.0],
                    "hull": [{"shape": "box", "length": 40.0, "width": 10.0,
                              "bottom": -5.0, "top": 3.0},
                             {"shape": "cylinder", "radius": 2.0, "bottom": -5.0,
                              "top": 3.0, "centre": [15.0, 0.0]}],
                    "loads": {"force": [0, 0, 0, 2.0e6, 5.0e5, 0]}}],
        "lines": [{"name": "L", "from": [0, 0, -100], "to": {"body": "barge",
                                                              "at": [0, 0, -5]},
                   "segments": [{"type": "rope", "length": 200.0}]}]}
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case)
    assert abs(result.bodies[0]["roll_deg"]) > 0.5
    assert audit_findings(result, case) == []
