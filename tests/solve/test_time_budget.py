"""The solve's time budget (``solver.max_time_s``) holds on the paths after IPOPT: the
overdamped drift, the search for a stable point from an unstable one and the weathervane
walk each stop when the budget has passed, and hand back what they have."""

from __future__ import annotations

import time

import numpy as np

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
