"""Study outputs: stiffness, restoring curves, natural periods, exact sensitivities.

Physical-property tier: the AD stiffness is symmetric (the legs' horizontal pull is a
central force H(X), which has a potential) and equals central differences of re-solved
leg equilibria at imposed offsets; AD sensitivities equal central differences of
re-solved equilibria of edited cases.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import moorsolve
from moorsolve.model.paths import with_values
from moorsolve.studies.stiffness import (mooring_force, natural_periods, restoring_curve,
                                   stiffness)
from conftest import ROOT

CASES = ROOT / "cases"
TOL = 1e-12


def _case(name, edits=None):
    case = moorsolve.load_case(CASES / name)
    return moorsolve.load_case(with_values(case.source, edits)) if edits else case


def _fd_stiffness(case, position, h=1e-3, h_deg=1e-4):
    """Central differences of the mooring force at imposed offsets (legs re-solved)."""
    K = np.zeros((3, 3))
    for j in range(3):
        step = h_deg if j == 2 else h
        e = np.zeros(3)
        e[j] = step
        fp, _ = mooring_force(case, position + e)
        fm, _ = mooring_force(case, position - e)
        K[:, j] = -(fp - fm) / (2 * step) * (180 / math.pi if j == 2 else 1.0)
    return K


def planar(K):
    """The surge, sway, yaw block of a 6x6 stiffness."""
    return np.asarray(K)[np.ix_((0, 1, 5), (0, 1, 5))]


def _normalised(K):
    d = np.sqrt(np.abs(np.diag(K)))
    d[d == 0] = 1.0
    return K / np.outer(d, d)


# Friction acts on the stretch of the grounded chain, so it needs an elastic line (a soft
# one, so the effect is large).
ELASTIC = {"line_types.chain.ea": 2.0e6}
FRICTION = {"environment.seabed.friction": 0.6, **ELASTIC}


@pytest.mark.parametrize("name, edits", [("floating_dock.yaml", None),
                                         ("buoy_vida.yaml", None),
                                         ("buoy_vida.yaml", FRICTION),
                                         ("ship_97m.yaml", None)])
def test_stiffness_is_symmetric_and_matches_finite_differences(name, edits):
    case = _case(name, edits)
    result = moorsolve.solve(case, tol=TOL)
    K6 = stiffness(result)
    assert K6.shape == (6, 6)
    K = planar(K6)
    # Symmetric to round-off, friction or not (see stiffness' Notes).
    assert np.max(np.abs(K - K.T)) <= 1e-12 * np.max(np.abs(K))
    b = result.body
    Kfd = _fd_stiffness(case, np.array([b["x_m"], b["y_m"], b["yaw_deg"]]))
    assert np.max(np.abs(_normalised(K) - _normalised(Kfd))) < 1e-5
    # Translational stiffness is positive definite for a spread mooring.
    assert np.all(np.linalg.eigvalsh(K[:2, :2]) > 0)
    assert np.allclose(planar(moorsolve.stiffness(result)), K, rtol=0,
                       atol=1e-9 * np.max(np.abs(K)))


def test_friction_changes_stiffness_but_keeps_it_symmetric():
    k0 = planar(stiffness(_case("buoy_vida.yaml", ELASTIC)))
    k1 = planar(stiffness(_case("buoy_vida.yaml", FRICTION)))
    assert not np.allclose(k0[:2, :2], k1[:2, :2], rtol=1e-3)
    assert abs(k1[0, 1] - k1[1, 0]) <= 1e-12 * np.max(np.abs(k1))


def test_taut_weightless_legs_analytic():
    """Two horizontal weightless elastic legs along x, pretensioned: K_xx = 2 EA / L
    (axial) and K_yy = 2 T / X (geometric), K_psi = 2 T r (r + X) / X with fairleads at
    +-r (the moment arm grows with the transverse offset of each fairlead)."""
    EA, L, X, r = 1.0e7, 99.0, 100.0, 5.0
    T = EA * (X / L - 1.0)
    leg = lambda name, ax, fx: {"name": name, "anchor": [ax, 0.0, 0.0],  # noqa: E731
                                "fairlead": [fx, 0.0, 0.0],
                                "segments": [{"type": "rope", "length": L}]}
    case = moorsolve.load_case({
        "name": "taut pair", "environment": {"depth": 50.0},
        "line_types": {"rope": {"weight_in_water": 0.0, "ea": EA}},
        "body": {"free": []},
        "legs": [leg("E", r + X, r), leg("W", -r - X, -r)]})
    K = planar(stiffness(case))
    assert K[0, 0] == pytest.approx(2 * EA / L, rel=1e-9)
    assert K[1, 1] == pytest.approx(2 * T / X, rel=1e-9)
    assert K[2, 2] == pytest.approx(2 * T * r * (r + X) / X, rel=1e-9)
    assert np.allclose(K[0, 1:], 0, atol=1e-6) and abs(K[1, 2]) < 1e-6 * K[2, 2]


def test_legs_alone_without_body():
    data = dict(_case("buoy_vida.yaml").source)
    data.pop("body")
    data["environment"] = {k: v for k, v in data["environment"].items() if k != "wind"}
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case, tol=TOL)
    K = planar(stiffness(result))
    Kfd = _fd_stiffness(case, np.zeros(3))
    assert np.max(np.abs(_normalised(K[:2, :2]) - _normalised(Kfd[:2, :2]))) < 1e-5
    # Three legs 120 deg apart: isotropic in the plane.
    assert K[0, 0] == pytest.approx(K[1, 1], rel=1e-3)


def test_restoring_curve_opposes_offset_and_passes_through_equilibrium():
    case = _case("ship_97m.yaml")
    result = moorsolve.solve(case, tol=TOL)
    about = (result.body["x_m"], 0.0, 0.0)
    curve = restoring_curve(case, "surge", [-2.0, -1.0, 0.0, 1.0, 2.0], about=about)
    fx = curve["force"][:, 0]
    # At the equilibrium the legs balance the body loads exactly.
    total_load = sum(v[0] for v in result.loads.values())
    assert fx[2] == pytest.approx(-total_load, rel=1e-8)
    assert np.all(np.diff(fx) < 0)              # restoring: more offset, less pull ahead
    assert np.all(np.diff(curve["max_tension_N"]) < 0)   # moving toward the anchor slackens
    with pytest.raises(ValueError, match="dof"):
        restoring_curve(case, "surge_x", [0.0])


def test_natural_periods_diagonal_and_coupled():
    K = np.diag([4.0e4, 9.0e4, 1.0e8])
    periods = natural_periods(K, 1.0e6, added_mass=[1e5, 2e5, 0.0], inertia=1.0e9)
    expected = [2 * math.pi * math.sqrt(m / k) for m, k in
                [(1.1e6, 4.0e4), (1.2e6, 9.0e4), (1.0e9, 1.0e8)]]
    assert sorted(periods.periods_s, reverse=True) == pytest.approx(
        sorted(expected, reverse=True), rel=1e-12)
    assert [periods.diagonal_s[d] for d in ("surge", "sway", "yaw")] == pytest.approx(
        expected, rel=1e-12)
    # Two equal masses coupled: w^2 = (k -+ c) / m.
    Kc = np.array([[3.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 1.0]])
    coupled = natural_periods(Kc, 2.0, dofs=("surge", "sway"))
    assert sorted(coupled.periods_s) == pytest.approx(
        [2 * math.pi / math.sqrt(4.0 / 2.0), 2 * math.pi / math.sqrt(2.0 / 2.0)])
    with pytest.raises(ValueError, match="inertia"):
        natural_periods(K, 1.0e6)


def test_natural_periods_of_the_dock_from_its_stiffness():
    K = planar(stiffness(_case("floating_dock.yaml")))
    m = 2.0e7   # kg (order of a 250 m dock's displacement; chosen)
    p = natural_periods(K, m, added_mass=[0.1 * m, 0.8 * m, 0.0], inertia=m * 70.0**2)
    assert np.all(np.isfinite(p.periods_s)) and np.all(p.periods_s > 0)
    # Surge period from the diagonal: 2 pi sqrt(1.1 m / K_xx).
    assert p.diagonal_s["surge"] == pytest.approx(2 * math.pi * math.sqrt(1.1 * m / K[0, 0]))


# ---- sensitivities ---------------------------------------------------------------------


def _outputs(result, names):
    d = result.to_dict(profiles=False)
    legs = {leg["name"]: leg for leg in d["legs"]}
    out = []
    for n in names:
        if n in ("x_m", "y_m", "yaw_deg"):
            out.append(d["body"][n])
        else:
            leg, field = n[len("legs["):].split("].")
            out.append(legs[leg][field])
    return np.array(out)


def _edit_leg(case, name, **changes):
    """``case`` with leg ``name``'s line (its own copy of the line type) or ends edited."""
    legs = []
    for leg in case.legs:
        if leg.name == name:
            lt = leg.line_type
            lt = dataclasses.replace(lt, **{k: v for k, v in changes.items()
                                            if k in ("ea", "weight_in_water")})
            seg = dataclasses.replace(leg.segments[0], line_type=lt,
                                      length=changes.get("length", leg.segments[0].length))
            leg = dataclasses.replace(
                leg, segments=(seg,),
                a=dataclasses.replace(leg.a, position=changes.get("anchor", leg.anchor)),
                b=dataclasses.replace(leg.b, position=changes.get("fairlead", leg.fairlead)))
        legs.append(leg)
    return dataclasses.replace(case, lines=tuple(legs))


def _leg_editor(leg, field):
    def edit(case, value):
        return _edit_leg(case, leg, **{field: value})
    return edit


def _vector_editor(leg, field, k):
    def edit(case, value):
        v = list(getattr(next(lg for lg in case.legs if lg.name == leg), field))
        v[k] = value
        return _edit_leg(case, leg, **{field: tuple(v)})
    return edit


def _path_editor(path):
    def edit(case, value):
        return moorsolve.load_case(with_values(case.source, {path: value}))
    return edit


def _fd_check(case, outputs, params):
    """``params``: name -> (editor, value, step). Checks every output/parameter pair."""
    result = moorsolve.solve(case, tol=TOL)
    sens = moorsolve.sensitivity(result, outputs, list(params))
    for j, (name, (edit, value, h)) in enumerate(params.items()):
        up = moorsolve.solve(edit(case, value + h), tol=TOL)
        down = moorsolve.solve(edit(case, value - h), tol=TOL)
        fd = (_outputs(up, outputs) - _outputs(down, outputs)) / (2 * h)
        ad = sens.matrix[:, j]
        scale = np.maximum(np.abs(fd), np.abs(ad))
        # Relative 1e-5, with a floor for outputs that do not move (a slack quantity).
        floor = 1e-9 * np.maximum(np.abs(_outputs(result, outputs)), 1.0) / abs(h)
        bad = np.abs(ad - fd) > 1e-5 * scale + floor
        assert not bad.any(), (name, [o for o, b in zip(outputs, bad) if b], ad, fd)
    return sens


DOCK_OUTPUTS = ["x_m", "y_m", "yaw_deg", "legs[L3].fairlead_tension_N",
                "legs[L3].anchor_vertical_N", "legs[L3].horizontal_tension_N",
                "legs[L9].anchor_tension_N", "legs[L9].grounded_length_m"]


def test_dock_sensitivities_match_finite_differences():
    case = _case("floating_dock.yaml", {"body.loads.force": [2.0e4, -1.0e4, 5.0e5]})
    leg = case.legs[2]
    params = {
        "legs[L3].length": (_leg_editor("L3", "length"), leg.length, 1e-3),
        "legs[L3].ea": (_leg_editor("L3", "ea"), leg.line_type.ea, 1e-3 * leg.line_type.ea),
        "legs[L3].weight": (_leg_editor("L3", "weight_in_water"),
                            leg.line_type.weight_in_water, 1e-3),
        "legs[L3].anchor_x": (_vector_editor("L3", "anchor", 0), leg.anchor[0], 1e-3),
        "legs[L3].anchor_y": (_vector_editor("L3", "anchor", 1), leg.anchor[1], 1e-3),
        "legs[L3].fairlead_z": (_vector_editor("L3", "fairlead", 2), leg.fairlead[2], 1e-3),
        "environment.current.speed": (_path_editor("environment.current.speed"), 1.0, 1e-4),
        "environment.wind.speed": (_path_editor("environment.wind.speed"), 40.0, 1e-3),
        "environment.wind.toward_deg": (_path_editor("environment.wind.toward_deg"),
                                        70.0, 1e-3),
        "environment.waves.hs": (_path_editor("environment.waves.hs"), 2.0, 1e-4),
        "body.loads.force[0]": (_path_editor("body.loads.force[0]"), 2.0e4, 10.0),
        "body.loads.force[2]": (_path_editor("body.loads.force[2]"), 5.0e5, 100.0),
        "line_types[chain81].ea": (_path_editor("line_types.chain81.ea"), 5.6e8, 5.6e5),
    }
    sens = _fd_check(case, DOCK_OUTPUTS, params)
    # More chain on L3 slackens it.
    assert sens["legs[L3].fairlead_tension_N", "legs[L3].length"] < 0


def test_buoy_sensitivities_with_friction_and_grounded_chain():
    case = _case("buoy_vida.yaml", {"environment.seabed.friction": 0.4, **ELASTIC})
    outputs = ["x_m", "y_m", "legs[W].fairlead_tension_N", "legs[W].grounded_length_m",
               "legs[NNE].anchor_horizontal_N", "legs[NNE].grounded_length_m"]
    leg = case.legs[2]
    params = {
        "legs[W].length": (_leg_editor("W", "length"), leg.length, 1e-4),
        "legs[W].weight": (_leg_editor("W", "weight_in_water"),
                           leg.line_type.weight_in_water, 1e-3),
        "legs[W].anchor_x": (_vector_editor("W", "anchor", 0), leg.anchor[0], 1e-4),
        "environment.seabed.friction": (_path_editor("environment.seabed.friction"),
                                        0.4, 1e-4),
        "environment.wind.speed": (_path_editor("environment.wind.speed"), 30.0, 1e-3),
    }
    _fd_check(case, outputs, params)


def test_sensitivity_rejects_what_it_cannot_differentiate():
    result = moorsolve.solve(_case("floating_dock.yaml"))
    with pytest.raises(ValueError, match="body.loads.force"):
        moorsolve.sensitivity(result, "x_m", "body.loads.force[0]")
    buoy = moorsolve.solve(_case("buoy_vida.yaml"))
    with pytest.raises(ValueError, match="no current"):
        moorsolve.sensitivity(buoy, "x_m", "environment.current.speed")
    with pytest.raises(ValueError, match="seabed"):
        moorsolve.sensitivity(result, "x_m", "legs[L3].anchor_z")
    with pytest.raises(ValueError, match="no leg 'L99'"):
        moorsolve.sensitivity(result, "legs[L99].fairlead_tension_N", "legs[L3].length")
    with pytest.raises(ValueError, match="output"):
        moorsolve.sensitivity(result, "legs[L3].colour", "legs[L3].length")
    with pytest.raises(ValueError, match="parameter"):
        moorsolve.sensitivity(result, "x_m", "legs[L3].colour")
    ship = moorsolve.solve(_case("ship_97m.yaml"))
    with pytest.raises(ValueError, match="no seabed friction"):
        moorsolve.sensitivity(ship, "x_m", "environment.seabed.friction")
