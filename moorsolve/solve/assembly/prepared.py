"""What a solve derives from a Case, computed once per Case object.

A :class:`~moorsolve.model.Case` is frozen, so everything that depends on it alone (its line
kinds, its structure key, its parameter vector, its scales) can be computed at its first
use and kept beside it: :func:`per_case` memoises a function of a case in a table keyed by
the object's identity, with a weak reference that drops the entry when the case is freed.
One solve asks for each of these several times (the problem cache, the start points, the
rest state); a sweep or a benchmark asks again for the same case object.

Cases made from one another by :func:`dataclasses.replace` (a new load on the same lines)
share their ``lines`` tuple: the line kinds, the costliest part of the structure key, are
also kept per lines tuple and the context they depend on (:func:`line_kinds_of`).

A loop that solves one scene under many constant loads makes a new Case object per load,
and each would derive everything again (tens of microseconds, more than a compiled solve of
a small scene). So the newest case seen on a lines tuple is kept as a *sibling* candidate:
a new case that differs from it only in the values of its bodies' constant forces
(:func:`_only_forces_differ`) takes over the values of every function memoised with
``per_case(..., load_independent=True)``, and its parameter vector is the sibling's with
the environment and body blocks (where the forces sit) made anew.

:func:`load_free` strips a parameter vector of what only acts through the load factor
(flows, constant forces, the load factor itself): the rest state and the closed-form start
depend on nothing else, so they are found once per geometry, not once per load.

Everything here is safe to call from many threads: the tables are guarded by one lock and
the values are immutable (parameter vectors are handed out as copies).
"""

from __future__ import annotations

import dataclasses
import functools
import threading
import weakref
from typing import NamedTuple

import numpy as np

from . import layout
from ...model import Body, BodyLoads
from ...concurrency import LockedLRU
from ..contact.blocks import contact_points

# Re-entrant: a case freed while the table is locked calls _forget on the same thread.
_LOCK = threading.RLock()
#: id(case) -> (weak reference to the case, {function: value}).
_TABLE: dict = {}


def _forget(key: int, ref) -> None:
    with _LOCK:
        entry = _TABLE.get(key)
        if entry is not None and entry[0] is ref:
            del _TABLE[key]


def _values_of(case) -> dict | None:
    """The memoised values of ``case`` (None before its first)."""
    entry = _TABLE.get(id(case))
    return entry[1] if entry is not None and entry[0]() is case else None


def _store(case, fn, value):
    """Memoise ``value`` as ``fn(case)``; the value kept (a racing thread's may win)."""
    return _store_many(case, {fn: value})[fn]


def _store_many(case, new: dict) -> dict:
    """Memoise every ``fn: value`` of ``new`` for ``case`` (values already there win);
    ``case``'s memoised values."""
    key = id(case)
    with _LOCK:
        entry = _TABLE.get(key)
        if entry is None or entry[0]() is not case:
            ref = weakref.ref(case, functools.partial(_forget, key))
            entry = _TABLE[key] = (ref, {})
        values = entry[1]
        for fn, value in new.items():
            values.setdefault(fn, value)
        return values


#: The functions memoised with ``load_independent=True`` (their undecorated selves).
_LOAD_INDEPENDENT: set = set()
_MISSING = object()


def per_case(fn=None, *, load_independent: bool = False):
    """Memoise ``fn(case)`` per Case object (see the module notes). ``fn`` must return an
    immutable value or one its callers never modify. ``load_independent``: the value does
    not depend on the values of the bodies' constant forces, so a sibling's is taken over
    (:func:`_sibling`)."""
    if fn is None:
        return functools.partial(per_case, load_independent=load_independent)
    if load_independent:
        _LOAD_INDEPENDENT.add(fn)

    @functools.wraps(fn)
    def wrapper(case):
        # Reads need no lock (a dict lookup is atomic); writes take it.
        values = _values_of(case)
        if values is not None and fn in values:
            return values[fn]
        if load_independent and (values is None or _SIBLING_KEY not in values):
            # The first look for a sibling takes over everything it knows at once.
            _sibling(case)
            value = _values_of(case).get(fn, _MISSING)
            if value is not _MISSING:
                return value
        return _store(case, fn, fn(case))

    return wrapper


#: Per lines tuple, the newest case seen on it (a strong reference: a loop's previous case
#: is usually freed before the next is made).
_NEWEST = LockedLRU(64)
#: The keys of a case's sibling (a weak reference, or None) and of the sibling's parameter
#: parts (:func:`_parameter_parts`) among its memoised values.
_SIBLING_KEY, _SIBLING_PARTS_KEY = "sibling", "sibling parameters"


def _sibling(case):
    """An earlier case whose load-independent values ``case`` takes over (it differs only
    in the values of its bodies' constant forces), or None; found once per case, when the
    values then known of the sibling are taken over."""
    values = _values_of(case)
    if values is not None and _SIBLING_KEY in values:
        ref = values[_SIBLING_KEY]
        return ref() if ref is not None else None
    lines = case.lines
    newest = _NEWEST.get(id(lines))
    found = None
    if newest is not None and newest[0] is lines and newest[1] is not case \
            and _only_forces_differ(case, newest[1]):
        found = newest[1]
    _NEWEST.put(id(lines), (lines, case))
    taken = {}
    if found is not None:
        known = _values_of(found) or {}
        taken = {fn: value for fn, value in list(known.items()) if fn in _LOAD_INDEPENDENT}
        # Its parameter vector too, to be remade in its force blocks only: the sibling
        # itself is usually freed next (a loop's previous case).
        parts = known.get(_PARTS_KEY)
        if parts is not None:
            taken[_SIBLING_PARTS_KEY] = parts
    # A weak reference: a chain of siblings must not keep every earlier case alive.
    taken[_SIBLING_KEY] = weakref.ref(found) if found is not None else None
    _store_many(case, taken)
    return found


_CASE_FIELDS = ("environment", "points", "solver", "contacts", "line_types", "form")
_BODY_FIELDS = tuple(f.name for f in dataclasses.fields(Body) if f.name != "loads")
_LOAD_FIELDS = tuple(f.name for f in dataclasses.fields(BodyLoads) if f.name != "force")


def _same(a, b) -> bool:
    return a is b or a == b


def _only_forces_differ(case, other) -> bool:
    """Whether ``case`` and ``other`` (on the same lines) differ at most in the values of
    their bodies' constant forces (each present in both or in neither, of one length)."""
    if len(case.bodies) != len(other.bodies):
        return False
    for f in _CASE_FIELDS:
        if not _same(getattr(case, f), getattr(other, f)):
            return False
    for a, b in zip(case.bodies, other.bodies):
        if a is b:
            continue
        for f in _BODY_FIELDS:
            if not _same(getattr(a, f), getattr(b, f)):
                return False
        la, lb = a.loads, b.loads
        if la is lb:
            continue
        if (la.force is None) != (lb.force is None) or (
                la.force is not None and len(la.force) != len(lb.force)):
            return False
        for f in _LOAD_FIELDS:
            if not _same(getattr(la, f), getattr(lb, f)):
                return False
    return True


class HashedKey(tuple):
    """A tuple that computes its hash once (keys made of dataclasses hash slowly, and a
    case's keys are looked up at every solve)."""

    def __new__(cls, items):
        key = super().__new__(cls, items)
        key._hash = tuple.__hash__(key)
        return key

    def __hash__(self) -> int:
        return self._hash


#: Line kinds per lines tuple and context (see :func:`line_kinds_of`).
_KINDS = LockedLRU(256)


def _kinds_context(case) -> tuple:
    """Everything besides the lines that :func:`~.line_kinds.line_kind` reads, or that shapes
    their parameters: the seabed, the current (whether there is one, its profile's length and
    whether its rows carry headings), the elements of a lumped line
    and every body's case pose (which end of a line hanging between bodies is lower)."""
    env = case.environment
    current = env.current
    return (env.depth, env.seabed, current is not None,
            len(current.profile) if current is not None and current.profile else 0,
            # Rows with a heading take three parameters, signed rows two.
            bool(current is not None and current.profile and current.profile_headings),
            case.solver.line_elements,
            tuple((b.name, tuple(b.position), tuple(b.orientation_deg)) for b in case.bodies))


@per_case(load_independent=True)
def line_kinds_of(case) -> tuple:
    """:func:`~.line_kinds.line_kinds` of ``case``, as a tuple, computed once per case and per
    lines tuple in the same context."""
    from ..lines.line_kinds import line_kinds

    key = (id(case.lines), _kinds_context(case))
    hit = _KINDS.get(key)
    if hit is not None and hit[0] is case.lines:
        return hit[1]
    kinds = HashedKey(line_kinds(case))
    _KINDS.put(key, (case.lines, kinds))
    return kinds


#: What each line's ends are attached to, per lines tuple.
_ENDS = LockedLRU(256)


def line_ends_of(case) -> HashedKey:
    """Per line, what its ends are attached to (part of the structure key), once per
    lines tuple."""
    hit = _ENDS.get(id(case.lines))
    if hit is not None and hit[0] is case.lines:
        return hit[1]
    ends = HashedKey((line.a.kind, line.a.on_seabed, line.a.point, line.a.body,
                      line.b.kind, line.b.on_seabed, line.b.point, line.b.body)
                     for line in case.lines)
    _ENDS.put(id(case.lines), (case.lines, ends))
    return ends


class LineFacts(NamedTuple):
    """What a Result's making asks of a case's lines at every solve."""
    #: Whether a line type is sealed (wall tension, audit warnings).
    sealed: bool
    #: Whether a one-segment line is weightless (a hawser).
    hawsers: bool
    #: Whether a segment is fibre rope.
    fibre: bool
    #: ``clump_weight`` and ``buoy`` where the lines carry them.
    clump_effects: tuple
    #: Each line's minimum breaking load [N] (inf where none is given; read-only).
    mbl: np.ndarray
    #: Whether any line has a minimum breaking load (else none can be over it).
    any_mbl: bool


_FACTS = LockedLRU(256)


@per_case(load_independent=True)
def line_facts(case) -> LineFacts:
    """:class:`LineFacts` of ``case``'s lines, once per lines tuple."""
    lines = case.lines
    hit = _FACTS.get(id(lines))
    if hit is not None and hit[0] is lines:
        return hit[1]
    segments = [seg for line in lines for seg in line.segments]
    clumps = [c.weight for line in lines for c in line.joint_clumps if c is not None]
    mbl = np.array([line.line_type.mbl or np.inf for line in lines])
    mbl.setflags(write=False)
    facts = LineFacts(
        sealed=any(seg.line_type.sealed for seg in segments),
        hawsers=any(line.line_type.weight_in_water == 0 and not line.multi_segment
                    for line in lines),
        fibre=any(seg.line_type.fibre for seg in segments),
        clump_effects=(("clump_weight",) if any(w > 0 for w in clumps) else ())
        + (("buoy",) if any(w < 0 for w in clumps) else ()),
        mbl=mbl, any_mbl=bool(np.isfinite(mbl).any()))
    _FACTS.put(id(lines), (lines, facts))
    return facts


#: The line and seabed blocks of parameter vectors, per lines tuple and seabed.
_LINE_BLOCKS = LockedLRU(256)


@per_case
def _parameter_parts(case) -> tuple:
    """``(p, body_block)``: the parameter vector at load factor 1 (read-only) and the slice
    of its body block. From a sibling (:func:`_sibling`) only the blocks that hold the
    constant forces, the environment's and the bodies', are made anew."""
    _sibling(case)
    # Only parts the sibling had made: asking it to make its own could recurse down a chain.
    parts = _values_of(case).get(_SIBLING_PARTS_KEY)
    if parts is not None:
        p_sibling, bodies = parts
        p = p_sibling.copy()
        p[:len(layout.ENV_PARAMS)] = layout.environment_parameters(case, 1.0)
        p[bodies] = layout.body_parameters(case)
        p.setflags(write=False)
        return p, bodies
    env = case.environment
    kinds = line_kinds_of(case)
    # The kinds too: the same lines are lumped in a current and closed-form without one.
    key = (id(case.lines), kinds, env.depth, env.seabed,
           env.current.profile if env.current is not None else None)
    hit = _LINE_BLOCKS.get(key)
    if hit is not None and hit[0] is case.lines:
        lines, laws = hit[1], hit[2]
    else:
        from ..lines.stretch_params import stretch_parameters
        lines = np.concatenate([layout.line_parameters(case),
                                layout.segment_parameters(case, kinds)])
        laws = stretch_parameters(case)
        _LINE_BLOCKS.put(key, (case.lines, lines, laws))
    body_block = layout.body_parameters(case)
    start = len(layout.ENV_PARAMS) + len(lines)
    p = np.concatenate([layout.environment_parameters(case, 1.0), lines, body_block,
                        layout.point_parameters(case), layout.contact_parameters(case), laws])
    p.setflags(write=False)
    return p, slice(start, start + len(body_block))


#: How :func:`_parameter_parts` is memoised (its undecorated self).
_PARTS_KEY = _parameter_parts.__wrapped__


def _parameters(case) -> np.ndarray:
    return _parameter_parts(case)[0]


def parameter_vector(case, load_factor: float = 1.0, kinds=None) -> np.ndarray:
    """The full parameter vector ``p`` of ``case``'s problem (a fresh array), assembled once
    per case object from :mod:`.layout`'s blocks (:func:`case_parameters`); ``kinds``, the
    case's own line kinds, is accepted for the callers that hold them."""
    return case_parameters(case, load_factor)


def case_parameters(case, load_factor: float = 1.0) -> np.ndarray:
    """The parameter vector of ``case`` (a fresh array) at ``load_factor``."""
    p = _parameters(case).copy()
    p[layout.LOAD_FACTOR_INDEX] = load_factor
    return p


#: Load masks per line kinds tuple and the shape of the bodies and points.
_MASKS = LockedLRU(64)


@per_case(load_independent=True)
def load_mask(case) -> np.ndarray:
    """Entries of ``case``'s parameter vector that act only through the load factor."""
    kinds = line_kinds_of(case)
    # The berth's block changes the vector's length (a fender's table rows, its height).
    # So does a current profile's row count (lumped lines see each row): cases that share
    # their lines (and so their kinds) may differ there.
    current = case.environment.current
    profile = (0 if current is None or not current.profile
               else (3 if current.profile_headings else 2) * len(current.profile))
    key = (id(kinds), tuple((b.stiffness is not None, len(b.hull)) for b in case.bodies),
           len(case.free_points), layout.contact_parameters(case).size, profile)
    hit = _MASKS.get(key)
    if hit is not None and hit[0] is kinds:
        return hit[1]
    mask = layout.build_layout(case, kinds).load_mask()
    mask.setflags(write=False)
    _MASKS.put(key, (kinds, mask))
    return mask


def load_free(case, p: np.ndarray) -> bytes:
    """``p`` with its load entries (:func:`load_mask`) zeroed, as bytes: a key for what
    does not depend on the loads (the rest state, the closed-form start)."""
    q = np.array(p, dtype=float)
    q[load_mask(case)] = 0.0
    return q.tobytes()


@per_case(load_independent=True)
def geometry_key(case) -> HashedKey:
    """``case``'s structure key and its load-free parameters: equal for two cases whose
    rest states are equal."""
    return HashedKey((structure_key(case), load_free(case, _parameters(case))))


def clear() -> None:
    """Forget every memoised value (for tests that measure a first solve)."""
    with _LOCK:
        _TABLE.clear()
    _KINDS.clear()
    _NEWEST.clear()


@per_case(load_independent=True)
def structure_key(case) -> tuple:
    """What decides the shape of the built problem (not its parameter values); computed
    once per case object."""
    bodies = tuple(
        (b.name, tuple(b.free), b.mass is not None, b.hydrostatics is not None,
         tuple(m.shape for m in b.hull), b.stiffness is not None,
         dataclasses.replace(b.loads, force=None), b.loads.force is not None)
        for b in case.bodies)
    berth = (tuple(w.name for w in case.contacts.walls),
             tuple(p.name for p in case.contacts.piles), tuple(contact_points(case)))
    return HashedKey((
        line_kinds_of(case), line_ends_of(case), bodies,
        tuple(p.name for p in case.free_points),
        case.form, berth,
        case.environment.wind is not None, case.environment.current is not None,
        case.environment.waves is not None,
        case.environment.air_density, case.environment.water_density,
        case.environment.gravity, case.environment.seabed.bathymetry is not None,
    ))
