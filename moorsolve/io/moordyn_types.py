"""The LINE TYPES and ROD TYPES of a MoorDyn file: diameter, mass per metre, EA (a number,
a tension-strain curve file or a SYROPE rope) and the dynamic columns, by moorsolve name."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .moordyn_curves import read_curve
from .moordyn_parse import MoorDynFile, Row, number_token
from .moordyn_rows import read_number, check_width
from .moordyn_syrope import is_syrope, read_syrope

__all__ = ["MDLineType", "MDRodType"]


@dataclass(frozen=True)
class MDLineType:
    name: str
    line: int
    diameter: float
    mass: float                       # [kg/m] in air
    ea: float                         # static axial stiffness [N] (None: a curve file)
    ea_token: str                     # as written ("6.0e8", "1.5e8|3.0e8", "poly.txt")
    columns: dict                     # dynamic columns by moorsolve name (ba, ei, cd, ...)
    layout: int                       # 1: v1's 9 columns, 2: v2's 10, 11 or 13
    stretch: dict = None              # the table law of an EA curve file (moordyn_curves)
    syrope: object = None             # a SYROPE rope's data until its lines get their laws


@dataclass(frozen=True)
class MDRodType:
    name: str
    line: int
    diameter: float
    mass: float
    columns: dict                     # cd, ca, cdend, caend



_LT_V1 = ("ba", "can", "cat", "cdn", "cdt")
_LT_V2 = ("ba", "ei", "cd", "ca", "cdax", "caax", "cl", "df", "cf")
_V1_TO_V2 = {"can": "ca", "cat": "caax", "cdn": "cd", "cdt": "cdax"}


def _line_types(md: MoorDynFile, scene_notes: list) -> dict:
    types = {}
    for row in md.tables.get("line_types", []):
        n = len(row.values)
        if n == 9:
            layout = 1
        elif n in (10, 11, 13):
            layout = 2
        else:
            raise md.error(row.line, f"LINE TYPES row has {n} columns; MoorDyn reads 9 (v1: "
                                     "Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt) or 10, 11 "
                                     "or 13 (v2: TypeName Diam Mass/m EA BA/-zeta EI Cd Ca "
                                     "CdAx CaAx [Cl [dF cF]])")
        name = row.values[0]
        if name in types:
            raise md.error(row.line, f"line type {name!r} is defined twice (first at line "
                                     f"{types[name].line})")
        diameter = read_number(md, row, 1, "Diam")
        if diameter < 0:
            raise md.error(row.line, f"column 'Diam': {row.values[1]!r} must be >= 0")
        mass = read_number(md, row, 2, "MassDen" if layout == 1 else "Mass/m")
        if mass < 0:
            raise md.error(row.line, f"column 'Mass/m': {row.values[2]!r} must be >= 0")
        ea_token = row.values[3]
        def error(message, line=row.line):
            return md.error(line, message)
        if is_syrope(ea_token):
            # Each line gets its law from its Tmax0 (moordyn_syrope.apply_syrope).
            keys = _LT_V1 if layout == 1 else _LT_V2
            columns = {_V1_TO_V2.get(k, k): t for k, t in zip(keys, row.values[4:])}
            types[name] = MDLineType(name=name, line=row.line, diameter=diameter, mass=mass,
                                     ea=None, ea_token=ea_token, columns=columns,
                                     layout=layout,
                                     syrope=read_syrope(Path(md.path).parent, ea_token, error))
            continue
        parts = ea_token.split("|")
        if len(parts) > 3:
            raise md.error(row.line, f"column 'EA': {ea_token!r} has more than 3 '|'-separated "
                                     "values (MoorDyn refuses it)")
        stretch = None
        if number_token(parts[0]) is None:
            # EA names a file of strain and tension: a table law (moordyn_curves.py).
            stretch = read_curve(Path(md.path).parent, parts[0],
                                 lambda message, line=row.line: md.error(line, message))
            ea = None
        else:
            ea = read_number(md, Row(row.line, parts), 0, "EA")
            if not ea > 0:
                raise md.error(row.line, f"column 'EA': {ea_token!r} must be > 0")
        for p in parts[1:]:
            read_number(md, Row(row.line, [p]), 0, "EA")
        keys = _LT_V1 if layout == 1 else _LT_V2
        columns = {_V1_TO_V2.get(k, k): t for k, t in zip(keys, row.values[4:])}
        if len(parts) > 1 or stretch is not None:
            columns["ea"] = ea_token
        if layout != md.version:
            scene_notes.append(f"line {row.line}: LINE TYPES row has v{layout}'s "
                               f"{n} columns in a v{md.version} file; its dynamic columns are "
                               f"read as v{layout}'s")
        types[name] = MDLineType(name=name, line=row.line, diameter=diameter, mass=mass, ea=ea,
                                 ea_token=ea_token, columns=columns, layout=layout,
                                 stretch=stretch)
    if not types:
        raise md.error(md.section_lines["line_types"], "section LINE TYPES has no line types")
    return types


def _rod_types(md: MoorDynFile) -> dict:
    types = {}
    for row in md.tables.get("rod_types", []):
        check_width(md, row, 7, "ROD TYPES", "TypeName Diam Mass/m Cd Ca CdEnd CaEnd")
        name = row.values[0]
        if name in types:
            raise md.error(row.line, f"rod type {name!r} is defined twice")
        diameter = read_number(md, row, 1, "Diam")
        mass = read_number(md, row, 2, "Mass/m")
        if diameter < 0 or mass < 0:
            raise md.error(row.line, "columns 'Diam' and 'Mass/m' must be >= 0")
        columns = dict(zip(("cd", "ca", "cdend", "caend"), row.values[3:7]))
        types[name] = MDRodType(name=name, line=row.line, diameter=diameter, mass=mass,
                                columns=columns)
    return types
