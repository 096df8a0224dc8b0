"""A parsed MoorDyn file read into typed entries with MoorDyn's meaning: line and rod types,
bodies, rods, points, lines and the environment, checked the way MoorDyn checks them.

Keywords and rules are those of MoorDyn-C v2 (``MoorDyn2.cpp``) and MoorDyn-F (OpenFAST),
case-insensitive as both read them:

- point attachment: ``Fixed`` / ``Fix`` / ``Anchor``; ``Body<N>``; ``Coupled`` / ``Vessel`` /
  ``Ves`` / ``Cpld`` / ``Fairlead``; ``Free`` / ``Point`` / ``P`` / ``Connect`` / ``Con``;
  ``Turbine<N>`` / ``T<N>`` (FAST.Farm, coupled to turbine N). Z may be ``seabed`` (also
  ``ground``, ``floor``): on the seabed at the water depth.
- body attachment: ``Fixed``; ``Coupled`` / ``Vessel``; ``CoupledPinned`` / ``VesselPinned`` /
  ``CpldPin`` / ``VesPin``; ``Turbine<N>``; ``Free`` (MoorDyn-C takes any other word as
  Free; so does this reader, with a note).
- rod attachment: ``Fixed``; ``Pinned`` / ``Pin``; ``Body<N>`` (rigid) or ``Body<N>Pinned``;
  ``Coupled`` / ``Vessel``; ``CoupledPinned``; ``Free`` / ``Point`` / ``Con``.
- line ends: ``<N>`` / ``P<N>`` / ``Point<N>`` / ``C<N>`` / ``Con<N>`` (point N), ``R<N>A`` /
  ``Rod<N>B`` (an end of rod N).
- v2 IDs run 1, 2, 3, ... in each table (both MoorDyn-C and MoorDyn-F refuse others); v1 IDs
  are any distinct positive whole numbers.
- LINE TYPES rows: 9 columns (v1: ``Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt``) or 10, 11
  or 13 (v2: ``TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx [Cl [dF cF]]``); EA may be
  ``EAs|EAd`` or ``EAs|alpha|beta`` (viscoelastic: the static stiffness EAs is the statics').
- water depth: WtrDpth (or Depth, WaterDepth); without it, the depth of the deepest point;
  a point below the given depth deepens the water to it (MoorDyn-C's rule). Gravity g
  (Gravity) default 9.80665 m/s^2; water density rho (rhoW, WtrDnsty) default 1025 kg/m^3.

Numbers must be numbers: MoorDyn-C reads a word such as ``5.0x`` as 5.0 and ``abc`` as 0;
this reader refuses them (naming the line and column), as MoorDyn-F does.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from typing import Optional

from .moordyn_options import (DEFAULT_GRAVITY, DEFAULT_WATER_DENSITY, KNOWN_OPTIONS,
                              read_environment)
from .moordyn_parse import MoorDynFile, number_token
from .moordyn_rows import bar_fields, table_entries, read_ident, read_number
from .moordyn_syrope import apply_syrope
from .moordyn_types import MDLineType, MDRodType, _line_types, _rod_types

__all__ = ["MDBody", "MDRod", "MDPoint", "MDLine", "MDScene",
           "read_scene", "vertical_force", "DEFAULT_GRAVITY", "DEFAULT_WATER_DENSITY",
           "KNOWN_OPTIONS"]

_FIXED = ("FIXED", "FIX", "ANCHOR")
_COUPLED = ("COUPLED", "VESSEL", "VES", "CPLD", "FAIRLEAD")
_PINNED_COUPLED = ("COUPLEDPINNED", "VESSELPINNED", "VESPIN", "CPLDPIN")
_FREE = ("FREE", "POINT", "P", "CONNECT", "CON")
_TURBINE = ("TURBINE", "T")
_SEABED = ("SEABED", "GROUND", "FLOOR")


def decompose(word: str) -> tuple:
    """MoorDyn's ``decomposeString``: (letters, digits, letters, rest) of an upper-cased word,
    e.g. ``Body1Pinned`` -> ("BODY", "1", "PINNED", "")."""
    m = re.fullmatch(r"([A-Z_]*)(\d*)([A-Z_]*)(.*)", word.upper())
    return m.groups()


@dataclass(frozen=True)
class MDBody:
    id: int
    line: int
    kind: str                         # fixed, coupled, pinned, free, turbine
    word: str
    pose: tuple                       # X0 Y0 Z0 [m], r0 p0 y0 [deg] as written
    mass: float
    cg: tuple                         # body frame [m]
    volume: float
    columns: dict                     # i, cda, ca tokens (and the raw cg, mass, volume)


@dataclass(frozen=True)
class MDRod:
    id: int
    line: int
    type: MDRodType
    kind: str                         # fixed, pinned, body, body_pinned, coupled,
    word: str                         # coupled_pinned, free
    body: int | None
    end_a: tuple                      # as written (body frame for body rods)
    end_b: tuple
    num_segs: str
    outputs: str

    @property
    def length(self) -> float:
        return math.dist(self.end_a, self.end_b)


@dataclass(frozen=True)
class MDPoint:
    id: int
    line: int
    kind: str                         # fixed, body, coupled, free, turbine
    word: str
    body: int | None                  # body (or turbine) number
    position: tuple                   # as written; body frame for body points
    on_seabed: bool                   # Z given as "seabed"
    mass: float
    volume: float
    force: tuple                      # FX FY FZ [N] (v1, or v2's 12-column rows)
    columns: dict                     # cda, ca (and fx fy fz) tokens


@dataclass(frozen=True)
class MDLine:
    id: int
    line: int
    type: MDLineType
    ends: tuple                       # ((kind, id, rod end), (kind, id, rod end)), A then B;
    length: float                     # kind "point" or "rod", rod end "A"/"B" or None
    num_segs: str
    outputs: str
    tokens: tuple                     # the AttachA, AttachB words as written


@dataclass
class MDScene:
    """Everything the file says, with MoorDyn's meaning; positions as written."""

    file: MoorDynFile
    depth: float
    gravity: float
    water_density: float
    line_types: dict
    rod_types: dict
    bodies: dict
    rods: dict
    points: dict
    lines: dict
    options: list                     # [name, token or None (mapped to the environment)]
    point_names: dict = field(default_factory=dict)   # id -> case name (default point<N>)
    line_names: dict = field(default_factory=dict)    # id -> case name (default line<N>)
    read: list = field(default_factory=list)
    converted: list = field(default_factory=list)
    ignored: list = field(default_factory=list)
    bathymetry: Optional[str] = None  # the SeafloorFile's absolute path


def _onto_grid(points: dict, depth: float, grid: dict, converted: list) -> None:
    """Fixed points on MoorDyn's flat seabed (z = -depth, or 'seabed') or below the grid's
    surface are put on that surface: they are anchors on the bathymetry. A free point below
    the surface starts on it (MoorDyn's seabed pushes it up there)."""
    from ..model.bathymetry import bathymetry_from_mapping

    surface = bathymetry_from_mapping(grid, "SeafloorFile")
    for p in list(points.values()):
        if p.kind not in ("fixed", "free"):
            continue
        x, y, z = p.position
        bed = surface.height(x, y)
        flat = p.kind == "fixed" and abs(z + depth) <= 1e-9 * depth
        if z != bed and (flat or z < bed):
            points[p.id] = replace(p, position=(x, y, bed))
            converted.append(f"point {p.id} (line {p.line}): z = {z:g} m is put on the "
                             f"bathymetry's surface, z = {bed:.6g} m")


def _bodies(md: MoorDynFile, notes: list) -> dict:
    bodies = {}
    for ident, row in table_entries(md, "bodies", 14, "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* "
                                                 "Volume CdA* Ca*", "body", "ID"):
        word = row.values[1]
        let, num, rest, _ = decompose(word)
        if let in _FIXED:
            kind = "fixed"
        elif let in _COUPLED:
            kind = "coupled"
        elif let in _PINNED_COUPLED:
            kind = "pinned"
        elif let in _TURBINE and num:
            kind = "turbine"
        else:
            kind = "free"
            if let != "FREE":
                notes.append(f"line {row.line}: body attachment {word!r} is not a MoorDyn "
                             "keyword; MoorDyn-C takes any such word as Free, and so does "
                             "this import")
        pose = tuple(read_number(md, row, 2 + i, c)
                     for i, c in enumerate(("X0", "Y0", "Z0", "r0", "p0", "y0")))
        mass = read_number(md, row, 8, "Mass")
        cg = bar_fields(md, row, 9, "CG*", (1, 3))
        cg = (0.0, 0.0, cg[0]) if len(cg) == 1 else tuple(cg)
        bar_fields(md, row, 10, "I*", (1, 3))
        volume = read_number(md, row, 11, "Volume")
        bar_fields(md, row, 12, "CdA*", (1, 2, 3, 6))
        bar_fields(md, row, 13, "Ca*", (1, 3))
        if mass < 0 or volume < 0:
            raise md.error(row.line, "columns 'Mass' and 'Volume' must be >= 0")
        columns = dict(zip(("mass", "cg", "i", "volume", "cda", "ca"), row.values[8:14]))
        bodies[ident] = MDBody(id=ident, line=row.line, kind=kind, word=word, pose=pose,
                               mass=mass, cg=cg, volume=volume, columns=columns)
    return bodies


def _rods(md: MoorDynFile, rod_types: dict, bodies: dict) -> dict:
    rods = {}
    for ident, row in table_entries(md, "rods", 11, "ID RodType Attachment Xa Ya Za Xb Yb Zb "
                                               "NumSegs RodOutputs", "rod", "ID"):
        tname = row.values[1]
        if tname not in rod_types:
            raise md.error(row.line, f"column 'RodType': unknown rod type {tname!r}; known: "
                                     f"{', '.join(rod_types) or '(no ROD TYPES section)'}")
        word = row.values[2]
        let, num, rest, _ = decompose(word)
        body = None
        if let in _FIXED:
            kind = "fixed"
        elif let in ("PINNED", "PIN"):
            kind = "pinned"
        elif let == "BODY":
            if not num or int(num) not in bodies:
                raise md.error(row.line, f"column 'Attachment': {word!r} names no body of the "
                                         "BODIES section")
            body = int(num)
            if rest in ("PINNED", "PIN"):
                kind = "body_pinned"
            elif rest == "":
                kind = "body"
            else:
                raise md.error(row.line, f"column 'Attachment': {word!r}: after Body<N> only "
                                         "'Pinned' may follow")
        elif let in _COUPLED:
            kind = "coupled"
        elif let in _PINNED_COUPLED:
            kind = "coupled_pinned"
        elif let in ("FREE", "POINT", "CON"):
            kind = "free"
        else:
            raise md.error(row.line, f"column 'Attachment': unknown rod attachment {word!r}; "
                                     "allowed: Fixed, Pinned, Body<N>, Body<N>Pinned, Coupled, "
                                     "CoupledPinned, Free")
        coords = [read_number(md, row, 3 + i, c)
                  for i, c in enumerate(("Xa", "Ya", "Za", "Xb", "Yb", "Zb"))]
        read_ident(md, row, 9, "NumSegs", least=0)     # 0: a zero-length, point-like rod
        rods[ident] = MDRod(id=ident, line=row.line, type=rod_types[tname], kind=kind,
                            word=word, body=body, end_a=tuple(coords[:3]),
                            end_b=tuple(coords[3:]), num_segs=row.values[9],
                            outputs=row.values[10])
    return rods


def _points(md: MoorDynFile, bodies: dict) -> dict:
    v1 = md.version == 1
    names = ("Node Type X Y Z M V FX FY FZ CdA CA" if v1
             else "ID Attachment X Y Z Mass Volume CdA Ca")
    points = {}
    for ident, row in table_entries(md, "points", 12 if v1 else 9, names, "point",
                               "Node" if v1 else "ID"):
        word = row.values[1]
        let, num, _, _ = decompose(word)
        body = None
        if let in _FIXED:
            kind = "fixed"
        elif let == "BODY" and num and not v1:
            kind, body = "body", int(num)
            if body not in bodies:
                raise md.error(row.line, f"column 'Attachment': {word!r} names body {body}, "
                                         "which the BODIES section does not define")
        elif let in _COUPLED:
            kind = "coupled"
        elif let in _FREE:
            kind = "free"
        elif let in _TURBINE and num:
            kind, body = "turbine", int(num)
        else:
            allowed = ("Fixed (Anchor), Coupled (Vessel), Free (Connect, Point), Body<N>, "
                       "Turbine<N>" if not v1 else "Fixed, Vessel, Connect")
            raise md.error(row.line, f"column {'Type' if v1 else 'Attachment'!r}: unknown "
                                     f"attachment {word!r}; allowed: {allowed}")
        x = read_number(md, row, 2, "X")
        y = read_number(md, row, 3, "Y")
        on_seabed = decompose(row.values[4])[0] in _SEABED and row.values[4].isalpha()
        z = math.nan if on_seabed else read_number(md, row, 4, "Z")
        mass = read_number(md, row, 5, "M" if v1 else "Mass")
        volume = read_number(md, row, 6, "V" if v1 else "Volume")
        # A 12-column row carries FX FY FZ (v1, and MoorDyn-C v2 reads them too); in v2, a
        # longer row whose words 8-12 are not all numbers is 9 columns and a comment.
        forced = v1 or (len(row.values) >= 12
                        and all(number_token(t) is not None for t in row.values[7:12]))
        if forced:
            force = tuple(read_number(md, row, 7 + i, c) for i, c in enumerate(("FX", "FY", "FZ")))
            columns = dict(zip(("fx", "fy", "fz", "cda", "ca"), row.values[7:12]))
        else:
            force = (0.0, 0.0, 0.0)
            columns = dict(zip(("cda", "ca"), row.values[7:9]))
        if kind == "free" and (mass < 0 or volume < 0):
            raise md.error(row.line, f"free point {ident}: mass and volume must be >= 0")
        points[ident] = MDPoint(id=ident, line=row.line, kind=kind, word=word, body=body,
                                position=(x, y, z), on_seabed=on_seabed, mass=mass,
                                volume=volume, force=force, columns=columns)
    return points


_END = re.compile(r"^(?:(R|ROD)(\d+)([AB])|(C|CON|P|POINT)?(\d+))$")


def _lines(md: MoorDynFile, types: dict, points: dict, rods: dict) -> dict:
    v1 = md.version == 1
    names = ("Line LineType UnstrLen NumSegs NodeAnch NodeFair Flags/Outputs" if v1
             else "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs")
    lines = {}
    for ident, row in table_entries(md, "lines", 7, names, "line", "Line" if v1 else "ID"):
        tname = row.values[1]
        if tname not in types:
            raise md.error(row.line, f"column 'LineType': unknown line type {tname!r}; known: "
                                     f"{', '.join(types)}")
        if v1:
            length_i, segs_i, ends_i, cols = 2, 3, (4, 5), ("NodeAnch", "NodeFair")
        else:
            length_i, segs_i, ends_i, cols = 4, 5, (2, 3), ("AttachA", "AttachB")
        ends = []
        for i, col in zip(ends_i, cols):
            token = row.values[i]
            m = _END.match(token.upper())
            if m is None:
                raise md.error(row.line, f"column {col!r}: {token!r} is not a point (N, PN, "
                                         "PointN, CN, ConN) or a rod end (RNA, RNB, RodNA)")
            if m.group(1):
                rid = int(m.group(2))
                if rid not in rods:
                    raise md.error(row.line, f"column {col!r}: {token!r}: unknown rod {rid}; "
                                             f"rods: {', '.join(map(str, rods)) or 'none'}")
                ends.append(("rod", rid, m.group(3)))
            else:
                pid = int(m.group(5))
                if pid not in points:
                    raise md.error(row.line, f"column {col!r}: unknown point {pid}; points: "
                                             f"{', '.join(str(p) for p in sorted(points))}")
                ends.append(("point", pid, None))
        if ends[0] == ends[1]:
            raise md.error(row.line, f"line {ident} starts and ends at the same place "
                                     f"({row.values[ends_i[0]]})")
        length = read_number(md, row, length_i, "UnstrLen")
        if not length > 0:
            raise md.error(row.line, f"column 'UnstrLen': {row.values[length_i]!r} must be > 0")
        read_ident(md, row, segs_i, "NumSegs")
        lines[ident] = MDLine(id=ident, line=row.line, type=types[tname], ends=tuple(ends),
                              length=length, num_segs=row.values[segs_i],
                              outputs=row.values[6],
                              tokens=(row.values[ends_i[0]], row.values[ends_i[1]]))
    if not lines:
        raise md.error(md.section_lines["lines"], "section LINES has no lines")
    return lines


def vertical_force(point, scene) -> float:
    """The steady vertical force FZ [N] on a free point (its horizontal FX, FY have no
    place in a case)."""
    fx, fy, fz = point.force
    if point.kind != "free":
        return 0.0
    if fx or fy:
        raise scene.file.error(point.line, f"free point {point.id}: a steady horizontal force "
                                           f"(FX {fx:g}, FY {fy:g} N) has no counterpart in a "
                                           "case; give 0")
    return fz


def read_scene(md: MoorDynFile) -> MDScene:
    """Read every table of a parsed file into typed entries (see the module notes).

    Raises
    ------
    MoorDynError
        Naming the line, the column and the value, and how the version was chosen.
    """
    read, converted, ignored = [], [], []
    notes = list(md.notes)
    types = _line_types(md, notes)
    rod_types = _rod_types(md)
    bodies = _bodies(md, notes)
    rods = _rods(md, rod_types, bodies)
    points = _points(md, bodies)
    lines = _lines(md, types, points, rods)
    depth, gravity, rho, options, seafloor = read_environment(md, points, read, converted,
                                                              ignored)
    if md.syrope_ic or any(t.syrope is not None for t in types.values()):
        types, lines = apply_syrope(md, types, lines, converted, ignored)
    for p in list(points.values()):
        if p.on_seabed:
            points[p.id] = replace(p, position=p.position[:2] + (-depth,))
            converted.append(f"point {p.id} (line {p.line}): Z 'seabed' is z = {-depth:g} m")
    if seafloor is not None:
        _onto_grid(points, depth, seafloor[1], converted)
    scene = MDScene(file=md, depth=depth, gravity=gravity, water_density=rho, line_types=types,
                    rod_types=rod_types, bodies=bodies, rods=rods, points=points, lines=lines,
                    options=options, read=read, converted=converted, ignored=ignored,
                    bathymetry=None if seafloor is None else seafloor[0])
    scene.read += [f"MoorDyn v{md.version} file ({md.version_reason})"]
    counts = [(len(types), "line type", "line types"), (len(rod_types), "rod type", "rod types"),
              (len(bodies), "body", "bodies"), (len(rods), "rod", "rods"),
              (len(points), "point", "points"), (len(lines), "line", "lines")]
    scene.read.append(", ".join(f"{n} {one if n == 1 else many}" for n, one, many in counts
                                if n))
    scene.read += notes
    return scene
