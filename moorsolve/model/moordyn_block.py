"""The ``moordyn:`` block of a case file: what a MoorDyn input file holds that moorsolve does
not use, kept so that an exported file gives it back unchanged.

``moorsolve import-moordyn`` writes the block; ``moorsolve export-moordyn`` reads it; the
solver ignores it. It is validated here (structure and cross references to the case's line
types and legs), not interpreted. Schema (strings are MoorDyn tokens exactly as read)::

    moordyn:
      version: 1 | 2                     format of the file it came from (default for export)
      header: [str, ...]                 the file's front matter, one entry per line
      notes: [str, ...]                  what the import could not carry over (free text)
      line_types:                        per case line type (name must exist in line_types)
        NAME: {ea: str, ba: str, ei: str, cd: str, ca: str, cdax: str, caax: str,
               cl: str, df: str, cf: str}          all optional; ea only when not a number
      body: {id: int, attachment: str, x0: m, y0: m, z0: m, yaw_deg: deg,
             r0_deg: deg, p0_deg: deg,                         (roll, pitch: MoorDyn's r0, p0)
             columns: {mass, cg, i, volume, cda, ca: str}}     optional; the fairlead body
      legs:                              per case leg (name must exist in legs)
        NAME:
          lines:  [{id: int, num_segs: str, outputs: str, reversed: bool}, ...]   one per segment
          points: [{id: int, attachment: str, position: [x, y, z] (joints only),
                    columns: {mass, volume, fx, fy, fz, cda, ca: str}}, ...]    anchor, joints,
                                                                                 fairlead
      options: [[name, str or null], ...]    in file order; null: written from the case
                                             (WtrDpth, g, rho/rhoW)
      outputs: [str, ...]                    the OUTPUTS section, one entry per line
      sections: {TITLE: [str, ...]}          other sections copied verbatim (v2 only): ROD TYPES,
                                             RODS, FAILURE, CONTROL, EXTERNAL LOADS
      network:                           a case in the network form (bodies, points, lines):
        lines:  {NAME: {id: int, num_segs: str, outputs: str}}     per case line
        points: {point<N>: {id: int, attachment: str, columns: {...}}}  per POINTS row used
        bodies: {body<N>: {id: int, attachment: str, columns: {...}}}   per BODIES row
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping

from ..errors import CaseError

__all__ = ["validate_moordyn_block", "LINE_TYPE_COLUMNS", "POINT_COLUMNS", "BODY_COLUMNS",
           "RAW_SECTIONS"]

#: Passthrough columns of a line type, in v2 order (``ea`` only holds a non-numeric EA).
LINE_TYPE_COLUMNS = ("ea", "ba", "ei", "cd", "ca", "cdax", "caax", "cl", "df", "cf")
#: Passthrough columns of a point (v1 has the steady forces FX FY FZ, v2 does not).
POINT_COLUMNS = ("mass", "volume", "fx", "fy", "fz", "cda", "ca")
#: Passthrough columns of a body row after its pose.
BODY_COLUMNS = ("mass", "cg", "i", "volume", "cda", "ca")
#: Sections moorsolve does not model, copied verbatim into a v2 file, in v2 order.
RAW_SECTIONS = ("ROD TYPES", "RODS", "FAILURE", "CONTROL", "EXTERNAL LOADS")


def _mapping(raw, path: str, allowed: tuple, required: tuple = ()) -> dict:
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{raw!r} is not a mapping; allowed keys: {', '.join(allowed)}")
    for key in raw:
        if key not in allowed:
            raise CaseError(f"{path}.{key}" if isinstance(key, str) else path,
                            f"unknown key {key!r}; allowed keys: {', '.join(allowed)}")
    for key in required:
        if key not in raw:
            raise CaseError(f"{path}.{key}", f"required key {key!r} is missing")
    return dict(raw)


def _strings(raw, path: str) -> list:
    if not isinstance(raw, (list, tuple)) or not all(isinstance(s, str) for s in raw):
        raise CaseError(path, f"{raw!r} must be a list of strings")
    return list(raw)


def _token(raw, path: str) -> str:
    if not isinstance(raw, str) or not raw or any(c.isspace() for c in raw):
        raise CaseError(path, f"{raw!r} must be one MoorDyn value (a string without spaces)")
    return raw


def _columns(raw, path: str, allowed: tuple) -> dict:
    m = _mapping(raw, path, allowed)
    return {k: _token(v, f"{path}.{k}") for k, v in m.items()}


def _integer(raw, path: str) -> int:
    if isinstance(raw, bool) or not isinstance(raw, numbers.Integral) or raw < 1:
        raise CaseError(path, f"{raw!r} must be a positive whole number (a MoorDyn ID)")
    return int(raw)


def _number(raw, path: str) -> float:
    if isinstance(raw, bool) or not isinstance(raw, numbers.Real) or not math.isfinite(raw):
        raise CaseError(path, f"{raw!r} is not a finite number")
    return float(raw)


def _leg(raw, path: str, n_segments: int) -> dict:
    m = _mapping(raw, path, ("lines", "points"), ("lines", "points"))
    lines = m["lines"]
    if not isinstance(lines, (list, tuple)) or len(lines) != n_segments:
        raise CaseError(f"{path}.lines", f"must list one MoorDyn line per segment of the leg "
                                         f"({n_segments}); the leg's segments were changed "
                                         "without this block: edit or delete the entry")
    for i, line in enumerate(lines):
        lpath = f"{path}.lines[{i}]"
        lm = _mapping(line, lpath, ("id", "num_segs", "outputs", "reversed"))
        if "id" in lm:
            _integer(lm["id"], f"{lpath}.id")
        for key in ("num_segs", "outputs"):
            if key in lm:
                _token(lm[key], f"{lpath}.{key}")
        if "reversed" in lm and not isinstance(lm["reversed"], bool):
            raise CaseError(f"{lpath}.reversed", f"{lm['reversed']!r} is not true or false")
    points = m["points"]
    if not isinstance(points, (list, tuple)) or len(points) != n_segments + 1:
        raise CaseError(f"{path}.points", f"must list the anchor, the {n_segments - 1} joint(s) "
                                          f"and the fairlead ({n_segments + 1} points)")
    for i, point in enumerate(points):
        ppath = f"{path}.points[{i}]"
        pm = _mapping(point, ppath, ("id", "attachment", "position", "columns"))
        if "id" in pm:
            _integer(pm["id"], f"{ppath}.id")
        if "attachment" in pm:
            _token(pm["attachment"], f"{ppath}.attachment")
        if "position" in pm:
            pos = pm["position"]
            if not isinstance(pos, (list, tuple)) or len(pos) != 3:
                raise CaseError(f"{ppath}.position", f"{pos!r} must be [x, y, z] [m]")
            for j, v in enumerate(pos):
                _number(v, f"{ppath}.position[{j}]")
        if "columns" in pm:
            _columns(pm["columns"], f"{ppath}.columns", POINT_COLUMNS)
    return m


def _network(raw, path: str, names: Mapping | None) -> None:
    """The ``network`` entry: per line, point and body of the case, its MoorDyn row."""
    m = _mapping(raw, path, ("lines", "points", "bodies"))
    columns = {"lines": (), "points": POINT_COLUMNS, "bodies": BODY_COLUMNS}
    for kind, entries in m.items():
        kpath = f"{path}.{kind}"
        known = tuple(names.get(kind, ())) if names is not None and kind == "lines" else None
        if not isinstance(entries, Mapping):
            raise CaseError(kpath, f"{entries!r} is not a mapping of names to MoorDyn rows")
        for name, entry in entries.items():
            epath = f"{kpath}.{name}"
            if known is not None and name not in known:
                raise CaseError(epath, f"the case has no {kind[:-1]} {name!r}; known: "
                                       f"{', '.join(known) or '(none)'}")
            if kind == "lines":
                e = _mapping(entry, epath, ("id", "num_segs", "outputs"), ("id",))
                for key in ("num_segs", "outputs"):
                    if key in e:
                        _token(e[key], f"{epath}.{key}")
            else:
                e = _mapping(entry, epath, ("id", "attachment", "columns"), ("id", "attachment"))
                _token(e["attachment"], f"{epath}.attachment")
                if "columns" in e:
                    _columns(e["columns"], f"{epath}.columns", columns[kind])
            _integer(e["id"], f"{epath}.id")


def validate_moordyn_block(raw, path: str, line_types: Mapping, legs: tuple,
                           network: Mapping | None = None) -> dict:
    """Check the ``moordyn`` block of a case file; returns it as a plain dict.

    ``legs`` are the case's lines (the legs of the legs form); the block's ``network.lines``
    may name only those (``network`` may give other names to check against).

    Raises
    ------
    CaseError
        Naming the field: an unknown key, a value of the wrong kind, a line type or leg the
        case does not have, or a leg whose segments no longer match its MoorDyn lines.
    """
    m = _mapping(raw, path, ("version", "header", "notes", "line_types", "body", "legs",
                             "options", "outputs", "sections", "network"))
    if "network" in m:
        if network is None:             # the case's lines (legs are the lines of that form)
            network = {"lines": [line.name for line in legs]}
        _network(m["network"], f"{path}.network", network)
    if "version" in m and (isinstance(m["version"], bool) or m["version"] not in (1, 2)):
        raise CaseError(f"{path}.version", f"{m['version']!r} must be 1 or 2")
    for key in ("header", "notes", "outputs"):
        if key in m:
            _strings(m[key], f"{path}.{key}")
    if "line_types" in m:
        lt = _mapping(m["line_types"], f"{path}.line_types", tuple(line_types))
        for name, cols in lt.items():
            _columns(cols, f"{path}.line_types.{name}", LINE_TYPE_COLUMNS)
    if m.get("body") is not None:
        bpath = f"{path}.body"
        b = _mapping(m["body"], bpath, ("id", "attachment", "x0", "y0", "z0", "yaw_deg",
                                        "r0_deg", "p0_deg", "columns"), ("id", "attachment"))
        _integer(b["id"], f"{bpath}.id")
        _token(b["attachment"], f"{bpath}.attachment")
        for key in ("x0", "y0", "z0", "yaw_deg", "r0_deg", "p0_deg"):
            if key in b:
                _number(b[key], f"{bpath}.{key}")
        if "columns" in b:
            _columns(b["columns"], f"{bpath}.columns", BODY_COLUMNS)
    if "legs" in m:
        by_name = {leg.name: leg for leg in legs}
        lm = _mapping(m["legs"], f"{path}.legs", tuple(by_name))
        for name, entry in lm.items():
            _leg(entry, f"{path}.legs.{name}", len(by_name[name].segments))
    if "options" in m:
        opts = m["options"]
        if not isinstance(opts, (list, tuple)):
            raise CaseError(f"{path}.options", f"{opts!r} must be a list of [name, value]")
        for i, item in enumerate(opts):
            ipath = f"{path}.options[{i}]"
            if not isinstance(item, (list, tuple)) or len(item) != 2:
                raise CaseError(ipath, f"{item!r} must be [name, value]")
            _token(item[0], f"{ipath}[0]")
            if item[1] is not None:
                _token(item[1], f"{ipath}[1]")
    if "sections" in m:
        sections = _mapping(m["sections"], f"{path}.sections", RAW_SECTIONS)
        for title, rows in sections.items():
            _strings(rows, f"{path}.sections[{title!r}]")
    return m
