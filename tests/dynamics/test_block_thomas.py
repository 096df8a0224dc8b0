"""The block tridiagonal sweep shared by the lines' dynamics
(moorsolve.dynamics.block_thomas) against dense solves of the same systems."""

import numpy as np
import pytest

from moorsolve.dynamics.block_thomas import inverse3, solve_block_tridiagonal


def _dense(D, upper, lower, k):
    n, batch = D.shape[0], D.shape[3:]
    upper, lower = (np.broadcast_to(b, b.shape[:3] + batch) for b in (upper, lower))
    A = np.zeros((3 * n, 3 * n), complex)
    for i in range(n):
        A[3 * i:3 * i + 3, 3 * i:3 * i + 3] = D[i][(...,) + k]
        if i < n - 1:
            A[3 * i:3 * i + 3, 3 * i + 3:3 * i + 6] = upper[i][(...,) + k]
            A[3 * i + 3:3 * i + 6, 3 * i:3 * i + 3] = lower[i][(...,) + k]
    return A


def test_sweep_solves_random_systems_with_distinct_lower_blocks():
    # Lower blocks unrelated to the upper ones, a batch of 4 x 5 systems.
    rng = np.random.default_rng(2)
    n, S = 7, (4, 5)
    D = rng.normal(size=(n, 3, 3) + S) + 1j * rng.normal(size=(n, 3, 3) + S)
    D += 8 * np.eye(3)[None, :, :, None, None]
    upper = rng.normal(size=(n - 1, 3, 3) + S)
    lower = rng.normal(size=(n - 1, 3, 3) + S) + 1j * rng.normal(size=(n - 1, 3, 3) + S)
    rhs = rng.normal(size=(n, 3) + S) + 1j * rng.normal(size=(n, 3) + S)
    x = solve_block_tridiagonal(D, upper, lower, rhs)
    for k in np.ndindex(*S):
        ref = np.linalg.solve(_dense(D, upper, lower, k), rhs[(...,) + k].ravel())
        assert np.allclose(x[(...,) + k].ravel(), ref, rtol=0, atol=1e-12 * np.abs(ref).max())


def test_sweep_broadcasts_blocks_shared_by_a_batch():
    # Coupling blocks per line (shape (..., 3, 1)) shared by all its frequencies, as in
    # the stacked lines; the same as the blocks broadcast out.
    rng = np.random.default_rng(3)
    n, S = 5, (3, 4)
    D = rng.normal(size=(n, 3, 3) + S) + 6 * np.eye(3)[None, :, :, None, None] + 0j
    upper = rng.normal(size=(n - 1, 3, 3, 3, 1))
    lower = upper.transpose(0, 2, 1, 3, 4).copy()
    rhs = rng.normal(size=(n, 3) + S) + 0j
    x = solve_block_tridiagonal(D, upper, lower, rhs)
    full = [np.broadcast_to(b, (n - 1, 3, 3) + S) for b in (upper, lower)]
    assert np.array_equal(x, solve_block_tridiagonal(D, *full, rhs))
    for k in np.ndindex(*S):
        ref = np.linalg.solve(_dense(D, *full, k), rhs[(...,) + k].ravel())
        assert np.allclose(x[(...,) + k].ravel(), ref, rtol=0, atol=1e-12 * np.abs(ref).max())


def test_sweep_keeps_the_digits_of_stiff_blocks():
    # A taut chain of axially stiff, laterally soft elements (EA/l : T/l = 1e6), ends
    # prescribed (identity rows, coupling masked as the lines' stack does), mass and
    # damping on the free nodes: condition numbers ~ 5e10. Pivoted solves of the blocks
    # reach 1.5e-9 of the dense solve here; the adjugate refined once 5e-8, twice 2e-9.
    rng = np.random.default_rng(4)
    n, N = 30, 6
    t = rng.normal(size=(n - 1, 3))
    t[:, 2] *= 0.1
    t[:, 0] = np.abs(t[:, 0]) + 2
    t /= np.linalg.norm(t, axis=1)[:, None]
    tt = t[:, :, None] * t[:, None, :]
    ke = 1e9 * tt + 1e3 * (np.eye(3) - tt)
    D = np.zeros((n, 3, 3))
    D[:-1] += ke
    D[1:] += ke
    fixed = np.zeros(n, bool)
    fixed[[0, -1]] = True
    D[fixed] = np.eye(3)
    upper, lower = -ke.copy(), -ke.copy()
    upper[fixed[:-1]] = 0.0
    lower[fixed[1:]] = 0.0
    w = np.linspace(0.2, 2.0, N)
    D = D[..., None] + ((-w ** 2 * 1e2 + 1j * w * 10) * np.eye(3)[None, :, :, None]
                        * (~fixed)[:, None, None, None])
    rhs = np.zeros((n, 3, N), complex)
    rhs[-1], rhs[0] = 1.0, 0.3j
    x1 = solve_block_tridiagonal(D, upper[..., None], lower[..., None], rhs)
    x2 = solve_block_tridiagonal(D, upper[..., None], lower[..., None], rhs, refine=2)
    for k in range(N):
        A = _dense(D, upper[..., None], lower[..., None], (k,))
        ref = np.linalg.solve(A, rhs[:, :, k].ravel())
        assert np.abs(x1[:, :, k].ravel() - ref).max() < 1e-7 * np.abs(ref).max()
        assert np.abs(x2[:, :, k].ravel() - ref).max() < 5e-9 * np.abs(ref).max()


def test_inverse_and_singular_blocks():
    rng = np.random.default_rng(5)
    M = rng.normal(size=(3, 3, 7)) + 1j * rng.normal(size=(3, 3, 7))
    inv = inverse3(M)
    for k in range(7):
        assert np.allclose(inv[:, :, k] @ M[:, :, k], np.eye(3), atol=1e-12)
    M[:, 2, 3] = M[:, 0, 3] + M[:, 1, 3]                      # one singular block
    M[:, :, 3] = M[:, :, 3].real
    M[0, 0, 3] = M[0, 1, 3] = 0.0
    M[:, 2, 3] = M[:, 0, 3]
    with pytest.raises(np.linalg.LinAlgError):
        inverse3(M)
    D = np.tile(np.eye(3)[None, :, :, None], (3, 1, 1, 2)).astype(complex)
    D[1, :, :, 1] = 0.0                                       # a node with nothing to hold it
    with pytest.raises(np.linalg.LinAlgError):
        solve_block_tridiagonal(D, np.zeros((2, 3, 3, 1)), np.zeros((2, 3, 3, 1)),
                                np.ones((3, 3, 2), complex))
