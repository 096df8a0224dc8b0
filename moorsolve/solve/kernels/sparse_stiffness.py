"""The condensed stiffness of a large scene and its stability test, sparse.

A farm's stiffness couples each body only with its neighbours on shared lines: condensing
the lines out of the sparse Jacobian (SuperLU on the lines' and points' block) keeps that
pattern, and the test that every eigenvalue has a clearly positive real part is a sparse
symmetric factorisation instead of a dense eigenvalue problem. Used by
:func:`.stability.assess` where :func:`uses_sparse_path` holds (which also decides
between the dense kernel of :mod:`.newton` and :mod:`.sparse_newton`).

The test is the dense kernel's (:func:`.stability.clearly_stable_graph`): with ``Kh`` the
homogenised stiffness (rotations as arc length at the scene's moment arm), ``S`` its
symmetric part and ``c = 1e-7 ||Kh||_F``, a positive definite ``S - c I`` bounds every
eigenvalue's real part below by ``c`` (the field of values), and ``||Kh||_F`` bounds its
size above. Positive definiteness is read from the pivots of an LU factorisation that
keeps to the diagonal under a symmetric permutation (``P S P^T = L D L^T``: Sylvester's
criterion on the permuted matrix); where SuperLU had to leave the diagonal the test is
inconclusive and the caller computes eigenvalues.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sps
from scipy.sparse.linalg import splu

from .sparse_arrow import arrow_plan, jacobian_values

#: Largest problem (unknowns) whose dense Newton kernel is compiled: beyond (some 190
#: one-segment lines) the C compiler takes minutes, and the sparse path serves the scene.
COMPILE_MAX_UNKNOWNS = 400
#: Most body DOFs whose condensed stiffness the dense kernel computes symbolically; beyond
#: (more than four six-DOF bodies) the sparse path serves the scene.
SPARSE_BODY_DOFS = 24


def uses_sparse_path(problem) -> bool:
    """Whether ``problem`` takes the sparse Newton path (:mod:`.sparse_newton`) and this
    module's stiffness: more body DOFs than :data:`SPARSE_BODY_DOFS` or more unknowns than
    :data:`COMPILE_MAX_UNKNOWNS`, and no complementarities (hawsers and contacts take the
    dense kernel's semismooth steps)."""
    found = problem.derived.get("sparse_path")
    if found is None:
        n_body = sum(owner == "body" for owner, _, _ in problem.nodes)
        found = not problem.smoothed and (n_body > SPARSE_BODY_DOFS
                                          or problem.n_x > COMPILE_MAX_UNKNOWNS)
        problem.derived["sparse_path"] = found
    return found


def _csc(problem, x, p) -> sps.csc_matrix:
    """The problem's Jacobian at the scaled point ``x`` as a scipy CSC matrix."""
    J = problem.jacobian(x, p)
    sp = J.sparsity()
    return sps.csc_matrix((np.asarray(J.nonzeros(), dtype=float),
                           np.asarray(sp.row(), dtype=np.int64),
                           np.asarray(sp.colind(), dtype=np.int64)),
                          shape=(sp.size1(), sp.size2()))


def inverse_2x2_blocks(D) -> sps.csr_matrix | None:
    """The inverse of ``D`` where it is block diagonal in 2x2 blocks (every one-segment
    line's two unknowns balance its own two span residuals), in closed form; None where it
    is not, or a block is singular."""
    n = D.shape[0]
    if n % 2 or D.shape[1] != n:
        return None
    coo = sps.coo_matrix(D)
    if np.any(coo.row // 2 != coo.col // 2):
        return None
    blocks = np.zeros((n // 2, 2, 2))
    np.add.at(blocks, (coo.row // 2, coo.row % 2, coo.col % 2), coo.data)
    a, b, c, d = blocks[:, 0, 0], blocks[:, 0, 1], blocks[:, 1, 0], blocks[:, 1, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        det = a * d - b * c
        inverse = np.stack([np.stack([d, -b], -1), np.stack([-c, a], -1)], -2) / det[:, None,
                                                                                     None]
    if not np.isfinite(inverse).all():
        return None
    index = np.arange(n // 2)
    return sps.bsr_matrix((inverse, index, np.arange(n // 2 + 1)), shape=(n, n)).tocsr()


def sparse_condensed_stiffness(problem, x, p, keep, rest, rq, rr) -> sps.spmatrix:
    """``K = -(J_qq - J_qr J_rr^-1 J_rq)`` [SI: N/m, N, N m/rad] of the body DOFs
    ``keep`` at ``x``, sparse: ``rq``/``rr`` are the residual rows that balance ``keep``
    and ``rest``. Raises RuntimeError where ``J_rr`` is singular (a slack line)."""
    plan = arrow_plan(problem)
    if plan is not None and keep.size == problem.n_q:
        # Bodies only (no free points): K is the Newton step's Schur complement.
        v = np.append(jacobian_values(problem, np.asarray(x, float), p), 0.0)
        inv = plan.inverses(v)
        if inv is None:
            raise RuntimeError("a line's block is singular")
        A = plan.schur(v, inv)[0]
        row_scale = np.array([problem.moment_scale if problem.rotational[j]
                              else problem.force_scale for j in keep])
        # Scaled entry by entry on S's own pattern (CSC: rows, and columns by pointer).
        A.data *= -row_scale[A.indices] / np.repeat(problem.x_scale[keep], np.diff(A.indptr))
        return A
    J = _csc(problem, x, p).tocsr()
    A = J[rq][:, keep]
    if rest.size:
        B = J[rq][:, rest].tocsc()
        C = J[rr][:, keep].tocsc()
        D = J[rr][:, rest].tocsc()
        inverse = inverse_2x2_blocks(D)
        if inverse is not None:         # lines only: closed form, sparse throughout
            A = A - B @ (inverse @ C)
        else:                           # free points, multi-segment lines
            lu = splu(D)
            # Only the columns of C that are not empty need a solve.
            cols = np.flatnonzero(np.diff(C.indptr))
            if cols.size:
                Y = lu.solve(C[:, cols].toarray())
                full = np.zeros((len(rq), keep.size))
                full[:, cols] = B @ Y
                A = A - sps.csr_matrix(full)
    row_scale = np.array([problem.moment_scale if problem.rotational[j]
                          else problem.force_scale for j in keep])
    K = -sps.diags(row_scale) @ A @ sps.diags(1.0 / problem.x_scale[keep])
    return sps.csr_matrix(K)


#: Most DOFs whose test factorises densely.
DENSE_DOFS = 150


def clearly_positive(Kh: sps.spmatrix, zero: float) -> bool:
    """Whether every eigenvalue of ``Kh`` has a real part above ``zero * ||Kh||_F``
    (sufficient, not necessary; see the module notes)."""
    Kh = sps.csc_matrix(Kh)
    n = Kh.shape[0]
    if n == 0:
        return True
    if not np.isfinite(Kh.data).all():
        return False
    c = zero * float(np.sqrt((Kh.data ** 2).sum()))
    if n <= DENSE_DOFS:
        # Small: LAPACK's Cholesky, the kernel's own test, costs less than the set-up.
        dense = Kh.toarray()
        try:
            np.linalg.cholesky((dense + dense.T) / 2 - c * np.eye(n))
        except np.linalg.LinAlgError:
            return False
        return True
    S = ((Kh + Kh.T) * 0.5 - c * sps.identity(n, format="csc")).tocsc()
    try:
        lu = splu(S, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                  options=dict(SymmetricMode=True))
    except RuntimeError:            # exactly singular: not clearly positive
        return False
    if not np.array_equal(lu.perm_r, lu.perm_c):
        return False                # left the diagonal: the pivots are not S's LDL^T
    return bool(np.all(lu.U.diagonal() > 0))


__all__ = ["uses_sparse_path", "SPARSE_BODY_DOFS", "COMPILE_MAX_UNKNOWNS",
           "sparse_condensed_stiffness", "clearly_positive", "inverse_2x2_blocks"]
