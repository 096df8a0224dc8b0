"""Block tridiagonal systems with 3x3 blocks, many at once (the block Thomas algorithm).

A lumped-mass line's dynamic stiffness couples each node only with its two neighbours, so
every frequency (and sea state, and line of a scene) is one block tridiagonal system. The
systems are stored components first, ``(nodes, 3, 3, *systems)``, so that each step of the
sweep down the nodes is a handful of numpy operations over all the systems together; the
3x3 inverses are taken by the adjugate, each block solve refined (which restores the
digits the adjugate loses on blocks with a wide stiffness range): cheaper than numpy's
batched LAPACK solves on ``(..., 3, 3)`` stacks, which pay a call per system.

Elimination without pivoting: the diagonal blocks of a line's dynamic stiffness carry the
node's positive axial and geometric stiffness, mass and damping (or are identity rows of
prescribed motions), and a singular block is reported, never divided by.
"""

from __future__ import annotations

import numpy as np

__all__ = ["solve_block_tridiagonal", "inverse3"]

_NEXT = np.array([1, 2, 0])
_LAST = np.array([2, 0, 1])


def inverse3(A: np.ndarray) -> np.ndarray:
    """Inverses of 3x3 matrices stored components first, ``A`` (3, 3, ...), by the adjugate.

    Raises ``numpy.linalg.LinAlgError`` if a determinant is zero or not finite.
    """
    a1, a2 = A[_NEXT], A[_LAST]
    # Cofactor (i, j) = A[i+1, j+1] A[i+2, j+2] - A[i+1, j+2] A[i+2, j+1], indices mod 3.
    cof = a1[:, _NEXT] * a2[:, _LAST] - a1[:, _LAST] * a2[:, _NEXT]
    det = np.sum(A[0] * cof[0], axis=0)
    if not np.all(np.isfinite(det)) or np.any(det == 0):
        raise np.linalg.LinAlgError("singular block")
    return np.swapaxes(cof, 0, 1) / det


def _mat(X, Y):
    """``X Y`` for components-first 3x3 stacks (3, 3, ...), broadcasting the rest."""
    return np.sum(X[:, :, None] * Y[None], axis=1)


def _vec(X, y):
    """``X y`` for a components-first 3x3 stack (3, 3, ...) and vectors (3, ...)."""
    return np.sum(X * y[None], axis=1)


def solve_block_tridiagonal(D, upper, lower, rhs, *, refine: int = 1) -> np.ndarray:
    """Solve block tridiagonal systems with 3x3 blocks.

    Parameters
    ----------
    D : ndarray (n, 3, 3, *S)
        Diagonal blocks, components first; ``S`` the shape of the batch of systems.
    upper, lower : ndarray (n - 1, 3, 3, ...)
        Blocks coupling node ``i`` to ``i + 1`` (row ``i``) and ``i + 1`` to ``i``
        (row ``i + 1``); any trailing shape that broadcasts against ``S``.
    rhs : ndarray (n, 3, *S)
        Right-hand sides.
    refine : int
        Refinement steps of each block solve (``X += inv (B - den X)``). The adjugate
        alone loses digits on blocks with a wide stiffness range (axial against
        geometric): on the 12-chain dock 3e-8 of the answer against a dense pivoted solve,
        one step 3e-11 (pivoted solves of the blocks: 5e-11); each step costs about half
        the unrefined sweep again.

    Returns
    -------
    ndarray (n, 3, *S)
        The solutions.

    Raises
    ------
    numpy.linalg.LinAlgError
        A pivot block is singular.
    """
    n = D.shape[0]
    dtype = np.result_type(D, upper, lower, rhs)
    # One dtype throughout: numpy's mixed real-complex products cost several times more.
    D, upper, lower, rhs = (np.asarray(a, dtype) for a in (D, upper, lower, rhs))
    # Row i of the elimination: [C_i | d_i] = den_i^-1 [U_i | r_i], stacked as 3x4 so that
    # each product is one numpy operation.
    Cd = np.empty((n, 3, 4) + rhs.shape[2:], dtype)
    B = np.empty_like(Cd[0])
    den = D[0]
    B[:, 3] = rhs[0]
    for i in range(n):
        if i > 0:
            LC = _mat(lower[i - 1], Cd[i - 1])
            den = D[i] - LC[:, :3]
            B[:, 3] = rhs[i] - LC[:, 3]
        if i < n - 1:
            B[:, :3] = upper[i]
            b = B
        else:
            b = B[:, 3:]
        inv = inverse3(den)
        X = _mat(inv, b)
        for _ in range(refine):
            X += _mat(inv, b - _mat(den, X))
        Cd[i, :, :X.shape[1]] = X
    x = np.empty(rhs.shape, dtype)
    x[n - 1] = Cd[n - 1, :, 0]                     # the last row has no C: d in column 0
    for i in range(n - 2, -1, -1):
        x[i] = Cd[i, :, 3] - _vec(Cd[i, :, :3], x[i + 1])
    return x
