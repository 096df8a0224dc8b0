"""The free surface as a boundary: the surface blocks against an independent ODE integration.

``reference_ode.integrate_from_anchor`` integrates a buoyant line from its anchor end with
scipy (DOP853, rtol 1e-13), lying it along a horizontal boundary at its vertex for a given
length; it shares no code with ``moorsolve.physics``. Each drawn line is placed so that the
boundary is the free surface: for a floating line the anchor's depth is the ODE's own
height of the vertex, for a suspended one the surface is above the ODE's highest point. The
block (:func:`~moorsolve.physics.catenary.surface_leg_equations`, solved from the anchor and
from the fairlead) must then close both spans at the ODE's state, give the ODE's end forces,
the floating length and the touch-up point, to 1e-8 relative.

Regimes: suspended below the surface (possibly rising above the anchor and dipping back),
floating up to a fairlead at the surface, floating and leaving the surface again down to a
fairlead below it, slack (H = 0: straight up to the surface, loose line floating), and near
the contact edge (the vertex a hair below the surface, or a hair of floating line).
"""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from hypothesis_budget import examples
from reference_ode import integrate_from_anchor

from moorsolve.physics.segments import evaluate_surface_leg

REL = 1e-8
REGIMES = ("suspended", "float_to_fairlead", "float_two_sided", "slack", "edge")


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0 ** e)


@st.composite
def buoyant_lines(draw, regime=None):
    """A buoyant line, its state at the anchor, and where the surface is."""
    regime = draw(st.sampled_from(REGIMES)) if regime is None else regime
    L = draw(log_uniform(1.0, 3000.0))
    w = -draw(log_uniform(0.1, 1e4))
    ea = draw(st.none() | log_uniform(1e3, 1e13))
    WL = -w * L
    H = 0.0 if regime == "slack" else draw(log_uniform(1e-4, 1e3)) * WL
    float_length = 0.0
    if regime == "suspended":
        # Any anchor force; the surface above the highest point.
        VA = WL * draw(st.floats(-1.0, 2.0))
    else:
        # Rising from the anchor to a vertex inside the line.
        s_v = L * draw(st.floats(0.02, 0.98))
        VA = -w * s_v
        rest = L - s_v
        if regime == "float_to_fairlead":
            float_length = rest
        elif regime == "edge":
            float_length = rest * draw(st.sampled_from([0.0, 1e-9, 1e-6]))
        else:
            float_length = rest * draw(st.floats(0.05, 0.95))
    ref = integrate_from_anchor(HA=H, VA=VA, L=L, w=w, ea=ea, float_length=float_length)
    if regime == "suspended" or (regime == "edge" and float_length == 0.0):
        gap = L * draw(st.sampled_from([0.0, 1e-6, 0.1, 1.0])) if regime == "suspended" \
            else L * 1e-9
        depth_anchor = ref["z_max"] + gap
    else:
        depth_anchor = ref["z_vertex"]
    # A slack line floats loose: part of its floating length is not stretched out.
    loose = float_length * draw(st.floats(0.0, 1.0)) if regime == "slack" else 0.0
    return dict(regime=regime, L=L, w=w, ea=ea, H=H, VA=VA, float_length=float_length,
                loose=loose, ref=ref, depth_anchor=depth_anchor,
                depth_fairlead=depth_anchor - ref["Z"])


def errors(line, from_fairlead):
    ref = line["ref"]
    ea_inv = 0.0 if line["ea"] is None else 1.0 / line["ea"]
    u = line["H"] if line["loose"] == 0.0 else line["w"] * line["loose"]
    # The unknown V: the fairlead's vertical force, or from the fairlead end the anchor's
    # force on the line (minus the line's pull on the anchor).
    V = -line["VA"] if from_fairlead else ref["VF"]
    d = max(line["depth_fairlead"], 0.0) if from_fairlead else line["depth_anchor"]
    out = evaluate_surface_leg(line["ea"] is not None, from_fairlead, ref["X"] - line["loose"],
                               ref["Z"], u, V, line["L"], line["w"], ea_inv, d)
    t_max = max(math.hypot(line["H"], line["VA"]), math.hypot(ref["HF"], ref["VF"]),
                abs(line["w"]) * line["L"])
    size = line["L"] * (1.0 + t_max * ea_inv)
    err = {"X": abs(out["rX"]) / size, "Z": abs(out["rZ"]) / size,
           "H": abs(out["H"] - line["H"]) / t_max,
           "VF": abs(out["VF"] - ref["VF"]) / t_max,
           "VA": abs(out["VA"] - line["VA"]) / t_max,
           "floating": abs(out["floating"] - line["float_length"]) / line["L"]}
    if line["float_length"] > 1e-6 * line["L"] and line["H"] > 0:
        err["touchup"] = abs(out["touchup_x"] - ref["x_vertex"]) / size
    return err, out


@settings(max_examples=examples(300), deadline=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(buoyant_lines(), st.booleans())
def test_surface_block_matches_the_ode(line, from_fairlead):
    if from_fairlead and line["depth_fairlead"] < 0:
        from_fairlead = False
    event(line["regime"] + (" from fairlead" if from_fairlead else " from anchor"))
    err, out = errors(line, from_fairlead)
    worst = max(err, key=err.get)
    # The block floors its square roots at 1e-9 N (derivatives at H = V = 0): on the drawn
    # lines of a tenth of a newton per metre that alone moves a span by 1e-9 N / |w|.
    allowed = REL + 1e-9 / (abs(line["w"]) * line["L"])
    assert err[worst] <= allowed, (worst, err, line, out)


@pytest.mark.parametrize("regime", REGIMES)
@pytest.mark.parametrize("from_fairlead", [False, True])
@settings(max_examples=examples(20), deadline=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_every_surface_regime_is_exercised(regime, from_fairlead, data):
    line = data.draw(buoyant_lines(regime))
    if from_fairlead and line["depth_fairlead"] < 0:
        return
    err, out = errors(line, from_fairlead)
    assert max(err.values()) <= REL, (err, line, out)


def test_floating_hose_closed_form():
    """Inextensible hose, anchor 30 m down, fairlead at the surface 100 m away, 120 m long.

    Closed form: the suspended part is a catenary with its vertex at the surface, so with
    ``a = H/|w|``, ``d = a (cosh(x_s/a) - 1)`` and ``s = a sinh(x_s/a)``; the rest floats:
    ``X = x_s + (L - s)``. For a = 20 m: x_s = a acosh(1 + d/a) = 20 acosh(2.5).
    """
    w, a, d = -50.0, 20.0, 30.0
    x_s = a * math.acosh(1 + d / a)
    s = a * math.sinh(x_s / a)
    L = 120.0
    X = x_s + (L - s)
    for from_fairlead in (False, True):
        V = -(-w * s) if from_fairlead else 0.0
        out = evaluate_surface_leg(False, from_fairlead, X, d, a * -w, V, L, w, 0.0,
                                   0.0 if from_fairlead else d)
        assert abs(out["rX"]) < 1e-12 * L and abs(out["rZ"]) < 1e-12 * L, out
        assert out["floating"] == pytest.approx(L - s, rel=1e-12)
        assert out["VA"] == pytest.approx(-w * s, rel=1e-12)
        assert out["VF"] == pytest.approx(0.0, abs=1e-9)
        assert out["touchup_x"] == pytest.approx(x_s, rel=1e-12)
