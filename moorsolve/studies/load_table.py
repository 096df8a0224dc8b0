"""Load tables: one row per load case, one column per case path, validated by column.

A load table is what an engineer's spreadsheet of load cases is: each row a load case,
each column a quantity named by its case path (:mod:`moorsolve.model.paths`), with an
optional unit in brackets: ``environment.wind.speed [kn]``,
``environment.wind.toward_deg``, ``body.loads.force[0] [kN]``,
``bodies[hull].loads.force[5] [kN m]``. A cell is a number in the header's unit (SI
without one), or a case-file value such as ``"20 kn"`` in a column without a unit.

Validating every row as a case file costs about a millisecond a row, more than solving it.
So the table is validated *by column*, through the parameter layout
(:mod:`moorsolve.solve.assembly.layout`): each column is applied to the case file at its smallest,
largest and median value, each validated like a case file (so units, names and ranges are
checked as always, and a bad value is named by its column and row). Where those probes show
that the column moves only load entries of the parameter vector (flow speeds, headings and
wave height, constant forces: :meth:`~moorsolve.solve.assembly.layout.ParameterLayout.load_mask`,
entries that act through the load factor and whose validity is a range) and moves them
affinely, every row's entries are interpolated from the probes: exact to rounding, and
every value lies between two validated ones. Any other column (a length, a weight, a line
type, an anchor) is validated once per distinct value, as a sweep axis is. Columns whose
entries overlap, or that change the problem's structure, leave every row to a full solve.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

import numpy as np

from ..errors import CaseError

#: Relative tolerance of the affine check of a column's probes.
_AFFINE_RTOL = 1e-12


def parse_header(name) -> tuple:
    """``"environment.wind.speed [kn]"`` as ``("environment.wind.speed", "kn")``; a header
    without a unit gives ``(path, None)``. The path's own brackets are selectors
    (``legs[L3].anchor``, ``body.loads.force[0]``); a unit is the last bracket after a
    space."""
    from ..model.paths import parse_path

    if not isinstance(name, str):
        raise CaseError("table", f"column {name!r} is not a case path")
    text = name.strip()
    unit = None
    m = re.match(r"^(.*\S)\s+\[\s*([^\]]+?)\s*\]$", text)
    if m:
        text, unit = m.group(1), m.group(2)
    try:
        parse_path(text)
    except CaseError as err:
        raise CaseError(f"table[{name!r}]", f"{err}; a column is a case path, optionally "
                                            "with a unit in brackets: "
                                            "environment.wind.speed [kn]") from None
    return text, unit


def _cell(value, unit):
    """A cell as the case file would hold it at its path."""
    if isinstance(value, (np.integer, np.floating)):
        value = value.item()
    if unit is None:
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CaseError("table", f"{value!r} is not a number in {unit}")
    return f"{value!r} {unit}"


class TableAxis:
    """The rows of a load table as one zipped sweep axis whose values are validated by
    column (see the module notes).

    Attributes
    ----------
    headers : list of str
        The table's column names, as given.
    paths, units : list
        Each column's case path and unit (None: SI or case-file values).
    rows : list of tuple
        The cells, row by row, as plain Python values.
    """

    def __init__(self, table):
        if hasattr(table, "columns") and hasattr(table, "to_numpy"):
            headers = [str(c) for c in table.columns]
            columns = [table[c].to_numpy() for c in table.columns]
        elif isinstance(table, Mapping):
            headers = [str(c) for c in table]
            columns = [np.asarray(list(v), dtype=object) for v in table.values()]
        else:
            raise CaseError("table", "a load table is a pandas DataFrame or a mapping of "
                                     "column names to values")
        if not headers:
            raise CaseError("table", "the load table has no columns")
        lengths = {len(c) for c in columns}
        if len(lengths) != 1 or 0 in lengths:
            raise CaseError("table", "every column must hold one value per row (and at "
                                     "least one row)")
        parsed = [parse_header(h) for h in headers]
        paths = [p for p, _ in parsed]
        for k, path in enumerate(paths):
            if path in paths[:k]:
                raise CaseError(f"table[{headers[k]!r}]", f"path {path!r} has two columns")
        self.headers, self.paths = headers, paths
        self.units = [u for _, u in parsed]
        self.n_rows = lengths.pop()
        self._columns = []
        #: Per column, whether every cell is a number (int or float, not bool).
        self.numeric = []
        for header, column in zip(headers, columns):
            if isinstance(column, np.ndarray) and column.dtype.kind in "iuf":
                # A column of numbers (a CSV's or Parquet's): converted and checked whole.
                bad = np.flatnonzero(~np.isfinite(column)) if column.dtype.kind == "f" \
                    else ()
                values = column.tolist()
                numeric = True
            else:
                values = [v.item() if isinstance(v, np.generic) else v for v in column]
                bad = [i for i, v in enumerate(values)
                       if isinstance(v, float) and not math.isfinite(v)]
                numeric = all(isinstance(v, (int, float)) and not isinstance(v, bool)
                              for v in values)
            if len(bad):
                i = int(bad[0])
                raise CaseError(f"table[{header!r}]", f"row {i}: {values[i]!r} is not a value")
            self._columns.append(values)
            self.numeric.append(numeric)
        self.rows = list(zip(*self._columns))

    def plain(self) -> dict:
        """The table as plain data (headers and rows), for records and Dask workers."""
        return {"columns": list(self.headers), "rows": [list(r) for r in self.rows]}

    def column(self, k: int) -> list:
        """The cells of column ``k``, as plain Python values."""
        return self._columns[k]

    def edits(self, row: int) -> dict:
        """``{path: value}`` of one row, values as the case file holds them."""
        return {path: _cell(v, unit)
                for path, unit, v in zip(self.paths, self.units, self.rows[row])}

    # -- validation by column --------------------------------------------------------------

    def vectors(self, case, point_vector, structure_key, loads) -> tuple:
        """Every row's point vector, from validating the columns, in compact form.

        ``point_vector(case)`` is the sweep's per-point vector, ``structure_key`` the
        problem's, and ``loads`` the mask of point-vector entries that are loads.
        Returns ``(mask, moved, same_structure)``: the entries some column moves, their
        values row by row (a row's other entries are the case's own), and False when a
        column changes the problem's structure or two columns move the same entry (every
        row is then solved in full).
        """
        base = point_vector(case)
        base_key = structure_key(case)
        moved = np.zeros(base.size, dtype=bool)
        blocks = []
        same = True

        def validate(k, value):
            header = self.headers[k]
            try:
                cell = _cell(value, self.units[k])
                probe = case.with_values({self.paths[k]: cell}, keep_source=False)
            except CaseError as err:
                row = self._columns[k].index(value)
                raise CaseError(f"table[{header!r}]", f"row {row}: {value!r}: {err}") \
                    from None
            return probe

        for k, values in enumerate(self._columns):
            mask, rows = None, None
            if self.numeric[k]:
                mask, rows = self._affine(k, values, validate, point_vector, structure_key,
                                          base, base_key, loads)
            if rows is None:
                vecs, keys = {}, set()
                for v in dict.fromkeys(values):
                    probe = validate(k, v)
                    keys.add(structure_key(probe) == base_key)
                    vecs[v] = point_vector(probe)
                same &= all(keys)
                if not all(keys):
                    # Another structure (its vector may differ in length): every row is
                    # solved in full, so nothing of it is kept.
                    blocks.append((np.zeros(base.size, dtype=bool), np.zeros((self.n_rows, 0))))
                    continue
                distinct = np.array(list(vecs.values()))
                mask = np.any(distinct != base, axis=0)
                where = {v: i for i, v in enumerate(vecs)}
                rows = distinct[[where[v] for v in values]][:, mask]
            if np.any(moved & mask):
                same = False
            moved |= mask
            blocks.append((mask, rows))
        # The moved entries of every row: the case's own, then each column's.
        out = np.tile(base[moved], (self.n_rows, 1))
        position = np.cumsum(moved) - 1
        for mask, rows in blocks:
            out[:, position[mask]] = rows
        return moved, out, bool(same)

    def _affine(self, k, values, validate, point_vector, structure_key, base, base_key,
                loads):
        """``(mask, rows of the moved entries)`` when column ``k`` moves only load entries
        and moves them affinely (checked at its median), else ``(None, None)``."""
        v = np.asarray(values, dtype=float)
        lo, hi, mid = float(v.min()), float(v.max()), float(np.median(v))
        probes = {}
        for value in dict.fromkeys((lo, hi, mid)):
            case = validate(k, values[int(np.argmin(np.abs(v - value)))]
                            if value == mid else value)
            if structure_key(case) != base_key:
                return None, None
            probes[value] = point_vector(case)
        mask = np.zeros(base.size, dtype=bool)
        for vec in probes.values():
            mask |= vec != base
        if np.any(mask & ~loads):
            return None, None
        if hi == lo:
            return mask, np.tile(probes[lo][mask], (v.size, 1))
        low, high = probes[lo][mask], probes[hi][mask]
        slope = (high - low) / (hi - lo)
        if mid not in (lo, hi):
            mid_value = float(v[int(np.argmin(np.abs(v - mid)))])
            error = np.abs(low + (mid_value - lo) * slope - probes[mid][mask])
            if np.any(error > _AFFINE_RTOL * np.maximum(np.maximum(np.abs(low),
                                                                   np.abs(high)), 1.0)):
                return None, None
        return mask, low[None, :] + (v - lo)[:, None] * slope[None, :]
