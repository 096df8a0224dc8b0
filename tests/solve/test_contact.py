"""Fenders, walls, piles and pile guides against hand-derived references (issue 15).

Every reference below is derived by hand in its docstring: statics of a rigid body on one or
two supports, with finite rotations where the body turns. Reactions and compressions agree
to 1e-6 relative (the solves are certified at 1e-12), and in or out of contact exactly.
Both solvers are run on each.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import moorsolve
from moorsolve import CaseError, load_case

SOLVERS = ("ipopt", "newton")
K = 2.0e6          # [N/m] linear fender stiffness
D = 10.0           # [m] fenders at y = +-D in the body frame, on the wall x = 0 at rest
F = 1.0e5          # [N] load onto the wall
EA = 2.0e7         # [N] hawser stiffness
REL = 1e-6


def berth(load, *, k1=K, k2=K, free=("surge", "yaw"), friction=0.0, reaction=None,
          lines=(), points=(), line_types=None) -> dict:
    """A body whose origin lies on the wall x = 0 (outward normal +x), with fenders F1, F2
    at body-frame (0, +-D, 0): both touch the wall at the case-file pose."""
    def fender(name, y, k):
        out = {"name": name, "body": "b", "at": [0, y, 0], "wall": "quay",
               "reaction": reaction if reaction is not None else {"stiffness": k}}
        if reaction is None:
            out["rated_deflection"] = 0.5
        return out
    return {
        "name": "berth test",
        "environment": {"depth": 15.0},
        "line_types": line_types or {"hawser": {"weight_in_water": 0, "ea": EA}},
        "bodies": [{"name": "b", "free": list(free), "loads": {"force": list(load)}}],
        "points": list(points),
        "lines": list(lines) or [
            # A slack line far from everything keeps the case a network case.
            {"name": "idle", "from": [60.0, 0.0, 0.0], "to": {"body": "b", "at": [20, 0, 0]},
             "segments": [{"type": "hawser", "length": 45.0}]}],
        "walls": [{"name": "quay", "point": [0, 0, 0], "normal": [1, 0, 0],
                   "friction": friction}],
        "fenders": [fender("F1", D, k1), fender("F2", -D, k2)],
    }


def solve(data, solver, **kw):
    return moorsolve.solve(load_case(data), solver=solver, tol=1e-12, **kw)


@pytest.mark.parametrize("solver", SOLVERS)
def test_two_fenders_share_a_load(solver):
    """Load F onto the wall through the origin, fenders of different stiffness k1 = 2 k2,
    body free in surge and yaw. With the fenders on the line through the origin (b = 0),
    fender i at (x -+ D sin t, +-D cos t): the moment balance (R1 - R2) D cos t = 0 gives
    R1 = R2 = F/2 at any rotation; each is compressed by its own R/k."""
    r = solve(berth([-F, 0, 0], k1=K, k2=K / 2), solver)
    f1, f2 = r.fender("F1"), r.fender("F2")
    assert f1["in_contact"] and f2["in_contact"]
    assert f1["reaction_N"] == pytest.approx(F / 2, rel=REL)
    assert f2["reaction_N"] == pytest.approx(F / 2, rel=REL)
    assert f1["compression_m"] == pytest.approx(F / (2 * K), rel=REL)
    assert f2["compression_m"] == pytest.approx(F / K, rel=REL)
    # Energy: the area under a linear curve, R^2 / (2 k).
    assert f2["energy_J"] == pytest.approx((F / 2) ** 2 / K, rel=REL)
    # The certificate: penetration within 1e-12 of the length scale (16 m).
    assert r.certificate.penetration_m <= 16e-12 and r.certificate.complementarity_N <= 1e-6


@pytest.mark.parametrize("solver", SOLVERS)
def test_an_offset_load_loads_the_nearer_fender(solver):
    """Load F onto the wall and a moment M (a load off the centre line), equal fenders.
    Fender i at (x -+ D s, +-D c), s, c = sin t, cos t; R_i = -k (x -+ D s).
    Force: R1 + R2 = -2 k x = F.  Moment about the origin: (R1 - R2) D c = M, with
    R1 - R2 = 2 k D s: k D^2 sin 2t = M. So t = asin(M / (k D^2)) / 2 (finite rotation,
    exact) and R1,2 = F/2 +- k D sin t."""
    M = 3.0e5
    r = solve(berth([-F, 0, M]), solver)
    t = 0.5 * math.asin(M / (K * D**2))
    R1, R2 = F / 2 + K * D * math.sin(t), F / 2 - K * D * math.sin(t)
    assert r.fender("F1")["reaction_N"] == pytest.approx(R1, rel=REL)
    assert r.fender("F2")["reaction_N"] == pytest.approx(R2, rel=REL)
    assert r.fender("F1")["compression_m"] == pytest.approx(R1 / K, rel=REL)
    assert r.body["yaw_deg"] == pytest.approx(math.degrees(t), rel=REL)
    # The linearised answer M / (2 D) per fender is off by the rotation: 1e-6 here.
    assert R1 - F / 2 == pytest.approx(M / (2 * D), rel=1e-5)


@pytest.mark.parametrize("solver", SOLVERS)
def test_a_table_fender_is_interpolated_and_its_energy_is_the_area(solver):
    """Two identical table fenders (a maker's rows, linear between them) share F = 2 x
    900 kN. 900 kN lies between the rows (0.3 m, 600 kN) and (0.5 m, 1000 kN): the
    compression is 0.3 + (900 - 600) / (1000 - 600) x 0.2 = 0.45 m; the energy is the area
    up to it: 0.5 x 0.1 x 150 + (150 + 600) / 2 x 0.2 + (600 + 900) / 2 x 0.15
    = 7.5 + 75 + 112.5 = 195 kJ."""
    table = {"table": [[0, 0], [0.1, "150 kN"], [0.3, "600 kN"], [0.5, "1000 kN"],
                       [0.6, "1300 kN"]]}
    r = solve(berth([-1.8e6, 0, 0], reaction=table), solver)
    for name in ("F1", "F2"):
        f = r.fender(name)
        assert f["reaction_N"] == pytest.approx(9.0e5, rel=REL)
        assert f["compression_m"] == pytest.approx(0.45, rel=REL)
        assert f["energy_J"] == pytest.approx(195e3, rel=REL)
        # The table's rated deflection defaults to its last row: 0.6 m.
        assert f["utilisation"] == pytest.approx(0.45 / 0.6, rel=REL)


@pytest.mark.parametrize("solver", SOLVERS)
def test_a_load_away_from_the_quay_is_held_by_hawsers_with_the_fenders_open(solver):
    """Two 8.5 m hawsers from bollards at (-5, +-D, 2) on the quay to the body at
    (3, +-D, 2): chord 8 m, slack at rest. A load F away from the quay (+x) draws them taut:
    T = F/2 each, the chord becomes 8.5 (1 + T/EA) m, so the body moves out by
    x = 8.5 (1 + F/(2 EA)) - 8 and both fenders open by exactly x, with no reaction."""
    points = [{"name": "B1", "position": [-5.0, D, 2.0]},
              {"name": "B2", "position": [-5.0, -D, 2.0]}]
    lines = [{"name": f"H{i}", "from": f"B{i}", "to": {"body": "b", "at": [3.0, y, 2.0]},
              "segments": [{"type": "hawser", "length": 8.5}]}
             for i, y in ((1, D), (2, -D))]
    r = solve(berth([F, 0, 0], free=("surge", "sway", "yaw"), points=points, lines=lines),
              solver)
    x = 8.5 * (1 + F / (2 * EA)) - 8.0
    assert r.body["x_m"] == pytest.approx(x, rel=REL)
    for name in ("F1", "F2"):
        f = r.fender(name)
        assert f["in_contact"] is False
        assert f["reaction_N"] == 0.0 and f["compression_m"] == 0.0
        assert f["gap_m"] == pytest.approx(x, rel=REL)
    for h in r.hawsers:
        assert h["tension_N"] == pytest.approx(F / 2, rel=REL) and not h["slack"]


@pytest.mark.parametrize("solver", SOLVERS)
def test_friction_holds_a_body_pressed_on_the_wall(solver):
    """Normal load N = F onto the wall, tangential load P = 0.2 N along it, friction 0.3:
    P < mu N, the fenders stick. Body free in surge and sway: each fender takes N/2 and,
    slipping by the same s, holds P/2 by friction, which is mu (N/2) s / delta in stick
    (delta = 1 mm, the mobilisation slip): the body is held within s = P delta / (mu N) of
    where it was placed."""
    P, mu = 0.2 * F, 0.3
    r = solve(berth([-F, P, 0], free=("surge", "sway"), friction=mu), solver)
    s = P * 1e-3 / (mu * F)
    assert r.body["y_m"] == pytest.approx(s, rel=REL)
    for name in ("F1", "F2"):
        f = r.fender(name)
        assert f["stick"] is True
        assert f["reaction_N"] == pytest.approx(F / 2, rel=REL)
        assert f["friction_N"] == pytest.approx(P / 2, rel=REL)
        assert f["friction_N"] < mu * f["reaction_N"]


@pytest.mark.parametrize("solver", SOLVERS)
def test_friction_slips_when_the_load_exceeds_it_and_a_line_takes_the_rest(solver):
    """P = 0.5 N > mu N with mu = 0.3: the fenders slip, each holding exactly mu N/2 against
    the slip (body free in surge and sway), and a spring line along -y takes P - mu N. The
    line runs from a bollard
    30 m down the quay at x = -N/(2k) (where the compressed fenders put the body's points),
    so at equilibrium it pulls exactly along -y: T = P - mu N, chord 30 (1 + T/EA)."""
    P, mu = 0.5 * F, 0.3
    x_face = -F / (2 * K)
    points = [{"name": "S", "position": [x_face, -30.0 - D, 0.0]}]
    lines = [{"name": "spring", "from": "S", "to": {"body": "b", "at": [0, -D, 0]},
              "segments": [{"type": "hawser", "length": 30.0}]}]
    r = solve(berth([-F, P, 0], free=("surge", "sway"), friction=mu, points=points,
                    lines=lines), solver)
    T = P - mu * F
    assert r.leg("spring").fairlead_tension_N == pytest.approx(T, rel=REL)
    assert r.body["y_m"] == pytest.approx(30.0 * T / EA, rel=REL)
    for name in ("F1", "F2"):
        f = r.fender(name)
        assert f["stick"] is False
        assert f["friction_N"] == pytest.approx(mu * F / 2, rel=REL)
        assert f["reaction_N"] == pytest.approx(F / 2, rel=REL)


@pytest.mark.parametrize("solver", SOLVERS)
def test_rigid_contacts_are_not_penetrated(solver):
    """Rigid contact points take F/2 each (symmetry) and the body stays exactly on the
    wall: the certificate's penetration is at round-off."""
    r = solve(berth([-F, 0, 0], reaction="rigid"), solver)
    assert r.body["x_m"] == pytest.approx(0.0, abs=16e-12)
    for name in ("F1", "F2"):
        assert r.fender(name)["reaction_N"] == pytest.approx(F / 2, rel=REL)
        assert r.fender(name)["compression_m"] == 0.0
    assert r.certificate.penetration_m <= 16e-12


EI = 6.8e8          # [N m^2] a steel pile, 0.8 m diameter, 16 mm wall


def pontoon(force, *, free=("surge", "sway", "yaw"), clearance=0.05, pads=8,
            bending=None) -> dict:
    """A pontoon on two guide piles at (+-10, 0), radius 0.4 m; its collars are centred on
    them at the case pose, 1 m above still water; the seabed is 8 m down."""
    piles = [{"name": "P1", "position": [10.0, 0.0], "radius": 0.4, "top": 4.0},
             {"name": "P2", "position": [-10.0, 0.0], "radius": 0.4, "top": 4.0}]
    if bending:
        for pile in piles:
            pile["bending_stiffness"] = bending
    return {
        "name": "pontoon on piles", "environment": {"depth": 8.0},
        "line_types": {"rope": {"weight_in_water": 0, "ea": 1e7}},
        "bodies": [{"name": "p", "free": list(free), "loads": {"force": list(force)}}],
        "lines": [{"name": "idle", "from": [0.0, 50.0, 0.0],
                   "to": {"body": "p", "at": [0, 0, 0]},
                   "segments": [{"type": "rope", "length": 60.0}]}],
        "piles": piles,
        "guides": [{"name": "G1", "body": "p", "at": [10.0, 0.0, 1.0], "pile": "P1",
                    "clearance": clearance, "pads": pads},
                   {"name": "G2", "body": "p", "at": [-10.0, 0.0, 1.0], "pile": "P2",
                    "clearance": clearance, "pads": pads}],
    }


@pytest.mark.parametrize("solver", SOLVERS)
def test_pile_guides_hold_a_pontoon(solver):
    """Rigid piles, a sideways load F (+y) through the centre, the pontoon free in sway and
    yaw: the collars move the clearance c across until the pad on their -y side bears on
    the pile; the moment balance about the centre, R1 x 10 = R2 x 10, shares F equally
    (sway alone would leave the share indeterminate: two rigid supports in parallel). The
    pile, a cantilever from the seabed (z = -8), carries F/2 at the collar (z = 1): moment
    F/2 x 9 m."""
    r = solve(pontoon([0, F, 0], free=("sway", "yaw")), solver)
    assert r.body["y_m"] == pytest.approx(0.05, rel=REL)
    for name in ("G1", "G2"):
        g = r.guide(name)
        assert g["in_contact"]
        assert g["reaction_N"] == pytest.approx(F / 2, rel=REL)
        assert g["pile_moment_Nm"] == pytest.approx(F / 2 * 9.0, rel=REL)
        assert g["offset_m"] == pytest.approx(0.05, rel=REL) and g["on_pile"]
        touching = [k["pad"] for k in g["pads"] if k["in_contact"]]
        assert touching == [6]          # of 8 pads, the one at 270 deg, on the -y side


@pytest.mark.parametrize("solver", SOLVERS)
def test_bending_piles_share_a_diagonal_load(solver):
    """Piles of bending stiffness E I, fixed at the seabed: at the collar, h = 9 m above
    it, each is a spring k = 3 E I / h^3. A load (Fx, Fy) through the centre, the pontoon
    free in surge and sway, four pads (square collars): each collar crosses the clearance c
    in x and in y and bears on two pads, compressing the pile by (Fx, Fy) / (2 k): the
    pontoon sits at x = c + Fx / (2 k), y = c + Fy / (2 k), each guide takes (Fx, Fy) / 2."""
    Fx, Fy = 0.6 * F, F
    k = 3 * EI / 9.0**3
    r = solve(pontoon([Fx, Fy, 0], free=("surge", "sway"), pads=4, bending=EI), solver)
    assert r.body["x_m"] == pytest.approx(0.05 + Fx / (2 * k), rel=REL)
    assert r.body["y_m"] == pytest.approx(0.05 + Fy / (2 * k), rel=REL)
    for name in ("G1", "G2"):
        g = r.guide(name)
        assert g["reaction_N"] == pytest.approx(math.hypot(Fx, Fy) / 2, rel=REL)
        assert sorted(p["pad"] for p in g["pads"] if p["in_contact"]) == [2, 3]


@pytest.mark.parametrize("solver", SOLVERS)
def test_an_unloaded_pontoon_touches_nothing(solver):
    """No load: the collars stay centred, every pad open, exactly no reaction."""
    r = solve(pontoon([0, 0, 0], bending=EI), solver)
    for name in ("G1", "G2"):
        g = r.guide(name)
        assert not g["in_contact"] and g["reaction_N"] == 0.0


# ---- structure-mounted fenders and piles as dolphins -----------------------------------


@pytest.mark.parametrize("solver", SOLVERS)
def test_quay_mounted_fenders_equal_body_mounted_ones_for_a_translation(solver):
    """Fenders mounted on the quay bearing on the body's side give the same reactions as
    the same fenders mounted on the body, for a load that only translates the body."""
    data = berth([-F, 0, 0], free=("surge",))
    on_quay = copy.deepcopy(data)
    for f in on_quay["fenders"]:
        f["mounted"] = "structure"
    a, b = solve(data, solver), solve(on_quay, solver)
    for name in ("F1", "F2"):
        assert b.fender(name)["reaction_N"] == pytest.approx(a.fender(name)["reaction_N"],
                                                             rel=1e-9)
        assert b.fender(name)["compression_m"] == pytest.approx(F / (2 * K), rel=REL)


@pytest.mark.parametrize("solver", SOLVERS)
def test_a_fender_bears_on_a_dolphin(solver):
    """A body-mounted fender against a pile (a breasting dolphin) of radius 1 m at (-1, 0):
    the fender's face at body (0, 0, 0) touches it. A load -F along x compresses it by F/k."""
    data = berth([-F, 0, 0], free=("surge",))
    data["piles"] = [{"name": "D1", "position": [-1.0, 0.0], "radius": 1.0}]
    data["fenders"] = [{"name": "F1", "body": "b", "at": [0, 0, 0], "pile": "D1",
                        "reaction": {"stiffness": K}, "rated_deflection": 0.5}]
    r = solve(data, solver)
    assert r.fender("F1")["reaction_N"] == pytest.approx(F, rel=REL)
    assert r.fender("F1")["compression_m"] == pytest.approx(F / K, rel=REL)


# ---- bad input --------------------------------------------------------------------------


def test_a_fender_not_touching_its_wall_is_refused():
    data = berth([-F, 0, 0])
    data["fenders"][1]["at"] = [0.25, -D, 0]
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "fenders[1].at"
    assert "0.25 m off wall 'quay'" in str(err.value) and "touch" in str(err.value)


def test_a_wall_normal_of_zero_length_is_refused():
    data = berth([-F, 0, 0])
    data["walls"][0]["normal"] = [0, 0, 0]
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "walls[0].normal" and "zero length" in str(err.value)


def test_a_wall_normal_of_huge_components_is_made_unit_not_zero():
    """Its length must not overflow to inf (the fuzz test's "overflow in dot"): that made
    the unit normal zero."""
    data = berth([-F, 0, 0])
    data["walls"][0]["normal"] = [1e300, 0, 0]
    assert load_case(data).contacts.walls[0].normal == (1.0, 0.0, 0.0)


def test_a_reaction_table_that_does_not_increase_is_refused():
    data = berth([-F, 0, 0], reaction={"table": [[0.1, "150 kN"], [0.3, "600 kN"],
                                                 [0.4, "550 kN"]]})
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "fenders[0].reaction.table[2][1]"
    assert "must increase" in str(err.value)


@pytest.mark.parametrize("edit, field, words", [
    (lambda d: d["fenders"][0].update(wall="pier"), "fenders[0].wall", "unknown wall"),
    (lambda d: d["fenders"][0].update(pile="P1"), "fenders[0]", "exactly one"),
    (lambda d: d["fenders"][0]["reaction"].update(extra=1), "fenders[0].reaction",
     "not a reaction law"),
    (lambda d: d["fenders"][0].pop("rated_deflection"), "fenders[0].rated_deflection",
     "rated deflection"),
    (lambda d: d["walls"][0].update(normal=[-1, 0, 0], point=[-2, 0, 0]), "fenders[0].at",
     "inside"),
    (lambda d: d.update(walls=d["walls"] * 2), "walls[1].name", "duplicate"),
])
def test_bad_berth_input_names_the_field(edit, field, words):
    data = berth([-F, 0, 0])
    edit(data)
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == field and words in str(err.value)


def test_a_guide_not_round_its_pile_is_refused():
    data = pontoon([0, 0, 0])
    data["guides"][0]["at"] = [10.0, 0.2, 1.0]
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "guides[0].at" and "through the collar" in str(err.value)


def test_berth_sections_need_the_network_form():
    data = {"environment": {"depth": 10}, "line_types": {"c": {"weight_in_water": 100}},
            "legs": [{"name": "L", "anchor": [50, 0], "fairlead": [0, 0, 0],
                      "segments": [{"type": "c", "length": 60}]}],
            "walls": []}
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "walls"


def test_residual_and_contact_fields_in_json():
    r = solve(berth([-F, 0, 0]), "newton")
    d = r.to_dict(profiles=False)
    assert {"penetration_m", "complementarity_N"} <= set(d["residual"])
    assert [f["name"] for f in d["fenders"]] == ["F1", "F2"]
    assert np.isfinite(d["fenders"][0]["energy_J"])
