"""Results in a notebook or a console: a one-line ``repr`` and HTML tables.

The result classes keep only one-line hooks (``__repr__`` and ``_repr_html_`` calling the
functions here): what a Result, a check report or an envelope looks like is decided in
one place, beside the text tables and the HTML report.
"""

from __future__ import annotations

import html
import math

from .text import leg_rows

__all__ = ["result_repr", "leg_repr", "result_html", "check_html_table", "envelope_html",
           "html_table"]


def _num(value, fmt: str) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return format(value, fmt)


def result_repr(result) -> str:
    """One line: the case, the certificate, the body and the worst leg."""
    c = result.certificate
    parts = [f"Result {result.case_name!r}" if result.case_name else "Result",
             f"{'certified' if result.converged else 'NOT certified'} "
             f"{c.force_N:.2g} N ({c.relative:.1e}) by {result.solver}, "
             f"{c.iterations} iterations"]
    bodies = getattr(result, "bodies", None) or ()
    if len(bodies) > 1:
        far = max(bodies, key=lambda b: math.hypot(b["offset"]["x_m"], b["offset"]["y_m"]))
        parts.append(f"{len(bodies)} bodies, largest offset "
                     f"{math.hypot(far['offset']['x_m'], far['offset']['y_m']):.3f} m "
                     f"({far['name']})")
    elif result.body is not None:
        b = result.body
        parts.append(f"body x {b['x_m']:+.3f} m y {b['y_m']:+.3f} m "
                     f"yaw {b['yaw_deg']:+.3f} deg")
    if result.legs:
        worst = max(result.legs, key=lambda leg: max(leg.fairlead_tension_N,
                                                     leg.anchor_tension_N))
        util = "" if worst.t_over_mbl is None else f", T/MBL {worst.t_over_mbl:.2f}"
        word = "legs" if getattr(result, "form", "legs") == "legs" else "lines"
        parts.append(f"{len(result.legs)} {word}, worst {worst.name} "
                     f"{max(worst.fairlead_tension_N, worst.anchor_tension_N) / 1e3:,.1f} kN"
                     f"{util}")
    return "<" + "; ".join(parts) + ">"


def leg_repr(leg) -> str:
    """One line per leg: tensions, state and T/MBL."""
    row = leg_rows([leg])[0]
    util = "" if leg.t_over_mbl is None else f", T/MBL {leg.t_over_mbl:.2f}"
    return (f"<LegResult {leg.name}: fairlead {leg.fairlead_tension_N / 1e3:,.1f} kN, "
            f"anchor {leg.anchor_tension_N / 1e3:,.1f} kN, {row['state']}{util}>")


def html_table(header: list, rows: list, caption: str = "", left: int = 1) -> str:
    """A plain HTML table; ``rows`` are lists of cells or ``(cells, css class)``."""
    out = ["<table>"]
    if caption:
        out.append(f"<caption>{html.escape(caption)}</caption>")
    out.append("<tr>" + "".join(
        f'<th style="text-align:{"left" if i < left else "right"}">{html.escape(str(h))}</th>'
        for i, h in enumerate(header)) + "</tr>")
    for row in rows:
        cells, cls = row if isinstance(row, tuple) else (row, "")
        style = ' style="background:#f8d0d0"' if cls == "fail" else ""
        out.append(f"<tr{style}>" + "".join(
            f'<td style="text-align:{"left" if i < left else "right"}">{html.escape(str(c))}'
            "</td>" for i, c in enumerate(cells)) + "</tr>")
    out.append("</table>")
    return "".join(out)


def result_html(result) -> str:
    """The equilibrium as two HTML tables: summary, then one row per leg."""
    c = result.certificate
    summary = [["certificate", f"force residual {c.force_N:.3g} N ({c.relative:.2e} of the "
                               f"largest tension; tolerance {c.tolerance:.0e}), moment "
                               f"{c.moment_Nm:.3g} N m"],
               ["solver", f"{result.solver}: {c.status}, {c.iterations} iterations, "
                          f"{c.solve_time_s * 1e3:.1f} ms"],
               ["effects", ", ".join(result.effects)]]
    for pose in reversed(getattr(result, "bodies", None) or ()):
        o = pose.get("offset", pose)
        summary.insert(0, [f"{pose['name']} offset",
                           f"x {o['x_m']:+.4f} m, y {o['y_m']:+.4f} m, z {o['z_m']:+.4f} m, "
                           f"roll {o['roll_deg']:+.4f}, pitch {o['pitch_deg']:+.4f}, "
                           f"yaw {o['yaw_deg']:+.4f} deg"])
    for point in getattr(result, "points", None) or ():
        summary.append([f"point {point['name']}", f"x {point['x_m']:+.3f} m, "
                                                  f"y {point['y_m']:+.3f} m, "
                                                  f"z {point['z_m']:+.3f} m"])
    for name, load in result.loads.items():
        # A legs-form load is (Fx, Fy, Mz); a network body's is the full 6-vector.
        fx, fy, mz = (load[0], load[1], load[2]) if len(load) == 3 else (load[0], load[1],
                                                                          load[5])
        text = f"Fx {fx / 1e3:,.2f} kN, Fy {fy / 1e3:,.2f} kN, Mz {mz / 1e3:,.1f} kN m"
        if len(load) == 6:
            text += (f" (Fz {load[2] / 1e3:,.2f} kN, Mx {load[3] / 1e3:,.1f} kN m, "
                     f"My {load[4] / 1e3:,.1f} kN m)")
        summary.append([f"load: {name}", text])
    summary += [["note", note] for note in result.notes]
    legs = [([r["name"], _num(r["T_fair"] / 1e3, ",.2f"), _num(r["H"] / 1e3, ",.2f"),
              _num(r["V"] / 1e3, ",.2f"), _num(r["T_anchor"] / 1e3, ",.2f"),
              _num(r["V_anchor"] / 1e3, ",.2f"), _num(r["grounded"], ".2f"),
              _num(r["t_over_mbl"], ".3f"), r["state"]],
             "fail" if (r["t_over_mbl"] or 0) > 1 else "")
            for r in leg_rows(result.legs)]
    title = result.case_name or "equilibrium"
    return (f"<div><b>{html.escape(title)}</b>"
            + html_table(["", ""], summary)
            + html_table(["leg", "T fairlead [kN]", "H [kN]", "V [kN]", "T anchor [kN]",
                          "V anchor [kN]", "grounded [m]", "T/MBL", "state"], legs)
            + "</div>")


def check_html_table(report) -> str:
    """A check report as one HTML table: each condition's worst values and verdict."""
    from .check_html import summary_table
    header, rows = summary_table(report)
    verdict = "PASS" if report.passed else "FAIL"
    caption = (f"Mooring check of {report.case_name} under {report.standard}: {verdict}, "
               f"{sum(c.passed for c in report.conditions)} of {len(report.conditions)} "
               "conditions pass")
    lost = [f"{c.name}: {d['message']}" for c in report.conditions for d in c.drifting]
    notes = [f"Line tension: {report.method}."] + [f"{n}." for n in report.notes]
    return html_table(header, rows, caption) + "".join(
        f'<p style="background:#f8d0d0">LOST: {html.escape(text)}</p>' for text in lost) + \
        "".join(f"<p>{html.escape(text)}</p>" for text in notes)


def envelope_html(envelope) -> str:
    """An offset envelope as an HTML table, one row per heading."""
    e = envelope
    rows = []
    for i in range(len(e.heading_deg)):
        h = e.file_heading(i)
        if not math.isfinite(e.worst_tension_N[i]):
            rows.append(([f"{h:g}", "-", "-", "-", "-", "-", e.reason[i]], "fail"))
            continue
        rows.append(([f"{h:g}", f"{e.offset_m[i]:.3f}", f"{e.file_direction(i):.1f}",
                      f"{e.yaw_deg[i]:.3f}", e.worst_leg[i],
                      f"{e.worst_tension_N[i] / 1e3:,.1f}", e.reason[i]],
                     "" if e.converged[i] else "fail"))
    direction = "bearing [deg]" if e.compass.nautical else "direction [deg]"
    return html_table([e.heading_label(), "offset [m]", direction, "yaw [deg]",
                       "worst leg", "worst tension [kN]", "note"], rows,
                      f"offset envelope of {e.case_name} ({', '.join(e.flows)} turned)")
