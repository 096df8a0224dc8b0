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
    for leg in result.legs:
        state = "slack" if leg.slack else ("uplift" if leg.uplift else
                                           ("touchdown" if leg.grounded_length_m > 0
                                            else "suspended"))
        if leg.floating_length_m > 0:
            state += ", floating"
        util = f"{leg.utilisation:.2f}" if leg.utilisation is not None else "-"
        lines.append(
            f"{leg.name:<8}{leg.fairlead_tension_N / 1e3:11.2f}"
            f"{leg.horizontal_tension_N / 1e3:10.2f}{leg.fairlead_vertical_N / 1e3:10.2f}"
            f"{leg.anchor_tension_N / 1e3:11.2f}{leg.anchor_vertical_N / 1e3:11.2f}"
            f"{leg.grounded_length_m:12.2f}{util:>7}  {state}")
    for note in result.notes:
        lines.append(f"note: {note}")
    # Last, where a terminal leaves them in view.
    lines += [f"WARNING: {w['message']}" for w in result.warnings]
    return "\n".join(lines)
