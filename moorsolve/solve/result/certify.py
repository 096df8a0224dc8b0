"""Judging a solved point: the certificate's numbers against the tolerance, and everything
a Result needs from the point in one evaluation (``post``).

A mixin of :class:`~.problem.EquilibriumProblem`: it reads the problem's certificate,
report functions, scales and kernel.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ...concurrency import SYMBOLIC_LOCK

#: Outputs of :meth:`EquilibriumProblem.post_function`: the certificate, the condensed
#: stiffness and its stability test, the seven outputs of ``report``, and the segment and
#: node tables.
POST_OUTPUTS = ("certificate", "stiffness", "clearly_stable", "lines", "unbalanced",
                "loads", "poses", "points", "wrenches", "hull_in_range", "segments", "nodes")


class Certification:
    """Certificate judgement and the one-call ``post`` of :class:`EquilibriumProblem`."""

    # -- certificate ------------------------------------------------------------------
    def certify(self, x, p, tol: float) -> tuple:
        """``(certified, force_N, moment_Nm, relative)`` of the scaled point ``x``."""
        if not np.all(np.isfinite(x)):
            return False, math.inf, math.inf, math.inf
        return self.judge(*(float(v) for v in self.certificate(x, p)), tol=tol)

    def contact_certificate(self, x, p) -> dict:
        """``penetration_m`` and ``complementarity_N`` of the certificate at ``x`` (None
        each in a scene without contacts)."""
        if not self.contacts:
            return dict(penetration_m=None, complementarity_N=None)
        values = [float(v) for v in self.certificate(x, p)]
        return dict(penetration_m=values[3], complementarity_N=values[4])

    def judge(self, force: float, moment: float, t_max: float, penetration: float = 0.0,
              complementarity: float = 0.0, *, tol: float):
        """``(certified, force, moment, relative)`` from the certificate's numbers.

        The force (and a contact's complementarity residual, a reaction across an open gap)
        must be within ``tol`` of the largest force in the balance (the largest line
        tension or contact reaction, or a body's weight, buoyancy or applied load where
        larger), the moment within ``tol`` of that force times the scene's moment arm, and
        the largest penetration of a contact within ``tol`` of the length scale.
        """
        scale = t_max if t_max > 0 else self.force_scale
        relative = max(force, complementarity) / scale
        moment_ok = moment <= tol * scale * self.moment_scale / self.force_scale
        ok = bool(math.isfinite(relative) and math.isfinite(moment) and relative <= tol
                  and moment_ok and penetration <= tol * self.length_scale)
        return ok, force, moment, relative

    def judge_rows(self, cert: np.ndarray, tol: float) -> tuple:
        """:meth:`judge` of every row of ``cert`` (a certificate a row, as the kernel
        returns it): arrays ``(certified, force, moment, relative)``."""
        cert = np.asarray(cert, dtype=float)
        force, moment, t_max = cert[:, 0], cert[:, 1], cert[:, 2]
        zero = np.zeros(len(cert))
        penetration = cert[:, 3] if cert.shape[1] > 3 else zero
        complementarity = cert[:, 4] if cert.shape[1] > 4 else zero
        scale = np.where(t_max > 0, t_max, self.force_scale)
        with np.errstate(invalid="ignore"):
            relative = np.maximum(force, complementarity) / scale
            ok = (np.isfinite(relative) & np.isfinite(moment) & (relative <= tol)
                  & (moment <= tol * scale * self.moment_scale / self.force_scale)
                  & (penetration <= tol * self.length_scale))
        return ok, force, moment, relative

    # -- everything a Result needs, in one evaluation -------------------------------------
    def post_function(self) -> ca.Function:
        """``post(x, p)``: the certificate ``[force, moment, t_max]``, the condensed
        stiffness of the free body DOFs (:func:`.static.stiffness_graph`) with its
        stability test (:func:`.static.clearly_stable_graph`) and the outputs of
        :attr:`report`, :attr:`segment_report` and :attr:`node_report` (see
        :data:`POST_OUTPUTS`), all dense: what certifying, the stability check and the
        Result need from a solved point, in one call. Compiled with the Newton kernel."""
        with self._lock:
            if self._post is None:
                from ..kernels.sparse_stiffness import uses_sparse_path
                from ..stability.static import clearly_stable_graph, stiffness_graph
                with SYMBOLIC_LOCK:
                    x = ca.MX.sym("x", self.n_x)
                    p = ca.MX.sym("p", self.n_p)
                    if uses_sparse_path(self):
                        # A large scene: its stability check condenses sparsely when
                        # it runs (.sparse_stiffness); no dense graph over every DOF.
                        K, stable = ca.MX(0, 0), ca.MX(0)
                    else:
                        K = stiffness_graph(self, self.jacobian(x, p))
                        stable = clearly_stable_graph(self, K)
                    outs = [ca.vertcat(*self.certificate(x, p)), K, stable,
                            *self.report(x, p), self.segment_report(x, p),
                            self.node_report(x, p)]
                    self._post = ca.Function("moorsolve_post", [x, p],
                                             [ca.densify(o) for o in outs],
                                             ["x", "p"], list(POST_OUTPUTS))
            return self._post

    def post(self, x, p) -> dict:
        """:meth:`post_function` at the scaled point ``x``: numpy arrays by name, through
        the compiled kernel's library when it is built, else interpreted."""
        kernel = self._newton
        if kernel is not None and kernel.compiled:
            return kernel.post(x, p)
        try:
            values = self.post_function()(x, p)
        except RuntimeError:
            # A singular condensed block stops the interpreted QR solve: report the
            # stiffness as unknown (the stability check then condenses it itself).
            n_b = sum(owner == "body" for owner, _, _ in self.nodes)
            values = [ca.vertcat(*self.certificate(x, p)), np.full((n_b, n_b), np.nan), 0.0,
                      *self.report(x, p), self.segment_report(x, p), self.node_report(x, p)]
        return {name: np.asarray(v, dtype=float)
                for name, v in zip(POST_OUTPUTS, values)}
