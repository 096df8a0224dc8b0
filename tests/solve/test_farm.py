"""Large scenes (wind farms) on the sparse Newton path: the same answers as the dense kernel,
the sparse stiffness as the dense condensation, the sparse stability verdict as the dense
eigenvalues' sign, and a certificate that still tells an equilibrium from a wrong state.

The farms are ``n`` x ``n`` grids of six-DOF semis on three chains each with shared lines
between neighbours (``benchmarks/farm.py``), of 4 and 9 bodies.
"""

import importlib.util
import sys

import numpy as np
import pytest

import moorsolve
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.solve.kernels.newton import CONVERGED, NewtonKernel
from moorsolve.solve.result.classes import DeferredStability
from moorsolve.solve.kernels.sparse_newton import SparseNewton, uses_sparse_path
from moorsolve.solve.kernels.sparse_stiffness import clearly_positive, inverse_2x2_blocks
from moorsolve.solve.stability.static import _ZERO, _layout, _rows, assess
from moorsolve.solve.kernels.strategies import rest_point
from conftest import ROOT


def _load_farm():
    spec = importlib.util.spec_from_file_location("farm", ROOT / "benchmarks" / "farm.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("farm", module)
    spec.loader.exec_module(module)
    return module


farm = _load_farm()


def _dense_condensed(problem, x, p):
    """The condensation written out densely (least squares on the condensed block), an
    independent computation of K = -(J_qq - J_qr J_rr^-1 J_rq) in SI units."""
    keep, rest = _layout(problem)[:2]
    J = np.asarray(problem.jacobian(x, p))
    rq, rr = _rows(problem, keep), _rows(problem, rest)
    A = J[np.ix_(rq, keep)] - J[np.ix_(rq, rest)] @ np.linalg.lstsq(
        J[np.ix_(rr, rest)], J[np.ix_(rr, keep)], rcond=None)[0]
    row = np.array([problem.moment_scale if problem.rotational[j] else problem.force_scale
                    for j in keep])
    return -(row[:, None] * A) / problem.x_scale[keep][None, :]


@pytest.fixture(scope="module")
def small():
    """A 2 x 2 farm (24 body DOFs: the dense kernel's scene), its problem, parameters and
    rest state."""
    case = farm.farm_case(2)
    problem = get_problem(case)
    p = problem.parameters(case, 1.0)
    return case, problem, p, rest_point(problem, case, case.solver.tol)


@pytest.fixture(scope="module")
def nine():
    """A 3 x 3 farm (54 body DOFs) solved on the sparse path, and its problem."""
    case = farm.farm_case(3)
    result = moorsolve.solve(case, solver="newton")
    problem = get_problem(case)
    return case, result, problem, problem.parameters(case, 1.0)


def test_sparse_path_is_taken_beyond_four_six_dof_bodies(small, nine):
    assert not uses_sparse_path(small[1])
    assert uses_sparse_path(nine[2]) and isinstance(nine[2].newton(), SparseNewton)


def test_sparse_newton_reaches_the_dense_kernels_point(small):
    # Same iteration, sparse steps (lines eliminated in closed form, SuperLU on the
    # bodies) against the dense kernel's unrolled graph: same point, same tensions.
    case, problem, p, x0 = small
    tol = case.solver.tol
    dense = NewtonKernel(problem, compile=False).solve(x0, p, tol)
    sparse = SparseNewton(problem).solve(x0, p, tol)
    assert dense["status"] == sparse["status"] == CONVERGED
    assert sparse["iterations"] == dense["iterations"]
    xd, xs = (o["x"] * problem.x_scale for o in (dense, sparse))
    lengths = [j for j in range(problem.n_q) if not problem.rotational[j]]
    assert np.max(np.abs(xs[lengths] - xd[lengths])) < 1e-9
    t_max = np.max(dense["fairlead_tension"])
    for key in ("fairlead_tension", "anchor_tension"):
        np.testing.assert_allclose(sparse[key], dense[key], rtol=0, atol=1e-9 * t_max)
    np.testing.assert_allclose(sparse["certificate"][2:], dense["certificate"][2:],
                               rtol=1e-12)
    assert problem.judge(*sparse["certificate"], tol=tol)[0]


@pytest.mark.parametrize("dense_nodes", [0, 150], ids=["superlu", "lapack"])
def test_arrow_step_equals_a_direct_sparse_solve(small, dense_nodes, monkeypatch):
    # The block elimination of the lines (the bodies' Schur complement by SuperLU or
    # LAPACK) against SuperLU on the whole Jacobian.
    from moorsolve.solve.kernels import sparse_arrow
    monkeypatch.setattr(sparse_arrow, "DENSE_NODES", dense_nodes)
    import scipy.sparse as sps
    from scipy.sparse.linalg import spsolve
    # Away from rest (the rest state balances the lines, so their residuals vanish there).
    case, problem, p, x0 = small
    kernel = SparseNewton(problem)
    x = x0 + 0.01 * np.random.default_rng(1).normal(size=x0.size)
    g, J = problem.residual_jacobian(x, p)
    g = np.asarray(g).ravel()
    assert np.max(np.abs(g[:2 * problem.n_legs])) > 1e-3
    Jd = sps.csc_matrix(np.asarray(J))
    direct = spsolve(Jd, g)
    arrow = kernel._arrow.step(g, np.asarray(J.nonzeros(), dtype=float))
    np.testing.assert_allclose(arrow, direct, rtol=1e-10, atol=1e-12 * np.max(np.abs(direct)))


def test_inverse_of_2x2_blocks_and_refusals():
    import scipy.sparse as sps
    rng = np.random.default_rng(3)
    blocks = [rng.normal(size=(2, 2)) + 3 * np.eye(2) for _ in range(4)]
    D = sps.block_diag(blocks, format="csr")
    inverse = inverse_2x2_blocks(D)
    np.testing.assert_allclose((inverse @ D).toarray(), np.eye(8), atol=1e-13)
    coupled = D.tolil()
    coupled[1, 2] = 1.0                     # couples two blocks: not block diagonal
    assert inverse_2x2_blocks(coupled.tocsr()) is None
    singular = sps.block_diag([np.ones((2, 2)), np.eye(2)], format="csr")
    assert inverse_2x2_blocks(singular) is None


def test_sparse_stiffness_equals_the_dense_condensation(nine):
    case, result, problem, p = nine
    from moorsolve.solve.stability.static import _sparse_condensed
    K = _sparse_condensed(problem, result.state, p).toarray()
    dense = _dense_condensed(problem, result.state, p)
    assert np.max(np.abs(K - dense)) <= 1e-9 * np.max(np.abs(dense))
    # A farm couples a body with its neighbours only: the stiffness stays sparse.
    assert np.count_nonzero(K) < 0.5 * K.size


def test_sparse_stiffness_with_free_points_equals_the_dense_condensation():
    # The general branch (SuperLU on the lines' and free points' block): three platforms
    # on bridles whose apexes are free points.
    from moorsolve.solve.kernels.sparse_stiffness import sparse_condensed_stiffness
    case = moorsolve.load_case(ROOT / "cases" / "three_platforms.yaml")
    result = moorsolve.solve(case, solver="newton")
    problem = get_problem(case)
    p = problem.parameters(case, 1.0)
    keep, rest = _layout(problem)[:2]
    assert keep.size < problem.n_q                  # free points are condensed too
    K = sparse_condensed_stiffness(problem, result.state, p, keep, rest,
                                   _rows(problem, keep), _rows(problem, rest)).toarray()
    dense = _dense_condensed(problem, result.state, p)
    assert np.max(np.abs(K - dense)) <= 1e-9 * np.max(np.abs(dense))


def test_stiffness_against_central_differences_of_the_residual(nine):
    # K = -dQ/dq with the lines in equilibrium: move one body DOF, re-settle the lines
    # (Newton on their rows with the bodies held), difference the generalized forces.
    from moorsolve.solve.stability.static import _sparse_condensed, _settle
    case, result, problem, p = nine
    keep, _, _, _, _ = _layout(problem)
    K = _sparse_condensed(problem, result.state, p).toarray()
    rq = _rows(problem, keep)
    row = np.array([problem.moment_scale if problem.rotational[j] else problem.force_scale
                    for j in keep])
    for col in (0, 4, 27):              # T0_0 surge, T0_0 pitch, T1_1 heave
        j = keep[col]
        step = (1e-3 if problem.rotational[j] else 1e-2) / problem.x_scale[j]
        Q = []
        for sign in (1.0, -1.0):
            trial = result.state.copy()
            trial[j] += sign * step
            trial, ok = _settle(problem, trial, p, keep)
            assert ok
            Q.append(np.asarray(problem.residual(trial, p)).ravel()[rq] * row)
        column = -(Q[0] - Q[1]) / (2 * step * problem.x_scale[j])
        scale = np.max(np.abs(K[:, col]))
        assert np.max(np.abs(column - K[:, col])) < 1e-4 * scale


def _homogenised(problem, x, p):
    from moorsolve.solve.stability.static import _sparse_condensed
    keep, _, h, _, _ = _layout(problem)
    return _sparse_condensed(problem, x, p).multiply((1 / h)[:, None]).multiply(
        (1 / h)[None, :]).tocsc()


def test_stable_verdict_equals_the_dense_eigenvalues_sign(nine):
    case, result, problem, p = nine
    Kh = _homogenised(problem, result.state, p)
    values = np.linalg.eigvals(Kh.toarray())
    assert values.real.min() > _ZERO * np.abs(values).max()
    assert clearly_positive(Kh, _ZERO)
    stability = result.stability
    assert stability.stable and isinstance(stability, DeferredStability)
    # Its eigenvalues, read lazily, are the dense ones.
    np.testing.assert_allclose(sorted(np.real(stability.eigenvalues)), sorted(values.real),
                               rtol=1e-9)
    assert stability.min_eigenvalue == pytest.approx(values.real.min(), rel=1e-9)


def test_unstable_farm_is_found_unstable_as_by_dense_eigenvalues():
    # Metacentre 20 m below the centre of gravity: roll and pitch unstable whatever the
    # chains add. Solved without the stability search, then assessed.
    data = farm.farm_dict(3)
    for body in data["bodies"]:
        body["centre_of_gravity"] = [0.0, 0.0, 5.0]
        body["hydrostatics"]["metacentre"] = [0.0, 0.0, -15.0]
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case, solver="newton", stability=False)
    problem = get_problem(case)
    p = problem.parameters(case, 1.0)
    Kh = _homogenised(problem, result.state, p)
    values = np.linalg.eigvals(Kh.toarray())
    assert values.real.min() < 0
    assert not clearly_positive(Kh, _ZERO)
    verdict = assess(problem, result.state, p)
    assert not verdict.stable and verdict.unstable_dofs
    assert verdict.min_eigenvalue == pytest.approx(values.real.min(), rel=1e-9)
    assert any(d.endswith(("roll", "pitch")) for d in verdict.unstable_dofs)


@pytest.mark.parametrize("dense_dofs", [0, 150], ids=["superlu", "lapack"])
def test_clearly_positive_against_eigenvalues_of_random_matrices(dense_dofs, monkeypatch):
    # Symmetric-part test: positive definite symmetric parts pass, an indefinite one
    # fails, whatever the sparse ordering (SuperLU's LDL^T pivots or LAPACK's Cholesky).
    import scipy.sparse as sps
    from moorsolve.solve.kernels import sparse_stiffness
    monkeypatch.setattr(sparse_stiffness, "DENSE_DOFS", dense_dofs)
    outcomes = set()
    rng = np.random.default_rng(7)
    for trial in range(20):
        n = 30
        A = sps.random(n, n, density=0.1, random_state=rng).toarray()
        shift = rng.uniform(-1.0, 3.0)
        M = A + A.T + shift * np.eye(n) + 0.1 * (A - A.T)
        S = (M + M.T) / 2
        c = _ZERO * np.linalg.norm(M)
        expected = np.linalg.eigvalsh(S).min() > c
        assert clearly_positive(sps.csc_matrix(M), _ZERO) == expected
        outcomes.add(expected)
    assert outcomes == {True, False}


def test_certificate_certifies_and_fails_on_a_planted_state(nine):
    case, result, problem, p = nine
    tol = case.solver.tol
    assert result.converged and result.certificate.relative <= tol
    post = problem.post(result.state, p)
    assert problem.judge(*post["certificate"].ravel().tolist(), tol=tol)[0]
    assert post["stiffness"].size == 0 and post["clearly_stable"].item() == 0
    wrong = result.state.copy()
    j = problem.nodes.index(("body", 4, "surge"))
    wrong[j] += 1.0 / problem.x_scale[j]        # the middle platform 1 m off
    post = problem.post(wrong, p)
    ok, force, _, _ = problem.judge(*post["certificate"].ravel().tolist(), tol=tol)
    assert not ok and force > 1e3
    assert not problem.certify(wrong, p, tol)[0]


def test_farm_result_carries_every_field(nine):
    case, result, problem, p = nine
    assert result.solver == "newton"
    assert len(result.lines) == len(case.lines) == 9 * 3 + 12
    assert len(result.bodies) == 9
    # Under a thrust toward +x every platform drifts downwind.
    assert all(b["x_m"] - b0["position"][0] > 1.0
               for b, b0 in zip(result.bodies, farm.farm_dict(3)["bodies"]))
    d = result.to_dict()
    assert d["stability"]["stable"] is True


def test_farm_load_table_rows_equal_single_solves(nine):
    # A load table through the sparse path's batch (run_many) and its sparse stability
    # check: each row as its own solve.
    import pandas as pd
    case, result, problem, p = nine
    thrusts = [800.0, 1900.0]
    table = pd.DataFrame({f"bodies[{b.name}].loads.force[0] [kN]": thrusts
                          for b in case.bodies})
    out = moorsolve.sweep(case, table=table, workers=1)
    assert out["converged"].all() and out["stable"].all()
    data = farm.farm_dict(3)
    for row, thrust in enumerate(thrusts):
        for body in data["bodies"]:
            body["loads"]["force"][0] = thrust * 1e3
        single = moorsolve.solve(moorsolve.load_case(data), solver="newton")
        for leg in single.legs:
            assert out[f"{leg.name}.fairlead_tension_N"][row] == pytest.approx(
                leg.fairlead_tension_N, rel=1e-9)
        assert out["min_eigenvalue"][row] == pytest.approx(
            single.stability.min_eigenvalue, rel=1e-6)


def test_multi_segment_farm_takes_the_general_sparse_step_and_agrees_with_ipopt():
    # Two-segment chains: more than two unknowns a line, so no closed-form elimination
    # (SuperLU on the whole Jacobian, the exact certificate as the stopping test).
    data = farm.farm_dict(3)
    for line in data["lines"]:
        if line["name"].startswith("T"):
            line["segments"] = [{"type": "chain", "length": 400.0},
                                {"type": "chain", "length": 450.0}]
    case = moorsolve.load_case(data)
    fast = moorsolve.solve(case, solver="newton")
    kernel = get_problem(case).newton()
    assert isinstance(kernel, SparseNewton) and kernel._arrow is None
    assert fast.solver == "newton" and fast.stability.stable
    ref = moorsolve.solve(case, solver="ipopt")
    t_max = max(leg.fairlead_tension_N for leg in ref.legs)
    for a, b in zip(fast.bodies, ref.bodies):
        for key in ("x_m", "y_m", "z_m"):
            assert abs(a[key] - b[key]) < 1e-9
    for a, b in zip(fast.legs, ref.legs):
        assert abs(a.fairlead_tension_N - b.fairlead_tension_N) < 1e-9 * t_max
