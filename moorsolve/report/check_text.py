"""The mooring check as text and JSON (``moorsolve check`` and ``--json``)."""

from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING

from .anchors import anchor_check_lines
from .berth import berth_check_lines
from .check_lines import design_tension_text
from .text import _finite

if TYPE_CHECKING:          # annotations only: the report reads what upstream made
    from ..checks import CheckReport

__all__ = ["check_json", "format_check_table", "summary_rows", "kN", "UTIL_LEGEND"]

#: What the check's ratios mean, printed with every table of them.
UTIL_LEGEND = ("util = tension / the standard's allowable tension (1.00 = the limit); "
               "MBL/T = safety factor, req = the least allowed")


def kN(value: float) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value / 1e3:.1f}"


def summary_rows(report: CheckReport) -> list:
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


def _num(value: float, width: int, digits: int) -> str:
    """A right-aligned number, or ``-`` where there is none (no chain in a berth's
    scene, no MBL)."""
    if value is None or not math.isfinite(value):
        return f"{'-':>{width}}"
    return f"{value:{width}.{digits}f}"


def mark(item) -> str:
    if item is None:
        return "-"
    return "ok" if item.passed else "FAIL"


def format_check_table(report: CheckReport) -> str:
    """The check as plain text: one line per condition, then every failure."""
    crit = {c.kind: c.criterion for c in report.conditions}
    analysis = ("dynamic" if any(c.method == "dynamic" for c in report.conditions)
                else "quasi-static")
    dynamic = any(c.method != "mean" for c in report.conditions)
    lines = [f"Mooring check: {report.case_name}",
             f"standard     {report.standard} ({analysis}): "
             + "; ".join(f"{k} {v.describe(dynamic=dynamic).split(': ', 1)[1]}"
                         for k, v in crit.items()),
             f"method       {report.method}",
             f"columns      {UTIL_LEGEND}"]
    rows = summary_rows(report)
    wide = max([22] + [len(row["condition"]) + 1 for row in rows])
    legs = max([6] + [len(str(row["leg"])) + 1 for row in rows])
    header = (f"{'condition':<{wide}}{'offset m':>9}{'leg':>{legs}}{'T max kN':>10}"
              f"{'MBL/T':>7}{'req':>6}{'util':>6}{'uplift':>8}{'grounded':>9}{'offset':>7}"
              "  result")
    lines += ["", header, "-" * len(header)]
    for row, c in zip(rows, report.conditions):
        if not row["solved"]:
            lines.append(f"{row['condition']:<{wide}}  no equilibrium: {row['reason']}  FAIL")
        else:
            uplift = row["anchor uplift"] or row["anchor uplift angle"]
            offset = "-" if row["offset"] is None else f"{row['offset']:.2f}"
            lines.append(
                f"{row['condition']:<{wide}}{offset:>9}{row['leg']:>{legs}}"
                f"{_num(row['T'] / 1e3, 10, 1)}{_num(row['mbl_over_T'], 7, 2)}"
                f"{_num(row['required'] if row['leg'] != '-' else None, 6, 2)}"
                f"{_num(row['tension_util'], 6, 2)}{mark(uplift):>8}"
                f"{mark(row['grounded length']):>9}{mark(row['offset check']):>7}"
                f"  {'PASS' if row['passed'] else 'FAIL'}")
        # A body lost in this condition, under its row where the eye is.
        lines += [f"{'':<4}LOST: {d['message']}" for d in c.drifting]
    lines += berth_check_lines(report, wide)  # hawsers, fenders, guides
    lines += anchor_check_lines(report, wide)
    lines += design_tension_text(report, wide)
    if report.fatigue is not None:
        from .fatigue import fatigue_text
        lines += ["", fatigue_text(report.fatigue)]
    lines += [f"note         {n}" for n in report.notes]
    lines.append("")
    failures = report.failures
    lines.append(f"result       {'PASS' if report.passed else 'FAIL'}: "
                 f"{sum(c.passed for c in report.conditions)} of {len(report.conditions)} "
                 f"conditions pass ({report.time_s:.2f} s)")
    for failure in failures:
        lines.append(f"  failed: {failure}")
    lines += [f"WARNING: {w['condition']}: {w['message']}" for w in report.warnings]
    return "\n".join(lines)


def check_json(report: CheckReport) -> str:
    """The check as JSON text; non-finite numbers become null."""
    return json.dumps(_finite(report.to_dict()), indent=2)
