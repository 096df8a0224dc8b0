"""The Newton step of a scene of one-segment lines by block elimination, on index arrays
worked out once from the Jacobian's sparsity.

With the lines' rows and unknowns first, ``J = [[A, B], [C, D]]``: ``A`` is block diagonal
(each line's two span residuals depend on its own two unknowns and on the nodes), ``B``
holds each line's dependence on the nodes at its ends, ``C`` the nodes' balances'
dependence on the lines attached to them, ``D`` the nodes' own terms. Then

    S = D - sum over lines of C_l A_l^-1 B_l,     S dq = g_q - sum C_l A_l^-1 g_l,
    dl_l = A_l^-1 (g_l - B_l dq),

where each line's term is a small dense block (its two rows against the few node columns
its ends move) added into ``S``'s fixed pattern: a farm's ``S`` couples each platform only
with its neighbours, and SuperLU factorises it. Everything per step is a gather, one
batched product and one scatter (no sparse-matrix construction but ``S``'s).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sps
from scipy.sparse.linalg import splu


class ArrowPlan:
    """Index arrays of the block elimination for one problem's Jacobian sparsity.

    ``rows``, ``cols`` are the Jacobian's nonzeros in its storage order (CSC), so the
    nonzero values of an evaluation index straight into them. Raises ValueError where the
    pattern has no arrow structure (a line's rows reaching another line's unknowns).
    """

    def __init__(self, rows: np.ndarray, cols: np.ndarray, n_q: int, n_legs: int):
        n_l = 2 * n_legs
        self.n_q, self.n_legs, self.n_l = n_q, n_legs, n_l
        k = np.arange(rows.size)
        pad = rows.size                 # index of an appended zero
        line_row, line_col = rows < n_l, cols >= n_q
        in_a = line_row & line_col
        if np.any((rows[in_a] // 2) != ((cols[in_a] - n_q) // 2)):
            raise ValueError("a line's residuals depend on another line's unknowns")
        # A: per line [a, b, c, d] (row-major 2x2).
        a_index = np.full((n_legs, 4), pad)
        a_index[rows[in_a] // 2, 2 * (rows[in_a] % 2) + (cols[in_a] - n_q) % 2] = k[in_a]
        self.a_index = a_index
        # B: per line, its node columns (padded) and the entries of its two rows there.
        in_b = line_row & ~line_col
        self.b_cols, self.b_index = self._gather(rows[in_b] // 2, rows[in_b] % 2,
                                                 cols[in_b], k[in_b], n_legs, pad,
                                                 transpose=False)
        # C: per line, the node rows its unknowns enter (padded), both unknowns' entries.
        in_c = ~line_row & line_col
        self.c_rows, self.c_index = self._gather((cols[in_c] - n_q) // 2,
                                                 (cols[in_c] - n_q) % 2, rows[in_c] - n_l,
                                                 k[in_c], n_legs, pad, transpose=True)
        # S's pattern: D's nonzeros and every line's (C rows x B cols) block.
        in_d = ~line_row & ~line_col
        d_r, d_c = rows[in_d] - n_l, cols[in_d]
        m_c, m_b = self.c_rows.shape[1], self.b_cols.shape[1]
        blk_r = np.broadcast_to(self.c_rows[:, :, None], (n_legs, m_c, m_b))
        blk_c = np.broadcast_to(self.b_cols[:, None, :], (n_legs, m_c, m_b))
        valid = (blk_r >= 0) & (blk_c >= 0)
        all_r = np.concatenate([d_r, blk_r[valid]])
        all_c = np.concatenate([d_c, blk_c[valid]])
        key = all_c.astype(np.int64) * max(n_q, 1) + all_r
        unique, where = np.unique(key, return_inverse=True)
        self.s_nnz = unique.size
        self.s_rows = (unique % max(n_q, 1)).astype(np.int64)
        s_cols = unique // max(n_q, 1)
        self.s_indptr = np.searchsorted(s_cols, np.arange(n_q + 1)).astype(np.int64)
        self.d_target, self.d_index = where[:d_r.size], k[in_d]
        target = np.full((n_legs, m_c, m_b), self.s_nnz)    # padding: a slot past the end
        target[valid] = where[d_r.size:]
        self.blk_target = target

    @staticmethod
    def _gather(line, side, other, k, n_legs, pad, transpose):
        """Per line the distinct ``other`` indices (padded with -1) and the nonzero index
        of each (side, other) entry (``pad`` where absent): shape (lines, 2, m) for B,
        (lines, m, 2) for C (``transpose``)."""
        per_line = [[] for _ in range(n_legs)]
        for li, o in zip(line.tolist(), other.tolist()):
            if o not in per_line[li]:
                per_line[li].append(o)
        m = max([len(v) for v in per_line] + [1])
        ids = np.full((n_legs, m), -1, dtype=np.int64)
        index = np.full((n_legs, 2, m), pad, dtype=np.int64)
        position = [{o: j for j, o in enumerate(sorted(v))} for v in per_line]
        for li, v in enumerate(per_line):
            ids[li, :len(v)] = sorted(v)
        for li, s, o, kk in zip(line.tolist(), side.tolist(), other.tolist(), k.tolist()):
            index[li, s, position[li][o]] = kk
        return ids, (index.transpose(0, 2, 1) if transpose else index)

    def blocks(self, values: np.ndarray) -> tuple:
        """Per line ``(a, b, c, d)`` of its 2x2 block (``values`` with a zero appended)."""
        return tuple(values[self.a_index[:, j]] for j in range(4))

    def inverses(self, v: np.ndarray):
        """Every line's ``A_l^-1`` (lines, 2, 2) from the nonzeros ``v`` (a zero
        appended), or None where one is singular."""
        a, b, c, d = self.blocks(v)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            det = a * d - b * c
            inv = np.stack([np.stack([d, -b], -1), np.stack([-c, a], -1)], -2) / det[:, None,
                                                                                     None]
        return inv if np.isfinite(inv).all() else None

    def schur(self, v: np.ndarray, inv: np.ndarray):
        """``(S, B, C)``: the nodes' Schur complement ``D - C A^-1 B`` (CSC) and every
        line's ``B_l``, ``C_l`` blocks, from the nonzeros ``v`` (a zero appended)."""
        B, C = v[self.b_index], v[self.c_index]            # (L, 2, mb), (L, mc, 2)
        data = np.zeros(self.s_nnz + 1)
        data[self.d_target] = v[self.d_index]
        data -= np.bincount(self.blk_target.ravel(),
                            weights=((C @ inv) @ B).ravel(),
                            minlength=self.s_nnz + 1)
        S = sps.csc_matrix((data[:-1], self.s_rows, self.s_indptr),
                           shape=(self.n_q, self.n_q))
        return S, B, C

    def step(self, g: np.ndarray, values: np.ndarray):
        """``J \\ g`` (nodes' part first, as the unknowns), or None where a line's block
        or ``S`` is singular or the step not finite. ``S`` is factorised by SuperLU, or
        densely while it is small (SuperLU's set-up costs more there)."""
        n_q, n_l = self.n_q, self.n_l
        v = np.append(values, 0.0)
        inv = self.inverses(v)
        if inv is None:
            return None
        y = (inv @ g[:n_l].reshape(-1, 2, 1))[:, :, 0]
        if n_q == 0:
            return y.ravel()
        S, B, C = self.schur(v, inv)
        rows = np.where(self.c_rows >= 0, self.c_rows, n_q)   # padding to a spare row
        rhs = g[n_l:] - np.bincount(rows.ravel(), weights=(C @ y[:, :, None]).ravel(),
                                    minlength=n_q + 1)[:n_q]
        try:
            if n_q <= DENSE_NODES:
                dq = np.linalg.solve(S.toarray(), rhs)
            else:
                # S is structurally symmetric (a line couples its two ends both ways).
                dq = splu(S, permc_spec="MMD_AT_PLUS_A").solve(rhs)
        except (RuntimeError, np.linalg.LinAlgError):        # exactly singular
            return None
        dq_b = np.append(dq, 0.0)[np.where(self.b_cols >= 0, self.b_cols, n_q)]
        dl = y - (inv @ (B @ dq_b[:, :, None]))[:, :, 0]
        step = np.concatenate([dq, dl.ravel()])
        return step if np.isfinite(step).all() else None


#: Most node unknowns whose Schur complement is factorised densely (LAPACK): below about
#: a hundred SuperLU's set-up costs more than the factorisation.
DENSE_NODES = 100


def arrow_plan(problem) -> ArrowPlan | None:
    """The :class:`ArrowPlan` of ``problem``'s Jacobian, worked out once (kept in
    ``problem.derived``); None where the lines have more than two unknowns each or the
    pattern has no arrow structure."""
    if "arrow_plan" not in problem.derived:
        plan = None
        if problem.n_x == problem.n_q + 2 * problem.n_legs:
            rows, cols = problem.jacobian.sparsity_out(0).get_triplet()
            try:
                plan = ArrowPlan(np.asarray(rows), np.asarray(cols), problem.n_q,
                                 problem.n_legs)
            except ValueError:
                plan = None
        problem.derived["arrow_plan"] = plan
    return problem.derived["arrow_plan"]


def keep_jacobian(problem, x, p, values) -> None:
    """Remember the Jacobian's nonzeros at the point a solve ends on, so that its
    stability check (:func:`jacobian_values`) need not evaluate them again."""
    problem.derived["last_jacobian"] = (x.tobytes() + np.asarray(p, float).tobytes(),
                                        values)


def jacobian_values(problem, x, p) -> np.ndarray:
    """The Jacobian's nonzeros at ``x`` (storage order): those kept by the solve that
    ended there, else evaluated."""
    kept = problem.derived.get("last_jacobian")
    if kept is not None and kept[0] == x.tobytes() + np.asarray(p, float).tobytes():
        return kept[1]
    return np.asarray(problem.jacobian(x, p).nonzeros(), dtype=float)


__all__ = ["ArrowPlan", "arrow_plan", "keep_jacobian", "jacobian_values", "DENSE_NODES"]
