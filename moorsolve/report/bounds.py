"""The upper- and lower-bound stiffness analysis as plain text (``moorsolve bounds``)."""

from __future__ import annotations

__all__ = ["format_bounds"]


def _stiffness(info: dict) -> str:
    if "law" in info:
        return info["law"]
    text = f"EA {info['ea_N'] / 1e6:.1f} MN"
    if "mean_load_N" in info:
        text += (f" (dynamic: {info['alpha']:.4g} + {info['beta']:.4g} x "
                 f"{info['mean_load_pct_mbl']:.1f} % MBL mean load)")
    return text


def format_bounds(bounds) -> str:
    """A :class:`~moorsolve.studies.bounds.BoundsResult` as a table and the verdict."""
    lines = [f"Stiffness bounds: {bounds.case_name}", ""]
    for s in bounds.solutions:
        for name, info in s.stiffness.items():
            lines.append(f"{s.bound:<6} {name}: {_stiffness(info)}")
    legs = [leg.name for leg in bounds.lower.result.legs]
    header = f"{'bound':<7}{'offset m':>10}{'yaw deg':>9}" + "".join(
        f"{name + ' kN':>12}" for name in legs)
    lines += ["", header, "-" * len(header)]
    for s in bounds.solutions:
        body = s.result.body
        yaw = f"{body['yaw_deg']:9.3f}" if body else f"{'-':>9}"
        tensions = "".join(f"{max(leg.fairlead_tension_N, leg.anchor_tension_N) / 1e3:12.1f}"
                           for leg in s.result.legs)
        lines.append(f"{s.bound:<7}{s.offset_m:10.3f}{yaw}{tensions}")
    off, ten = bounds.governing_offset, bounds.governing_tension
    T, leg = ten.max_tension
    lines += ["", f"worst offset   {off.offset_m:.3f} m with the {off.bound} bound",
              f"worst tension  {T / 1e3:.1f} kN in leg {leg} with the {ten.bound} bound"]
    for s in bounds.solutions:
        lines += [f"note ({s.bound}): {note}" for note in s.result.notes]
    return "\n".join(lines)
