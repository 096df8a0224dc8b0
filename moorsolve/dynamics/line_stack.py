"""Several lines' frequency-domain equations solved together (the engine of
:mod:`.line_dynamics`).

Each node of a lumped-mass line couples only with its two neighbours, so a line's dynamic
stiffness ``K - omega^2 M + i omega B`` is block tridiagonal with 3x3 blocks. The lines of a
scene are stacked (padded with inert nodes to the longest one) and every line and every
frequency is eliminated at once, node by node down the lines: one block Thomas sweep
(:func:`.block_thomas.solve_block_tridiagonal`) instead of one banded solve per line and
frequency. Masking a prescribed row's coupling leaves the lower blocks different from the
upper ones' transposes, so the sweep takes both.

A prescribed displacement (the ends, a grounded node held vertically, a grounded run
without tension held where it lies) keeps its row as the identity's, with its motion on the
right-hand side, so the system stays block tridiagonal.
"""

from __future__ import annotations

import numpy as np

from ..errors import ConvergenceError
from .block_thomas import solve_block_tridiagonal

__all__ = ["LineStack"]


def element_blocks(model) -> np.ndarray:
    """Each element's 3x3 stiffness ``EA/l0 t t^T + T/l (I - t t^T)`` [N/m], (n, 3, 3)."""
    t = model.direction
    tt = t[:, :, None] * t[:, None, :]
    return (model.axial[:, None, None] * tt
            + (model.tension / model.chord)[:, None, None] * (np.eye(3) - tt))


def _fixed(model) -> np.ndarray:
    """Prescribed DOFs ``(n + 1, 3)``: the ends, grounded nodes vertically (without a
    seabed spring), and grounded nodes between two elements without tension (friction has
    used the tension up, or the run lies slack: no stiffness along the seabed, held where
    they lie as the friction holding them would)."""
    N = model.n_elements + 1
    fixed = np.zeros((N, 3), bool)
    fixed[0] = fixed[-1] = True
    if model.seabed_spring is None:
        fixed[model.grounded, 2] = True
    T = np.concatenate([[0.0], model.tension, [0.0]])
    loose = 1e-9 * max(float(np.max(np.abs(model.tension))), 1.0)
    held = model.grounded & (T[:-1] <= loose) & (T[1:] <= loose)
    fixed[held, :2] = True
    return fixed


class LineStack:
    """The block matrices of ``models``, padded to the longest (index ``[line, node]``)."""

    def __init__(self, models):
        self.models = list(models)
        self.sizes = np.array([m.n_elements + 1 for m in self.models])
        L, N = len(self.models), int(self.sizes.max())
        self.n_lines, self.n_nodes = L, N
        self.Pt = np.zeros((L, N, 3, 3))
        self.M = np.zeros((L, N, 3, 3))
        self.K_diag = np.zeros((L, N, 3, 3))
        self.K_upper = np.zeros((L, N - 1, 3, 3))
        self.K_lower = np.zeros((L, N - 1, 3, 3))
        self.fixed = np.ones((L, N, 3), bool)
        self.qn = np.zeros((L, N))
        self.qt = np.zeros((L, N))
        self.ke = []
        for k, m in enumerate(self.models):
            n = m.n_elements
            t = m.tangent
            Pt = t[:, :, None] * t[:, None, :]
            self.Pt[k, :n + 1] = Pt
            self.M[k, :n + 1] = (m.mass[:, None, None] * np.eye(3)
                                 + m.added_mass[:, None, None] * (np.eye(3) - Pt))
            ke = element_blocks(m)
            self.ke.append(ke)
            self.K_diag[k, :n] += ke
            self.K_diag[k, 1:n + 1] += ke
            if m.seabed_spring is not None:
                self.K_diag[k, :n + 1, 2, 2] += np.where(m.grounded, m.seabed_spring, 0.0)
            self.K_upper[k, :n] = -ke
            self.K_lower[k, :n] = -ke
            self.fixed[k, :n + 1] = _fixed(m)
            self.qn[k, :n + 1] = m.drag_normal
            self.qt[k, :n + 1] = m.drag_tangential
        self.Pn = np.eye(3) - self.Pt
        free = (~self.fixed).astype(float)
        self.free = free
        self.K_upper *= free[:, :-1, :, None]        # a prescribed row couples to nothing
        self.K_lower *= free[:, 1:, :, None]
        self._static = None

    def solve(self, omega, u_a, u_b, bn, bt) -> np.ndarray:
        """Node displacements ``(lines, n_omega, nodes, 3)`` for end motions ``u_a``,
        ``u_b`` ``(lines, n_omega, 3)`` and drag coefficients per node ``bn``, ``bt``
        ``(lines, n_omega, nodes)``."""
        L, N, nw = self.n_lines, self.n_nodes, len(omega)
        w = omega[None, :, None, None, None]
        rows = self.free[:, None, :, :, None]
        if self._static is None or self._static[0] is not omega:
            # The part the drag iteration does not change, built once per frequency set.
            Z0 = (self.K_diag[:, None] - w ** 2 * self.M[:, None]) * rows \
                + (1 - rows) * np.eye(3)
            self._static = (omega, Z0, 1j * w * rows)
        _, Z0, iw = self._static
        Z = Z0 + iw * (bn[..., None, None] * self.Pn[:, None]
                       + bt[..., None, None] * self.Pt[:, None])   # (L, nw, N, 3, 3)
        rhs = np.zeros((L, nw, N, 3), complex)
        rhs[:, :, 0] = u_a
        rhs[np.arange(L), :, self.sizes - 1] = u_b
        # Components first, (nodes, 3, 3, lines, n_omega), for the sweep down the nodes.
        upper = self.K_upper.transpose(1, 2, 3, 0)[..., None]
        lower = self.K_lower.transpose(1, 2, 3, 0)[..., None]
        try:
            u = solve_block_tridiagonal(Z.transpose(2, 3, 4, 0, 1), upper, lower,
                                        rhs.transpose(2, 3, 0, 1))
        except np.linalg.LinAlgError:
            raise ConvergenceError(
                "the line's dynamic stiffness is singular at one of the frequencies (a node "
                "with neither tension nor mass to hold it, or omega = 0 on a line without "
                "tension)") from None
        return u.transpose(2, 3, 0, 1)

    def split_velocity(self, v):
        """Magnitudes of the normal and tangential parts of node velocities ``v``
        ``(lines, n_omega, nodes, 3)``, components added in quadrature."""
        vt = np.einsum("lnij,lwnj->lwni", self.Pt, v)
        vn = v - vt
        return np.sqrt(np.sum(np.abs(vn) ** 2, -1)), np.sqrt(np.sum(np.abs(vt) ** 2, -1))
