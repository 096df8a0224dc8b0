"""Values of a MoorDyn table's rows, read as MoorDyn reads them: numbers, IDs (in order for
v2), widths and bar-separated fields, each refused with the line and the column."""

from __future__ import annotations

import math
import re

from .moordyn_parse import MoorDynFile, Row, number_token



def read_number(md: MoorDynFile, row: Row, index: int, column: str) -> float:
    token = row.values[index]
    value = number_token(token)
    if value is None:
        raise md.error(row.line, f"column {column!r}: {token!r} is not a number")
    if not math.isfinite(value):
        raise md.error(row.line, f"column {column!r}: {token!r} is not a finite number")
    return value


def read_ident(md: MoorDynFile, row: Row, index: int, column: str, least: int = 1) -> int:
    token = row.values[index]
    if not re.fullmatch(r"\+?\d+", token) or int(token) < least:
        what = "a positive" if least == 1 else "a non-negative"
        raise md.error(row.line, f"column {column!r}: {token!r} is not {what} whole number")
    return int(token)


def check_width(md: MoorDynFile, row: Row, least: int, title: str, columns: str) -> None:
    if len(row.values) < least:
        raise md.error(row.line, f"{title} row has {len(row.values)} columns; expected "
                                 f"{least} or more ({columns})")


def table_entries(md: MoorDynFile, kind: str, least: int, columns: str, title: str,
             id_column: str) -> list:
    """``(ID, row)`` of every row of a table, each at least ``least`` words wide."""
    rows = md.tables.get(kind, [])
    for row in rows:
        check_width(md, row, least, kind.upper(), columns)
    return list(zip(row_ids(md, rows, title, id_column), rows))


def row_ids(md: MoorDynFile, rows: list, title: str, column: str) -> list:
    """The rows' IDs, checked: v2 needs 1, 2, 3, ... in order; v1 distinct numbers."""
    seen, ids = {}, []
    for k, row in enumerate(rows, start=1):
        ident = read_ident(md, row, 0, column)
        if ident in seen:
            raise md.error(row.line, f"{title} {ident} is defined twice (first at line "
                                     f"{seen[ident]})")
        if md.version == 2 and ident != k:
            raise md.error(row.line, f"{title} ID {ident} out of order: MoorDyn v2 needs the "
                                     f"IDs 1, 2, 3, ... in order (this row is number {k})")
        seen[ident] = row.line
        ids.append(ident)
    return ids


def bar_fields(md: MoorDynFile, row: Row, index: int, column: str, counts: tuple) -> list:
    parts = row.values[index].split("|")
    if len(parts) not in counts:
        raise md.error(row.line, f"column {column!r}: {row.values[index]!r} must have "
                                 f"{' or '.join(map(str, counts))} '|'-separated numbers")
    return [read_number(md, Row(row.line, parts), i, column) for i in range(len(parts))]
