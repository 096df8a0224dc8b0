"""Many solves of one scene: a cartesian grid of case edits, one built problem for all.

``grid`` maps dotted case paths (:mod:`moorsolve.model.paths`) to lists of values. An axis
of plain numbers (or of lists of numbers: a force per value) is validated by column, as a
load table's columns are (:mod:`.load_table`); any other axis value is applied to the
case-file data and validated once (so units and field names work as in a case file). A key may also be a tuple of paths whose values are tuples, one value
per path: a *zipped* axis (``("environment.wind.toward_deg",
"environment.current.toward_deg"): [(0, 0), (15, 15), ...]`` turns wind and current
together). When every edit only changes problem parameters (loads, headings, speeds,
anchors, lengths, weights, stiffness, friction, breaking loads) and different axes change
different parameters, the grid's parameter matrix is assembled by indexing and the points
are solved by the compiled Newton kernel, each warm-started from its neighbour: the grid
is walked in a snake order (consecutive points differ in one index by one). A point whose
loads are nearer to none than to its neighbour's (a list of unrelated load cases) starts
from the rest state instead, batched as a load table's rows are.

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

from collections.abc import Mapping

import numpy as np

from ..model import Case
from .sweep_chunks import TEXT_COLUMNS, _Table
from .sweep_plan import SweepPlan
from .sweep_run import _client, _progress_bar, _run_dask, _run_local




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
        joined = np.concatenate([np.asarray(c[name], dtype=object if name in TEXT_COLUMNS
                                            else None) for _, c in frames])
        columns[name] = joined[order] if name not in TEXT_COLUMNS \
            else [str(v) for v in joined[order]]
    return plan.frame(points[order], columns)


