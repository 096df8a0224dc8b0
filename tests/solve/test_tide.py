"""The tide: a floating body keeps its draft as the still water rises (its held height
follows ``environment.water_level``); a structure fixed to the seabed does not.

The closed-form reference: with the seabed and the anchors on the datum, a floating body at
the water level ``h`` sits ``h`` higher above every anchor, exactly as the same body at level
0 over water ``h`` deeper with its anchors ``h`` lower (nothing else in these scenes knows the
datum): the two solves must agree to the solver's tolerance.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve import CaseError, load_case, solve
from moorsolve.model.paths import with_values

CASES = Path(__file__).resolve().parents[2] / "cases"
DOCK = CASES / "floating_dock.yaml"          # legs form, anchors given on the seabed
QUAY = CASES / "dock_quay.yaml"              # network form, held in heave, hawsers ashore


def _at(case, **edits):
    return load_case(with_values(case.source, edits))


def _tensions(result):
    return np.array([[leg.fairlead_tension_N, leg.anchor_tension_N,
                      leg.horizontal_tension_N] for leg in result.legs])


@pytest.mark.parametrize("level", [3.0, -2.0])
def test_a_floating_dock_at_a_tide_is_the_dock_over_deeper_water(level):
    """Hu & Tang's dock (held in heave, free in surge, sway and yaw) at the water level
    ``h`` against the same dock at level 0 with the depth ``20.85 + h`` (its anchors are
    given as [x, y]: on the seabed)."""
    base = load_case(DOCK)
    tide = solve(_at(base, **{"environment.water_level": level}))
    deeper = solve(_at(base, **{"environment.depth": 20.85 + level}))
    assert tide.bodies[0]["z_m"] == pytest.approx(level, abs=1e-12)
    assert deeper.bodies[0]["z_m"] == pytest.approx(0.0, abs=1e-12)
    ref = _tensions(deeper)
    assert np.allclose(_tensions(tide), ref, rtol=1e-7, atol=1e-6 * ref.max())
    for key in ("x_m", "y_m", "yaw_deg"):
        assert tide.body[key] == pytest.approx(deeper.body[key], abs=1e-7)
    # And the tide does change the answer: the chains are 3 m (or 2 m) shorter of reach.
    still = _tensions(solve(base))
    assert not np.allclose(_tensions(tide), still, rtol=1e-3)


def test_a_structure_fixed_to_the_seabed_stays_on_the_datum():
    """The same dock ``fixed_to: seabed`` (a jetty on piles, say) does not rise: at +3 m its
    chains, wholly under water either way, carry exactly what they carry at level 0."""
    data = yaml.safe_load(DOCK.read_text())
    data["body"]["fixed_to"] = "seabed"
    fixed = load_case(data)
    assert fixed.body.fixed_to == "seabed"
    still = solve(fixed)
    tide = solve(_at(fixed, **{"environment.water_level": 3.0}))
    assert tide.bodies[0]["z_m"] == 0.0
    assert np.allclose(_tensions(tide), _tensions(still), rtol=1e-9)


def test_a_dock_at_a_quay_rises_against_its_hawsers():
    """The berthed dock (held in heave) at +3 m: its chains are the chains of a dock over
    water 3 m deeper, and its hawsers, made fast to bollards on the quay (on the datum), are
    drawn taut by the rise, where at level 0 they hang slack."""
    base = load_case(QUAY)
    still = solve(base, solver="newton")
    tide = solve(_at(base, **{"environment.water_level": 3.0}), solver="newton")
    assert tide.bodies[0]["z_m"] == pytest.approx(3.0, abs=1e-12)
    assert all(h["slack"] for h in still.hawsers)
    assert all(not h["slack"] and h["tension_N"] > 1e5 for h in tide.hawsers)
    for a, b in zip(still.legs[:4], tide.legs[:4]):
        assert b.fairlead_tension_N > a.fairlead_tension_N


def _quay_datum_lowered(base, level):
    """The berthed dock at level 0 with everything fixed to the datum ``level`` lower: the
    seabed (and the anchors on it), the bollards and the fenders on the quay. The hawsers
    keep the lengths their pretension gave them at the case-file pose (made fast at
    level 0), not a pretension re-applied in the lowered scene."""
    data = yaml.safe_load(QUAY.read_text())
    for line in data["lines"]:
        if "pretension" in line["segments"][0]:
            made_fast = next(x for x in base.lines if x.name == line["name"]).length
            line["segments"] = [{"type": "hawser", "length": made_fast}]
    data["environment"]["depth"] = 14.0 + level
    for point in data["points"]:
        if len(point["position"]) == 3:
            point["position"][2] -= level
    for fender in data["fenders"]:
        fender["at"][2] -= level
    return load_case(data)


def test_a_sweep_of_the_water_level_moves_a_floating_dock():
    """``moorsolve sweep cases/dock_quay.yaml --set environment.water_level=...``: each
    point's dock floats at the water level, and each point's tensions and fender reactions
    are those of the dock at level 0 with the datum (seabed, bollards, quay fenders) that
    much lower."""
    base = load_case(QUAY)
    levels = [0.0, 1.5, 3.0]
    table = moorsolve.sweep(base, {"environment.water_level": levels}, workers=1)
    assert table["converged"].all()
    assert np.allclose(table["dock.z_m"], levels, atol=1e-12)
    for level, (_, row) in zip(levels, table.iterrows()):
        ref = solve(_quay_datum_lowered(base, level), solver="newton")
        for leg in ref.legs:
            assert row[f"{leg.name}.fairlead_tension_N"] == pytest.approx(
                leg.fairlead_tension_N, rel=1e-6, abs=1e-3)
        for fender in ref.fenders:
            assert row[f"{fender['name']}.reaction_N"] == pytest.approx(
                fender["reaction_N"], rel=1e-6)


@pytest.mark.parametrize("edit, field", [
    ({"fixed_to": "ground"}, "body.fixed_to"),
    ({"fixed_to": 0}, "body.fixed_to"),
])
def test_bad_fixed_to_in_the_legs_form(edit, field):
    data = yaml.safe_load(DOCK.read_text())
    data["body"].update(edit)
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == field
    assert "water" in str(err.value) and "seabed" in str(err.value)


def test_a_body_fixed_to_the_seabed_may_not_be_free_in_heave():
    data = yaml.safe_load((CASES / "pontoon_piles.yaml").read_text())
    data["bodies"][0]["fixed_to"] = "seabed"
    with pytest.raises(CaseError) as err:
        load_case(data)
    assert err.value.field == "bodies[0].fixed_to"
    assert "heave" in str(err.value)


def test_stiffness_and_restoring_force_at_a_tide_are_those_over_deeper_water():
    """The studies that hold a body at a pose (``moorsolve.stiffness``, ``mooring_force``)
    hold it relative to its rest at the tide: at +3 m they equal the dock over water 3 m
    deeper (central differences of re-solved lines, and a held offset)."""
    from moorsolve.studies.stiffness import mooring_force
    base = load_case(DOCK)
    tide = _at(base, **{"environment.water_level": 3.0})
    deeper = _at(base, **{"environment.depth": 23.85})
    K_tide = moorsolve.stiffness(solve(tide))
    K_deep = moorsolve.stiffness(solve(deeper))
    assert np.allclose(K_tide, K_deep, rtol=1e-6, atol=1e-6 * np.abs(K_deep).max())
    f_tide, held = mooring_force(tide, (1.0, 0.5, 0.2))
    f_deep, _ = mooring_force(deeper, (1.0, 0.5, 0.2))
    assert np.allclose(f_tide, f_deep, rtol=1e-7)
    assert held.bodies[0]["z_m"] == pytest.approx(3.0, abs=1e-12)
