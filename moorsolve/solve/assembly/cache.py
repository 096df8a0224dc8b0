"""The built problems, one per scene structure, shared by every caller under a lock.

Building a problem (and compiling its Newton kernel) costs far more than solving it, so
problems are kept by what decides their shape. The cache is an object that owns its lock:
any number of threads may ask for a problem at once and get the same one, built once.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict

from ...model import Case
from .prepared import HashedKey, per_case
from .prepared import structure_key
from .problem import EquilibriumProblem
from ..kernels.start import scales


class ProblemCache:
    """Built :class:`EquilibriumProblem` objects by structure, least recently used last."""

    def __init__(self, capacity: int = 32):
        self._capacity = capacity
        self._problems: "OrderedDict[tuple, EquilibriumProblem]" = OrderedDict()
        self._lock = threading.Lock()
        self._building: dict = {}

    def get(self, case: Case) -> EquilibriumProblem:
        """The built problem for ``case``'s structure, built on first use."""
        # The scales shape the solver's path (and, where a case has more than one
        # equilibrium, which one it finds), so they are part of the key: a case gets the same
        # problem whatever was solved before it. Rounding them to powers of two lets cases
        # that differ a little (a sweep, a damaged condition) share one build.
        key = problem_key(case)
        force_scale, length_scale = key[1:]
        with self._lock:
            problem = self._problems.get(key)
            if problem is not None:
                self._problems.move_to_end(key)
                return problem
            gate = self._building.get(key)
            if gate is None:
                gate = self._building[key] = threading.Lock()
        # Build outside the cache lock (other structures go on), once per key.
        with gate:
            with self._lock:
                problem = self._problems.get(key)
            if problem is None:
                problem = EquilibriumProblem(case, force_scale, length_scale)
                with self._lock:
                    self._problems[key] = problem
                    self._building.pop(key, None)
                    while len(self._problems) > self._capacity:
                        self._problems.popitem(last=False)
        return problem

    def clear(self) -> None:
        with self._lock:
            self._problems.clear()


@per_case(load_independent=True)
def problem_key(case: Case) -> HashedKey:
    """The key of ``case``'s problem: its structure and its scales rounded to powers of two
    (see :meth:`ProblemCache.get`); computed once per case object."""
    force_scale, length_scale = (2.0 ** round(math.log2(v)) for v in scales(case))
    return HashedKey((structure_key(case), force_scale, length_scale))


#: The process's problem cache.
PROBLEMS = ProblemCache()


def get_problem(case: Case) -> EquilibriumProblem:
    """The built problem for ``case``'s structure (from :data:`PROBLEMS`)."""
    return PROBLEMS.get(case)
