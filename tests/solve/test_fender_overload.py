"""A fender past its rated deflection is an overload, as a line past its MBL is; past its
full compression (its height) the hull bears on the wall, and never passes into it.

Hand statics: a body whose origin is on the wall x = 0 (outward normal +x), two linear
fenders of stiffness k on its face at (0, +-D, 0), free in surge, pushed onto the wall by
F. Each fender takes F/2 and is compressed F / (2 k) while that is under its height h.
Past it the hull bears on the wall through the fully compressed fender with the stiffness
K = HULL_STIFFNESS: with the hull's give d, the fender carries k (h + d) and the hull
K d, so d = (F/2 - k h) / (k + K).
"""

from __future__ import annotations

import copy
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve import CaseError, ConvergenceError, load_case
from moorsolve.cli import main
from moorsolve.constants import HULL_STIFFNESS
from moorsolve.audit.bodies import wall_findings

CASES = Path(__file__).resolve().parents[2] / "cases"
SOLVERS = ("ipopt", "newton")
k = 2.0e6          # [N/m] fender stiffness
D = 10.0           # [m] fenders at y = +-D
RATED = 0.30       # [m]
HEIGHT = 0.60      # [m] full compression


def berth(F: float, *, height=HEIGHT, rated=RATED) -> dict:
    def fender(name, y):
        out = {"name": name, "body": "b", "at": [0.0, y, 0.0], "wall": "quay",
               "reaction": {"stiffness": k}, "rated_deflection": rated}
        if height is not None:
            out["height"] = height
        return out
    return {
        "name": "fender overload",
        "environment": {"depth": 15.0},
        "bodies": [{"name": "b", "free": ["surge"], "loads": {"force": [-F, 0.0, 0.0]}}],
        "walls": [{"name": "quay", "point": [0, 0, 0], "normal": [1, 0, 0]}],
        "fenders": [fender("F1", D), fender("F2", -D)],
    }


def solve(data, solver, **kw):
    return moorsolve.solve(load_case(data), solver=solver, tol=1e-12, **kw)


@pytest.mark.parametrize("solver", SOLVERS)
def test_within_the_rating_nothing_is_said(solver):
    F = 2 * k * 0.2                      # 0.2 m each, under the 0.3 m rating
    r = solve(berth(F), solver)
    for f in r.fenders:
        assert f["compression_m"] == pytest.approx(0.2, rel=1e-9)
        assert not f["overloaded"] and not f["hull_bears"] and f["hull_reaction_N"] == 0.0
        assert f["hull_gap_m"] == pytest.approx(HEIGHT - 0.2, rel=1e-9)
        assert f["height_m"] == HEIGHT


@pytest.mark.parametrize("solver", SOLVERS)
def test_past_the_rating_is_an_overload(solver):
    F = 2 * k * 0.4                      # 0.4 m each: past the rating, short of the height
    with pytest.raises(ConvergenceError) as err:
        solve(berth(F), solver)
    reason = err.value.reason
    assert reason.startswith("overload: ") and "allow_overload" in reason
    assert "fender F1 is compressed 0.400 m, past its rated deflection 0.300 m" in reason
    assert "hull" not in reason.split("(the mooring")[0]
    r = solve(berth(F), solver, allow_overload=True)
    for f in r.fenders:
        assert f["compression_m"] == pytest.approx(0.4, rel=1e-9)
        assert f["overloaded"] and not f["hull_bears"]
        assert f["utilisation"] == pytest.approx(0.4 / RATED, rel=1e-9)


@pytest.mark.parametrize("solver", SOLVERS)
def test_past_full_compression_the_hull_bears_on_the_wall(solver):
    F = 6.0e6                            # each fender would need 1.5 m: far past its 0.6 m
    give = (F / 2 - k * HEIGHT) / (k + HULL_STIFFNESS)
    r = solve(berth(F), solver, allow_overload=True)
    assert r.body["x_m"] == pytest.approx(-(HEIGHT + give), rel=1e-9)
    for f in r.fenders:
        assert f["overloaded"] and f["hull_bears"]
        assert f["compression_m"] == pytest.approx(HEIGHT + give, rel=1e-9)
        assert f["reaction_N"] == pytest.approx(k * (HEIGHT + give), rel=1e-8)
        assert f["hull_reaction_N"] == pytest.approx(HULL_STIFFNESS * give, rel=1e-6)
        assert f["reaction_N"] + f["hull_reaction_N"] == pytest.approx(F / 2, rel=1e-9)
    assert give < 2e-3                   # 1 mm per MN: never a body inside the quay
    assert wall_findings(r, r.case) == []
    with pytest.raises(ConvergenceError) as err:
        solve(berth(F), solver)
    assert "the hull of b bears on quay behind it" in err.value.reason


def test_without_a_height_the_hull_is_not_modelled():
    """A body-mounted fender of unknown height: past its rating it is still an overload;
    no hull is placed behind it."""
    r = solve(berth(2 * k * 0.4, height=None), "newton", allow_overload=True)
    for f in r.fenders:
        assert f["overloaded"] and f["height_m"] is None and f["hull_gap_m"] is None


def test_the_audit_finds_a_body_inside_the_wall():
    r = solve(berth(6.0e6), "newton", allow_overload=True)
    body = dict(r.bodies[0], x_m=r.bodies[0]["x_m"] - 0.05)     # 5 cm further in
    moved = dataclasses.replace(r, bodies=(body,))
    found = wall_findings(moved, r.case)
    assert len(found) == 2 and "inside quay" in found[0]


def _soft_dock(tmp_path) -> Path:
    """The shipped dock at its quay with soft fenders rated 0.30 m (the quay-mounted faces
    are 1.6 m out from the wall: their height), under its storm onto the quay."""
    data = yaml.safe_load((CASES / "dock_quay.yaml").read_text())
    for f in data["fenders"]:
        f["reaction"] = {"stiffness": 1.0e5}
        f["rated_deflection"] = 0.30
    path = tmp_path / "soft_dock.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def test_the_soft_dock_is_refused_and_never_inside_the_quay(tmp_path, capsys):
    path = _soft_dock(tmp_path)
    assert main(["solve", str(path), "--solver", "newton"]) == 1
    err = capsys.readouterr().err
    assert "fender F1 is compressed 1.600 m, past its rated deflection 0.300 m" in err
    assert "the hull of dock bears on quay" in err
    assert main(["solve", str(path), "--solver", "newton", "--allow-overload"]) == 0
    out = capsys.readouterr().out
    assert "OVER RATED" in out and "HULL ON quay" in out and "OVERLOAD: fender F1" in out
    assert main(["solve", str(path), "--solver", "newton", "--allow-overload", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for f in data["fenders"]:
        assert f["overloaded"] and f["hull_bears"] and f["height_m"] == pytest.approx(1.6)
    # The dock's quay side (body y = +15) stops at the wall (y = 0, the quay at y > 0),
    # pressed into it by no more than its give, about 0.1 mm under about 85 kN a fender.
    y = data["bodies"][0]["y_m"] + 15.0
    gives = [f["hull_reaction_N"] / HULL_STIFFNESS for f in data["fenders"]]
    assert 0.0 < y <= max(gives) * (1 + 1e-6) and max(gives) < 1e-4
    newton = moorsolve.solve(load_case(path), solver="newton", allow_overload=True)
    ipopt = moorsolve.solve(load_case(path), solver="ipopt", allow_overload=True)
    a = np.array([f["hull_reaction_N"] for f in newton.fenders])
    b = np.array([f["hull_reaction_N"] for f in ipopt.fenders])
    assert np.allclose(a, b, rtol=1e-3)           # a determinate share, either solver
    assert a.sum() == pytest.approx(b.sum(), rel=1e-6)


def test_the_check_names_the_hull(tmp_path):
    from moorsolve.checks.run import run_checks
    report = run_checks(load_case(_soft_dock(tmp_path)), damaged=False)
    assert not report.passed
    fenders = [f for f in report.failures if "fender compression" in f]
    assert len(fenders) == 4 and "the hull bears on quay" in fenders[0]


def test_a_sweep_marks_the_overloaded_points():
    case = load_case(berth(1.0))
    loads = [[-F, 0.0, 0.0] for F in (2 * k * 0.2, 2 * k * 0.4)]
    table = moorsolve.sweep(case, {"bodies[b].loads.force": loads}, workers=1)
    assert list(table["converged"]) == [True, False]
    assert "fender F1 is past its rated deflection" in table["reason"].iloc[1] \
        or "fender F1 is compressed 0.400 m" in table["reason"].iloc[1]
    kept = moorsolve.sweep(case, {"bodies[b].loads.force": loads}, workers=1,
                           allow_overload=True)
    assert kept["converged"].all() and "fender F1" in kept["reason"].iloc[1]
    assert kept["F1.reaction_N"].iloc[1] == pytest.approx(k * 0.4, rel=1e-9)


def test_bad_heights():
    data = berth(1.0, height=0.25)        # under its 0.30 m rating
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "fenders[0].rated_deflection" and "height" in str(err.value)
    data = berth(1.0)
    for f in data["fenders"]:
        f["mounted"] = "structure"
        f["at"][0] = 1.0                  # the face 1 m out from the wall: its height
    data["bodies"][0]["position"] = [1.0, 0.0, 0.0]
    with pytest.raises(CaseError) as err:
        load_case(copy.deepcopy(data))
    assert err.value.field == "fenders[0].height" and "distance" in str(err.value)
    for f in data["fenders"]:
        del f["height"]
    assert [f.height for f in load_case(data).contacts.fenders] == [1.0, 1.0]


@pytest.mark.parametrize("solver", SOLVERS)
def test_a_dolphin_fender_bottoms_out(solver):
    """A fender mounted on a breasting dolphin (a pile of radius 1 m at (-1, 0)), its face
    0.5 m out from the pile (its height), bearing on the body's flat side; the body, free
    in surge, pushed onto it by F far past what the fender takes at full compression: the
    hull bears on the pile, d = (F - k h) / (k + K)."""
    F, h = 3.0e6, 0.5
    data = berth(F)
    del data["walls"]
    data["piles"] = [{"name": "D1", "position": [-1.0, 0.0], "radius": 1.0}]
    data["bodies"][0]["position"] = [0.5, 0.0, 0.0]
    data["fenders"] = [{"name": "F1", "body": "b", "mounted": "structure", "pile": "D1",
                        "at": [0.5, 0.0, 0.0], "reaction": {"stiffness": k},
                        "rated_deflection": RATED}]
    case = load_case(data)
    assert case.contacts.fenders[0].height == pytest.approx(h)
    give = (F - k * h) / (k + HULL_STIFFNESS)
    r = moorsolve.solve(case, solver=solver, tol=1e-12, allow_overload=True)
    f = r.fender("F1")
    assert f["hull_bears"] and f["overloaded"]
    assert r.bodies[0]["x_m"] == pytest.approx(0.5 - h - give, rel=1e-9)
    assert f["hull_reaction_N"] == pytest.approx(HULL_STIFFNESS * give, rel=1e-6)
    assert f["reaction_N"] + f["hull_reaction_N"] == pytest.approx(F, rel=1e-9)
    assert wall_findings(r, case) == []
