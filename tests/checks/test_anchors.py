"""Anchor capacity: the maker's curves, the padeye transfer, the H-V envelope, the check."""

import math

import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import solve_ivp

from hypothesis_budget import examples

import moorsolve
from moorsolve.catalog.anchors import drag_curve
from moorsolve.checks.anchors import (anchor_criterion, envelope_utilisation,
                                      suction_exponents)
from moorsolve.checks.padeye import clay_resistance, padeye_load
from moorsolve.checks.run import run_checks
from moorsolve.errors import CaseError

# ---- the maker's curves ------------------------------------------------------------------


@pytest.mark.parametrize("soil, a, b", [("soft_clay", 509.96, 0.93),
                                        ("medium_clay", 701.49, 0.93),
                                        ("hard_clay", 904.21, 0.92), ("sand", 904.21, 0.92)])
def test_drag_curves_are_moorpys_stevpris_mk6_fits(soil, a, b):
    # MoorPy 1.3 MoorProps.getAnchorMass, Vryhof Stevpris Mk6: uhc = a (mass/1000)^b * 1000
    # [N, kg]; the coefficients printed there to 2 decimals.
    curve = drag_curve(soil)
    assert (curve.a_kN, curve.b) == (a, b)
    for mass in (1e3, 10e3, 35e3):
        assert curve.capacity_N(mass) == pytest.approx(a * (mass / 1e3) ** b * 1e3, rel=1e-14)
        assert curve.mass_kg(curve.capacity_N(mass)) == pytest.approx(mass, rel=1e-12)


def test_moorpy_gives_the_same_drag_capacity():
    MoorProps = pytest.importorskip("moorpy.MoorProps")
    for soil, name in (("soft_clay", "soft clay"), ("medium_clay", "medium clay"),
                       ("sand", "sand")):
        uhc, _, _ = MoorProps.getAnchorMass(uhc_mode=True, mass_int=12e3, soil_type=name)
        assert drag_curve(soil).capacity_N(12e3) == pytest.approx(uhc, rel=1e-12)


def test_the_contracts_example_10_t_in_soft_clay_holds_4_3_MN():
    assert drag_curve("soft_clay").capacity_N(10e3) == pytest.approx(4.34e6, rel=1e-3)


# ---- padeye transfer ---------------------------------------------------------------------


def _ode(Tm, theta_m, za, d, su0, k, mu, small_angle=False, Nc=8.5, Ab=2.5):
    """Integrate the embedded chain from the mudline down (weightless chain):
    dT/ds = -mu Q, T dtheta/ds = Q, dz/ds = sin(theta) (or theta), Q = A_b d N_c s_u(z)."""
    def rhs(s, y):
        T, th, z = y
        Q = Ab * d * Nc * (su0 + k * z)
        return [-mu * Q, Q / T, th if small_angle else math.sin(th)]

    def bottom(s, y):
        return y[2] - za
    bottom.terminal = True
    sol = solve_ivp(rhs, [0, 50 * za], [Tm, theta_m, 0.0], events=bottom, rtol=1e-12,
                    atol=1e-12, method="DOP853")
    assert sol.status == 1
    return sol.y[0, -1], sol.y[1, -1]


@pytest.mark.parametrize("theta_m_deg", [0.0, 5.0, 12.0])
def test_padeye_transfer_without_friction_is_exact_for_small_angles(theta_m_deg):
    # With mu = 0 and dz/ds = theta the closed form is the exact integral of the ODEs.
    tm, za, d, su0, k = 1.5e6, 8.0, 0.12, 2e3, 1.5e3
    th = math.radians(theta_m_deg)
    zq = clay_resistance(za, diameter=d, su0=su0, su_gradient=k)
    load = padeye_load(tm, th, zq, 0.0)
    T, theta = _ode(tm, th, za, d, su0, k, 0.0, small_angle=True)
    assert load.tension == pytest.approx(T, rel=1e-10)
    assert load.angle == pytest.approx(theta, rel=1e-8)


def test_padeye_transfer_against_the_full_embedded_chain_equations():
    # Neubecker & Randolph's closed form takes small angles and T_a in the profile integral;
    # against the full equations (sin theta, friction) it is within a few per cent.
    # Case of FAModel's example: 160 mm chain, padeye 10 m, s_u = 2.4 + 1.41 z kPa, 1.16 MN.
    tm, za, d, su0, k, mu = 1.16e6, 10.0, 0.16, 2.4e3, 1.41e3, 0.4
    zq = clay_resistance(za, diameter=d, su0=su0, su_gradient=k)
    assert zq == pytest.approx(2.5 * 0.16 * 8.5 * (2.4e3 * 10 + 1.41e3 * 50), rel=1e-14)
    load = padeye_load(tm, 0.0, zq, mu)
    T, theta = _ode(tm, 0.0, za, d, su0, k, mu)
    # the closed form's own equations hold at its root
    assert tm * load.angle ** 2 == pytest.approx(2 * zq * math.exp(mu * load.angle), rel=1e-12)
    assert load.tension == pytest.approx(tm * math.exp(-mu * load.angle), rel=1e-14)
    # seen: closed form 812.8 kN at 50.94 deg, equations 823.0 kN at 49.16 deg
    assert load.tension == pytest.approx(T, rel=0.02)
    assert math.degrees(load.angle) == pytest.approx(math.degrees(theta), abs=2.0)


def test_padeye_transfer_edges():
    # no soil, no tension: nothing changes
    assert padeye_load(1e6, 0.2, 0.0, 0.4).tension == 1e6
    assert padeye_load(0.0, 0.2, 1e5, 0.4).angle == 0.2
    # a soil too strong for the tension: vertical at the padeye, bounded tension, flagged
    load = padeye_load(1e5, 0.0, 1e6, 0.4)
    assert load.vertical and load.angle == math.pi / 2
    assert load.tension == pytest.approx(1e5 * math.exp(-0.4 * math.pi / 2), rel=1e-14)
    # more soil resistance turns the line more and sheds more tension (monotone)
    prev = padeye_load(1e6, 0.05, 1e3, 0.4)
    for zq in (1e4, 5e4, 1e5, 2e5):
        load = padeye_load(1e6, 0.05, zq, 0.4)
        assert load.angle > prev.angle and load.tension < prev.tension
        prev = load
    with pytest.raises(ValueError):
        padeye_load(-1.0, 0.0, 1.0, 0.4)


@settings(max_examples=examples(200), deadline=None)
@given(tension=st.floats(1e3, 5e7), angle=st.floats(0.0, 1.5),
       resistance=st.floats(0.0, 2e7), friction=st.floats(0.0, 1.0))
def test_padeye_transfer_properties(tension, angle, resistance, friction):
    load = padeye_load(tension, angle, resistance, friction)
    assert angle <= load.angle <= math.pi / 2 and 0 <= load.tension <= tension
    if load.vertical:           # no root below 90 deg: f(pi/2) <= 0
        assert tension * ((math.pi / 2) ** 2 - angle ** 2) <= 2 * resistance * math.exp(
            friction * (math.pi / 2 - angle)) * (1 + 1e-12)
    elif resistance > 0:        # the root: T_a / 2 (theta_a^2 - theta_m^2) = z Q_av
        lhs = load.tension * (load.angle ** 2 - angle ** 2) / 2
        assert lhs == pytest.approx(resistance, rel=1e-9, abs=1e-9 * tension)
    assert load.tension == pytest.approx(
        tension * math.exp(-friction * (load.angle - angle)), rel=1e-12)


# ---- suction anchor envelope -------------------------------------------------------------


def test_suction_envelope_exponents_and_corners():
    a, b = suction_exponents(20.0, 5.0)
    assert (a, b) == pytest.approx((4.5, 4.5 + 4.0 / 3.0))
    assert envelope_utilisation(0.7, 0.0, a, b) == 0.7        # pure horizontal corner
    assert envelope_utilisation(0.0, 0.9, a, b) == 0.9        # pure vertical corner
    assert envelope_utilisation(0.0, 0.0, a, b) == 0.0
    # on the envelope: utilisation 1; radial scaling scales it
    x = 0.8
    y = (1 - x ** a) ** (1 / b)
    assert envelope_utilisation(x, y, a, b) == pytest.approx(1.0, rel=1e-12)
    assert envelope_utilisation(0.5 * x, 0.5 * y, a, b) == pytest.approx(0.5, rel=1e-12)


@settings(max_examples=examples(200), deadline=None)
@given(h=st.floats(1e-4, 5.0), v=st.floats(1e-4, 5.0), ratio=st.floats(0.2, 8.0),
       scale=st.floats(0.1, 10.0))
def test_suction_envelope_utilisation_is_radial(h, v, ratio, scale):
    a, b = suction_exponents(ratio, 1.0)
    u = envelope_utilisation(h, v, a, b)
    assert (h / u) ** a + (v / u) ** b == pytest.approx(1.0, rel=1e-10)
    assert max(h, v) <= u * (1 + 1e-12)
    assert envelope_utilisation(scale * h, scale * v, a, b) == pytest.approx(scale * u,
                                                                             rel=1e-10)


# ---- the check, end to end ---------------------------------------------------------------


def _case(anchors, anchor_type="drag", standard="api-rp-2sk"):
    return {
        "name": "three legs", "environment": {"depth": 100},
        "line_types": {"ch": {"catalog": "studless_r4", "diameter": "120 mm"}},
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": [1.5e6, 0, 0]}},
        "legs": [{"name": n, "anchor": a, "fairlead": f,
                  "segments": [{"type": "ch", "length": 640}]} for n, a, f in (
            ("L1", [-600, 0], [-20, 0, 0]), ("L2", [300, 520], [10, 17.3, 0]),
            ("L3", [300, -520], [10, -17.3, 0]))],
        "checks": {"standard": standard, "damaged": False,
                   "anchor": ({"type": "pile", "allowed_uplift_angle_deg": 20}
                              if anchor_type == "pile" else {"type": anchor_type}),
                   "anchors": anchors}}


def _items(report):
    return [i for c in report.conditions for i in c.items if i.check == "anchor capacity"]


def test_drag_anchor_check_with_embedment():
    emb = {"padeye_depth": "10 m", "su0": "2.4 kPa", "su_gradient": "1.41 kPa/m"}
    report = run_checks(moorsolve.load_case(_case(
        {"drag": {"fluke_weight": "10 t", "soil": "soft_clay", "embedment": emb}})))
    item = next(i for i in _items(report) if i.leg == "L1")
    d = item.detail
    T = report.conditions[0].result.leg("L1").anchor_tension_N
    assert d["mudline_tension_N"] == T and d["mudline_angle_deg"] == 0.0
    zq = clay_resistance(10.0, diameter=0.12, su0=2.4e3, su_gradient=1.41e3)
    load = padeye_load(T, 0.0, zq, 0.4)
    assert d["padeye_tension_N"] == pytest.approx(load.tension, rel=1e-12)
    assert item.utilisation == pytest.approx(1.8 * load.tension / drag_curve(
        "soft_clay").capacity_N(10e3), rel=1e-12)
    assert item.passed == (item.utilisation <= 1)
    # the least Stevpris Mk6 that holds the design load: the curve inverted
    required = d["required_mass_kg"]
    assert drag_curve("soft_clay").capacity_N(required) == pytest.approx(d["design_N"],
                                                                       rel=1e-12)
    assert required / 10e3 == pytest.approx(item.utilisation ** (1 / 0.93), rel=1e-12)
    # the uplift rule stays for a drag anchor
    assert any(i.check == "anchor uplift" for i in report.conditions[0].items)
    from moorsolve.report.check_text import check_json, format_check_table
    assert "anchor capacity" in format_check_table(report)
    assert '"padeye_angle_deg"' in check_json(report)


def test_drag_capacity_given_fails_when_too_small():
    report = run_checks(moorsolve.load_case(_case({"drag": {"capacity": "1 MN"}})))
    worst = max(_items(report), key=lambda i: i.utilisation)
    T = report.conditions[0].result.leg(worst.leg).anchor_tension_N
    assert worst.utilisation == pytest.approx(1.8 * T / 1e6, rel=1e-12)
    assert not worst.passed and not report.passed


def test_suction_and_pile_checks():
    suction = {"h_max": "6 MN", "v_max": "4 MN", "length": "15 m", "diameter": "5 m",
               "embedment": {"padeye_depth": "8 m", "su0": "2 kPa", "su_gradient": "1.5 kPa/m"}}
    report = run_checks(moorsolve.load_case(_case({"suction": suction}, "suction")))
    assert not any(i.check.startswith("anchor uplift") for i in report.conditions[0].items)
    item = next(i for i in _items(report) if i.leg == "L1")
    d = item.detail
    a, b = suction_exponents(15.0, 5.0)
    u = envelope_utilisation(1.6 * d["padeye_horizontal_N"] / 6e6,
                             2.0 * d["padeye_vertical_N"] / 4e6, a, b)
    assert item.utilisation == pytest.approx(u, rel=1e-12)
    pile = {"h_max": "3 MN", "v_max": "1 MN"}
    report = run_checks(moorsolve.load_case(_case({"pile": pile}, "pile")))
    item = next(i for i in _items(report) if i.leg == "L1")
    # no embedment: the padeye is at the mudline, the line lies on the seabed (V = 0)
    assert item.utilisation == pytest.approx(
        1.6 * item.detail["padeye_horizontal_N"] / 3e6, rel=1e-12)


def test_dnv_drag_uses_the_line_factors_and_gamma_m():
    report = run_checks(moorsolve.load_case(_case({"drag": {"capacity": "5 MN"}},
                                                  standard="dnv-os-e301")))
    item = next(i for i in _items(report) if i.leg == "L1")
    T = item.detail["mudline_tension_N"]
    row = anchor_criterion("dnv-os-e301", "drag", "intact", "quasi-static", 1)
    assert item.utilisation == pytest.approx(1.10 * T / (5e6 / row.material_factor),
                                             rel=1e-12)


def test_a_missing_design_fails_with_its_reason():
    report = run_checks(moorsolve.load_case(_case({"pile": {"h_max": 1e6, "v_max": 1e6}})))
    assert all(not i.passed and "checks.anchors.drag" in i.criterion for i in _items(report))


@pytest.mark.parametrize("anchors, field", [
    ({"drag": {"fluke_weight": "10 t", "soil": "mud"}}, "checks.anchors.drag.soil"),
    ({"drag": {"capacity": -1}}, "checks.anchors.drag.capacity"),
    ({"drag": {"capacity": "4 MN", "soil": "sand"}}, "checks.anchors.drag.soil"),
    ({"drag": {}}, "checks.anchors.drag"),
    ({"suction": {"h_max": 1e6, "v_max": 1e6, "length": 10}},
     "checks.anchors.suction.diameter"),
    ({"suction": {"h_max": 1e6, "v_max": 1e6, "length": 10, "diameter": 4,
                  "embedment": {"padeye_depth": 12, "su0": 1e3, "su_gradient": 1e3}}},
     "checks.anchors.suction.embedment.padeye_depth"),
    ({"pile": {"h_max": 1e6, "v_max": 1e6, "embedment": {"padeye_depth": 5, "su0": 0,
                                                         "su_gradient": 0}}},
     "checks.anchors.pile.embedment.su0"),
    ({"pile": {"h_max": 1e6, "v_max": 1e6, "embedment": {"padeye_depth": 5,
                                                         "su0": "5 kN"}}},
     "checks.anchors.pile.embedment.su_gradient"),
    ({"gravity": {}}, "checks.anchors.gravity"),
])
def test_bad_anchor_input_names_the_field(anchors, field):
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(_case(anchors))
    assert err.value.field == field


def test_embedded_non_catalogue_line_needs_its_diameter():
    data = _case({"drag": {"capacity": "5 MN", "embedment": {
        "padeye_depth": 5, "su0": 2e3, "su_gradient": 1e3}}})
    data["line_types"] = {"ch": {"weight_in_water": 2500, "ea": 1e9, "mbl": 1e7}}
    with pytest.raises(CaseError) as err:
        run_checks(moorsolve.load_case(data))
    assert err.value.field == "checks.anchors.drag.embedment.line_diameter"


def test_cli_bad_anchor_input_exits_2_naming_the_field(tmp_path, capsys):
    import yaml
    from moorsolve.cli import main
    data = _case({"drag": {"fluke_weight": "10 t", "soil": "peat"}})
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "checks.anchors.drag.soil" in err and "Traceback" not in err


def test_design_offset_method_checks_the_anchor_at_the_design_offset():
    # API RP 2SK in a sea state: the anchor load is the held (design offset) solve's.
    import yaml
    from pathlib import Path
    data = yaml.safe_load((Path(__file__).parents[2] / "cases" / "buoy_sea.yaml").read_text())
    data["checks"] = dict(data.get("checks") or {}, standard="api-rp-2sk", damaged=False,
                          method="quasi_static",
                          anchor={"type": "pile", "allowed_uplift_angle_deg": 89},
                          anchors={"pile": {"h_max": "200 kN", "v_max": "150 kN"}})
    report = run_checks(moorsolve.load_case(data))
    c = report.conditions[0]
    assert c.method == "design offset"
    for item in (i for i in c.items if i.check == "anchor capacity"):
        held = c.held.leg(item.leg)
        assert item.detail["mudline_tension_N"] == held.anchor_tension_N
        assert item.detail["mudline_tension_N"] != c.result.leg(item.leg).anchor_tension_N
        assert item.utilisation == pytest.approx(max(
            1.6 * item.detail["padeye_horizontal_N"] / 200e3,
            2.0 * item.detail["padeye_vertical_N"] / 150e3), rel=1e-12)


def test_with_line_dynamics_the_anchor_takes_its_ends_dynamic_tension():
    # DNV-OS-E301 with the lines' own dynamics: the anchor's load is the anchor end's mean
    # tension plus its characteristic dynamic part (sigma_T sqrt(2 ln N) at that end), not
    # the quasi-static tension at the design offset.
    import yaml
    from pathlib import Path
    data = yaml.safe_load((Path(__file__).parents[2] / "cases" / "buoy_sea.yaml").read_text())
    data["checks"] = dict(data.get("checks") or {}, standard="dnv-os-e301", damaged=False,
                          anchors={"drag": {"capacity": "2 MN"}})
    report = run_checks(moorsolve.load_case(data))
    c = report.conditions[0]
    assert c.method == "dynamic"
    items = [i for i in c.items if i.check == "anchor capacity"]
    assert len(items) == 3
    for item in items:
        sea = c.tensions[item.leg].anchor
        t_mean = c.result.leg(item.leg).anchor_tension_N
        assert sea.t_dyn_N > 0
        assert item.detail["mudline_tension_N"] == pytest.approx(t_mean + sea.t_dyn_N,
                                                                 rel=1e-12)
        # 1.10 T_mean + 1.50 T_dyn against UHC / 1.3 (drag, consequence class 1)
        assert item.detail["design_N"] == pytest.approx(1.10 * t_mean + 1.50 * sea.t_dyn_N,
                                                        rel=1e-12)
