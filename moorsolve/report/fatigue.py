"""The fatigue check as a text table."""

from __future__ import annotations

__all__ = ["fatigue_text"]


def fatigue_text(fr) -> str:
    """A :class:`moorsolve.life.fatigue.FatigueResult` as a table: per line end the damage
    over the design life, the life in years and ``DFF x D`` against 1."""
    life = fr.design_life_y
    source = ("tension records counted by rainflow, scaled to the design life"
              if fr.method == "rainflow" else f"{len(fr.sea_states)} sea states")
    lines = [f"Fatigue ({fr.method.replace('_', ' ')}): design life {life:.4g} y, "
             f"{source}, design fatigue factor "
             f"{fr.design_fatigue_factor:g} (the adjacent-line rule is not applied)"]
    if fr.method != "rainflow":
        lines.append("  wave-frequency tension only: the slow-drift tension and each sea "
                     "state's mean offset are not simulated")
    lines.append(f"  {'line':<10} {'end':<9} {'curve':<18} {'mean kN':>9} {'damage':>10} "
                 f"{'life y':>10} {'DFF x D':>8}  result")
    for e in fr.ends:
        life_y = "inf" if e.life_y == float("inf") else f"{e.life_y:10.4g}"
        lines.append(f"  {e.line:<10} {e.end:<9} {e.curve.name:<18} {e.mean_N / 1e3:9.1f} "
                     f"{e.damage:10.3e} {life_y:>10} {e.utilisation:8.3f}  "
                     f"{'pass' if e.passed else 'FAIL'}")
    for c in fr.curves:
        lines.append(f"  curve {c.name}: N = {c.a_d:.4g} S^-{c.m:g} ({c.basis}); {c.source}")
    return "\n".join(lines)
