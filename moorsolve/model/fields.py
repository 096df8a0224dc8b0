"""Checked conversion of case-file values: mappings, lists, quantities with units, names.

Every failure raises :class:`~moorsolve.errors.CaseError` with the dotted path of the value
(``legs[3].segments[0].length``) and a message naming the value and what is allowed. The
plausibility limits below catch unit slips (mm for m) before they reach the solver.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from ..errors import CaseError
from .schema import get as get_section
from .units import describe, format_si, show_value, to_si


#: Highest fairlead allowed [m above still water]; catches a unit slip (mm for m) early.
FAIRLEAD_Z_MAX = 1000.0
#: Steepest seabed accepted (rise per metre): 45 deg. A chain does not rest on a steeper one.
MAX_GRADIENT = 1.0
#: The deepest ocean is under 11 km; a larger depth is a unit mistake.
MAX_DEPTH = 12_000.0
#: Longer than any mooring line ever laid: a unit mistake.
MAX_LINE_LENGTH = 100_000.0

#: Plausibility limits: values outside them are unit slips or nonsense, and would only
#: reach the solver as overflow or underflow.
MIN_DEPTH = 0.01                 # [m]
MIN_LINE_LENGTH = 1e-3           # [m]; shorter than a millimetre is a unit mistake
MAX_WEIGHT = 1e6                 # [N/m] (100 t/m; the heaviest chain is about 0.3 t/m)
MIN_WEIGHT = 1e-6                # [N/m]; a lighter line is neutral: give 0
MIN_EA, MAX_EA = 1.0, 1e15       # [N]
MAX_FORCE = 1e12                 # [N] (a hundred million tonnes-force)
MAX_MOMENT = 1e15                # [N m]
MAX_SPEED = 200.0                # [m/s] for wind and current
MAX_HS = 100.0                   # [m]
MAX_AREA = 1e8                   # [m^2]
GRAVITY_RANGE = (0.1, 100.0)     # [m/s^2]
MAX_DENSITY = 1e5                # [kg/m^3]

#: Most elements of a discretised leg: beyond it the build time, not the accuracy, grows.
MAX_LINE_ELEMENTS = 400

#: Largest ``solver.max_iter``: IPOPT takes it as a C int.
MAX_ITER_LIMIT = 2**31 - 1

_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


# ---- small helpers ----------------------------------------------------------------------


def field_path(path: str, key) -> str:
    """Extend a dotted path by a mapping key (str) or a list index (int)."""
    if isinstance(key, int):
        return f"{path}[{key}]"
    if isinstance(key, str) and _IDENTIFIER.match(key):
        return f"{path}.{key}" if path else key
    return f"{path}[{show_value(key)}]"


def check_mapping(raw, path: str, required=(), optional=(), *, section: str = "") -> dict:
    """Check that ``raw`` is a mapping with string keys, all known and the required present.

    ``section`` names the case-file section of :mod:`moorsolve.model.schema` whose keys
    (and required keys) these are; the case-file validators always give it, so that the
    documented schema and the accepted keys are one list. ``required`` and ``optional``
    serve other files (study files).
    """
    if section:
        spec = get_section(section)
        required, optional = spec.required, spec.optional
    allowed = tuple(required) + tuple(optional)
    where = path or "the case"
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping; {where} takes the keys "
                              f"{', '.join(allowed)}")
    for key in raw:
        if not isinstance(key, str):
            raise CaseError(path, f"key {show_value(key)} is not a string; allowed keys: "
                                  f"{', '.join(allowed)}")
        if key not in allowed:
            raise CaseError(field_path(path, key), f"unknown key {key!r} in {where}; allowed keys: "
                                              f"{', '.join(allowed)}")
    for key in required:
        if key not in raw:
            raise CaseError(field_path(path, key), f"required key {key!r} is missing from {where}")
    return dict(raw)


def check_list(raw, path: str, what: str) -> list:
    """Check that ``raw`` is a list (or tuple) and return it as a list."""
    if isinstance(raw, (list, tuple)):
        return list(raw)
    raise CaseError(path, f"{show_value(raw)} is not a list; {path or 'this'} must be {what}")


def check_rows(raw, path: str, shape: str, *, width: int, min_rows: int, empty: str):
    """Check that ``raw`` is a list of at least ``min_rows`` rows of ``width`` values each
    (``shape`` names a row, e.g. ``"[z, speed]"``) and yield ``(row_path, row)``."""
    rows = check_list(raw, path, f"a list of rows {shape}")
    if len(rows) < min_rows:
        plural = "row" if min_rows == 1 else "rows"
        raise CaseError(path, f"{len(rows)} row(s); {empty} needs at least {min_rows} "
                              f"{plural} {shape}")
    for i, row_raw in enumerate(rows):
        rpath = field_path(path, i)
        row = check_list(row_raw, rpath, f"a row {shape}")
        if len(row) != width:
            raise CaseError(rpath, f"{show_value(row_raw)} has {len(row)} values; a row is "
                                   f"{shape}")
        yield rpath, row


def check_bounds(raw, value: float, kind: str, path: str, *, gt=None, ge=None, lt=None,
                  le=None) -> float:
    def bound(b):
        return "0" if b == 0 else format_si(b, kind)

    if gt is not None and not value > gt:
        raise CaseError(path, f"{describe(raw, value, kind)} must be > {bound(gt)}")
    if ge is not None and not value >= ge:
        raise CaseError(path, f"{describe(raw, value, kind)} must be >= {bound(ge)}")
    if lt is not None and not value < lt:
        raise CaseError(path, f"{describe(raw, value, kind)} must be < {bound(lt)}")
    if le is not None and not value <= le:
        raise CaseError(path, f"{describe(raw, value, kind)} must be <= {bound(le)}")
    return value


def quantity(raw, path: str, kind: str, **bounds) -> float:
    """Convert a quantity to SI and check its bounds (gt, ge, lt, le, in SI)."""
    return check_bounds(raw, to_si(raw, kind, path), kind, path, **bounds)


def optional_quantity(m: dict, path: str, key: str, kind: str, default, **bounds) -> float:
    """A quantity with a default: absent -> default, present -> converted and checked."""
    if key not in m:
        return default
    return quantity(m[key], field_path(path, key), kind, **bounds)


def schema_quantity(m: dict, path: str, section: str, key: str, **bounds) -> float:
    """A quantity whose kind (unit) and default come from the schema's ``section``."""
    spec = get_section(section).keys[key]
    if key not in m:
        return spec.default
    return quantity(m[key], field_path(path, key), spec.kind, **bounds)


def nullable_quantity(m: dict, path: str, key: str, kind: str, **bounds):
    """A quantity whose absence (or null) means None."""
    if m.get(key) is None:
        return None
    return quantity(m[key], field_path(path, key), kind, **bounds)


def check_name(raw, path: str, what: str) -> str:
    if not isinstance(raw, str) or not raw.strip():
        raise CaseError(path, f"{show_value(raw)} is not a valid {what}; give a non-empty string")
    return raw


def check_point(raw, path: str, sizes: tuple) -> tuple:
    """A list of lengths [m] with one of the allowed ``sizes``."""
    shape = " or ".join({2: "[x, y]", 3: "[x, y, z]"}[n] for n in sizes)
    items = check_list(raw, path, f"a list {shape} of lengths [m]")
    if len(items) not in sizes:
        raise CaseError(path, f"{show_value(raw)} has {len(items)} values; it must be {shape}")
    return tuple(quantity(v, field_path(path, i), "length") for i, v in enumerate(items))


def check_centre(m: dict, path: str) -> tuple:
    """A load model's centre of action, body frame: ``[x, y]`` (at z = 0) or ``[x, y, z]``."""
    if "centre" not in m:
        return (0.0, 0.0)
    return check_point(m["centre"], field_path(path, "centre"), (2, 3))


def check_choices(raw, path: str, allowed: tuple, what: str = "degree of freedom") -> tuple:
    """A list of distinct names drawn from ``allowed``, returned in ``allowed``'s order (so
    that nothing downstream depends on how the user listed them)."""
    items = check_list(raw, path, f"a list drawn from {', '.join(allowed)}")
    seen = set()
    for i, item in enumerate(items):
        if not isinstance(item, str) or item not in allowed:
            raise CaseError(field_path(path, i), f"unknown {what} {show_value(item)}; "
                                                 f"allowed: {', '.join(allowed)}")
        if item in seen:
            raise CaseError(field_path(path, i), f"{item!r} is listed twice")
        seen.add(item)
    return tuple(name for name in allowed if name in seen)
