"""Edits of a validated scene made on the model itself (never through file text).

A damaged condition removes one line: :func:`without_line`. The case keeps its form; its
case-file data (``source``) no longer matches and is dropped.
"""

from __future__ import annotations

import dataclasses

from .scene import Case


def without_line(case: Case, name: str) -> Case:
    """``case`` with the line ``name`` removed.

    A free point that no remaining line holds is removed with it (nothing would hold it: a
    bridle apex whose last leg broke), and so is every line that then only joins removed
    points. Raises KeyError for an unknown line.
    """
    if name not in {line.name for line in case.lines}:
        raise KeyError(name)
    lines = [line for line in case.lines if line.name != name]
    points = list(case.points)
    while True:
        attached = {end.point for line in lines for end in (line.a, line.b) if end.point}
        orphans = {p.name for p in points if p.free and p.name not in attached}
        if not orphans:
            break
        points = [p for p in points if p.name not in orphans]
        lines = [line for line in lines
                 if not ({line.a.point, line.b.point} & orphans)]
    return dataclasses.replace(case, lines=tuple(lines), points=tuple(points), source=None)
