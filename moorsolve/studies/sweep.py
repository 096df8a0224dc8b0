"""Many solves of one scene: a cartesian grid of case edits, one built problem for all.

``grid`` maps dotted case paths (:mod:`moorsolve.model.paths`) to lists of values. Each axis
value is applied to the case-file data and validated once (so units and field names work
as in a case file). A key may also be a tuple of paths whose values are tuples, one value
per path: a *zipped* axis (``("environment.wind.toward_deg",
"environment.current.toward_deg"): [(0, 0), (15, 15), ...]`` turns wind and current
together). When every edit only changes problem parameters (loads, headings, speeds,
anchors, lengths, weights, stiffness, friction, breaking loads) and different axes change
different parameters, the grid's parameter matrix is assembled by indexing and the points
are solved by the compiled Newton kernel, each warm-started from its neighbour: the grid
is walked in a snake order (consecutive points differ in one index by one).

The snake order is cut into contiguous *chunks* whose layout depends only on the grid (not
on the number of workers), so every run of a sweep, local or on a Dask cluster, whole or
resumed, solves each point from the same start. Chunks run on worker threads (the kernel
releases the GIL) or as tasks on a ``dask.distributed`` cluster, and each finished chunk
is handed to the output file (:mod:`moorsolve.io.sweep_output`) at once.

A point the kernel does not certify is re-solved by :func:`moorsolve.solve` with IPOPT
(rest state and load stepping included); a point with no equilibrium becomes a row with
``converged = False`` and the reason, never an abort. Edits that change the problem's
structure (adding wind, changing a drag area or the gravity) fall back to one full solve
per point, still warm-started where the structure allows. Full solves are serialised
within one process (the problem cache is shared); Dask workers in separate processes run
them in parallel.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
import sys
import threading
from collections import OrderedDict
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import CaseError, ConvergenceError
from ..model import Case
from ..model.paths import concrete_paths
from ..model.units import KINDS, recording
from ..physics.kinematics import wrap_degrees
from ..solve.cache import get_problem
from ..solve.equilibrium import over_mbl, rest_point, solve, turn_jumps
from ..solve.stability import assess
from ..solve.start import initial_point
from ..solve.layout import parameter_vector
from ..solve.problem import structure_key

_PARALLEL_MIN_POINTS = 64
_MIN_CHUNK = 64
_MAX_CHUNKS = 64

# Full solves and the problem cache are not for concurrent threads of one process.
_SOLVE_LOCK = threading.RLock()


def sweep(case: Case, grid: Mapping | None = None, *, table=None, solver: str = "newton",
          tol: float | None = None, workers: int | None = None, output=None,
          resume: bool = False, overwrite: bool = False, scheduler=None, progress=False,
          chunk_size: int | None = None, allow_overload: bool = False):
    """Solve ``case`` at every point of the cartesian product of ``grid``, or at every row
    of a load ``table``.

    Parameters
    ----------
    case : Case
        From :func:`moorsolve.load_case` (the sweep edits the case-file data it came from).
    grid : mapping
        Dotted case path (``"environment.wind.toward_deg"``, ``"body.loads.force"``,
        ``"legs[*].segments[0].length"``) to the values it takes; each value is what the
        case file would hold at that path (a number, a list, or a string with a unit).
        A tuple of paths maps to a list of tuples (a zipped axis: the paths change
        together).
    table : pandas.DataFrame or mapping, optional
        A load table instead of a grid (:mod:`moorsolve.studies.load_table`): each row a
        load case, each column a case path with an optional unit in brackets
        (``environment.wind.speed [kn]``). Validated by column, not by row; its columns
        lead the result as given.
    solver : {"newton", "ipopt"}
        ``"newton"`` (default): the compiled fast path, IPOPT for points it cannot
        certify. ``"ipopt"``: every point by :func:`moorsolve.solve` with IPOPT.
    tol : float, optional
        Certified relative force residual; defaults to the case's ``solver.tol``.
    workers : int, optional
        Local threads for the fast path; defaults to the number of cores (one below 64
        points). Ignored with ``scheduler``.
    output : str or path, optional
        ``.csv`` or ``.parquet`` file written as chunks complete
        (:mod:`moorsolve.io.sweep_output`), with a ``<output>.sweep.json`` record of the
        case and grid it belongs to. At the end the file holds every point in product
        order. An existing output is an error unless ``resume`` or ``overwrite``.
    resume : bool
        Solve only the points missing from ``output`` (made by an interrupted sweep of
        the same case, grid, solver and tolerance; anything else is refused).
    overwrite : bool
        Replace an existing ``output``.
    scheduler : str or distributed.Client, optional
        Run the chunks on an existing Dask cluster (``"tcp://host:port"`` or a client).
        Each worker rebuilds the problem from the case-file data.
    progress : bool or file, optional
        Show a progress bar (tqdm) on stderr, or on the given file.
    chunk_size : int, optional
        Points per chunk (default: at least 64, at most 64 chunks).
    allow_overload : bool
        An equilibrium in which a line exceeds its MBL is a converged row (its ``reason``
        still names the overload) instead of ``converged = False``.

    Returns
    -------
    pandas.DataFrame
        One row per point in the product order of ``grid``, indexed by ``point`` (the
        position in that order): the grid values, then ``converged``, ``reason``,
        ``solver``, ``iterations``, ``residual_N``, ``residual_Nm``,
        ``residual_relative``, ``x_m``, ``y_m``, ``yaw_deg`` and, per leg,
        ``<name>.fairlead_tension_N`` and ``<name>.anchor_tension_N``, per fender and pile
        guide ``<name>.reaction_N`` (0 out of contact). Grid values are
        SI numbers in columns named with their unit (``environment.wind.speed [m/s]``
        for ``"20 kn"``; ``body.loads.force[0] [N]`` ... for a list); values that are
        not quantities keep the path as name. With ``output`` it is the finished file
        read back (those other values are text there, lists as JSON).
    """
    plan = SweepPlan(case, grid, table=table, solver=solver, tol=tol, chunk_size=chunk_size,
                     allow_overload=allow_overload)
    sink = None
    if output is not None:
        from ..io.sweep_output import open_sink
        sink = open_sink(output, plan, resume=resume, overwrite=overwrite)
    client, own_client = (None, False) if scheduler is None else _client(scheduler)
    try:
        if sink is not None:
            sink.start()
        done = sink.done if sink is not None else set()
        chunks = [[i for i in c if i not in done] for c in plan.chunks]
        chunks = [c for c in chunks if c]
        frames = []

        def finished(points, columns):
            if sink is not None:
                sink.write(plan.frame(points, columns, for_file=True))
            else:
                frames.append((points, columns))
            bar.update(len(points))

        bar = _progress_bar(progress, plan.n_points, len(done))
        try:
            if client is not None:
                _run_dask(client, plan, chunks, finished)
            else:
                _run_local(plan, chunks, workers, finished)
        finally:
            bar.close()
    finally:
        if own_client:
            client.close()
    if sink is not None:
        return sink.finish()
    if not frames:
        return plan.frame(np.zeros(0, int), _Table(0, plan.names, plan.body_names,
                                                   plan.contacts).columns())
    points = np.concatenate([p for p, _ in frames])
    order = np.argsort(points, kind="stable")
    columns = {}
    for name in frames[0][1]:
        joined = np.concatenate([np.asarray(c[name], dtype=object if name in ("reason", "solver")
                                            else None) for _, c in frames])
        columns[name] = joined[order] if name not in ("reason", "solver") \
            else [str(v) for v in joined[order]]
    return plan.frame(points[order], columns)


# ---- the plan: what defines the points ------------------------------------------------------


class SweepPlan:
    """The points of a sweep and how to solve any chunk of them.

    Built identically from ``(case.source, grid, solver, tol)`` anywhere (a Dask worker
    rebuilds it from :meth:`spec`).
    """

    def __init__(self, case: Case, grid: Mapping | None = None, *, table=None,
                 solver: str = "newton", tol: float | None = None,
                 chunk_size: int | None = None, allow_overload: bool = False):
        from ..io import load_case
        from ..model.paths import with_values

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
        self._with_values, self._load_case = with_values, load_case

        base_key = structure_key(case)
        base_vec = _point_vector(case)
        if self.table is not None:
            # Validated by column (load_table), not row by row; its columns as given.
            loads = np.concatenate([get_problem(case).load_mask,
                                    np.zeros(len(case.legs), dtype=bool)])
            vecs, same = self.table.vectors(case, _point_vector, structure_key, loads)
            axis_vectors, same = [vecs], [same]
            self._grid = [[_GridColumn(header, [row[j] for row in self.table.rows],
                                       all(_numeric(row[j]) for row in self.table.rows))
                           for j, header in enumerate(self.table.headers)]]
        else:
            # Each axis value validated once, as a case of its own; what it converted to
            # SI gives the grid's columns (numbers in SI, the unit in the name).
            axis_vectors, same, self._grid = [], [], []
            for paths, values in self.axes:
                vecs, keys, quantities = [], [], []
                for value in values:
                    try:
                        with recording() as converted:
                            c = load_case(with_values(case.source, _edits(paths, value)),
                                          keep_source=False)
                    except CaseError as err:
                        raise CaseError(f"grid[{_label(paths)!r}]",
                                        f"value {value!r}: {err}") from None
                    quantities.append(converted)
                    vecs.append(_point_vector(c))
                    keys.append(structure_key(c) == base_key)
                axis_vectors.append(np.array(vecs))
                same.append(all(keys))
                self._grid.append(_grid_columns(case.source, paths, values, quantities))

        fast = solver == "newton" and all(same)
        masks = []
        if fast:
            for vecs in axis_vectors:
                masks.append(np.any(vecs != base_vec, axis=0))
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
        self._vectors = None
        self._x_rest = None
        self._problem = None

    # -- identity ---------------------------------------------------------------------------

    def spec(self) -> dict:
        """Plain data from which a worker rebuilds this plan."""
        return {"source": self.case.source, "grid": self._plain_points(),
                "table": self.table is not None, "solver": self.solver, "tol": self.tol,
                "chunks": self.chunks, "allow_overload": self.allow_overload}

    @classmethod
    def from_spec(cls, spec: dict) -> "SweepPlan":
        from ..io import load_case
        options = dict(solver=spec["solver"], tol=spec["tol"],
                       allow_overload=spec["allow_overload"])
        if spec.get("table"):
            table = dict(zip(spec["grid"]["columns"], zip(*spec["grid"]["rows"])))
            plan = cls(load_case(spec["source"]), table=table, **options)
        else:
            grid = {(tuple(k[1]) if k[0] == "zip" else k[1]): v for k, v in spec["grid"]}
            plan = cls(load_case(spec["source"]), grid, **options)
        plan.chunks = spec["chunks"]
        return plan

    def _plain_points(self):
        return self.table.plain() if self.table is not None else _plain_grid(self.grid)

    def fingerprint(self) -> dict:
        """What a resumed sweep must share with the one that wrote the file."""
        return {"case_sha256": _sha(self.case.source),
                "grid_sha256": _sha(self._plain_points()),
                "solver": self.solver, "tol": self.tol, "n_points": self.n_points,
                "allow_overload": self.allow_overload}

    def grid_columns(self) -> list[str]:
        return [col.name for columns in self._grid for col in columns]

    def result_columns(self) -> list[str]:
        return list(_Table(0, self.names, self.body_names, self.contacts).columns())

    def grid_record(self) -> dict:
        """The grid (or the load table) as plain data, for the record beside an output
        file."""
        if self.table is not None:
            return {"table": self.table.plain()}
        return {_label(paths): _plain(values) for paths, values in self.axes}

    # -- solving ------------------------------------------------------------------------------

    def point_case(self, i: int) -> Case:
        if self.table is not None:
            edits = self.table.edits(i)
        else:
            edits = {}
            for (paths, values), k in zip(self.axes, self.indices[i]):
                edits.update(_edits(paths, values[k]))
        return self._load_case(self._with_values(self.case.source, edits), keep_source=False)

    def vectors(self) -> np.ndarray:
        if self._vectors is None:
            vectors = np.empty((self.n_points, self._base_vec.size))
            vectors[:] = self._base_vec
            index_array = np.array(self.indices, dtype=int).reshape(self.n_points,
                                                                    len(self.axes))
            for k, (vecs, mask) in enumerate(zip(self._axis_vectors, self._masks)):
                vectors[:, mask] = vecs[index_array[:, k]][:, mask]
            self._vectors = vectors
        return self._vectors

    def prepare(self) -> None:
        """Build (and compile) what the chunks share, once, before they run."""
        if self.fast and self._x_rest is None:
            with _SOLVE_LOCK:
                if self._x_rest is None:
                    self._problem = problem = get_problem(self.case)
                    _kernel_pool(problem)
                    # A table's rows start as single solves do: from the rest state.
                    self._x_rest = (rest_point(problem, self.case, self.tol,
                                               problem.newton())
                                    if self.table is not None
                                    else initial_point(problem, self.case))
            self.vectors()

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
                _solve_fast(problem, kernel, self._x_rest, self.vectors(), points, table,
                            self.tol, self.case.body is not None, self.allow_overload,
                            self.table is not None)
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
            data["reason"] = [r.replace("\n", " ").replace("\r", " ") for r in data["reason"]]
        index = pd.Index(np.asarray(points, dtype=int), name="point")
        return pd.DataFrame(data, index=index)


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
    parameters, then each leg's minimum breaking load (for the overload check)."""
    mbl = [leg.line_type.mbl if leg.line_type.mbl is not None else np.inf
           for leg in case.legs]
    return np.concatenate([parameter_vector(case, 1.0), mbl])


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


# ---- solving a chunk ------------------------------------------------------------------------


#: Per body of a network case: its absolute pose columns ``<body>.<field>``.
_POSE_FIELDS = ("x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg")


class _Table:
    """Results of ``n`` points, one array per column, filled by row."""

    def __init__(self, n: int, names: list[str], bodies: tuple = (), contacts: list[str] = ()):
        self.names = names
        self.bodies = tuple(bodies)
        self.poses = np.full((n, 6 * len(self.bodies)), np.nan)
        #: Fenders and guides: their reaction [N] per point.
        self.contacts = list(contacts)
        self.reactions = np.full((n, len(self.contacts)), np.nan)
        self.done = np.zeros(n, bool)
        self.converged = np.zeros(n, bool)
        self.reason = [""] * n
        self.solver = [""] * n
        self.iterations = np.zeros(n, int)
        self.residual = np.full((n, 3), np.nan)      # force, moment, relative
        self.body = np.full((n, 3), np.nan)
        self.t_fair = np.full((n, len(names)), np.nan)
        self.t_anchor = np.full((n, len(names)), np.nan)

    def from_result(self, i: int, result, reason: str = "", converged=None) -> None:
        c = result.certificate
        self.done[i] = True
        self.converged[i] = not reason if converged is None else converged
        self.reason[i], self.solver[i] = reason, result.solver
        self.iterations[i] = c.iterations
        self.residual[i] = (c.force_N, c.moment_Nm, c.relative)
        if result.body is not None:
            self.body[i] = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
        for k, b in enumerate(result.bodies[:len(self.bodies)]):
            self.poses[i, 6 * k: 6 * k + 6] = [b[f] for f in _POSE_FIELDS]
        self.t_fair[i] = [leg.fairlead_tension_N for leg in result.legs]
        self.t_anchor[i] = [leg.anchor_tension_N for leg in result.legs]
        self.reactions[i] = ([f["reaction_N"] for f in result.fenders]
                             + [g["reaction_N"] for g in result.guides])

    def columns(self) -> dict:
        out = {"converged": self.converged, "reason": self.reason, "solver": self.solver,
               "iterations": self.iterations, "residual_N": self.residual[:, 0],
               "residual_Nm": self.residual[:, 1], "residual_relative": self.residual[:, 2],
               "x_m": self.body[:, 0], "y_m": self.body[:, 1], "yaw_deg": self.body[:, 2]}
        for k, name in enumerate(self.bodies):
            for j, field in enumerate(_POSE_FIELDS):
                out[f"{name}.{field}"] = self.poses[:, 6 * k + j]
        for k, name in enumerate(self.names):
            out[f"{name}.fairlead_tension_N"] = self.t_fair[:, k]
            out[f"{name}.anchor_tension_N"] = self.t_anchor[:, k]
        for k, name in enumerate(self.contacts):
            out[f"{name}.reaction_N"] = self.reactions[:, k]
        return out


def _kernel_pool(problem):
    return problem.kernel_pool()


def _solve_fast(problem, kernel, x_rest, vectors, points, table, tol, has_body,
                allow_overload=False, from_rest=False):
    """The kernel at every point: from the previous point's solution (a grid's snake), or
    with ``from_rest`` from the rest state as a single solve starts (a load table's rows,
    which need not be neighbours: run as one batch, :func:`_solve_rows`). A point that
    does not certify, is not clearly stable or (from rest) turns a body far is left for a
    full solve."""
    if from_rest:
        _solve_rows(problem, kernel, x_rest, vectors, points, table, tol, has_body,
                    allow_overload)
        return
    n_p = problem.n_p
    # A certified point may be an unstable equilibrium (a ship turned stern to the wind).
    check_stability = _has_body_nodes(problem)
    x_prev = x_rest.copy()
    for row, i in enumerate(points):
        p = vectors[i, :n_p]
        x, _, iterations, cert, body, tf, ta, reactions, stable = kernel.raw(x_prev, p, tol)
        ok, force, moment, relative = problem.judge(*cert, tol=tol)
        if not ok:
            continue            # left for the full solve
        if check_stability and not (stable[0] > 0.5 or _stable(problem, x, p)):
            continue            # the full solve looks for the stable equilibrium
        x_prev[:] = x
        table.done[row] = True
        table.iterations[row] = iterations[0]
        table.residual[row] = (force, moment, relative)
        _record(table, [row], body[None, :], tf[None, :], ta[None, :], reactions[None, :],
                vectors[i:i + 1, n_p:], has_body, allow_overload)


def _solve_rows(problem, kernel, x_rest, vectors, points, table, tol, has_body,
                allow_overload):
    """:func:`_solve_fast` for a load table: the kernel from the rest state at every row
    in one batch (:meth:`~moorsolve.solve.newton.NewtonKernel.run_many`), judged and
    recorded as arrays. A row is kept when it certifies, no angle turned
    further than a single solve's Newton step takes (:func:`turn_jumps`), and the kernel's
    stability test passes (else the full check, :func:`_stable`)."""
    n_p = problem.n_p
    out = kernel.run_many(x_rest, vectors[points, :n_p], tol)
    x = out["x"]
    ok, force, moment, relative = problem.judge_rows(out["certificate"], tol)
    ok &= np.isfinite(x).all(axis=1) & ~turn_jumps(problem, x_rest, x)
    if _has_body_nodes(problem):
        doubtful = np.flatnonzero(ok & ~(out["clearly_stable"][:, 0] > 0.5))
        for row in doubtful:
            ok[row] = _stable(problem, x[row], vectors[points[row], :n_p])
    rows = np.flatnonzero(ok)
    table.done[rows] = True
    table.iterations[rows] = out["iterations"][rows, 0]
    table.residual[rows] = np.column_stack([force, moment, relative])[rows]
    _record(table, rows, out["body"][rows], out["fairlead_tension"][rows],
            out["anchor_tension"][rows], out["reactions"][rows],
            vectors[points[rows], n_p:], has_body, allow_overload)


def _record(table, rows, body, tf, ta, reactions, mbl, has_body, allow_overload) -> None:
    """Write the kernel's outputs of certified ``rows`` (arrays with one row each) into
    ``table``: body pose, tensions, reactions, and an overload against ``mbl``."""
    if len(rows) == 0:
        return
    rows = np.asarray(rows)
    for row in rows.tolist():
        table.solver[row] = "newton"
    if has_body:
        table.body[rows] = np.column_stack(
            [body[:, 0], body[:, 1], wrap_degrees(np.degrees(body[:, 2]))])
    if table.bodies:
        pose = body[:, 3:].reshape(len(rows), -1, 6).copy()
        pose[:, :, 3:] = np.degrees(pose[:, :, 3:])
        pose[:, :, 5] = wrap_degrees(pose[:, :, 5])
        table.poses[rows] = pose.reshape(len(rows), -1)
    table.t_fair[rows], table.t_anchor[rows] = tf, ta
    table.reactions[rows] = reactions
    over = np.maximum(tf, ta) > mbl
    table.converged[rows] = allow_overload | ~over.any(axis=1)
    for k in np.flatnonzero(over.any(axis=1)).tolist():
        row = int(rows[k])
        table.reason[row] = "overload: " + "; ".join(
            f"leg {table.names[j]} would break: tension "
            f"{max(tf[k, j], ta[k, j]) / 1e3:.1f} kN > MBL {mbl[k, j] / 1e3:.1f} kN"
            for j in np.flatnonzero(over[k]))


def _has_body_nodes(problem) -> bool:
    return any(owner == "body" for owner, _, _ in problem.nodes)


def _overload(result) -> str:
    """The overload of an equilibrium accepted with ``allow_overload`` (else "")."""
    over = over_mbl(result)
    return "overload: " + "; ".join(over) if over else ""


def _stable(problem, x, p) -> bool:
    """Whether the kernel's point, which its own stability test did not call clearly
    stable, is a stable equilibrium: the full check
    (:func:`~moorsolve.solve.stability.assess`)."""
    with problem.lock:
        return assess(problem, x, p).stable


def _solve_each(rows, points, table, point_case, tol, allow_overload=False,
                from_rest=False):
    """Full solves (IPOPT strategy), warm-started while the structure stays the same; with
    ``from_rest`` each point solved as on its own (Newton strategy, no warm start)."""
    previous = {}
    for row in rows:
        pc = point_case(int(points[row]))
        key = id(get_problem(pc))        # a state is only meaningful to its own problem
        try:
            result = solve(pc, tol=tol, solver="newton" if from_rest else "ipopt",
                           start=None if from_rest else previous.get(key),
                           allow_overload=allow_overload)
        except ConvergenceError as err:
            if err.result is not None and err.result.converged:
                table.from_result(row, err.result, reason=err.reason)   # e.g. overload
            else:
                table.done[row] = True
                table.reason[row], table.solver[row] = err.reason, "ipopt"
                table.iterations[row] = err.iterations
                table.residual[row, :2] = (err.residual_N, err.residual_Nm)
            continue
        previous[key] = result.state
        table.from_result(row, result, reason=_overload(result), converged=True)


# ---- running the chunks ----------------------------------------------------------------------


def _run_local(plan: SweepPlan, chunks, workers, finished) -> None:
    if not chunks:
        return
    plan.prepare()
    if workers is None:
        workers = os.cpu_count() or 1
    workers = max(1, min(int(workers), len(chunks)))
    if plan.n_points < _PARALLEL_MIN_POINTS or not plan.fast:
        workers = 1          # full solves are serialised anyway
    if workers == 1:
        for chunk in chunks:
            finished(*plan.solve_chunk(chunk))
        return
    from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
    pool = ThreadPoolExecutor(max_workers=workers)
    try:
        pending = {pool.submit(plan.solve_chunk, c) for c in chunks}
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                finished(*fut.result())
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _client(scheduler):
    """``(client, created_here)`` for a scheduler address or an existing client."""
    try:
        from distributed import Client
    except ImportError:          # pragma: no cover - a runtime dependency
        raise CaseError("scheduler", "dask.distributed is not installed") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if not isinstance(scheduler, str) or "://" not in scheduler:
        raise CaseError("scheduler", f"{scheduler!r} must be an address like "
                                     f"tcp://HOST:PORT or a distributed.Client")
    try:
        return Client(scheduler, timeout="10s"), True
    except (OSError, TimeoutError, ValueError) as err:
        raise CaseError("scheduler", f"cannot connect to {scheduler}: {err}") from None


def _run_dask(client, plan: SweepPlan, chunks, finished) -> None:
    if not chunks:
        return
    from distributed import as_completed

    spec = plan.spec()
    key = _sha(spec)
    [spec_future] = client.scatter([spec], broadcast=True, hash=False)
    futures = [client.submit(_remote_chunk, key, spec_future, chunk, pure=False)
               for chunk in chunks]
    try:
        for fut in as_completed(futures):
            finished(*fut.result())
    finally:
        client.cancel(futures)


_REMOTE_PLANS: "OrderedDict[str, SweepPlan]" = OrderedDict()


def _remote_chunk(key: str, spec: dict, points):
    """A Dask task: the plan rebuilt from the case-file data (once per worker process),
    then the same chunk solver as a local run."""
    with _SOLVE_LOCK:
        plan = _REMOTE_PLANS.get(key)
        if plan is None:
            plan = _REMOTE_PLANS[key] = SweepPlan.from_spec(spec)
            while len(_REMOTE_PLANS) > 4:
                _REMOTE_PLANS.popitem(last=False)
    return plan.solve_chunk(points)


def _progress_bar(progress, total: int, initial: int):
    if not progress:
        return _NoBar()
    from tqdm import tqdm
    file = sys.stderr if progress is True else progress
    return tqdm(total=total, initial=initial, unit="pt", desc="sweep", file=file,
                mininterval=0.2, smoothing=0.1)


class _NoBar:
    def update(self, n: int) -> None:
        pass

    def close(self) -> None:
        pass
