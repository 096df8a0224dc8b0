"""The leg block against published single-leg numbers (REFERENCE.md section 4).

Each inverse problem is driven through the quantities the source gives (given H, find the
span; given the span, find H), never by feeding back a rounded published result, and is
checked to the digits the source prints.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

import moorsolve
from moorsolve.physics.catenary import (LegKind, evaluate_leg)
from moorsolve.physics.profile import leg_profile

KGF = 9.80665
INEXTENSIBLE_CONTACT = LegKind(elastic=False, contact=True)


def touchdown_at_anchor(H, Z, w):
    """Line state with touchdown exactly at the anchor for horizontal tension H."""
    V = brentq(lambda V: evaluate_leg(INEXTENSIBLE_CONTACT, 0.0, Z, H, V, 1e6, w)["rZ"],
               1e-9, 1e9)
    L = V / w
    X = evaluate_leg(INEXTENSIBLE_CONTACT, 0.0, Z, H, V, L, w)["rX"]  # span at X = 0
    return V, L, X


def fixed_leg_case(X, Z, L, w, depth=None, ea=None, gravity=9.80665, anchor_z=None):
    """A no-body case: one leg, fairlead fixed in space X m from the anchor."""
    depth = Z if depth is None else depth
    line = {"weight_in_water": w}
    if ea is not None:
        line["ea"] = ea
    anchor = [0.0, 0.0] if anchor_z is None else [0.0, 0.0, anchor_z]
    return moorsolve.load_case({
        "name": "single leg",
        "environment": {"depth": depth, "gravity": gravity},
        "line_types": {"line": line},
        "legs": [{"name": "A", "anchor": anchor, "fairlead": [X, 0.0, Z - depth],
                  "segments": [{"type": "line", "length": L}]}],
    })


class TestMerkinAnchorChain:
    """Merkin 1980 (seed 004), section 2.1: chain partly on the seabed.

    H = 2000 kgf, 25 kgf/m in water, depth 40 m, 150 m paid out: a = 80 m, suspended
    89.443 m, grounded 60.557 m, fairlead to touchdown 76.994 m, to anchor 137.551 m,
    fairlead tension 3000 kgf at 48.19 deg.
    """

    H, w, Z, L = 2000 * KGF, 25 * KGF, 40.0, 150.0

    def test_given_H_find_span(self):
        V = math.sqrt((self.w * self.Z + self.H) ** 2 - self.H ** 2)
        out = evaluate_leg(INEXTENSIBLE_CONTACT, 0.0, self.Z, self.H, V, self.L, self.w)
        assert out["rZ"] == pytest.approx(0.0, abs=1e-12)
        assert self.H / self.w == pytest.approx(80.0, abs=1e-12)
        assert V / self.w == pytest.approx(89.443, abs=5e-4)
        assert out["grounded"] == pytest.approx(60.557, abs=5e-4)
        assert out["suspended_x"] == pytest.approx(76.994, abs=5e-4)
        assert out["rX"] == pytest.approx(137.551, abs=5e-4)
        assert math.hypot(self.H, V) / KGF == pytest.approx(3000.0, abs=5e-3)
        assert math.degrees(math.atan2(V, self.H)) == pytest.approx(48.19, abs=5e-3)

    def test_given_span_find_H(self):
        # The span is printed to 0.001 m; H must lie between the solutions at its ends.
        def H_at(X):
            return moorsolve.solve(fixed_leg_case(X, self.Z, self.L, self.w)).legs[0]
        lo, mid, hi = H_at(137.5505), H_at(137.551), H_at(137.5515)
        assert lo.horizontal_tension_N < 2000 * KGF < hi.horizontal_tension_N
        assert lo.fairlead_tension_N < 3000 * KGF < hi.fairlead_tension_N
        assert mid.grounded_length_m == pytest.approx(60.557, abs=2e-3)
        assert mid.touchdown_from_anchor_m == pytest.approx(137.551 - 76.994, abs=2e-3)


class TestMerkinElasticRope:
    """Merkin 1980 (seed 004), section 2.3: elastic rope between level supports.

    L0 = 110 m, span 100 m, 1.56 kgf/m, EA = 4e6 kgf: H = 102.15617 kgf (inextensible
    102.174), relative stretch 2.8284e-5, top tension 133.407 kgf.
    """

    L, X, w, EA = 110.0, 100.0, 1.56 * KGF, 4e6 * KGF

    def solve_span(self, elastic):
        kind = LegKind(elastic=elastic, contact=False)
        ea_inv = 1 / self.EA if elastic else 0.0

        def residual(z):
            out = evaluate_leg(kind, self.X, 0.0, z[0] * 1e3, z[1] * 1e3, self.L, self.w, ea_inv)
            return [out["rX"], out["rZ"]]
        H, V = np.array(fsolve(residual, [1.0, 0.8], xtol=1e-13)) * 1e3
        return H, V

    def test_elastic_horizontal_tension(self):
        H, V = self.solve_span(elastic=True)
        assert H / KGF == pytest.approx(102.15617, abs=5e-6)
        assert V == pytest.approx(self.w * self.L / 2, rel=1e-10)    # symmetric supports
        assert math.hypot(H, V) / KGF == pytest.approx(133.407, abs=5e-4)

    def test_inextensible_horizontal_tension(self):
        H, _ = self.solve_span(elastic=False)
        assert H / KGF == pytest.approx(102.174, abs=5e-4)

    def test_relative_stretch(self):
        H, V = self.solve_span(elastic=True)
        prof = leg_profile(LegKind(True, False), H=H, V=V, L=self.L, w=self.w, ea=self.EA,
                           mu=0.0, X=self.X, n=20001)
        stretch = np.trapezoid(prof["tension"], prof["s"]) / self.EA / self.L
        assert stretch == pytest.approx(2.8284e-5, abs=5e-9)
        # The profile closes on the far support.
        assert prof["x"][-1] == pytest.approx(self.X, abs=1e-9)
        assert prof["z"][-1] == pytest.approx(0.0, abs=1e-9)


class TestHuTangChains:
    """Hu & Tang 2004 (seed 001), Tables 1-4; w in t/m converted with g = 10."""

    Z = 20.85
    w = 1300.0          # 0.13 t/m, floating dock chain

    def test_table2_pretension_touchdown_at_anchor(self):
        V, L, X = touchdown_at_anchor(372e3, self.Z, self.w)
        assert X == pytest.approx(108.5839, abs=5e-5)
        # Exactly T = H + w Z = 399.1050; the paper's search stopped at 399.1048.
        assert math.hypot(372e3, V) / 1e3 == pytest.approx(399.1048, rel=1e-6)
        assert L == pytest.approx(111.2086, abs=1.5e-4)   # printed value rounds down
        # 7 printed digits, but the paper's search closes the depth only to 1e-5 m.
        assert math.degrees(math.atan2(V, 372e3)) == pytest.approx(21.23776, rel=4e-6)

    def test_table3_typhoon_uplift(self):
        H, X = 1584.6e3, 121.06
        kind = LegKind(elastic=False, contact=True)

        def residual(z):      # unknowns: V [100 kN], L [100 m]
            out = evaluate_leg(kind, X, self.Z, H, z[0] * 1e5, z[1] * 100, self.w)
            return [out["rX"], out["rZ"]]
        V, L = np.array(fsolve(residual, [3.0, 1.22], xtol=1e-13)) * [1e5, 100]
        VA = V - self.w * L
        assert VA > 0
        # The given span is printed to 5 digits (121.06); the uplift angle and force are
        # sensitive to it, so they reproduce to 4e-5 relative rather than to every digit.
        assert math.degrees(math.atan2(VA, H)) == pytest.approx(6.9537, rel=4e-5)
        assert VA / 1e3 == pytest.approx(193.264, rel=4e-5)
        assert math.hypot(H, V) / 1e3 == pytest.approx(1623.448, rel=2e-6)
        assert L == pytest.approx(122.8915, rel=2e-6)

    def test_table4_minimum_anchor_distance(self):
        T = 1623.5e3
        H = T - self.w * self.Z     # touchdown at the anchor: T - H = w Z
        V = math.sqrt(T**2 - H**2)
        L = V / self.w
        out = evaluate_leg(INEXTENSIBLE_CONTACT, 0.0, self.Z, H, V, L, self.w)
        assert out["rZ"] == pytest.approx(0.0, abs=1e-9)
        assert H / 1e3 == pytest.approx(1596.4, abs=0.05)
        # H is given rounded (1596.4; exactly 1596.395): L to 2e-6 relative.
        assert L == pytest.approx(227.2494, rel=2e-6)
        assert math.degrees(math.atan2(V, H)) == pytest.approx(10.48439, rel=4e-6)
        # Printed 255.9719 is a misprint for 225.97 (the span cannot exceed the length).
        assert out["rX"] == pytest.approx(225.97, abs=5e-3)

    def test_table1_ship_chain(self):
        # 0.0517 t/m in 80 m of water; reproduces with H = 89.63 kN (REFERENCE.md).
        # The paper's search stops once the depth matches to its printed 0.01 m (80.00),
        # and H is given to 4 digits: span and length agree to 1e-4 relative.
        V, L, X = touchdown_at_anchor(89.63e3, 80.0, 517.0)
        assert X == pytest.approx(160.74, rel=1e-4)
        assert math.hypot(89.63e3, V) / 1e3 == pytest.approx(130.9, rel=1e-3)
        assert L == pytest.approx(184.78, rel=1e-4)
        assert math.degrees(math.atan2(V, 89.63e3)) == pytest.approx(46.82, abs=5e-3)


class TestMalacicVida:
    """Malacic, "Sidrna veriga" (seed 002): one chain of the buoy Vida.

    Anchor 33 m from the buoy, fairlead 22 m above the seabed, 50 m of chain, 22.0 kg/m
    submerged (g = 9.81): a = 2.4487 m, lift-off 25.674 m from the anchor, slope 9.93 at
    the buoy, horizontal force 528.5 N.
    """

    def test_given_span_find_H(self):
        w = 22.0 * 9.81
        result = moorsolve.solve(fixed_leg_case(33.0, 22.0, 50.0, w, gravity=9.81))
        leg = result.legs[0]
        # 2.44879 exactly; the paper truncates its iteration at 2.4487 (4e-5 relative).
        assert leg.horizontal_tension_N / w == pytest.approx(2.4487, rel=4e-5)
        assert leg.horizontal_tension_N == pytest.approx(528.5, abs=0.05)
        assert leg.touchdown_from_anchor_m == pytest.approx(25.674, abs=5e-4)
        assert leg.fairlead_vertical_N / leg.horizontal_tension_N == pytest.approx(9.93, abs=5e-3)
        assert leg.fairlead_angle_deg == pytest.approx(84.25, abs=5e-3)
        assert not leg.uplift and not leg.slack
