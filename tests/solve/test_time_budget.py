"""The solve's time budget (``solver.max_time_s``) holds on the paths after IPOPT: the
overdamped drift, the search for a stable point from an unstable one and the weathervane
walk each stop when the budget has passed, and hand back what they have."""

from __future__ import annotations

import time

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve.solve.assembly.cache import get_problem
from moorsolve.solve.stability.static import assess, find_stable, pseudo_transient
from moorsolve.solve.kernels.start import initial_point
from moorsolve.solve.stability.weathervane import stable_heading

from conftest import CASES


def _problem(name):
    case = moorsolve.load_case(CASES / name)
    problem = get_problem(case)
    return case, problem, initial_point(problem, case), problem.parameters(case, 1.0)


def test_the_drift_stops_where_it_is_at_the_deadline():
    case, problem, x0, p = _problem("floating_dock.yaml")
    moved = pseudo_transient(problem, x0, p, steps=5)
    assert not np.array_equal(moved, x0)            # without a deadline it moves
    stopped = pseudo_transient(problem, x0, p, steps=5, deadline=time.perf_counter())
    np.testing.assert_array_equal(stopped, x0)


def test_the_stable_point_search_gives_up_at_the_deadline():
    case, problem, x0, p = _problem("turret_ship.yaml")
    calls = []

    def polish(z):
        calls.append(z)
        return z

    found = find_stable(problem, x0, p, 1e-9, assess(problem, x0, p), polish,
                        deadline=time.perf_counter())
    assert found is None and not calls


def test_the_weathervane_walk_gives_up_at_the_deadline():
    case, problem, x0, p = _problem("turret_ship.yaml")
    calls = []

    def polish(z):
        calls.append(z)
        return z

    assert stable_heading(problem, x0, p, 1e-9, polish, deadline=time.perf_counter()) is None
    assert not calls


class _Clock:
    """A ``time`` module whose ``perf_counter`` advances ``tick`` seconds at each call, so
    a budget is a number of checks, whatever the machine's speed."""

    def __init__(self, tick: float):
        self.t, self.tick, self.calls = 0.0, tick, 0

    def perf_counter(self) -> float:
        self.calls += 1
        self.t += self.tick
        return self.t


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_a_hard_case_on_a_tiny_budget_says_which_path_ran_out(monkeypatch, solver):
    """Vida's chains all slack at rest: only the overdamped drift (up to 2000 steps)
    reaches the equilibrium. On a budget of 20 clock checks the drift stops early and
    the solve says so, instead of drifting on past the budget."""
    import types

    from moorsolve.solve import equilibrium
    from moorsolve.solve.kernels import strategies
    from moorsolve.solve.result import verdict
    from moorsolve.solve.stability import static, weathervane

    data = yaml.safe_load((CASES / "buoy_vida.yaml").read_text())
    data["environment"].pop("wind")
    data["body"] = {"free": ["surge", "sway"], "loads": {"force": [5000.0, 0.0, 0.0]}}
    for leg in data["legs"]:
        leg["segments"][0]["length"] = 90.0
    result = moorsolve.solve(moorsolve.load_case(data), solver=solver)   # no budget issue
    assert "pseudo-transient" in result.certificate.status

    # 5 s of budget, which IPOPT's own clock (real time) never reaches here, and a clock
    # that passes it in 20 checks: the drift, whose steps each check, stops early.
    clock = _Clock(0.25)
    for module in (equilibrium, strategies, verdict, static, weathervane):
        monkeypatch.setattr(module, "time", types.SimpleNamespace(
            perf_counter=clock.perf_counter))
    data["solver"] = {"max_time_s": 5.0}
    with pytest.raises(moorsolve.ConvergenceError) as info:
        moorsolve.solve(moorsolve.load_case(data), solver=solver)
    err = info.value
    assert err.status.startswith("budget_exhausted")
    assert "pseudo-transient fallback" in err.status and "max_time_s = 5 s" in err.status
    assert err.reason.startswith("budget_exhausted") and "max_time_s" in err.reason
    # At most twice the budget in clock checks (20 to the deadline), not 2000 drift steps.
    assert clock.calls <= 40


def test_the_newton_continuation_stops_at_the_deadline():
    from moorsolve.solve.kernels.strategies import _newton_continuation

    case = moorsolve.load_case(CASES / "floating_dock.yaml")
    problem = get_problem(case)
    stats = {"iterations": 0, "status": "not run"}
    x = _newton_continuation(problem, case, problem.newton(), problem.parameters(case, 1.0),
                             1e-9, stats, deadline=time.perf_counter())
    assert x is None and stats["out_of_time"] == "the Newton load continuation"
    assert stats["iterations"] == 0
