"""The standards' arithmetic of a line's design tension (moorsolve.checks.design_tension),
checked by hand: T_mean 2.0 MN, T_dyn 1.0 MN, MBL 5.0 MN unless said otherwise."""

from __future__ import annotations

import pytest

import moorsolve
from moorsolve.checks.design_tension import design_tension, line_design_tensions
from moorsolve.errors import CaseError

T_MEAN, T_DYN, MBL = 2.0e6, 1.0e6, 5.0e6


@pytest.mark.parametrize("condition, cc, design", [
    ("intact", 1, 1.10 * 2.0e6 + 1.50 * 1.0e6),     # ULS CC1: 3.70 MN
    ("intact", 2, 1.40 * 2.0e6 + 2.10 * 1.0e6),     # ULS CC2: 4.90 MN
    ("damaged", 1, 1.00 * 2.0e6 + 1.10 * 1.0e6),    # ALS CC1: 3.10 MN
    ("damaged", 2, 1.00 * 2.0e6 + 1.25 * 1.0e6),    # ALS CC2: 3.25 MN
])
def test_dnv_os_e301_design_tension_by_hand(condition, cc, design):
    d = design_tension(standard="dnv-os-e301", condition=condition, t_mean=T_MEAN,
                       t_dyn=T_DYN, mbl=MBL, consequence_class=cc)
    assert d.design_N == pytest.approx(design, rel=1e-12)
    assert d.capacity_N == pytest.approx(0.95 * 5.0e6, rel=1e-12)      # 4.75 MN
    assert d.utilisation == pytest.approx(design / 4.75e6, rel=1e-12)
    assert d.t_max_N == 3.0e6
    assert d.passed == (design <= 4.75e6)


@pytest.mark.parametrize("condition, method, sf", [
    ("intact", "quasi_static", 2.00), ("damaged", "quasi_static", 1.43),
    ("intact", "dynamic", 1.67), ("damaged", "dynamic", 1.25)])
def test_api_rp_2sk_design_tension_by_hand(condition, method, sf):
    """MBL / T_max >= SF, T_max = 3.0 MN: utilisation SF x 3.0 / 5.0 (1.20, 0.858, 1.002,
    0.75)."""
    d = design_tension(standard="api-rp-2sk", condition=condition, t_mean=T_MEAN,
                       t_dyn=T_DYN, mbl=MBL, method=method, consequence_class=2)
    assert d.design_N == pytest.approx(sf * 3.0e6, rel=1e-12)
    assert d.capacity_N == 5.0e6
    assert d.utilisation == pytest.approx(sf * 0.6, rel=1e-12)
    assert d.consequence_class is None
    assert set(d.to_dict()) == {"t_mean_N", "t_dyn_N", "t_max_N", "design_N", "capacity_N",
                                "utilisation"}


@pytest.mark.parametrize("kwargs, field", [
    ({"standard": "iso"}, "checks.standard"),
    ({"condition": "broken"}, "condition"),
    ({"method": "static"}, "checks.method"),
    ({"consequence_class": 3}, "checks.consequence_class"),
    ({"t_dyn": -1.0}, "t_dyn"),
    ({"mbl": 0.0}, "mbl"),
    ({"t_mean": float("nan")}, "t_mean"),
])
def test_bad_input_names_the_field(kwargs, field):
    args = dict(standard="dnv-os-e301", condition="intact", t_mean=T_MEAN, t_dyn=T_DYN,
                mbl=MBL)
    args.update(kwargs)
    with pytest.raises(CaseError) as err:
        design_tension(**args)
    assert err.value.field == field


def test_every_line_of_a_result_at_its_worse_end():
    """Two chains of the buoy case: mean tensions from the static result, a dynamic part
    given per end; the worse end and its figures are those of the hand formula."""
    case = moorsolve.load_case({
        "environment": {"depth": 50.0},
        "line_types": {"chain": {"weight_in_water": 1300.0, "ea": 5.6e8, "mbl": 5.0e6}},
        "legs": [{"name": "A", "anchor": [-300.0, 0.0], "fairlead": [0.0, 0.0, -5.0],
                  "segments": [{"type": "chain", "length": 320.0}]},
                 {"name": "B", "anchor": [300.0, 0.0], "fairlead": [0.0, 0.0, -5.0],
                  "segments": [{"type": "chain", "length": 320.0}]}]})
    result = moorsolve.solve(case)
    legs = {leg.name: leg for leg in result.legs}
    out = line_design_tensions(result, {"A": (5.0e5, 1.0e5)}, standard="dnv-os-e301")
    end, d = out["A"]
    ta, tb = legs["A"].anchor_tension_N, legs["A"].fairlead_tension_N
    ua, ub = (1.1 * ta + 1.5 * 5.0e5) / 4.75e6, (1.1 * tb + 1.5 * 1.0e5) / 4.75e6
    assert end == ("anchor" if ua > ub else "fairlead")
    assert d.utilisation == pytest.approx(max(ua, ub), rel=1e-12)
    end_b, d_b = out["B"]                                    # mean only
    assert end_b == "fairlead" and d_b.t_dyn_N == 0.0
    assert d_b.design_N == pytest.approx(1.1 * legs["B"].fairlead_tension_N, rel=1e-12)
    with pytest.raises(CaseError, match="no line named C"):
        line_design_tensions(result, {"C": (0.0, 0.0)}, standard="dnv-os-e301")
