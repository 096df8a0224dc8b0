"""The mooring check out: a text summary, JSON, and a self-contained HTML report.

The HTML report is one file: the plots are embedded as base64 PNG images made by
:mod:`moorsolve.plot`. It is written beside its target and renamed into place, so a failure
never leaves a half-written report.
"""

from __future__ import annotations

import base64
import html
import json
import math

from ..checks import CheckReport
from ..io.output_files import write_text
from .text import _finite

__all__ = ["check_json", "format_check_table", "render_html", "write_html_report"]


def _kN(value: float) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value / 1e3:.1f}"


def _summary_rows(report: CheckReport) -> list:
    """One row per condition: the worst value of each check and the verdict."""
    rows = []
    for c in report.conditions:
        row = {"condition": c.name, "solved": c.solved, "passed": c.passed,
               "reason": c.reason}
        t = c.worst("tension")
        row["leg"] = t.leg if t else "-"
        row["T"] = t.value if t else math.nan
        row["mbl_over_T"] = (t.limit * c.criterion.factor / c.criterion.capacity_factor
                             / t.value if t and t.value > 0 and math.isfinite(t.limit)
                             else math.nan)
        row["required"] = c.criterion.required_safety_factor
        row["tension_util"] = t.utilisation if t else math.nan
        for check in ("anchor uplift", "anchor uplift angle", "grounded length"):
            row[check] = c.worst(check)
        row["offset check"] = c.worst("offset")
        row["offset"] = c.offset_m
        rows.append(row)
    return rows


def _mark(item) -> str:
    if item is None:
        return "-"
    return "ok" if item.passed else "FAIL"


def format_check_table(report: CheckReport) -> str:
    """The check as plain text: one line per condition, then every failure."""
    crit = {c.condition: c for c in report.criteria if c.analysis == "quasi-static"
            and c.consequence_class in (None, report.consequence_class)}
    lines = [f"Mooring check: {report.case_name}",
             f"standard     {report.standard} (quasi-static): "
             + "; ".join(f"{k} {v.describe().split(': ', 1)[1]}" for k, v in crit.items())]
    header = (f"{'condition':<22}{'offset m':>9}{'leg':>6}{'T max kN':>10}{'MBL/T':>7}"
              f"{'req':>6}{'util':>6}{'uplift':>8}{'grounded':>9}{'offset':>7}  result")
    lines += ["", header, "-" * len(header)]
    for row in _summary_rows(report):
        if not row["solved"]:
            lines.append(f"{row['condition']:<22}  no equilibrium: {row['reason']}  FAIL")
            continue
        uplift = row["anchor uplift"] or row["anchor uplift angle"]
        offset = "-" if row["offset"] is None else f"{row['offset']:.2f}"
        lines.append(
            f"{row['condition']:<22}{offset:>9}{row['leg']:>6}{row['T'] / 1e3:10.1f}"
            f"{row['mbl_over_T']:7.2f}{row['required']:6.2f}{row['tension_util']:6.2f}"
            f"{_mark(uplift):>8}{_mark(row['grounded length']):>9}{_mark(row['offset check']):>7}"
            f"  {'PASS' if row['passed'] else 'FAIL'}")
    lines.append("")
    failures = report.failures
    lines.append(f"result       {'PASS' if report.passed else 'FAIL'}: "
                 f"{sum(c.passed for c in report.conditions)} of {len(report.conditions)} "
                 f"conditions pass ({report.time_s:.2f} s)")
    for failure in failures:
        lines.append(f"  failed: {failure}")
    return "\n".join(lines)


def check_json(report: CheckReport) -> str:
    """The check as JSON text; non-finite numbers become null."""
    return json.dumps(_finite(report.to_dict()), indent=2)


# ---- HTML --------------------------------------------------------------------------------

_STYLE = """
body { font-family: sans-serif; margin: 2em; max-width: 1200px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 3px 8px; text-align: right; }
th { background: #eee; } td.l, th.l { text-align: left; }
.pass { background: #d9f2d9; } .fail { background: #f8d0d0; font-weight: bold; }
img { max-width: 100%; } .note { color: #555; font-size: 0.9em; }
"""


def _e(text) -> str:
    return html.escape(str(text))


def _img(png: bytes, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return f'<img alt="{_e(alt)}" src="data:image/png;base64,{data}">'


def _table(header: list, rows: list, left: int = 1) -> str:
    out = ["<table><tr>" + "".join(
        f'<th class="{"l" if i < left else ""}">{_e(h)}</th>' for i, h in enumerate(header))
        + "</tr>"]
    for row in rows:
        cells, cls = row if isinstance(row, tuple) else (row, "")
        out.append(f'<tr class="{cls}">' + "".join(
            f'<td class="{"l" if i < left else ""}">{_e(c)}</td>' for i, c in enumerate(cells))
            + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def render_html(report: CheckReport, case, images: dict) -> str:
    """The report as one HTML document.

    Parameters
    ----------
    report : CheckReport
    case : moorsolve.model.Case
    images : dict
        ``name -> PNG bytes``; ``"intact"``, ``"governing"`` (plan and elevation of the
        intact and of the worst damaged condition) and ``"utilisation"`` are placed.
    """
    env = case.environment
    verdict = "PASS" if report.passed else "FAIL"
    parts = [(f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Mooring check: "
              f"{_e(report.case_name)}</title><style>{_STYLE}</style></head><body>"),
             f"<h1>Mooring check: {_e(report.case_name)}</h1>",
             (f'<p class="{verdict.lower()}">Result: <b>{verdict}</b>: '
              f"{sum(c.passed for c in report.conditions)} of {len(report.conditions)} "
              f"conditions pass under {_e(report.standard)} (quasi-static analysis).</p>")]

    # 1. Case summary.
    parts.append("<h2>1. Case</h2>")
    flows = []
    for label, flow in (("wind", env.wind), ("current", env.current)):
        if flow is not None:
            flows.append(f"{label} {flow.speed:.2f} m/s toward {flow.toward_deg:.1f} deg")
    if env.waves is not None:
        flows.append(f"waves Hs {env.waves.hs:.2f} m toward {env.waves.toward_deg:.1f} deg")
    parts.append(_table(["quantity", "value"], [
        ["water depth", f"{env.depth:.2f} m"],
        ["water density, gravity", f"{env.water_density:.1f} kg/m^3, {env.gravity:.5f} m/s^2"],
        ["seabed friction", f"{env.seabed.friction:.2f}"],
        ["environment", "; ".join(flows) or "none"],
        ["body", "none (fairleads fixed)" if case.body is None
         else "free: " + ", ".join(case.body.free)],
        ["legs", str(len(case.legs))],
    ]))
    parts.append(_table(
        ["line type", "w [N/m]", "EA [MN]", "MBL [kN]", "diameter [mm]", "source"],
        [[lt.name, f"{lt.weight_in_water:.1f}",
          (lt.stretch.describe() if lt.stretch is not None
           else "inextensible" if lt.ea is None else f"{lt.ea / 1e6:.1f}"),
          _kN(lt.mbl) if lt.mbl else "none", "-" if lt.diameter is None
          else f"{lt.diameter * 1e3:.1f}",
          (f"catalogue {lt.catalog}"
           + (f", corrosion allowance {lt.corrosion_allowance * 1e3:.1f} mm"
              if lt.corrosion_allowance else "") + f" ({lt.source})") if lt.catalog
          else "case file"] for lt in case.line_types.values()]))
    checks = report.checks
    default_anchor = checks.anchor
    parts.append(_table(
        ["leg", "anchor [m]", "fairlead [m]", "length [m]", "line", "anchor type"],
        [[leg.name, ", ".join(f"{v:.2f}" for v in leg.anchor),
          ", ".join(f"{v:.2f}" for v in leg.fairlead), f"{leg.length:.2f}",
          leg.line_type.name, _anchor_text(leg.anchor_type or default_anchor)]
         for leg in case.legs]))

    # 2. Plots.
    parts.append("<h2>2. Plan and elevation</h2>")
    if "intact" in images:
        parts.append("<h3>Intact</h3>" + _img(images["intact"], "intact plan and elevation"))
    if "governing" in images:
        parts.append(f"<h3>Governing damaged condition: {_e(images.get('governing_name', ''))}"
                     "</h3>" + _img(images["governing"], "damaged plan and elevation"))

    # 3. Utilisation chart.
    parts.append("<h2>3. Tension utilisation per leg and condition</h2>")
    if "utilisation" in images:
        parts.append(_img(images["utilisation"], "utilisation chart"))

    # 4. Pass/fail table.
    parts.append("<h2>4. Checks</h2>")
    rows = []
    for row in _summary_rows(report):
        uplift = row["anchor uplift"] or row["anchor uplift angle"]
        if not row["solved"]:
            rows.append(([row["condition"], "no equilibrium", "-", "-", "-", "-", "-", "-",
                          "-", row["reason"], "FAIL"], "fail"))
            continue
        rows.append(([row["condition"], "-" if row["offset"] is None else f"{row['offset']:.2f}",
                      row["leg"], _kN(row["T"]), f"{row['mbl_over_T']:.2f}",
                      f"{row['required']:.2f}", f"{row['tension_util']:.3f}",
                      _item_text(uplift), _item_text(row["grounded length"]),
                      _item_text(row["offset check"]), "PASS" if row["passed"] else "FAIL"],
                     "pass" if row["passed"] else "fail"))
    parts.append(_table(["condition", "offset [m]", "worst leg", "T max [kN]", "MBL/T",
                         "required", "utilisation", "anchor uplift", "grounded length",
                         "offset check", "result"], rows))
    detail = []
    for c in report.conditions:
        for item in c.items:
            if item.leg is None:
                continue
            detail.append(([c.name, item.leg, item.check, _value(item.value, item.unit),
                            _value(item.limit, item.unit), f"{item.utilisation:.3f}",
                            item.criterion, "ok" if item.passed else "FAIL"],
                           "" if item.passed else "fail"))
    parts.append("<details><summary>Every leg in every condition</summary>"
                 + _table(["condition", "leg", "check", "value", "limit", "utilisation",
                           "criterion", "result"], detail, left=3) + "</details>")
    if report.failures:
        parts.append("<p><b>Failures</b></p><ul>" + "".join(
            f"<li>{_e(f)}</li>" for f in report.failures) + "</ul>")

    # 5. Criteria with citations.
    parts.append("<h2>5. Criteria</h2>")
    parts.append(_table(
        ["standard", "condition", "analysis", "class", "factor on T", "gamma_dyn",
         "capacity", "MBL/T required", "source", "verified"],
        [[c.standard, c.condition, c.analysis, c.consequence_class or "-",
          f"{c.factor:.2f}", "-" if c.gamma_dyn is None else f"{c.gamma_dyn:.2f}",
          f"{c.capacity_factor:.2f} MBL", f"{c.required_safety_factor:.2f}", c.source,
          c.verified] for c in report.criteria], left=3))
    damaged_offset = checks.offset_limit_damaged or checks.offset_limit
    damaged_grounded = checks.min_grounded_length_damaged or checks.min_grounded_length
    limits = [(f"offset limit intact {_opt(checks.offset_limit, 'm')}, damaged "
               f"{_opt(damaged_offset, 'm')}"),
              (f"minimum grounded length intact {_opt(checks.min_grounded_length, 'm')}, "
               f"damaged {_opt(damaged_grounded, 'm')}"),
              f"default anchor: {_anchor_text(default_anchor)}"]
    parts.append("<ul>" + "".join(f"<li>{_e(x)}</li>" for x in limits) + "</ul>")
    parts.append('<p class="note">The line tension is the larger of the fairlead and anchor '
                 "tension of the quasi-static equilibrium under the mean environmental loads. "
                 "Damaged conditions remove one leg and solve the body again. Only the "
                 "quasi-static rows of the table are applied; a DNV-OS-E301 check on a "
                 "quasi-static solution covers the mean tension only (no dynamic part), so "
                 "it is necessary but not sufficient.</p>")
    parts.append("</body></html>")
    return "\n".join(parts)


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


def write_html_report(report: CheckReport, case, path: str) -> None:
    """Render the plots and write the report to ``path`` atomically."""
    import matplotlib
    matplotlib.use("Agg")
    from ..plot import figure_png, plot_equilibrium, utilisation_figure

    images = {}
    intact = report.conditions[0]
    if intact.result is not None:
        images["intact"] = figure_png(plot_equilibrium(intact.result,
                                                       depth=case.environment.depth))
    damaged = [c for c in report.conditions[1:] if c.result is not None and c.worst()]
    if damaged:
        governing = max(damaged, key=lambda c: c.worst().utilisation)
        images["governing"] = figure_png(plot_equilibrium(governing.result,
                                                          depth=case.environment.depth))
        images["governing_name"] = governing.name
    images["utilisation"] = figure_png(utilisation_figure(report))
    text = render_html(report, case, images)
    write_text(path, text)
