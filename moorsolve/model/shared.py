"""One object for equal parts of separately validated cases.

A loop that loads one scene many times (``solve(load_case(d))`` with a new load in each
``d``) makes a new, equal, ``lines`` tuple (and environment, solver options, contacts) per
case. Everything the solver derives from a case's lines is kept per lines *object*
(:mod:`moorsolve.solve.assembly.prepared`), so equal parts made anew would derive it all again.
:func:`shared_parts` hands a new case the parts of an earlier case that equal its own
(frozen values that compare equal: sharing them changes nothing but their identity;
equality merges 0.0 and -0.0, the same position or heading), so what was
derived from the earlier case's parts (line kinds, parameter blocks, the built problem) is
found again.
"""

from __future__ import annotations

import dataclasses

from ..concurrency import LockedLRU

#: Case fields whose equal values are shared (each hashable: frozen dataclasses of tuples).
_FIELDS = ("lines", "environment", "solver", "contacts", "points")
#: Per field, recently seen values: value -> the same value (the one kept).
_SEEN = {name: LockedLRU(32) for name in _FIELDS}
#: Validated line types and legs by their case-file data (model/build.validated_legs).
LEGS = LockedLRU(16)
#: The kept values by identity (an identity check costs nothing; a hash of the lines, tens
#: of microseconds).
_KEPT = LockedLRU(len(_FIELDS) * 32)


def shared_parts(case):
    """``case`` with each of its parts that equals the same part of a recently built case
    replaced by that earlier object (``case`` itself when none does); thread-safe."""
    changes = {}
    for name in _FIELDS:
        value = getattr(case, name)
        if _KEPT.get(id(value)) is value:
            continue                 # already the kept object: no need to hash it
        key = (value, _uncompared(value)) if name == "environment" else value
        try:
            kept = _SEEN[name].get(key)
        except TypeError:            # an unhashable part (a list in a user's subclass)
            continue
        if kept is None:
            _SEEN[name].put(key, value)
            _KEPT.put(id(value), value)
        elif kept is not value:
            changes[name] = kept
    return dataclasses.replace(case, **changes) if changes else case


def _uncompared(environment) -> tuple:
    """What equality of two environments leaves out: where a bathymetry grid was read from
    (``Bathymetry.source``, the one field of the model compared by value only). Two
    environments equal but for it are not the same part to hand on: the case would report
    the other file."""
    seabed = getattr(environment, "seabed", None)
    grid = getattr(seabed, "bathymetry", None)
    return () if grid is None else (grid.source,)


def clear() -> None:
    """Forget the parts seen and the legs validated (for tests)."""
    for seen in _SEEN.values():
        seen.clear()
    _KEPT.clear()
    LEGS.clear()


__all__ = ["shared_parts", "clear"]
