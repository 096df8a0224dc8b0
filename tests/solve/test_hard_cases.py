"""Hard cases: every regime of the leg converges with a certificate, or fails with a reason.

Slack leeward legs, a leg taut near its breaking load, a nearly straight inextensible leg,
vertical legs, a fully grounded leg, uplifted anchors, buoyant and weightless lines, and
loads beyond capacity.
"""

import dataclasses
import math

import numpy as np
import pytest
import yaml

from moorsolve import ConvergenceError, load_case, solve
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.solve.result.diagnosis import pulled_straight
from moorsolve.solve.assembly.problem import LINE_COLUMNS
from conftest import ROOT

CASES = ROOT / "cases"
CHAIN_W, CHAIN_EA, CHAIN_MBL = 1275.0, 5.6e8, 5.5e6


def single_leg(X, Z, L, w, ea=None, mbl=None, depth=None, anchor_z=None):
    depth = Z if depth is None else depth
    line = {"weight_in_water": w}
    if ea is not None:
        line["ea"] = ea
    if mbl is not None:
        line["mbl"] = mbl
    anchor = [0.0, 0.0] if anchor_z is None else [0.0, 0.0, anchor_z]
    return load_case({
        "environment": {"depth": depth},
        "line_types": {"line": line},
        "legs": [{"name": "A", "anchor": anchor, "fairlead": [X, 0.0, Z - depth],
                  "segments": [{"type": "line", "length": L}]}]})


def buoy_with_force(fx, fy=0.0, **line_changes):
    data = yaml.safe_load((CASES / "buoy_vida.yaml").read_text())
    data["environment"].pop("wind")
    data["body"]["loads"] = {"force": [fx, fy, 0.0]}
    data["line_types"]["chain"].update(line_changes)
    return load_case(data)


def assert_certified(result):
    assert result.converged
    assert result.certificate.certified
    t_max = max(max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in result.legs)
    assert result.certificate.force_N <= 1e-9 * max(t_max, 1.0)


def leg_balance(leg, w, L):
    """Vertical balance of a whole leg: fairlead pull = weight + anchor pull (no seabed)."""
    return leg.fairlead_vertical_N - (w * L + leg.anchor_vertical_N)


@pytest.mark.parametrize("force", [1.0e3, 1.6e3, 3.0e3, 1.0e4])
def test_leeward_leg_goes_slack_and_tension_stays_continuous(force):
    result = solve(buoy_with_force(-force))
    assert_certified(result)
    west = result.leg("W")
    north, south = result.leg("NNE"), result.leg("SSE")
    # Mirror symmetry about the x axis holds through the slack switch.
    assert north.fairlead_tension_N == pytest.approx(south.fairlead_tension_N, rel=1e-9)
    assert result.body["y_m"] == pytest.approx(0.0, abs=1e-9)
    if force >= 1.6e3:
        # REFERENCE.md section 1: the buoy's leeward leg goes slack at about 1.5 kN.
        assert west.slack and west.horizontal_tension_N == 0.0
        w = 22.0 * 9.81
        # A slack chain hangs straight down: V = w times the depth under the fairlead.
        assert west.fairlead_vertical_N == pytest.approx(w * 22.0, rel=1e-9)
        assert west.grounded_length_m == pytest.approx(50.0 - 22.0, rel=1e-9)
    else:
        assert not west.slack


def test_tension_continuous_across_the_slack_switch():
    forces = np.linspace(1.0e3, 2.0e3, 21)
    h_west, offsets = [], []
    for f in forces:
        r = solve(buoy_with_force(-f))
        h_west.append(r.leg("W").horizontal_tension_N)
        offsets.append(r.body["x_m"])
    assert h_west[0] > 0 and h_west[-1] == 0
    # No jumps: each step changes H and offset by a small fraction of the range.
    assert np.max(np.abs(np.diff(h_west))) < 0.2 * h_west[0]
    assert np.all(np.diff(offsets) < 0) and np.max(np.abs(np.diff(offsets))) < 0.5


def test_taut_leg_just_below_breaking_load():
    # Find the span at which the fairlead tension is 0.999 MBL, then solve there.
    L, Z = 122.5, 20.85

    def tension(X):
        r = solve(single_leg(X, Z, L, CHAIN_W, CHAIN_EA, CHAIN_MBL), allow_overload=True)
        return r.legs[0].fairlead_tension_N
    lo, hi = math.sqrt(L**2 - Z**2), math.sqrt((L * 1.02) ** 2 - Z**2)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if tension(mid) < 0.999 * CHAIN_MBL else (lo, mid)
    result = solve(single_leg(lo, Z, L, CHAIN_W, CHAIN_EA, CHAIN_MBL))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.fairlead_tension_N == pytest.approx(0.999 * CHAIN_MBL, rel=1e-6)
    assert leg.uplift
    # Beyond the breaking load the same leg is reported as breaking.
    with pytest.raises(ConvergenceError, match="would break"):
        solve(single_leg(hi * 1.001, Z, L, CHAIN_W, CHAIN_EA, CHAIN_MBL))


def test_inextensible_leg_within_a_thousandth_of_straight():
    L, Z = 122.5, 20.85
    X = math.sqrt((0.999 * L) ** 2 - Z**2)
    result = solve(single_leg(X, Z, L, CHAIN_W))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.uplift and leg.grounded_length_m == 0.0
    assert leg.horizontal_tension_N > 5 * CHAIN_W * L    # nearly straight: tension >> weight
    assert leg_balance(leg, CHAIN_W, L) == pytest.approx(0.0, abs=1e-6 * leg.fairlead_tension_N)


def test_vertical_leg_hanging_with_chain_on_the_seabed():
    result = solve(single_leg(0.0, 20.85, 40.0, CHAIN_W))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.horizontal_tension_N == 0.0 and leg.slack
    assert leg.fairlead_vertical_N == pytest.approx(CHAIN_W * 20.85, rel=1e-12)
    assert leg.grounded_length_m == pytest.approx(40.0 - 20.85, rel=1e-12)


def test_vertical_leg_stretched():
    L, Z = 20.0, 20.85
    result = solve(single_leg(0.0, Z, L, CHAIN_W, CHAIN_EA))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.uplift and not leg.slack
    # Straight vertical elastic bar under its own weight: Z = L + (V L - w L^2/2)/EA.
    V = (Z - L) * CHAIN_EA / L + CHAIN_W * L / 2
    assert leg.fairlead_vertical_N == pytest.approx(V, rel=1e-9)


def test_uplifted_anchor_matches_vertical_balance():
    result = solve(load_case(str(CASES / "floating_dock.yaml")))
    uplifted = [leg for leg in result.legs if leg.uplift]
    assert uplifted, "the typhoon should lift at least one sinker"
    w = 0.13e3 * 9.80665
    for leg in uplifted:
        assert leg.grounded_length_m == 0.0 and leg.anchor_vertical_N > 0
        assert leg_balance(leg, w, 122.52) == pytest.approx(0.0, abs=1e-6)
        assert leg.uplift_angle_deg == pytest.approx(
            math.degrees(math.atan2(leg.anchor_vertical_N, leg.anchor_horizontal_N)))


def test_buoyant_line_arches_up_and_holds_the_fairlead_down():
    # Anchor 30 m down, fairlead 10 m down: the 100 m line's free arch would rise about
    # 10 m into the air (this test once asserted that); the surface stops it and about
    # 39 m of it floats, carried by the surface (REFERENCE.md section 7).
    w = -200.0
    result = solve(single_leg(80.0, 20.0, 100.0, w, CHAIN_EA, depth=30.0))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.fairlead_vertical_N < 0 < leg.anchor_vertical_N
    assert leg.anchor_tension_N > leg.fairlead_tension_N
    assert leg.floating_length_m > 10.0
    # Only the suspended length hangs on the ends.
    suspended = 100.0 - leg.floating_length_m
    assert leg.fairlead_vertical_N - (w * suspended + leg.anchor_vertical_N) == \
        pytest.approx(0.0, abs=1e-6)
    z = leg.profile["z_m"]
    assert np.max(z) == pytest.approx(0.0, abs=1e-9)
    assert np.count_nonzero(np.abs(z) <= 1e-9) >= 2        # a run along the surface


def test_weightless_line_is_straight_or_loose():
    taut = solve(single_leg(80.0, 20.0, 82.4, 0.0, 1e7)).legs[0]
    chord = math.hypot(80.0, 20.0)
    assert taut.fairlead_tension_N == pytest.approx(1e7 * (chord / 82.4 - 1), rel=1e-9)
    assert taut.fairlead_vertical_N / taut.horizontal_tension_N == pytest.approx(0.25)
    loose = solve(single_leg(80.0, 20.0, 100.0, 0.0, 1e7)).legs[0]
    assert loose.slack and loose.fairlead_tension_N == 0.0


def test_anchor_above_the_seabed_hangs_as_one_catenary():
    # A short slack chain from a pile head 5 m above the seabed: one catenary that clears it.
    result = solve(single_leg(80.0, 20.0, 84.0, CHAIN_W, CHAIN_EA, depth=30.0,
                              anchor_z=-25.0))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.grounded_length_m == 0.0
    assert np.min(leg.profile["z_m"]) > -30.0
    assert leg_balance(leg, CHAIN_W, 84.0) == pytest.approx(0.0, abs=1e-6)


def test_anchor_above_the_seabed_touches_down_between():
    # The same pile head with 100 m of chain: the catenary would pass 5 m below the seabed
    # (the answer before the network core, with a note); the chain runs down to the
    # seabed, lies on it and rises to the fairlead, never below it.
    result = solve(single_leg(80.0, 20.0, 100.0, CHAIN_W, CHAIN_EA, depth=30.0,
                              anchor_z=-25.0))
    assert_certified(result)
    leg = result.legs[0]
    assert leg.grounded_length_m > 0.0
    assert np.min(leg.profile["z_m"]) >= -30.0 - 1e-9
    assert not any("below the seabed" in n for n in result.notes)
    # Vertical balance of the whole chain: the two ends hold up its weight less the
    # grounded part, which the seabed holds (the anchor is pulled down: a negative pull).
    lifted = leg.fairlead_vertical_N - leg.anchor_vertical_N
    assert lifted == pytest.approx(CHAIN_W * (100.0 - leg.grounded_length_m), rel=1e-9)


def test_load_beyond_breaking_raises_with_the_legs_that_break():
    with pytest.raises(ConvergenceError) as err:
        solve(buoy_with_force(5e6, mbl="100 kN"))
    assert "W would break" in err.value.reason
    assert err.value.residual_N >= 0


def test_inextensible_mooring_pulled_straight_is_explained():
    # 50 MN on a 22 kg/m inextensible chain: an equilibrium exists with the chain straight
    # to 1.3e-9 of its length; since the leg block lost its cancellation (issue 7) it is
    # found and certified. At 500 MN the sag is below what double precision resolves.
    nearly = solve(buoy_with_force(5e7))
    assert_certified(nearly)
    west = nearly.leg("W")
    assert 1 - 1e-8 < math.dist(west.anchor, west.fairlead) / 50.0 < 1
    # At 500 MN the sag is about 1e-11 of the span: either the polish still resolves it
    # (a certified equilibrium, chain straight to 1e-9) or the failure names the cause.
    try:
        taut = solve(buoy_with_force(5e8))
    except ConvergenceError as err:
        assert "pulled straight" in err.reason and "W" in err.reason
        assert math.isfinite(err.residual_N)
    else:
        assert_certified(taut)
        west = taut.leg("W")
        assert 1 - 1e-9 < math.dist(west.anchor, west.fairlead) / 50.0 <= 1


def test_inextensible_line_straighter_than_double_precision_is_refused_even_certified():
    """Whether a solver certifies a point where an inextensible line's length exceeds its
    chord by less than double precision resolves is round-off luck (numpy 2.4's OpenBLAS
    certifies tests/data/hard_cases/cannot_reach.yaml on some CPUs): such a point is refused
    by rule, and a line double precision still resolves, or one hanging vertically, is not."""
    case = buoy_with_force(1e12)
    problem = get_problem(case)
    table = np.zeros((len(case.lines), len(LINE_COLUMNS)))
    w = case.lines[0].line_type.weight_in_water
    west = [line.name for line in case.lines].index("W")

    def straight(H, X):
        table[west, LINE_COLUMNS.index("H")] = H
        table[west, LINE_COLUMNS.index("X")] = X
        return pulled_straight(problem, case, {"lines": table})

    assert "leg W is pulled straight" in " ".join(straight(1e12, 44.9))
    # Length less chord w^2 X^4 / (24 H^2 L): 1e-11 of the length at 5e8 N (resolved).
    assert (w * 44.9 ** 2 / 5e8) ** 2 / 24 / 50.0 ** 2 > 1e-12
    assert straight(5e8, 44.9) == [] and straight(5e7, 44.9) == []
    assert straight(1e12, 0.01) == []          # hanging vertically: straight by itself
    # End to end, whether the solver reaches the near-straight point at all is round-off
    # luck too (it does on some CPUs' OpenBLAS kernels; on an AMD EPYC with AVX-512 IPOPT
    # runs away to a point where the legs cannot reach, though they span at rest): never an
    # answer, always leg W named, and a run-away said to be one.
    with pytest.raises(ConvergenceError,
                       match="leg W is pulled straight|W cannot reach at the best point "
                             "reached .* though each spans its ends at the case's pose"):
        solve(case)


def test_a_run_away_is_not_called_a_line_that_cannot_reach():
    """A best point where inextensible lines that span their ends at the case's pose are
    stretched beyond their length is the solver's excursion, not a scene that cannot
    close; a line too short at the case's pose still cannot reach."""
    from moorsolve.solve.result.diagnosis import diagnose
    case = buoy_with_force(1e3)
    result = solve(case)
    far = [dataclasses.replace(leg, fairlead=(leg.fairlead[0] + 300.0, *leg.fairlead[1:]))
           for leg in result.legs]
    reason = diagnose(get_problem(case), case, dataclasses.replace(result, legs=far))
    assert "cannot reach at the best point reached" in reason
    assert "though each spans its ends at the case's pose" in reason
    assert "anchor-fairlead distance" not in reason
    short = buoy_with_force(1e3)
    lines = tuple(dataclasses.replace(line, segments=tuple(
        dataclasses.replace(seg, length=30.0) for seg in line.segments))
        for line in short.lines)
    short = dataclasses.replace(short, lines=lines)
    reason = diagnose(get_problem(short), short, dataclasses.replace(result, legs=far))
    assert "anchor-fairlead distance" in reason and "at the best point" not in reason


def test_allow_overload_returns_the_equilibrium():
    result = solve(buoy_with_force(5e3, mbl="5 kN"), allow_overload=True)
    assert_certified(result)
    assert result.leg("W").t_over_mbl > 1.0


@pytest.mark.parametrize("scene", ["buoy", "soft_dock"])
def test_random_loads_all_converge_including_slack_legs(scene):
    """REFERENCE.md section 1: 100/100 random loads converged on a 3-leg buoy and a 12-leg
    dock, including loads that push legs slack. Here 30 per scene, every one certified."""
    rng = np.random.default_rng(7)
    name = "buoy_vida" if scene == "buoy" else "floating_dock"
    data = yaml.safe_load((CASES / f"{name}.yaml").read_text())
    for key in ("wind", "current", "waves"):
        data["environment"].pop(key, None)
    if scene == "soft_dock":
        data["line_types"]["chain81"]["ea"] = 1e8
        for leg in data["legs"]:
            leg["segments"][0]["length"] = 135.0     # long chains: leeward legs go slack
    scale, moment = (5e3, 0.0) if scene == "buoy" else (2e7, 1e8)
    slack = 0
    for _ in range(30):
        force, angle = rng.uniform(0, scale), rng.uniform(0, 2 * np.pi)
        data["body"]["loads"] = {"force": [force * np.cos(angle), force * np.sin(angle),
                                           rng.uniform(-1, 1) * moment]}
        result = solve(load_case(data), allow_overload=True)
        assert_certified(result)
        slack += sum(leg.slack for leg in result.legs)
    assert slack > 0


def test_weightless_profile_runs_along_the_chord():
    for L in (82.4, 100.0):          # taut and loose
        leg = solve(single_leg(80.0, 20.0, L, 0.0, 1e7)).legs[0]
        p = leg.profile
        assert (p["x_m"][-1], p["y_m"][-1], p["z_m"][-1]) == pytest.approx(leg.fairlead,
                                                                           abs=1e-9)


def test_large_couple_stays_on_the_quasi_static_branch():
    # Issue 7 found this layout: a direct solve certifies an equilibrium at 36.5 deg yaw,
    # while loading the body gradually ends at 20.8 deg (L0 at 82.4 kN). The solve must
    # give the quasi-static one, by either solver.
    legs = [("L0", [144.888874, 38.822857], [4.829629, 1.294095, 0]),
            ("L1", [-75, 129.903811], [-2.5, 4.330127, 0]),
            ("L2", [-75, -129.903811], [-2.5, -4.330127, 0])]
    data = {"environment": {"depth": 42, "current": {"speed": 1.0, "toward_deg": 248}},
            "line_types": {"c": {"weight_in_water": 312, "ea": 1e8}},
            "body": {"free": ["surge", "sway", "yaw"],
                     "loads": {"force": [0, 0, 655200],
                               "current": {"model": "drag", "area_x": 300, "area_y": 900,
                                           "cx": 0.8, "cy": 1.0, "centre": [0, 0]}}},
            "legs": [{"name": n, "anchor": a, "fairlead": f,
                      "segments": [{"type": "c", "length": 166}]} for n, a, f in legs]}
    case = load_case(data)
    for solver in ("ipopt", "newton"):
        result = solve(case, solver=solver)
        # The Newton path follows the load up itself (issue 16), without IPOPT.
        assert result.solver == solver
        assert result.body["yaw_deg"] == pytest.approx(20.83, abs=0.01)
        assert result.leg("L0").fairlead_tension_N == pytest.approx(82.4e3, rel=1e-3)


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
@pytest.mark.parametrize("length, force", [(60.0, 500.0), (75.0, 2000.0), (90.0, 5000.0)])
def test_every_leg_slack_at_rest_then_loaded(length, force, solver):
    """Vida's three chains lengthened until all hang slack at rest (L > X + Z): the body has
    no horizontal stiffness there, so Newton and IPOPT cannot start from rest; the solve
    drifts with the load (pseudo-transient continuation) until a chain takes it. Checked by
    an independent balance: the lines' horizontal pull on the body equals the load."""
    data = yaml.safe_load((CASES / "buoy_vida.yaml").read_text())
    data["environment"].pop("wind")
    data["body"] = {"free": ["surge", "sway"], "loads": {"force": [force, 0.0, 0.0]}}
    for leg in data["legs"]:
        leg["segments"][0]["length"] = length
    result = solve(load_case(data), solver=solver)
    assert_certified(result)
    pull = np.sum([leg.fairlead_force[:2] for leg in result.legs], axis=0)
    assert pull[0] == pytest.approx(-force, rel=1e-9)
    assert abs(pull[1]) < 1e-9 * force
    assert result.body["x_m"] > 0 and result.stability.stable


@pytest.mark.parametrize("weight, mass", [(-1.6e-5, 1e5), (1.6e-5, 1e5), (0.0, 1e5),
                                          (0.0, 10.0)])
@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_a_pendulum_on_a_near_neutral_line_hangs_straight_down(weight, mass, solver):
    """A bob on a 100.5 m line whose weight in water is a millionth of its weight in air
    (MoorDyn's pendulum tests have one), starting slack and off to the side. The scene's
    force scale came from the line weights alone (1e-3 N here: the solve gave up with a
    3.97e9 N residual), or for a weightless line from 1 % of its EA (1e7 N against a 10 kg
    bob's 98 N: no equilibrium). The bob hangs below the fixed point at the stretched
    length."""
    ea, length = 1.0e9, 100.5
    case = load_case({
        "name": "pendulum",
        "environment": {"depth": 500.0, "water_density": 1000.0, "gravity": 9.80665},
        "line_types": {"main": {"weight_in_water": weight, "ea": ea}},
        "points": [{"name": "top", "position": [0.0, 0.0, 0.0]},
                   {"name": "bob", "position": [10.0, 0.0, -100.0], "free": True,
                    "mass": mass}],
        "lines": [{"name": "rod", "from": "top", "to": "bob",
                   "segments": [{"type": "main", "length": length}]}]})
    result = solve(case, solver=solver)
    tension = mass * 9.80665
    bob = result.points[0]
    assert result.converged
    assert bob["x_m"] == pytest.approx(0.0, abs=1e-9)
    # Weight w L = 1.6e-3 N along the line changes the stretch by ~1e-13 m: below the digits.
    assert bob["z_m"] == pytest.approx(-length * (1.0 + tension / ea), abs=1e-9)
    assert result.lines[0].fairlead_tension_N == pytest.approx(tension, rel=1e-9)
