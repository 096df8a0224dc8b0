"""The motions of a scene's bodies as a text table."""

from __future__ import annotations

import math


def format_motions(m) -> str:
    """Text of :class:`moorsolve.dynamics.motions.Motions`: the sea state, what was
    simulated, and per body and DOF the mean, WF and LF statistics and the design offset."""
    sea = m.sea
    out = []
    if "hs_m" in sea:
        spec = sea["spectrum"] + (f" (gamma {sea['gamma']:.3g})" if "gamma" in sea else "")
        tp = f"Tp {sea['tp_s']:.3g} s, " if sea.get("tp_s") else ""
        out.append(f"sea state: {spec}, Hs {sea['hs_m']:.3g} m, {tp}toward "
                   f"{sea['toward_deg']:.4g} deg, {sea['duration_s'] / 3600:.3g} h")
    if m.static:
        out.append(f"static answer only: {sea['reason']}")
        return "\n".join(out)
    out.append("simulated: " + ", ".join(s.replace("_", " ") for s in sea["simulated"])
               + f"; the tables' frequencies hold {sea['coverage']:.1%} of m0")
    for b in m.bodies:
        out.append("")
        out.append(f"body {b.name} (waves at {b.heading_deg:.4g} deg to its x axis)")
        out.append(f"  {'dof':<6} {'unit':>4} {'mean':>10} {'WF sig':>9} {'WF Tz s':>8} "
                   f"{'WF max':>9} {'LF sig':>9} {'LF Tz s':>8} {'LF max':>9}")
        for k, dof in enumerate(b.dofs):
            unit = "deg" if dof in ("roll", "pitch", "yaw") else "m"
            tz = [s["tz_s"][k] for s in (b.wf, b.lf)]
            tzs = ["-" if not math.isfinite(t) else f"{t:.1f}" for t in tz]
            out.append(f"  {dof:<6} {unit:>4} {b.mean[k]:>10.4g} {b.wf['sigma'][k]:>9.3g} "
                       f"{tzs[0]:>8} {b.wf['max'][k]:>9.3g} {b.lf['sigma'][k]:>9.3g} "
                       f"{tzs[1]:>8} {b.lf['max'][k]:>9.3g}")
        if b.design_offset_m is not None:
            out.append(f"  design offset (API RP 2SK): {b.design_offset_m:.3f} m")
        if any(b.mean_drift):
            f = b.mean_drift
            out.append(f"  mean drift force: {math.hypot(f[0], f[1]) / 1e3:.3g} kN "
                       f"horizontal (in the static loads)")
    return "\n".join(out)
