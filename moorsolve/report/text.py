"""Results out: the readable table and the JSON of ``moorsolve solve``."""

from __future__ import annotations

import json
import math

from .berth import berth_lines

# The results come from moorsolve.solve (a moorsolve.Result); they are not imported here,
# not even for annotations: Result shows itself through this package (its repr and notebook
# view), so an import back would close a cycle.


def to_json(result, profiles: bool = True) -> str:
    """The result as JSON text (the ``solve --json`` document); non-finite numbers become null."""
    return json.dumps(_finite(result.to_dict(profiles=profiles)), indent=2)


def _finite(obj):
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    return obj


def format_table(result) -> str:
    """A plain-text summary: body offset, certificate and one row per leg."""
    c = result.certificate
    lines = [f"{result.case_name}" if result.case_name else "equilibrium"]
    if result.form == "legs" and result.body is not None:
        b = result.body
        lines.append(f"body offset  x {b['x_m']:+.3f} m   y {b['y_m']:+.3f} m   "
                     f"yaw {b['yaw_deg']:+.4f} deg")
    else:
        for b in result.bodies:
            # The pose is where the body is; the offset (from the case pose) is what an
            # engineer compares with a limit, so both are given.
            off = b["offset"]
            lines.append(f"body {b['name']:<8} x {b['x_m']:+.3f} m  y {b['y_m']:+.3f} m  "
                         f"z {b['z_m']:+.3f} m  roll {b['roll_deg']:+.4f}  pitch "
                         f"{b['pitch_deg']:+.4f}  yaw {b['yaw_deg']:+.4f} deg  (offset "
                         f"{math.hypot(off['x_m'], off['y_m']):.3f} m)")
        for pt in result.points:
            lines.append(f"point {pt['name']:<7} x {pt['x_m']:+.3f} m  y {pt['y_m']:+.3f} m  "
                         f"z {pt['z_m']:+.3f} m" + (
                             f"  seabed reaction {pt['seabed_reaction_N'] / 1e3:.2f} kN"
                             if pt["seabed_reaction_N"] > 0 else ""))
    lines.append(f"certificate  force residual {c.force_N:.2e} N ({c.relative:.1e} of max "
                 f"tension), moment residual {c.moment_Nm:.2e} N m")
    lines.append(f"solver       {result.solver}: {c.status}, {c.iterations} iterations, "
                 f"{c.solve_time_s * 1e3:.1f} ms")
    lines.append("effects      " + ", ".join(result.effects))
    st = result.stability
    if st is not None and (st.dofs or not st.stable):
        text = "stable" if st.stable else "UNSTABLE in " + ", ".join(st.unstable_dofs)
        if st.neutral_dofs:
            text += f"; neutral (indifferent): {', '.join(st.neutral_dofs)}"
        lines.append(f"stability    {text} (smallest stiffness eigenvalue "
                     f"{st.min_eigenvalue:.3g})")
    for name, load in result.loads.items():
        if len(load) == 6:
            lines.append(f"load         {name:<15} F [{load[0] / 1e3:.2f}, {load[1] / 1e3:.2f}, "
                         f"{load[2] / 1e3:.2f}] kN  M [{load[3] / 1e3:.1f}, "
                         f"{load[4] / 1e3:.1f}, {load[5] / 1e3:.1f}] kN m")
            continue
        fx, fy, mz = load
        lines.append(f"load         {name:<15} Fx {fx / 1e3:10.2f} kN  Fy {fy / 1e3:10.2f} kN  "
                     f"Mz {mz / 1e3:12.1f} kN m")
    word = "leg" if result.form == "legs" else "line"
    header = (f"{word:<8}{'T_fair kN':>11}{'H kN':>10}{'V kN':>10}{'T_anch kN':>11}"
              f"{'V_anch kN':>11}{'grounded m':>12}{'T/MBL':>7}  state")
    lines += ["", header, "-" * len(header)]
    for r in leg_rows(result.legs):
        util = f"{r['t_over_mbl']:.2f}" if r["t_over_mbl"] is not None else "-"
        lines.append(
            f"{r['name']:<8}{r['T_fair'] / 1e3:11.2f}{r['H'] / 1e3:10.2f}{r['V'] / 1e3:10.2f}"
            f"{r['T_anchor'] / 1e3:11.2f}{r['V_anchor'] / 1e3:11.2f}"
            f"{r['grounded']:12.2f}{util:>7}  {r['state']}")
    lines += berth_lines(result)
    for note in result.notes:
        lines.append(f"note: {note}")
    over = [r["name"] for r in leg_rows(result.legs) if (r["t_over_mbl"] or 0) > 1]
    if over:
        lines.append(f"OVERLOAD: {', '.join(over)} above the minimum breaking load "
                     "(accepted with --allow-overload)")
    crushed = [f["name"] for f in result.fenders if f.get("overloaded")]
    if crushed:
        bearing = [f["name"] for f in result.fenders if f.get("hull_bears")]
        lines.append(f"OVERLOAD: fender {', '.join(crushed)} past the rated deflection"
                     + (f"; the hull bears on the wall behind {', '.join(bearing)}"
                        if bearing else "") + " (accepted with --allow-overload)")
    # Last, where a terminal leaves them in view (moorsolve.audit.result_warnings).
    lines += [f"WARNING: {w['message']}" for w in result.warnings]
    return "\n".join(lines)


def leg_rows(legs) -> list[dict]:
    """Per leg what the tables show: tensions [N], grounded length [m], ``t_over_mbl``
    (largest tension over MBL: not a standard's utilisation, which ``moorsolve check``
    reports) and state (``slack``, ``uplift``, ``touchdown`` or ``suspended``; ``OVER MBL``
    added when T/MBL exceeds 1)."""
    rows = []
    for leg in legs:
        state = "slack" if leg.slack else ("uplift" if leg.uplift else
                                           ("touchdown" if leg.grounded_length_m > 0
                                            else "suspended"))
        if leg.floating_length_m > 0:
            state += ", floating"
        if leg.t_over_mbl is not None and leg.t_over_mbl > 1:
            state += ", OVER MBL"
        rows.append({"name": leg.name, "T_fair": leg.fairlead_tension_N,
                     "H": leg.horizontal_tension_N, "V": leg.fairlead_vertical_N,
                     "T_anchor": leg.anchor_tension_N, "V_anchor": leg.anchor_vertical_N,
                     "grounded": leg.grounded_length_m, "t_over_mbl": leg.t_over_mbl,
                     "state": state})
    return rows


def format_stiffness(K, body, case_name: str = "", held=()) -> str:
    """The 6x6 stiffness as a labelled table (:func:`moorsolve.report.matrix.stiffness_table`:
    rows the forces Fx ... Mz, columns the displacements surge ... yaw, each with its unit;
    an entry's unit is its row's over its column's: N/m, N/rad, N m/m, N m/rad). ``held``:
    the other bodies, held at their solved poses while this one moves."""
    from .matrix import stiffness_table
    table = stiffness_table(K, ("surge", "sway", "heave", "roll", "pitch", "yaw"))
    others = (f"; {', '.join(held)} held at their solved poses, free points and lines "
              "re-equilibrating" if held else "")
    return (f"{case_name}: mooring stiffness of {body or 'the fairlead frame'} about its "
            f"solved position (K = -dF/dq, global axes{others})\n{table!r}")
