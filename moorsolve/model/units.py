"""Quantities with units in case files, converted to SI once at load time.

A quantity in a case file is either a plain number, taken as SI (m, N, kg, s, N/m, m/s,
kg/m^3, m^2; degrees for angles), or a string holding a number and a unit such as
``"0.13 t/m"``, ``"372 kN"``, ``"81 mm"`` or ``"20 kn"``. Units are read by one pint
registry, made when the first unit string is read (importing pint costs a few tenths of a
second, so a case of plain numbers never pays it); nothing outside ``moorsolve.io`` sees
pint.

Every failure raises :class:`moorsolve.errors.CaseError` naming the field.
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
import math
import numbers
import re
import reprlib
import threading

from ..errors import CaseError
from .common_units import COMMON_UNITS

__all__ = ["registry", "KINDS", "to_si", "weight_per_length_to_si", "format_si", "describe",
           "show_value", "recording"]

_REGISTRY = []
_REGISTRY_LOCK = threading.Lock()


def registry():
    """The one unit registry of moorsolve, made on first use (also ``units.UREG``).

    In pint ``t`` is the metric tonne, ``tf`` the tonne-force, ``kgf`` the kilogram-force
    and ``kn`` / ``kt`` the knot.
    """
    if not _REGISTRY:
        with _REGISTRY_LOCK:
            if not _REGISTRY:
                import pint
                _REGISTRY.append(pint.UnitRegistry())
    return _REGISTRY[0]


def __getattr__(name):
    if name == "UREG":
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

#: kind -> (SI unit as pint reads it, SI symbol shown in messages, noun for messages)
KINDS = {
    "length": ("m", "m", "a length"),
    "area": ("m**2", "m^2", "an area"),
    "volume": ("m**3", "m^3", "a volume"),
    "mass": ("kg", "kg", "a mass"),
    "force": ("N", "N", "a force"),
    "moment": ("N*m", "N m", "a moment (force x length)"),
    "force_per_length": ("N/m", "N/m", "a force per length"),
    "mass_per_length": ("kg/m", "kg/m", "a mass per length"),
    "speed": ("m/s", "m/s", "a speed"),
    "density": ("kg/m**3", "kg/m^3", "a density"),
    "pressure": ("Pa", "Pa", "a pressure or soil strength"),
    "pressure_per_length": ("Pa/m", "Pa/m", "a pressure gradient with depth"),
    "acceleration": ("m/s**2", "m/s^2", "an acceleration"),
    "time": ("s", "s", "a time"),
    "moment_of_inertia": ("kg*m**2", "kg m^2", "a moment of inertia"),
    "bending_stiffness": ("N*m**2", "N m^2", "a bending stiffness E I (force x length^2)"),
    "angle": ("degree", "deg", "an angle"),
    "dimensionless": ("", "", "a plain number"),
}

# Example strings for the hint in error messages.
_EXAMPLES = {
    "length": "'81 mm'",
    "area": "'120 m^2'",
    "volume": "'1.5 m^3'",
    "mass": "'8 t'",
    "force": "'372 kN'",
    "moment": "'50 kN*m'",
    "force_per_length": "'1.27 kN/m' or '0.13 t/m'",
    "mass_per_length": "'130 kg/m'",
    "speed": "'20 kn'",
    "density": "'1.2 kg/m^3'",
    "pressure": "'5 kPa'",
    "pressure_per_length": "'1.5 kPa/m'",
    "acceleration": "'9.81 m/s^2'",
    "time": "'5 s'",
    "moment_of_inertia": "'4.2e9 kg*m^2'",
    "bending_stiffness": "'6.8e8 N*m^2'",
    "angle": "'30 deg'",
    "dimensionless": "'0.5'",
}

# Units accepted for an angle; radian-based dimensionless ratios like "m/m" are not angles.
_ANGLE_UNITS = frozenset({"degree", "radian", "arcminute", "arcsecond", "turn"})

_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
# One unit name with an optional small integer power. The grammar is deliberately narrow
# so that pint's expression evaluator never sees arithmetic such as "9**9**9**9".
_UNIT = r"[A-Za-z_]+(?:\s*(?:\^|\*\*)\s*[+-]?\d{1,2})?"
_UNIT_EXPR = rf"{_UNIT}(?:\s*[*/]\s*{_UNIT}|\s+{_UNIT})*"
_QUANTITY_RE = re.compile(rf"^\s*({_NUMBER})\s*({_UNIT_EXPR})?\s*$")

#: While :func:`recording` is active: field path -> (SI value, kind) of every quantity
#: converted (per context, so threads recording at once keep their own tables).
_RECORDING: contextvars.ContextVar = contextvars.ContextVar("moorsolve_quantities",
                                                            default=None)


@contextlib.contextmanager
def recording():
    """Collect every quantity converted in the block: ``{field: (SI value, kind)}``.

    A sweep validates each grid value as a case and reads back what the case made of it
    (``"20 kn"`` at ``environment.wind.speed`` is 10.29 m/s), without knowing the schema.
    """
    table: dict = {}
    token = _RECORDING.set(table)
    try:
        yield table
    finally:
        _RECORDING.reset(token)


def recording_active() -> bool:
    """Whether a :func:`recording` block is collecting conversions (in this context)."""
    return _RECORDING.get() is not None


def _record(field: str, value: float, kind: str) -> float:
    table = _RECORDING.get()
    if table is not None and field:
        table[field] = (value, kind)
    return value


@functools.lru_cache(maxsize=None)
def _dimensionality(kind: str):
    return registry().parse_units(KINDS[kind][0]).dimensionality


def format_si(value: float, kind: str) -> str:
    """Format an SI value with its unit symbol, e.g. ``-5 m``.

    Parameters
    ----------
    value : float
        The value in SI units.
    kind : str
        A key of :data:`KINDS`.

    Returns
    -------
    str
    """
    symbol = KINDS[kind][1]
    return f"{value:.6g} {symbol}" if symbol else f"{value:.6g}"


def describe(raw, value: float, kind: str) -> str:
    """Show a value as the user gave it and, for a unit string, its SI value.

    Parameters
    ----------
    raw : number or str
        The value as written in the case.
    value : float
        The same value in SI units.
    kind : str
        A key of :data:`KINDS`.

    Returns
    -------
    str
        ``-5 m`` for a number, ``'-5 mm' (-0.005 m)`` for a string.
    """
    if isinstance(raw, str):
        return f"{raw!r} ({format_si(value, kind)})"
    return format_si(value, kind)


_REPR = reprlib.Repr()
_REPR.maxstring = 60
_REPR.maxother = 60
_REPR.maxlist = 6
_REPR.maxdict = 6


def show_value(raw) -> str:
    """A short repr of a user value for error messages; never raises.

    Parameters
    ----------
    raw : object
        Any value found in a case.

    Returns
    -------
    str
        ``repr(raw)``, shortened for long strings and containers.
    """
    try:
        return _REPR.repr(raw)
    except Exception:  # a user object with a broken __repr__ must not escape as itself
        return f"<{type(raw).__name__}>"


def _not_a(raw, kind: str, field: str) -> CaseError:
    noun = KINDS[kind][2]
    symbol = KINDS[kind][1]
    if kind == "dimensionless":
        hint = "give a number"
    else:
        hint = f"give a number in {symbol} or a string with a unit like {_EXAMPLES[kind]}"
    return CaseError(field, f"{show_value(raw)} is not {noun} ({hint})")


def _finite(value: float, raw, field: str) -> float:
    if not math.isfinite(value):
        raise CaseError(field, f"{show_value(raw)} is not finite; a finite number is required")
    return value


def _real_to_float(number, raw, field: str) -> float:
    try:
        value = float(number)
    except (OverflowError, ValueError, TypeError):
        raise CaseError(field, f"{show_value(raw)} is too large or not a number") from None
    return _finite(value, raw, field)


def _parse_units(text: str, raw, field: str):
    try:
        return registry().parse_units(text)
    except Exception:  # pint raises many exception types; each one means "not a unit"
        raise CaseError(field, f"{show_value(raw)}: {text!r} is not a known unit") from None


def _split(raw: str, kind: str, field: str):
    """Split a quantity string into its number and its unit text ('' if none)."""
    match = _QUANTITY_RE.match(raw)
    if match is None:
        raise _not_a(raw, kind, field)
    number = _real_to_float(match.group(1), raw, field)
    return number, (match.group(2) or "")


def _string_to_si(raw: str, kinds: tuple, field: str):
    """Convert a quantity string to SI, trying each kind in turn; return (value, kind)."""
    number, unit_text = _split(raw, kinds[0], field)
    if not unit_text:
        # A bare numeric string is read as SI: PyYAML loads "1e-9" as a string.
        return number, kinds[0]
    common = COMMON_UNITS.get(unit_text)
    if common is not None and common[0] in kinds:
        # A unit every case uses, without pint's registry (model/common_units.py).
        return _finite(number * common[1], raw, field), common[0]
    units = _parse_units(unit_text, raw, field)
    for kind in kinds:
        if kind == "dimensionless":
            continue
        if kind == "angle":
            if str(units) not in _ANGLE_UNITS:
                continue
        elif units.dimensionality != _dimensionality(kind):
            continue
        try:
            value = registry().Quantity(number, units).to(KINDS[kind][0]).magnitude
        except Exception:  # an offset or logarithmic unit: not a plain quantity
            raise _not_a(raw, kind, field) from None
        return _finite(float(value), raw, field), kind
    if kinds[0] == "dimensionless":
        raise CaseError(field, f"{show_value(raw)} must be a plain number without a unit")
    raise _not_a(raw, kinds[0], field)


@functools.lru_cache(maxsize=4096)
def _cached_string_to_si(raw: str, kinds: tuple):
    return _string_to_si(raw, kinds, "")


def _convert_string(raw: str, kinds: tuple, field: str):
    """:func:`_string_to_si`, remembering successful conversions (pint parses slowly and
    sweeps validate the same strings many times); a failure is re-raised with its field."""
    try:
        return _cached_string_to_si(raw, kinds)
    except CaseError:
        return _string_to_si(raw, kinds, field)


def to_si(raw, kind: str, field: str) -> float:
    """Convert a case-file quantity to a finite SI float.

    Parameters
    ----------
    raw : object
        A real number (not a bool), taken as SI (degrees for ``kind="angle"``), or a string
        with a number and an optional unit, e.g. ``"81 mm"``.
    kind : str
        The expected kind of quantity, a key of :data:`KINDS`.
    field : str
        Dotted path of the field, used in error messages.

    Returns
    -------
    float
        The value in SI units [m, N, N m, N/m, kg/m, m/s, kg/m^3, m/s^2, s], in degrees for
        an angle, or the plain number for ``"dimensionless"``.

    Raises
    ------
    CaseError
        If the value is not a number or quantity string, has the wrong dimension, an
        unknown unit, or is NaN or infinite.
    """
    if kind not in KINDS:
        raise ValueError(f"unknown quantity kind {kind!r}")
    if isinstance(raw, bool):
        raise _not_a(raw, kind, field)
    if isinstance(raw, numbers.Real):
        return _record(field, _real_to_float(raw, raw, field), kind)
    if isinstance(raw, str):
        return _record(field, _convert_string(raw, (kind,), field)[0], kind)
    raise _not_a(raw, kind, field)


def weight_per_length_to_si(raw, gravity: float, field: str) -> float:
    """Convert a submerged weight per length to SI [N/m].

    A force per length (``"1.27 kN/m"``, ``"130 kgf/m"``, a plain number in N/m) is taken
    as is. A mass per length (``"0.13 t/m"``, ``"22 kg/m"``) is read as the weight of that
    mass, i.e. multiplied by ``gravity``: engineers quote submerged chain weight in t/m
    meaning tonne-force per metre.

    Parameters
    ----------
    raw : object
        The value as written in the case.
    gravity : float
        Acceleration of gravity of the case [m/s^2].
    field : str
        Dotted path of the field, used in error messages.

    Returns
    -------
    float
        Weight per length [N/m]; any finite sign.

    Raises
    ------
    CaseError
        If the value is not a force or mass per length, or is not finite.
    """
    if isinstance(raw, str):
        value, kind = _convert_string(raw, ("force_per_length", "mass_per_length"), field)
        if kind == "mass_per_length":
            value = _finite(value * gravity, raw, field)
        return _record(field, value, "force_per_length")
    return to_si(raw, "force_per_length", field)
