"""Solving a chunk of sweep points: the compiled kernel where it certifies a stable point,
full solves for the rest, and the columns they fill."""

from __future__ import annotations


import math

import numpy as np

from ..errors import ConvergenceError
from ..physics.kinematics import wrap_degrees
from ..solve.assembly.cache import get_problem
from ..solve.contact.results import OVER_RATED
from ..solve.result.diagnosis import over_mbl, over_rated
from ..solve.equilibrium import solve, turn_jumps
from ..solve.stability.static import _layout, assess
from .sweep_warnings import NONE, POSE, POST, screen

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
        #: Stability of each point: stable, the smallest eigenvalue's real part of the
        #: homogenised stiffness [N/m], and the Result's warnings as one text.
        self.stable = np.zeros(n, bool)
        self.min_eigenvalue = np.full(n, np.nan)
        self.warnings = [""] * n

    def from_result(self, i: int, result, reason: str = "", converged=None) -> None:
        c = result.certificate
        self.done[i] = True
        self.converged[i] = not reason if converged is None else converged
        self.reason[i], self.solver[i] = reason, result.solver
        self.iterations[i] = c.iterations
        self.residual[i] = (c.force_N, c.moment_Nm, c.relative)
        stability = result.stability
        if stability is not None:
            self.stable[i] = stability.stable
            self.min_eigenvalue[i] = stability.min_eigenvalue
            if not stability.stable:
                # Certified but unstable: never a clean row.
                self.reason[i] = "; ".join(filter(None, (unstable_reason(stability), reason)))
        self.warnings[i] = "; ".join(w["message"] for w in result.warnings)
        if result.body is not None:
            self.body[i] = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
        for k, b in enumerate(result.bodies[:len(self.bodies)]):
            self.poses[i, 6 * k: 6 * k + 6] = [b[f] for f in _POSE_FIELDS]
        self.t_fair[i] = [leg.fairlead_tension_N for leg in result.legs]
        self.t_anchor[i] = [leg.anchor_tension_N for leg in result.legs]
        self.reactions[i] = ([f["reaction_N"] for f in result.fenders]
                             + [g["reaction_N"] for g in result.guides])

    def put(self, rows, part: "_Table") -> None:
        """Copy every row of ``part`` (a table of ``len(rows)`` points) to ``rows``."""
        for name, value in vars(part).items():
            if isinstance(value, np.ndarray):
                getattr(self, name)[rows] = value
            elif isinstance(value, list) and name not in ("names", "contacts"):
                mine = getattr(self, name)
                for k, row in enumerate(rows.tolist()):
                    mine[row] = value[k]

    def columns(self) -> dict:
        out = {"converged": self.converged, "reason": self.reason, "stable": self.stable,
               "min_eigenvalue": self.min_eigenvalue, "warnings": self.warnings,
               "solver": self.solver, "iterations": self.iterations, "residual_N": self.residual[:, 0],
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


#: Text columns of a sweep's table.
TEXT_COLUMNS = ("reason", "warnings", "solver")


def unstable_reason(stability) -> str:
    """The reason column of a certified but unstable equilibrium."""
    where = ", ".join(stability.unstable_dofs) or "a coupled mode"
    return (f"unstable equilibrium (unstable in {where}): no stable equilibrium was found; "
            "a small disturbance moves the body away from it")


def _stiffness_minima(problem, K: np.ndarray) -> np.ndarray:
    """The smallest real part of the eigenvalues of each row's homogenised condensed
    stiffness (the kernel's ``stiffness`` output, one flattened matrix a row) [N/m], as
    :func:`~moorsolve.solve.stability.static.assess` reports it; NaN where it is not finite."""
    hh = _layout(problem)[4]
    n = hh.shape[0]
    out = np.full(len(K), np.nan)
    if n == 0:
        out[:] = np.inf
        return out
    # CasADi's vec is column-major: the transpose of numpy's row-major reshape.
    mats = np.asarray(K, dtype=float).reshape(len(K), n, n).transpose(0, 2, 1) * hh
    finite = np.isfinite(mats).all(axis=(1, 2))
    if finite.any():
        out[finite] = np.linalg.eigvals(mats[finite]).real.min(axis=1)
    return out


def _kernel_pool(problem):
    return problem.kernel_pool()


def _solve_fast(problem, kernel, x_rest, vectors, points, table, tol, has_body,
                allow_overload=False, from_rest=False, rest=None):
    """The kernel at every point: from the previous point's solution (a grid's snake), or
    with ``from_rest`` from the rest state as a single solve starts (a load table's rows,
    which need not be neighbours: run as one batch, :func:`_solve_rows`). A point that
    does not certify, is not clearly stable or (from rest) turns a body far is left for a
    full solve.

    ``rest``, ``(x, load mask, base vector)``: a grid point whose loads are nearer to
    none than to the previous point's (a list of unrelated load cases on one axis), and
    whose other parameters are the base case's, starts from the rest state ``x`` instead
    (:func:`_nearer_rest`)."""
    if from_rest:
        _solve_rows(problem, kernel, x_rest, vectors, points, table, tol, has_body,
                    allow_overload)
        return
    n_p = problem.n_p
    use_rest = (_nearer_rest(vectors[np.asarray(points), :n_p], rest[1], rest[2])
                if rest is not None else np.zeros(len(points), bool))
    x_from_rest = None
    if use_rest.any():
        # Those points start as a load table's rows do: one batch from the rest state.
        batch = np.flatnonzero(use_rest)
        part = _Table(len(batch), table.names, table.bodies, table.contacts)
        x_from_rest = np.full((len(points), rest[0].size), np.nan)
        x_from_rest[batch] = _solve_rows(problem, kernel, rest[0], vectors,
                                         np.asarray(points)[batch], part, tol, has_body,
                                         allow_overload)
        table.put(batch, part)
    # A certified point may be an unstable equilibrium (a ship turned stern to the wind).
    check_stability = _has_body_nodes(problem)
    x_prev = x_rest.copy()
    stiffness = None
    states = np.full((len(points), x_rest.size), np.nan) if screen(problem).mode == POST \
        else None
    for row, i in enumerate(points):
        if use_rest[row]:
            if table.done[row]:
                x_prev[:] = x_from_rest[row]
                if states is not None:
                    states[row] = x_prev
            continue
        p = vectors[i, :n_p]
        x, _, iterations, cert, body, tf, ta, reactions, stable, K = kernel.raw(x_prev, p,
                                                                                tol)
        ok, force, moment, relative = problem.judge(*cert, tol=tol)
        if not ok:
            continue            # left for the full solve
        minimum = math.nan
        if check_stability and not stable[0] > 0.5:
            stability = _stable(problem, x, p)
            if not stability.stable:
                continue        # the full solve looks for the stable equilibrium
            minimum = stability.min_eigenvalue
        x_prev[:] = x
        if states is not None:
            states[row] = x
        table.done[row] = True
        table.stable[row] = True
        if math.isnan(minimum):
            if stiffness is None:
                stiffness = np.full((len(points), K.size), np.nan)
            stiffness[row] = K      # its eigenvalues below, all rows in one call
        else:
            table.min_eigenvalue[row] = minimum
        table.iterations[row] = iterations[0]
        table.residual[row] = (force, moment, relative)
        _record(table, [row], body[None, :], tf[None, :], ta[None, :], reactions[None, :],
                vectors[i:i + 1, n_p:], has_body, allow_overload)
    if stiffness is not None:
        rows = np.flatnonzero(np.isfinite(stiffness).all(axis=1))
        table.min_eigenvalue[rows] = _stiffness_minima(problem, stiffness[rows])
    _leave_warnings(problem, kernel, table, states, vectors[np.asarray(points), :n_p])


def _nearer_rest(P, loads, base) -> np.ndarray:
    """Per row of parameters ``P`` (a chunk in its walking order), whether its load entries
    (mask ``loads``) are nearer to none than to the previous row's, each entry measured in
    its largest size over the chunk, and its other entries are those of ``base`` (the
    rest state is the base geometry's). Depends on the chunk alone, so every run of a
    sweep starts each point alike."""
    out = np.zeros(len(P), bool)
    if len(P) < 2 or not loads.any():
        return out
    L = P[:, loads]
    size = np.abs(L).max(axis=0)
    size[size == 0] = 1.0
    L = L / size
    to_rest = np.linalg.norm(L[1:], axis=1)
    to_previous = np.linalg.norm(L[1:] - L[:-1], axis=1)
    same_geometry = (P[:, ~loads] == base[~loads]).all(axis=1)
    out[1:] = (to_rest < to_previous) & same_geometry[1:]
    return out


def _poses(table, rows) -> np.ndarray:
    """The kernel's ``body`` output of ``rows`` rebuilt from the table (first-body
    offsets, then every body's pose, m and rad), for :class:`.sweep_warnings.WarningScreen`."""
    poses = table.poses[rows].reshape(len(rows), -1, 6).copy()
    poses[:, :, 3:] = np.radians(poses[:, :, 3:])
    return np.column_stack([np.zeros((len(rows), 3)), poses.reshape(len(rows), -1)])


def _leave_warnings(problem, kernel, table, X, P) -> None:
    """Hand the rows the kernel solved (points ``X`` where kept, parameters ``P``, a row
    each) that might carry a warning to the full solve, which words them
    (:mod:`.sweep_warnings`)."""
    check = screen(problem)
    rows = np.flatnonzero(table.done[:len(P)])
    if check.mode == NONE or len(rows) == 0:
        return
    flagged = rows[check.rows(kernel, None if X is None else X[rows], P[rows],
                              _poses(table, rows) if check.mode == POSE else None)]
    table.done[flagged] = False
    table.stable[flagged] = False
    table.min_eigenvalue[flagged] = np.nan


def _solve_rows(problem, kernel, x_rest, vectors, points, table, tol, has_body,
                allow_overload):
    """:func:`_solve_fast` for a load table: the kernel from the rest state at every row
    in one batch (:meth:`~moorsolve.solve.kernels.newton.NewtonKernel.run_many`), judged and
    recorded as arrays. A row is kept when it certifies, no angle turned
    further than a single solve's Newton step takes (:func:`turn_jumps`), and the kernel's
    stability test passes (else the full check, :func:`_stable`)."""
    n_p = problem.n_p
    out = kernel.run_many(x_rest, vectors[points, :n_p], tol)
    x = out["x"]
    ok, force, moment, relative = problem.judge_rows(out["certificate"], tol)
    ok &= np.isfinite(x).all(axis=1) & ~turn_jumps(problem, x_rest, x)
    minima = _stiffness_minima(problem, out["stiffness"])
    if _has_body_nodes(problem):
        doubtful = np.flatnonzero(ok & ~(out["clearly_stable"][:, 0] > 0.5))
        for row in doubtful:
            stability = _stable(problem, x[row], vectors[points[row], :n_p])
            ok[row], minima[row] = stability.stable, stability.min_eigenvalue
    check = screen(problem)
    if check.mode != NONE:
        kept = np.flatnonzero(ok)
        ok[kept] = ~check.rows(kernel, x[kept], vectors[points[kept], :n_p], out["body"][kept])
    rows = np.flatnonzero(ok)
    table.done[rows] = True
    table.stable[rows] = True
    table.min_eigenvalue[rows] = minima[rows]
    table.iterations[rows] = out["iterations"][rows, 0]
    table.residual[rows] = np.column_stack([force, moment, relative])[rows]
    _record(table, rows, out["body"][rows], out["fairlead_tension"][rows],
            out["anchor_tension"][rows], out["reactions"][rows],
            vectors[points[rows], n_p:], has_body, allow_overload)
    return x


def _record(table, rows, body, tf, ta, reactions, limits, has_body, allow_overload) -> None:
    """Write the kernel's outputs of certified ``rows`` (arrays with one row each) into
    ``table``: body pose, tensions, reactions, and an overload against ``limits`` (each
    line's MBL, then each fender's reaction at its rated deflection,
    :func:`.sweep_grid.rated_reactions`)."""
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
    n = len(table.names)
    mbl, rated = limits[:, :n], limits[:, n:]
    over = np.maximum(tf, ta) > mbl
    crushed = reactions > rated * (1.0 + OVER_RATED)
    table.converged[rows] = allow_overload | ~(over.any(axis=1) | crushed.any(axis=1))
    for k in np.flatnonzero(over.any(axis=1) | crushed.any(axis=1)).tolist():
        row = int(rows[k])
        table.reason[row] = "overload: " + "; ".join(
            [f"leg {table.names[j]} would break: tension "
             f"{max(tf[k, j], ta[k, j]) / 1e3:.1f} kN > MBL {mbl[k, j] / 1e3:.1f} kN"
             for j in np.flatnonzero(over[k])]
            + [f"fender {table.contacts[j]} is past its rated deflection: reaction "
               f"{reactions[k, j] / 1e3:.1f} kN > {rated[k, j] / 1e3:.1f} kN at the rating"
               for j in np.flatnonzero(crushed[k])])


def _has_body_nodes(problem) -> bool:
    return any(owner == "body" for owner, _, _ in problem.nodes)


def _overload(result) -> str:
    """The overload of an equilibrium accepted with ``allow_overload`` (else "")."""
    over = over_mbl(result) + over_rated(result)
    return "overload: " + "; ".join(over) if over else ""


def _stable(problem, x, p):
    """The :class:`~moorsolve.solve.result.classes.Stability` of the kernel's point, which its own
    stability test did not call clearly stable: the full check
    (:func:`~moorsolve.solve.stability.static.assess`)."""
    with problem.lock:
        return assess(problem, x, p)


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


