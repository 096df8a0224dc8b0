"""The anchor capacity rows of the check report: the load at each padeye and its capacity."""

from __future__ import annotations

import math

__all__ = ["anchor_check_lines"]


def _kN(value) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value / 1e3:.1f}"


def anchor_check_lines(report, wide: int) -> list:
    """One row per anchor and condition with an anchor capacity item (none: no rows)."""
    rows = [(c, i) for c in report.conditions for i in c.items if i.check == "anchor capacity"]
    if not rows:
        return []
    header = (f"{'condition':<{wide}}{'leg':>6}{'kind':>9}{'T mud kN':>10}{'deg':>6}"
              f"{'T pad kN':>10}{'deg':>6}{'capacity kN':>13}{'util':>7}  result")
    out = ["", "anchor capacity (load at the padeye; capacity: UHC or H_max / V_max):",
           header, "-" * len(header)]
    last = None
    for c, item in rows:
        d = item.detail
        if not d:       # no design or no factors: the criterion says why
            out.append(f"{(c.name if c.name != last else ''):<{wide}}{item.leg:>6}  "
                       f"{item.criterion}  FAIL")
            last = c.name
            continue
        capacity = (_kN(d["capacity_N"]) if d["kind"] == "drag"
                    else f"{_kN(d['h_max_N'])}/{_kN(d['v_max_N'])}")
        out.append(f"{(c.name if c.name != last else ''):<{wide}}{item.leg:>6}{d['kind']:>9}"
                   f"{_kN(d['mudline_tension_N']):>10}{d['mudline_angle_deg']:>6.1f}"
                   f"{_kN(d['padeye_tension_N']):>10}{d['padeye_angle_deg']:>6.1f}"
                   f"{capacity:>13}{item.utilisation:>7.3f}  "
                   f"{'ok' if item.passed else 'FAIL'}"
                   + ("  (line vertical in the soil above the padeye: 90 deg, T pad an "
                      "upper bound)" if d["reached_vertical"] else ""))
        last = c.name
    crits = sorted({i.criterion for _, i in rows if i.detail})
    out += [f"{'':<4}{text}" for text in crits]
    return out
