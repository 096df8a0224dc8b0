"""The stress corpus (tests/data/hard_cases/): cases at the edge of every regime switch.

Each case either converges with a residual below the certificate threshold, with the
physics the edge demands (checked here), or raises ConvergenceError naming the leg and the
reason. Then two load ramps on the Vida buoy: from zero to beyond the chains' breaking load
in fine steps (certified, then "would break" naming the legs, never anything else), and a
continuation check that tensions and offset vary continuously across every regime switch
met on the way (slack, touchdown, anchor uplift), by bisecting each switch.

Bounded time: every case carries the default solver budget (IPOPT capped at
``solver.max_time_s`` = 5 s per stage); the whole module takes a few seconds.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
import yaml

from moorsolve import ConvergenceError, load_case, solve
from conftest import TESTS


CORPUS = TESTS / "data" / "hard_cases"
CASES = TESTS.parent / "cases"


def certified(result):
    assert result.converged and result.certificate.certified
    assert result.certificate.relative <= result.certificate.tolerance
    return result


def leg(result, name="A"):
    return result.leg(name)


def check_touchdown_at_anchor(r):
    a = leg(r)
    assert a.horizontal_tension_N == pytest.approx(372e3, rel=1e-9)
    assert a.grounded_length_m == pytest.approx(0.0, abs=1e-6)
    assert a.anchor_vertical_N == pytest.approx(0.0, abs=1e-3)
    # T_F = H + w Z for touchdown at the anchor (Hu & Tang Table 2: 399.1050 kN exactly).
    assert a.fairlead_tension_N == pytest.approx(372e3 + 1300.0 * 20.85, rel=1e-9)


def check_touchdown_at_anchor_elastic(r):
    a = leg(r)
    assert a.horizontal_tension_N == pytest.approx(372e3, rel=1e-9)
    assert a.grounded_length_m == pytest.approx(0.0, abs=1e-6)
    assert a.anchor_vertical_N == pytest.approx(0.0, abs=1e-3)


def check_liftoff_at_fairlead(r):
    a = leg(r)
    assert a.horizontal_tension_N == pytest.approx(5.6e8 * 1e-4, rel=1e-9)
    # V is determined only to second order here (Z ~ V^2): zero to the certificate's 1e-8.
    assert a.fairlead_vertical_N == pytest.approx(0.0, abs=1e-8 * a.horizontal_tension_N)
    assert a.grounded_length_m == pytest.approx(100.0, rel=1e-9)


def check_liftoff_at_fairlead_slack(r):
    a = leg(r)
    weight = 1275.0 * 100.0          # zero tension, to 1e-9 of the line's weight
    assert a.horizontal_tension_N == pytest.approx(0.0, abs=1e-9 * weight)
    assert a.fairlead_vertical_N == pytest.approx(0.0, abs=1e-9 * weight)


def check_h_zero_inextensible(r):
    a = leg(r)
    assert a.horizontal_tension_N == pytest.approx(0.0, abs=1e-6)
    assert a.fairlead_vertical_N == pytest.approx(1275.0 * 20.85, rel=1e-9)
    assert a.grounded_length_m == pytest.approx(100.0 - 20.85, rel=1e-9)


def check_h_zero_elastic(r):
    a = leg(r)
    w, EA, Z = 1300.0, 5.6e8, 20.85
    hanging = (math.sqrt(1 + 2 * w * Z / EA) - 1) * EA / w   # Ls + w Ls^2/(2 EA) = Z
    assert a.horizontal_tension_N == pytest.approx(0.0, abs=1e-3)
    assert a.fairlead_vertical_N == pytest.approx(w * hanging, rel=1e-9)


def vertical_balance(a, w, L):
    """Fairlead pull = line weight + anchor pull, for a leg with no seabed contact."""
    return a.fairlead_vertical_N - (w * L + a.anchor_vertical_N)


def check_just_reaches_elastic(r):
    a = leg(r)
    assert a.uplift and a.grounded_length_m == 0.0
    assert vertical_balance(a, 80.0, 50.0) == pytest.approx(0.0, abs=1e-6 * a.fairlead_tension_N)


def check_just_reaches_inextensible(r):
    a = leg(r)
    assert a.uplift and a.horizontal_tension_N > 100 * 80.0 * 50.0
    assert vertical_balance(a, 80.0, 50.00005) == pytest.approx(
        0.0, abs=1e-6 * a.fairlead_tension_N)


def check_stiff_light_line(r):
    for name, (X, Z) in {"A": (80.00008, 60.0), "B": (60.00006, 80.00008)}.items():
        a = leg(r, name)
        chord = math.hypot(X, Z)
        # Nearly straight: T = EA (chord / L - 1) up to the line's 10 N weight.
        assert a.fairlead_tension_N == pytest.approx(1e13 * (chord / 100.0 - 1), rel=1e-5)


def check_soft_heavy_line(r):
    a = leg(r)
    w, EA, Z = 1275.0, 1e3, 20.0
    hanging = (math.sqrt(1 + 2 * w * Z / EA) - 1) * EA / w
    assert a.slack and a.horizontal_tension_N == 0.0
    assert a.fairlead_vertical_N == pytest.approx(w * hanging, rel=1e-9)


def check_shared_anchors(r):
    assert r.body["y_m"] == pytest.approx(0.0, abs=1e-9)
    assert r.body["yaw_deg"] == pytest.approx(0.0, abs=1e-9)
    for k in range(4):      # F_k and F_{7-k} mirror each other about the x axis
        assert r.leg(f"F{k}").fairlead_tension_N == pytest.approx(
            r.leg(f"F{7 - k}").fairlead_tension_N, rel=1e-9)
    assert r.leg("N").fairlead_tension_N == pytest.approx(r.leg("S").fairlead_tension_N,
                                                          rel=1e-9)
    pulled = sum(lr.horizontal_tension_N * (lr.anchor[0] - lr.fairlead[0])
                 / math.hypot(lr.anchor[0] - lr.fairlead[0], lr.anchor[1] - lr.fairlead[1])
                 for lr in r.legs)
    assert pulled == pytest.approx(-3.0e5, rel=1e-9)     # the legs balance the 300 kN push


EXPECT = {
    "touchdown_at_anchor": check_touchdown_at_anchor,
    "touchdown_at_anchor_elastic": check_touchdown_at_anchor_elastic,
    "liftoff_at_fairlead": check_liftoff_at_fairlead,
    "liftoff_at_fairlead_slack": check_liftoff_at_fairlead_slack,
    "h_zero_inextensible": check_h_zero_inextensible,
    "h_zero_elastic": check_h_zero_elastic,
    "just_reaches_elastic": check_just_reaches_elastic,
    "just_reaches_inextensible": check_just_reaches_inextensible,
    "stiff_light_line": check_stiff_light_line,
    "soft_heavy_line": check_soft_heavy_line,
    "shared_anchors": check_shared_anchors,
    "cannot_reach": r"leg West (cannot reach|is pulled straight)",
}


def test_every_corpus_file_has_an_expectation():
    assert sorted(p.stem for p in CORPUS.glob("*.yaml")) == sorted(EXPECT)


#: Also through the compiled Newton fast path (each structure compiles once, ~1 s cold).
NEWTON = ("touchdown_at_anchor_elastic", "liftoff_at_fairlead", "h_zero_elastic",
          "stiff_light_line", "shared_anchors", "cannot_reach")


@pytest.mark.parametrize("name, solver", [(n, "ipopt") for n in sorted(EXPECT)]
                         + [(n, "newton") for n in NEWTON])
def test_corpus_case(name, solver):
    case = load_case(CORPUS / f"{name}.yaml")
    expect = EXPECT[name]
    if isinstance(expect, str):
        with pytest.raises(ConvergenceError, match=expect) as err:
            solve(case, solver=solver)
        assert math.isfinite(err.value.residual_N)
    else:
        expect(certified(solve(case, solver=solver)))


# ---- load ramps on the Vida buoy -----------------------------------------------------------

def buoy(force, heading_deg=200.0, **line):
    data = yaml.safe_load((CASES / "buoy_vida.yaml").read_text(encoding="utf-8"))
    data["environment"].pop("wind")
    data["line_types"]["chain"].update({"ea": 3.4e7, "mbl": 3.0e5, **line})
    a = math.radians(heading_deg)
    data["body"]["loads"] = {"force": [force * math.cos(a), force * math.sin(a), 0.0]}
    return load_case(data)


RAMP = np.linspace(0.0, 6.0e5, 61)         # 10 kN steps to twice the breaking load


def test_load_ramp_to_beyond_capacity():
    """Zero to 600 kN: certified while the chains hold, then 'would break' naming legs."""
    state, broken_from, t_max = None, None, []
    for force in RAMP:
        try:
            r = solve(buoy(force), start=state)
        except ConvergenceError as err:
            assert "would break" in err.reason, err.reason
            assert any(f"leg {n} would break" in err.reason for n in ("NNE", "SSE", "W"))
            assert math.isfinite(err.residual_N)
            if broken_from is None:
                broken_from = force
            continue
        assert broken_from is None, f"certified at {force} N after breaking at {broken_from} N"
        certified(r)
        state = r.state
        t_max.append(max(lr.fairlead_tension_N for lr in r.legs))
    assert broken_from is not None and 1e5 < broken_from < 6e5
    assert np.all(np.diff(t_max) > 0)               # more load, more tension
    assert t_max[-1] <= 3.0e5                       # certified points are within the MBL


def regimes(result):
    return tuple((lr.slack, lr.uplift, lr.grounded_length_m > 0) for lr in result.legs)


def observables(result):
    return np.array([result.body["x_m"], result.body["y_m"]]
                    + [lr.fairlead_tension_N for lr in result.legs]
                    + [lr.anchor_tension_N for lr in result.legs])


def test_tension_and_offset_continuous_across_regime_switches():
    """Every switch met on the ramp is bisected five times: the jump across it must shrink
    with the interval (continuity), not stay (a jump between branches)."""
    forces = np.linspace(0.0, 2.4e5, 25)
    results, state = [], None
    for f in forces:
        r = certified(solve(buoy(f, heading_deg=20.0), start=state))
        results.append(r)
        state = r.state
    switches = [i for i in range(len(forces) - 1)
                if regimes(results[i]) != regimes(results[i + 1])]
    assert len(switches) >= 2, "the ramp should cross slack and uplift switches"
    for i in switches:
        lo, hi = forces[i], forces[i + 1]
        r_lo, r_hi = results[i], results[i + 1]
        jump0 = np.abs(observables(r_hi) - observables(r_lo))
        for _ in range(5):
            mid = 0.5 * (lo + hi)
            r_mid = certified(solve(buoy(mid, heading_deg=20.0), start=r_lo.state))
            if regimes(r_mid) == regimes(r_lo):
                lo, r_lo = mid, r_mid
            else:
                hi, r_hi = mid, r_mid
        jump = np.abs(observables(r_hi) - observables(r_lo))
        scale = np.abs(observables(r_hi)) + 1.0
        # Lipschitz across the switch: the jump falls with the interval (1/32 of it),
        # allowing a factor 4 for a change of slope at the switch.
        assert np.all(jump <= 4 * jump0 / 32 + 1e-9 * scale), (forces[i], jump, jump0)


def test_ramp_is_reproducible_cold():
    """A warm-started ramp point equals the cold solve of the same load."""
    warm = None
    for f in (1.0e5, 1.5e5, 2.0e5):
        warm = solve(buoy(f), start=None if warm is None else warm.state)
    cold = solve(buoy(2.0e5))
    assert observables(warm) == pytest.approx(observables(cold), rel=1e-8, abs=1e-8)


def test_many_legs_sharing_an_anchor_rotated_load():
    """The shared-anchor layout under loads toward every 30 deg: all certified."""
    data = yaml.safe_load((CORPUS / "shared_anchors.yaml").read_text(encoding="utf-8"))
    state = None
    for heading in range(0, 360, 30):
        d = copy.deepcopy(data)
        a = math.radians(heading)
        d["body"]["loads"]["force"] = [3e5 * math.cos(a), 3e5 * math.sin(a), 1e6]
        r = certified(solve(load_case(d), start=state))
        state = r.state
        assert {r.leg(f"F{k}").anchor for k in (2, 3, 4, 5)} == {(-250.0, 0.0, -50.0)}
        assert {r.leg(f"F{k}").anchor for k in (0, 1, 6, 7)} == {(250.0, 0.0, -50.0)}
