"""The priced mooring as text: one row per segment and anchor, then the totals."""

from __future__ import annotations

__all__ = ["format_cost_table"]


def format_cost_table(priced, case_name: str) -> str:
    """``priced`` (:class:`moorsolve.checks.cost.MooringCost`) as plain text."""
    cur = priced.currency
    header = (f"{'item':<18}{'material':>16}{'quantity':>14}{'rate':>16}"
              f"{'cost ' + cur:>16}")
    lines = [f"Mooring cost: {case_name} ({cur} of 2024, material only)", "", header,
             "-" * len(header)]
    for item in priced.items:
        unit = "USD/m" if item.unit == "m" else "USD/kg"
        lines.append(f"{item.name:<18}{item.material:>16}"
                     f"{f'{item.quantity:,.1f} {item.unit}':>14}"
                     f"{f'{item.rate:,.2f} {unit}':>16}{item.cost:>16,.0f}")
    lines += ["-" * len(header),
              f"{'lines':<18}{priced.lines:>62,.0f}",
              f"{'anchors':<18}{priced.anchors:>62,.0f}",
              f"{'total':<18}{priced.total:>62,.0f}"]
    lines += [f"not priced: {what}" for what in priced.unpriced]
    sources = dict.fromkeys(item.source for item in priced.items)
    lines += ["", "basis:"] + [f"  {s}" for s in sources]
    return "\n".join(lines)
