"""The design-optimisation report as text and JSON (``moorsolve optimise``)."""

from __future__ import annotations

import json
import math

_LABEL = {"safety_factor": "safety factor", "anchor_uplift": "anchor uplift",
          "grounded_length": "grounded length", "offset": "offset", "cost": "cost (max_cost)"}


def _value(v: float, unit: str) -> str:
    if not math.isfinite(v):
        return "inf"
    if unit == "N":
        return f"{v / 1e3:.1f} kN"
    if unit == "-":
        return f"{v:.3f}"
    if unit != "m":  # a currency: the cost cap
        return f"{v:,.0f} {unit}"
    return f"{v:.3f} m"


def _amount(v: float, unit: str) -> str:
    return f"{v:,.0f} {unit}"


def optimisation_json(opt) -> str:
    """Every variable, constraint, multiplier and verification, as JSON."""
    return json.dumps(opt.to_dict(), indent=2, default=float)


def format_optimisation(opt, every_constraint: bool = False) -> str:
    """A readable report of an :class:`~moorsolve.studies.optimise.Optimisation`.

    Constraints are listed per load case and kind by their tightest leg (every one with
    ``every_constraint``); active ones are marked ``*``.
    """
    what = "line mass" if opt.objective == "mass" else "cost"
    saving = opt.objective_start - opt.objective_optimum
    pct = 100 * saving / opt.objective_start if opt.objective_start else 0.0
    lines = [
        f"Design optimisation: {opt.study_name} ({opt.case_name})",
        f"objective ({what}): start {_amount(opt.objective_start, opt.unit)}, optimum "
        f"{_amount(opt.objective_optimum, opt.unit)}, saving {_amount(saving, opt.unit)} "
        f"({pct:.2f} %)",
        *([] if opt.max_cost is None else [
            f"cost: {_amount(opt.cost, opt.currency)} against max_cost "
            f"{_amount(opt.max_cost, opt.currency)}, utilisation {opt.cost_utilisation:.4f}"
            + ("" if opt.cost_within_cap else " (OVER THE CAP)")]),
        f"IPOPT: {opt.status}, {opt.iterations} iterations, {opt.solve_time_s:.3f} s "
        f"({opt.total_time_s:.2f} s with the start solves, build and verification)",
        "",
        f"{'variable':<16} {'type':<16} {'start m':>10} {'optimum m':>10} {'change m':>9} "
        f"{'bounds m':>17}  legs",
    ]
    for v in opt.variables:
        bound = f"[{v.lower:g}, {v.upper:g}]" + ("*" if v.at_bound else " ")
        lines.append(f"{v.name:<16} {v.kind:<16} {v.start:10.3f} {v.optimum:10.3f} "
                     f"{v.change:+9.3f} {bound:>17}  {', '.join(v.legs)}")
    scope = "every one" if every_constraint else "tightest leg per load case and kind"
    lines += ["", f"constraints ({scope}; * active, margin > 0 satisfied):",
              f"  {'load case':<22} {'constraint':<16} {'leg':<6} {'value':>12} "
              f"{'limit':>12} {'margin':>12} {'multiplier':>11}"]
    rows = opt.constraints
    if not every_constraint:
        tight = {}
        for c in rows:
            key = (c.load_case, c.kind)
            if key not in tight or c.margin < tight[key].margin:
                tight[key] = c
        shown = set(map(id, tight.values())) | {id(c) for c in rows if c.active}
        rows = [c for c in rows if id(c) in shown]
    for c in rows:
        lines.append(f"{'*' if c.active else ' '} {c.load_case:<22} {_LABEL[c.kind]:<16} "
                     f"{c.leg or '-':<6} {_value(c.value, c.unit):>12} "
                     f"{_value(c.limit, c.unit):>12} {_value(c.margin, c.unit):>12} "
                     f"{c.multiplier:11.3g}")
    words = opt.plain_words()
    lines += ["", "active constraints and what relaxing them is worth (linear estimates):"]
    lines += [f"  - {w}" for w in words] or ["  (none: the optimum is interior)"]
    if opt.verification:
        lines += ["", "verification: every load case solved again at the optimum by "
                      "moorsolve.solve",
                  f"  {'load case':<22} {'certified':>9} {'residual N':>11} {'offset m':>9} "
                  f"{'vs NLP m':>9}  violations"]
        for v in opt.verification:
            off = "-" if v.offset_m is None else f"{v.offset_m:.4f}"
            bad = "; ".join(v.violations) or (v.reason if not v.certified else "none")
            lines.append(f"  {v.load_case:<22} {str(v.certified):>9} {v.residual_N:11.2e} "
                         f"{off:>9} {v.position_difference_m:9.1e}  {bad}")
        lines.append("verified: every constraint holds in every load case" if opt.verified
                     else "NOT VERIFIED: see the violations above")
    for note in opt.notes:
        lines.append(f"note: {note}")
    return "\n".join(lines)
