"""Edits of a validated scene made on the model itself (never through file text).

A damaged condition removes one line: :func:`without_line`. The case keeps its form; its
case-file data (``source``) no longer matches and is dropped.

A sweep point, a load case or a design sets values by dotted path (:mod:`.paths`) in the
case-file data the case was validated from, and validates the edited data again as a case
(:func:`with_values`, :meth:`Case.with_values <moorsolve.model.scene.Case.with_values>`;
:func:`variant` names the study field at fault). No file is read: a bathymetry grid the
case read from a file is the grid it holds.
"""

from __future__ import annotations

import copy
import dataclasses
import warnings
from collections.abc import Mapping

from ..errors import CaseError, UnusedInputWarning
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


def with_values(case: Case, assignments: Mapping, *, keep_source: bool = True) -> Case:
    """``case`` with each ``path: value`` of ``assignments`` set in its case-file data
    (:func:`moorsolve.model.paths.with_values`) and validated again, as
    :func:`moorsolve.load_case` validates a case file.

    Parameters
    ----------
    case : Case
        A case with its case-file data (``source``: from :func:`moorsolve.load_case`).
    assignments : mapping
        Dotted case paths to values (a value may carry a unit: ``"150 m"``).
    keep_source : bool
        Keep the edited data as the new case's ``source`` and warn about inputs no model
        uses (as ``load_case`` does); a caller validating many throw-away variants skips
        both.

    Raises
    ------
    CaseError
        The case has no case-file data, or the edited data is not a valid case (naming the
        field). An edit may not name another bathymetry file (a file is read by
        ``load_case``, relative to its case file).
    """
    from .paths import with_values as set_values

    if case.source is None:
        raise CaseError("case", "edits need the case-file data; load the case with "
                                "moorsolve.load_case (from a file or a dict)")
    data = set_values(case.source, assignments)
    # ``data`` is this function's own: the edited path copied, the rest shared with
    # case.source, which nothing edits; so it is kept without a copy.
    return build_with_source(_with_grid(data, case), data, "case", keep_source, stacklevel=4,
                             private=True)


def build_with_source(built: Mapping, data: Mapping, default_name: str, keep_source: bool,
                      stacklevel: int, private: bool = False) -> Case:
    """The Case of the case-file data ``built``, keeping ``data`` (the same data as the user
    wrote it; a copy unless ``private``, data no caller holds) as its source and warning of
    every input no model uses (at ``stacklevel``, counted from this function), as load_case
    and edits both do."""
    from .build import build_case
    from .usage import unused_inputs

    try:
        case = build_case(built, default_name)
    except RecursionError:
        # A self-referencing or absurdly nested dict: bad input, not a crash.
        raise CaseError("", "the case is nested too deeply") from None
    if not keep_source:
        return case
    source = dict(data) if private else plain_copy(dict(data))
    source["name"] = case.name
    case = dataclasses.replace(case, source=source)
    for field, message in unused_inputs(case):
        warnings.warn(UnusedInputWarning(field, message), stacklevel=stacklevel)
    return case


def plain_copy(data):
    """A deep copy of case-file data: dicts, lists and scalars copied by hand (a few
    times faster than :func:`copy.deepcopy`, which a loop of ``load_case`` paid at every
    case), anything else by :func:`copy.deepcopy`."""
    if isinstance(data, dict):
        return {k: plain_copy(v) for k, v in data.items()}
    if isinstance(data, list):
        return [plain_copy(v) for v in data]
    if isinstance(data, (str, int, float, bool)) or data is None:
        return data
    return copy.deepcopy(data)


def variant(case: Case, edits: Mapping, path: str = "set") -> Case:
    """``case`` with the case-file ``edits`` (dotted path -> value) applied and validated;
    a failure is reported under the study field ``path`` (``load_cases[1].set``)."""
    if not edits:
        return case
    if case.source is None:
        raise CaseError(path, "edits need the case-file data; load the case with "
                              "moorsolve.load_case (from a file or a dict)")
    try:
        return with_values(case, edits)
    except CaseError as exc:
        raise CaseError(f"{path}: {exc.field}" if exc.field else path, exc.detail) from None


def inline_source(case: Case) -> Mapping:
    """``case``'s case-file data with the bathymetry file it names replaced by the grid
    read from it: plain data from which :func:`from_source` rebuilds the case anywhere (a
    sweep's worker process) without reading a file."""
    if case.source is None:
        raise CaseError("case", "the case has no case-file data; load the case with "
                                "moorsolve.load_case (from a file or a dict)")
    return _with_grid(case.source, case)


def from_source(data: Mapping) -> Case:
    """The case validated from case-file ``data`` that names no file (as
    :func:`inline_source` gives it), keeping ``data`` as its ``source``."""
    from .build import build_case

    case = build_case(data, "case")
    source = copy.deepcopy(dict(data))
    source["name"] = case.name
    return dataclasses.replace(case, source=source)


def _with_grid(data, case: Case):
    """``data`` with the bathymetry file it names replaced by the grid ``case`` read from
    it (``data`` itself when it names no file)."""
    env = data.get("environment") if isinstance(data, Mapping) else None
    seabed = env.get("seabed") if isinstance(env, Mapping) else None
    name = seabed.get("bathymetry") if isinstance(seabed, Mapping) else None
    if not isinstance(name, str):
        return data
    grid = case.environment.seabed.bathymetry
    before = (case.source.get("environment", {}).get("seabed", {}) or {}).get("bathymetry")
    if grid is None or name != before:
        raise CaseError("environment.seabed.bathymetry",
                        f"file {name!r} is read by moorsolve.load_case (relative to its "
                        "case file), not by an edit of a loaded case")
    read = {"x": list(grid.x), "y": list(grid.y), "depth": [list(r) for r in grid.depth],
            "source": grid.source}
    return {**data, "environment": {**env, "seabed": {**seabed, "bathymetry": read}}}
