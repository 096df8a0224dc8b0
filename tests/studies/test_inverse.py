"""Hu & Tang's inverse questions (seed 001, Tables 1-4) through moorsolve.studies.inverse.

Each is driven by the quantities the paper gives (REFERENCE.md section 4) with tolerances
matching the printed digits; w in t/m is converted with g = 10 as in the paper.
"""

import math

import pytest

from moorsolve.cli import main
from moorsolve.studies.inverse import (
    minimum_anchor_distance,
    required_chain_length,
    uplift_at_distance,
)

Z, W = 20.85, 1300.0        # floating dock: fairlead height, 0.13 t/m


def test_table2_minimum_distance_at_pretension():
    a = minimum_anchor_distance(Z, W, horizontal_tension=372e3)
    assert a.anchor_distance_m == pytest.approx(108.5839, abs=5e-5)
    assert a.fairlead_tension_N / 1e3 == pytest.approx(399.1048, rel=1e-6)
    assert a.length_m == pytest.approx(111.2086, abs=1.5e-4)
    assert a.fairlead_angle_deg == pytest.approx(21.23776, rel=4e-6)
    assert a.anchor_vertical_N == pytest.approx(0.0, abs=1e-3)
    assert a.anchor_distance_m < 120.0        # the paper's 120 m anchor distance suffices


def test_table4_minimum_distance_for_a_fairlead_tension():
    a = minimum_anchor_distance(Z, W, fairlead_tension=1623.5e3)
    assert a.horizontal_tension_N / 1e3 == pytest.approx(1596.4, abs=0.05)
    assert a.length_m == pytest.approx(227.2494, rel=2e-6)
    assert a.fairlead_angle_deg == pytest.approx(10.48439, rel=4e-6)
    assert a.anchor_distance_m == pytest.approx(225.97, abs=5e-3)   # printed 255.97: misprint


def test_table3_uplift_at_given_distance():
    a = uplift_at_distance(Z, W, 121.06, horizontal_tension=1584.6e3)
    assert a.uplift_angle_deg == pytest.approx(6.9537, rel=4e-5)
    assert a.anchor_vertical_N / 1e3 == pytest.approx(193.264, rel=4e-5)
    assert a.fairlead_tension_N / 1e3 == pytest.approx(1623.448, rel=2e-6)
    assert a.length_m == pytest.approx(122.8915, rel=2e-6)
    # Beyond the minimum distance the same load lifts nothing.
    far = uplift_at_distance(Z, W, 300.0, horizontal_tension=1584.6e3)
    assert far.anchor_vertical_N == 0.0 and far.grounded_length_m > 0


def test_table1_ship_chain_and_required_length():
    a = minimum_anchor_distance(80.0, 517.0, horizontal_tension=89.63e3)
    assert a.anchor_distance_m == pytest.approx(160.74, rel=1e-4)
    assert a.fairlead_tension_N / 1e3 == pytest.approx(130.9, rel=1e-3)
    assert a.length_m == pytest.approx(184.78, rel=1e-4)
    # 45 m kept on the seabed and 15 m inboard: L = 184.78 + 45 + 15 = 244.78 m.
    c = required_chain_length(80.0, 517.0, 45.0, horizontal_tension=89.63e3,
                              inboard_length=15.0)
    assert c.grounded_length_m == pytest.approx(45.0, abs=1e-6)
    assert c.length_m == pytest.approx(a.length_m + 45.0, rel=1e-9)
    assert c.order_length_m == pytest.approx(244.78, rel=1e-4)
    assert c.anchor_distance_m == pytest.approx(a.anchor_distance_m + 45.0, rel=1e-9)


def test_elastic_line_needs_a_little_less_chain():
    rigid = minimum_anchor_distance(Z, W, horizontal_tension=372e3)
    elastic = minimum_anchor_distance(Z, W, horizontal_tension=372e3, ea=5.6e8)
    assert elastic.length_m < rigid.length_m
    assert elastic.anchor_distance_m > rigid.anchor_distance_m
    assert elastic.anchor_distance_m - rigid.anchor_distance_m < 0.1


def test_bad_inputs():
    with pytest.raises(ValueError):
        minimum_anchor_distance(Z, W, fairlead_tension=1e3)       # cannot lift its own chain
    with pytest.raises(ValueError):
        minimum_anchor_distance(Z, W)
    with pytest.raises(ValueError):
        uplift_at_distance(Z, -W, 100.0, horizontal_tension=1e5)
    with pytest.raises(ValueError):
        required_chain_length(Z, W, -1.0, horizontal_tension=1e5)
    # An anchor almost under the fairlead still has a (steep, strongly lifting) answer.
    steep = uplift_at_distance(Z, W, 1.0, horizontal_tension=1e6)
    assert steep.uplift_angle_deg > 80


def test_cli_inverse_commands(capsys):
    argv = ["--height", "20.85 m", "--weight", "0.13 t/m", "--gravity", "10"]
    assert main(["anchor-distance", *argv, "--tension", "1623.5 kN"]) == 0
    assert "225.97" in capsys.readouterr().out
    assert main(["uplift", *argv, "--distance", "121.06", "--horizontal-tension",
                 "1584.6 kN", "--json"]) == 0
    import json
    data = json.loads(capsys.readouterr().out)
    assert math.isclose(data["uplift_angle_deg"], 6.9537, rel_tol=4e-5)
    assert main(["chain-length", *argv, "--horizontal-tension", "372 kN",
                 "--grounded", "45 m"]) == 0
    capsys.readouterr()
    assert main(["anchor-distance", *argv, "--tension", "12 parsecs"]) == 2
    assert "--tension" in capsys.readouterr().err


@pytest.mark.parametrize("H", [1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6])
def test_any_horizontal_tension_down_to_a_nearly_vertical_line(H):
    """Issue 20: a tiny horizontal tension (a nearly vertical line) gave "no equilibrium"
    where the answer exists. Closed form of the inextensible line touching down at its
    anchor: ``V = sqrt((H + w h)^2 - H^2)``, ``X = (H/w) asinh(V/H)``, ``L = V/w``."""
    from moorsolve.studies import inverse
    w, h = 1275.0, 20.0
    V = math.sqrt((H + w * h) ** 2 - H**2)
    X = (H / w) * math.asinh(V / H)
    least = inverse.minimum_anchor_distance(h, w, horizontal_tension=H)
    assert least.anchor_distance_m == pytest.approx(X, rel=1e-8, abs=1e-12)
    assert least.length_m == pytest.approx(V / w, rel=1e-10)
    chain = inverse.required_chain_length(h, w, 10.0, horizontal_tension=H)
    assert chain.length_m == pytest.approx(V / w + 10.0, rel=1e-10)
    assert chain.anchor_distance_m == pytest.approx(X + 10.0, rel=1e-10)
    up = inverse.uplift_at_distance(h, w, X + 5.0, horizontal_tension=H)
    assert up.grounded_length_m == pytest.approx(5.0, rel=1e-8)
