"""Wave spectra: DNV-RP-C205's JONSWAP and Pierson-Moskowitz, the gamma rule, a table, and
the sea-state fields of a case file."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from moorsolve import CaseError, load_case
from moorsolve.dynamics.spectra import (gamma_dnv, jonswap, pierson_moskowitz, spectrum_of,
                                        tabulated)

HS, TP = 6.0, 11.0
WP = 2 * math.pi / TP


def _m(n, f, *args):
    return quad(lambda w: w ** n * f(w, *args), 0.0, math.inf, limit=400, epsabs=0,
                epsrel=1e-10, points=None)[0]


def test_pierson_moskowitz_closed_form():
    # DNV-RP-C205 eq. 3.5.5.1 integrates exactly to Hs^2/16, and its peak is at wp.
    assert _m(0, lambda w: float(pierson_moskowitz(w, HS, TP))) == pytest.approx(
        HS ** 2 / 16, rel=1e-9)
    # Closed form at the peak: 5/16 Hs^2 / wp e^-5/4.
    assert float(pierson_moskowitz(WP, HS, TP)) == pytest.approx(
        5 / 16 * HS ** 2 / WP * math.exp(-1.25), rel=1e-12)
    # Its second moment in closed form: m2 = 5/16 Hs^2 wp^2 Gamma(1/2) (5/4)^-1/2 / 4.
    m2 = 5 / 16 * HS ** 2 * WP ** 2 * math.gamma(0.5) / 4 / math.sqrt(1.25)
    assert _m(2, lambda w: float(pierson_moskowitz(w, HS, TP))) == pytest.approx(m2, rel=1e-8)


@pytest.mark.parametrize("gamma, tol", [(1.0, 1e-9), (2.0, 3e-3), (3.3, 3e-3), (5.0, 3e-3),
                                        (7.0, 2e-2)])
def test_jonswap_normalisation(gamma, tol):
    # A_gamma = 1 - 0.287 ln(gamma) (DNV-RP-C205 3.5.5.2) is an approximation: m0 = Hs^2/16
    # to the few tenths of a percent its three printed digits carry for gamma 1..5.
    f = lambda w: float(jonswap(w, HS, TP, gamma))  # noqa: E731
    m0 = quad(f, 0.0, 0.7 * WP, limit=400, epsrel=1e-11)[0] + \
        quad(f, 0.7 * WP, 1.5 * WP, limit=400, epsrel=1e-11)[0] + \
        quad(f, 1.5 * WP, math.inf, limit=400, epsrel=1e-11)[0]
    assert m0 == pytest.approx(HS ** 2 / 16, rel=tol)


@pytest.mark.parametrize("gamma", [1.0, 3.3, 5.0])
def test_jonswap_peak_at_tp(gamma):
    w = np.linspace(0.5 * WP, 2 * WP, 300001)
    assert w[np.argmax(jonswap(w, HS, TP, gamma))] == pytest.approx(WP, abs=2e-5)
    # The peak value is gamma A_gamma times the PM peak.
    assert float(jonswap(WP, HS, TP, gamma)) == pytest.approx(
        gamma * (1 - 0.287 * math.log(gamma)) * float(pierson_moskowitz(WP, HS, TP)))


def test_jonswap_widths():
    # sigma 0.07 below the peak, 0.09 above: the enhancement at wp (1 +- s) follows each.
    gamma = 3.3
    for s, sigma in ((-0.1, 0.07), (0.1, 0.09)):
        w = WP * (1 + s)
        ratio = float(jonswap(w, HS, TP, gamma)) / float(pierson_moskowitz(w, HS, TP))
        expected = (1 - 0.287 * math.log(gamma)) * gamma ** math.exp(-0.5 * (s / sigma) ** 2)
        assert ratio == pytest.approx(expected, rel=1e-12)


def test_gamma_rule():
    # DNV-RP-C205 3.5.5.5: 5 up to Tp/sqrt(Hs) = 3.6, exp(5.75 - 1.15 r) up to 5, then 1.
    assert gamma_dnv(4.0, 3.6 * 2.0) == 5.0
    assert gamma_dnv(4.0, 4.0 * 2.0) == pytest.approx(math.exp(5.75 - 4.6))
    assert gamma_dnv(4.0, 5.0 * 2.0) == 1.0
    assert gamma_dnv(4.0, 10.0) == 1.0
    # Continuous at both ends to the printed digits (e^(5.75-4.14) = 5.003; e^0 = 1).
    assert math.exp(5.75 - 1.15 * 3.6) == pytest.approx(5.0, abs=5e-3)
    assert gamma_dnv(1.0, 4.9999) == pytest.approx(1.0, abs=1e-3)
    # A jonswap without gamma uses the rule.
    assert float(jonswap(0.5, 4.0, 8.0)) == float(jonswap(0.5, 4.0, 8.0, gamma_dnv(4.0, 8.0)))


def test_tabulated():
    t = [[0.2, 0.0], [0.5, 2.0], [0.8, 0.0]]
    assert tabulated([0.1, 0.35, 0.5, 0.9], t) == pytest.approx([0.0, 1.0, 2.0, 0.0], abs=1e-15)


def _case(waves: dict) -> dict:
    return {"environment": {"depth": 50, "waves": waves},
            "line_types": {"c": {"weight_in_water": 1000, "ea": 1e9}},
            "body": {"free": ["surge", "sway"]},
            "legs": [{"name": n, "anchor": [x, y], "fairlead": [0, 0, 0],
                      "segments": [{"type": "c", "length": 300}]}
                     for n, x, y in (("a", 250, 0), ("b", -250, 0), ("c", 0, 250))]}


def test_case_fields():
    w = load_case(_case({"hs": 6, "tp": "11 s", "duration": "1 h"})).environment.waves
    assert (w.tp, w.duration, w.spectrum.model, w.spectrum.gamma) == (11.0, 3600.0, "jonswap",
                                                                      None)
    assert w.sea_state
    w = load_case(_case({"hs": 6})).environment.waves
    assert not w.sea_state and w.duration == 3 * 3600.0
    w = load_case(_case({"hs": 6, "tp": 11, "spectrum": {"model": "pierson_moskowitz"}}))
    f = spectrum_of(w.environment.waves)
    assert float(f(WP)) == float(pierson_moskowitz(WP, 6, 11))
    # A table whose 4 sqrt(m0) is hs.
    om = np.linspace(0.2, 2.0, 200)
    S = jonswap(om, 2.0, 8.0, 3.3)
    hs = 4 * math.sqrt(np.trapezoid(S, om))
    w = load_case(_case({"hs": hs, "spectrum": {"table": np.c_[om, S].tolist()}}))
    assert w.environment.waves.sea_state and w.environment.waves.tp is None


@pytest.mark.parametrize("waves, field, words", [
    ({"hs": 6, "spectrum": {"model": "jonswap"}}, "environment.waves.tp", "peak period"),
    ({"hs": 6, "tp": 11, "spectrum": {"model": "bretschneider"}},
     "environment.waves.spectrum.model", "jonswap, pierson_moskowitz"),
    ({"hs": 6, "tp": 11, "spectrum": {"model": "jonswap", "gamma": 0.5}},
     "environment.waves.spectrum.gamma", ">= 1"),
    ({"hs": 6, "tp": 11, "spectrum": {"model": "pierson_moskowitz", "gamma": 2}},
     "environment.waves.spectrum.gamma", "only a jonswap"),
    ({"hs": 6, "tp": -1}, "environment.waves.tp", "> 0"),
    ({"hs": 6, "tp": 11, "duration": "10 s"}, "environment.waves.duration", "storm"),
    ({"hs": 1, "spectrum": {"table": [[0.2, 0], [0.5, 2], [0.8, 0]]}},
     "environment.waves.spectrum.table", "significant height"),
    ({"hs": 1, "spectrum": {"table": [[0.5, 0], [0.2, 2], [0.8, 0]]}},
     "environment.waves.spectrum.table", "increasing"),
])
def test_bad_sea_states(waves, field, words):
    with pytest.raises(CaseError) as err:
        load_case(_case(waves))
    assert err.value.field == field
    assert words in str(err.value)
