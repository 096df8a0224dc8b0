"""Where the mooring force is continuous but its derivative is not: a weightless elastic line
exactly at its slack point, a fender or guide pad exactly at first contact. Found from a
Result, so that the derived quantities can give both one-sided limits or say that theirs
is neither (:mod:`.one_sided`, :mod:`.stiffness`).
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from ..errors import MoorsolveWarning
from ..model import Case

#: A weightless elastic line whose chord is within this fraction of its length of its
#: unstretched length is at its slack point.
AT_SLACK_POINT = 1e-6
#: Strain [-] of a line drawn taut to evaluate the taut side's limit.
TAUT_STRAIN = 1e-7


def lines_at_slack_point(result) -> tuple:
    """Names of the one-segment weightless elastic lines of ``result`` (Hooke or another
    stretch law) at their slack point (chord and unstretched length equal to
    :data:`AT_SLACK_POINT` of the length). An inextensible one is a constraint when taut,
    not a spring: it is not among them."""
    names = []
    for line, leg in zip(result.case.lines, result.legs):
        kind = line.line_type
        if line.multi_segment or kind.weight_in_water != 0 \
                or (kind.ea is None and kind.stretch is None):
            continue
        chord = float(np.linalg.norm(np.subtract(leg.fairlead, leg.anchor)))
        if abs(chord - line.length) <= AT_SLACK_POINT * line.length:
            names.append(line.name)
    return tuple(names)


def with_lines(case: Case, names, *, taut: bool) -> Case:
    """``case`` with the lines ``names`` drawn taut (their unstretched length shortened by
    the fraction :data:`TAUT_STRAIN`: at their slack point that is a strain of it) or
    removed (slack)."""
    names = set(names)
    if not taut:
        return dataclasses.replace(case, lines=tuple(ln for ln in case.lines
                                                     if ln.name not in names))
    lines = []
    for line in case.lines:
        if line.name in names:
            seg = line.segments[0]
            seg = dataclasses.replace(seg, length=seg.length / (1 + TAUT_STRAIN))
            line = dataclasses.replace(line, segments=(seg,))
        lines.append(line)
    return dataclasses.replace(case, lines=tuple(lines))


def contacts_at_first_contact(result) -> tuple:
    """Names of the fenders and guide pads of ``result`` exactly at first contact: touching
    (opening within :data:`AT_SLACK_POINT` of the scene's length scale) with no reaction
    (within that fraction of its force scale). Closing them adds their stiffness, opening
    them nothing: the tangent stiffness differs on the two sides there."""
    from ..solve.lines.bathymetry import result_parameters
    from ..solve.assembly.cache import get_problem
    from ..solve.contact.blocks import CONTACT_COLUMNS

    problem = get_problem(result.case)
    if not getattr(problem, "contacts", None):
        return ()
    table = np.atleast_2d(np.asarray(problem.contact_report(
        result.state, result_parameters(problem, result)), dtype=float))
    opening, reaction = CONTACT_COLUMNS.index("opening"), CONTACT_COLUMNS.index("reaction")
    return tuple(point.name for point, row in zip(problem.contacts, table)
                 if abs(row[opening]) <= AT_SLACK_POINT * problem.length_scale
                 and abs(row[reaction]) <= AT_SLACK_POINT * problem.force_scale)


def warn_one_sided(names) -> None:
    warnings.warn(
        f"line(s) {', '.join(names)} at their slack point (chord = unstretched length): "
        "the stiffness differs on the two sides; this is the taut side's "
        "(moorsolve.one_sided_stiffness gives both)", MoorsolveWarning, stacklevel=3)
