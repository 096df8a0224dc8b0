"""The berth's rows of the text table: fenders, pile guides and the contacts' certificate. Kept apart from :mod:`.text` so that the table's layout and the berth's rows
change independently."""

from __future__ import annotations


def _table(header: str, rows: list) -> list:
    return ["", header, "-" * len(header)] + rows


def _fender_row(f: dict) -> str:
    util = "-" if f["utilisation"] is None else f"{f['utilisation']:.2f}"
    state = ("open" if not f["in_contact"] else
             "stick" if f["stick"] else "slip" if f["stick"] is False else "closed")
    if f.get("overloaded"):
        state += ", OVER RATED"
    if f.get("hull_bears"):
        state += f", HULL ON {f['bears_on']} {f['hull_reaction_N'] / 1e3:.1f} kN"
    return (f"{f['name']:<10}{'yes' if f['in_contact'] else 'no':>8}"
            f"{f['compression_m']:10.4f}{f['reaction_N'] / 1e3:10.2f}"
            f"{f['friction_N'] / 1e3:13.2f}{f['energy_J'] / 1e3:11.2f}{util:>7}  {state}")


def _guide_row(g: dict) -> str:
    on = "on" if g["on_pile"] else "OFF the top of"
    return (f"{g['name']:<10}{'yes' if g['in_contact'] else 'no':>8}"
            f"{g['reaction_N'] / 1e3:10.2f}{g['offset_m']:10.4f}{g['height_m']:10.3f}"
            f"{g['pile_moment_Nm'] / 1e3:13.1f}  {on} {g['pile']}")


def berth_lines(result) -> list:
    """Text rows for the fenders and pile guides of ``result`` (a
    :class:`moorsolve.Result`; none without them)."""
    c = result.certificate
    lines = []
    if c.penetration_m is not None:
        lines.append(f"contacts     largest penetration {c.penetration_m:.2e} m, "
                     f"complementarity residual {c.complementarity_N:.2e} N")
    if result.fenders:
        lines += _table(f"{'fender':<10}{'contact':>8}{'compr. m':>10}{'R kN':>10}"
                        f"{'friction kN':>13}{'energy kJ':>11}{'util':>7}  state",
                        [_fender_row(f) for f in result.fenders])
    if result.guides:
        lines += _table(f"{'guide':<10}{'contact':>8}{'R kN':>10}{'offset m':>10}"
                        f"{'height m':>10}{'pile M kN m':>13}  pile",
                        [_guide_row(g) for g in result.guides])
    return lines




def berth_check_lines(report, width: int = 22) -> list:
    """Per condition of a check report, the worst hawser (against MEG4's working load
    limit), fender (against its rated deflection) and pile guide (against its pile's top);
    none without them. ``width`` is the condition column's, as in the table above."""
    lines = []
    for c in report.conditions:
        worst = [(c.worst(check), what) for check, what in (
            ("hawser tension", "hawser"), ("fender compression", "fender"),
            ("guide on pile", "guide"))]
        parts = [f"{what} {item.leg} {_show(item)} (util {item.utilisation:.2f}"
                 f"{'' if item.passed else ', FAIL'})" for item, what in worst if item]
        if parts:
            lines.append(f"{c.name:<{width}}  " + "; ".join(parts))
    return ["", "berth (worst per condition)"] + lines if lines else []


def _show(item) -> str:
    return f"{item.value / 1e3:.1f} kN" if item.unit == "N" else f"{item.value:.3f} {item.unit}"


__all__ = ["berth_lines", "berth_check_lines"]
