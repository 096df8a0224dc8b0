"""The design-wide cost cap of a design study (``max_cost``): a mass optimum dearer than the
cap is moved along the constraint to a design at the cap, a cap above the optimum changes
nothing, an impossible cap says so with the least cost reached, and bad caps name the field."""

import json
import math

import pytest

import moorsolve
from moorsolve.errors import CaseError, ConvergenceError
from moorsolve.io.study_file import load_study
from moorsolve.studies.optimise import design_case, load_case_scene, optimise

# Prices in EUR per metre and per anchor (given in the study, so the arithmetic is by hand).
LEE_MASS, LEE_PRICE = 200.0, 250.0        # leg L1: heavy and cheap
CHAIN_MASS, CHAIN_PRICE = 100.0, 600.0    # legs L2, L3, L4: light and dear
ANCHOR = 40000.0


def spread():
    """Four legs round a body pushed toward +x: L3 is the loaded leg, L1 the lee leg. A
    shorter lee leg pulls the body further downwind and loads L3 more, so the lee and the
    loaded leg trade: mass prefers a short (heavy) lee leg, cost a short (dear) loaded leg."""
    legs = []
    for i, ang in enumerate((0, 90, 180, 270)):
        a = math.radians(ang)
        fx, fy = 20 * math.cos(a), 20 * math.sin(a)
        legs.append({"name": f"L{i + 1}", "fairlead": [fx, fy, -5.0],
                     "anchor": [fx + 250 * math.cos(a), fy + 250 * math.sin(a)],
                     "segments": [{"type": "lee" if i == 0 else "chain", "length": 290.0}]})
    lt = {"weight_in_water": 1200.0, "ea": 6e8, "mbl": 6e6}
    return moorsolve.load_case({
        "name": "spread", "environment": {"depth": 60.0},
        "line_types": {"chain": lt, "lee": dict(lt)},
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": [4e5, 0, 0]}},
        "legs": legs})


def study_data(**extra):
    data = {"objective": "mass", "currency": "EUR",
            "line_types": {"chain": {"mass_per_length": CHAIN_MASS,
                                     "cost_per_length": CHAIN_PRICE},
                           "lee": {"mass_per_length": LEE_MASS, "cost_per_length": LEE_PRICE}},
            "anchor_cost": ANCHOR,
            "variables": {"lee": {"type": "length", "legs": ["L1"], "lower": 240, "upper": 400},
                          "wind": {"type": "length", "legs": ["L3"], "lower": 240,
                                   "upper": 400}},
            "limits": {"safety_factor": 6},
            "load_cases": [{"name": "storm"}, {"name": "storm 20",
                                               "set": {"body.loads.force": [3.8e5, 1.3e5, 0]}}]}
    data.update(extra)
    return data


def hand_cost(case):
    """Lines and anchors priced by hand from the case's leg lengths [EUR]."""
    lengths = {leg.name: leg.length for leg in case.legs}
    return (LEE_PRICE * lengths["L1"]
            + CHAIN_PRICE * (lengths["L2"] + lengths["L3"] + lengths["L4"]) + 4 * ANCHOR)


def hand_mass(case):
    lengths = {leg.name: leg.length for leg in case.legs}
    return LEE_MASS * lengths["L1"] + CHAIN_MASS * (lengths["L2"] + lengths["L3"]
                                                     + lengths["L4"])


def least_safety_factor(case, study, opt):
    """Least MBL / tension over every leg and load case, by independent solves."""
    designed = design_case(case, study, [v.optimum for v in opt.variables])
    worst = math.inf
    for k in range(len(study.load_cases)):
        result = moorsolve.solve(load_case_scene(designed, study, k), allow_overload=True)
        assert result.converged
        for lr in result.legs:
            worst = min(worst, lr.mbl_N / max(lr.fairlead_tension_N, lr.anchor_tension_N))
    return worst


@pytest.fixture(scope="module")
def optima():
    case = spread()
    mass_opt = optimise(case, load_study(study_data(), case))
    cost_opt = optimise(case, load_study(study_data(objective="cost"), case))
    return case, mass_opt, cost_opt


def test_the_trade_exists(optima):
    # The premise of the tests below: the mass optimum is dearer than the least cost.
    case, mass_opt, cost_opt = optima
    assert mass_opt.verified and cost_opt.verified
    assert mass_opt.cost is None and mass_opt.max_cost is None  # a mass study prices nothing
    dear = hand_cost(mass_opt.optimised_case)
    assert dear > cost_opt.objective_optimum * 1.01
    assert cost_opt.cost == pytest.approx(hand_cost(cost_opt.optimised_case), rel=1e-12)


def test_cap_below_the_mass_optimum_gives_a_design_at_the_cap(optima):
    case, mass_opt, cost_opt = optima
    dear, least = hand_cost(mass_opt.optimised_case), cost_opt.objective_optimum
    cap = 0.5 * (dear + least)
    study = load_study(study_data(max_cost=cap), case)
    opt = optimise(case, study)
    assert opt.verified and opt.status == "Solve_Succeeded"
    # The cost priced by hand from the optimised case: at the cap within the solver's
    # constraint tolerance (scaled by the cap), and reported as such.
    assert hand_cost(opt.optimised_case) == pytest.approx(cap, rel=1e-7)
    assert opt.cost == pytest.approx(hand_cost(opt.optimised_case), rel=1e-12)
    assert opt.cost_utilisation == pytest.approx(1.0, abs=1e-7)
    # Every load-case constraint still met, by independent solves (the safety factor 6).
    assert least_safety_factor(case, study, opt) >= 6 * (1 - 1e-7)
    # The cap costs mass: more than the uncapped optimum, less than the least-cost design.
    assert mass_opt.objective_optimum < opt.objective_optimum < hand_mass(
        cost_opt.optimised_case)
    (cap_row,) = [c for c in opt.constraints if c.kind == "cost"]
    assert cap_row.active and cap_row.load_case == "whole design" and cap_row.unit == "EUR"
    assert cap_row.value == pytest.approx(cap, rel=1e-7)
    assert any("cost cap (max_cost)" in w and "kg" in w for w in opt.plain_words())
    # The multiplier in words (mass saved by raising the cap by 1 %) against the central
    # difference of the optimum mass re-optimised at caps either side.
    h = 1e-3 * cap
    m_hi = optimise(case, load_study(study_data(max_cost=cap + h), case),
                    verify=False).objective_optimum
    m_lo = optimise(case, load_study(study_data(max_cost=cap - h), case),
                    verify=False).objective_optimum
    dm_dcap = (m_hi - m_lo) / (2 * h)
    assert dm_dcap < 0
    assert cap_row.saving == pytest.approx(-dm_dcap * cap_row.step, rel=1e-3)
    d = opt.to_dict()
    assert d["cost"] == opt.cost and d["max_cost"] == cap and d["currency"] == "EUR"
    assert d["cost_utilisation"] == pytest.approx(1.0, abs=1e-7)


def test_cap_above_the_optimum_changes_nothing(optima):
    case, mass_opt, _ = optima
    dear = hand_cost(mass_opt.optimised_case)
    opt = optimise(case, load_study(study_data(max_cost=f"{1.05 * dear:.2f} EUR"), case))
    assert opt.verified
    for v, w in zip(opt.variables, mass_opt.variables):
        assert v.optimum == pytest.approx(w.optimum, abs=1e-6)
    assert opt.cost == pytest.approx(dear, rel=1e-9)
    assert opt.cost_utilisation == pytest.approx(dear / (1.05 * dear), rel=1e-6)
    (cap_row,) = [c for c in opt.constraints if c.kind == "cost"]
    assert not cap_row.active and cap_row.margin == pytest.approx(0.05 * dear, rel=1e-4)


def test_impossible_cap_says_so_with_the_least_cost(optima):
    case, _, cost_opt = optima
    least = cost_opt.objective_optimum
    study = load_study(study_data(max_cost=0.98 * least), case)
    with pytest.raises(ConvergenceError) as err:
        optimise(case, study)
    text = str(err.value)
    assert "no feasible design" in text and "meets max_cost" in text
    assert f"least cost of a design that meets every load-case constraint is {least:,.0f} EUR" \
        in text, text
    assert f"cost utilisation {least / (0.98 * least):.4f}" in text
    # Below even the anchors and the fixed legs: the same clear message.
    with pytest.raises(ConvergenceError, match="meets max_cost 100,000 EUR"):
        optimise(case, load_study(study_data(max_cost=1e5), case))


def test_cap_prices_from_the_cost_basis_in_usd():
    # The dock's chain priced from the basis (USD/kg of chain): the cap in USD is accepted and
    # the design's cost is the basis' price of its lines plus nothing for anchors.
    case = moorsolve.load_case("cases/floating_dock.yaml")
    study = load_study({"objective": "mass", "line_types": {"chain81": {"material": "chain",
                                                     "mass_per_length": 149.5}},
                        "max_cost": "900,000 USD",
                        "variables": {"c": {"type": "length", "legs": "*", "lower": 120.5,
                                            "upper": 135}},
                        "limits": {"max_anchor_uplift": "281 kN"},
                        "load_cases": [{"name": "t"}]}, case)
    assert study.max_cost == 900000 and study.currency == "USD"
    priced = moorsolve.cost(case, materials={"chain81": "chain"})
    from moorsolve.studies.optimise_design import cost_value
    assert cost_value(case, study) == pytest.approx(priced.lines, rel=1e-12)


@pytest.mark.parametrize("value, field, words", [
    (-5e5, "max_cost", "positive"),
    (0, "max_cost", "positive"),
    ("600000 USD", "max_cost", "not the study's currency EUR"),
    ("600000 kg", "max_cost", "not the study's currency"),
    ("a lot EUR", "max_cost", "not an amount"),
    ("600000", "max_cost", "not an amount"),
    (True, "max_cost", "positive"),
    (float("inf"), "max_cost", "positive"),
])
def test_bad_cap_names_the_field(value, field, words):
    with pytest.raises(CaseError) as err:
        load_study(study_data(max_cost=value), spread())
    assert err.value.field == field and words in str(err.value), str(err.value)


def test_cap_needs_every_line_priced():
    data = study_data(max_cost=7e5)
    del data["line_types"]["lee"]["cost_per_length"]
    with pytest.raises(CaseError) as err:
        load_study(data, spread())
    assert err.value.field == "line_types.lee.cost_per_length"
    assert "max_cost" in str(err.value)


def test_cli_reports_the_cap(tmp_path, capsys, optima):
    import yaml
    from moorsolve.cli import main
    case_path = tmp_path / "spread.yaml"
    case_path.write_text(yaml.safe_dump(spread().source))
    _, mass_opt, cost_opt = optima
    cap = 0.5 * (hand_cost(mass_opt.optimised_case) + cost_opt.objective_optimum)
    study = tmp_path / "s.yaml"
    study.write_text(yaml.safe_dump(study_data(max_cost=f"{cap:.2f} EUR")))
    assert main(["optimise", str(case_path), "--study", str(study)]) == 0
    text = capsys.readouterr().out
    assert f"against max_cost {cap:,.0f} EUR, utilisation 1.0000" in text
    assert "whole design" in text and "verified: every constraint holds" in text
    assert main(["optimise", str(case_path), "--study", str(study), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["max_cost"] == pytest.approx(cap) and data["cost_utilisation"] == \
        pytest.approx(1.0, abs=1e-7)
    # An impossible cap: exit 1 and the message; a bad one: exit 2 naming the field.
    study.write_text(yaml.safe_dump(study_data(max_cost=1e5)))
    assert main(["optimise", str(case_path), "--study", str(study)]) == 1
    err = capsys.readouterr().err
    assert "meets max_cost" in err and "least cost" in err and "Traceback" not in err
    study.write_text(yaml.safe_dump(study_data(max_cost="-3 EUR")))
    assert main(["optimise", str(case_path), "--study", str(study)]) == 2
    err = capsys.readouterr().err
    assert "max_cost" in err and "Traceback" not in err
