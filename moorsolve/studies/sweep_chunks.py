"""Solving a chunk of sweep points: the compiled kernel where it certifies a stable point,
full solves for the rest, and the columns they fill."""

from __future__ import annotations


import math

import numpy as np

from ..errors import ConvergenceError
from ..physics.kinematics import wrap_degrees
from ..solve.cache import get_problem
from ..solve.diagnosis import over_mbl
from ..solve.equilibrium import solve, turn_jumps
from ..solve.prepared import line_facts
from ..solve.problem import LINE_COLUMNS
from ..solve.stability import _layout, assess

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
    :func:`~moorsolve.solve.stability.assess` reports it; NaN where it is not finite."""
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
    warning_free = _warning_free(problem)
    x_prev = x_rest.copy()
    for row, i in enumerate(points):
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
        if not warning_free and _may_warn_at(problem, kernel, x, p):
            continue            # the full solve words its warnings
        x_prev[:] = x
        table.done[row] = True
        table.stable[row] = True
        table.min_eigenvalue[row] = (minimum if not math.isnan(minimum)
                                     else _stiffness_minima(problem, K[None, :])[0])
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
    minima = _stiffness_minima(problem, out["stiffness"])
    if _has_body_nodes(problem):
        doubtful = np.flatnonzero(ok & ~(out["clearly_stable"][:, 0] > 0.5))
        for row in doubtful:
            stability = _stable(problem, x[row], vectors[points[row], :n_p])
            ok[row], minima[row] = stability.stable, stability.min_eigenvalue
    if not _warning_free(problem):
        for row in np.flatnonzero(ok):
            ok[row] = not _may_warn_at(problem, kernel, x[row], vectors[points[row], :n_p])
    rows = np.flatnonzero(ok)
    table.done[rows] = True
    table.stable[rows] = True
    table.min_eigenvalue[rows] = minima[rows]
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


def _stable(problem, x, p):
    """The :class:`~moorsolve.solve.result.Stability` of the kernel's point, which its own
    stability test did not call clearly stable: the full check
    (:func:`~moorsolve.solve.stability.assess`)."""
    with problem.lock:
        return assess(problem, x, p)


def _warning_free(problem) -> bool:
    """Whether no point of the scene can carry a Result warning (:func:`result_warnings`),
    from the case alone: one-segment lines of unsealed types that sink, every end at or
    below the water at the case pose, and no body or point that could lift one (free in
    heave, roll or pitch, or a free point). Else each kernel point is screened
    (:func:`_may_warn_at`)."""
    found = problem.derived.get("sweep_warning_free")
    if found is None:
        case = problem.case
        level = case.environment.water_level
        sinking = all(seg.line_type.weight_in_water > 0 for line in case.lines
                      for seg in line.segments)
        lifting = any(dof in ("heave", "roll", "pitch") for owner, _, dof in problem.nodes
                      if owner == "body") or any(owner != "body" for owner, _, _ in
                                                  problem.nodes)
        found = (problem.all_single and not line_facts(case).sealed and sinking
                 and not lifting and _ends_below(problem, level))
        problem.derived["sweep_warning_free"] = found
    return found


def _ends_below(problem, level: float) -> bool:
    """Whether every line end is at or below the water at the case pose (from a post at
    the closed-form start: end heights do not depend on the load when nothing lifts)."""
    from ..solve.start import initial_point
    post = problem.post(initial_point(problem, problem.case),
                        problem.parameters(problem.case, 0.0))
    table = np.asarray(post["lines"])
    cols = [LINE_COLUMNS.index(c) for c in ("az", "bz")]
    return bool(np.all(table.reshape(-1, table.shape[-1])[:, cols] <= min(0.0, level)))


def _may_warn_at(problem, kernel, x, p) -> bool:
    """Whether the kernel's point might carry a warning (a sealed line, line afloat, an
    end above the water): such a point is left for the full solve, which words them."""
    if line_facts(problem.case).sealed:
        return True
    post = kernel.post(x, p) if kernel.compiled else problem.post(x, p)
    table = np.asarray(post["lines"])
    cols = [LINE_COLUMNS.index(c) for c in ("floating", "az", "bz")]
    level = min(0.0, problem.case.environment.water_level)
    rows = table.reshape(-1, table.shape[-1])
    return bool((rows[:, cols[0]] > 0).any() or (rows[:, cols[1:]] > level).any())


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


