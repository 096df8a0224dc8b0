"""MoorDyn's SYROPE polyester-rope model read as its static law (moorsolve/io/moordyn_syrope.py).

The files in tests/data/moordyn_syrope/ hold a 10 m rope straight in zero gravity between a
fixed and a coupled point, so its tension is the law's at the strain ``span/10 - 1``. The
reference here is the working-curve formula of the MoorDyn documentation ("Syrope Model for
Polyester Lines") and MoorDyn's ``Line::setWorkingCurve``, written out again below: the
strain of each file lands on one of MoorDyn's 30 working-curve points (or on a row of the
original curve above Tmax0), where MoorDyn's linear interpolation, the imported law (the
same chords) and the formula all agree, so the tension must match to round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import DATA

import moorsolve
from moorsolve.errors import CaseError
from moorsolve.io.moordyn import convert_moordyn

SYROPE = DATA / "moordyn_syrope"
TMAX0 = 3.0e6


def _owc():
    rows = np.loadtxt(SYROPE / "owc.dat", skiprows=3)       # MoorDyn skips three lines
    return rows[:, 0], rows[:, 1]


def _expected_tension(strain, form, k1, k2):
    """The rope's mean tension at rest at total strain ``strain`` on the working curve of
    Tmax0 (or on the original curve above it)."""
    e, T = _owc()
    eps_max = float(np.interp(TMAX0, T, e))
    if strain > eps_max:
        return float(np.interp(strain, e, T))
    eps_min = e[0] + k1 * (eps_max - e[0])
    if form == "linear" and k1 >= 1.0:
        eps_min = eps_max - TMAX0 / k1
    xi = (strain - eps_min) / (eps_max - eps_min)
    if form == "linear":
        return TMAX0 * xi
    if form == "quadratic":
        return TMAX0 * xi * (k2 * xi + 1.0 - k2)
    return TMAX0 * (1.0 - math.exp(k2 * xi)) / (1.0 - math.exp(k2))


def _span(path) -> float:
    for row in path.read_text().splitlines():
        words = row.split()
        if len(words) > 2 and words[1] == "Coupled":
            return float(words[2])
    raise AssertionError("no coupled point")


@pytest.mark.parametrize("name, form, k1, k2", [
    ("linear", "linear", 2.0e8, 0.0), ("quadratic", "quadratic", 0.3, 0.6),
    ("exp", "exp", 0.2, 1.5), ("beyond", "linear", 2.0e8, 0.0)])
def test_a_syrope_rope_at_rest_sits_on_its_working_curve(name, form, k1, k2):
    path = SYROPE / f"rope_{name}.txt"
    data = moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(path))
    result = moorsolve.solve(moorsolve.load_case(data))
    assert result.converged
    expected = _expected_tension(_span(path) / 10.0 - 1.0, form, k1, k2)
    assert result.leg("L1").fairlead_tension_N == pytest.approx(expected, rel=1e-9)
    if name == "beyond":
        assert expected > TMAX0                          # on the original curve again


def test_the_permanent_stretch_lengthens_the_rope_and_keeps_its_mass():
    path = SYROPE / "rope_quadratic.txt"
    imported = convert_moordyn(moorsolve.read_moordyn(path))
    data = imported.data
    e, T = _owc()
    eps_max = float(np.interp(TMAX0, T, e))
    eps_min = 0.3 * eps_max
    (line,) = data["legs"] if "legs" in data else data["lines"]
    length = sum(s["length"] for s in line["segments"])
    assert length == pytest.approx(10.0 * (1.0 + eps_min), rel=1e-12)
    (name,) = data["line_types"]
    assert name == "poly_line1"
    law = data["line_types"][name]["stretch"]
    assert law["strain"][0] == 0.0 and law["tension"][0] == 0.0
    assert len(law["strain"]) == 30 + sum(T > TMAX0)
    text = "\n".join(imported.report.converted + imported.report.ignored)
    assert "SYROPE rope poly (quadratic working curve" in text
    assert "Tmean0 1e+06 N" in text


def _edited(tmp_path, old, new, config=None):
    for f in ("owc.dat", "linear.dat", "quadratic.dat", "exp.dat"):
        (tmp_path / f).write_text((SYROPE / f).read_text())
    if config is not None:
        (tmp_path / "linear.dat").write_text(config)
    text = (SYROPE / "rope_linear.txt").read_text()
    assert old in text
    (tmp_path / "rope.txt").write_text(text.replace(old, new))
    return tmp_path / "rope.txt"


@pytest.mark.parametrize("old, new, config, message", [
    ("1         3e+06     1.0e6", "", None, r"rope.txt:15: line 1 is a SYROPE rope \(poly\) "
                                              "without a row in a SYROPE IC section"),
    ("1         3e+06     1.0e6", "1         9e+06     1.0e6", None,
     r"rope.txt:19: line 1: Tmax0 9e\+06 N is outside the original working curve"),
    ("1         3e+06     1.0e6", "2         3e+06     1.0e6", None,
     "SYROPE IC names line 2; the file has lines 1"),
    ("1         3e+06     1.0e6", "1         3e+06", None, "has 2 fields; MoorDyn requires 3"),
    ("SYROPE:linear.dat|1.2e8|20.0", "SYROPE:linear.dat|1.2e8", None,
     "a SYROPE line type takes 3 '|'-separated values"),
    ("SYROPE:linear.dat|1.2e8|20.0", "SYROPE:missing.dat|1.2e8|20.0", None,
     "SYROPE config file 'missing.dat' not found"),
    ("SYROPE:linear.dat|1.2e8|20.0", "1.2e8", None,
     "a SYROPE IC section, but no line type is a SYROPE rope"),
    ("", "", "owc.dat OWC\nLINEAR WCType\n2e8 k1\n", "gives no k2"),
    ("", "", "owc.dat OWC\nCUBIC WCType\n2e8 k1\n0 k2\n", "WCType 'CUBIC' must be LINEAR"),
])
def test_syrope_errors_name_the_line_and_the_reason(tmp_path, old, new, config, message):
    path = _edited(tmp_path, old, new, config)
    with pytest.raises(CaseError, match=message):
        moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(path))


def test_a_quadratic_curve_that_turns_back_is_refused(tmp_path):
    # k2 > 1 makes the quadratic working curve fall below zero tension near xi = 0.
    path = _edited(tmp_path, "SYROPE:linear.dat", "SYROPE:quadratic.dat",
                   None)
    (tmp_path / "quadratic.dat").write_text("owc.dat OWC\nQUADRATIC WCType\n0.3 k1\n3.0 k2\n")
    with pytest.raises(CaseError, match="does not rise strictly in strain and tension"):
        moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(path))


def test_an_imported_syrope_rope_exports_as_a_curve_and_solves_the_same(tmp_path):
    path = SYROPE / "rope_linear.txt"
    case = moorsolve.load_case(moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(path)))
    out = tmp_path / "back.dat"
    moorsolve.export_moordyn(case, out)
    assert "SYROPE:" not in out.read_text()     # a table law now: MoorDyn reads its curve
    curve = (tmp_path / "back_poly_line1_ea.txt").read_text()
    assert "30 of its rows" in curve.splitlines()[0]
    rows = [tuple(map(float, r.split())) for r in curve.splitlines()[3:]]
    law = case.line_types["poly_line1"].stretch
    assert len(rows) == 30 and set(rows) <= set(zip(law.strain, law.tension))
    assert (law.strain[29], law.tension[29]) in rows     # the working curve's end, Tmax0
    again = moorsolve.load_case(moorsolve.moordyn_to_case_data(moorsolve.read_moordyn(out)))
    a, b = moorsolve.solve(case), moorsolve.solve(again)
    # Collinear working-curve rows were dropped; the cubic through the rest differs a
    # little from the full table's near the working curve's end.
    assert b.leg("L1").fairlead_tension_N == pytest.approx(a.leg("L1").fairlead_tension_N,
                                                           rel=1e-3)
