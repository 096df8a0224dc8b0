"""A one-segment line with both ends above the water (moorsolve/physics/air.py), against an
independent integration of the line's ODE whose weight per length changes wherever the
line crosses the surface (``reference_ode.integrate_air_and_water``: scipy DOP853, an event
at every crossing, no code shared with moorsolve).

Regimes: in air throughout (the vertex above the water), dipping into the water between two
parts in air, and the lower end under the water (one crossing); Hooke, inextensible, and the
stretch laws (monotone-cubic and linear tables, Baranov). The block's spans close at the
ODE's spans, its end forces and length in air are the ODE's; its derivative is the central
difference of its residuals; it is continuous where the regimes meet; the profile drawn
from a solved state meets both ends.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from reference_ode import integrate_air_and_water, linear_table_reference, table_reference

from moorsolve.physics.air import air_line, air_line_profile
from moorsolve.physics.catenary import LegKind, air_part, leg_function
from moorsolve.physics.stretch import Law, NumericLaw, StretchModel

STRAIN = [0.0, 0.01, 0.02, 0.035, 0.05, 0.07]
TENSION = [0.0, 1.0e4, 3.0e4, 7.0e4, 1.2e5, 2.0e5]
BARANOV_N = 2.5e-4                      # 5 % strain at 40 kN

#: name -> (EA or None, law model, law parameters, strain function for the ODE)
LAWS = {
    "hooke": (2e7, None, None, None),
    "inextensible": (None, None, None, None),
    "table": (None, StretchModel("table", 6), STRAIN + TENSION,
              table_reference(STRAIN, TENSION)),
    "table_linear": (None, StretchModel("table", 6, "linear"), STRAIN + TENSION,
                     linear_table_reference(STRAIN, TENSION)),
    "baranov": (None, StretchModel("baranov"), [BARANOV_N],
                lambda T: BARANOV_N * math.sqrt(T)),
}

#: (H, V at the upper end, z_top, L): a chain bridle (w 1300 N/m in water, 1500 in air)
REGIMES = {
    "in_air": (5e4, 1.5e4, 3.0, 12.0),         # vertex above the water
    "dips": (2e3, 1.5e4, 3.0, 20.0),           # two crossings, end A above the water
    "dips_taut": (2.95e4, 1.05e4, 1.0, 16.0),
    "under": (2e3, 2e4, 3.0, 20.0),            # one crossing, end A under the water
    "under_deep": (5e3, 4e4, 2.0, 35.0),
}
W, W_AIR = 1300.0, 1500.0


def _block(law_name, X, Z, H, V, z_top, L):
    ea, model, params, _ = LAWS[law_name]
    syms = [ca.SX.sym(n) for n in ("X", "Z", "H", "V")]
    law = Law(model, params) if model is not None else None
    out = air_line(*syms, z_top, L, W, W_AIR, 1.0 / ea if ea else 0.0, law=law)
    names = ("rX", "rZ", "VA", "in_air")
    J = ca.jacobian(ca.vertcat(out["rX"], out["rZ"]), ca.vertcat(syms[2], syms[3]))
    fn = ca.Function("b", syms, [out[k] for k in names] + [J])
    vals = fn(X, Z, H, V)
    return {k: float(v) for k, v in zip(names, vals[:4])} | {"J": np.array(vals[4])}, fn


def _ode(law_name, H, V, z_top, L):
    ea, _, _, strain = LAWS[law_name]
    return integrate_air_and_water(H=H, V=V, L=L, w_water=W, w_air=W_AIR, z_top=z_top,
                                   ea=ea, strain=strain)


@pytest.mark.parametrize("law_name", sorted(LAWS))
@pytest.mark.parametrize("regime", sorted(REGIMES))
def test_block_closes_at_the_odes_spans(law_name, regime):
    """At the ODE's spans the residuals vanish (1e-9 of the length) and the lower end's
    vertical force and the length in air are the ODE's (1e-9)."""
    H, V, z_top, L = REGIMES[regime]
    ref = _ode(law_name, H, V, z_top, L)
    expected = {"in_air": 0, "dips": 2, "dips_taut": 2, "under": 1, "under_deep": 1}[regime]
    assert len(ref["crossings"]) == expected
    out, _ = _block(law_name, ref["X"], ref["Z"], H, V, z_top, L)
    T = math.hypot(H, V)
    assert abs(out["rX"]) <= 1e-9 * L and abs(out["rZ"]) <= 1e-9 * L, out
    assert out["VA"] == pytest.approx(ref["VA"], abs=1e-9 * T)
    assert out["in_air"] == pytest.approx(ref["air_length"], abs=1e-9 * L)


@pytest.mark.parametrize("law_name", ["hooke", "table", "table_linear", "baranov"])
@pytest.mark.parametrize("regime", sorted(REGIMES))
def test_span_derivative_is_the_central_difference(law_name, regime):
    """``d(rX, rZ)/d(H, V)`` (what Newton and the certificate use) against central
    differences of the residuals, step 1e-6 of the tension, to 1e-6."""
    H, V, z_top, L = REGIMES[regime]
    ref = _ode(law_name, H, V, z_top, L)
    out, fn = _block(law_name, ref["X"], ref["Z"], H, V, z_top, L)
    T = math.hypot(H, V)
    h = 1e-6 * T
    for j, (dH, dV) in enumerate([(h, 0.0), (0.0, h)]):
        plus = fn(ref["X"], ref["Z"], H + dH, V + dV)
        minus = fn(ref["X"], ref["Z"], H - dH, V - dV)
        for i in range(2):
            cd = (float(plus[i]) - float(minus[i])) / (2 * h)
            assert out["J"][i, j] == pytest.approx(cd, rel=1e-6, abs=1e-9 * L / T)


@pytest.mark.parametrize("law_name", ["hooke", "table", "baranov"])
def test_regimes_meet_continuously(law_name):
    """Where the vertex just touches the surface (in air / dipping: the crossing's vertical
    tension is 0) and where end A is at the surface (dipping / under: the water run is
    the length that brings the line back up), found by bisection on the part in air, the
    residuals and the lower end's force are continuous: their change across the switch
    vanishes with the step. Where the vertex grazes the surface the length in water grows
    as the square root of the dip, so there the change falls as the step's square root
    (a factor 10 per two decades), elsewhere linearly."""
    H, z_top, L = 2e3, 3.0, 20.0
    ea, model, params, _ = LAWS[law_name]
    law = Law(model, params) if model is not None else None
    c = 1.0 / ea if ea else 0.0

    def top(V):
        part = air_part(H, V, z_top, W_AIR, c, law=law)
        return float(part["V"]), float(part["length"])

    def touches(V):                    # > 0 once the line reaches the water
        return top(V)[0]

    def under(V):                      # > 0 once end A is under the water
        Vc, lB = top(V)
        return 2 * Vc / W - (L - lB)

    ref = _ode(law_name, H, 2e4, z_top, L)
    _, fn = _block(law_name, ref["X"], ref["Z"], H, 2e4, z_top, L)
    for g, a, b in ((touches, 1e3, 5e4), (under, 1e4, 5e4)):
        assert g(a) < 0 < g(b)
        for _ in range(200):
            m = (a + b) / 2
            a, b = (m, b) if g(m) < 0 else (a, m)
            if b - a <= 1e-12 * b:
                break
        V0 = (a + b) / 2
        jumps = []
        for rel in (1e-6, 1e-8, 1e-10):
            dV = rel * math.hypot(H, V0)
            low = np.array([float(v) for v in fn(ref["X"], ref["Z"], H, V0 - dV)[:3]])
            high = np.array([float(v) for v in fn(ref["X"], ref["Z"], H, V0 + dV)[:3]])
            jumps.append(np.abs(high - low) / np.array([L, L, math.hypot(H, V0)]))
        assert np.all(jumps[2] <= 1e-5), jumps
        assert np.all(jumps[2] <= jumps[1] / 5 + 1e-15), jumps
        assert np.all(jumps[1] <= jumps[0] / 5 + 1e-15), jumps


@pytest.mark.parametrize("law_name", ["hooke", "inextensible", "table"])
@pytest.mark.parametrize("regime", sorted(REGIMES))
def test_profile_meets_both_ends_and_the_ode(law_name, regime):
    """The profile of a solved state runs from end A (0, z_top - Z) to end B (X, z_top),
    its arc length from 0 to L, its lowest point the ODE's, and it is above the water
    exactly along the ODE's length in air (to the profile's resolution)."""
    H, V, z_top, L = REGIMES[regime]
    ea, model, params, _ = LAWS[law_name]
    ref = _ode(law_name, H, V, z_top, L)
    law = NumericLaw(model, tuple(params)) if model is not None else None
    prof = air_line_profile(H=H, V=V, z_top=z_top, L=L, w=W, w_air=W_AIR, ea=ea, n=601,
                            law=law)
    assert prof["s"][0] == pytest.approx(0.0, abs=1e-12) and prof["s"][-1] == pytest.approx(L)
    assert prof["x"][0] == pytest.approx(0.0, abs=1e-12)
    assert prof["x"][-1] == pytest.approx(ref["X"], abs=1e-9 * L)
    assert prof["z"][-1] == pytest.approx(z_top, abs=1e-12)
    assert prof["z"][0] == pytest.approx(z_top - ref["Z"], abs=1e-9 * L)
    assert np.all(np.diff(prof["s"]) >= 0)
    assert prof["tension"][0] == pytest.approx(math.hypot(H, ref["VA"]), rel=1e-9)
    steps = np.hypot(np.diff(prof["x"]), np.diff(prof["z"]))
    assert np.max(steps) <= 2 * L / 100


def test_with_one_weight_it_is_the_suspended_leg():
    """With the same weight in air as in water the line is one catenary: the block is the
    suspended leg block's, to round-off, in every regime."""
    fn = leg_function(LegKind(elastic=True, contact=False))
    for H, V, z_top, L in REGIMES.values():
        ref = integrate_air_and_water(H=H, V=V, L=L, w_water=W, w_air=W, z_top=z_top, ea=2e7)
        X, Z = ref["X"] * 1.001, ref["Z"] * 0.999
        out = air_line(X, Z, H, V, z_top, L, W, W, 5e-8)
        leg = fn(X=X, Z=Z, u=H, V=V, L=L, w=W, ea_inv=5e-8, mu=0.0)
        for k in ("rX", "rZ", "VA"):
            assert float(out[k]) == pytest.approx(float(leg[k]), rel=1e-10, abs=1e-10 * L), k
