"""The free surface as a boundary, end to end (issue 20; REFERENCE.md section 7).

A buoyant line whose catenary would rise above z = 0 reaches the surface, floats along it at
constant tension and (if its far end is below) leaves it again. Checked through ``solve``:
the closed form of a floating hose; a one-segment leg against the same leg split into
segments (the multi-segment floating block) and against the lumped-node line in a
vanishing current (the node clipping); buoyant segments of a lazy wave that surface; and the
solver's status when it certifies after a failed IPOPT run.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorsolve import ConvergenceError, load_case, solve


def hose_case(X=100.0, L=120.0, depth=30.0, w=-50.0, ea=None, fz=0.0, cuts=None,
              current=None, elements=20):
    line = {"weight_in_water": w}
    if ea is not None:
        line["ea"] = ea
    env = {"depth": depth}
    if current is not None:
        env["current"] = {"speed": current, "toward_deg": 90}
        line.update(diameter=0.2, drag={"normal": 1.1})
    return load_case({
        "environment": env, "line_types": {"hose": line},
        "legs": [{"name": "H", "anchor": [0, 0], "fairlead": [X, 0, fz],
                  "segments": [{"type": "hose", "length": c} for c in (cuts or [L])]}],
        "solver": {"line_elements": elements}})


def test_floating_hose_matches_the_closed_form():
    """Inextensible hose, anchor 30 m down, fairlead at the surface 100 m away, 120 m long.

    The suspended part is a catenary with its vertex at the surface: with ``a = H/|w|``,
    ``30 = a (cosh(x_s/a) - 1)``, suspended length ``s = a sinh(x_s/a)``, and the rest
    floats: ``100 = x_s + 120 - s``. Solved here by bisection on ``a``.
    """
    def gap(a):
        x_s = a * math.acosh(1 + 30.0 / a)
        return x_s + 120.0 - a * math.sinh(x_s / a) - 100.0
    lo, hi = 1e-3, 1e4
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if gap(mid) < 0 else (lo, mid)
    a = math.sqrt(lo * hi)
    x_s = a * math.acosh(1 + 30.0 / a)
    s = a * math.sinh(x_s / a)
    leg = solve(hose_case()).legs[0]
    assert leg.horizontal_tension_N == pytest.approx(50.0 * a, rel=1e-9)
    assert leg.floating_length_m == pytest.approx(120.0 - s, rel=1e-9)
    assert leg.touchup_from_anchor_m == pytest.approx(x_s, rel=1e-9)
    assert leg.anchor_vertical_N == pytest.approx(50.0 * s, rel=1e-9)
    assert leg.fairlead_vertical_N == pytest.approx(0.0, abs=1e-6)
    assert leg.fairlead_tension_N == pytest.approx(50.0 * a, rel=1e-9)   # constant afloat
    assert np.max(leg.profile["z_m"]) == pytest.approx(0.0, abs=1e-12)


def test_slack_hose_rises_straight_and_floats_loose():
    leg = solve(hose_case(X=60.0)).legs[0]
    assert leg.slack and leg.horizontal_tension_N == 0.0
    assert leg.floating_length_m == pytest.approx(120.0 - 30.0, rel=1e-9)
    assert leg.anchor_vertical_N == pytest.approx(50.0 * 30.0, rel=1e-9)


@pytest.mark.parametrize("fz, cuts", [(0.0, (30.0, 90.0)), (0.0, (10.0, 20.0, 90.0)),
                                      (-8.0, (40.0, 40.0, 40.0))])
@pytest.mark.parametrize("ea", [None, 2e6])
def test_split_into_segments_is_the_same_line(fz, cuts, ea):
    """The multi-segment floating block (and the surface's hold on a joint) against the
    one-segment block: the same line cut in pieces gives the same state."""
    one = solve(hose_case(fz=fz, ea=ea)).legs[0]
    cut = solve(hose_case(fz=fz, ea=ea, cuts=cuts)).legs[0]
    assert one.floating_length_m > 5.0
    for field in ("horizontal_tension_N", "fairlead_vertical_N", "anchor_vertical_N",
                  "floating_length_m"):
        assert getattr(cut, field) == pytest.approx(getattr(one, field), rel=1e-7,
                                                    abs=1e-6), field
    assert cut.touchup_from_anchor_m == pytest.approx(one.touchup_from_anchor_m, abs=2.0)


def test_top_segment_afloat_end_to_end_is_right_or_refused():
    """A top segment floating over its whole length between a joint and a fairlead both on
    the surface: its height equation is degenerate there (Z ~ V|V| at V = 0), so the solve
    may not certify; it must then refuse, and never report another state."""
    one = solve(hose_case(ea=2e6)).legs[0]
    try:
        cut = solve(hose_case(ea=2e6, cuts=(40.0, 40.0, 40.0))).legs[0]
    except ConvergenceError as exc:
        assert "leg H" in exc.reason
        return
    assert cut.horizontal_tension_N == pytest.approx(one.horizontal_tension_N, rel=1e-7)


def test_lumped_node_line_floats_and_converges_to_the_analytic_hose():
    """Lumped nodes in a vanishing current against the analytic floating hose: the error in
    the anchor tension falls with the element count at second order."""
    exact = solve(hose_case(ea=1e7)).legs[0]
    errors = []
    for n in (20, 40, 80):
        leg = solve(hose_case(ea=1e7, current=1e-6, elements=n)).legs[0]
        assert np.max(leg.profile["z_m"]) <= 1e-9
        assert leg.floating_length_m > 0
        errors.append(abs(leg.anchor_tension_N - exact.anchor_tension_N))
    order = [math.log2(errors[k] / errors[k + 1]) for k in range(2)]
    assert min(order) > 1.5, (errors, order)


def lazy_wave(float_weight, fz=0.0):
    return load_case({
        "environment": {"depth": 60},
        "line_types": {"chain": {"weight_in_water": 800.0, "ea": 5e8},
                       "float": {"weight_in_water": float_weight, "ea": 1e8}},
        "legs": [{"name": "A", "anchor": [0, 0], "fairlead": [250, 0, fz],
                  "segments": [{"type": "chain", "length": 100},
                               {"type": "float", "length": 120},
                               {"type": "chain", "length": 80}]}]})


def test_lazy_wave_with_too_much_buoyancy_floats_its_buoyant_segment():
    """Issue 20: the buoyant segment's arch rose 11.7 m into the air, certified."""
    result = solve(lazy_wave(-600.0, fz=-5.0))
    leg = result.legs[0]
    assert leg.segments[1]["floating_length_m"] > 5.0
    assert leg.floating_length_m == pytest.approx(leg.segments[1]["floating_length_m"])
    assert np.max(leg.profile["z_m"]) == pytest.approx(0.0, abs=1e-9)
    assert [w["code"] for w in result.warnings] == ["floating"]
    # Each joint balances: the segment above pulls, the segment below holds.
    for k, joint in enumerate(leg.joints):
        below, above = leg.segments[k], leg.segments[k + 1]
        assert above["bottom_vertical_N"] - below["top_vertical_N"] \
            + joint["seabed_reaction_N"] - joint["surface_reaction_N"] == \
            pytest.approx(0.0, abs=1e-6 * leg.fairlead_tension_N)


def test_lazy_wave_that_stays_submerged_is_unchanged():
    leg = solve(lazy_wave(-300.0)).legs[0]
    assert leg.floating_length_m == 0.0
    assert np.max(leg.profile["z_m"][:-1]) < 0.0


def test_status_is_explained_when_ipopt_stops_early_but_the_point_certifies():
    """Issue 20: status "maximum iterations exceeded" came with converged true and no word."""
    case = load_case({
        "environment": {"depth": 50},
        "line_types": {"c": {"weight_in_water": 100.0, "ea": 1e8}},
        "legs": [{"name": "A", "anchor": [0, 0], "fairlead": [80, 0, 0],
                  "segments": [{"type": "c", "length": 100}]}],
        "solver": {"max_iter": 1}})
    result = solve(case)
    assert result.converged
    status = result.certificate.status
    assert status.startswith("Maximum_Iterations_Exceeded")
    assert "certified after" in status and "Newton polish" in status


def test_folded_line_reports_a_clean_success():
    """Issue 20: the folded line (H = 0, end above the anchor) came with IPOPT's maximum
    iterations; without the bound on u at H = 0 it is an interior root."""
    case = load_case({
        "environment": {"depth": 50},
        "line_types": {"c": {"weight_in_water": 100.0, "ea": 1e8}},
        "legs": [{"name": "A", "anchor": [0, 0, -30], "fairlead": [0, 0, -10],
                  "segments": [{"type": "c", "length": 30}]}]})
    result = solve(case)
    assert result.certificate.status == "Solve_Succeeded"
    assert not result.notes and not result.warnings
    leg = result.legs[0]
    assert leg.fairlead_vertical_N == pytest.approx(2500.0, rel=1e-4)
    assert leg.anchor_vertical_N == pytest.approx(-500.0, rel=1e-3)


def test_a_bare_joint_pulled_out_of_the_water_is_not_blamed_on_a_buoy():
    """Issue 20: a joint without a buoy, lifted out of the water by the floating hose above a
    weightless rope, was reported as "the buoy is too large for this leg". No joint here has
    a buoy; the model has no surface for a joint above a rope: refused, with the reason."""
    case = load_case({
        "environment": {"depth": 40},
        "line_types": {"chain": {"weight_in_water": 300.0, "ea": 1e8},
                       "rope": {"weight_in_water": 0.0, "ea": 1e7},
                       "hose": {"weight_in_water": -400.0, "ea": 1e7}},
        "legs": [{"name": "A", "anchor": [0, 0], "fairlead": [120, 0, 0],
                  "segments": [{"type": "chain", "length": 30}, {"type": "rope", "length": 45},
                               {"type": "hose", "length": 80}]}]})
    with pytest.raises(ConvergenceError) as err:
        solve(case)
    assert "buoy is too large" not in err.value.reason
    assert "a buoy breaking" not in err.value.reason
    assert "joint 2 is" in err.value.reason and "above the still-water level" in err.value.reason


def test_a_buoy_that_breaks_the_surface_is_named():
    """A buoy lifting its joint out of the water: its lift is modelled as fully submerged,
    so the state is refused, naming the buoy."""
    case = load_case({
        "environment": {"depth": 40},
        "line_types": {"chain": {"weight_in_water": 300.0, "ea": 1e8}},
        "legs": [{"name": "A", "anchor": [0, 0], "fairlead": [20, 0, -10],
                  "segments": [{"type": "chain", "length": 50},
                               {"clump": {"weight": -1e5}},
                               {"type": "chain", "length": 30}]}]})
    with pytest.raises(ConvergenceError, match="a buoy breaking the surface"):
        solve(case)


@pytest.mark.parametrize("w_air", [1500.0, 3000.0])
@pytest.mark.parametrize("z_top", [2.0, 8.0])
def test_a_fairlead_in_air_uses_the_weight_in_air(w_air, z_top):
    """Issue 20: a fairlead above the water took the line's weight in water for the part in
    air, without a note. With the line type's weight_in_air the part above the surface is
    its own catenary: the reported end forces, integrated down the line's ODE with the
    weight changing at the surface (tests/reference_ode.py), land on the anchor."""
    from reference_ode import integrate_through_surface
    case = load_case({
        "environment": {"depth": 20.0},
        "line_types": {"c": {"weight_in_water": 1300.0, "ea": 5e8, "weight_in_air": w_air}},
        "legs": [{"name": "A", "anchor": [0, 0, -12.0], "fairlead": [100, 0, z_top],
                  "segments": [{"type": "c", "length": 106.0}]}]})
    result = solve(case)
    leg = result.legs[0]
    ref = integrate_through_surface(H=leg.horizontal_tension_N, V=leg.fairlead_vertical_N,
                                    L=106.0, w_water=1300.0, w_air=w_air, z_top=z_top, ea=5e8)
    assert ref["X"] == pytest.approx(100.0, abs=1e-7 * 106)
    assert ref["Z"] == pytest.approx(z_top + 12.0, abs=1e-7 * 106)
    assert ref["VA"] == pytest.approx(leg.anchor_vertical_N, abs=1e-7 * leg.fairlead_tension_N)
    assert [w["code"] for w in result.warnings] == ["end_in_air"]
    assert "weight in air" in result.warnings[0]["message"]
    # Without the weight in air the part above is taken with the weight in water, and the
    # warning says so.
    plain = load_case({**case.source, "line_types": {"c": {"weight_in_water": 1300.0,
                                                           "ea": 5e8}}})
    warned = solve(plain)
    assert "weight_in_air" in warned.warnings[0]["message"]
    assert warned.legs[0].fairlead_vertical_N < leg.fairlead_vertical_N


def test_weight_in_air_is_validated_and_comes_from_the_catalogue():
    from moorsolve import CaseError
    base = {"environment": {"depth": 20.0},
            "legs": [{"name": "A", "anchor": [0, 0], "fairlead": [100, 0, 5.0],
                      "segments": [{"type": "c", "length": 110.0}]}]}
    with pytest.raises(CaseError, match=r"line_types.c.weight_in_air.*less than the weight"):
        load_case({**base, "line_types": {"c": {"weight_in_water": 1300.0,
                                                "weight_in_air": 1000.0}}})
    case = load_case({**base, "line_types": {"c": {"catalog": "studless_r3",
                                                   "diameter": "81 mm"}}})
    lt = case.line_types["c"]
    assert lt.weight_in_air == pytest.approx(0.0199 * 81**2 * 9.80665, rel=1e-12)
    assert lt.weight_in_air > lt.weight_in_water
