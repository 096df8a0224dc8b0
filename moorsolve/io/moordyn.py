"""MoorDyn input files in: parse a MoorDyn v1 or v2 file and map it onto a moorsolve case.

The format (MoorDyn documentation, "Input Files"): free-form front matter, then sections
opened by a header line of dashes around a title. Table sections begin with a line of column
names and a line of units, then one row per entry; OPTIONS rows are ``value name``; OUTPUTS
rows are channel names. Values are separated by white space; ``!``, ``#`` and ``%`` start a
comment in a data row.

=============  =====================================================================
v2 section     columns
=============  =====================================================================
LINE TYPES     TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx [Cl dF cF]
BODIES         ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*
POINTS         ID Attachment X Y Z Mass Volume CdA Ca
LINES          ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs
OPTIONS        value name (WtrDpth, g, rho, dtM, kBot, cBot, ...)
=============  =====================================================================

v1 (MoorDyn v1 and MoorDyn-F before v2): LINE DICTIONARY / LINE TYPES ``Name Diam MassDen EA
BA/-zeta Can Cat Cdn Cdt``; NODE / POINT / CONNECTION PROPERTIES ``Node Type X Y Z M V FX FY
FZ CdA CA`` with types Fixed, Vessel, Connect; LINE PROPERTIES ``Line LineType UnstrLen
NumSegs NodeAnch NodeFair Flags/Outputs``; SOLVER OPTIONS (water density ``rhoW``). The
version is told by the width of the points table (12 columns v1, 9 columns v2).

Mapping onto a case (see :func:`moordyn_to_case_data`): each chain of lines joined end to end
through free points that join exactly two lines becomes one leg, from its fixed point (the
anchor) to its fairlead (a point on the body: Coupled, Vessel or Body#); a free point's mass
and volume become a clump on the joint. Columns moorsolve does not use go into the case
file's ``moordyn`` block (:mod:`moorsolve.model.moordyn_block`) and come back on export.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from os import PathLike
from pathlib import Path


from ..errors import CaseError
from ..model.moordyn_block import RAW_SECTIONS
from .moordyn_curves import is_number, read_curve
from .output_files import write_case_yaml

__all__ = ["MoorDynError", "MoorDynFile", "read_moordyn", "moordyn_to_case_data",
           "import_moordyn"]

#: MoorDyn's own defaults where a file leaves an option out (MoorDyn documentation): the
#: water density is 1025 kg/m^3 in both versions; gravity 9.80665 (v1) and 9.81 (v2-C).
DEFAULT_GRAVITY = {1: 9.80665, 2: 9.81}
DEFAULT_WATER_DENSITY = 1025.0

#: Option names (lower case) that map onto the case's environment.
DEPTH_OPTIONS = ("wtrdpth",)
GRAVITY_OPTIONS = ("g", "gravity")
DENSITY_OPTIONS = ("rho", "rhow", "wtrdnsty")


class MoorDynError(CaseError):
    """A MoorDyn file that cannot be read or mapped: ``field`` is ``FILE:LINE`` (or ``FILE``).

    The message names the column and the value, e.g. ``lines.dat:14: column 'UnstrLen':
    'abc' is not a number``.
    """

    def __init__(self, file: str, line: int | None, message: str):
        self.file = file
        self.line = line
        super().__init__(f"{file}:{line}" if line else file, message)


# ---- sections ----------------------------------------------------------------------------

_SECTION_TITLES = {
    "LINE TYPES": "line_types", "LINE DICTIONARY": "line_types",
    "ROD TYPES": "ROD TYPES", "ROD DICTIONARY": "ROD TYPES",
    "BODIES": "bodies", "BODY LIST": "bodies", "BODY PROPERTIES": "bodies",
    "RODS": "RODS", "ROD LIST": "RODS", "ROD PROPERTIES": "RODS",
    "POINTS": "points", "POINT LIST": "points", "POINT PROPERTIES": "points",
    "CONNECTION PROPERTIES": "points", "NODE PROPERTIES": "points", "CONNECTIONS": "points",
    "LINES": "lines", "LINE LIST": "lines", "LINE PROPERTIES": "lines",
    "OPTIONS": "options", "SOLVER OPTIONS": "options",
    "OUTPUTS": "outputs", "OUTPUT LIST": "outputs", "OUTPUT": "outputs",
    "FAILURE": "FAILURE", "CONTROL": "CONTROL", "EXTERNAL LOADS": "EXTERNAL LOADS",
}

#: Columns of each table, per version; (names, least count, most count).
COLUMNS = {
    ("line_types", 1): ("Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt", 9, 9),
    ("line_types", 2): ("TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx Cl dF cF", 10, 13),
    ("points", 1): ("Node Type X Y Z M V FX FY FZ CdA CA", 12, 12),
    ("points", 2): ("ID Attachment X Y Z Mass Volume CdA Ca", 9, 9),
    ("lines", 1): ("Line LineType UnstrLen NumSegs NodeAnch NodeFair Flags/Outputs", 7, 7),
    ("lines", 2): ("ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs", 7, 7),
    ("bodies", 2): ("ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*", 14, 14),
}

_DASHES = re.compile(r"^\s*-{3,}")
_FORTRAN_EXPONENT = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))[dD]([+-]?\d+)$")


@dataclass
class Row:
    """One data row of a table: its line number and its values (comments removed)."""

    line: int
    values: list


@dataclass
class MoorDynFile:
    """A MoorDyn input file as read: tables of rows, options, outputs, verbatim sections.

    ``tables`` maps ``line_types``, ``points``, ``lines`` (and ``bodies``) to their rows;
    ``sections`` holds the sections moorsolve does not model, verbatim (header and unit
    lines included); ``options`` is ``[(name, value, line), ...]`` in file order.
    """

    path: str
    version: int
    header: list
    tables: dict
    options: list
    outputs: list
    sections: dict = field(default_factory=dict)
    section_lines: dict = field(default_factory=dict)

    @property
    def name(self) -> str:
        return os.path.basename(self.path)

    def error(self, line, message: str) -> MoorDynError:
        return MoorDynError(self.name, line, message)


def _section_title(text: str):
    """The section a header line opens (a key of ``_SECTION_TITLES``), or None."""
    words = " ".join(re.sub(r"[^A-Za-z ]", " ", text).upper().split())
    return words


def _strip_comment(text: str) -> str:
    cut = len(text)
    for mark in "!#%":
        i = text.find(mark)
        if i >= 0:
            cut = min(cut, i)
    return text[:cut]


def read_moordyn(source) -> MoorDynFile:
    """Read a MoorDyn input file (v1 or v2) into its sections.

    Parameters
    ----------
    source : str or pathlib.Path
        The file.

    Raises
    ------
    MoorDynError
        Naming the file and line: unreadable file, unknown or repeated section, missing
        LINE TYPES, POINTS or LINES section, a table row of the wrong width.
    """
    path = Path(source)
    name = path.name
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise MoorDynError(name, None, "MoorDyn file not found") from None
    except IsADirectoryError:
        raise MoorDynError(name, None, "is a directory, not a MoorDyn file") from None
    except UnicodeDecodeError as exc:
        raise MoorDynError(name, None, f"is not UTF-8 text ({exc.reason} at byte "
                                       f"{exc.start})") from None
    except OSError as exc:
        raise MoorDynError(name, None, f"cannot read the file: {exc}") from None

    header, blocks, order = [], {}, []
    current, done = None, False
    for number, line in enumerate(text.splitlines(), start=1):
        if _DASHES.match(line) and re.search(r"[A-Za-z]", line):
            title = _section_title(line)
            if current is None and title not in _SECTION_TITLES:
                header.append(line.rstrip())      # e.g. "---- MoorDyn Input File ----"
                continue
            if current == "outputs" or done:
                done = True                       # the line that closes OUTPUTS
                continue
            if title not in _SECTION_TITLES:
                raise MoorDynError(name, number, f"unknown section {title!r}; known sections: "
                                                 + ", ".join(sorted(set(_SECTION_TITLES))))
            current = _SECTION_TITLES[title]
            if current in blocks:
                raise MoorDynError(name, number, f"section {title!r} appears twice")
            blocks[current] = {"title": title, "line": number, "lines": []}
            order.append(current)
            continue
        if done:
            continue
        if current is None:
            header.append(line.rstrip())
            continue
        blocks[current]["lines"].append((number, line.rstrip()))

    for required in ("line_types", "points", "lines"):
        if required not in blocks:
            title = {"line_types": "LINE TYPES", "points": "POINTS", "lines": "LINES"}[required]
            raise MoorDynError(name, None, f"missing section {title} (a header line such as "
                                           f"'---------- {title} ----------')")

    # The version: the points table has 12 columns in v1 and 9 in v2 (its column-name row).
    points = [(n, t) for n, t in blocks["points"]["lines"] if t.strip()]
    if not points:
        raise MoorDynError(name, blocks["points"]["line"], "section POINTS has no column-name "
                                                           "row")
    width = len(points[0][1].split())
    if width == 12:
        version = 1
    elif width == 9:
        version = 2
    else:
        raise MoorDynError(name, points[0][0], f"the POINTS table has {width} columns; MoorDyn "
                                               f"v2 has 9 ({COLUMNS[('points', 2)][0]}), v1 has "
                                               f"12 ({COLUMNS[('points', 1)][0]})")

    tables, sections = {}, {}
    for key, block in blocks.items():
        if key in ("line_types", "points", "lines", "bodies"):
            tables[key] = _table(name, key, version, block)
        elif key in RAW_SECTIONS:
            if version == 1:
                raise MoorDynError(name, block["line"], f"section {block['title']} is not part of "
                                                        "MoorDyn v1 (the points table has v1 "
                                                        "columns)")
            sections[key] = [t for _, t in block["lines"] if t.strip()]
    options = []
    for number, line in blocks.get("options", {"lines": []})["lines"]:
        words = _strip_comment(line).split()
        if not words:
            continue
        if len(words) < 2:
            raise MoorDynError(name, number, f"option row {line.strip()!r} needs a value and a "
                                             "name ('0.001 dtM')")
        options.append((words[1], words[0], number))
    seen = {}
    for opt, _, number in options:
        if opt.lower() in seen:
            raise MoorDynError(name, number, f"option {opt!r} is given twice (first at line "
                                             f"{seen[opt.lower()]})")
        seen[opt.lower()] = number
    outputs = []
    for _, line in blocks.get("outputs", {"lines": []})["lines"]:
        if line.strip().upper() == "END":
            break
        if line.strip():
            outputs.append(line.strip())
    return MoorDynFile(path=str(path), version=version, header=header, tables=tables,
                       options=options, outputs=outputs, sections=sections,
                       section_lines={k: b["line"] for k, b in blocks.items()})


def _table(name: str, key: str, version: int, block: dict) -> list:
    """Rows of a table section: skip the column-name and unit rows, check each row's width."""
    spec = COLUMNS.get((key, version))
    if spec is None:
        raise MoorDynError(name, block["line"], f"section {block['title']} is not part of "
                                                f"MoorDyn v{version}")
    columns, least, most = spec
    lines = [(n, t) for n, t in block["lines"] if t.strip()]
    if len(lines) < 2:
        raise MoorDynError(name, block["line"], f"section {block['title']} needs a column-name "
                                                f"row and a units row ({columns})")
    rows = []
    for number, line in lines[2:]:
        values = _strip_comment(line).split()
        if not values:
            continue
        if not least <= len(values) <= most:
            want = str(least) if least == most else f"{least} to {most}"
            raise MoorDynError(name, number, f"{block['title']} row has {len(values)} columns; "
                                             f"expected {want} ({columns})")
        rows.append(Row(line=number, values=values))
    return rows


# ---- values ------------------------------------------------------------------------------


def _number(md: MoorDynFile, row: Row, index: int, column: str, what: str = "column") -> float:
    token = row.values[index]
    column = f"{what} {column!r}"
    m = _FORTRAN_EXPONENT.match(token)
    try:
        value = float(f"{m.group(1)}e{m.group(2)}" if m else token)
    except ValueError:
        raise md.error(row.line, f"{column}: {token!r} is not a number") from None
    if not math.isfinite(value):
        raise md.error(row.line, f"{column}: {token!r} is not a finite number")
    return value


def _ident(md: MoorDynFile, row: Row, index: int, column: str) -> int:
    token = row.values[index]
    if not token.isdigit() or int(token) < 1:
        raise md.error(row.line, f"column {column!r}: {token!r} is not a positive whole number")
    return int(token)


def _attachment(md: MoorDynFile, row: Row, column: str) -> tuple:
    """The kind of a point's attachment: ("fixed" | "free" | "coupled", None) or ("body", N)."""
    token = row.values[1]
    word = token.upper()
    if word in ("FIXED", "FIX", "ANCHOR"):
        return "fixed", None
    if word in ("COUPLED", "VESSEL", "VES", "CPLD"):
        return "coupled", None
    if word in ("FREE", "CONNECT", "CON", "POINT"):
        return "free", None
    m = re.fullmatch(r"BODY(\d+)", word)
    if m and md.version == 2 and int(m.group(1)) >= 1:
        return "body", int(m.group(1))
    allowed = ("Fixed (Anchor), Coupled (Vessel), Free (Connect), Body<N>" if md.version == 2
               else "Fixed, Vessel, Connect")
    raise md.error(row.line, f"column {column!r}: unknown attachment {token!r}; allowed: "
                             f"{allowed}")


# ---- mapping onto a case -----------------------------------------------------------------


def _line_types(md: MoorDynFile, gravity: float, rho: float):
    """Case line types and their passthrough columns."""
    types, passthrough, rows = {}, {}, {}
    v1 = md.version == 1
    for row in md.tables["line_types"]:
        name = row.values[0]
        if name in types:
            raise md.error(row.line, f"line type {name!r} is defined twice (first at line "
                                     f"{rows[name]})")
        rows[name] = row.line
        diameter = _number(md, row, 1, "Diam")
        if not diameter > 0:
            raise md.error(row.line, f"column 'Diam': {row.values[1]!r} must be > 0")
        mass = _number(md, row, 2, "MassDen" if v1 else "Mass/m")
        if mass < 0:
            raise md.error(row.line, f"column 'Mass/m': {row.values[2]!r} must be >= 0")
        ea_token = row.values[3]
        cols = {}
        weight = gravity * (mass - rho * math.pi * diameter ** 2 / 4.0)
        static = ea_token.split("|")[0] if not v1 else ea_token
        if not is_number(static):
            # EA names a file of strain and tension (moorsolve.io.moordyn_curves).
            stretch = read_curve(Path(md.path).parent, static,
                                 lambda message, line=row.line: md.error(line, message))
            cols["ea"] = ea_token
            types[name] = {"weight_in_water": weight, "stretch": stretch, "diameter": diameter}
        else:
            if "|" in ea_token and not v1:
                # Static and dynamic stiffness "EA_s|EA_d(|slope)": the static one is the
                # statics'.
                first = Row(row.line, [static])
                ea = _number(md, first, 0, "EA")
                cols["ea"] = ea_token
            else:
                ea = _number(md, row, 3, "EA")
            if not ea > 0:
                raise md.error(row.line, f"column 'EA': {ea_token!r} must be > 0")
            types[name] = {"weight_in_water": weight, "ea": ea, "diameter": diameter}
        keys = (("ba", "can", "cat", "cdn", "cdt") if v1
                else ("ba", "ei", "cd", "ca", "cdax", "caax", "cl", "df", "cf"))
        names = {"can": "ca", "cat": "caax", "cdn": "cd", "cdt": "cdax"}
        for key, token in zip(keys, row.values[4:]):
            cols[names.get(key, key)] = token
        passthrough[name] = cols
    if not types:
        raise md.error(md.section_lines["line_types"], "section LINE TYPES has no line types")
    return types, passthrough


@dataclass
class _Point:
    id: int
    line: int
    kind: str                 # fixed, free, coupled, body
    body: int | None
    attachment: str           # the keyword as written
    position: tuple           # as written (body frame for body points)
    mass: float
    volume: float
    columns: dict             # passthrough tokens
    force: tuple = (0.0, 0.0, 0.0)


def _points(md: MoorDynFile) -> dict:
    points = {}
    v1 = md.version == 1
    for row in md.tables["points"]:
        pid = _ident(md, row, 0, "Node" if v1 else "ID")
        if pid in points:
            raise md.error(row.line, f"point {pid} is defined twice (first at line "
                                     f"{points[pid].line})")
        kind, body = _attachment(md, row, "Type" if v1 else "Attachment")
        names = ("X", "Y", "Z")
        position = tuple(_number(md, row, 2 + i, names[i]) for i in range(3))
        mass = _number(md, row, 5, "M" if v1 else "Mass")
        volume = _number(md, row, 6, "V" if v1 else "Volume")
        if v1:
            keys = ("fx", "fy", "fz", "cda", "ca")
            force = tuple(_number(md, row, 7 + i, c) for i, c in enumerate(("FX", "FY", "FZ")))
        else:
            keys, force = ("cda", "ca"), (0.0, 0.0, 0.0)
        columns = dict(zip(keys, row.values[7:]))
        if kind == "free":
            if mass < 0 or volume < 0:
                raise md.error(row.line, f"free point {pid}: mass and volume must be >= 0")
            if any(f != 0.0 for f in force):
                raise md.error(row.line, f"free point {pid}: a steady external force (FX FY FZ) "
                                         "is not represented in a moorsolve case; give a mass or "
                                         "volume instead")
        else:
            columns = {"mass": row.values[5], "volume": row.values[6], **columns}
        points[pid] = _Point(id=pid, line=row.line, kind=kind, body=body,
                             attachment=row.values[1], position=position, mass=mass,
                             volume=volume, columns=columns, force=force)
    return points


@dataclass
class _Line:
    id: int
    line: int
    type: str
    ends: tuple               # (AttachA point id, AttachB point id)
    length: float
    num_segs: str
    outputs: str


def _lines(md: MoorDynFile, types: dict, points: dict) -> dict:
    lines = {}
    v1 = md.version == 1
    for row in md.tables["lines"]:
        lid = _ident(md, row, 0, "Line" if v1 else "ID")
        if lid in lines:
            raise md.error(row.line, f"line {lid} is defined twice (first at line "
                                     f"{lines[lid].line})")
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
            if re.fullmatch(r"[Rr]\d+[AaBb]", token):
                raise md.error(row.line, f"column {col!r}: {token!r} attaches the line to a rod "
                                         "end; moorsolve has no rods")
            pid = _ident(md, row, i, col)
            if pid not in points:
                raise md.error(row.line, f"column {col!r}: unknown point {pid}; points: "
                                         f"{', '.join(str(p) for p in sorted(points))}")
            ends.append(pid)
        if ends[0] == ends[1]:
            raise md.error(row.line, f"line {lid} starts and ends at point {ends[0]}")
        length = _number(md, row, length_i, "UnstrLen")
        if not length > 0:
            raise md.error(row.line, f"column 'UnstrLen': {row.values[length_i]!r} must be > 0")
        num_segs = row.values[segs_i]
        _ident(md, row, segs_i, "NumSegs")
        lines[lid] = _Line(id=lid, line=row.line, type=tname, ends=tuple(ends), length=length,
                           num_segs=num_segs, outputs=row.values[6])
    if not lines:
        raise md.error(md.section_lines["lines"], "section LINES has no lines")
    return lines


def _body(md: MoorDynFile, points: dict):
    """The one body that carries the fairleads, when the file has BODIES: its pose and row."""
    rows = md.tables.get("bodies", [])
    bodies = {}
    for row in rows:
        bid = _ident(md, row, 0, "ID")
        if bid in bodies:
            raise md.error(row.line, f"body {bid} is defined twice")
        bodies[bid] = row
    used = sorted({p.body for p in points.values() if p.kind == "body"})
    if len(bodies) > 1 or len(used) > 1:
        line = rows[1].line if len(rows) > 1 else next(p.line for p in points.values()
                                                       if p.kind == "body" and p.body == used[1])
        raise md.error(line, "more than one body: a moorsolve case has one body")
    for bid in used:
        if bid not in bodies:
            point = next(p for p in points.values() if p.body == bid)
            raise md.error(point.line, f"column 'Attachment': {point.attachment!r} names body "
                                       f"{bid}, which the BODIES section does not define")
    if not bodies:
        return None
    (bid, row), = bodies.items()
    word = row.values[1].upper()
    if word in ("FIXED", "FIX", "ANCHOR"):
        free = []
    elif word in ("COUPLED", "VESSEL", "VES", "CPLD", "FREE"):
        free = ["surge", "sway", "yaw"]
    else:
        raise md.error(row.line, f"column 'Attachment': unknown body attachment "
                                 f"{row.values[1]!r}; allowed: Fixed, Coupled (Vessel), Free")
    pose = [_number(md, row, 2 + i, c) for i, c in enumerate(("X0", "Y0", "Z0", "r0", "p0",
                                                               "y0"))]
    for value, col, index in ((pose[3], "r0", 5), (pose[4], "p0", 6)):
        if value != 0.0:
            raise md.error(row.line, f"column {col!r}: {row.values[index]!r}: a body with roll or "
                                     "pitch is not represented (moorsolve's body moves in the "
                                     "horizontal plane); give 0")
    columns = dict(zip(("mass", "cg", "i", "volume", "cda", "ca"), row.values[8:]))
    return {"id": bid, "attachment": row.values[1], "x0": pose[0], "y0": pose[1],
            "z0": pose[2], "yaw_deg": pose[5], "columns": columns, "free": free}


def _environment(md: MoorDynFile, points: dict):
    """Depth, gravity, water density and the options list (mapped ones with value None)."""
    values, options = {}, []
    for opt, token, number in md.options:
        low = opt.lower()
        key = ("depth" if low in DEPTH_OPTIONS else "gravity" if low in GRAVITY_OPTIONS
               else "water_density" if low in DENSITY_OPTIONS else None)
        if key is None:
            options.append([opt, token])
            continue
        row = Row(number, [token])
        value = _number(md, row, 0, opt, "option")
        if not value > 0:
            raise md.error(number, f"option {opt!r}: {token!r} must be > 0")
        if key in values:
            raise md.error(number, f"option {opt!r} repeats the {key.replace('_', ' ')} given "
                                   "by another option")
        values[key] = value
        options.append([opt, None])
    notes = []
    if "depth" not in values:
        fixed = [p.position[2] for p in points.values() if p.kind == "fixed"]
        if not fixed or min(fixed) >= 0:
            raise md.error(None, "no water depth: give the option WtrDpth (or a fixed point "
                                 "below the water line)")
        values["depth"] = -min(fixed)
        notes.append("The file gives no WtrDpth: the depth is that of the deepest fixed "
                     "point.")
    if "gravity" not in values:
        values["gravity"] = DEFAULT_GRAVITY[md.version]
        notes.append(f"The file gives no g: MoorDyn v{md.version}'s default "
                     f"{values['gravity']} m/s^2 is used.")
    values.setdefault("water_density", DEFAULT_WATER_DENSITY)
    return values, options, notes


def _legs(md: MoorDynFile, points: dict, lines: dict, has_body: bool):
    """Chains of lines through free points joining two lines, anchor end first."""
    at = {pid: [] for pid in points}
    for line in lines.values():
        for pid in line.ends:
            at[pid].append(line.id)
    for pid, attached in at.items():
        p = points[pid]
        if not attached:
            raise md.error(p.line, f"point {pid} is attached to no line; moorsolve cannot keep "
                                   "it (remove it)")
        if p.kind == "free" and len(attached) == 1:
            raise md.error(p.line, f"free point {pid} ends line {attached[0]} without joining "
                                   "another line; a moorsolve leg ends at an anchor and a "
                                   "fairlead")
        if p.kind == "free" and len(attached) > 2:
            raise md.error(p.line, f"free point {pid} joins {len(attached)} lines ("
                                   f"{', '.join(str(i) for i in sorted(attached))}): a bridle or "
                                   "hub is not representable (a moorsolve leg is one chain of "
                                   "segments from anchor to fairlead)")
    used, chains = set(), []
    for lid in sorted(lines):
        if lid in used:
            continue
        # Walk to one terminal (non-free) end of this chain, then collect it from there.
        start_line, start_point = lid, lines[lid].ends[0]
        seen = {lid}
        while points[start_point].kind == "free":
            other = next(i for i in at[start_point] if i != start_line)
            if other in seen:
                loop = ", ".join(map(str, sorted(seen)))
                raise md.error(points[start_point].line,
                               f"lines {loop} form a closed loop through free points")
            seen.add(other)
            a, b = lines[other].ends
            start_point = a if b == start_point else b
            start_line = other
        chain, point, current = [], start_point, start_line
        while True:
            a, b = lines[current].ends
            reverse = a != point
            chain.append((current, reverse))
            used.add(current)
            point = a if reverse else b
            if points[point].kind != "free":
                break
            current = next(i for i in at[point] if i != current)
        chains.append((start_point, chain, point))

    legs = []
    for first, chain, last in chains:
        kinds = (points[first].kind, points[last].kind)
        on_body = {"coupled", "body"}
        ids = ", ".join(str(i) for i, _ in chain)
        if kinds[0] in on_body and kinds[1] in on_body:
            raise md.error(lines[chain[0][0]].line, f"line(s) {ids} join two fairleads (points "
                                                    f"{first} and {last}); a moorsolve leg runs "
                                                    "from an anchor to a fairlead")
        if kinds[0] == "fixed" and kinds[1] == "fixed":
            if has_body:
                raise md.error(lines[chain[0][0]].line, f"line(s) {ids} join two fixed points "
                                                        f"({first} and {last}) in a model with a "
                                                        "body: every leg must end on the body")
            flip = points[first].position[2] > points[last].position[2]
        else:
            flip = kinds[0] in on_body
        if flip:
            first, last = last, first
            chain = [(i, not r) for i, r in reversed(chain)]
        legs.append((first, chain, last))
    return legs


def moordyn_to_case_data(md: MoorDynFile) -> dict:
    """Map a parsed MoorDyn file onto a case dictionary (the shape of a case file).

    Line types keep their names; the submerged weight is ``g (Mass/m - rho pi Diam^2 / 4)``
    (Diam is MoorDyn's volume-equivalent diameter). Each leg is named ``L<id>`` after the
    MoorDyn line at its anchor. Fixed points are anchors ``[x, y, z]``; Coupled, Vessel and
    Body# points are fairleads on the case's body (global coordinates at the body's
    reference pose; a body given in BODIES is placed by its X0, Y0 and yaw y0); free points
    joining two lines are joints, with ``{clump: {mass, volume}}`` when they carry either.
    WtrDpth, g and rho/rhoW go to the environment; everything else to the ``moordyn`` block.
    The body gets no loads: the case solves at rest until loads are added.

    Raises
    ------
    MoorDynError
        Naming the file, the line and the column of what cannot be mapped.
    """
    points = _points(md)
    body = _body(md, points)
    env, options, notes = _environment(md, points)
    types, type_columns = _line_types(md, env["gravity"], env["water_density"])
    lines = _lines(md, types, points)
    fairlead_kinds = {p.kind for p in points.values() if p.kind in ("coupled", "body")}
    if fairlead_kinds == {"coupled", "body"}:
        point = next(p for p in points.values() if p.kind == "coupled")
        raise md.error(point.line, f"point {point.id} is coupled while other fairleads are on a "
                                   "body: a moorsolve case has one body; attach them all to it")
    has_body = bool(fairlead_kinds)
    legs_found = _legs(md, points, lines, has_body)

    yaw0 = math.radians(body["yaw_deg"]) if body else 0.0
    origin = (body["x0"], body["y0"], body["z0"]) if body else (0.0, 0.0, 0.0)

    def global_position(p: _Point) -> list:
        if p.kind != "body":
            return list(p.position)
        x, y, z = p.position
        c, s = math.cos(yaw0), math.sin(yaw0)
        return [origin[0] + c * x - s * y, origin[1] + s * x + c * y, origin[2] + z]

    legs, leg_blocks = [], {}
    for first, chain, last in sorted(legs_found, key=lambda leg: min(i for i, _ in leg[1])):
        name = f"L{chain[0][0]}"
        segments, block_lines, block_points = [], [], []
        anchor = points[first]
        block_points.append({"id": anchor.id, "attachment": anchor.attachment,
                             "columns": dict(anchor.columns)})
        for k, (lid, reverse) in enumerate(chain):
            line = lines[lid]
            if k > 0:
                joint_id = line.ends[1] if reverse else line.ends[0]
                joint = points[joint_id]
                if joint.mass or joint.volume:
                    segments.append({"clump": {"mass": joint.mass, "volume": joint.volume}})
                block_points.append({"id": joint.id, "attachment": joint.attachment,
                                     "position": list(joint.position),
                                     "columns": dict(joint.columns)})
            segments.append({"type": line.type, "length": line.length})
            block_lines.append({"id": lid, "num_segs": line.num_segs, "outputs": line.outputs,
                                "reversed": reverse})
        fair = points[last]
        block_points.append({"id": fair.id, "attachment": fair.attachment,
                             "columns": dict(fair.columns)})
        legs.append({"name": name, "anchor": global_position(anchor),
                     "fairlead": global_position(fair), "segments": segments})
        leg_blocks[name] = {"lines": block_lines, "points": block_points}

    block = {"version": md.version, "header": list(md.header)}
    notes += ["Not in a MoorDyn file, to fill in here: body.loads (wind, current, wave drift, "
              "a constant force), line_types.*.mbl (for the checks), environment.seabed."
              "friction (0 here; MoorDyn's FrictionCoefficient, if any, stays in "
              "moordyn.options)."]
    block["notes"] = notes
    block["line_types"] = {k: v for k, v in type_columns.items() if v}
    if body is not None:
        block["body"] = {k: v for k, v in body.items() if k != "free"}
    block["legs"] = leg_blocks
    block["options"] = options
    block["outputs"] = list(md.outputs)
    if md.sections:
        block["sections"] = {k: list(v) for k, v in md.sections.items()}

    stem = os.path.splitext(md.name)[0] or "moordyn"
    data = {"name": f"{stem} (imported from MoorDyn v{md.version})",
            "environment": {"depth": env["depth"], "water_density": env["water_density"],
                            "gravity": env["gravity"]},
            "line_types": types}
    if has_body:
        data["body"] = {"free": body["free"] if body else ["surge", "sway", "yaw"]}
    data["legs"] = legs
    data["moordyn"] = block
    return data


# ---- writing the case file ---------------------------------------------------------------

_YAML_PREAMBLE = """\
# Imported from the MoorDyn v{version} file {source} by `moorsolve import-moordyn`.
# The geometry, line types and environment are the file's. MoorDyn cannot hold what a
# static analysis adds, so the body has no loads (the case solves at rest) and the lines
# no MBL: add body.loads, line_types.*.mbl and environment.seabed.friction as needed.
# The `moordyn` block keeps the columns moorsolve does not use (dynamic coefficients,
# NumSegs, outputs, options, IDs); `moorsolve export-moordyn` writes them back unchanged.
"""


def import_moordyn(source, out=None) -> dict:
    """Read a MoorDyn file, map it onto a case, validate it, and optionally write the YAML.

    Parameters
    ----------
    source : str or pathlib.Path
        MoorDyn input file (v1 or v2).
    out : str or pathlib.Path, optional
        Case file to write (atomically, only when everything succeeded).

    Returns
    -------
    dict
        The case dictionary (``moorsolve.load_case`` accepts it).

    Raises
    ------
    MoorDynError
        The file is malformed or holds what a case cannot (a bridle, rods on lines, ...).
    CaseError
        The mapped case fails the case-file validation (e.g. an anchor below the seabed);
        the message names the MoorDyn file and the case field.
    """
    if not isinstance(source, (str, PathLike)):
        raise CaseError("", f"{source!r} is not a path to a MoorDyn file")
    md = read_moordyn(source)
    data = moordyn_to_case_data(md)
    from .case_file import load_case
    try:
        load_case(data, keep_source=False)
    except MoorDynError:
        raise
    except CaseError as exc:
        raise MoorDynError(md.name, None, f"the imported case is not valid: {exc}") from None
    if out is not None:
        write_case_yaml(data, out, _YAML_PREAMBLE.format(version=md.version, source=md.name))
    return data
