"""The mooring check as a self-contained HTML report an engineer can sign and hand over.

One file: what was checked (package version, date, the case file and its SHA-256, the
standard and the solver tolerance), the case (environment, every segment of every line,
clumps and anchors), the pictures (intact and governing damaged condition, utilisation
chart) embedded as PNG, the results per condition and per leg, the criteria with their
sources, and a block for the signatures. It prints to A4 cleanly: page margins, table
headers repeated on every page, no row or figure split across pages, nothing wider than
the page (``tests/test_report_print.py`` prints it through headless Chromium).

It is written beside its target and renamed into place, so a failure never leaves a
half-written report.
"""

from __future__ import annotations

import base64
import datetime
import hashlib
import html
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING

from ..io.output_files import write_text
from .check_lines import design_tension_table
from .check_text import UTIL_LEGEND, check_json, format_check_table, kN, summary_rows

if TYPE_CHECKING:          # annotations only: the report reads what upstream made
    from ..checks import CheckReport

__all__ = ["check_json", "format_check_table", "render_html", "write_html_report",
           "summary_table", "case_fingerprint"]

_STYLE = """
@page { size: A4; margin: 14mm 12mm 16mm 12mm; }
body { font-family: "DejaVu Sans", Arial, sans-serif; margin: 2em auto; max-width: 1100px;
       color: #222; font-size: 10.5pt; }
h1 { font-size: 17pt; margin-bottom: 0.2em; } h2 { font-size: 13pt; margin-top: 1.4em;
     border-bottom: 1px solid #999; } h3 { font-size: 11pt; }
table { border-collapse: collapse; margin: 0.4em 0 1.2em; font-size: 9pt; }
th, td { border: 1px solid #bbb; padding: 2px 6px; text-align: right; vertical-align: top; }
th { background: #eee; } td.l, th.l { text-align: left; }
.pass { background: #d9f2d9; } .fail { background: #f8d0d0; font-weight: bold; }
img { max-width: 100%; display: block; margin: 0.3em 0; }
.note { color: #555; font-size: 9pt; }
.meta td { text-align: left; } .meta th { text-align: left; width: 12em; }
.verdict { font-size: 13pt; padding: 0.3em 0.6em; display: inline-block; }
.sign td { height: 2.4em; min-width: 12em; text-align: left; }
.mono { font-family: "DejaVu Sans Mono", monospace; font-size: 8.5pt; word-break: break-all; }
figure { margin: 0 0 1em; break-inside: avoid; page-break-inside: avoid; }
figcaption { font-size: 9pt; color: #444; }
@media print {
  body { margin: 0; max-width: none; font-size: 9.5pt; }
  h2 { break-after: avoid; page-break-after: avoid; }
  h3 { break-after: avoid; page-break-after: avoid; }
  table { font-size: 8pt; width: 100%; }
  thead { display: table-header-group; }
  tr, img, figure, .sign { break-inside: avoid; page-break-inside: avoid; }
  .pass, .fail, th { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
  .pagebreak { break-before: page; page-break-before: always; }
}
"""


def _e(text) -> str:
    return html.escape(str(text))


def _figure(png: bytes, caption: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return (f'<figure><img alt="{_e(caption)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{_e(caption)}</figcaption></figure>")


def _table(header, rows: list, left=1, cls: str = "") -> str:
    """An HTML table; ``left`` is how many leading columns are text (left-aligned) or a
    tuple of the text columns' indices; no ``header`` row when it is None."""
    text = set(range(left)) if isinstance(left, int) else set(left)

    def align(i):
        return "l" if i in text else ""
    out = [f'<table class="{cls}">']
    if header is not None:
        out.append("<thead><tr>" + "".join(f'<th class="{align(i)}">{_e(h)}</th>'
                                           for i, h in enumerate(header)) + "</tr></thead>")
    out.append("<tbody>")
    for row in rows:
        cells, css = row if isinstance(row, tuple) else (row, "")
        out.append(f'<tr class="{css}">' + "".join(
            f'<td class="{align(i)}">{_e(c)}</td>' for i, c in enumerate(cells)) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def case_fingerprint(case, case_file=None) -> tuple[str, str, str]:
    """``(source, what was hashed, sha256)``: the SHA-256 of the case file's bytes when
    given (what ``sha256sum FILE`` prints), else of the case data as canonical JSON."""
    if case_file is not None:
        digest = hashlib.sha256(Path(case_file).read_bytes()).hexdigest()
        return str(case_file), "SHA-256 of the case file", digest
    data = case.source if getattr(case, "source", None) is not None else {"name": case.name}
    text = json.dumps(data, sort_keys=True, separators=(",", ":"), default=str)
    return ("case data (no file)", "SHA-256 of the case data (canonical JSON)",
            hashlib.sha256(text.encode()).hexdigest())


def summary_table(report: CheckReport) -> tuple[list, list]:
    """``(header, rows)`` of the per-condition summary (worst values and the verdict)."""
    rows = []
    for row in summary_rows(report):
        uplift = row["anchor uplift"] or row["anchor uplift angle"]
        if not row["solved"]:
            rows.append(([row["condition"], "no equilibrium", "-", "-", "-", "-", "-", "-",
                          "-", row["reason"], "FAIL"], "fail"))
            continue
        rows.append(([row["condition"], "-" if row["offset"] is None else f"{row['offset']:.2f}",
                      row["leg"], kN(row["T"]), f"{row['mbl_over_T']:.2f}",
                      f"{row['required']:.2f}", f"{row['tension_util']:.3f}",
                      _item_text(uplift), _item_text(row["grounded length"]),
                      _item_text(row["offset check"]), "PASS" if row["passed"] else "FAIL"],
                     "pass" if row["passed"] else "fail"))
    header = ["condition", "offset [m]", "worst leg", "T max [kN]", "MBL/T", "required",
              "utilisation", "anchor uplift", "grounded length", "offset check", "result"]
    return header, rows


def render_html(report: CheckReport, case, images: dict, *, case_file=None,
                created=None) -> str:
    """The report as one HTML document.

    Parameters
    ----------
    report : CheckReport
    case : moorsolve.model.Case
    images : dict
        ``name -> PNG bytes``; ``"intact"``, ``"governing"`` (the views of the intact and
        of the worst damaged condition), ``"utilisation"`` and ``"sea"`` (the intact
        condition's sea, RAOs and tension spectra, with line dynamics) are placed.
    case_file : str or path, optional
        The case file checked: its path and SHA-256 are stated.
    created : datetime.datetime, optional
        The report's date (default now, UTC).
    """
    from .._version import __version__
    created = created or datetime.datetime.now(datetime.timezone.utc)
    verdict = "PASS" if report.passed else "FAIL"
    source, hashed, digest = case_fingerprint(case, case_file)
    standard = report.standard + (f", consequence class {report.consequence_class}"
                                  if report.standard == "dnv-os-e301" else "")
    footer = (f"Mooring check: {report.case_name}, {created:%Y-%m-%d}, "
              f"case SHA-256 {digest[:12]}")
    margins = ("@page { @bottom-left { content: " + _css_string(footer) + "; font-size: 7pt; "
               "color: #666; } @bottom-right { content: 'page ' counter(page) ' of ' "
               "counter(pages); font-size: 7pt; color: #666; } }")
    parts = [(f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
              f"<title>Mooring check: {_e(report.case_name)}</title>"
              f"<style>{_STYLE}{margins}</style></head><body>"),
             f"<h1>Mooring check: {_e(report.case_name)}</h1>",
             (f'<p><span class="verdict {verdict.lower()}">Result: <b>{verdict}</b></span> '
              f"{sum(c.passed for c in report.conditions)} of {len(report.conditions)} "
              f"conditions pass under {_e(standard)} ({_e(_analysis(report))}).</p>"),
             _table(None, [
                 ["software", f"moorsolve {__version__}"],
                 ["date", created.strftime("%Y-%m-%d %H:%M UTC")],
                 ["case", source],
                 [hashed, digest],
                 ["standard", standard],
                 ["solver tolerance", f"force residual <= {report.tolerance:.0e} of the largest "
                                      "line tension, certified per condition"],
                 ["conditions", f"intact and {len(report.conditions) - 1} damaged "
                                "(each leg removed in turn)"],
                 ["run time", f"{report.time_s:.2f} s"],
             ], left=2, cls="meta").replace('<td class="l">' + digest,
                                            '<td class="l mono">' + digest)]
    if report.warnings:
        # What no engineer may miss (moorsolve.audit.result_warnings), before all else.
        parts.append('<div class="fail"><p>Warnings:</p><ul>' + "".join(
            f"<li>{_e(w['condition'])}: {_e(w['message'])}</li>" for w in report.warnings)
            + "</ul></div>")
    parts += _case_section(report, case)
    parts.append("<h2>2. Plan, elevation and 3-D view</h2>")
    if "intact" in images:
        parts.append(_figure(images["intact"], "Intact condition: plan (loads in the inset, "
                                               "offset arrow), elevation and 3-D view; lines "
                                               "coloured by T/MBL (tension over breaking load) "
                                               "or tension."))
    if "governing" in images:
        parts.append(_figure(images["governing"], "Governing damaged condition: "
                                                  f"{images.get('governing_name', '')}."))
    parts.append("<h2>3. Tension utilisation per leg and condition</h2>")
    if "utilisation" in images:
        parts.append(_figure(images["utilisation"], "Tension over the allowed tension of the "
                                                    "standard (1.0 = limit); blank: the leg "
                                                    "removed; hatched: no equilibrium."))
    parts.append("<h2>4. Checks</h2>")
    header, rows = summary_table(report)
    parts.append(_table(header, rows))
    parts.append(f'<p class="note">{_e(UTIL_LEGEND)}.</p>')
    title, header, rows = design_tension_table(report)
    if rows:
        parts.append("<h3>Line design tensions</h3>")
        parts.append(f'<p class="note">{_e(title)}.</p>')
        parts.append(_table(header, rows, left=3))
    parts += [f'<p class="note">{_e(n)}.</p>' for n in report.notes]
    if "sea" in images:
        parts.append(_figure(images["sea"], "Intact condition: the wave spectrum, the "
                                            "body's RAOs, and every line's wave- and "
                                            "low-frequency tension spectra at its end of "
                                            "larger sigma."))
    if report.failures:
        parts.append("<p><b>Failures</b></p><ul>" + "".join(
            f"<li>{_e(f)}</li>" for f in report.failures) + "</ul>")
    parts += _criteria_section(report)
    parts += _detail_section(report)
    parts.append("<h2>7. Sign-off</h2>" + _table(
        ["", "name", "signature", "date"],
        [["prepared by", "", "", ""], ["checked by", "", "", ""],
         ["approved by", "", "", ""]], left=4, cls="sign"))
    parts.append("</body></html>")
    return "\n".join(parts)


def _case_section(report: CheckReport, case) -> list:
    env = case.environment
    flows = []
    for label, flow in (("wind", env.wind), ("current", env.current)):
        if flow is not None:
            flows.append(f"{label} {flow.speed:.2f} m/s {env.compass.describe(flow.toward_deg)}")
    if env.waves is not None:
        flows.append(f"waves Hs {env.waves.hs:.2f} m {env.compass.describe(env.waves.toward_deg)}")
    seabed = f"friction {env.seabed.friction:.2f}"
    grid = env.seabed.bathymetry
    if grid is not None:
        seabed += (f", bathymetry grid {len(grid.x)} x {len(grid.y)} nodes, depths "
                   f"{min(map(min, grid.depth)):.2f} to {max(map(max, grid.depth)):.2f} m")
    elif env.seabed.sloped:
        seabed += (f", sloped: z = -{env.depth:.2f} + {env.seabed.gradient[0]:g} x + "
                   f"{env.seabed.gradient[1]:g} y")
    out = ["<h2>1. Case</h2>", _table(None, [
        ["water depth", f"{env.depth:.2f} m"],
        ["water density, gravity", f"{env.water_density:.1f} kg/m^3, {env.gravity:.5f} m/s^2"],
        ["seabed", seabed],
        ["environment", "; ".join(flows) or "none"],
        ["bodies", "; ".join(f"{b.name}: free {', '.join(b.free) or 'none (held)'}"
                             for b in case.bodies) or "none (fairleads fixed)"],
        ["lines", str(len(case.lines))],
    ], left=2, cls="meta")]
    out.append(_table(
        ["line type", "w [N/m]", "EA [MN]", "MBL [kN]", "diameter [mm]", "source"],
        [[lt.name, f"{lt.weight_in_water:.1f}",
          (lt.stretch.describe() if lt.stretch is not None
           else "inextensible" if lt.ea is None else f"{lt.ea / 1e6:.1f}"),
          kN(lt.mbl) if lt.mbl else "none", "-" if lt.diameter is None
          else f"{lt.diameter * 1e3:.1f}",
          (f"catalogue {lt.catalog}"
           + (f", corrosion allowance {lt.corrosion_allowance * 1e3:.1f} mm"
              if lt.corrosion_allowance else "") + f" ({lt.source})") if lt.catalog
          else "case file"] for lt in case.line_types.values()], left=(0, 5)))
    checks = report.checks
    rows = []
    for leg in case.legs:
        anchor = _anchor_text(leg.anchor_type or checks.anchor)
        for k, seg in enumerate(leg.segments):
            first = k == 0
            rows.append([leg.name if first else "", _end_text(leg.a) if first else "",
                         _end_text(leg.b) if first else "",
                         f"{k + 1} of {len(leg.segments)}", seg.line_type.name,
                         f"{seg.length:.2f}", anchor if first else ""])
            clump = leg.joint_clumps[k] if k < len(leg.segments) - 1 else None
            if clump is not None:
                kind = "buoy" if clump.weight < 0 else "clump"
                given = ("" if clump.mass is None else f" ({clump.mass / 1e3:g} t, "
                         f"{clump.volume or 0.0:g} m^3)")
                rows.append(["", "", "", f"joint {k + 1}", kind,
                             f"{abs(clump.weight) / 1e3:.2f} kN "
                             f"{'net lift' if clump.weight < 0 else 'in water'}{given}", ""])
        if leg.multi_segment:
            rows.append(["", "", "", "total", "", f"{leg.length:.2f}", ""])
    out.append("<h3>Every line, segment by segment (from the anchor up)</h3>")
    out.append(_table(["line", "end A: anchor [m]", "end B: fairlead [m]", "segment",
                       "line type", "length [m]", "anchor type"], rows, left=7))
    return out


def _criteria_section(report: CheckReport) -> list:
    checks = report.checks
    out = ["<h2>5. Criteria</h2>", _table(
        ["standard", "condition", "analysis", "class", "factor on T", "gamma_dyn",
         "capacity", "MBL/T required", "source", "verified"],
        [[c.standard, c.condition, c.analysis, c.consequence_class or "-",
          f"{c.factor:.2f}", "-" if c.gamma_dyn is None else f"{c.gamma_dyn:.2f}",
          f"{c.capacity_factor:.2f} MBL", f"{c.required_safety_factor:.2f}", c.source,
          c.verified] for c in report.criteria], left=(0, 1, 2, 8, 9))]
    damaged_offset = checks.offset_limit_damaged or checks.offset_limit
    damaged_grounded = checks.min_grounded_length_damaged or checks.min_grounded_length
    limits = [(f"offset limit intact {_opt(checks.offset_limit, 'm')}, damaged "
               f"{_opt(damaged_offset, 'm')}"),
              (f"minimum grounded length intact {_opt(checks.min_grounded_length, 'm')}, "
               f"damaged {_opt(damaged_grounded, 'm')}"),
              f"default anchor: {_anchor_text(checks.anchor)}"]
    out.append("<ul>" + "".join(f"<li>{_e(x)}</li>" for x in limits) + "</ul>")
    out.append(f'<p class="note">Line tension: {_e(report.method)}.</p>')
    methods = {c.method for c in report.conditions if c.solved}
    if "dynamic" in methods:
        where = ("the mean tension (mean drift included) plus the dynamic part from each "
                 "line's dynamics driven by the bodies' motions, at the end of larger "
                 "utilisation; the offset, uplift and grounded length at the design offset")
    elif "design offset" in methods:
        where = ("the larger of the fairlead and anchor tension with each moving body held "
                 "at its design offset, the lines re-solved")
    else:
        where = ("the larger of the fairlead and anchor tension of the quasi-static "
                 "equilibrium under the mean environmental loads; a DNV-OS-E301 check on "
                 "it covers the mean tension only (no dynamic part), so it is necessary "
                 "but not sufficient")
    out.append(f'<p class="note">The line tension is {where}. Damaged conditions remove '
               "one leg and solve the body again (its motions and line dynamics "
               "re-computed where they run).</p>")
    return out


def _detail_section(report: CheckReport) -> list:
    detail = []
    for c in report.conditions:
        # A body lost in the condition (nothing holds it) heads the condition's rows.
        detail += [([c.name, f"body {d['body']}", "held by the mooring", "-", "-", "-",
                     d["message"], "FAIL"], "fail") for d in c.drifting]
        for item in c.items:
            if item.leg is None:
                continue
            detail.append(([c.name, item.leg, item.check, _value(item.value, item.unit),
                            _value(item.limit, item.unit), f"{item.utilisation:.3f}",
                            item.criterion, "ok" if item.passed else "FAIL"],
                           "" if item.passed else "fail"))
    return ['<h2 class="pagebreak">6. Every leg in every condition</h2>',
            _table(["condition", "leg", "check", "value", "limit", "utilisation",
                    "criterion", "result"], detail, left=3)]


def _analysis(report: CheckReport) -> str:
    methods = {c.method for c in report.conditions if c.solved}
    if "dynamic" in methods:
        return "line dynamics in the sea state"
    if "design offset" in methods:
        return "quasi-static analysis at the design offset"
    return "quasi-static analysis, mean tension"


def _css_string(text: str) -> str:
    """``text`` as a CSS string literal (inside a <style> element)."""
    safe = "".join(c if c.isprintable() and c not in "\\'<>" else " " for c in text)
    return f"'{safe}'"


def _end_text(end) -> str:
    """A line end in words: coordinates (fixed), a point's name, or a body and where on it."""
    xyz = ", ".join(f"{v:.2f}" for v in end.position)
    if end.body is not None:
        return f"{end.body}: {xyz} (body frame)"
    if end.point is not None:
        return f"point {end.point}"
    return xyz


def _opt(value, unit: str) -> str:
    return "none" if value is None else f"{value:.2f} {unit}"


def _value(value: float, unit: str) -> str:
    if value is None or not math.isfinite(value):
        return "-"
    if unit == "N":
        return f"{value / 1e3:.1f} kN"
    return f"{value:.2f} {unit}"


def _item_text(item) -> str:
    if item is None:
        return "-"
    return f"{_value(item.value, item.unit)} / {_value(item.limit, item.unit)} " \
           f"{'ok' if item.passed else 'FAIL'}"


def _anchor_text(anchor) -> str:
    if anchor.kind == "deadweight":
        return f"deadweight, uplift <= {anchor.allowed_uplift / 1e3:.1f} kN"
    if anchor.kind == "pile":
        return f"pile, uplift angle <= {anchor.allowed_uplift_angle_deg:.1f} deg"
    return "drag, no uplift"


def write_html_report(report: CheckReport, case, path: str, *, case_file=None) -> None:
    """Render the pictures and write the report to ``path`` atomically.

    ``case_file`` is the case file checked (its path and SHA-256 go in the report).
    """
    import matplotlib
    matplotlib.use("Agg")
    from ..plot import figure_png, plot_equilibrium, utilisation_figure

    images = {}
    intact = report.conditions[0]
    if intact.result is not None:
        images["intact"] = figure_png(plot_equilibrium(intact.result, layout="portrait"),
                                      dpi=110)
    damaged = [c for c in report.conditions[1:] if c.result is not None and c.worst()]
    if damaged:
        governing = max(damaged, key=lambda c: c.worst().utilisation)
        images["governing"] = figure_png(plot_equilibrium(
            governing.result, layout="portrait", removed_from=intact.result), dpi=110)
        images["governing_name"] = governing.name
    images["utilisation"] = figure_png(utilisation_figure(report), dpi=130)
    if intact.tensions:
        from ..plot.line_tension import sea_check_figure
        images["sea"] = figure_png(sea_check_figure(intact), dpi=100)
    text = render_html(report, case, images, case_file=case_file)
    write_text(path, text)
