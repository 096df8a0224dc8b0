"""What lets many threads use moorsolve at once: locked caches and the symbolic-build lock.

CasADi's symbolic expressions share reference-counted nodes that are not safe to create or
destroy from two threads at once, so every construction of a CasADi graph or Function
(building a problem, its Newton kernel, an IPOPT solver, a derived study function) happens
under :data:`SYMBOLIC_LOCK`. Evaluating a built Function is guarded per problem
(:attr:`moorsolve.solve.assembly.problem.EquilibriumProblem.lock`); compiled kernels give each
thread its own buffers.
"""

from __future__ import annotations

import threading
from collections import OrderedDict


#: Held while a CasADi graph or Function is built (re-entrant: builds nest).
SYMBOLIC_LOCK = threading.RLock()


class LockedLRU:
    """``get``/``put`` of at most ``capacity`` entries; safe to use from many threads."""

    def __init__(self, capacity: int):
        self._capacity = capacity
        self._items: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key, default=None):
        with self._lock:
            value = self._items.get(key, default)
            if key in self._items:
                self._items.move_to_end(key)
            return value

    def put(self, key, value) -> None:
        with self._lock:
            self._items[key] = value
            self._items.move_to_end(key)
            while len(self._items) > self._capacity:
                self._items.popitem(last=False)

    def __len__(self) -> int:
        with self._lock:
            return len(self._items)

    def clear(self) -> None:
        with self._lock:
            self._items.clear()
