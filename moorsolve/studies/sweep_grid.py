"""A sweep's grid: axes of case-file edits, their columns in SI, and the walk through them."""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import CaseError
from ..model import Case
from ..model.paths import concrete_paths
from ..model.units import KINDS
from ..solve.assembly.prepared import parameter_vector


def _edits(paths: tuple, value) -> dict:
    if len(paths) == 1:
        return {paths[0]: value}
    return dict(zip(paths, value))


def _component(paths, value, j):
    return value if len(paths) == 1 else value[j]


def _label(paths: tuple) -> str:
    return paths[0] if len(paths) == 1 else ",".join(paths)


class _GridColumn:
    """One grid column: its name and its value for each value of the axis."""

    def __init__(self, name: str, values: list, numeric: bool):
        self.name, self.values, self.numeric = name, values, numeric

    def file_cells(self, cells: list) -> list:
        if self.numeric:
            return [float(v) for v in cells]
        return [v if isinstance(v, str) else json.dumps(_plain(v)) for v in cells]


def _unit(kind: str) -> str:
    return KINDS[kind][1] or "-"


def _grid_columns(source, paths: tuple, values: list, quantities: list) -> list:
    """The columns of one axis from the quantities each value converted to SI.

    A path whose every value is one quantity is one column ``PATH [unit]``; a list of
    quantities (``anchor``, ``body.loads.force``) one column per item, ``PATH[i] [unit]``
    (NaN where a value is shorter); anything else (a name, a list of names) one text
    column ``PATH`` with the values as given.
    """
    out = []
    for j, path in enumerate(paths):
        found = concrete_paths(source, path)
        field = found[0] if found else path
        scalars = [q.get(field) for q in quantities]
        if all(item is not None for item in scalars):
            out.append(_GridColumn(f"{path} [{_unit(scalars[0][1])}]",
                                   [item[0] for item in scalars], True))
            continue
        items = [_items(q, field) for q in quantities]
        width = max(len(row) for row in items)
        if width and all(items):
            for i in range(width):
                kind = next(row[i][1] for row in items if len(row) > i)
                out.append(_GridColumn(f"{path}[{i}] [{_unit(kind)}]",
                                       [row[i][0] if len(row) > i else math.nan
                                        for row in items], True))
            continue
        out.append(_GridColumn(path, [_component(paths, v, j) for v in values], all(
            _numeric(_component(paths, v, j)) for v in values)))
    return out


def _items(quantities: dict, field: str) -> list:
    """``[(value, kind), ...]`` of ``field[0]``, ``field[1]``, ... while recorded."""
    out = []
    while f"{field}[{len(out)}]" in quantities:
        out.append(quantities[f"{field}[{len(out)}]"])
    return out


def _numeric(v) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


def _plain(obj):
    """Case-file data as JSON-able plain data (numpy scalars and arrays included)."""
    if isinstance(obj, Mapping):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, np.ndarray)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        return float(obj)
    if isinstance(obj, (str, int, float, bool)) or obj is None:
        return obj
    return str(obj)


def _plain_grid(grid: Mapping) -> list:
    out = []
    for key, values in grid.items():
        tag = ["zip", list(key)] if isinstance(key, tuple) else ["path", key]
        out.append([tag, _plain(list(values))])
    return out


def _sha(obj) -> str:
    try:
        # Data that is plain already (a load table's cells) needs no walk through
        # _plain, which costs seconds on 100,000 rows; the text is the same.
        text = json.dumps(obj, sort_keys=True, separators=(",", ":"))
    except (TypeError, ValueError):
        text = json.dumps(_plain(obj), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def _axes(grid) -> list[tuple[tuple, list]]:
    from ..model.paths import parse_path

    if not isinstance(grid, Mapping) or not grid:
        raise CaseError("grid", "must be a non-empty mapping of case paths to lists of values")
    axes, seen = [], set()
    for key, values in grid.items():
        paths = tuple(key) if isinstance(key, tuple) else (key,)
        label = f"grid[{_label(paths)!r}]"
        if not paths:
            raise CaseError("grid", "an empty tuple of paths")
        for path in paths:
            parse_path(path)
            if path in seen:
                raise CaseError(label, f"path {path!r} appears on more than one axis")
            seen.add(path)
        if isinstance(values, (str, bytes, Mapping)) or not isinstance(
                values, (Sequence, np.ndarray, range)):
            raise CaseError(label, f"{values!r} must be a list of values")
        values = list(values.tolist() if isinstance(values, np.ndarray) else values)
        if not values:
            raise CaseError(label, "the list of values is empty")
        if isinstance(key, tuple):
            for v in values:
                if isinstance(v, (str, bytes, Mapping)) or not isinstance(v, Sequence) \
                        or len(v) != len(paths):
                    raise CaseError(label, f"value {v!r} must be a tuple of {len(paths)} "
                                           f"values, one per path")
            if len(paths) == 1:
                values = [v[0] for v in values]
        axes.append((paths, values))
    return axes


def _point_vector(case: Case) -> np.ndarray:
    """Everything a point may change without changing the problem: the solver's
    parameters, then each leg's minimum breaking load and each fender's and guide's
    reaction limit (for the overload check)."""
    mbl = [leg.line_type.mbl if leg.line_type.mbl is not None else np.inf
           for leg in case.legs]
    return np.concatenate([parameter_vector(case, 1.0), mbl, rated_reactions(case)])


def rated_reactions(case: Case) -> list:
    """Per fender, then per guide, the reaction [N] past which it is overloaded: a fender's
    at its rated deflection (its reaction rises strictly with compression, so a reaction
    above it is a compression past the rating); infinite for a rigid fender and a guide."""
    from ..physics.contact import fender_reaction
    out = []
    for fender in case.contacts.fenders:
        law = fender.law
        out.append(np.inf if law.kind == "rigid" or fender.rated_deflection is None
                   else float(fender_reaction(fender.rated_deflection, *law.curve)))
    return out + [np.inf] * len(case.contacts.guides)


def snake_order(shape: tuple[int, ...]) -> list[tuple[int, ...]]:
    """Every index of ``shape`` once, consecutive ones differing in one index by one
    (a reflected mixed-radix Gray code), so each point warm-starts from a neighbour."""
    if not shape:
        return [()]
    inner = snake_order(shape[1:])
    out = []
    for i in range(shape[0]):
        for rest in (inner if i % 2 == 0 else inner[::-1]):
            out.append((i, *rest))
    return out




def axis_columns(paths: tuple, values: list) -> dict | None:
    """A grid axis as load-table columns (:mod:`.load_table`), so that it is validated by
    column, not value by value: a path whose every value is a number is one column
    ``PATH``; a path whose every value is a list of numbers of one length is one column per
    item, ``PATH[i]``. None when a value is anything else (a string with a unit, a name),
    which is validated as a case of its own."""
    table = {}
    for j, path in enumerate(paths):
        items = [_component(paths, v, j) for v in values]
        if all(_numeric(c) for c in items):
            table[path] = items
        elif (all(isinstance(c, (list, tuple)) for c in items) and items[0]
              and len({len(c) for c in items}) == 1
              and all(_numeric(x) for c in items for x in c)):
            for i in range(len(items[0])):
                table[f"{path}[{i}]"] = [c[i] for c in items]
        else:
            return None
    return table


def axis_quantities(source, paths: tuple, values: list, probe: dict) -> list | None:
    """Per value of an axis of numbers (:func:`axis_columns`), what validating it converts
    to SI (``{field: (value, kind)}``, as :func:`moorsolve.model.units.recording` gives
    it), from what validating its first value recorded (``probe``): a plain number is SI,
    so each value is its own SI value in the kind the probe found. None when the probe
    did not record every number as given (a field that reads numbers otherwise)."""
    first = values[0]
    fields = []
    for j, path in enumerate(paths):
        found = concrete_paths(source, path)
        field = found[0] if found else path
        item = _component(paths, first, j)
        if _numeric(item):
            got = probe.get(field)
            if got is None or got[0] != float(item):
                return None
            fields.append((j, None, field, got[1]))
        else:
            for i, x in enumerate(item):
                got = probe.get(f"{field}[{i}]")
                if got is None or got[0] != float(x):
                    return None
                fields.append((j, i, f"{field}[{i}]", got[1]))
    out = []
    for v in values:
        q = {}
        for j, i, field, kind in fields:
            item = _component(paths, v, j)
            q[field] = (float(item if i is None else item[i]), kind)
        out.append(q)
    return out
