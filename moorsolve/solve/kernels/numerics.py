"""The numerical solvers of a built problem: IPOPT solver objects, the compiled Newton
kernel and its pool, the Newton step's Jacobian (smoothed where the scene has
complementarities) and the bounds on the unknowns.

A mixin of :class:`~.problem.EquilibriumProblem`; the only place that calls ``nlpsol``.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ...concurrency import SYMBOLIC_LOCK
from .ipopt_solvers import IpoptSolvers


class SolverAccess:
    """Solver objects and step data of :class:`EquilibriumProblem`."""

    #: Jacobian smoothing relative to the residual: ``eps = SMOOTHING * L * min(1, |g|)``
    #: [m], with ``L`` the length scale and ``|g|`` the largest scaled residual.
    SMOOTHING = 0.01

    def smoothing(self, g) -> float:
        """The Jacobian smoothing ``eps`` [m] for a (scaled) residual vector ``g``."""
        size = float(np.max(np.abs(g))) if np.size(g) else 0.0
        if not np.isfinite(size):
            size = 1.0
        return self.SMOOTHING * self.length_scale * min(1.0, size)

    #: A weak spring on every node unknown in the step Jacobian (scaled units), where
    #: the scene has complementarities: a body that nothing holds in some direction at
    #: the current point (slack hawsers, open contacts, a hawser's sideways stiffness
    #: T/D at zero tension) moves with its unbalanced force instead of making the step
    #: singular; elsewhere it changes the step by parts in 1e9.
    REGULARISATION = 1e-9

    def regularisation(self, value: float | None = None) -> ca.DM:
        """The sparse matrix subtracted from the step Jacobian (``value``, default
        :data:`REGULARISATION`, on the balance row of every node unknown); empty without
        complementarities."""
        n_lines = self.n_x - self.n_q
        rows = [n_lines + j for j in range(self.n_q)] if self.smoothed else []
        sp = ca.Sparsity.triplet(self.n_x, self.n_x, rows, list(range(len(rows))))
        return ca.DM(sp, self.REGULARISATION if value is None else value)

    def step_sparsity(self) -> ca.Sparsity:
        """The sparsity of the step Jacobian (the Jacobian's and the regularisation's)."""
        sp = self.jacobian.sparsity_out(0)
        if self.smoothed:
            sp = sp + self.smoothed_jacobian.sparsity_out(0) + self.regularisation().sparsity()
        return sp

    def step_jacobian(self, x, p, g) -> np.ndarray:
        """The Jacobian a Newton step uses at ``x`` with residual ``g``: the exact one, or,
        where the scene has complementarities, that of their smoothed form with ``eps``
        tied to ``|g|`` (Jacobian smoothing; :mod:`moorsolve.physics.contact`) less the
        weak spring of :meth:`regularisation`."""
        if not self.smoothed:
            return np.asarray(self.jacobian(x, p))
        J = self.smoothed_jacobian(x, p, self.smoothing(g)) - self.regularisation()
        return np.asarray(ca.densify(J))

    # -- solvers --------------------------------------------------------------------
    def ipopt(self, tol: float, max_iter: int, max_time_s: float) -> ca.Function:
        """An IPOPT solver for the feasibility NLP, cached per setting; compiled once the
        problem has been solved a few times (:mod:`.ipopt_solvers`).

        A CasADi solver object is not safe to run from two threads at once: callers hold
        :attr:`lock` while they run it.
        """
        with self._lock:
            return self.ipopt_solvers.get(tol, max_iter, max_time_s)

    @property
    def ipopt_solvers(self) -> IpoptSolvers:
        """IPOPT's solvers of this problem, interpreted, then compiled."""
        with self._lock:
            if self._ipopt_solvers is None:
                self._ipopt_solvers = IpoptSolvers(self)
            return self._ipopt_solvers

    #: The smoothings IPOPT solves with in turn, relative to the length scale (the polish
    #: that follows makes the complementarities exact).
    IPOPT_SMOOTHING = (1e-3, 1e-5)

    #: Weight of the distance from the start in IPOPT's objective (scaled unknowns).
    IPOPT_PROXIMITY = 1e-6

    def ipopt_smoothings(self) -> tuple:
        """The smoothings [m] IPOPT solves with in turn (one run, unsmoothed-free, without
        complementarities)."""
        if not self.smoothed:
            return (None,)
        return tuple(s * self.length_scale for s in self.IPOPT_SMOOTHING)

    def nlp_parameters(self, p, start, smoothing=None) -> np.ndarray:
        """The parameters of the IPOPT problem for the problem's parameters ``p``, the
        (scaled) start ``start`` and a smoothing [m]."""
        if not self.smoothed:
            return p
        return np.concatenate([p, [smoothing], start])

    def newton(self):
        """The fast-path Newton kernel (:mod:`.newton`), built and compiled on first use;
        for a large scene its sparse form (:mod:`.sparse_newton`), which compiles nothing."""
        with self._lock:
            if self._newton is None:
                from .newton import NewtonKernel
                from .sparse_newton import SparseNewton
                from .sparse_stiffness import uses_sparse_path
                with SYMBOLIC_LOCK:
                    self._newton = (SparseNewton(self) if uses_sparse_path(self)
                                    else NewtonKernel(self))
            return self._newton

    def kernel_pool(self):
        """Clones of the Newton kernel, one per concurrently running caller (sweeps)."""
        with self._lock:
            if self._kernel_pool is None:
                from .newton import KernelPool
                self._kernel_pool = KernelPool(self.newton())
            return self._kernel_pool

    def bounds(self) -> tuple:
        lb = np.full(self.n_x, -np.inf)
        ub = np.full(self.n_x, np.inf)
        for j, (_, _, dof) in enumerate(self.nodes):
            if dof == "pitch":
                # z-y-x angles are singular at +-90 deg of pitch.
                lb[j], ub[j] = -0.49 * math.pi, 0.49 * math.pi
        # No bound on a line's u: every block continues its spans monotonically for u < 0
        # (loose line on a boundary, or, for a line with nothing to lie on, no root there),
        # so H = max(u, 0) = 0 is an interior root, not a bound IPOPT must reach (a folded
        # line hit IPOPT's iteration limit at that bound). A hawser's u is its
        # tension and a rigid contact's unknown its reaction (Fischer-Burmeister
        # complementarities): neither pulls, and the bound keeps a Newton step from making
        # them pull where the smoothed Jacobian would.
        for i, kind in enumerate(self.kinds):
            if kind.single and kind.neutral:
                lb[self.line_offsets[i]] = 0.0
        for point, io in zip(self.contacts, self.contact_offsets):
            if point.n_unknowns:
                lb[io] = 0.0
        return lb, ub
