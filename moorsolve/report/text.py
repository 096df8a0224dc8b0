"""Results out: the readable table and the JSON of ``moorsolve solve``."""

from __future__ import annotations

import json
import math

from ..solve.result import Result


def to_json(result: Result, profiles: bool = True) -> str:
    """The result as JSON text (CONTRACT.md "Result"); non-finite numbers become null."""
    return json.dumps(_finite(result.to_dict(profiles=profiles)), indent=2)


def _finite(obj):
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    return obj


def format_table(result: Result) -> str:
    """A plain-text summary: body offset, certificate and one row per leg."""
    c = result.certificate
    lines = [f"{result.case_name}" if result.case_name else "equilibrium"]
    if result.body is not None:
        b = result.body
        lines.append(f"body offset  x {b['x_m']:+.3f} m   y {b['y_m']:+.3f} m   "
                     f"yaw {b['yaw_deg']:+.4f} deg")
    lines.append(f"certificate  force residual {c.force_N:.2e} N ({c.relative:.1e} of max "
                 f"tension), moment residual {c.moment_Nm:.2e} N m")
    lines.append(f"solver       {result.solver}: {c.status}, {c.iterations} iterations, "
                 f"{c.solve_time_s * 1e3:.1f} ms")
    lines.append("effects      " + ", ".join(result.effects))
    for name, (fx, fy, mz) in result.loads.items():
        lines.append(f"load         {name:<15} Fx {fx / 1e3:10.2f} kN  Fy {fy / 1e3:10.2f} kN  "
                     f"Mz {mz / 1e3:12.1f} kN m")
    header = (f"{'leg':<8}{'T_fair kN':>11}{'H kN':>10}{'V kN':>10}{'T_anch kN':>11}"
              f"{'V_anch kN':>11}{'grounded m':>12}{'util':>7}  state")
    lines += ["", header, "-" * len(header)]
    for r in leg_rows(result.legs):
        util = f"{r['utilisation']:.2f}" if r["utilisation"] is not None else "-"
        lines.append(
            f"{r['name']:<8}{r['T_fair'] / 1e3:11.2f}{r['H'] / 1e3:10.2f}{r['V'] / 1e3:10.2f}"
            f"{r['T_anchor'] / 1e3:11.2f}{r['V_anchor'] / 1e3:11.2f}"
            f"{r['grounded']:12.2f}{util:>7}  {r['state']}")
    for note in result.notes:
        lines.append(f"note: {note}")
    over = [r["name"] for r in leg_rows(result.legs) if (r["utilisation"] or 0) > 1]
    if over:
        lines.append(f"OVERLOAD: {', '.join(over)} above the minimum breaking load "
                     "(accepted with --allow-overload)")
    return "\n".join(lines)


def leg_rows(legs) -> list[dict]:
    """Per leg what the tables show: tensions [N], grounded length [m], utilisation and
    state (``slack``, ``uplift``, ``touchdown`` or ``suspended``; ``OVER MBL`` added
    when the utilisation exceeds 1)."""
    rows = []
    for leg in legs:
        state = "slack" if leg.slack else ("uplift" if leg.uplift else
                                           ("touchdown" if leg.grounded_length_m > 0
                                            else "suspended"))
        if leg.utilisation is not None and leg.utilisation > 1:
            state += ", OVER MBL"
        rows.append({"name": leg.name, "T_fair": leg.fairlead_tension_N,
                     "H": leg.horizontal_tension_N, "V": leg.fairlead_vertical_N,
                     "T_anchor": leg.anchor_tension_N, "V_anchor": leg.anchor_vertical_N,
                     "grounded": leg.grounded_length_m, "utilisation": leg.utilisation,
                     "state": state})
    return rows
