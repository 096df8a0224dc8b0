"""Reports (issue 18): the HTML check report an engineer signs, printed through a real
browser engine when one is installed; the notebook views of results; labelled stiffness."""

from __future__ import annotations

import base64
import datetime
import hashlib
import html
import re
import shutil
import subprocess

import numpy as np
import pytest

import moorsolve
from moorsolve.checks import run_checks
from moorsolve.cli import main
from moorsolve.report.check_html import render_html, write_html_report
from moorsolve.report.matrix import stiffness_table

from conftest import CASES

CLUMP = CASES / "chain_polyester_clump.yaml"


def _browser():
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    return None


@pytest.fixture(scope="module")
def clump_report(tmp_path_factory):
    case = moorsolve.load_case(CLUMP)
    report = run_checks(case)
    out = tmp_path_factory.mktemp("report") / "check.html"
    write_html_report(report, case, out, case_file=CLUMP)
    return case, report, out, out.read_text(encoding="utf-8")


# ---- what the HTML report states ------------------------------------------------------


def test_report_states_version_date_hash_tolerance_standard(clump_report):
    case, report, _, text = clump_report
    plain = html.unescape(re.sub(r"<[^>]+>", " ", text))
    assert f"moorsolve {moorsolve.__version__}" in plain
    assert re.search(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", plain)
    assert hashlib.sha256(CLUMP.read_bytes()).hexdigest() in plain
    assert str(CLUMP) in plain
    assert "api-rp-2sk" in plain
    assert f"{case.solver.tol:.0e} of the largest line tension" in plain
    assert report.tolerance == case.solver.tol
    assert "prepared by" in plain and "approved by" in plain


def test_report_lists_every_segment_and_clump(clump_report):
    case, _, _, text = clump_report
    plain = html.unescape(re.sub(r"<[^>]+>", " ", text))
    for leg in case.legs:
        n = len(leg.segments)
        for k, seg in enumerate(leg.segments):
            assert f"{k + 1} of {n}" in plain
        assert plain.count(f"{k + 1} of {n}") == len(case.legs)
    rows = re.findall(r"<tr[^>]*>(.*?)</tr>", text, re.S)
    segment_rows = [r for r in rows if re.search(r">\d of \d<", r)]
    assert len(segment_rows) == sum(len(leg.segments) for leg in case.legs)
    for leg in case.legs:
        for seg in leg.segments:
            assert any(seg.line_type.name in r and f"{seg.length:.2f}" in r
                       for r in segment_rows)
    clumps = [r for r in rows if ">clump<" in r]
    assert len(clumps) == sum(c is not None for leg in case.legs for c in leg.clumps)
    assert "15 t, 1.91 m^3" in clumps[0]


def test_report_embeds_its_figures_as_png(clump_report):
    _, _, _, text = clump_report
    images = re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', text)
    assert len(images) == 3                            # intact, governing damaged, chart
    for data in images:
        assert base64.b64decode(data)[:8] == b"\x89PNG\r\n\x1a\n"
    assert "http://" not in text and "https://" not in text      # self-contained


def test_report_of_case_data_hashes_the_data():
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    report = run_checks(case)
    when = datetime.datetime(2030, 1, 2, 3, 4, tzinfo=datetime.timezone.utc)
    a = render_html(report, case, {}, created=when)
    b = render_html(report, case, {}, created=when)
    assert a == b and "2030-01-02 03:04 UTC" in a
    assert "SHA-256 of the case data (canonical JSON)" in a


def test_check_command_writes_the_report_with_the_file_hash(tmp_path, capsys):
    out = tmp_path / "dock.html"
    status = main(["check", str(CASES / "floating_dock.yaml"), "--report", str(out)])
    assert status == 1                                   # the dock fails one uplift check
    text = out.read_text(encoding="utf-8")
    assert hashlib.sha256((CASES / "floating_dock.yaml").read_bytes()).hexdigest() in text
    assert "L4 removed" in text


# ---- printing through a browser engine ---------------------------------------------------


def test_report_prints_to_pdf_in_a_browser(clump_report, tmp_path):
    browser = _browser()
    if browser is None:
        pytest.skip("no Chromium or Chrome installed: the print test needs a browser engine")
    _, _, path, _ = clump_report
    pdf = tmp_path / "check.pdf"
    run = subprocess.run(
        [browser, "--headless", "--no-sandbox", "--disable-gpu",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--no-first-run", "--disable-default-apps", "--disable-extensions",
         "--no-pdf-header-footer", f"--print-to-pdf={pdf}", path.as_uri()],
        capture_output=True, text=True, timeout=180)
    assert pdf.exists() and pdf.read_bytes()[:5] == b"%PDF-", run.stderr[-2000:]
    if shutil.which("pdfinfo"):
        info = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True).stdout
        pages = int(re.search(r"Pages:\s+(\d+)", info).group(1))
        assert 3 <= pages <= 20, info
        assert "(A4)" in info, info
    if shutil.which("pdftotext"):
        text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True,
                              text=True).stdout
        assert "Mooring check: FPU" in text
        assert re.search(r"page 1 of \d+", text)          # the page footer
        assert "7. Sign-off" in text and "approved by" in text
        # Every row of the per-leg table made it onto paper (nothing cut at a page edge):
        # each value of its utilisation column is printed at least as often as it occurs.
        _, report, _, _ = clump_report
        from collections import Counter
        wanted = Counter(f"{i.utilisation:.3f}" for c in report.conditions for i in c.items
                         if i.leg is not None and np.isfinite(i.utilisation))
        printed = Counter(re.findall(r"(?<![\d.])\d+\.\d{3}(?![\d.])", text))
        assert all(printed[v] >= n for v, n in wanted.items()), (wanted, printed)
    if shutil.which("pdftoppm"):
        subprocess.run(["pdftoppm", "-r", "30", "-png", "-f", "1", "-l", "2", str(pdf),
                        str(tmp_path / "page")], check=True)
        import matplotlib.image as mpimg
        for png in sorted(tmp_path.glob("page*.png")):
            pixels = mpimg.imread(png)
            assert pixels.std() > 0.05, png                 # not a blank page


# ---- notebooks ---------------------------------------------------------------------------


def test_result_repr_is_one_short_line():
    result = moorsolve.solve(moorsolve.load_case(CLUMP))
    text = repr(result)
    assert "\n" not in text and len(text) < 300, text
    assert text.startswith("<Result 'FPU") and "certified" in text
    assert "4 legs, worst" in text
    for leg in result.legs:
        assert "\n" not in repr(leg) and len(repr(leg)) < 160
    assert f"{result.legs[0].fairlead_tension_N / 1e3:,.1f} kN" in repr(result.legs[0])


def test_result_html_has_every_leg_and_the_certificate():
    result = moorsolve.solve(moorsolve.load_case(CASES / "floating_dock.yaml"))
    page = result._repr_html_()
    assert page.count("<table>") == 2
    for leg in result.legs:
        assert f"<td style=\"text-align:left\">{leg.name}</td>" in page
        assert f"{leg.fairlead_tension_N / 1e3:,.2f}" in page
    assert f"{result.certificate.force_N:.3g} N" in page


def test_check_report_and_envelope_in_a_notebook():
    case = moorsolve.load_case(CASES / "check_failures.yaml")
    report = run_checks(case)
    assert "\n" not in repr(report) and "FAIL" in repr(report)
    page = report._repr_html_()
    assert page.count("<tr") == 1 + len(report.conditions)
    # One verdict cell per condition, FAIL for each that fails.
    assert page.count('">FAIL</td>') == sum(not c.passed for c in report.conditions) > 0
    for c in report.conditions:
        assert html.escape(c.name) in page
    assert all("\n" not in repr(c) for c in report.conditions)
    env = moorsolve.offset_envelope(moorsolve.load_case(CASES / "buoy_vida.yaml"), step_deg=90)
    page = env._repr_html_()
    assert page.count("<tr") == 1 + len(env.heading_deg)
    assert "\n" not in repr(env) and len(repr(env)) < 300


def test_stiffness_is_labelled_with_dofs_and_units(capsys):
    result = moorsolve.solve(moorsolve.load_case(CASES / "floating_dock.yaml"))
    K = moorsolve.stiffness(result)
    table = stiffness_table(K)
    assert table.rows == ("Fx [N]", "Fy [N]", "Fz [N]", "Mx [N m]", "My [N m]", "Mz [N m]")
    assert table.columns == ("surge [m]", "sway [m]", "heave [m]", "roll [rad]",
                             "pitch [rad]", "yaw [rad]")
    np.testing.assert_array_equal(np.asarray(table), K)
    assert table[5, 5] == K[5, 5]
    frame = table.to_frame()
    assert frame.loc["Mz [N m]", "yaw [rad]"] == K[5, 5]
    assert frame.loc["Fx [N]", "surge [m]"] == K[0, 0]
    assert "<caption>" in table._repr_html_()
    planar = stiffness_table(K[np.ix_((0, 1, 5), (0, 1, 5))])
    assert planar.rows == ("Fx [N]", "Fy [N]", "Mz [N m]")
    status = main(["stiffness", str(CASES / "floating_dock.yaml"), "--json"])
    import json
    data = json.loads(capsys.readouterr().out)
    assert status == 0 and data["dofs"] == ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    assert data["rows"][5] == "Mz [N m]" and data["columns"][3] == "roll [rad]"
    np.testing.assert_allclose(data["matrix"], K, rtol=1e-9)
    assert main(["stiffness", str(CASES / "floating_dock.yaml")]) == 0
    out = capsys.readouterr().out
    assert "Mz [N m]" in out and "yaw [rad]" in out
