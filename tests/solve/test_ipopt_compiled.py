"""IPOPT's NLP functions compiled once a problem is hot (issue 16): the same iterates, so
the same certified points, interpreted or compiled; the compile starts only after repeated
solves and never where compiling is off. Tests never assert times."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import moorsolve
from moorsolve.solve.kernels import ipopt_solvers
from moorsolve.solve.assembly.cache import PROBLEMS, get_problem
from conftest import CASES


@pytest.fixture(autouse=True)
def fresh_problems():
    """Each test meets its problems newly built (none made hot by another test)."""
    PROBLEMS.clear()


def scene(force=(2e4, 5e3, 1e5)) -> dict:
    """One body on two chains."""
    return {"environment": {"depth": 30.0},
            "line_types": {"chain": {"weight_in_water": 900.0, "ea": 4e8}},
            "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": list(force)}},
            "legs": [{"name": "W", "anchor": [-150.0, 0.0], "fairlead": [-5.0, 0.0, 0.0],
                      "segments": [{"type": "chain", "length": 160.0}]},
                     {"name": "E", "anchor": [150.0, 0.0], "fairlead": [5.0, 0.0, 0.0],
                      "segments": [{"type": "chain", "length": 160.0}]}]}


def quay_cases(n) -> list:
    """The shipped dock at a quay (fenders and hawsers: IPOPT solves their smoothed
    complementarities) under ``n`` wind speeds."""
    data = copy.deepcopy(moorsolve.load_case(CASES / "dock_quay.yaml").source)
    out = []
    for speed in np.linspace(20.0, 35.0, n):
        data["environment"]["wind"]["speed"] = float(speed)
        out.append(moorsolve.load_case(copy.deepcopy(data)))
    return out


def chain_cases(n) -> list:
    base = scene()
    rng = np.random.default_rng(7)
    out = []
    for _ in range(n):
        base["body"]["loads"]["force"] = [rng.uniform(-3e4, 3e4), rng.uniform(-3e4, 3e4),
                                          rng.uniform(-1e5, 1e5)]
        out.append(moorsolve.load_case(copy.deepcopy(base)))
    return out


@pytest.mark.parametrize("make", [chain_cases, quay_cases])
def test_compiled_ipopt_gives_the_same_points(make):
    cases = make(3)
    before = [moorsolve.solve(c) for c in cases]
    solvers = get_problem(cases[0]).ipopt_solvers
    assert not solvers.compiled
    if not solvers.wait_compiled(600):
        return          # no C compiler here: nothing compiled to compare
    after = [moorsolve.solve(c) for c in cases]
    assert solvers.compiled
    for a, b in zip(before, after):
        assert b.certificate.relative <= b.certificate.tolerance
        assert np.array_equal(a.state, b.state)
        assert a.certificate.iterations == b.certificate.iterations
    # The strategy's certificate, compiled: the problem's numbers, here and off equilibrium.
    problem = get_problem(cases[0])
    rng = np.random.default_rng(3)
    for case, result in zip(cases, after):
        p = problem.parameters(case)
        for x in (result.state, result.state * (1 + 1e-3 * rng.standard_normal(problem.n_x))):
            expected = [float(v) for v in problem.certificate(x, p)]
            assert solvers.certificate_values(x, p) == expected
            assert solvers.certify(x, p, 1e-9) == problem.certify(x, p, 1e-9)[0]


def test_compile_starts_after_repeated_solves(monkeypatch):
    monkeypatch.setattr(ipopt_solvers, "COMPILE_AFTER", 3)
    case = moorsolve.load_case(scene())
    solvers = get_problem(case).ipopt_solvers
    for _ in range(2):
        moorsolve.solve(case)
    assert solvers.library is None
    moorsolve.solve(case)
    assert solvers.library is not None
    solvers.library.wait(600)
    moorsolve.solve(case)           # on whichever solver is ready


def test_compile_off_runs_interpreted(monkeypatch):
    monkeypatch.setenv("MOORSOLVE_COMPILE", "off")
    case = moorsolve.load_case(scene())
    result = moorsolve.solve(case)
    solvers = get_problem(case).ipopt_solvers
    assert not solvers.wait_compiled(1)
    assert np.array_equal(moorsolve.solve(case).state, result.state)
