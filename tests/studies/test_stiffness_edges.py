"""Derivatives at the non-smooth points of the line model: an exactly vertical weighted
line, a weightless tether hanging straight, touchdown exactly at the anchor.

A line hanging straight down pulls sideways with ``H(X) e`` where ``X = |offset|`` has a
kink at 0 but ``H(X) e = (H/X) offset`` does not: the lateral stiffness is the limit
``dH/dX`` from the taut side, which for the elastic catenary with end tensions ``V`` (top)
and ``V_A = V - w L`` (bottom) is ``1 / (ln(V/V_A)/w + L/EA)`` (Merkin 1980, the suspended
span ``X = (H/w)[asinh(V/H) - asinh(V_A/H)] + H L/EA`` differentiated at ``H -> 0+``; for
``w -> 0`` it is ``T / (L (1 + T/EA))``, the taut string). Everything the stiffness feeds
(per-body and coupled stiffness, stability eigenvalues, natural periods, sensitivities) is
checked against central differences of re-solved cases (tests/studies/resolved.py), to
1e-3 relative or better.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import eigh

import moorsolve
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.studies.stiffness import body_natural_periods, rigid_body_mass

from edge_scenes import tlp, touchdown_at_anchor, vertical_chain_buoy
from resolved import (assert_matrix_close, homogenised_eigenvalues, resolved_coupled,
                      resolved_sensitivity, resolved_stiffness)


def pendulum_stiffness(leg, w: float, length: float, ea: float) -> float:
    """``dH/dX`` at ``X = 0+`` of an elastic catenary hanging straight [N/m]."""
    V, VA = leg.fairlead_tension_N, leg.anchor_tension_N
    compliance = length / ea
    if w > 0:
        compliance += math.log(V / VA) / w
    else:
        compliance += length / V
    return 1.0 / compliance


def check_derivatives(data: dict, body: str, force_step: float, outputs) -> dict:
    """Every derivative of the scene against its re-solved reference; returns the figures."""
    result = moorsolve.solve(moorsolve.load_case(data), tol=1e-12)
    assert result.converged
    K = moorsolve.stiffness(result, body=body)
    K_ref = resolved_stiffness(result, body)
    assert_matrix_close(K, K_ref, label=f"{body} mooring")
    C, dofs = moorsolve.coupled_stiffness(result)
    C_ref = resolved_coupled(result)
    assert_matrix_close(C, C_ref, label="coupled")
    problem = get_problem(result.case)
    arm = problem.moment_scale / problem.force_scale
    stab = result.stability
    assert stab.stable and not stab.neutral_dofs
    got = np.sort_complex(np.asarray(stab.eigenvalues, dtype=complex))
    ref = homogenised_eigenvalues(C_ref, dofs, arm)
    np.testing.assert_allclose(got.real, ref.real, rtol=1e-3)
    spec = result.case.body_named(body)
    periods = body_natural_periods(result, body)
    own = [i for i, d in enumerate(dofs) if d.startswith(body + ".")]
    M = rigid_body_mass(spec.mass, spec.centre_of_gravity, spec.inertia or (0.0, 0.0, 0.0))
    idx = [moorsolve.model.DOFS.index(dofs[i].split(".", 1)[1]) for i in own]
    Ks = C_ref[np.ix_(own, own)]
    w2 = eigh(0.5 * (Ks + Ks.T), M[np.ix_(idx, idx)], eigvals_only=True)
    assert np.all(w2 > 0) and np.all(np.isfinite(periods.periods_s))
    np.testing.assert_allclose(np.sort(periods.periods_s), np.sort(2 * np.pi / np.sqrt(w2)),
                               rtol=1e-3)
    s = moorsolve.sensitivity(result, outputs, [f"bodies[{body}].loads.force[0]"])
    s_ref = resolved_sensitivity(data, outputs, body, 0, force_step)
    scale = np.abs(s_ref).max()
    np.testing.assert_allclose(s.matrix[:, 0], s_ref, rtol=1e-3, atol=1e-3 * scale)
    return dict(result=result, K=K, K_ref=K_ref, C=C, C_ref=C_ref, periods=periods,
                sens=s.matrix[:, 0], sens_ref=s_ref)


def test_tlp_on_four_vertical_weighted_tendons():
    """Before: K11 6.3e3 N/m against 1.76e5 re-solved, coupled K11 ~1e-7, zero
    eigenvalues called stable, an infinite surge period, dx/dFx off by 2."""
    data = tlp()
    out = check_derivatives(data, "tlp", 1.0e4, ["bodies[tlp].x_m", "bodies[tlp].z_m",
                                                 "legs[T1].fairlead_tension_N"])
    result, K = out["result"], out["K"]
    k = sum(pendulum_stiffness(leg, 3000.0, 178.0, 8.0e9) for leg in result.legs)
    assert K[0, 0] == pytest.approx(k, rel=1e-6)
    assert K[1, 1] == pytest.approx(k, rel=1e-6)
    # Yaw: each tendon's lateral stiffness at its arm (25 m, 25 m from the centre).
    assert K[5, 5] == pytest.approx(k * 1250.0, rel=1e-6)
    # The platform sways as an inverted pendulum: roughly 50 s, nowhere near infinite.
    assert 30.0 < max(out["periods"].periods_s) < 80.0


def test_buoy_on_one_vertical_chain():
    """Before: K11 967 N/m against 14,316 re-solved (here 2.8e4 for this chain)."""
    data = vertical_chain_buoy()
    out = check_derivatives(data, "buoy", 500.0, ["bodies[buoy].x_m",
                                                  "legs[chain].fairlead_tension_N"])
    leg = out["result"].leg("chain")
    k = pendulum_stiffness(leg, 400.0, 50.0, 5.0e8)
    assert out["K"][0, 0] == pytest.approx(k, rel=1e-6)


def test_buoy_on_a_vertical_weightless_tether():
    """The weightless limit: the taut string's ``T / L_stretched``."""
    data = vertical_chain_buoy(chain_weight=0.0)
    out = check_derivatives(data, "buoy", 500.0, ["bodies[buoy].x_m"])
    leg = out["result"].leg("chain")
    T = leg.fairlead_tension_N
    assert out["K"][0, 0] == pytest.approx(T / (50.0 * (1 + T / 5.0e8)), rel=1e-6)


def test_touchdown_exactly_at_the_anchor():
    """Suspended and touchdown branches meet with equal first derivatives (the spans and
    their derivatives by ``H`` and ``V`` agree at ``V_A = 0``): the stiffness of the held
    body is the one re-solved poses give on both sides."""
    result = moorsolve.solve(moorsolve.load_case(touchdown_at_anchor()), tol=1e-12)
    leg = result.leg("leg")
    assert leg.anchor_vertical_N == pytest.approx(0.0, abs=1e-3)
    assert leg.grounded_length_m == pytest.approx(0.0, abs=1e-6)
    K = moorsolve.stiffness(result, body="hull")
    assert_matrix_close(K, resolved_stiffness(result, "hull"), label="touchdown")


def quay_hawsers(length: float) -> dict:
    """A held body on two parallel horizontal 2e7 N hawsers to bollards 30 m away along -x,
    ``length`` [m] unstretched (30: exactly at their slack point)."""
    lines, points = [], []
    for k, y in enumerate((5.0, -5.0)):
        points.append({"name": f"P{k}", "position": [-30.0, y, 2.0]})
        lines.append({"name": f"H{k}", "from": f"P{k}", "to": {"body": "b", "at": [0.0, y, 2.0]},
                      "segments": [{"type": "hawser", "length": length}]})
    return {"name": "hawsers at their slack point", "environment": {"depth": 20.0},
            "line_types": {"hawser": {"weight_in_water": 0, "ea": 2.0e7, "mbl": 1e7}},
            "bodies": [{"name": "b", "free": []}], "points": points, "lines": lines}


def test_hawsers_exactly_at_their_slack_point_give_both_sides():
    """At the slack point the force is continuous but its derivative is not: pulling the body
    away stretches both hawsers (``2 EA/L`` along x), pushing it closer leaves them slack
    (nothing). Both one-sided limits against one-sided differences of re-solved poses, and
    ``stiffness`` gives the taut side with a warning instead of the solver's corner."""
    from resolved import held_wrench, displaced
    from moorsolve.studies.stiffness import _solved_poses

    result = moorsolve.solve(moorsolve.load_case(quay_hawsers(30.0)))
    pair = moorsolve.one_sided_stiffness(result)
    assert pair.lines == ("H0", "H1")
    poses, case, h = _solved_poses(result), result.case, 1e-4
    at_rest = held_wrench(case, poses, "b")
    for side, K in ((1, pair.taut), (-1, pair.slack)):
        moved = held_wrench(case, displaced(poses, "b", 0, side * h), "b")
        column = -(moved - at_rest) / (side * h)
        np.testing.assert_allclose(K[:, 0], column, rtol=1e-3, atol=1e-3 * 2 * 2.0e7 / 30)
    assert pair.taut[0, 0] == pytest.approx(2 * 2.0e7 / 30.0, rel=1e-5)
    assert np.all(pair.slack == 0)
    with pytest.warns(moorsolve.MoorsolveWarning, match="slack point"):
        K = moorsolve.stiffness(result)
    np.testing.assert_array_equal(K, pair.taut)
    # The coupled matrix at the point is not either side's: said.
    data = quay_hawsers(30.0)
    data["bodies"][0].update(free=["surge", "sway", "yaw"], stiffness=[
        [1e5 if i == j else 0 for j in range(6)] for i in range(6)])
    with pytest.warns(moorsolve.MoorsolveWarning, match="neither"):
        moorsolve.coupled_stiffness(moorsolve.solve(moorsolve.load_case(data)))
    # Off the point by far more than AT_SLACK_POINT: one matrix, no pair.
    assert moorsolve.one_sided_stiffness(moorsolve.solve(moorsolve.load_case(
        quay_hawsers(30.5)))) is None


def test_cli_prints_both_sides(tmp_path, capsys):
    import json

    import yaml
    from moorsolve.cli import main

    path = tmp_path / "hawsers.yaml"
    path.write_text(yaml.safe_dump(quay_hawsers(30.0)))
    assert main(["stiffness", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["one_sided"]["lines"] == ["H0", "H1"]
    assert out["matrix"] == out["one_sided"]["taut"]
    assert np.all(np.asarray(out["one_sided"]["slack"]) == 0)
    assert main(["stiffness", str(path)]) == 0
    assert "exactly at their slack point" in capsys.readouterr().out


@pytest.mark.parametrize("top", [{"weight_in_water": 50.0, "ea": 3.0e8},
                                 {"weight_in_water": 0.0, "ea": 3.0e8}])
def test_multi_segment_line_hanging_straight(top):
    """Chain below, wire (or weightless rope) above, hanging straight: the segments' spans
    add as springs in series, ``1/k = sum(ln(V_k/V_Ak)/w_k + L_k/EA_k)``."""
    data = vertical_chain_buoy()
    data["line_types"]["top"] = dict(top, mbl=5e6)
    data["lines"][0]["segments"] = [{"type": "chain", "length": 20.0},
                                    {"type": "top", "length": 30.0}]
    out = check_derivatives(data, "buoy", 500.0, ["bodies[buoy].x_m"])
    leg = out["result"].leg("chain")
    V = leg.fairlead_tension_N
    V_joint = V - top["weight_in_water"] * 30.0
    compliance = 20.0 / 5.0e8 + math.log(V_joint / leg.anchor_tension_N) / 400.0 \
        + 30.0 / top["ea"] + (math.log(V / V_joint) / top["weight_in_water"]
                              if top["weight_in_water"] else 30.0 / V)
    assert out["K"][0, 0] == pytest.approx(1 / compliance, rel=1e-5)


def test_horizontal_tension_of_a_straight_line_is_a_kink_and_said():
    """The horizontal tension of a tendon hanging straight grows as the offset's size on
    every side: re-solved with the load +-dF it rises both ways (one-sided slopes of
    opposite sign), so no derivative exists and ``sensitivity`` says so; the pose's
    derivative, smooth, comes without a word."""
    import warnings

    data = tlp()
    result = moorsolve.solve(moorsolve.load_case(data), tol=1e-12)
    plus = moorsolve.solve(moorsolve.load_case(tlp(force=(1e4, 0, 0))), tol=1e-12)
    minus = moorsolve.solve(moorsolve.load_case(tlp(force=(-1e4, 0, 0))), tol=1e-12)
    # Each tendon takes about a quarter of the load on either side: slopes +-1/4.
    right = plus.leg("T1").horizontal_tension_N / 1e4
    left = -minus.leg("T1").horizontal_tension_N / 1e4
    assert right == pytest.approx(0.25, rel=0.02) and left == pytest.approx(-0.25, rel=0.02)
    central = resolved_sensitivity(data, ["legs[T1].horizontal_tension_N"], "tlp", 0, 1e4)[0]
    assert abs(central) < 1e-3 * right           # the kink averaged away
    with pytest.warns(moorsolve.MoorsolveWarning, match="kink"):
        moorsolve.sensitivity(result, ["legs[T1].horizontal_tension_N"],
                              ["bodies[tlp].loads.force[0]"])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        moorsolve.sensitivity(result, ["bodies[tlp].x_m"], ["bodies[tlp].loads.force[0]"])


def fendered(load_x: float) -> dict:
    """A body on a yaw and surge spring with two 2e6 N/m fenders touching a quay wall at
    rest (x = 0, outward normal +x), pushed onto it by ``-load_x`` [N]."""
    def fender(name, y):
        return {"name": name, "body": "b", "at": [0, y, 0], "wall": "quay",
                "reaction": {"stiffness": 2.0e6}, "rated_deflection": 0.5}
    return {
        "name": "fenders at first contact", "environment": {"depth": 15.0},
        "line_types": {"hawser": {"weight_in_water": 0, "ea": 2.0e7}},
        "bodies": [{"name": "b", "free": ["surge", "yaw"], "loads": {"force": [load_x, 0, 0]},
                    "stiffness": [[1e5 if i == j else 0 for j in range(6)]
                                  for i in range(6)]}],
        "lines": [{"name": "idle", "from": [60.0, 0.0, 0.0],
                   "to": {"body": "b", "at": [20, 0, 0]},
                   "segments": [{"type": "hawser", "length": 45.0}]}],
        "walls": [{"name": "quay", "point": [0, 0, 0], "normal": [1, 0, 0]}],
        "fenders": [fender("F1", 10.0), fender("F2", -10.0)],
    }


def test_fenders_exactly_at_first_contact_are_said():
    """Touching with no reaction, closing adds 2 x 2e6 N/m and opening nothing: the coupled
    stiffness is one side's and says so; pressed on, it is one matrix and silent."""
    import warnings

    result = moorsolve.solve(moorsolve.load_case(fendered(0.0)))
    with pytest.warns(moorsolve.MoorsolveWarning, match="F1, F2 exactly at first contact"):
        moorsolve.coupled_stiffness(result)
    pressed = moorsolve.solve(moorsolve.load_case(fendered(-1.0e5)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        C, _ = moorsolve.coupled_stiffness(pressed)
    assert C[0, 0] == pytest.approx(1e5 + 2 * 2.0e6, rel=1e-6)
