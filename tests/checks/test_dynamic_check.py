"""``moorsolve check`` with the lines' own dynamics in a sea state (``checks.method: dynamic``):
the line tension's low- and wave-frequency parts against re-solved statics, the standards'
arithmetic by hand (DNV-OS-E301 (2010) Ch.2 Sec.2: ULS 1.10 / 1.50 and 1.40 / 2.10, ALS
1.00 / 1.10 and 1.00 / 1.25 on 0.95 MBS; API RP 2SK (2005) sections 6.4.2 and 7.4: the
larger of mean + LF_sig + WF_max and mean + LF_max + WF_sig, 1.67 / 1.25), the case fields
and the text, JSON and report."""

from __future__ import annotations

import json
from html import escape as html_escape
import math

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve.checks import run_checks
from moorsolve.checks.dynamic import METHOD_DYNAMIC, TRANSIENT_NOTE
from moorsolve.cli import main
from moorsolve.dynamics.line_dynamics import HARMONIC, line_response
from moorsolve.dynamics.line_model import line_model
from moorsolve.dynamics.line_sea import end_motion_map, line_tensions
from moorsolve.dynamics.system import solved_pose
from moorsolve.errors import CaseError
from moorsolve.studies.stiffness import posed_case
from conftest import ROOT

BUOY = ROOT / "cases" / "buoy_sea.yaml"
DOCK = ROOT / "cases" / "dock_sea.yaml"
#: The buoy's chain MBL [N] in its case file.
MBL = 1.5e6
DURATION = 3 * 3600.0


@pytest.fixture(scope="module")
def buoy():
    return moorsolve.load_case(BUOY)


@pytest.fixture(scope="module")
def buoy_motions(buoy):
    return moorsolve.motions(buoy)


def _central_difference(mean, body, dof: int, step: float) -> np.ndarray:
    """d(anchor, fairlead tension)/d(DOF) of every line by re-solving the statics with the
    body held a step either side of its mean pose [N/m, N/rad], (lines, 2)."""
    p0 = solved_pose(mean, body)
    out = []
    for sign in (1, -1):
        p = p0.copy()
        p[dof] += sign * step
        r = moorsolve.solve(posed_case(mean.case, {body: p}), stability=False)
        out.append([(lr.anchor_tension_N, lr.fairlead_tension_N) for lr in r.legs])
    return (np.array(out[0]) - np.array(out[1])) / (2 * step)


@pytest.mark.parametrize("dof", range(6))
def test_low_frequency_tension_is_the_resolved_statics(buoy_motions, dof):
    # The LF tension change per unit of each DOF (translations and rotations of the buoy)
    # is the line's quasi-static stiffness: central differences of the re-solved statics,
    # to the lumped-mass model's discretisation (the check's 40 elements: seen 1.2e-3 of
    # the largest; 6e-4 at 60).
    tensions = line_tensions(buoy_motions)
    fd = _central_difference(buoy_motions.result, "buoy", dof, 1e-3 if dof < 3 else 1e-4)
    for k, name in enumerate(["L1", "L2", "L3"]):
        g = tensions[name].lf_gradient[:, dof]
        scale = np.max(np.abs(tensions[name].lf_gradient))
        assert np.all(np.abs(g - fd[k]) <= 2e-3 * scale), (name, g, fd[k])


def test_long_period_limit_of_the_wave_frequency_tension(buoy_motions):
    # Driven through the body's kinematics at a period of 10^4 s, the line's dynamic
    # tension transfer equals the central difference of re-solved statics: surge and pitch
    # of the buoy, both ends of each line.
    mean = buoy_motions.result
    case = mean.case
    for dof, step in ((0, 1e-3), (4, 1e-4)):
        fd = _central_difference(mean, "buoy", dof, step)
        for k, line in enumerate(case.lines):
            P = end_motion_map(line.b, buoy_motions, mean)
            drive = P[:, [dof]].astype(complex)
            r = line_response(line_model(case, mean, line.name), [2 * math.pi / 1e4], drive,
                              linearisation=HARMONIC)
            got = np.array([r.tension_a[0].real, r.tension_b[0].real])
            assert np.allclose(got, fd[k], rtol=2e-3, atol=2e-3 * np.max(np.abs(fd[k])))
            assert abs(r.tension_b[0].imag) < 1e-3 * abs(r.tension_b[0].real)


def test_sigma_and_period_from_the_tension_spectra(buoy_motions):
    # sigma_T^2 = sigma_LF^2 + sigma_WF^2 and T_z from both parts' moments, integrated
    # here from the spectra the result carries; T_dyn = sigma_T sqrt(2 ln(duration / T_z)).
    for name, t in line_tensions(buoy_motions).items():
        for k, end in enumerate((t.anchor, t.fairlead)):
            m0w = np.trapezoid(t.wf_spectrum[k], t.omega)
            m2w = np.trapezoid(t.omega ** 2 * t.wf_spectrum[k], t.omega)
            m0l = np.trapezoid(t.lf_spectrum[k], t.lf_omega)
            m2l = np.trapezoid(t.lf_omega ** 2 * t.lf_spectrum[k], t.lf_omega)
            assert end.sigma_wf_N == pytest.approx(math.sqrt(m0w), rel=1e-12)
            assert end.sigma_lf_N == pytest.approx(math.sqrt(m0l), rel=1e-12)
            assert end.sigma_N == pytest.approx(math.hypot(end.sigma_wf_N, end.sigma_lf_N))
            tz = 2 * math.pi * math.sqrt((m0w + m0l) / (m2w + m2l))
            assert end.tz_s == pytest.approx(tz, rel=1e-12)
            assert end.t_dyn_N == pytest.approx(
                end.sigma_N * math.sqrt(2 * math.log(DURATION / tz)), rel=1e-12)
            assert end.wf_max_N == pytest.approx(
                end.sigma_wf_N * math.sqrt(2 * math.log(DURATION / end.tz_wf_s)), rel=1e-12)
            assert end.lf_max_N == pytest.approx(
                end.sigma_lf_N * math.sqrt(2 * math.log(DURATION / end.tz_lf_s)), rel=1e-12)
            # The wave-frequency part dominates a 51 mm chain on a small buoy, and the
            # LF tension's period is the slow drift's (tens of seconds).
            assert end.sigma_wf_N > end.sigma_lf_N > 0
            assert end.tz_lf_s > 5 * end.tz_wf_s


#: DNV-OS-E301 (2010) Ch.2 Sec.2 partial factors (gamma_mean, gamma_dyn) by class.
DNV = {("intact", 1): (1.10, 1.50), ("intact", 2): (1.40, 2.10),
       ("damaged", 1): (1.00, 1.10), ("damaged", 2): (1.00, 1.25)}


@pytest.mark.parametrize("cclass", [1, 2])
def test_dnv_uls_and_als_by_hand(buoy, cclass):
    case = buoy.with_values({"checks": {"standard": "dnv-os-e301",
                                        "consequence_class": cclass}})
    report = run_checks(case)
    assert report.method == METHOD_DYNAMIC["dnv-os-e301"]
    assert TRANSIENT_NOTE in report.notes
    assert len(report.conditions) == 4
    for cond in report.conditions:
        assert cond.solved and cond.method == "dynamic"
        g_mean, g_dyn = DNV[(cond.kind, cclass)]
        for line in cond.lines:
            d = line["dynamic"]
            sigma = math.hypot(d["sigma_wf_N"], d["sigma_lf_N"])
            t_dyn = sigma * math.sqrt(2 * math.log(DURATION / d["tz_s"]))
            assert line["t_dyn_N"] == pytest.approx(t_dyn, rel=1e-9)
            design = g_mean * line["t_mean_N"] + g_dyn * t_dyn
            assert line["design_N"] == pytest.approx(design, rel=1e-9)
            assert line["capacity_N"] == pytest.approx(0.95 * MBL, rel=1e-12)
            assert line["utilisation"] == pytest.approx(design / (0.95 * MBL), rel=1e-9)
            item = next(i for i in cond.items if i.check == "tension" and i.leg == line["leg"])
            assert item.utilisation == pytest.approx(line["utilisation"], rel=1e-12)
            assert f"{g_dyn:.2f} T_dyn" in item.criterion
            # The mean is the mean equilibrium's (mean drift included), at that end.
            lr = next(lr for lr in cond.result.legs if lr.name == line["leg"])
            t_end = lr.fairlead_tension_N if line["end"] == "fairlead" else lr.anchor_tension_N
            assert line["t_mean_N"] == pytest.approx(t_end, rel=1e-12)


def test_api_dynamic_method_by_hand(buoy):
    report = run_checks(buoy, standard="api-rp-2sk")
    assert report.method == METHOD_DYNAMIC["api-rp-2sk"]
    for cond in report.conditions:
        sf = 1.67 if cond.kind == "intact" else 1.25
        assert cond.criterion.analysis == "dynamic" and cond.criterion.factor == sf
        for line in cond.lines:
            d = line["dynamic"]
            wf_max = d["sigma_wf_N"] * math.sqrt(2 * math.log(DURATION / d["tz_wf_s"]))
            lf_max = d["sigma_lf_N"] * math.sqrt(2 * math.log(DURATION / d["tz_lf_s"]))
            t_max = line["t_mean_N"] + max(2 * d["sigma_lf_N"] + wf_max,
                                           lf_max + 2 * d["sigma_wf_N"])
            assert line["t_max_N"] == pytest.approx(t_max, rel=1e-9)
            assert line["utilisation"] == pytest.approx(sf * t_max / MBL, rel=1e-9)
            assert line["t_dyn_N"] == pytest.approx(t_max - line["t_mean_N"], rel=1e-9)


def test_quasi_static_and_dynamic_methods_share_the_design_offset(buoy):
    # The offset, uplift and grounded length are checked at the same design offset by
    # both methods; only the tension's dynamic part differs.
    dyn = run_checks(buoy, damaged=False)
    qs = run_checks(buoy, damaged=False, method="quasi_static")
    assert dyn.conditions[0].design_offset_m == qs.conditions[0].design_offset_m
    for check in ("anchor uplift", "grounded length"):
        a = [(i.leg, i.value) for i in dyn.conditions[0].items if i.check == check]
        b = [(i.leg, i.value) for i in qs.conditions[0].items if i.check == check]
        assert a == b


def _edited(tmp_path, edit) -> str:
    data = yaml.safe_load(BUOY.read_text())
    edit(data)
    path = tmp_path / "edited.yaml"
    path.write_text(yaml.safe_dump(data))
    return str(path)


@pytest.mark.parametrize("edit, field", [
    (lambda d: d.update(analysis={"lines": "dynamic"}) or d["environment"]["waves"].pop("tp")
     and d["environment"]["waves"].pop("spectrum"), "analysis.lines"),
    (lambda d: d.update(analysis={"lines": "sometimes"}), "analysis.lines"),
    (lambda d: d.update(checks={"method": "dynamic"}) or d["bodies"][0].pop("hydrodynamics")
     or d["bodies"][0].update(free=[]), "checks.method"),
    (lambda d: d.update(checks={"method": "fast"}), "checks.method"),
    (lambda d: d.update(analysis={"lines": "quasi_static"}, checks={"method": "dynamic"}),
     "checks.method"),
])
def test_bad_analysis_and_method_are_named(tmp_path, capsys, edit, field):
    path = _edited(tmp_path, edit)
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(path)
    assert err.value.field == field
    assert main(["check", path]) == 2
    out = capsys.readouterr()
    assert field in out.err and "Traceback" not in out.err


def test_a_chain_without_a_diameter_is_refused_by_name(tmp_path, capsys):
    path = _edited(tmp_path, lambda d: d["line_types"]["chain"].pop("diameter"))
    assert main(["check", path]) == 2
    assert "line_types.chain.diameter" in capsys.readouterr().err
    # The quasi-static method needs no diameter.
    assert main(["check", path, "--method", "quasi_static", "--no-damaged"]) == 0


def test_cli_text_json_and_report_carry_the_dynamic_figures(tmp_path, capsys):
    assert main(["check", str(BUOY), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["method"] == METHOD_DYNAMIC["api-rp-2sk"]
    assert data["notes"] == [TRANSIENT_NOTE]
    assert main(["check", str(BUOY)]) == 0
    text = capsys.readouterr().out
    assert "api-rp-2sk (dynamic)" in text and f"note         {TRANSIENT_NOTE}" in text
    for cond in data["conditions"]:
        assert cond["method"] == "dynamic"
        for line in cond["lines"]:
            assert {"t_mean_N", "t_dyn_N", "t_max_N", "design_N", "capacity_N",
                    "utilisation"} <= set(line)
            row = (f"{line['leg']:>6}{line['end']:>9}{line['t_mean_N'] / 1e3:11.1f}"
                   f"{line['t_dyn_N'] / 1e3:10.1f}{line['t_max_N'] / 1e3:10.1f}"
                   f"{line['design_N'] / 1e3:11.1f}{line['capacity_N'] / 1e3:13.1f}"
                   f"{line['utilisation']:7.3f}"
                   f"{line['dynamic']['sigma_wf_N'] / 1e3:11.1f}"
                   f"{line['dynamic']['sigma_lf_N'] / 1e3:11.1f}")
            assert row in text
    html = tmp_path / "r.html"
    assert main(["check", str(BUOY), "--no-damaged", "--report", str(html)]) == 0
    capsys.readouterr()
    page = html.read_text()
    assert html_escape(METHOD_DYNAMIC["api-rp-2sk"]) in page
    first = data["conditions"][0]["lines"][0]
    assert f"{first['design_N'] / 1e3:.1f}" in page and "T dyn kN" in page
    assert "low-frequency tension spectra" in page and "data:image/png;base64" in page


def test_sea_check_figure_draws_every_line(buoy):
    import matplotlib
    matplotlib.use("Agg")
    from moorsolve.plot.line_tension import sea_check_figure
    cond = run_checks(buoy, damaged=False).conditions[0]
    fig = sea_check_figure(cond)
    wave, rao, wf, lf = fig.axes[:4]
    assert len(wf.get_lines()) == len(lf.get_lines()) == 3
    # The plotted WF spectrum is the line's, in kN^2 s/rad.
    t = cond.tensions["L1"]
    k = int(t.fairlead.sigma_N >= t.anchor.sigma_N)
    y = wf.get_lines()[0].get_ydata()
    assert np.allclose(y, t.wf_spectrum[k] / 1e6)


# ---- the 12-chain dock with a sea state, intact and every chain removed -------------------


@pytest.fixture(scope="module")
def dock_report():
    return run_checks(moorsolve.load_case(DOCK))


def _fairleads(case) -> dict:
    return {ln.name: np.array(ln.b.position[:2]) for ln in case.lines}


def test_dock_every_condition_runs_the_line_dynamics(dock_report):
    assert len(dock_report.conditions) == 13
    for cond in dock_report.conditions:
        assert cond.solved, cond.reason
        assert cond.method == "dynamic"
        names = {line["leg"] for line in cond.lines}
        expected = {f"L{i}" for i in range(1, 13)} - {cond.removed}
        assert names == expected
        for line in cond.lines:
            assert line["t_dyn_N"] > 0 and line["dynamic"]["sigma_lf_N"] > 0
            assert line["dynamic"]["sigma_wf_N"] > 0


def test_dock_a_broken_chain_loads_its_neighbour(dock_report):
    # With a chain gone its neighbour (the chain pulling the nearest way) takes more: its
    # mean and its largest tension rise over the intact condition's, and so does its
    # utilisation under the same factors (ALS's are lower than ULS's: 1.00 / 1.10 against
    # 1.10 / 1.50, so the ALS utilisation itself may fall).
    case = moorsolve.load_case(DOCK)
    fair = _fairleads(case)
    pull = {ln.name: math.atan2(ln.a.position[1] - fair[ln.name][1],
                                ln.a.position[0] - fair[ln.name][0]) for ln in case.lines}
    intact = {x["leg"]: x for x in dock_report.conditions[0].lines}
    for cond in dock_report.conditions[1:]:
        lost = cond.removed
        neighbour = min((n for n in fair if n != lost),
                        key=lambda n: (abs(math.remainder(pull[n] - pull[lost], 2 * math.pi)),
                                       np.linalg.norm(fair[n] - fair[lost])))
        line = next(x for x in cond.lines if x["leg"] == neighbour)
        assert line["t_mean_N"] > intact[neighbour]["t_mean_N"], (lost, neighbour)
        assert line["t_max_N"] > intact[neighbour]["t_max_N"], (lost, neighbour)
        uls = (1.10 * line["t_mean_N"] + 1.50 * line["t_dyn_N"]) / line["capacity_N"]
        assert uls > intact[neighbour]["utilisation"], (lost, neighbour)
        assert line["utilisation"] == pytest.approx(
            (line["t_mean_N"] + 1.10 * line["t_dyn_N"]) / line["capacity_N"], rel=1e-9)


def test_dock_damaged_design_offset_follows_the_lost_line(dock_report):
    # Losing a chain removes its pull toward its anchor: the dock's mean position moves
    # away from that anchor, and the design offset is along the damaged condition's own
    # mean offset (the held pose lies on it), not the intact direction.
    case = moorsolve.load_case(DOCK)
    anchors = {ln.name: np.array(ln.a.position[:2]) for ln in case.lines}
    fair = _fairleads(case)
    intact = dock_report.conditions[0].result.body_named("dock")["offset"]
    x0 = np.array([intact["x_m"], intact["y_m"]])
    turned = 0
    for cond in dock_report.conditions[1:]:
        off = cond.result.body_named("dock")["offset"]
        x = np.array([off["x_m"], off["y_m"]])
        pull = anchors[cond.removed] - fair[cond.removed]
        assert (x - x0) @ pull < 0, cond.removed
        held = cond.held.body_named("dock")
        h = np.array([held["x_m"], held["y_m"]])
        assert abs(h[0] * x[1] - h[1] * x[0]) <= 1e-9 * np.linalg.norm(h) * np.linalg.norm(x)
        assert h @ x > 0
        assert np.linalg.norm(h) == pytest.approx(cond.design_offset_m["dock"], rel=1e-9)
        angle = math.degrees(math.acos(np.clip(x @ x0 / np.linalg.norm(x) /
                                               np.linalg.norm(x0), -1, 1)))
        turned += angle > 1.0
    assert turned >= 4      # the direction differs from the intact one for many chains


def test_dock_mean_drift_comes_from_the_tables(dock_report):
    m = dock_report.conditions[0].sea.motions
    assert "mean_drift" in m.sea["simulated"] and "slow_drift" in m.sea["simulated"]
    assert np.linalg.norm(m.body("dock").mean_drift[:2]) > 0


def test_notebook_view_says_what_the_tension_check_covered(buoy):
    report = run_checks(buoy, damaged=False)
    page = report._repr_html_()
    assert html_escape(f"Line tension: {report.method}.") in page
