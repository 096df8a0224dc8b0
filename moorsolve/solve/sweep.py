"""Many solves of one scene: a cartesian grid of case edits, one built problem for all.

``grid`` maps dotted case paths (:mod:`moorsolve.io.paths`) to lists of values. Each axis
value is applied to the case-file data and validated once (so units and field names work
as in a case file). When every edit only changes problem parameters (loads, headings,
speeds, anchors, lengths, weights, stiffness, friction, breaking loads) and different axes
change different parameters, the grid's parameter matrix is assembled by indexing and the
points are solved by the compiled Newton kernel, each warm-started from its neighbour: the
grid is walked in a snake order (consecutive points differ in one index by one), split
into one contiguous run per worker thread. The kernel releases the GIL, so threads use
separate cores.

A point the kernel does not certify is re-solved by :func:`moorsolve.solve` with IPOPT
(rest state and load stepping included); a point with no equilibrium becomes a row with
``converged = False`` and the reason, never an abort. Edits that change the problem's
structure (adding wind, changing a drag area or the gravity) fall back to one full solve
per point, still warm-started where the structure allows.
"""

from __future__ import annotations

import itertools
import math
import os
import threading
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import CaseError, ConvergenceError
from ..model import Case
from .equilibrium import get_problem, initial_point, solve
from .problem import parameter_vector, structure_key

_PARALLEL_MIN_POINTS = 64


def sweep(case: Case, grid: Mapping[str, Sequence], *, solver: str = "newton",
          tol: float | None = None, workers: int | None = None):
    """Solve ``case`` at every point of the cartesian product of ``grid``.

    Parameters
    ----------
    case : Case
        From :func:`moorsolve.load_case` (the sweep edits the case-file data it came from).
    grid : mapping of str to sequence
        Dotted case path (``"environment.wind.toward_deg"``, ``"body.loads.force"``,
        ``"legs[*].segments[0].length"``) to the values it takes; each value is what the
        case file would hold at that path (a number, a list, or a string with a unit).
    solver : {"newton", "ipopt"}
        ``"newton"`` (default): the compiled fast path, IPOPT for points it cannot
        certify. ``"ipopt"``: every point by :func:`moorsolve.solve` with IPOPT.
    tol : float, optional
        Certified relative force residual; defaults to the case's ``solver.tol``.
    workers : int, optional
        Threads for the fast path; defaults to the number of cores (at most 2 below
        64 points: one).

    Returns
    -------
    pandas.DataFrame
        One row per point in the product order of ``grid``: the grid values, then
        ``converged``, ``reason``, ``solver``, ``iterations``, ``residual_N``,
        ``residual_Nm``, ``residual_relative``, ``x_m``, ``y_m``, ``yaw_deg`` and, per
        leg, ``<name>.fairlead_tension_N`` and ``<name>.anchor_tension_N``.
    """
    import pandas as pd

    from ..io import load_case
    from ..io.paths import parse_path, with_values

    if solver not in ("newton", "ipopt"):
        raise ValueError(f"solver {solver!r}: must be 'newton' or 'ipopt'")
    if case.source is None:
        raise CaseError("case", "a sweep edits the case-file data; load the case with "
                                "moorsolve.load_case (from a file or a dict)")
    axes = _axes(grid, parse_path)
    tol = case.solver.tol if tol is None else tol
    shape = tuple(len(values) for _, values in axes)
    n_points = math.prod(shape)

    # Each axis value validated once, as a case of its own.
    axis_cases = []
    for path, values in axes:
        cases = []
        for value in values:
            try:
                cases.append(load_case(with_values(case.source, {path: value}), keep_source=False))
            except CaseError as err:
                raise CaseError(f"grid[{path!r}]", f"value {value!r}: {err}") from None
        axis_cases.append(cases)

    base_key = structure_key(case)
    base_vec = _point_vector(case)
    masks = []
    fast = solver == "newton" and all(
        structure_key(c) == base_key for cases in axis_cases for c in cases)
    if fast:
        for cases in axis_cases:
            vecs = np.array([_point_vector(c) for c in cases])
            masks.append(np.any(vecs != base_vec, axis=0))
        used = np.zeros_like(base_vec, dtype=bool)
        for m in masks:
            fast &= not np.any(used & m)
            used |= m

    def point_case(index):
        edits = {path: values[i] for (path, values), i in zip(axes, index)}
        return load_case(with_values(case.source, edits), keep_source=False)

    indices = list(itertools.product(*[range(n) for n in shape]))
    table = _Table(n_points, [leg.name for leg in case.legs])
    if fast:
        vectors = np.empty((n_points, base_vec.size))
        vectors[:] = base_vec
        index_array = np.array(indices, dtype=int).reshape(n_points, len(axes))
        for k, (cases, mask) in enumerate(zip(axis_cases, masks)):
            vecs = np.array([_point_vector(c) for c in cases])
            vectors[:, mask] = vecs[index_array[:, k]][:, mask]
        _solve_fast(case, vectors, shape, table, tol, workers)
        retry = np.flatnonzero(~table.done).tolist()
    else:
        retry = list(range(n_points))
    _solve_each(retry, indices, table, point_case, tol)

    columns = {}
    for k, (path, values) in enumerate(axes):
        columns[path] = [values[idx[k]] for idx in indices]
    columns.update(table.columns())
    return pd.DataFrame(columns)


def _axes(grid, parse_path) -> list[tuple[str, list]]:
    if not isinstance(grid, Mapping) or not grid:
        raise CaseError("grid", "must be a non-empty mapping of case paths to lists of values")
    axes = []
    for path, values in grid.items():
        parse_path(path)
        if isinstance(values, (str, bytes, Mapping)) or not isinstance(
                values, (Sequence, np.ndarray)):
            raise CaseError(f"grid[{path!r}]", f"{values!r} must be a list of values")
        values = list(values.tolist() if isinstance(values, np.ndarray) else values)
        if not values:
            raise CaseError(f"grid[{path!r}]", "the list of values is empty")
        axes.append((path, values))
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


class _Table:
    """The sweep's results, one array per column, filled by point index."""

    def __init__(self, n: int, names: list[str]):
        self.names = names
        self.done = np.zeros(n, bool)
        self.converged = np.zeros(n, bool)
        self.reason = [""] * n
        self.solver = [""] * n
        self.iterations = np.zeros(n, int)
        self.residual = np.full((n, 3), np.nan)      # force, moment, relative
        self.body = np.full((n, 3), np.nan)
        self.t_fair = np.full((n, len(names)), np.nan)
        self.t_anchor = np.full((n, len(names)), np.nan)

    def from_result(self, i: int, result, reason: str = "") -> None:
        c = result.certificate
        self.done[i] = True
        self.converged[i] = not reason
        self.reason[i], self.solver[i] = reason, result.solver
        self.iterations[i] = c.iterations
        self.residual[i] = (c.force_N, c.moment_Nm, c.relative)
        if result.body is not None:
            self.body[i] = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
        self.t_fair[i] = [leg.fairlead_tension_N for leg in result.legs]
        self.t_anchor[i] = [leg.anchor_tension_N for leg in result.legs]

    def columns(self) -> dict:
        out = {"converged": self.converged, "reason": self.reason, "solver": self.solver,
               "iterations": self.iterations, "residual_N": self.residual[:, 0],
               "residual_Nm": self.residual[:, 1], "residual_relative": self.residual[:, 2],
               "x_m": self.body[:, 0], "y_m": self.body[:, 1], "yaw_deg": self.body[:, 2]}
        for k, name in enumerate(self.names):
            out[f"{name}.fairlead_tension_N"] = self.t_fair[:, k]
            out[f"{name}.anchor_tension_N"] = self.t_anchor[:, k]
        return out


def _solve_fast(case, vectors, shape, table, tol, workers):
    problem = get_problem(case)
    kernel = problem.newton()
    n_p = problem.n_p
    order = [int(np.ravel_multi_index(idx, shape)) for idx in snake_order(shape)]
    if workers is None:
        workers = os.cpu_count() or 1
    workers = max(1, min(int(workers), len(order)))
    if len(order) < _PARALLEL_MIN_POINTS:
        workers = 1
    x_rest = initial_point(problem, case)
    has_body = case.body is not None
    bounds = np.linspace(0, len(order), workers + 1).astype(int)
    chunks = [order[a:b] for a, b in zip(bounds[:-1], bounds[1:])]

    def run(chunk, kern):
        x_prev = x_rest.copy()
        for i in chunk:
            x, _, iterations, cert, body, tf, ta = kern.raw(x_prev, vectors[i, :n_p], tol)
            ok, force, moment, relative = problem.judge(cert[0], cert[1], cert[2], tol)
            if not ok:
                continue            # left for the IPOPT pass
            x_prev[:] = x
            mbl = vectors[i, n_p:]
            over = np.maximum(tf, ta) > mbl
            table.done[i] = True
            table.converged[i] = not over.any()
            table.solver[i] = "newton"
            table.iterations[i] = iterations[0]
            table.residual[i] = (force, moment, relative)
            if has_body:
                table.body[i] = (body[0], body[1], math.degrees(body[2]))
            table.t_fair[i], table.t_anchor[i] = tf, ta
            if over.any():
                table.reason[i] = "overload: " + "; ".join(
                    f"leg {table.names[k]} would break: tension "
                    f"{max(tf[k], ta[k]) / 1e3:.1f} kN > MBL {mbl[k] / 1e3:.1f} kN"
                    for k in np.flatnonzero(over))

    kernels = [kernel] + [kernel.clone() for _ in range(len(chunks) - 1)]
    if len(chunks) == 1:
        run(chunks[0], kernels[0])
        return
    threads = [threading.Thread(target=run, args=(c, k)) for c, k in zip(chunks, kernels)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()


def _solve_each(todo, indices, table, point_case, tol):
    """Full solves (IPOPT strategy), warm-started while the structure stays the same."""
    previous = {}
    for i in todo:
        pc = point_case(indices[i])
        key = id(get_problem(pc))        # a state is only meaningful to its own problem
        try:
            result = solve(pc, tol=tol, solver="ipopt", start=previous.get(key))
        except ConvergenceError as err:
            if err.result is not None and err.result.converged:
                table.from_result(i, err.result, reason=err.reason)   # e.g. overload
            else:
                table.done[i] = True
                table.reason[i], table.solver[i] = err.reason, "ipopt"
                table.iterations[i] = err.iterations
                table.residual[i, :2] = (err.residual_N, err.residual_Nm)
            continue
        previous[key] = result.state
        table.from_result(i, result)
