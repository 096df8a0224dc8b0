"""Offset envelope: symmetry, agreement with individual solves, the command and its plot."""

import json

import numpy as np
import pytest

import moorsolve
from moorsolve.cli import main
from moorsolve.errors import CaseError
from moorsolve.model.paths import with_values
from conftest import ROOT

CASES = ROOT / "cases"
BUOY = CASES / "buoy_vida.yaml"
DOCK = CASES / "floating_dock.yaml"


def _square_buoy():
    """Four chains at 45, 135, 225 and 315 deg and a wind drag with equal areas and
    coefficients: loads and layout share the symmetry of the square."""
    source = dict(moorsolve.load_case(BUOY).source)
    r = 33.0
    source["legs"] = [
        {"name": f"L{k}", "anchor": [r * np.cos(np.radians(a)), r * np.sin(np.radians(a))],
         "fairlead": [0.0, 0.0, 0.0], "segments": [{"type": "chain", "length": 50.0}]}
        for k, a in enumerate((45, 135, 225, 315), start=1)]
    return moorsolve.load_case(source)


def test_square_layout_gives_a_square_envelope():
    e = moorsolve.offset_envelope(_square_buoy(), step_deg=15)
    assert e.converged.all() and len(e.heading_deg) == 24
    n = len(e.heading_deg)
    for shift in (6, 12, 18):               # turned by 90, 180 and 270 deg
        np.testing.assert_allclose(np.roll(e.offset_m, shift), e.offset_m, rtol=1e-9)
        np.testing.assert_allclose(np.roll(e.worst_tension_N, shift), e.worst_tension_N,
                                   rtol=1e-9)
        turned = (e.offset_direction_deg + 15 * shift) % 360
        np.testing.assert_allclose(np.cos(np.radians(np.roll(turned, shift))),
                                   np.cos(np.radians(e.offset_direction_deg)), atol=1e-9)
    mirror = (-np.arange(n)) % n            # heading -h
    np.testing.assert_allclose(e.offset_m[mirror], e.offset_m, rtol=1e-9)
    np.testing.assert_allclose(e.worst_tension_N[mirror], e.worst_tension_N, rtol=1e-9)
    # Along a diagonal the load pulls straight away from one anchor: offset and load align.
    diagonal = list(e.heading_deg).index(225.0)
    assert e.offset_direction_deg[diagonal] == pytest.approx(225.0, abs=1e-6)
    assert e.worst_leg[diagonal] == "L1"


def test_buoy_envelope_is_mirror_symmetric():
    e = moorsolve.offset_envelope(moorsolve.load_case(BUOY), step_deg=30)
    n = len(e.heading_deg)
    mirror = (-np.arange(n)) % n
    np.testing.assert_allclose(e.offset_m[mirror], e.offset_m, rtol=1e-9)
    np.testing.assert_allclose(e.y_m[mirror], -e.y_m, atol=1e-9)
    np.testing.assert_allclose(e.worst_tension_N[mirror], e.worst_tension_N, rtol=1e-9)
    swap = {"NNE": "SSE", "SSE": "NNE", "W": "W"}
    for i in range(n):
        if e.heading_deg[i] not in (0.0, 180.0):      # ties on the axis of symmetry
            assert e.worst_leg[mirror[i]] == swap[e.worst_leg[i]]


def test_each_envelope_point_equals_an_individual_solve():
    case = moorsolve.load_case(DOCK)
    e = moorsolve.offset_envelope(case, headings_deg=[0, 70, 135, 200, 290])
    assert e.flows == ("wind", "current", "waves")
    for i, h in enumerate(e.heading_deg):
        # The dock's flows are aligned (all toward 70 deg), so each travels toward h.
        point = moorsolve.load_case(with_values(case.source, {
            f"environment.{f}.toward_deg": h for f in e.flows}))
        r = moorsolve.solve(point)
        tensions = [max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in r.legs]
        names = [leg.name for leg in r.legs]
        # The named leg carries the largest tension (mirror-image legs may tie).
        assert tensions[names.index(e.worst_leg[i])] == pytest.approx(max(tensions), rel=1e-9)
        assert e.worst_tension_N[i] == pytest.approx(max(tensions), rel=1e-9)
        assert e.x_m[i] == pytest.approx(r.body["x_m"], abs=1e-7)
        assert e.y_m[i] == pytest.approx(r.body["y_m"], abs=1e-7)
        assert e.yaw_deg[i] == pytest.approx(r.body["yaw_deg"], abs=1e-7)
        assert e.offset_m[i] == pytest.approx(np.hypot(r.body["x_m"], r.body["y_m"]),
                                              abs=1e-7)
    assert e.row(1)["heading_deg"] == 70.0
    np.testing.assert_allclose(e.worst_tension_N[1],
                               max(leg.fairlead_tension_N for leg in moorsolve.solve(case).legs),
                               rtol=1e-9)


def test_turning_a_subset_keeps_the_other_flows():
    case = moorsolve.load_case(DOCK)
    e = moorsolve.offset_envelope(case, headings_deg=[160], flows=["wind"])
    point = moorsolve.load_case(with_values(case.source, {"environment.wind.toward_deg": 160}))
    r = moorsolve.solve(point)
    assert e.worst_tension_N[0] == pytest.approx(
        max(leg.fairlead_tension_N for leg in r.legs), rel=1e-9)
    with pytest.raises(CaseError, match="flows"):
        moorsolve.offset_envelope(moorsolve.load_case(BUOY), flows=["current"])
    with pytest.raises(CaseError, match="step_deg"):
        moorsolve.offset_envelope(case, step_deg=0)


def test_envelope_command_writes_a_png_and_json(tmp_path, capsys):
    png = tmp_path / "env.png"
    assert main(["envelope", str(BUOY), "--step", "45", "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "worst tension:" in out and f"wrote {png}" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["envelope", str(BUOY), "--step", "90", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [h["heading_deg"] for h in data["headings"]] == [0, 90, 180, 270]
    assert data["worst"]["worst_tension_N"] == max(h["worst_tension_N"]
                                                  for h in data["headings"])
    assert main(["envelope", str(BUOY), "--flows", "waves", "--plot", str(png)]) == 2
    assert capsys.readouterr().err.startswith("moorsolve: bad input: --flows")
    assert main(["envelope", str(BUOY), "--plot", str(tmp_path / "env.txt")]) == 2
    assert not (tmp_path / "env.txt").exists()


def test_a_nautical_case_reads_its_envelope_in_compass_bearings():
    """The same scene written with nautical ``from_deg`` headings: the envelope solves the
    same equilibria, and its tables speak the file's terms (the wind's bearing it comes
    from, the offset as a bearing)."""
    base = _square_buoy()
    source = dict(base.source)
    env = dict(source["environment"])
    env["directions"] = "nautical"
    wind = dict(env["wind"])
    toward = wind.pop("toward_deg", 0.0)
    wind["from_deg"] = (90.0 - toward + 180.0) % 360.0      # the same flow, as a bearing
    env["wind"] = wind
    source["environment"] = env
    nautical = moorsolve.load_case(source)
    plain = moorsolve.offset_envelope(base, step_deg=45)
    e = moorsolve.offset_envelope(nautical, step_deg=45)
    np.testing.assert_allclose(e.worst_tension_N, plain.worst_tension_N, rtol=1e-9)
    assert e.heading_key == "from_deg" and e.compass.nautical
    # Internal heading h (toward, CCW from +x) is the bearing the wind comes from: 270 - h.
    np.testing.assert_allclose(e.case_heading_deg, (270.0 - e.heading_deg) % 360.0, atol=1e-9)
    for i in range(len(e.heading_deg)):
        assert e.file_direction(i) == pytest.approx(
            (90.0 - e.offset_direction_deg[i]) % 360.0, abs=1e-9)
    text = moorsolve.studies.envelope.format_envelope(e)
    assert "wind from [deg, clockwise from N]" in text and "brg deg" in text
    assert "clockwise from north" in text.splitlines()[-1]
    row = e.to_dict()["headings"][0]
    assert row["case_heading"] == {"key": "from_deg", "deg": float(e.case_heading_deg[0]),
                                   "convention": "nautical"}
    assert "wind from [deg, clockwise from N]" in e._repr_html_()
