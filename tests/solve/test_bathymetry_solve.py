"""Lines on a bathymetry grid (issue 19, item 3): a grid that holds a plane gives today's
sloped-seabed solution; on a curved seabed every line lies on its own plane through the
seabed under its anchor and under its touchdown, balanced, above the surface within the
reported deviation; a line through the surface fails the audit."""

import copy

import numpy as np
import pytest
import yaml

from moorsolve import load_case, solve
from moorsolve.audit import AuditFailure
from moorsolve.solve.lines.bathymetry import TOUCHDOWN_REL
from conftest import CASES


def _grid(xs, ys, depth):
    return {"x": [float(v) for v in xs], "y": [float(v) for v in ys],
            "depth": [[float(depth(x, y)) for x in xs] for y in ys]}


def _sloped_dock():
    return yaml.safe_load((CASES / "floating_dock_sloped.yaml").read_text())


def test_a_grid_holding_the_plane_reproduces_the_sloped_seabed():
    plane = _sloped_dock()
    grid = copy.deepcopy(plane)
    # The dock's plane (2 % rise toward +y) sampled on a coarse, uneven grid.
    grid["environment"]["seabed"] = {"bathymetry": _grid(
        [-300, -120, 40, 310], [-210, -15, 200], lambda x, y: 20.85 - 0.02 * y)}
    a, b = solve(load_case(plane)), solve(load_case(grid))
    assert "bathymetry" in b.effects and "bathymetry" not in a.effects
    for la, lb in zip(a.legs, b.legs):
        scale = max(la.fairlead_tension_N, 1.0)
        for key in ("fairlead_tension_N", "anchor_tension_N", "horizontal_tension_N",
                    "anchor_vertical_N"):
            assert getattr(lb, key) == pytest.approx(getattr(la, key), abs=1e-9 * scale)
        assert lb.grounded_length_m == pytest.approx(la.grounded_length_m, abs=1e-9 * 122.52)
        assert lb.seabed_plane == pytest.approx((-20.85, 0.0, 0.02), abs=1e-12)
        assert lb.seabed_deviation_m < 1e-9
        assert la.seabed_plane is None and la.seabed_deviation_m is None
    for key in ("x_m", "y_m", "yaw_deg"):
        assert b.body[key] == pytest.approx(a.body[key], abs=1e-9)
    assert not [n for n in b.notes if "departs" in n]


def _one_leg(depth_fn, friction=0.0, tolerance=None):
    seabed = {"friction": friction,
              "bathymetry": _grid(np.arange(-50, 551, 25.0), [-100.0, 0.0, 100.0], depth_fn)}
    if tolerance is not None:
        seabed["tolerance"] = tolerance
    return {"environment": {"depth": 100.0, "seabed": seabed},
            "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5e8}},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [400.0, 0.0, -5.0],
                      "segments": [{"type": "chain", "length": 460}]}]}


def _bank(height, at=60.0):
    """A seabed rising 3 % toward the fairlead with a bank of ``height`` under the chain."""
    return lambda x, y: 100.0 - 0.03 * x - height * np.exp(-((x - at) / 50.0) ** 2)


@pytest.mark.parametrize("friction", [0.0, 0.5])
def test_a_curved_seabed_by_physics(friction):
    case = load_case(_one_leg(_bank(0.05), friction))
    res = solve(case)
    leg = res.legs[0]
    env = case.environment
    assert res.converged and leg.grounded_length_m > 50.0
    z0, gx, gy = leg.seabed_plane
    # The plane passes through the surface under the anchor and under the touchdown.
    assert z0 + gx * 0.0 + gy * 0.0 == pytest.approx(env.seabed_z(0.0, 0.0), abs=1e-9)
    tx, ty, tz = leg.touchdown_point
    assert tz == pytest.approx(env.seabed_z(tx, ty), abs=1e-6 * 460)
    assert tz == pytest.approx(z0 + gx * tx + gy * ty, abs=1e-9)
    # The plane's slope is the chord's, not the local slope at the anchor (0.03 plus the bank).
    assert gx == pytest.approx((env.seabed_z(tx, ty) - env.seabed_z(0, 0)) / tx, abs=1e-6)
    # The grounded run lies on the plane; the profile is above the grid's surface within
    # the reported deviation, and the deviation is what the profile shows.
    x, y, z = (np.asarray(leg.profile[k]) for k in ("x_m", "y_m", "z_m"))
    bed = env.seabed_z(x, y)
    grounded = x <= tx - 1e-6
    np.testing.assert_allclose(z[grounded], (z0 + gx * x + gy * y)[grounded], atol=1e-9)
    assert np.all(z >= bed - leg.seabed_deviation_m - 1e-12)
    assert leg.seabed_deviation_m == pytest.approx(
        max(np.max(np.abs(z - bed)[grounded]), np.max(bed - z)), rel=1e-9, abs=1e-12)
    assert 1e-4 < leg.seabed_deviation_m < env.seabed.tolerance
    # Balance: the fairlead pull's vertical part carries the suspended weight (frictionless
    # slope's reaction is normal; checked by the certificate), and the horizontal tension
    # at the fairlead equals the reported one.
    assert res.certificate.force_N < 1e-6 * leg.fairlead_tension_N
    assert leg.horizontal_tension_N == pytest.approx(
        np.hypot(*leg.fairlead_force[:2]), rel=1e-12)


def test_the_planes_are_settled():
    """Re-solving with the planes from the reported touchdowns moves no touchdown."""
    data = _one_leg(_bank(0.05))
    res = solve(load_case(data))
    leg = res.legs[0]
    assert any("settled in" in n for n in res.notes)
    # Cutting the grid down to the reported plane gives the same touchdown (the plane is
    # the chord to the touchdown, so the iteration's fixed point).
    z0, gx, gy = leg.seabed_plane
    flat = copy.deepcopy(data)
    flat["environment"]["seabed"] = {"gradient": [gx, gy]}
    flat["environment"]["depth"] = -z0
    ref = solve(load_case(flat)).legs[0]
    assert leg.touchdown_from_anchor_m == pytest.approx(ref.touchdown_from_anchor_m,
                                                        abs=10 * TOUCHDOWN_REL * 460)
    assert leg.fairlead_tension_N == pytest.approx(ref.fairlead_tension_N, rel=1e-6)


def test_the_seabed_under_the_touchdown_decides_the_plane():
    """The model's limit, measured: a bank under the touchdown (about 363 m out) moves it;
    the same bank in the middle of the grounded run changes only the deviation."""
    flat = solve(load_case(_one_leg(_bank(0.0)))).legs[0]
    middle = solve(load_case(_one_leg(_bank(0.5, at=180.0), tolerance=1.0))).legs[0]
    under = solve(load_case(_one_leg(_bank(0.5, at=360.0), tolerance=1.0))).legs[0]
    assert abs(under.touchdown_from_anchor_m - flat.touchdown_from_anchor_m) > 0.5
    assert under.fairlead_tension_N < flat.fairlead_tension_N - 500.0     # a shallower end
    assert abs(middle.touchdown_from_anchor_m - flat.touchdown_from_anchor_m) < 1e-2
    assert middle.seabed_deviation_m == pytest.approx(0.5, rel=0.05)


def test_a_departure_beyond_the_tolerance_is_noted_then_fails_the_audit():
    res = solve(load_case(_one_leg(_bank(0.3), tolerance=0.5)))
    leg = res.legs[0]
    assert 0.05 < leg.seabed_deviation_m < 0.5
    note = [n for n in res.notes if "departs" in n]
    assert note and f"{leg.seabed_deviation_m:.3g} m" in note[0]
    with pytest.raises(AuditFailure, match="below the seabed.*tolerance is 0.01 m"):
        solve(load_case(_one_leg(_bank(0.3), tolerance=0.01)))


def test_a_trough_deeper_than_the_tolerance_under_the_grounded_run_is_a_warning():
    """A trough (a negative bank) under the grounded run leaves the modelled chain lying
    straight above the surface by more than the tolerance: the result stands (the chain
    would bridge or sag into it), with a warning an engineer cannot miss, not a note."""
    res = solve(load_case(_one_leg(_bank(-0.4, at=180.0), tolerance=0.2)))
    leg = res.legs[0]
    assert res.converged and leg.grounded_length_m > 180.0
    assert 0.2 < leg.seabed_deviation_m < 0.45
    (warning,) = [w for w in res.warnings if w["code"] == "seabed_departure"]
    assert warning["leg"] == "A" and f"{leg.seabed_deviation_m:.3g} m" in warning["message"]
    assert not [n for n in res.notes if "departs" in n]
    assert res.to_dict()["warnings"][-1]["code"] == "seabed_departure"


def test_a_suspended_line_is_clear_of_the_surface():
    # A taut leg over a seabed falling away from the anchor: nothing touches down.
    data = _one_leg(lambda x, y: 100.0 + 0.02 * x)
    data["legs"][0]["segments"][0]["length"] = 405.0
    leg = solve(load_case(data)).legs[0]
    assert leg.grounded_length_m == 0.0
    assert leg.seabed_deviation_m == 0.0


def test_shipped_bathymetry_case():
    case = load_case(CASES / "dock_bathymetry.yaml")
    assert case.environment.seabed.bathymetry is not None
    res = solve(case)
    devs = [leg.seabed_deviation_m for leg in res.legs]
    assert max(devs) < case.environment.seabed.tolerance
    assert any(leg.grounded_length_m > 0 for leg in res.legs)


def test_stiffness_on_a_plane_grid_is_the_planes():
    """Studies take each line's plane where the solve left it (result_parameters)."""
    from moorsolve.studies.stiffness import stiffness

    plane = _sloped_dock()
    grid = copy.deepcopy(plane)
    grid["environment"]["seabed"] = {"bathymetry": _grid(
        [-300, 300], [-210, 200], lambda x, y: 20.85 - 0.02 * y)}
    Ka = np.asarray(stiffness(solve(load_case(plane)))[0])
    Kb = np.asarray(stiffness(solve(load_case(grid)))[0])
    np.testing.assert_allclose(Kb, Ka, rtol=0, atol=1e-9 * np.max(np.abs(Ka)))


def test_design_optimisation_on_a_grid_is_refused_by_name():
    from moorsolve.errors import CaseError
    from moorsolve.io.study_file import load_study

    case = load_case(CASES / "dock_bathymetry.yaml")
    with pytest.raises(CaseError, match="bathymetry grid are not modelled") as err:
        load_study(CASES / "studies" / "floating_dock_chain.yaml", case)
    assert err.value.field == "variables"


def test_damaged_conditions_share_a_problem_whatever_the_lines_are_called():
    """A problem serves every scene of its structure: a damaged condition (a line removed)
    reuses one built for other line names, and each line keeps its own plane by position."""
    from moorsolve.checks import run_checks

    case = load_case(CASES / "dock_bathymetry.yaml")
    report = run_checks(case)
    assert all(c.solved for c in report.conditions)
    intact = solve(case)
    for condition in report.conditions[1:]:
        for leg in condition.result.legs:
            z0, gx, gy = leg.seabed_plane
            ax, ay, az = leg.anchor
            assert z0 + gx * ax + gy * ay == pytest.approx(az, abs=1e-9)
            assert leg.seabed_deviation_m < case.environment.seabed.tolerance
    assert report.conditions[0].result.legs[7].seabed_plane == pytest.approx(
        intact.legs[7].seabed_plane, abs=1e-12)


def test_a_sweep_on_a_grid_solves_each_point_with_settled_planes():
    """Sweeps take full solves on a grid (the kernel alone would keep the first planes)."""
    import moorsolve

    case = load_case(CASES / "dock_bathymetry.yaml")
    out = moorsolve.sweep(case, {"environment.wind.toward_deg": [70.0, 90.0]})
    for k, heading in enumerate((70.0, 90.0)):
        data = yaml.safe_load((CASES / "dock_bathymetry.yaml").read_text())
        data["environment"]["wind"]["toward_deg"] = heading
        one = solve(_load_beside(data))
        for leg in one.legs:
            got = np.asarray(out[f"{leg.name}.fairlead_tension_N"])[k]
            assert got == pytest.approx(leg.fairlead_tension_N, rel=1e-7)


def _load_beside(data):
    """A case dict of cases/ with its grid file named absolutely."""
    data["environment"]["seabed"]["bathymetry"] = str(CASES / "dock_bathymetry_seafloor.txt")
    return load_case(data)


def test_planes_that_do_not_settle_are_said_so(monkeypatch):
    """With the iteration cut to one solve, the touchdown on a curved seabed is still moving:
    the note says so, and the deviation measures how far the chain is off the surface."""
    import importlib

    bathymetry = importlib.import_module("moorsolve.solve.lines.bathymetry")
    monkeypatch.setattr(bathymetry, "MAX_ROUNDS", 1)
    res = solve(load_case(_one_leg(_bank(0.05), tolerance=1.0)))
    leg = res.legs[0]
    assert any("did not settle in 1 solves" in n for n in res.notes)
    # The reported plane is the one the chain lies on (the first: to under the fairlead).
    z0, gx, gy = leg.seabed_plane
    x, z = np.asarray(leg.profile["x_m"]), np.asarray(leg.profile["z_m"])
    grounded = x < leg.touchdown_from_anchor_m - 1e-6
    np.testing.assert_allclose(z[grounded], (z0 + gx * x)[grounded], atol=1e-9)
    # Unsettled, the plane's far end is not where the chain leaves the surface: the
    # touchdown point is off the grid by far more than once settled.
    monkeypatch.undo()
    case = load_case(_one_leg(_bank(0.05)))
    settled = solve(case).legs[0]
    off = [abs(lg.touchdown_point[2] - case.environment.seabed_z(*lg.touchdown_point[:2]))
           for lg in (leg, settled)]
    assert off[0] > 1e-4 and off[1] < 1e-6 * 460
