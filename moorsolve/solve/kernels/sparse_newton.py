"""The Newton path of large scenes (wind farms): sparse steps, nothing compiled.

The kernel of :mod:`.newton` unrolls forty iterations, each with its line search, into one
CasADi graph over every line: its C grows with the scene and takes minutes to compile past
a few hundred unknowns, and its condensed stiffness (a dense symbolic elimination over
every body DOF) costs more than the solve. Here the same iteration runs in Python over
the problem's residual and Jacobian (:attr:`EquilibriumProblem.residual_jacobian`, an SX
graph evaluated without compiling, linear in the lines). Each step eliminates the lines
in closed form and factorises the bodies' Schur complement (:mod:`.sparse_arrow`; SuperLU
on the whole Jacobian where the lines have more than two unknowns). The stiffness and the
stability test are left to :mod:`.stability`, which condenses and factorises sparsely
(:mod:`.sparse_stiffness`) from the Jacobian the solve ended with.

The iteration is the kernel's (same convergence estimate, step limits, projection onto
the bounds, Armijo backtracking), so both paths reach the same point: it is used where
:func:`.sparse_stiffness.uses_sparse_path` holds, for scenes without complementarities.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sps
from scipy.sparse.linalg import splu

from .newton import (_ARMIJO, _BACKTRACKS, _OUTPUTS, CONVERGED, MAX_ITER, MAX_ITERATIONS,
                     STALLED, _inverse_step_limits)
from .sparse_arrow import arrow_plan, keep_jacobian
from .sparse_stiffness import SPARSE_BODY_DOFS, uses_sparse_path

class SparseNewton:
    """The Newton kernel's interface (:class:`.newton.NewtonKernel`) on sparse steps.

    ``solve``, ``raw`` and ``run_many`` return the kernel's outputs; ``clearly_stable`` is
    0 and ``stiffness`` NaN (the caller's stability check condenses sparsely,
    :func:`.stability.assess`). Nothing is compiled: ``compiled`` is False and
    ``wait_compiled`` returns at once.
    """

    compiled = False

    def __init__(self, problem):
        self.problem = problem
        self.function = None
        sp = problem.jacobian.sparsity_out(0)
        rows, cols = sp.get_triplet()
        self._shape = (sp.size1(), sp.size2())
        # CasADi stores the nonzeros column by column: its (colind, row) are CSC's.
        self._indptr = np.asarray(sp.colind(), dtype=np.int64)
        self._indices = np.asarray(sp.row(), dtype=np.int64)
        self._inverse_limit = np.asarray(_inverse_step_limits(problem), dtype=float)
        self._lb, self._ub = problem.bounds()
        n_q, n_legs = problem.n_q, problem.n_legs
        # The kernel's certificate estimate needs a 2x2 block per line.
        self._estimate = problem.n_x == n_q + 2 * n_legs
        if self._estimate:
            dense_index = {(r, c): k for k, (r, c) in enumerate(zip(rows, cols))}
            blocks = []
            for i in range(n_legs):
                r, c = 2 * i, n_q + 2 * i
                blocks.append([dense_index.get(rc, -1) for rc in
                               ((r, c), (r, c + 1), (r + 1, c), (r + 1, c + 1))])
            self._blocks = np.array(blocks, dtype=np.int64).reshape(-1, 4)
            rot = np.array(problem.rotational, dtype=bool)
            self._node_rot = rot
            self._line_cols = n_q + 2 * np.arange(n_legs)
        self._arrow = arrow_plan(problem)
        n_keep = sum(owner == "body" for owner, _, _ in problem.nodes)
        self._n_stiffness = n_keep * n_keep

    # -- the interface of NewtonKernel -------------------------------------------------
    def wait_compiled(self, timeout: float | None = None) -> bool:
        return False

    def clone(self) -> "SparseNewton":
        """Stateless between calls: the same object serves every thread."""
        return self

    def post(self, x, p) -> dict:        # pragma: no cover - compiled kernels only
        raise RuntimeError("the sparse Newton path has no compiled post function")

    def solve(self, x0: np.ndarray, p: np.ndarray, tol: float) -> dict:
        out = dict(zip(_OUTPUTS, self.raw(x0, p, tol)))
        out["status"] = int(out["status"][0])
        out["iterations"] = int(out["iterations"][0])
        return out

    def run_many(self, x0: np.ndarray, P: np.ndarray, tol: float) -> dict:
        runs = [self.raw(x0, p, tol) for p in P]
        return {name: np.array([r[k] for r in runs]) for k, name in enumerate(_OUTPUTS)}

    def raw(self, x0: np.ndarray, p: np.ndarray, tol: float) -> list[np.ndarray]:
        """The kernel's outputs in order (fresh arrays)."""
        problem = self.problem
        x, status, count = self.iterate(np.array(x0, dtype=float).ravel(),
                                        np.asarray(p, dtype=float).ravel(), tol)
        cert = np.asarray(problem.certificate(x, p), dtype=float).ravel() \
            if np.isfinite(x).all() else np.full(5, math.inf)
        body, t_fair, t_anchor, reactions = (np.asarray(v, dtype=float).ravel()
                                             for v in problem.summary(x, p))
        return [x, np.array([float(status)]), np.array([float(count)]), cert, body, t_fair,
                t_anchor, reactions, np.zeros(1), np.full(self._n_stiffness, math.nan)]

    # -- the iteration ---------------------------------------------------------------
    def iterate(self, x: np.ndarray, p: np.ndarray, tol: float) -> tuple:
        """``(x, status, iterations)`` of the damped Newton method from ``x``."""
        evaluated = self._evaluate(x, p)
        for count in range(MAX_ITERATIONS + 1):
            g, values = evaluated
            if self._converged(x, p, g, values, tol):
                keep_jacobian(self.problem, x, p, values)
                return x, CONVERGED, count
            if count == MAX_ITERATIONS:
                break
            step = self._step(g, values)
            if step is None:
                return x, STALLED, count
            found = self._search(x, p, step, float(g @ g))
            if found is None:
                return x, STALLED, count
            x, evaluated = found
        return x, MAX_ITER, MAX_ITERATIONS

    def _evaluate(self, x, p) -> tuple:
        """``(g, J's nonzeros)`` at ``x`` (CasADi's column-major order, as CSC)."""
        g, J = self.problem.residual_jacobian(x, p)
        return (np.asarray(g, dtype=float).ravel(),
                np.asarray(J.nonzeros(), dtype=float))

    def _converged(self, x, p, g, values, tol) -> bool:
        """The kernel's stopping test: each line's span mismatch turned into fairlead
        force through its own 2x2 block, the nodes' unbalanced forces and moments, against
        ``tol`` times the largest fairlead tension (the exact certificate where the
        lines have more unknowns than two)."""
        problem = self.problem
        if not (np.isfinite(g).all() and np.isfinite(x).all()):
            return False
        fs = problem.force_scale
        if not self._estimate:
            force, moment, t_max = (float(v) for v in problem.certificate(x, p)[:3])
            t_est = max(t_max, fs * 1e-12)
        else:
            n_legs = problem.n_legs
            with np.errstate(divide="ignore", invalid="ignore"):
                padded = np.append(values, 0.0)
                a, b, c, d = (padded[self._blocks[:, k]] for k in range(4))
                det = a * d - b * c
                gu, gv = g[0:2 * n_legs:2], g[1:2 * n_legs:2]
                du, dv = d * gu - b * gv, -c * gu + a * gv
                forces = fs * np.hypot(du, dv) / np.abs(det)
            nodes = np.abs(g[2 * n_legs:])
            forces = np.concatenate([forces, nodes[~self._node_rot] * fs])
            moment = float(np.max(nodes[self._node_rot] * problem.moment_scale,
                                  initial=0.0))
            xp = x * problem.x_scale
            u, v = xp[self._line_cols], xp[self._line_cols + 1]
            fair = np.hypot(np.maximum(u, 0.0), v)
            t_est = max(float(np.max(fair, initial=0.0)), fs * 1e-12) if n_legs else fs
            force = float(np.max(forces, initial=0.0))
        return bool(force <= tol * t_est and moment <= tol * t_est * problem.moment_scale / fs)

    def _step(self, g, values):
        """``J \\ g``, scaled to the step limits; None where ``J`` is singular or the step
        not finite (a stall, as in the kernel).

        With one-segment lines only, ``J = [[A, B], [C, D]]`` (lines' rows first, nodes'
        columns first) has ``A`` block diagonal in 2x2 blocks: the lines are eliminated
        in closed form and SuperLU factorises the nodes' Schur complement
        ``D - C A^-1 B`` (a farm's bodies and their neighbours); otherwise, or where a
        block is singular, SuperLU factorises ``J`` whole."""
        d = self._arrow.step(g, values) if self._arrow is not None else None
        if d is None:
            J = sps.csc_matrix((values, self._indices, self._indptr), shape=self._shape)
            try:
                d = splu(J).solve(g)
            except RuntimeError:        # exactly singular
                return None
        if not np.isfinite(d).all():
            return None
        worst = float(np.max(np.abs(d) * self._inverse_limit, initial=0.0))
        return d * min(1.0, 1.0 / worst) if worst > 0 else d

    def _search(self, x, p, d, m0):
        """Backtracking ``x - a d`` (``a = 1, 1/2, ...``) projected onto the bounds until
        the squared residual falls by the Armijo factor: ``(x, (g, J))`` there, or None
        if no step does. The full step, usually taken, is evaluated with its Jacobian (the
        next iteration's); shorter ones with the residual alone."""
        residual = self.problem.residual
        for j in range(_BACKTRACKS):
            a = 0.5 ** j
            xa = np.minimum(np.maximum(x - a * d, self._lb), self._ub)
            if j == 0:
                evaluated = self._evaluate(xa, p)
                r = evaluated[0]
            else:
                r = np.asarray(residual(xa, p), dtype=float).ravel()
            m = float(r @ r)
            if m <= (1 - 2 * _ARMIJO * a) * m0:
                return xa, (evaluated if j == 0 else self._evaluate(xa, p))
        return None


__all__ = ["SparseNewton", "uses_sparse_path", "SPARSE_BODY_DOFS"]
