"""Design optimisation (issue 6 part 4): the optimum satisfies every constraint in
independent solves, is a KKT point by finite differences of independent solves, no
feasible neighbour is cheaper, and closed-form catenary answers are reproduced."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import moorsolve
from moorsolve.errors import CaseError, ConvergenceError
from moorsolve.io.study_file import load_study
from moorsolve.studies.optimise import design_case, load_case_scene, optimise

DOCK = "cases/floating_dock.yaml"
DOCK_STUDY = "cases/studies/floating_dock_chain.yaml"

# ---- helpers ---------------------------------------------------------------------------


def constraint_value(kind, leg, result, mbl=None):
    """The physical value of a constraint, as the report gives it, from a solved Result."""
    if kind == "offset":
        return math.hypot(result.body["x_m"], result.body["y_m"])
    lr = next(lr for lr in result.legs if lr.name == leg)
    if kind == "safety_factor":
        return lr.mbl_N / max(lr.fairlead_tension_N, lr.anchor_tension_N)
    if kind == "anchor_uplift":
        return lr.anchor_vertical_N
    return lr.grounded_length_m


#: +1: an upper limit (value <= limit); -1: a lower limit (value >= limit).
SENSE = {"offset": 1, "anchor_uplift": 1, "safety_factor": -1, "grounded_length": -1}


def solve_all(case, study, design):
    """Every load case solved by moorsolve.solve (no warm start) at ``design``."""
    designed = design_case(case, study, design)
    return [moorsolve.solve(load_case_scene(designed, study, k), allow_overload=True)
            for k in range(len(study.load_cases))]


def feasible(opt, results, study, slack=1e-7):
    names = [lc.name for lc in study.load_cases]
    for c in opt.constraints:
        v = constraint_value(c.kind, c.leg, results[names.index(c.load_case)])
        scale = max(abs(c.limit), 1.0)
        if SENSE[c.kind] * (v - c.limit) > slack * scale:
            return False
    return True


def _objective(case, study, design):
    from moorsolve.studies.optimise import objective_value
    return objective_value(design_case(case, study, design), study)


def check_kkt(case, study, opt, step=1e-3, rtol=2e-3):
    """grad f = sum over active constraints of sense * mu * grad(value), for every
    variable not at a bound, with gradients from central differences of independent solves.
    mu is the multiplier in objective units per unit of the limit (saving / step)."""
    d = np.array([v.optimum for v in opt.variables])
    names = [lc.name for lc in study.load_cases]
    active = opt.active
    assert active, "expected active constraints"
    for i, var in enumerate(opt.variables):
        if var.at_bound:
            continue
        plus, minus = d.copy(), d.copy()
        plus[i] += step
        minus[i] -= step
        rp, rm = solve_all(case, study, plus), solve_all(case, study, minus)
        df = (_objective(case, study, plus) - _objective(case, study, minus)) / (2 * step)
        terms = []
        for c in active:
            k = names.index(c.load_case)
            dc = (constraint_value(c.kind, c.leg, rp[k])
                  - constraint_value(c.kind, c.leg, rm[k])) / (2 * step)
            mu = c.saving / c.step
            terms.append(-SENSE[c.kind] * mu * dc)
        scale = abs(df) + sum(abs(t) for t in terms) + 1e-9
        assert abs(df - sum(terms)) <= rtol * scale, (var.name, df, terms)


# ---- the dock ----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def dock():
    case = moorsolve.load_case(DOCK)
    study = load_study(DOCK_STUDY, case)
    return case, study, optimise(case, study)


def test_dock_optimum_verified_and_cheaper(dock):
    case, study, opt = dock
    assert opt.status == "Solve_Succeeded"
    assert opt.verified
    assert len(opt.verification) == 8 == len(study.load_cases)
    assert [lc.name for lc in study.load_cases][:3] == ["typhoon 0 deg", "typhoon 45 deg",
                                                      "typhoon 90 deg"]
    assert opt.objective_optimum < opt.objective_start
    # The starting mass is 12 chains of 122.52 m at 149.5 kg/m.
    assert opt.objective_start == pytest.approx(12 * 122.52 * 149.5, rel=1e-12)
    # Every constraint holds with its reported margin.
    assert all(c.margin > -1e-6 * max(c.limit, 1.0) for c in opt.constraints)
    # The sinker blocks' uplift limit governs the beam-on headings, not the chain strength.
    kinds = {c.kind for c in opt.active}
    assert kinds == {"anchor_uplift"}
    assert {c.load_case for c in opt.active} == {"typhoon 90 deg", "typhoon 270 deg"}
    words = opt.plain_words()
    assert any("anchor uplift limit of 281 kN" in w and "would save" in w for w in words)


def test_dock_optimum_is_kkt_by_independent_solves(dock):
    case, study, opt = dock
    check_kkt(case, study, opt)


def test_dock_no_cheaper_feasible_neighbour(dock):
    # Every neighbour 2 cm away (each variable -, 0 or + a step) that is cheaper must break
    # a constraint in some load case, by independent solves. (Lengthening the breast chains
    # alone is not feasible either: the end chains then take more of the beam load.)
    case, study, opt = dock
    d = np.array([v.optimum for v in opt.variables])
    f_opt = _objective(case, study, d)
    cheaper = 0
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            trial = d + 0.02 * np.array([di, dj])
            if (di, dj) == (0, 0) or _objective(case, study, trial) >= f_opt:
                continue
            cheaper += 1
            assert not feasible(opt, solve_all(case, study, trial), study), (di, dj)
    assert cheaper == 4     # 8 breast chains weigh more than 4 end chains


def test_dock_written_case_round_trips(dock, tmp_path):
    from moorsolve.io.study_file import write_case_file
    case, study, opt = dock
    path = tmp_path / "opt.yaml"
    write_case_file(opt.optimised_data, path)
    again = moorsolve.load_case(path)
    lengths = {leg.name: leg.length for leg in again.legs}
    breast = next(v for v in opt.variables if v.name == "breast_chain")
    assert lengths["L3"] == pytest.approx(breast.optimum, rel=1e-12)
    assert again.legs[0].anchor == pytest.approx(case.legs[0].anchor)


# ---- closed-form answers: one inextensible leg, fairlead fixed ----------------------------

H_DEPTH, W, X_SPAN = 50.0, 1000.0, 300.0


def single_leg(length=340.0, mbl=None):
    lt = {"weight_in_water": W}
    if mbl is not None:
        lt["mbl"] = mbl
    return moorsolve.load_case({
        "name": "one leg", "environment": {"depth": H_DEPTH}, "line_types": {"chain": lt},
        "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [X_SPAN, 0.0, 0.0],
                  "segments": [{"type": "chain", "length": length}]}]})


def suspended_extent(H):
    """Horizontal extent of a catenary from a zero-slope touchdown up to height h [m]."""
    return (H / W) * math.acosh(1 + W * H_DEPTH / H)


def suspended_length(H):
    return math.sqrt(H_DEPTH**2 + 2 * H_DEPTH * H / W)


def one_leg_study(case, limits, lower=305.0):
    return load_study({"objective": "mass",
                       "line_types": {"chain": {"mass_per_length": "100 kg/m"}},
                       "variables": {"L": {"type": "length", "legs": "*", "lower": lower,
                                           "upper": 400}},
                       "limits": limits, "load_cases": [{"name": "calm"}]}, case)


def test_minimum_grounded_length_closed_form():
    # Shortest chain keeping G = 60 m on the seabed: the suspended catenary spans X - G
    # (Merkin's touchdown catenary, REFERENCE.md section 1), L = G + sqrt(h^2 + 2 h H/w).
    G = 60.0
    H = brentq(lambda H: suspended_extent(H) - (X_SPAN - G), 1.0, 1e9)
    expected = G + suspended_length(H)
    case = single_leg()
    opt = optimise(case, one_leg_study(case, {"min_grounded_length": G}))
    assert opt.verified
    assert opt.variables[0].optimum == pytest.approx(expected, rel=1e-7)
    assert [c.kind for c in opt.active] == ["grounded_length"]
    # Relaxing G by 1 m saves dL*/dG * 100 kg/m; by finite differences of the closed form.
    H2 = brentq(lambda H: suspended_extent(H) - (X_SPAN - G + 1e-3), 1.0, 1e9)
    dL_dG = ((G - 1e-3 + suspended_length(H2)) - expected) / -1e-3
    assert opt.active[0].saving == pytest.approx(100.0 * dL_dG, rel=1e-3)


def test_safety_factor_closed_form():
    # T_F = H + w h for an inextensible touchdown catenary: the shortest chain has
    # H = MBL/SF - w h, and L = (X - x_s(H)) + L_s(H).
    mbl, sf = 1.0e6, 2.0
    H = mbl / sf - W * H_DEPTH
    expected = X_SPAN - suspended_extent(H) + suspended_length(H)
    case = single_leg(mbl=mbl)
    opt = optimise(case, one_leg_study(case, {"safety_factor": sf}, lower=304.5))
    assert opt.verified
    assert opt.variables[0].optimum == pytest.approx(expected, rel=1e-7)
    assert [c.kind for c in opt.active] == ["safety_factor"]
    assert opt.active[0].value == pytest.approx(sf, rel=1e-8)


def test_drag_anchor_no_uplift_closed_form():
    # A drag anchor takes no uplift: the shortest chain touches down exactly at the anchor,
    # X = (H/w) acosh(1 + w h / H) and L = sqrt(h^2 + 2 h H / w).
    H = brentq(lambda H: suspended_extent(H) - X_SPAN, 1.0, 1e9)
    case = single_leg()
    opt = optimise(case, one_leg_study(case, {"max_anchor_uplift": 0}))
    assert opt.verified
    assert opt.variables[0].optimum == pytest.approx(suspended_length(H), rel=1e-7)


# ---- a small moored body: lengths and anchor distances, several active constraints -------

def four_leg_case(line_type=None):
    """Four legs of 290 m round a body; ``line_type`` (case-file data) replaces the chain."""
    legs = []
    for i, ang in enumerate((0, 90, 180, 270)):
        a = math.radians(ang)
        fx, fy = 20 * math.cos(a), 20 * math.sin(a)
        legs.append({"name": f"L{i + 1}", "fairlead": [fx, fy, -5.0],
                     "anchor": [fx + 250 * math.cos(a), fy + 250 * math.sin(a)],
                     "segments": [{"type": "chain", "length": 290.0}]})
    return moorsolve.load_case({
        "name": "four legs", "environment": {"depth": 60.0},
        "line_types": {"chain": line_type or {"weight_in_water": 1200.0, "ea": 6e8,
                                              "mbl": 6e6}},
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": [4e5, 1.5e5, 2e6]}},
        "legs": legs})


def four_leg_study(case):
    """Cost of line and anchors; two length groups and the anchor radius; offset, grounded
    length and safety factor limits over two storm headings and a calm."""
    return load_study({
        "objective": "cost", "currency": "EUR",
        "line_types": {"chain": {"cost_per_length": 250}}, "anchor_cost": 40000,
        "variables": {
            "x_legs": {"type": "length", "legs": ["L1", "L3"], "lower": 200, "upper": 400},
            "y_legs": {"type": "length", "legs": ["L2", "L4"], "lower": 200, "upper": 400},
            "radius": {"type": "anchor_radius", "legs": "*", "lower": 240, "upper": 300}},
        "limits": {"offset_limit": "6 m", "min_grounded_length": "15 m", "safety_factor": 2},
        "load_cases": [{"name": "storm", "headings": [0, 90]},
                       {"name": "calm", "set": {"body.loads.force": [0, 0, 0]}}]}, case)


@pytest.fixture(scope="module")
def four_legs():
    case = four_leg_case()
    study = four_leg_study(case)
    return case, study, optimise(case, study)


def test_four_legs_verified_kkt(four_legs):
    case, study, opt = four_legs
    assert opt.verified
    assert [lc.name for lc in study.load_cases] == ["storm 0 deg", "storm 90 deg", "calm"]
    assert opt.objective_optimum < opt.objective_start
    # Anchor cost is a constant in the total: 4 anchors.
    lengths = sum(leg.length for leg in opt.optimised_case.legs)
    assert opt.objective_optimum == pytest.approx(250 * lengths + 4 * 40000, rel=1e-12)
    check_kkt(case, study, opt, step=1e-3)


def test_infeasible_study_names_the_constraints():
    case = four_leg_case()
    study = load_study({
        "objective": "mass", "line_types": {"chain": {"mass_per_length": 130}},
        "variables": {"all": {"type": "length", "legs": "*", "lower": 280, "upper": 300}},
        "limits": {"offset_limit": "0.5 m"},
        "load_cases": [{"name": "storm"}]}, case)
    with pytest.raises(ConvergenceError) as err:
        optimise(case, study)
    text = str(err.value)
    assert "no feasible design" in text and "offset limit" in text and "'storm'" in text


# ---- bad study files ----------------------------------------------------------------------

BASE = {"variables": {"c": {"type": "length", "legs": "*", "lower": 110, "upper": 130}},
        "line_types": {"chain81": {"mass_per_length": 149.5}},
        "load_cases": [{"name": "t"}]}


@pytest.mark.parametrize("edit, field", [
    ({"objective": "weight"}, "objective"),
    ({"variables": {"c": {"type": "diameter", "legs": "*", "lower": 1, "upper": 2}}},
     "variables.c.type"),
    ({"variables": {"c": {"type": "length", "legs": ["L99"], "lower": 110, "upper": 130}}},
     "variables.c.legs[0]"),
    ({"variables": {"c": {"type": "length", "legs": "*", "lower": 130, "upper": 110}}},
     "variables.c.upper"),
    ({"variables": {"c": {"type": "length", "legs": "*", "lower": 125, "upper": 130}}},
     "variables.c.legs"),
    ({"variables": {"c": {"type": "length", "legs": "*", "lower": 110, "upper": 130,
                          "stride": 1}}}, "variables.c.stride"),
    ({"line_types": {}}, "line_types.chain81.mass_per_length"),
    ({"limits": {"safety_factor": 0.5}}, "limits.safety_factor"),
    ({"load_cases": []}, "load_cases"),
    ({"load_cases": [{"name": "t", "set": {"environment.wind.speed": -3}}]},
     "load_cases[0].set: environment.wind.speed"),
    ({"load_cases": [{"name": "t", "headings": {"every_deg": 0}}]},
     "load_cases[0].headings.every_deg"),
    ({"load_cases": [{"name": "t"}, {"name": "t"}]}, "load_cases[1].name"),
])
def test_bad_study_names_the_field(edit, field):
    case = moorsolve.load_case(DOCK)
    with pytest.raises(CaseError) as err:
        load_study({**BASE, **edit}, case)
    assert err.value.field == field, str(err.value)


def test_cli_optimise(tmp_path, capsys):
    from moorsolve.cli import main
    study = tmp_path / "s.yaml"
    study.write_text("variables: {c: {type: length, legs: '*', lower: 120.5 m, upper: 130}}\n"
                     "line_types: {chain81: {mass_per_length: 149.5 kg/m}}\n"
                     "limits: {max_anchor_uplift: 281 kN}\n"
                     "load_cases: [{name: beam, set: {environment.wind.toward_deg: 90,"
                     " environment.current.toward_deg: 90, environment.waves.toward_deg: 90}}]\n")
    out = tmp_path / "opt.yaml"
    assert main(["optimise", DOCK, "--study", str(study), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "verified: every constraint holds" in text and "would save" in text
    assert moorsolve.load_case(out).legs[0].length < 122.52
    # The case file itself, edited: every line that holds no changed value is kept as is,
    # comments and alignment included.
    original = Path(DOCK).read_text(encoding="utf-8").splitlines()
    written = out.read_text(encoding="utf-8").splitlines()
    assert written[0].startswith("# ") and "optimised by moorsolve optimise" in written[0]
    kept = [line for line in original if "length:" not in line and not line.startswith("name:")]
    assert [line for line in written[2:] if "length:" not in line
            and not line.startswith("name:")] == kept
    assert any(line.lstrip().startswith("#") for line in kept)
    # Bad input: exit 2, one line, nothing written.
    bad = tmp_path / "bad.yaml"
    bad.write_text("variables: {c: {type: length, legs: '*', lower: -1, upper: 130}}\n"
                   "line_types: {chain81: {mass_per_length: 149.5 kg/m}}\n"
                   "load_cases: [{name: x}]\n")
    out2 = tmp_path / "none.yaml"
    assert main(["optimise", DOCK, "--study", str(bad), "-o", str(out2)]) == 2
    err = capsys.readouterr().err
    assert "variables.c.lower" in err and "Traceback" not in err
    assert not out2.exists()
    assert main(["optimise", DOCK, "--study", str(study), "-o", str(tmp_path / "x.txt")]) == 2


def test_network_case_optimises_its_lines_and_verifies():
    """The OC3 spar (network form, six DOFs): the three lines' common length against an
    offset limit under thrust; the optimum is verified by independent solves, and the
    offset limit is met at the verified optimum."""
    from conftest import CASES
    case = moorsolve.load_case(CASES / "oc3_spar.yaml")
    study = load_study({
        "objective": "mass",
        "line_types": {"oc3_chain": {"mass_per_length": "77.7066 kg/m"}},
        "variables": {"line": {"type": "length", "legs": ["L1", "L2", "L3"],
                               "lower": "885 m", "upper": "940 m"}},
        "limits": {"offset_limit": "30 m"},
        "load_cases": [{"name": "thrust",
                        "set": {"bodies[spar].loads.force": [1.2e6, 0, 0, 0, 0, 0]}}]},
        case)
    opt = optimise(case, study)
    assert opt.verified
    length = opt.variables[0].optimum
    design = design_case(case, study, [length])
    result = moorsolve.solve(load_case_scene(design, study, 0))
    offset = math.hypot(result.bodies[0]["x_m"], result.bodies[0]["y_m"])
    assert offset <= 30.0 * (1 + 1e-6)
    # The offset limit binds: a slightly longer line would drift past it.
    assert offset == pytest.approx(30.0, rel=1e-4) or length == pytest.approx(885.0)


def test_optimisation_through_a_table_law_is_verified_and_kkt():
    """The four-leg design study with a table-law rope (issue 17): the optimum holds in
    independent solves and is a KKT point by their central differences (derivatives flow
    through the stretch law)."""
    case = four_leg_case({"weight_in_water": 1200.0, "mbl": 6e6, "stretch": {
        "model": "table", "strain": [0.002, 0.004, 0.007, 0.01],
        "tension": [2e5, 6e5, 1.5e6, 2.6e6]}})
    study = four_leg_study(case)
    opt = optimise(case, study)
    assert opt.verified and opt.objective_optimum < opt.objective_start
    check_kkt(case, study, opt, step=1e-3)


def test_a_study_file_is_read_above_the_study():
    """The study reads no file: it takes a validated Study; moorsolve.optimise (and the
    command) read and validate a study file first, in one pass."""
    case = moorsolve.load_case(DOCK)
    with pytest.raises(TypeError, match="not a Study"):
        optimise(case, str(DOCK_STUDY))
