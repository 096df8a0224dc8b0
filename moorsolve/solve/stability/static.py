"""Static stability of an equilibrium, and the search for a stable one.

The total tangent stiffness of the free body degrees of freedom is ``K = -dQ/dq``, with
``Q`` the generalized forces of :mod:`.problem` (mooring, weight, hydrostatics, springs and
the load models' own dependence on position and heading: wind and current drag turn with
the body) and every line unknown and free point condensed out (they follow the bodies):
``K = -(J_qq - J_qr J_rr^-1 J_rq)`` from the Jacobian of the residuals.
``K`` need not be symmetric. The equilibrium is statically stable when every
eigenvalue has a positive real part. Rotations are measured as arc length at the scene's
moment arm ``L`` (``moment_scale / force_scale``) so that every entry is a stiffness in N/m
and the eigenvalues compare.

A zero eigenvalue is decided by the restoring force at finite perturbations along its mode,
on both sides: restoring on both sides is stable (a drag yaw moment
that grows with the square of the angle); zero on both sides is neutral (a degree of freedom
nothing restrains nor loads, e.g. the yaw of a body whose lines all meet at one point and on
which no load turns: it keeps its given value); pushing away on either side is unstable.

Where the equilibrium found is unstable, :func:`find_stable` follows the scene's own
overdamped motion from small perturbations along each unstable mode (pseudo-transient
continuation: implicit Euler steps of ``q' = Q(q)`` with the lines in equilibrium at every
step, the step growing as the residual falls), which converges to stable equilibria only,
and then from turned starts (a weathervaning ship may need to turn half round).
"""

from __future__ import annotations

import math

import time

import numpy as np
import scipy.sparse as sps

from ..kernels.sparse_stiffness import (clearly_positive, sparse_condensed_stiffness,
                                       uses_sparse_path)
from ..result.classes import DeferredStability, Stability

#: A mode whose eigenvalue is below this fraction of the largest is examined as zero.
_ZERO = 1e-7
#: Finite perturbations [fraction of the moment arm L] used to decide zero modes.
_PROBES = (1e-3, 1e-2)


def _layout(problem) -> tuple:
    """``(keep, rest, h, names, hh)`` of ``problem`` (``hh`` the homogenising factors'
    outer product, inverted), worked out once and kept in ``problem.derived``."""
    found = problem.derived.get("stability")
    if found is None:
        keep = [j for j, (owner, _, _) in enumerate(problem.nodes) if owner == "body"]
        kept = set(keep)
        rest = [j for j in range(problem.n_x) if j not in kept]
        keep, rest = np.array(keep, dtype=int), np.array(rest, dtype=int)
        h = homogenising(problem, keep)
        found = (keep, rest, h, tuple(_dof_names(problem, keep)), 1.0 / np.outer(h, h))
        problem.derived["stability"] = found
    return found


def _split(problem):
    """Indices of the body unknowns (kept) and of everything condensed out."""
    return _layout(problem)[:2]


def _rows(problem, cols):
    """Residual rows that balance the unknowns ``cols``: lines' rows pair with the lines'
    unknowns (they come first), node rows with node unknowns."""
    n_line_rows = problem.n_x - problem.n_q
    out = []
    for j in cols:
        if j < problem.n_q:
            out.append(n_line_rows + j)
        else:
            out.append(j - problem.n_q)
    return np.array(out, dtype=int)


def homogenising(problem, keep) -> np.ndarray:
    """Per kept unknown: the factor turning it into metres (1 or the moment arm L)."""
    arm = problem.moment_scale / problem.force_scale
    return np.array([arm if problem.rotational[j] else 1.0 for j in keep])


def condensed_stiffness(problem, x, p) -> tuple:
    """``(K, keep)``: the tangent stiffness ``-dQ/dq`` [SI] of the free body DOFs at the
    scaled point ``x``, lines and free points condensed out, and the kept unknowns."""
    keep, rest = _split(problem)
    if uses_sparse_path(problem):
        try:
            return _sparse_condensed(problem, x, p).toarray(), keep
        except RuntimeError:        # a singular condensed block: least squares below
            pass
    J = np.asarray(problem.jacobian(x, p))
    rq, rr = _rows(problem, keep), _rows(problem, rest)
    A = J[np.ix_(rq, keep)]
    if rest.size:
        B = J[np.ix_(rq, rest)]
        C = J[np.ix_(rr, keep)]
        D = J[np.ix_(rr, rest)]
        A = A - B @ np.linalg.lstsq(D, C, rcond=None)[0]
    row_scale = np.array([problem.moment_scale if problem.rotational[j]
                          else problem.force_scale for j in keep])
    K = -(row_scale[:, None] * A) / problem.x_scale[keep][None, :]
    return K, keep


def _sparse_condensed(problem, x, p):
    """:func:`condensed_stiffness` as a sparse matrix (:mod:`.sparse_stiffness`)."""
    keep, rest = _split(problem)
    rows = problem.derived.get("stability_rows")
    if rows is None:
        rows = problem.derived["stability_rows"] = (_rows(problem, keep), _rows(problem, rest))
    return sparse_condensed_stiffness(problem, x, p, keep, rest, *rows)


def stiffness_modes(problem, x, p) -> tuple:
    """``(values, vectors, keep)``: eigenvalues and modes (columns, over the kept body DOFs)
    of the homogenised tangent stiffness at ``x``.

    Where the scene has complementarities (hawsers, contacts) an active rigid contact or a
    taut inextensible hawser is a constraint: the condensed block is singular and the
    stiffness infinite across the constraint. The eigenvalues are then the finite ones of
    the pencil ``(A, B)`` (``A`` the homogenised Jacobian of bodies and condensed unknowns,
    ``B`` the identity on the bodies' rows): the stiffness along the directions the
    constraints allow. Without constraints it is ``eig(K)`` either way.
    """
    keep, rest = _split(problem)
    h = homogenising(problem, keep)
    if not problem.smoothed or rest.size == 0:
        K, keep = condensed_stiffness(problem, x, p)
        values, vectors = np.linalg.eig(K / h[None, :] / h[:, None])
        return values, vectors, keep
    from scipy.linalg import eig
    J = np.asarray(problem.jacobian(x, p))
    rq, rr = _rows(problem, keep), _rows(problem, rest)
    row_scale = np.array([problem.moment_scale if problem.rotational[j]
                          else problem.force_scale for j in keep]) / h
    col_scale = problem.x_scale[keep] * h
    n = keep.size
    A = np.block([[-row_scale[:, None] * J[np.ix_(rq, keep)] / col_scale[None, :],
                   -row_scale[:, None] * J[np.ix_(rq, rest)]],
                  [J[np.ix_(rr, keep)] / col_scale[None, :], J[np.ix_(rr, rest)]]])
    B = np.zeros_like(A)
    B[:n, :n] = np.eye(n)
    values, vectors = eig(A, B)
    # The constrained directions' eigenvalues are infinite; in floating point some come out
    # finite but enormous (1e27 where the stiffnesses are 1e6).
    bound = 1e6 * max(float(np.max(np.abs(A))), problem.contact_stiffness)
    finite = np.isfinite(values) & (np.abs(values) < bound)
    values, vectors = values[finite], vectors[:n, finite]
    return values, vectors, keep


def stiffness_graph(problem, J):
    """:func:`condensed_stiffness` as a CasADi expression of the Jacobian ``J`` (MX): the
    condensed unknowns eliminated by a sparse QR solve, so the compiled kernel returns the
    stiffness with the equilibrium. Non-finite where the condensed block is singular (the
    caller then uses :func:`condensed_stiffness`)."""
    import casadi as ca

    keep, rest = _split(problem)
    if keep.size == 0:
        return ca.MX(0, 0)
    rq, rr = _rows(problem, keep).tolist(), _rows(problem, rest).tolist()
    keep_l, rest_l = keep.tolist(), rest.tolist()
    A = J[rq, keep_l]
    if rest.size:
        A = A - J[rq, rest_l] @ ca.solve(J[rr, rest_l], J[rr, keep_l], "qr")
    row_scale = np.array([problem.moment_scale if problem.rotational[j]
                          else problem.force_scale for j in keep])
    return ca.densify(-(ca.DM(np.diag(row_scale)) @ A) @ ca.DM(np.diag(
        1.0 / problem.x_scale[keep])))


#: Most kept DOFs for which the compiled kernel decides "clearly stable" itself.
_GRAPH_TEST_DOFS = 24


def clearly_stable_graph(problem, K):
    """1 where the condensed stiffness ``K`` (MX, SI) is clearly stable, else 0: a test
    the compiled kernel runs with the equilibrium, so that :func:`assess` computes no
    eigenvalues for the usual point.

    With ``Kh`` the homogenised stiffness and ``S`` its symmetric part, every eigenvalue
    ``lambda`` of ``Kh`` has ``Re lambda >= lambda_min(S)`` (the field of values), and
    ``|lambda| <= ||Kh||_F``. So when ``S - c I`` has a Cholesky factor for
    ``c = _ZERO ||Kh||_F``, every eigenvalue has a positive real part and a size above
    ``_ZERO`` times the largest: exactly the case :func:`assess` calls stable without
    further examination. The test is one-sided (a strongly non-symmetric stiffness may be
    stable and fail it; :func:`assess` then decides), and 0 for a non-finite ``K``.
    """
    import casadi as ca

    keep, _, _, _, hh = _layout(problem)
    n = keep.size
    if n == 0 or n > _GRAPH_TEST_DOFS:
        return ca.MX(0)
    k = ca.SX.sym("K", n, n)
    kh = k * ca.DM(hh)
    c = _ZERO * ca.sqrt(ca.sumsqr(kh))
    S = (kh + kh.T) / 2 - c * ca.SX.eye(n)
    L = [[None] * n for _ in range(n)]
    pivots = []
    for i in range(n):
        for j in range(i + 1):
            acc = S[i, j] - sum((L[i][m] * L[j][m] for m in range(j)), ca.SX(0))
            if i == j:
                pivots.append(acc)
                L[i][i] = ca.sqrt(ca.fmax(acc, 1e-300))
            else:
                L[i][j] = acc / L[j][j]
    flag = ca.mmin(ca.vertcat(*pivots)) > 0
    return ca.Function("clearly_stable", [k], [flag])(K)


def _dof_names(problem, keep) -> list:
    names = []
    for j in keep:
        _, index, dof = problem.nodes[j]
        names.append(f"{problem.case.bodies[index].name}.{dof}")
    return names


def _settle(problem, x, p, keep, iterations: int = 30):
    """Solve the condensed unknowns (lines, points) with the bodies held: Newton on those
    rows only. Returns the point and whether it settled."""
    keep_set = set(keep.tolist())
    rest = np.array([j for j in range(problem.n_x) if j not in keep_set], dtype=int)
    rr = _rows(problem, rest)
    lb, ub = problem.bounds()
    x = x.copy()
    for _ in range(iterations):
        g = np.asarray(problem.residual(x, p)).ravel()
        gr = g[rr]
        if np.max(np.abs(gr), initial=0.0) < 1e-13:
            return x, True
        J = np.asarray(problem.jacobian(x, p))[np.ix_(rr, rest)]
        step = np.linalg.lstsq(J, gr, rcond=None)[0]
        norm0 = np.max(np.abs(gr))
        alpha, moved = 1.0, False
        for _ in range(12):
            trial = x.copy()
            trial[rest] = np.clip(x[rest] - alpha * step, lb[rest], ub[rest])
            gt = np.asarray(problem.residual(trial, p)).ravel()[rr]
            if np.all(np.isfinite(gt)) and np.max(np.abs(gt)) < norm0:
                x, moved = trial, True
                break
            alpha *= 0.5
        if not moved:
            break
    g = np.asarray(problem.residual(x, p)).ravel()[rr]
    return x, bool(np.max(np.abs(g), initial=0.0) < 1e-9)


def _restoring(problem, x, p, keep, mode) -> list:
    """The generalized force along ``mode`` (homogenised) after moving the bodies by each
    probe along it, both ways: negative is restoring. ``None`` where the lines would not
    settle."""
    h = homogenising(problem, keep)
    arm = problem.moment_scale / problem.force_scale
    rq = _rows(problem, keep)
    row_scale = np.array([problem.moment_scale if problem.rotational[j]
                          else problem.force_scale for j in keep])
    out = []
    for probe in _PROBES:
        for sign in (1.0, -1.0):
            trial = x.copy()
            # Move the physical unknowns by probe * L along the mode (metres).
            trial[keep] = x[keep] + sign * probe * arm * mode / h / problem.x_scale[keep]
            trial, ok = _settle(problem, trial, p, keep)
            if not ok:
                out.append(None)
                continue
            Q = np.asarray(problem.residual(trial, p)).ravel()[rq] * row_scale / h
            out.append(float(sign * mode @ Q))
    return out


def assess(problem, x, p, stiffness=None, clearly_stable=False) -> Stability:
    """The :class:`Stability` of the scaled point ``x`` (an equilibrium of ``problem``).

    ``stiffness``, the condensed stiffness at ``x`` if the caller has it (the compiled
    kernel returns it, :func:`stiffness_graph`), saves recomputing it, and
    ``clearly_stable``, the kernel's test of it (:func:`clearly_stable_graph`), saves its
    eigenvalues until they are read. Where every eigenvalue is clearly away from zero with
    a positive real part the point is stable and nothing more is done; a zero or negative
    one is examined as described in the module notes. A scene with complementarities
    (hawsers, contacts) is always examined through :func:`stiffness_modes`.
    """
    keep, _, h, names, hh = _layout(problem)
    if keep.size == 0:
        return Stability(stable=True, min_eigenvalue=math.inf)
    if uses_sparse_path(problem):
        # A large scene: condensed and tested sparsely, eigenvalues only when read or
        # when the test is inconclusive.
        try:
            Kh = sps.csc_matrix(_sparse_condensed(problem, x, p))
            # Homogenised entry by entry: K_ij / (h_i h_j).
            Kh.data /= h[Kh.indices] * np.repeat(h, np.diff(Kh.indptr))
        except RuntimeError:        # a singular condensed block
            Kh = None
        if Kh is not None and clearly_positive(Kh, _ZERO):
            return DeferredStability(Kh.toarray(), names)
        stiffness = None if Kh is None else Kh.toarray() / hh
    if not problem.smoothed:
        if clearly_stable and stiffness is not None:
            # The product is a fresh array (no copy of the kernel's output needed first).
            return DeferredStability(
                np.asarray(stiffness, dtype=float).reshape(keep.size, keep.size) * hh, names)
        values = None
        if stiffness is not None:
            try:
                values = np.linalg.eigvals(
                    np.asarray(stiffness, dtype=float).reshape(keep.size, keep.size) * hh)
            except np.linalg.LinAlgError:      # not finite: condensed below
                values = None
        if values is None:
            values = np.linalg.eigvals(condensed_stiffness(problem, x, p)[0] * hh)
        size = np.abs(values)
        if size.min() > _ZERO * max(size.max(), 1e-300) and values.real.min() >= 0:
            return Stability(stable=True, min_eigenvalue=float(values.real.min()),
                             eigenvalues=tuple(values.astype(complex).tolist()), dofs=names)
    values, vectors, keep = stiffness_modes(problem, x, p)
    names = _dof_names(problem, keep)
    # Zero is judged against the largest eigenvalue, and against the scene's stiffness
    # scale where constraints leave few finite ones.
    scale = max(float(np.max(np.abs(values), initial=0.0)),
                problem.contact_stiffness if problem.smoothed else 0.0, 1e-300)
    unstable, neutral = [], []
    stable = True
    for k, lam in enumerate(values):
        mode = np.real(vectors[:, k])
        if np.linalg.norm(mode) == 0:
            mode = np.imag(vectors[:, k])
        mode = mode / np.linalg.norm(mode)
        main = names[int(np.argmax(np.abs(mode)))]
        if abs(lam) <= _ZERO * scale:
            forces = _restoring(problem, x, p, keep, mode)
            known = [f for f in forces if f is not None]
            size = max([abs(f) for f in known], default=0.0)
            tiny = 1e-9 * problem.force_scale
            if not known or size <= tiny:
                neutral.append(main)
            elif any(f > tiny for f in known):
                stable = False
                unstable.append(main)
            continue
        if lam.real < 0:
            stable = False
            unstable.append(main)
    return Stability(stable=stable, min_eigenvalue=float(np.min(values.real, initial=math.inf)),
                     unstable_dofs=tuple(dict.fromkeys(unstable)),
                     neutral_dofs=tuple(dict.fromkeys(neutral)),
                     eigenvalues=tuple(complex(v) for v in values), dofs=tuple(names))


def pseudo_transient(problem, x, p, steps: int = 400, deadline: float | None = None):
    """Pseudo-transient continuation from ``x``: implicit Euler steps of the overdamped
    motion of the free nodes with the lines in equilibrium; returns the end point (None if
    the motion blew up). At ``deadline`` (a :func:`time.perf_counter` time) it stops where
    it is.

    It converges to stable equilibria only, and it moves through states where the bodies
    have no stiffness at all (every line slack at rest: Newton's Jacobian is singular
    there, while the overdamped motion simply drifts with the load until a line tightens).
    """
    n_line_rows = problem.n_x - problem.n_q
    mass = np.zeros(problem.n_x)
    mass[:problem.n_q] = 1.0
    # The residual rows are ordered lines first; the unknowns nodes first.
    order = np.concatenate([np.arange(n_line_rows, problem.n_x), np.arange(n_line_rows)])
    lb, ub = problem.bounds()
    g = np.asarray(problem.residual(x, p)).ravel()[order]
    norm = float(np.linalg.norm(g))
    J = np.asarray(problem.jacobian(x, p))[order]
    dt = 1e-2 / max(float(np.max(np.abs(np.diag(J)[:problem.n_q]), initial=1.0)), 1e-12)
    for _ in range(steps):
        if not np.isfinite(norm):
            return None
        if norm < 1e-14 or (deadline is not None and time.perf_counter() >= deadline):
            break
        M = np.diag(mass / dt) - J
        try:
            step = np.linalg.solve(M, g)
        except np.linalg.LinAlgError:
            step = np.linalg.lstsq(M, g, rcond=None)[0]
        # Limit each move to a tenth of a radian or of the scene's length.
        big = np.max(np.abs(step[:problem.n_q]), initial=0.0)
        if big > 0.1:
            step *= 0.1 / big
        trial = np.clip(x + step, lb, ub)
        g_new = np.asarray(problem.residual(trial, p)).ravel()[order]
        n_new = float(np.linalg.norm(g_new))
        if not np.isfinite(n_new) or n_new > 10 * norm + 1e-12:
            dt *= 0.25
            if dt < 1e-12:
                return None
            continue
        x, g = trial, g_new
        dt = min(dt * max(norm / max(n_new, 1e-300), 0.5) * 1.5, 1e12)
        norm = n_new
        J = np.asarray(problem.jacobian(x, p))[order]
    return x


def find_stable(problem, x, p, tol, assessment: Stability, polish, deadline=None):
    """A stable certified equilibrium reached from the unstable point ``x``, or None.

    Tries the overdamped motion from small and large perturbations along every unstable
    mode, then from the bodies turned by a quarter and a half turn about the vertical.
    Returns ``(x, Stability)``; None also when ``deadline`` (a :func:`time.perf_counter`
    time, the solve's budget) passes.
    """
    keep, _ = _split(problem)
    if keep.size == 0:
        return None
    values, vectors, keep = stiffness_modes(problem, x, p)
    h = homogenising(problem, keep)
    arm = problem.moment_scale / problem.force_scale
    starts = []
    for k in np.argsort(values.real):
        if values[k].real >= 0 and abs(values[k]) > _ZERO * max(np.max(np.abs(values)),
                                                                  1e-300):
            continue
        mode = np.real(vectors[:, k])
        mode = mode / max(np.linalg.norm(mode), 1e-300)
        for size in (1e-2, 0.2):
            for sign in (1.0, -1.0):
                trial = x.copy()
                trial[keep] = x[keep] + sign * size * arm * mode / h / problem.x_scale[keep]
                starts.append(trial)
    yaw = [j for j in keep if problem.free[j] == "yaw"]
    for turn in (math.pi / 2, -math.pi / 2, math.pi):
        if yaw:
            trial = x.copy()
            for j in yaw:
                trial[j] = x[j] + turn / problem.x_scale[j]
            starts.append(trial)
    for start in starts:
        if deadline is not None and time.perf_counter() >= deadline:
            return None
        end = pseudo_transient(problem, start, p, deadline=deadline)
        if end is None:
            continue
        end = polish(end)
        if not problem.certify(end, p, tol)[0]:
            continue
        result = assess(problem, end, p)
        if result.stable:
            return end, result
    return None
