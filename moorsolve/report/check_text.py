"""The mooring check as text and JSON (``moorsolve check`` and ``--json``)."""

from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING

from .berth import berth_check_lines
from .text import _finite

if TYPE_CHECKING:          # annotations only: the report reads what upstream made
    from ..checks import CheckReport

__all__ = ["check_json", "format_check_table", "summary_rows", "kN"]


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


def _number(value, applies: bool = True) -> str:
    """Two decimals, or "-" where the column does not apply (no mooring line: only hawsers)."""
    return f"{value:.2f}" if applies and value is not None and math.isfinite(value) else "-"


def mark(item) -> str:
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
    for row in summary_rows(report):
        if not row["solved"]:
            lines.append(f"{row['condition']:<22}  no equilibrium: {row['reason']}  FAIL")
            continue
        uplift = row["anchor uplift"] or row["anchor uplift angle"]
        offset = "-" if row["offset"] is None else f"{row['offset']:.2f}"
        lines.append(
            f"{row['condition']:<22}{offset:>9}{row['leg']:>6}{kN(row['T']):>10}"
            f"{_number(row['mbl_over_T']):>7}{_number(row['required'], row['leg'] != '-'):>6}"
            f"{_number(row['tension_util']):>6}"
            f"{mark(uplift):>8}{mark(row['grounded length']):>9}{mark(row['offset check']):>7}"
            f"  {'PASS' if row['passed'] else 'FAIL'}")
    lines += berth_check_lines(report)       # hawsers, fenders, guides (issue 15)
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
