"""The design-tension table of a check: every line in every condition, as the standard
writes it (``T_mean``, ``T_dyn``, ``T_max``, the design tension, the capacity and the
utilisation), for the text output and the HTML report alike."""

from __future__ import annotations

import math

__all__ = ["design_tension_table", "design_tension_text"]

_TITLE = {
    "mean": "the mean tension (no dynamic part)",
    "design offset": "T max at the design offset; T mean with the mean drift",
    "dynamic": ("T dyn from the lines' dynamics; sig WF, sig LF the wave- and low-frequency "
                "standard deviations at that end"),
}


def design_tension_table(report, methods=("design offset", "dynamic")) -> tuple:
    """``(title, header, rows)`` of the lines' design tensions in the solved conditions
    checked by one of ``methods``; rows of strings (forces in kN), the condition's name on
    its first line only, and a last row per condition with its design offsets. ``rows`` is
    empty where no condition qualifies."""
    conds = [c for c in report.conditions if c.solved and c.method in methods and c.lines]
    used = sorted({c.method for c in conds})
    dynamic = "dynamic" in used
    header = ["condition", "leg", "end", "T mean kN", "T dyn kN", "T max kN", "design kN",
              "capacity kN", "util"] + (["sig WF kN", "sig LF kN"] if dynamic else [])
    rows = []
    for c in conds:
        for i, line in enumerate(c.lines):
            row = [c.name if i == 0 else "", line["leg"], line["end"],
                   _kn(line["t_mean_N"]), _kn(line["t_dyn_N"]), _kn(line["t_max_N"]),
                   _kn(line["design_N"]), _kn(line["capacity_N"]),
                   _num(line["utilisation"], 3)]
            if dynamic:
                d = line.get("dynamic") or {}
                row += [_kn(d.get("sigma_wf_N")), _kn(d.get("sigma_lf_N"))]
            rows.append(row)
        if c.design_offset_m:
            offsets = ", ".join(f"{name} {d:.2f} m" for name, d in c.design_offset_m.items())
            rows.append(["", f"design offset: {offsets}"] + [""] * (len(header) - 2))
    title = "; ".join(_TITLE[m] for m in used)
    return title, header, rows


def design_tension_text(report, wide: int) -> list:
    """The table as text lines (empty where no condition ran in a sea state)."""
    title, header, rows = design_tension_table(report)
    if not rows:
        return []
    widths = [wide, 6, 9, 11, 10, 10, 11, 13, 7, 11, 11][:len(header)]
    head = "".join(f"{h:<{w}}" if k == 0 else f"{h:>{w}}"
                   for k, (h, w) in enumerate(zip(header, widths)))
    out = ["", f"line design tension ({title}):", head, "-" * len(head)]
    for row in rows:
        if row[1].startswith("design offset"):
            out.append(f"{'':<{wide}}{row[1]}")
            continue
        out.append("".join(f"{v:<{w}}" if k == 0 else f"{v:>{w}}"
                           for k, (v, w) in enumerate(zip(row, widths))))
    return out


def _kn(value) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value / 1e3:.1f}"


def _num(value, digits: int) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value:.{digits}f}"
