"""Fibre ropes end to end: case files with stretch laws, the shipped chain-polyester-chain
case, sensitivities and optimisation through the law, the fibre-rope checks and the
upper/lower-bound stiffness analysis (MoorDyn curve files: tests/io/test_moordyn_curves.py).

The independent references are the ODE of ``reference_ode`` with scipy's PCHIP (see
tests/physics/test_stretch_laws.py) and central differences of re-solved equilibria.
"""

from __future__ import annotations

import copy
import json
import math
import re

import numpy as np
import pytest
import yaml
from conftest import CASES
from reference_ode import integrate_leg, integrate_through_surface, table_reference

import moorsolve
from moorsolve.catalog import line_properties
from moorsolve.cli import main
from moorsolve.errors import CaseError
from moorsolve.solve.assembly.prepared import structure_key

FPU = CASES / "fpu_polyester_table.yaml"


def fpu_data():
    return yaml.safe_load(FPU.read_text())


def single_rope(stretch, *, X=520.0, Z=190.0, w=50.0, length=545.0, extra=None):
    """One rope from a seabed anchor to a fixed fairlead."""
    lt = {"weight_in_water": w, "stretch": stretch, **(extra or {})}
    return {"environment": {"depth": 200.0},
            "line_types": {"rope": lt},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [X, 0.0, Z - 200.0],
                      "segments": [{"type": "rope", "length": length}]}]}


TABLE = {"model": "table", "strain": [0.004, 0.009, 0.015, 0.022, 0.030],
         "tension": [5e4, 1.4e5, 2.8e5, 4.9e5, 7.8e5]}


# ---- case files ------------------------------------------------------------------------------


@pytest.mark.parametrize("edit, field", [
    (lambda lt: lt.update(ea=1e8), "line_types.rope.stretch"),
    (lambda lt: lt["stretch"]["strain"].__setitem__(2, 0.005), "line_types.rope.stretch.strain[3]"),
    (lambda lt: lt["stretch"]["tension"].__setitem__(3, 2e5), "line_types.rope.stretch.tension[4]"),
    (lambda lt: lt["stretch"]["tension"].pop(), "line_types.rope.stretch.tension"),
    (lambda lt: lt["stretch"].update(model="spline"), "line_types.rope.stretch.model"),
    (lambda lt: lt["stretch"].update(shape="cubic"), "line_types.rope.stretch.shape"),
    (lambda lt: lt["stretch"]["tension"].__setitem__(0, -1.0),
     "line_types.rope.stretch.tension[0]"),
    (lambda lt: lt.update(stretch={"model": "baranov", "n": -2e-4}), "line_types.rope.stretch.n"),
    (lambda lt: lt.update(stretch={"model": "baranov", "n": 3.0}), "line_types.rope.stretch.n"),
    (lambda lt: lt.update(stretch={"model": "baranov"}), "line_types.rope.stretch.n"),
    (lambda lt: lt.update(stretch={"model": "hooke", "ea": 0}), "line_types.rope.stretch.ea"),
    (lambda lt: lt.update(stretch={"model": "table", "strain": [0, 0.01], "tension": [1e3, 2e5]}),
     "line_types.rope.stretch.tension[0]"),
    (lambda lt: lt.update(min_tension=-5), "line_types.rope.min_tension"),
    (lambda lt: lt.update(fibre="yes"), "line_types.rope.fibre"),
    (lambda lt: lt.update(stiffness_bounds={"lower": 1e8}),
     "line_types.rope.stiffness_bounds.upper"),
    (lambda lt: lt.update(stiffness_bounds={"lower": 1e8, "upper": {"model": "dynamic",
                                                                      "alpha": 11}}),
     "line_types.rope.stiffness_bounds.upper.beta"),
])
def test_bad_stretch_input_names_the_field(edit, field):
    data = single_rope(copy.deepcopy(TABLE))
    edit(data["line_types"]["rope"])
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(data)
    assert err.value.field == field, str(err.value)


def test_stretch_forms_and_defaults():
    data = single_rope(copy.deepcopy(TABLE))
    lt = moorsolve.load_case(data).line_types["rope"]
    # The (0, 0) row is added; the values are SI; a table is not fibre unless said so.
    assert lt.stretch.strain[0] == 0 and lt.stretch.tension[0] == 0 and lt.stretch.rows == 6
    assert lt.ea is None and lt.elastic and not lt.fibre
    hooke = single_rope({"model": "hooke", "ea": "120 MN"})
    plain = copy.deepcopy(hooke)
    plain["line_types"]["rope"].pop("stretch")
    plain["line_types"]["rope"]["ea"] = 1.2e8
    assert moorsolve.load_case(hooke).line_types == moorsolve.load_case(plain).line_types
    baranov = moorsolve.load_case(single_rope({"model": "baranov", "n": 2e-4}))
    assert baranov.line_types["rope"].fibre          # a plant-fibre rope
    units = single_rope({"model": "table", "strain": [0.01, 0.02], "tension": ["50 kN", "1.2e5"]})
    assert moorsolve.load_case(units).line_types["rope"].stretch.tension == (0.0, 5e4, 1.2e5)


def test_hooke_written_as_a_stretch_law_solves_to_the_same_numbers():
    a = moorsolve.solve(moorsolve.load_case(single_rope({"model": "hooke", "ea": 2.4e7})))
    data = single_rope(None)
    data["line_types"]["rope"].pop("stretch")
    data["line_types"]["rope"]["ea"] = 2.4e7
    b = moorsolve.solve(moorsolve.load_case(data))
    assert a.legs[0].to_dict() == b.legs[0].to_dict()


def test_catalogue_fibre_ropes_are_the_published_fits():
    # NREL MoorPy property library (MoorProps_default.yaml; library/readme.md), d in m:
    # polyester MBL 308.2e6 d^2, mass 678.75 d^2, Krs 14, Krd = 11.615 + 0.396 Lm;
    # nylon MBL 230.29e6 d^3 + 207.0e6 d^2; HMPE 650.65e6 d^3 + 579.5e6 d^2, 975 kg/m^3.
    d = 0.16
    poly = line_properties("fibre_polyester", d)
    assert poly.mbl == pytest.approx(308.2e6 * d**2, rel=1e-12)
    assert poly.mass_per_length == pytest.approx(678.75 * d**2, rel=1e-12)
    assert poly.ea == pytest.approx(14 * poly.mbl, rel=1e-12)
    assert poly.dynamic_stiffness == (11.615, 0.396)
    assert poly.entry.dynamic_ea_N(d, 0.2 * poly.mbl) == pytest.approx(
        (11.615 + 0.396 * 20) * poly.mbl, rel=1e-12)
    nylon = line_properties("fibre_nylon", d)
    assert nylon.mbl == pytest.approx(230.29e6 * d**3 + 207.0e6 * d**2, rel=1e-12)
    assert nylon.ea == pytest.approx(5 * nylon.mbl, rel=1e-12)
    hmpe = line_properties("fibre_hmpe", d)
    assert hmpe.mbl == pytest.approx(650.65e6 * d**3 + 579.5e6 * d**2, rel=1e-12)
    assert hmpe.weight_in_water < 0                       # HMPE floats
    assert all(p.fibre and "NREL MoorPy" in p.source for p in (poly, nylon, hmpe))
    case = moorsolve.load_case({
        "environment": {"depth": 100}, "line_types": {"p": {"catalog": "fibre_polyester",
                                                            "diameter": "160 mm"}},
        "legs": [{"name": "A", "anchor": [-300, 0], "fairlead": [0, 0, 0],
                  "segments": [{"type": "p", "length": 320}]}]})
    lt = case.line_types["p"]
    assert lt.fibre and lt.ea == pytest.approx(poly.ea)
    assert lt.stiffness_bounds.lower == pytest.approx(poly.ea)
    assert (lt.stiffness_bounds.upper.alpha, lt.stiffness_bounds.upper.beta) == (11.615, 0.396)


# ---- the shipped chain-polyester-chain case --------------------------------------------------


@pytest.fixture(scope="module")
def fpu():
    case = moorsolve.load_case(str(FPU))
    return case, moorsolve.solve(case)


def test_shipped_polyester_case_solves_with_both_solvers(fpu):
    case, result = fpu
    assert result.converged and "nonlinear_stretch" in result.effects
    newton = moorsolve.solve(case, solver="newton")
    assert newton.solver == "newton"
    scale = max(leg.fairlead_tension_N for leg in result.legs)
    for a, b in zip(result.legs, newton.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, abs=1e-9 * scale)
    assert [leg.fibre_grounded_m for leg in result.legs] == [0.0, 0.0, 0.0]


def test_polyester_segments_land_where_the_ode_puts_them(fpu):
    """Each polyester segment, integrated independently from its solved top forces with
    scipy's PCHIP of the case's table, ends at the solved joint below it."""
    case, result = fpu
    lt = case.line_types["polyester160"]
    law = table_reference(list(lt.stretch.strain), list(lt.stretch.tension))
    for leg, lr in zip(case.legs, result.legs):
        seg = lr.segments[1]
        lower, upper = lr.joints[0]["position_m"], lr.joints[1]["position_m"]
        ref = integrate_leg(H=seg["horizontal_tension_N"], V=seg["top_vertical_N"],
                            L=leg.segments[1].length, w=lt.weight_in_water, contact=False,
                            strain=law, tension_breaks=lt.stretch.tension)
        X = math.hypot(upper[0] - lower[0], upper[1] - lower[1])
        assert ref["X"] == pytest.approx(X, abs=1e-8 * leg.segments[1].length)
        assert ref["Z"] == pytest.approx(upper[2] - lower[2], abs=1e-8 * leg.segments[1].length)
        assert ref["VA"] == pytest.approx(seg["bottom_vertical_N"], abs=1e-8 * seg["top_tension_N"])
        # The profile ends on the fairlead.
        assert lr.profile["z_m"][-1] == pytest.approx(lr.fairlead[2], abs=1e-8)


def test_sweep_over_table_values_needs_no_rebuild(fpu):
    case, result = fpu
    data = fpu_data()
    stiffer = [f"{1.1 * float(t.split()[0])} kN" for t in
               data["line_types"]["polyester160"]["stretch"]["tension"]]
    path = "line_types.polyester160.stretch.tension"
    other = moorsolve.load_case({**data, "line_types": {
        **data["line_types"], "polyester160": {**data["line_types"]["polyester160"],
                                               "stretch": {**data["line_types"]["polyester160"]
                                                           ["stretch"], "tension": stiffer}}}})
    assert structure_key(other) == structure_key(case)
    table = moorsolve.sweep(case, {path: [data["line_types"]["polyester160"]["stretch"]
                                          ["tension"], stiffer]})
    assert table["converged"].all()
    alone = moorsolve.solve(other)
    assert table["L3.fairlead_tension_N"].iloc[1] == pytest.approx(
        alone.leg("L3").fairlead_tension_N, rel=1e-8)
    assert table["L3.fairlead_tension_N"].iloc[0] == pytest.approx(
        result.leg("L3").fairlead_tension_N, rel=1e-8)


def test_a_linear_table_is_hookes_law_in_a_network():
    """The three-platform network (six-DOF bodies, bridles, shared lines): its shared lines
    given as a table whose rows lie on Hooke's line solve to the same tensions."""
    data = yaml.safe_load((CASES / "three_platforms.yaml").read_text())
    hooke = moorsolve.solve(moorsolve.load_case(data))
    lt = data["line_types"]["shared"]
    ea = float(lt.pop("ea"))
    lt["stretch"] = {"model": "table", "strain": [0.001, 0.002, 0.004],
                     "tension": [ea * 0.001, ea * 0.002, ea * 0.004]}
    table = moorsolve.solve(moorsolve.load_case(data))
    assert "nonlinear_stretch" in table.effects
    scale = max(leg.fairlead_tension_N for leg in hooke.legs)
    for a, b in zip(hooke.legs, table.legs):
        assert b.fairlead_tension_N == pytest.approx(a.fairlead_tension_N, abs=1e-10 * scale)
        assert b.anchor_tension_N == pytest.approx(a.anchor_tension_N, abs=1e-10 * scale)


# ---- derivatives through the law -------------------------------------------------------------


def _scaled(data, name, k):
    data = copy.deepcopy(data)
    st = data["line_types"][name]["stretch"]
    if st["model"] == "baranov":
        st["n"] = st["n"] / math.sqrt(k)
    else:
        st["tension"] = [k * moorsolve.load_case(data).line_types[name].stretch.tension[i + 1]
                         for i in range(len(st["tension"]))]
    data["line_types"][name].pop("stiffness_bounds", None)
    return data


def test_sensitivity_to_a_table_ropes_stiffness_is_the_central_difference(fpu):
    """The polyester's table and the chain's EA (Hooke segments of the multi-segment legs)
    made stiffer by a factor: against re-solved equilibria."""
    case, result = fpu
    outputs = ["x_m", "yaw_deg", "legs[L1].fairlead_tension_N", "legs[L3].anchor_tension_N"]
    exact = moorsolve.sensitivity(result, outputs,
                                  ["line_types[polyester160].stiffness_scale",
                                   "line_types[chain84].stiffness_scale"]).matrix
    h = 1e-4
    for col, edit in ((0, lambda k: _scaled(fpu_data(), "polyester160", k)),
                      (1, lambda k: _stiffer_chain(k))):
        values = []
        for k in (1 + h, 1 - h):
            r = moorsolve.solve(moorsolve.load_case(edit(k)), start=result.state)
            values.append([r.body["x_m"], r.body["yaw_deg"], r.leg("L1").fairlead_tension_N,
                           r.leg("L3").anchor_tension_N])
        fd = (np.array(values[0]) - np.array(values[1])) / (2 * h)
        assert exact[:, col] == pytest.approx(fd, rel=1e-5, abs=1e-9), col


def _stiffer_chain(k):
    data = fpu_data()
    data["line_types"]["chain84"]["ea"] = float(data["line_types"]["chain84"]["ea"]) * k
    return data


def buoy_baranov():
    """A buoy on three plant-fibre (Baranov) ropes, one of them slack on the seabed."""
    legs = [{"name": f"R{i}", "anchor": [60 * math.cos(a), 60 * math.sin(a)],
             "fairlead": [0.0, 0.0, 0.0], "segments": [{"type": "hemp", "length": 70.0}]}
            for i, a in enumerate((0.0, 2.1, 4.2))]
    return {"environment": {"depth": 30.0, "seabed": {"friction": 0.4}},
            "line_types": {"hemp": {"weight_in_water": 25.0, "mbl": 2e5,
                                    "stretch": {"model": "baranov", "n": 4e-4}}},
            "body": {"free": ["surge", "sway"], "loads": {"force": [1.5e3, 4e2, 0]}},
            "legs": legs}


def test_sensitivity_to_baranovs_n_is_the_central_difference():
    result = moorsolve.solve(moorsolve.load_case(buoy_baranov()))
    outputs = ["x_m", "y_m", "legs[R0].fairlead_tension_N", "legs[R1].grounded_length_m"]
    exact = moorsolve.sensitivity(result, outputs, ["line_types[hemp].n",
                                                    "line_types[hemp].stiffness_scale"]).matrix
    n, h = 4e-4, 1e-4
    for col, edit in ((0, lambda k: {"n": n * k}), (1, lambda k: {"n": n / math.sqrt(k)})):
        values = []
        for k in (1 + h, 1 - h):
            data = buoy_baranov()
            data["line_types"]["hemp"]["stretch"].update(edit(k))
            r = moorsolve.solve(moorsolve.load_case(data), start=result.state)
            values.append([r.body["x_m"], r.body["y_m"], r.leg("R0").fairlead_tension_N,
                           r.leg("R1").grounded_length_m])
        fd = (np.array(values[0]) - np.array(values[1])) / (2 * h * (n if col == 0 else 1))
        assert exact[:, col] == pytest.approx(fd, rel=1e-5, abs=1e-9), col


def test_sensitivity_names_what_it_cannot_map(fpu):
    case, result = fpu
    with pytest.raises(ValueError, match="Baranov"):
        moorsolve.sensitivity(result, ["x_m"], ["line_types[polyester160].n"])
    buoy = moorsolve.solve(moorsolve.load_case(buoy_baranov()))
    with pytest.raises(ValueError, match="follows a stretch law .*stiffness_scale"):
        moorsolve.sensitivity(buoy, ["x_m"], ["legs[R0].ea"])
    with pytest.raises(ValueError, match="no line uses"):
        moorsolve.sensitivity(result, ["x_m"], ["line_types[rope].stiffness_scale"])


# ---- a rope end above the water ---------------------------------------------------------------


@pytest.mark.parametrize("stretch", [{"model": "hooke", "ea": 2.6e7}, TABLE,
                                     {"model": "baranov", "n": 3e-5}],
                         ids=["hooke", "table", "baranov"])
def test_a_rope_whose_fairlead_is_above_the_water_matches_the_ode(stretch):
    """A suspended rope 310 m long to a fairlead 12 m above the water, four times heavier in
    air: integrated from the solved fairlead forces through the surface (the ODE with the
    law), it reaches the anchor (300 m across, 112 m down) and pulls it as reported, to
    1e-8. The audit passes: the end's direction is judged with the weight in air there."""
    data = {"environment": {"depth": 100.0},
            "line_types": {"rope": {"weight_in_water": 60.0, "weight_in_air": 240.0,
                                    "stretch": copy.deepcopy(stretch)}},
            "legs": [{"name": "A", "anchor": [0.0, 0.0], "fairlead": [300.0, 0.0, 12.0],
                      "segments": [{"type": "rope", "length": 310.0}]}]}
    leg = moorsolve.solve(moorsolve.load_case(data)).leg("A")
    law = {"hooke": lambda T: T / 2.6e7, "baranov": lambda T: 3e-5 * math.sqrt(T),
           "table": table_reference([0.0] + TABLE["strain"], [0.0] + TABLE["tension"])}
    ref = integrate_through_surface(H=leg.horizontal_tension_N, V=leg.fairlead_vertical_N,
                                    L=310.0, w_water=60.0, w_air=240.0, z_top=12.0,
                                    strain=law[stretch["model"]])
    assert ref["X"] == pytest.approx(300.0, abs=1e-8 * 310)
    assert ref["Z"] == pytest.approx(112.0, abs=1e-8 * 310)
    assert ref["VA"] == pytest.approx(leg.anchor_vertical_N, rel=1e-8)
    assert ref["air_length"] > 30.0


# ---- fibre hawsers (weightless lines) ---------------------------------------------------------


NYLON = {"model": "table", "strain": [0.02, 0.05, 0.10, 0.16],
         "tension": [1.5e4, 5e4, 1.3e5, 2.4e5]}


def nylon_hawsers(pretension=None, free=()):
    """The berth of tests/solve/test_berth.py moored by two nylon hawsers (a stiffening
    table law, weightless), each given by a length or by its pretension."""
    from test_berth import away_case
    data = away_case()
    data["bodies"][0]["free"] = list(free)
    data["line_types"]["hawser"] = {"weight_in_water": 0, "stretch": copy.deepcopy(NYLON)}
    if pretension is not None:
        for line in data["lines"]:
            line["segments"] = [{"type": "hawser", "pretension": pretension}]
    return data


def test_a_fibre_hawser_given_by_its_pretension_carries_it_at_the_case_pose():
    """``L = D / (1 + eps(T0))``, eps the table's monotone cubic (the scipy reference), and
    the solved tension is T0 with the body held where the case places it (D = 8.0 m)."""
    result = moorsolve.solve(moorsolve.load_case(nylon_hawsers("30 kN")))
    eps = table_reference([0.0] + NYLON["strain"], [0.0] + NYLON["tension"])(30e3)
    assert 0.02 < eps < 0.05
    for h in result.hawsers:
        assert h["length_m"] == pytest.approx(8.0 / (1 + eps), rel=1e-12)
        assert h["tension_N"] == pytest.approx(30e3, rel=1e-9)


def test_a_load_draws_slack_fibre_hawsers_taut_through_the_law():
    """Two 8.5 m nylon hawsers, slack at rest (chord 8 m), take a load away from the quay
    half each (statics), stretched as the law says: the body moves until the chord is
    ``8.5 (1 + eps(F/2))`` (the hawsers stay parallel to x: equal loads, no yaw)."""
    from test_contact import F
    data = nylon_hawsers(free=("surge",))
    data["bodies"][0]["loads"]["force"] = [2 * F, 0, 0]
    result = moorsolve.solve(moorsolve.load_case(data))
    assert result.certificate.certified
    eps = table_reference([0.0] + NYLON["strain"], [0.0] + NYLON["tension"])(F)
    for name in ("H1", "H2"):
        assert result.leg(name).fairlead_tension_N == pytest.approx(F, rel=1e-6)
    assert result.body["x_m"] == pytest.approx(8.5 * (1 + eps) - 8.0, rel=1e-6)


# ---- lumped-node lines -----------------------------------------------------------------------


def test_lumped_node_rope_converges_to_the_exact_law_catenary():
    """A rope in a still current is discretised (it has drag data) yet feels no flow: its
    fairlead tension tends to the analytic leg's at second order in the element length."""
    data = single_rope(copy.deepcopy(TABLE), extra={"diameter": 0.13,
                                                    "drag": {"normal": 1.2}})
    data["environment"]["current"] = {"speed": 0.0, "toward_deg": 0}
    exact_data = copy.deepcopy(data)
    del exact_data["environment"]["current"]
    exact = moorsolve.solve(moorsolve.load_case(exact_data)).legs[0].fairlead_tension_N
    errors = []
    for n in (20, 40, 80):
        data["solver"] = {"line_elements": n}
        r = moorsolve.solve(moorsolve.load_case(data))
        assert "line_drag" in r.effects
        errors.append(abs(r.legs[0].fairlead_tension_N - exact) / exact)
    assert errors[2] < 1e-4
    assert errors[0] / errors[1] > 3.5 and errors[1] / errors[2] > 3.5   # second order


# ---- checks: fibre on the seabed, minimum tension --------------------------------------------


def test_fibre_rope_on_the_seabed_is_flagged_and_fails_the_checks():
    from moorsolve.checks.run import run_checks
    data = fpu_data()
    data["body"]["loads"]["force"] = [3.5e6, 0, 0]     # toward L1's anchor: L1 goes slack
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case, allow_overload=True)
    l1 = result.leg("L1")
    assert l1.fibre_grounded_m == pytest.approx(l1.segments[1]["grounded_length_m"])
    assert l1.fibre_grounded_m > 1.0
    assert any("fibre rope (polyester160) lies on the seabed" in n for n in result.notes)
    assert l1.to_dict()["fibre_grounded_length_m"] == l1.fibre_grounded_m
    report = run_checks(case, damaged=False)
    items = {(i.leg, i.check): i for i in report.conditions[0].items}
    assert not items[("L1", "fibre on seabed")].passed
    least = items[("L1", "minimum tension")]
    # On the seabed (no friction here) the tension is the horizontal tension.
    assert least.value == pytest.approx(l1.horizontal_tension_N, rel=1e-9)
    assert not least.passed and least.limit == 158e3
    assert items[("L3", "minimum tension")].passed
    assert any(f.startswith("intact: minimum tension of L1") for f in report.failures)


def test_minimum_tension_of_a_suspended_segment_is_found_at_its_vertex():
    from moorsolve.checks.fibre import segment_min_tension
    case = moorsolve.load_case(str(FPU))
    result = moorsolve.solve(case)
    for leg, lr in zip(case.legs, result.legs):
        least = dict((lt.name, t) for lt, t in segment_min_tension(leg, lr))["polyester160"]
        seg = lr.segments[1]
        # Along the segment the tension is sqrt(H^2 + Tv^2), Tv linear: the least of the
        # sampled profile inside the segment is never below it.
        assert least <= min(seg["top_tension_N"], seg["bottom_tension_N"]) + 1e-9
        assert least >= seg["horizontal_tension_N"] - 1e-9


# ---- upper/lower-bound stiffness analysis ----------------------------------------------------


def test_stiffness_bounds_of_the_shipped_case(fpu):
    case, result = fpu
    bounds = moorsolve.stiffness_bounds(case)
    lower, upper = bounds.lower, bounds.upper
    # The lower bound is the working curve itself: the case's own answer.
    assert lower.offset_m == pytest.approx(math.hypot(result.body["x_m"], result.body["y_m"]),
                                           rel=1e-9)
    # The upper bound's EA is the dynamic stiffness at its own mean load (a fixed point).
    info = upper.stiffness["polyester160"]
    mbl = case.line_types["polyester160"].mbl
    mean = max(max(s["top_tension_N"], s["bottom_tension_N"]) for leg in upper.result.legs
               for s in leg.segments if s["type"] == "polyester160")
    assert info["mean_load_N"] == pytest.approx(mean, rel=1e-12)
    assert info["ea_N"] == pytest.approx((11.615 + 0.396 * 100 * mean / mbl) * mbl, rel=1e-8)
    # A stiffer rope: less offset, more tension. Each governs its quantity.
    assert upper.offset_m < lower.offset_m and upper.max_tension[0] > lower.max_tension[0]
    assert bounds.governing_offset is lower and bounds.governing_tension is upper
    d = bounds.to_dict()
    assert d["governing"]["tension"]["bound"] == "upper"
    assert d["governing"]["offset"]["offset_m"] == pytest.approx(lower.offset_m)


def test_bounds_command(capsys, tmp_path):
    assert main(["bounds", str(FPU)]) == 0
    out = capsys.readouterr().out
    assert "worst offset" in out and "with the lower bound" in out
    assert re.search(r"worst tension .* with the upper bound", out)
    assert main(["bounds", str(FPU), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["governing"]["tension"]["bound"] == "upper"
    plain = fpu_data()
    plain["line_types"]["polyester160"].pop("stiffness_bounds")
    path = tmp_path / "plain.yaml"
    path.write_text(yaml.safe_dump(plain))
    assert main(["bounds", str(path)]) == 2
    assert "stiffness_bounds" in capsys.readouterr().err
