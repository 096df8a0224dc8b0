"""Corrosion and creep over a design life: the ``checks`` keys ``design_life``,
``corrosion`` and ``creep`` (:mod:`moorsolve.checks.wear` uses them).

Schema (rates are per year of service)::

    checks:
      design_life: 20 y                       years in service ("y", "yr", "year", "a")
      corrosion:                              diameter loss of steel lines (chain, wire)
        rate: 0.4 mm/y | {splash: RATE, catenary: RATE, bottom: RATE}
        splash_depth: 4 m                     needed with a splash rate: the depth below
                                              the still water down to which a line counts
                                              in the splash zone
        line_types: {NAME: {rate: ...}}       one line type's own rate
        segments: [{line: NAME, segment: i, rate: ...}]   one segment's own rate
      creep:                                  permanent elongation of fibre ropes
        rate: 0.1 %/y                         strain per year (or a plain fraction)
        line_types: {NAME: {rate: ...}}

A segment's rate is its own, else its line type's, else the common one; the common
corrosion rate applies to every line type with a diameter that is not a fibre rope, the
common creep rate to every fibre rope.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Optional

from ..errors import CaseError
from .fields import check_list, check_mapping, field_path, quantity
from .units import show_value

__all__ = ["ZONES", "Corrosion", "Creep", "Wear", "wear_fields", "WEAR_KEYS", "design_life_years",
           "SECONDS_PER_YEAR"]

#: The zones of a line, from the surface down: on and near the surface, hanging free,
#: lying on the seabed.
ZONES = ("splash", "catenary", "bottom")

#: The ``checks`` keys this module reads.
WEAR_KEYS = ("design_life", "corrosion", "creep")

SECONDS_PER_YEAR = 365.25 * 86400.0
_YEAR_WORDS = r"(?:y|yr|yrs|year|years|a)"
_PER_YEAR = re.compile(rf"^(.*?)\s*/\s*{_YEAR_WORDS}\s*$")
_YEARS = re.compile(rf"^(.*?)\s*{_YEAR_WORDS}\s*$")
_NUMBER = re.compile(r"^\s*[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?\s*$")
#: Bounds that catch a unit mistake: no mooring steel loses 10 mm a year, no rope creeps
#: 10 % a year, no mooring serves 200 years.
MAX_CORROSION_RATE = 10e-3
MAX_CREEP_RATE = 0.1
MAX_LIFE_YEARS = 200.0


@dataclass(frozen=True)
class ZoneRates:
    """Diameter loss per year [m/y] in each zone."""

    splash: float
    catenary: float
    bottom: float

    def at(self, zone: str) -> float:
        return getattr(self, zone)

    @property
    def uniform(self) -> bool:
        return self.splash == self.catenary == self.bottom


@dataclass(frozen=True)
class Corrosion:
    """Diameter loss rates [m per year] of steel lines.

    ``rate`` is the common one (None: only the listed line types and segments corrode);
    ``line_types`` maps a line type name, ``segments`` a ``(line, index)`` pair to its own.
    ``splash_depth`` [m] is the depth below the still water down to which a line is in the
    splash zone (None when no rate differs by zone).
    """

    rate: Optional[ZoneRates] = None
    line_types: tuple = ()
    segments: tuple = ()
    splash_depth: Optional[float] = None

    def rates_for(self, line: str, index: int, line_type) -> Optional[ZoneRates]:
        """The rates of segment ``index`` of ``line`` (of type ``line_type``), or None."""
        own = dict(self.segments).get((line, index))
        if own is not None:
            return own
        own = dict(self.line_types).get(line_type.name)
        if own is not None:
            return own
        if line_type.fibre or line_type.diameter is None:
            return None
        return self.rate


@dataclass(frozen=True)
class Creep:
    """Permanent strain of fibre ropes per year [1/y]: the common ``rate`` for every
    fibre line type (None: none) and ``line_types``' own."""

    rate: Optional[float] = None
    line_types: tuple = ()

    def rate_for(self, line_type) -> Optional[float]:
        own = dict(self.line_types).get(line_type.name)
        if own is not None:
            return own
        return self.rate if line_type.fibre else None


@dataclass(frozen=True)
class Wear:
    """What a mooring loses over its design life (``design_life`` [years])."""

    design_life: float
    corrosion: Optional[Corrosion] = None
    creep: Optional[Creep] = None


def _per_year(raw, path: str, kind: str) -> float:
    """A rate per year: ``"0.4 mm/y"`` (a length) or ``"0.1 %/y"`` (a strain), or a plain
    number (m/y, or a fraction per year)."""
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
        raise CaseError(path, f"{show_value(raw)} is not a rate per year; give e.g. "
                              + ("'0.4 mm/y'" if kind == "length" else "'0.1 %/y'"))
    if isinstance(raw, str):
        m = _PER_YEAR.match(raw.strip())
        if m is None:
            if not _NUMBER.match(raw):
                raise CaseError(path, f"{raw!r} is not a rate per year; give e.g. "
                                      + ("'0.4 mm/y'" if kind == "length" else "'0.1 %/y'"))
            value = float(raw)
        elif kind == "strain":
            text = m.group(1).strip()
            scale = 1.0
            if text.endswith("%"):
                text, scale = text[:-1], 0.01
            if not _NUMBER.match(text):
                raise CaseError(path, f"{raw!r} is not a strain per year; give e.g. '0.1 %/y'")
            value = float(text) * scale
        else:
            value = quantity(m.group(1), path, "length")
    else:
        value = float(raw)
    limit = MAX_CORROSION_RATE if kind == "length" else MAX_CREEP_RATE
    shown = (f"{value * 1e3:g} mm/y" if kind == "length" else f"{value * 100:g} %/y")
    if not 0 <= value <= limit:
        raise CaseError(path, f"{shown} must be >= 0 and at most "
                              + (f"{limit * 1e3:g} mm/y" if kind == "length"
                                 else f"{limit * 100:g} %/y") + " (a unit mistake?)")
    return value


def design_life_years(raw, path: str) -> float:
    """A design life in years: '20 y', '20 years', '25 a', a time ('1000 d') or a plain number
    of years (seconds would be no design life). Raises CaseError naming ``path``."""
    if isinstance(raw, str):
        m = _YEARS.match(raw.strip())
        text = raw if m is None else m.group(1)
        if m is None and not _NUMBER.match(raw):
            value = quantity(raw, path, "time") / SECONDS_PER_YEAR
        else:
            if not _NUMBER.match(text):
                raise CaseError(path, f"{raw!r} is not a number of years; give e.g. '20 y'")
            value = float(text)
    elif isinstance(raw, (int, float)) and not isinstance(raw, bool):
        value = float(raw)      # a plain number is years: seconds would be no design life
    else:
        raise CaseError(path, f"{show_value(raw)} is not a number of years; give e.g. '20 y'")
    if not 0 < value <= MAX_LIFE_YEARS:
        raise CaseError(path, f"{value:g} years must be > 0 and at most {MAX_LIFE_YEARS:g}")
    return value


def _zone_rates(raw, path: str) -> ZoneRates:
    if isinstance(raw, Mapping):
        m = check_mapping(raw, path, section="corrosion_zones")
        return ZoneRates(*(_per_year(m[z], field_path(path, z), "length") for z in ZONES))
    rate = _per_year(raw, path, "length")
    return ZoneRates(rate, rate, rate)


def _line_type_names(raw, path: str, line_types: dict, rate, section: str) -> tuple:
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping of line type names to "
                              "{rate: ...}")
    out = []
    for name, spec in raw.items():
        if name not in line_types:
            raise CaseError(field_path(path, name),
                            f"unknown line type {show_value(name)}; known line types: "
                            f"{', '.join(line_types)}")
        sub = field_path(path, name)
        m = check_mapping(spec, sub, section=section)
        out.append((name, rate(m["rate"], field_path(sub, "rate"))))
    return tuple(out)


def _corrosion(raw, path: str, line_types: dict, lines: tuple) -> Corrosion:
    m = check_mapping(raw, path, section="corrosion")
    if not any(k in m for k in ("rate", "line_types", "segments")):
        raise CaseError(field_path(path, "rate"), "no corrosion rate; give rate (e.g. "
                        "'0.4 mm/y'), or line_types or segments with their own")
    common = None if "rate" not in m else _zone_rates(m["rate"], field_path(path, "rate"))
    own = () if "line_types" not in m else _line_type_names(
        m["line_types"], field_path(path, "line_types"), line_types, _zone_rates,
        "corrosion_line_type")
    for name, _ in own:
        if line_types[name].diameter is None:
            raise CaseError(field_path(field_path(path, "line_types"), name),
                            f"line type {name!r} has no diameter to lose; give its "
                            "diameter or a catalogue line")
    segments = ()
    if "segments" in m:
        spath = field_path(path, "segments")
        by_name = {line.name: line for line in lines}
        seen = []
        for i, item in enumerate(check_list(m["segments"], spath,
                                            "a list of {line, segment, rate}")):
            ipath = field_path(spath, i)
            s = check_mapping(item, ipath, section="corrosion_segment")
            line = by_name.get(s["line"])
            if line is None:
                raise CaseError(field_path(ipath, "line"),
                                f"unknown line {show_value(s['line'])}; known lines: "
                                f"{', '.join(by_name)}")
            j = s["segment"]
            if isinstance(j, bool) or not isinstance(j, int) or not 0 <= j < len(line.segments):
                raise CaseError(field_path(ipath, "segment"),
                                f"{show_value(j)} must be a segment index 0 to "
                                f"{len(line.segments) - 1} of line {line.name!r} (from end A)")
            if line.segments[j].line_type.diameter is None:
                raise CaseError(field_path(ipath, "segment"),
                                f"segment {j} of line {line.name!r} has no diameter to lose")
            if (line.name, j) in seen:
                raise CaseError(ipath, f"segment {j} of line {line.name!r} is listed twice")
            seen.append((line.name, j))
            segments += (((line.name, j), _zone_rates(s["rate"], field_path(ipath, "rate"))),)
    zoned = [r for r in [common, *(r for _, r in own), *(r for _, r in segments)]
             if r is not None and not r.uniform]
    depth = None
    if "splash_depth" in m:
        depth = quantity(m["splash_depth"], field_path(path, "splash_depth"), "length",
                         ge=0, le=100.0)
    elif zoned:
        raise CaseError(field_path(path, "splash_depth"),
                        "rates by zone need the splash zone's depth below the still water "
                        "(e.g. '4 m'): the part of a line above it is in the splash zone")
    return Corrosion(rate=common, line_types=own, segments=segments, splash_depth=depth)


def _strain_rate(raw, path: str) -> float:
    return _per_year(raw, path, "strain")


def _creep(raw, path: str, line_types: dict) -> Creep:
    m = check_mapping(raw, path, section="creep")
    if not m:
        raise CaseError(field_path(path, "rate"), "no creep rate; give rate (e.g. "
                                                  "'0.1 %/y') or line_types with their own")
    common = None if "rate" not in m else _strain_rate(m["rate"], field_path(path, "rate"))
    own = () if "line_types" not in m else _line_type_names(
        m["line_types"], field_path(path, "line_types"), line_types, _strain_rate,
        "creep_line_type")
    return Creep(rate=common, line_types=own)


def wear_fields(m: dict, path: str, line_types: dict, lines: tuple) -> Optional[Wear]:
    """The :class:`Wear` of a validated ``checks`` mapping ``m`` (None without
    ``corrosion`` and ``creep``). Raises CaseError naming the field."""
    corrosion = (None if m.get("corrosion") is None
                 else _corrosion(m["corrosion"], field_path(path, "corrosion"), line_types,
                                 lines))
    creep = (None if m.get("creep") is None
             else _creep(m["creep"], field_path(path, "creep"), line_types))
    if corrosion is None and creep is None:
        if m.get("design_life") is not None:
            design_life_years(m["design_life"], field_path(path, "design_life"))
        return None
    if m.get("design_life") is None:
        raise CaseError(field_path(path, "design_life"),
                        "corrosion and creep act over the design life; give design_life "
                        "(e.g. '20 y')")
    return Wear(design_life=design_life_years(m["design_life"], field_path(path, "design_life")),
                corrosion=corrosion, creep=creep)
