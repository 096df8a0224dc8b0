"""Property suite: scenes generated across the line model's edges, every derivative compared
with central differences of re-solved cases (tests/studies/resolved.py).

Regimes: lines hanging straight down (weighted and weightless, held and free bodies),
touchdown exactly at the anchor, hawsers slack beside taut ones, two bodies joined by a
hawser, several bodies on shared lines and bridles. The tolerance is 1e-3 relative to each
entry's scale ``sqrt(K_ii K_jj)``; the central differences themselves are accurate to
~1e-6 there (steps of 1e-3 m and 1e-5 rad against spans of tens of metres).
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import moorsolve
from hypothesis_budget import examples

from edge_scenes import calm_and_tanker, touchdown_at_anchor
from resolved import (assert_matrix_close, homogenised_eigenvalues, resolved_coupled,
                      resolved_sensitivity, resolved_stiffness)

CASES = Path(__file__).resolve().parents[2] / "cases"
SETTINGS = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)


def hanging_line(span, weight, ea, strain, free, lift=0.0) -> dict:
    """A body at the surface exactly above its anchor on one line of ``span`` [m] stretched
    by ``strain`` (so that the top tension is ``strain EA + w L / 2`` and the bottom one
    ``strain EA - w L / 2``), the anchor ``lift`` [m] above the seabed; ``free`` the body's
    free DOFs (held in the rest)."""
    length = span / (1 + strain)
    return {
        "name": "body on a hanging line",
        "environment": {"depth": span + lift},
        "line_types": {"line": {"weight_in_water": weight, "ea": ea, "mbl": 1e12}},
        "bodies": [{"name": "b", "free": list(free), "mass": 1.0e5,
                    "loads": {"force": [0.0, 0.0, 0.0]}}],
        "lines": [{"name": "L", "from": [0.0, 0.0, -span],
                   "to": {"body": "b", "at": [0.0, 0.0, 0.0]},
                   "segments": [{"type": "line", "length": length}]}],
    }


@st.composite
def hanging_lines(draw):
    span = draw(st.floats(20.0, 400.0))
    weight = draw(st.sampled_from([-50.0, 0.0, 1.0, 50.0, 400.0, 3000.0]))
    ea = draw(st.floats(1e7, 1e10))
    # Taut all the way: both end tensions at least half the line's weight.
    least = max(1e-5, abs(weight) * span / ea)
    strain = draw(st.floats(least, max(2 * least, 0.01)))
    # The anchor on the seabed (leg blocks; a buoyant line rising to the surface: the
    # surface block) or lifted above it (the lifted block).
    lift = draw(st.sampled_from([0.0, 15.0]))
    return span, weight, ea, strain, lift


@settings(max_examples=examples(10), **SETTINGS)
@given(hanging_lines(), st.sampled_from([("surge", "sway"), ()]))
@example((120.0, -50.0, 1e8, 1e-3, 0.0), ("surge", "sway"))     # buoyant, to the surface
@example((80.0, 3000.0, 5e9, 1e-3, 15.0), ("surge", "sway"))    # heavy, anchor lifted
@example((60.0, 0.0, 1e8, 1e-4, 15.0), ())                      # weightless tether
def test_line_hanging_straight(line, free):
    """Per-body stiffness (and, free, the coupled stiffness and stability eigenvalues) of a
    body on a line hanging straight down equal the re-solved ones, and the lateral entry is
    the closed-form ``1 / (ln(V/V_A)/w + L/EA)`` (``L/V + L/EA`` weightless)."""
    span, weight, ea, strain, lift = line
    data = hanging_line(span, weight, ea, strain, free, lift)
    result = moorsolve.solve(moorsolve.load_case(data), tol=1e-12)
    K = moorsolve.stiffness(result, body="b")
    assert_matrix_close(K, resolved_stiffness(result, "b"), label="hanging")
    leg = result.leg("L")
    V, VA, L = leg.fairlead_tension_N, leg.anchor_tension_N, span / (1 + strain)
    compliance = L / ea + (math.log(V / VA) / weight if weight else L / V)
    assert K[0, 0] == pytest.approx(1 / compliance, rel=1e-6)
    assert K[1, 1] == pytest.approx(1 / compliance, rel=1e-6)
    if free:
        C, dofs = moorsolve.coupled_stiffness(result)
        C_ref = resolved_coupled(result)
        assert_matrix_close(C, C_ref, label="coupled")
        assert result.stability.stable
        got = np.sort(np.real(result.stability.eigenvalues))
        np.testing.assert_allclose(got, np.sort(np.real(homogenised_eigenvalues(
            C_ref, dofs, 1.0))), rtol=1e-3)
        periods = moorsolve.body_natural_periods(result, "b")
        assert np.allclose(periods.periods_s, 2 * np.pi * math.sqrt(1.0e5 * compliance),
                           rtol=1e-3)


@settings(max_examples=examples(4), **SETTINGS)
@given(st.floats(2e4, 2e6), st.floats(100.0, 2000.0), st.floats(100.0, 600.0),
       st.floats(5e7, 5e9))
def test_touchdown_exactly_at_the_anchor(H, w, length, ea):
    """The held body's stiffness where the touchdown point is exactly the anchor."""
    result = moorsolve.solve(moorsolve.load_case(touchdown_at_anchor(H, w, length, ea)),
                             tol=1e-12)
    assert result.leg("leg").grounded_length_m == pytest.approx(0.0, abs=1e-6 * length)
    K = moorsolve.stiffness(result, body="hull")
    assert_matrix_close(K, resolved_stiffness(result, "hull"), label="touchdown")


def hawsers(load, slack, ea) -> dict:
    """A body pushed along +x by ``load`` [N] against two hawsers (30 m to bollards at
    x = -30, drawn taut), with two more to bollards at x = +30 longer than their chord by
    ``slack`` [m] (slack, the more so as the body moves toward them), and a spring in
    yaw."""
    lines, points = [], []
    for k, (x, y, extra) in enumerate([(-30.0, 6.0, 0.0), (-30.0, -6.0, 0.0),
                                       (30.0, 6.0, slack), (30.0, -6.0, slack)]):
        points.append({"name": f"P{k}", "position": [x, y, 2.0]})
        lines.append({"name": f"H{k}", "from": f"P{k}",
                      "to": {"body": "b", "at": [0.0, y, 2.0]},
                      "segments": [{"type": "hawser", "length": 30.0 + extra}]})
    return {
        "name": "hawsers slack and taut",
        "environment": {"depth": 20.0},
        "line_types": {"hawser": {"weight_in_water": 0.0, "ea": ea, "mbl": 1e12}},
        "bodies": [{"name": "b", "free": ["surge", "sway", "yaw"], "mass": 2.0e6,
                    "inertia": [1e9, 1e9, 1e9], "loads": {"force": [load, 0.0, 0.0]},
                    "stiffness": [[0] * 6] * 5 + [[0, 0, 0, 0, 0, 1e7]]}],
        "points": points,
        "lines": lines,
    }


@settings(max_examples=examples(4), **SETTINGS)
@given(st.floats(0.05, 1.0), st.floats(0.05, 3.0), st.floats(1e7, 1e9))
def test_hawsers_slack_beside_taut_ones(stretch, slack, ea):
    """Slack hawsers add nothing; the taut ones their bar and string stiffness: per-body,
    coupled, stability and the sensitivity of the pose to the load. The taut hawsers are
    stretched by ``stretch`` [m], well beyond the central differences' steps (a step
    longer than the stretch would cross the slack point: a kink, not a derivative)."""
    load = 2 * ea * stretch / 30.0
    data = hawsers(load, slack, ea)
    result = moorsolve.solve(moorsolve.load_case(data), tol=1e-12)
    assert result.leg("H2").slack and result.leg("H3").slack
    assert not result.leg("H0").slack
    K = moorsolve.stiffness(result, body="b")
    assert_matrix_close(K, resolved_stiffness(result, "b"), label="hawsers")
    # The two taut 30 m bars side by side: 2 EA/L along x.
    assert K[0, 0] == pytest.approx(2 * ea / 30.0, rel=1e-6)
    C, dofs = moorsolve.coupled_stiffness(result)
    assert_matrix_close(C, resolved_coupled(result), label="coupled")
    outputs = ["bodies[b].x_m", "legs[H0].fairlead_tension_N"]
    s = moorsolve.sensitivity(result, outputs, ["bodies[b].loads.force[0]"])
    ref = resolved_sensitivity(data, outputs, "b", 0, 1e-3 * abs(load))
    np.testing.assert_allclose(s.matrix[:, 0], ref, rtol=1e-3)


@settings(max_examples=examples(3), **SETTINGS)
@given(st.floats(5e4, 8e5), st.floats(40.0, 90.0), st.floats(2e7, 2e8))
def test_two_bodies_on_a_hawser(load, length, ea):
    """A CALM buoy and a tanker on one weightless hawser: each body's stiffness, the
    coupled matrix, stability eigenvalues and the tanker's dx/dF."""
    data = calm_and_tanker(load, length, ea)
    result = moorsolve.solve(moorsolve.load_case(data), tol=1e-12)
    for body in ("buoy", "tanker"):
        K = moorsolve.stiffness(result, body=body)
        assert_matrix_close(K, resolved_stiffness(result, body), label=body)
        assert K[0, 0] > 0
    C, dofs = moorsolve.coupled_stiffness(result)
    C_ref = resolved_coupled(result)
    assert_matrix_close(C, C_ref, label="coupled")
    from moorsolve.solve.assembly.cache import get_problem
    problem = get_problem(result.case)
    got = np.sort_complex(np.asarray(result.stability.eigenvalues, dtype=complex))
    ref = homogenised_eigenvalues(C_ref, dofs, problem.moment_scale / problem.force_scale)
    np.testing.assert_allclose(got.real, ref.real, rtol=1e-3)
    outputs = ["bodies[tanker].x_m", "bodies[buoy].x_m", "legs[hawser].fairlead_tension_N"]
    s = moorsolve.sensitivity(result, outputs, ["bodies[tanker].loads.force[0]"])
    ref = resolved_sensitivity(data, outputs, "tanker", 0, 1e-3 * load)
    np.testing.assert_allclose(s.matrix[:, 0], ref, rtol=1e-3)


@pytest.fixture(scope="module")
def platforms():
    return moorsolve.solve(moorsolve.load_case(CASES / "three_platforms.yaml"), tol=1e-12)


def test_three_platforms_coupled(platforms):
    """Three platforms on shared lines and bridles with free apexes: the coupled 18x18
    matrix and the stability eigenvalues (the per-body matrices are in
    test_stiffness_bodies.py)."""
    C, dofs = moorsolve.coupled_stiffness(platforms)
    C_ref = resolved_coupled(platforms)
    assert_matrix_close(C, C_ref, label="coupled")
    from moorsolve.solve.assembly.cache import get_problem
    problem = get_problem(platforms.case)
    got = np.sort(np.real(np.asarray(platforms.stability.eigenvalues, dtype=complex)))
    ref = np.sort(homogenised_eigenvalues(C_ref, dofs,
                                          problem.moment_scale / problem.force_scale).real)
    np.testing.assert_allclose(got, ref, rtol=1e-3)
