"""The end-of-life check as text and JSON (:mod:`moorsolve.checks.end_of_life`)."""

from __future__ import annotations

import json

from .check_text import format_check_table
from .text import _finite

__all__ = ["end_of_life_text", "end_of_life_json"]


def _mm(value) -> str:
    return "-" if value is None else f"{value * 1e3:.1f}"


def _kn(value) -> str:
    return "-" if value is None else f"{value / 1e3:.0f}"


def end_of_life_text(eol) -> str:
    """The worn lines (age, zones, diameters, MBL, weight, length) then the check table."""
    head = [f"End of life: after {eol.design_life_y:g} years of corrosion and creep",
            "zones from the new mooring's intact mean equilibrium: bottom on the seabed, "
            + ("splash down to "
               f"{eol.splash_depth_m:g} m below still water, " if eol.splash_depth_m
               is not None else "no splash zone given, ")
            + "catenary the rest"]
    header = (f"{'line':>8}{'seg':>4} {'type':<14}{'zone':<24}{'L m':>9}{'L eol m':>9}"
              f"{'mm/y':>6}{'d mm':>7}{'d eol':>7}{'d fat':>7}{'MBL kN':>8}{'eol kN':>8}"
              f"{'w N/m':>8}{'eol N/m':>8}")
    head += ["", header, "-" * len(header)]
    for row in eol.segments:
        for k, part in enumerate(row["parts"]):
            rate = part["rate_mm_per_y"]
            head.append(
                f"{(row['line'] if k == 0 else ''):>8}{(row['segment'] if k == 0 else ''):>4} "
                f"{(row['line_type'] if k == 0 else ''):<14}{part['zone']:<24}"
                f"{part['length_m']:9.2f}{part['length_eol_m']:9.2f}"
                f"{'-' if rate is None else f'{rate:.2f}':>6}"
                f"{_mm(part['diameter_m']):>7}{_mm(part['diameter_eol_m']):>7}"
                f"{_mm(part['fatigue_diameter_m']):>7}{_kn(part['mbl_N']):>8}"
                f"{_kn(part['mbl_eol_N']):>8}{part['weight_N_per_m']:8.1f}"
                f"{part['weight_eol_N_per_m']:8.1f}")
        if row["creep_strain"] is not None:
            head.append(f"{'':>13}creep: {row['creep_strain'] * 100:.2f} % longer")
    head.append(f"{'':>13}d fat: the fatigue diameter (nominal less half the loss)")
    return "\n".join(head + ["", format_check_table(eol.report)])


def end_of_life_json(eol) -> str:
    """The end-of-life check as JSON: the check report's fields and ``end_of_life``."""
    return json.dumps(_finite(eol.to_dict()), indent=2)
