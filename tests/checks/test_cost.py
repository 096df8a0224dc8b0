"""The cost of a mooring from the cited basis, and cost as the objective of a design study."""

import math

import pytest

import moorsolve
from moorsolve.catalog.costs import cost_rates
from moorsolve.errors import CaseError

DOCK = "cases/floating_dock.yaml"


def test_basis_rates_are_moorpys():
    # MoorPy 1.3 library/MoorProps_default.yaml and PointProps_default.yaml, as printed.
    rates = cost_rates()
    assert rates["chain"].per_kg == 2.585 and rates["polyester"].per_N_m == 2.3e-05
    assert rates["drag"].per_kg == 5.705 and rates["suction"].per_kg == 4.435
    assert rates["pile"].per_kg == 3.81 and rates["wire"].per_N_m == 1.2e-05


def test_dock_cost_by_hand():
    case = moorsolve.load_case(DOCK)
    priced = moorsolve.cost(case, materials={"chain81": "chain"})
    # 0.13 t/m in water is steel of 130 / (1 - 1025/7850) kg/m in air, at 2.585 USD/kg
    rate = 2.585 * 130.0 / (1 - 1025 / 7850)
    assert rate == pytest.approx(386.5, abs=0.05)
    total_length = sum(leg.length for leg in case.legs)
    assert priced.lines == pytest.approx(rate * total_length, rel=1e-12)
    assert [i.name for i in priced.items] == [leg.name for leg in case.legs]
    # the sinker blocks have no mass in the case: not priced, and said so
    assert not priced.complete and len(priced.unpriced) == 12 and priced.anchors == 0


def test_anchors_priced_by_mass_and_breakdown():
    case = moorsolve.load_case({
        "environment": {"depth": 100},
        "line_types": {"ch": {"catalog": "studless_r4", "diameter": "120 mm"},
                       "poly": {"catalog": "fibre_polyester", "diameter": "150 mm"}},
        "legs": [{"name": "L1", "anchor": [-600, 0], "fairlead": [-20, 0, 0],
                  "segments": [{"type": "ch", "length": 300}, {"type": "poly", "length": 340}]}],
        "checks": {"anchors": {"drag": {"fluke_weight": "12 t", "soil": "sand"}}}})
    priced = moorsolve.cost(case)
    chain = moorsolve.catalog.entries()["studless_r4"].mass_per_length(0.12)
    assert chain == pytest.approx(0.0199 * 120 ** 2, rel=1e-12)   # catalogue: 0.0199 d^2
    mbl = case.line_types["poly"].mbl
    assert priced.items[0].cost == pytest.approx(2.585 * chain * 300, rel=1e-12)
    assert priced.items[1].cost == pytest.approx(2.3e-5 * mbl * 340, rel=1e-12)
    assert priced.anchors == pytest.approx(5.705 * 12e3, rel=1e-14)
    assert priced.total == pytest.approx(math.fsum(i.cost for i in priced.items))
    assert priced.complete and priced.per_leg()["L1"] == pytest.approx(priced.total)
    assert priced.to_dict()["currency"] == "USD"


def test_unpriced_line_type_names_the_field():
    with pytest.raises(CaseError) as err:
        moorsolve.cost(moorsolve.load_case(DOCK))
    assert err.value.field == "materials.chain81"
    with pytest.raises(CaseError) as err:
        moorsolve.cost(moorsolve.load_case(DOCK), materials={"chain81": "gold"})
    assert err.value.field == "materials.chain81"


def _study(objective, line_types, **extra):
    return dict({
        "objective": objective, "line_types": line_types,
        "variables": {
            "breast_chain": {"type": "length", "legs": ["L1", "L2", "L3", "L4", "L7", "L8",
                                                        "L9", "L10"],
                             "lower": "120.5 m", "upper": "135 m"},
            "end_chain": {"type": "length", "legs": ["L5", "L6", "L11", "L12"],
                          "lower": "120.5 m", "upper": "135 m"}},
        "limits": {"safety_factor": 2.0, "max_anchor_uplift": "281 kN", "offset_limit": "3 m"},
        "load_cases": [{"name": "typhoon", "headings": [0, 90]}]}, **extra)


def test_optimise_with_the_basis_cost_objective():
    # Chain priced by mass: the cheapest design is the lightest one, and its cost is the
    # basis rate times its mass (an independent run with the mass objective).
    case = moorsolve.load_case(DOCK)
    steel = 130.0 / (1 - 1025 / 7850)
    light = moorsolve.optimise(case, _study("mass", {"chain81": {"mass_per_length": steel}}))
    cheap = moorsolve.optimise(case, _study("cost", {"chain81": {"material": "chain"}}))
    assert light.verified and cheap.verified and cheap.unit == "USD"
    for a, b in zip(light.variables, cheap.variables):
        assert b.optimum == pytest.approx(a.optimum, abs=1e-6)
    assert cheap.objective_optimum == pytest.approx(2.585 * light.objective_optimum, rel=1e-9)


def test_study_cost_basis_errors():
    case = moorsolve.load_case(DOCK)
    with pytest.raises(CaseError) as err:
        moorsolve.optimise(case, _study("cost", {}))
    assert err.value.field == "line_types.chain81.cost_per_length"
    with pytest.raises(CaseError) as err:
        moorsolve.optimise(case, _study("cost", {"chain81": {"material": "steel"}}))
    assert err.value.field == "line_types.chain81.material"
    with pytest.raises(CaseError) as err:
        moorsolve.optimise(case, _study("cost", {"chain81": {"material": "chain"}},
                                        currency="EUR"))
    assert err.value.field == "currency"


def test_cost_command(capsys):
    import json

    from moorsolve.cli import main
    assert main(["cost", DOCK, "--material", "chain81=chain", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    case = moorsolve.load_case(DOCK)
    assert out["lines"] == pytest.approx(moorsolve.cost(
        case, materials={"chain81": "chain"}).lines, rel=1e-12)
    assert main(["cost", DOCK, "--price", "chain81=300"]) == 0
    text = capsys.readouterr().out
    total = 300 * sum(leg.length for leg in case.legs)
    assert f"{total:,.0f}" in text and "not priced: L1 anchor" in text
    for argv, field in ((["cost", DOCK], "--material"),
                        (["cost", DOCK, "--price", "chain81=-1"], "--price"),
                        (["cost", DOCK, "--price", "nope=1"], "--price"),
                        (["cost", DOCK, "--material", "chain81"], "--material")):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert f"bad input: {field}" in err and "Traceback" not in err
