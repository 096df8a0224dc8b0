"""The plan of a sweep: what defines its points, in what order, and how a chunk is solved."""

from __future__ import annotations

import itertools
import math
import threading
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import CaseError
from ..model import Case
from ..model.edit import from_source, inline_source
from ..model.units import recording
from ..solve.assembly.cache import get_problem
from ..solve.equilibrium import rest_point
from ..solve.kernels.start import initial_point
from ..solve.assembly.prepared import structure_key
from .sweep_chunks import TEXT_COLUMNS, _Table, _kernel_pool, _solve_each, _solve_fast
from .sweep_grid import (_GridColumn, _axes, _edits, _grid_columns, _label, _plain,
                         _plain_grid, _point_vector, _sha, axis_columns, axis_quantities,
                         snake_order)

_PARALLEL_MIN_POINTS = 64
_MIN_CHUNK = 64
_MAX_CHUNKS = 64

# Guards the plan's shared preparation and the remote plans of a Dask worker.
_SOLVE_LOCK = threading.RLock()



def _validated(case, paths, value):
    """``(what it converted to SI, the case)`` of one grid value validated as a case."""
    try:
        with recording() as converted:
            c = case.with_values(_edits(paths, value), keep_source=False)
    except CaseError as err:
        raise CaseError(f"grid[{_label(paths)!r}]", f"value {value!r}: {err}") from None
    return converted, c


def _load_entries(case) -> np.ndarray:
    """The point-vector entries that are loads: the problem's load entries; none of the
    limits after them (each line's MBL, each fender's and guide's rated reaction)."""
    mask = np.asarray(get_problem(case).load_mask, dtype=bool)
    return np.concatenate([mask, np.zeros(_point_vector(case).size - mask.size, dtype=bool)])


def _axis_by_column(case, paths, values):
    """``(point vectors, same structure, quantities)`` of an axis of numbers validated by
    column as a load table's columns are (:class:`.load_table.TableAxis`: each column at
    its extremes and median, load entries interpolated, others per distinct value), or
    None for an axis validated value by value (strings with units, names, or an edit a
    column cannot make, such as an item of a force the case does not give)."""
    from .load_table import TableAxis

    columns = axis_columns(paths, values)
    if columns is None:
        return None
    probe, _ = _validated(case, paths, values[0])
    quantities = axis_quantities(case.source, paths, values, probe)
    if quantities is None:
        return None
    loads = _load_entries(case)
    try:
        mask, moved, same = TableAxis(columns).vectors(case, _point_vector, structure_key,
                                                       loads)
    except CaseError:
        return None             # validated value by value, which names the value at fault
    return (mask, moved), same, quantities


# ---- the plan: what defines the points ------------------------------------------------------


class SweepPlan:
    """The points of a sweep and how to solve any chunk of them.

    Built identically from ``(case.source, grid, solver, tol)`` anywhere (a Dask worker
    rebuilds it from :meth:`spec`).
    """

    def __init__(self, case: Case, grid: Mapping | None = None, *, table=None,
                 solver: str = "newton", tol: float | None = None,
                 chunk_size: int | None = None, allow_overload: bool = False):
        if solver not in ("newton", "ipopt"):
            raise ValueError(f"solver {solver!r}: must be 'newton' or 'ipopt'")
        if case.source is None:
            raise CaseError("case", "a sweep edits the case-file data; load the case with "
                                    "moorsolve.load_case (from a file or a dict)")
        if (grid is None) == (table is None):
            raise CaseError("grid", "give a grid of case paths or a load table (not both)")
        self.case, self.solver = case, solver
        self.allow_overload = bool(allow_overload)
        self.grid = grid
        self.table = None
        if table is not None:
            from .load_table import TableAxis
            self.table = TableAxis(table)
            self.axes = [(tuple(self.table.paths), self.table.rows)]
        else:
            self.axes = _axes(grid)
        self.tol = case.solver.tol if tol is None else float(tol)
        self.shape = tuple(len(values) for _, values in self.axes)
        self.n_points = math.prod(self.shape)
        self.names = [leg.name for leg in case.legs]
        self.body_names = tuple(b.name for b in case.bodies) if case.form == "network" else ()
        self.contacts = ([f.name for f in case.contacts.fenders]
                         + [g.name for g in case.contacts.guides])

        base_key = structure_key(case)
        base_vec = _point_vector(case)
        if self.table is not None:
            # Validated by column (load_table), not row by row; its columns as given.
            loads = _load_entries(case)
            mask, moved, same = self.table.vectors(case, _point_vector, structure_key, loads)
            axis_vectors, same = [(mask, moved)], [same]
            self._grid = [[_GridColumn(header, self.table.column(j), self.table.numeric[j])
                           for j, header in enumerate(self.table.headers)]]
        else:
            # Each axis value validated once, as a case of its own; what it converted to
            # SI gives the grid's columns (numbers in SI, the unit in the name).
            axis_vectors, same, self._grid = [], [], []
            for paths, values in self.axes:
                by_column = _axis_by_column(case, paths, values)
                if by_column is not None:
                    vecs, same_k, quantities = by_column
                else:
                    vecs, keys, quantities = [], [], []
                    for value in values:
                        converted, c = _validated(case, paths, value)
                        quantities.append(converted)
                        vecs.append(_point_vector(c))
                        keys.append(structure_key(c) == base_key)
                    same_k = all(keys)
                    if same_k:
                        vecs = np.array(vecs)
                        mask = np.any(vecs != base_vec, axis=0)
                        vecs = (mask, vecs[:, mask])
                    else:   # full solves: another structure's vectors are not kept
                        vecs = (np.zeros(base_vec.size, dtype=bool),
                                np.zeros((len(values), 0)))
                axis_vectors.append(vecs)
                same.append(same_k)
                self._grid.append(_grid_columns(case.source, paths, values, quantities))

        # On a bathymetry grid every point re-seats its lines' seabed planes (solve/
        # bathymetry.py): full solves, not the kernel on fixed parameters.
        fast = (solver == "newton" and all(same)
                and case.environment.seabed.bathymetry is None)
        # Each axis as (the entries it moves, their values per axis value): a point's
        # vector is made when its chunk runs (vectors), never the whole grid's at once.
        masks = [mask for mask, _ in axis_vectors]
        if fast:
            used = np.zeros_like(base_vec, dtype=bool)
            for m in masks:
                fast &= not np.any(used & m)
                used |= m
        self.fast = bool(fast)
        self._axis_vectors, self._masks, self._base_vec = axis_vectors, masks, base_vec

        self.indices = list(itertools.product(*[range(n) for n in self.shape]))
        # A table's rows are solved in their order; a grid is walked in a snake.
        order = list(range(self.n_points)) if self.table is not None else [
            int(np.ravel_multi_index(idx, self.shape)) for idx in snake_order(self.shape)]
        if chunk_size is None:
            chunk_size = max(_MIN_CHUNK, -(-self.n_points // _MAX_CHUNKS))
        if int(chunk_size) < 1:
            raise ValueError(f"chunk_size {chunk_size}: must be >= 1")
        chunk_size = int(chunk_size)
        self.chunks = [order[a:a + chunk_size] for a in range(0, len(order), chunk_size)]
        self._x_rest = None
        self._rest = None
        self._plain = self._grid_sha = None
        self._problem = None

    # -- identity ---------------------------------------------------------------------------

    def spec(self) -> dict:
        """Plain data from which a worker rebuilds this plan."""
        return {"source": inline_source(self.case), "grid": self._plain_points(),
                "table": self.table is not None, "solver": self.solver, "tol": self.tol,
                "chunks": self.chunks, "allow_overload": self.allow_overload}

    @classmethod
    def from_spec(cls, spec: dict) -> "SweepPlan":
        options = dict(solver=spec["solver"], tol=spec["tol"],
                       allow_overload=spec["allow_overload"])
        if spec.get("table"):
            table = dict(zip(spec["grid"]["columns"], zip(*spec["grid"]["rows"])))
            plan = cls(from_source(spec["source"]), table=table, **options)
        else:
            grid = {(tuple(k[1]) if k[0] == "zip" else k[1]): v for k, v in spec["grid"]}
            plan = cls(from_source(spec["source"]), grid, **options)
        plan.chunks = spec["chunks"]
        return plan

    def _plain_points(self):
        if self._plain is None:      # made once: a table's rows are many
            self._plain = (self.table.plain() if self.table is not None
                           else _plain_grid(self.grid))
        return self._plain

    def fingerprint(self) -> dict:
        """What a resumed sweep must share with the one that wrote the file."""
        if self._grid_sha is None:
            self._grid_sha = _sha(self._plain_points())
        return {"case_sha256": _sha(self.case.source),
                "grid_sha256": self._grid_sha,
                "solver": self.solver, "tol": self.tol, "n_points": self.n_points,
                "allow_overload": self.allow_overload}

    def grid_columns(self) -> list[str]:
        return [col.name for columns in self._grid for col in columns]

    def result_columns(self) -> list[str]:
        return list(_Table(0, self.names, self.body_names, self.contacts).columns())

    def column_types(self) -> dict:
        """The type of each column of the output file as read back: ``float``,
        ``bool``, ``int`` or ``str`` (text and JSON values)."""
        types = {"point": int}
        for columns in self._grid:
            for col in columns:
                types[col.name] = float if col.numeric else str
        for name, value in _Table(1, self.names, self.body_names,
                                  self.contacts).columns().items():
            types[name] = (str if name in TEXT_COLUMNS else bool
                           if np.asarray(value).dtype == bool else int
                           if np.asarray(value).dtype.kind == "i" else float)
        return types

    def grid_record(self) -> dict:
        """The grid (or the load table) as plain data, for the record beside an output
        file."""
        if self.table is not None:
            # Its rows are in the output and their hash in the fingerprint; the record
            # names the columns (a copy of 100,000 rows cost more than solving them).
            return {"table": {"columns": list(self.table.headers),
                              "rows": self.table.n_rows}}
        return {_label(paths): _plain(values) for paths, values in self.axes}

    # -- solving ------------------------------------------------------------------------------

    def point_case(self, i: int) -> Case:
        if self.table is not None:
            edits = self.table.edits(i)
        else:
            edits = {}
            for (paths, values), k in zip(self.axes, self.indices[i]):
                edits.update(_edits(paths, values[k]))
        return self.case.with_values(edits, keep_source=False)

    def vectors(self, points=None) -> np.ndarray:
        """The point vectors of ``points`` (every point by default), one row each."""
        points = (np.arange(self.n_points) if points is None
                  else np.asarray(points, dtype=int))
        vectors = np.tile(self._base_vec, (len(points), 1))
        index = (points[:, None] if self.table is not None
                 else np.column_stack(np.unravel_index(points, self.shape)))
        for k, (mask, moved) in enumerate(self._axis_vectors):
            if moved.shape[1]:
                vectors[:, mask] = moved[index[:, k]]
        return vectors

    def prepare(self) -> None:
        """Build (and compile) what the chunks share, once, before they run."""
        if self.fast and self._x_rest is None:
            with _SOLVE_LOCK:
                if self._x_rest is None:
                    self._problem = problem = get_problem(self.case)
                    _kernel_pool(problem)
                    # A table's rows start as single solves do: from the rest state.
                    rest = rest_point(problem, self.case, self.tol, problem.newton())
                    if self.table is None:
                        # A grid walks from the case's pose; a point nearer to no load
                        # than to its neighbour starts from rest (sweep_chunks._nearer_rest).
                        self._rest = (rest, np.asarray(problem.load_mask, bool),
                                      self._base_vec[:problem.n_p])
                    self._x_rest = rest if self.table is not None \
                        else initial_point(problem, self.case)

    def solve_chunk(self, points: Sequence[int]) -> tuple[np.ndarray, dict]:
        """Solve ``points`` (snake order) and return them with their result columns."""
        points = np.asarray(points, dtype=int)
        table = _Table(len(points), self.names, self.body_names, self.contacts)
        if self.fast:
            self.prepare()
            problem = self._problem
            pool = _kernel_pool(problem)
            kernel = pool.acquire()
            try:
                # The chunk's own vectors, row k for points[k].
                _solve_fast(problem, kernel, self._x_rest, self.vectors(points),
                            np.arange(len(points)), table,
                            self.tol, self.case.body is not None, self.allow_overload,
                            self.table is not None, self._rest)
            finally:
                pool.release(kernel)
            retry = np.flatnonzero(~table.done).tolist()
        else:
            retry = list(range(len(points)))
        _solve_each(retry, points, table, self.point_case, self.tol, self.allow_overload,
                    self.table is not None and self.solver == "newton")
        return points, table.columns()

    # -- rows ---------------------------------------------------------------------------------

    def frame(self, points, columns: dict, for_file: bool = False):
        """A DataFrame of solved ``points`` indexed by ``point``. Grid values that are
        quantities are SI numbers in columns named with their unit (``environment.wind.speed
        [m/s]``; a list gives one column per item, ``body.loads.force[2] [N m]``); other
        values keep the path as name, and ``for_file`` writes them as text (lists as JSON)."""
        import pandas as pd

        data = {}
        for k, columns_k in enumerate(self._grid):
            for col in columns_k:
                cells = [col.values[self.indices[i][k]] for i in points]
                data[col.name] = col.file_cells(cells) if for_file else cells
        data.update(columns)
        if for_file:
            for name in ("reason", "warnings"):
                data[name] = [r.replace("\n", " ").replace("\r", " ") for r in data[name]]
        index = pd.Index(np.asarray(points, dtype=int), name="point")
        return pd.DataFrame(data, index=index)


