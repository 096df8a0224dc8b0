"""MoorDyn input files as text: sections, rows, the format version, options and outputs.

This module reads the file the way MoorDyn's own parsers do (MoorDyn-C v2 ``MoorDyn2.cpp``,
MoorDyn-C v1, and MoorDyn-F in OpenFAST, v1 and v2), and is as tolerant as they are:

- A line containing ``---`` ends the section before it. It opens a new section when its
  upper-cased text contains a section name, checked in MoorDyn-F's order (``LINE TYPES``
  before ``LINES``, ...); any other words on it do not matter (``LINE TYPES Chain studless``).
  A ``---`` line naming no section (``--- need this line ---``, ``--- END ---``) just
  closes the one before it; the rows of a section MoorDyn does not know are skipped, as
  MoorDyn skips them.
- Blank lines and comment lines (first character ``#`` or ``!``, which MoorDyn-F drops) are
  skipped anywhere; ``#`` or ``!`` inside a row ends it (MoorDyn-C cuts a row at ``#``).
- A table section starts with an optional count row (OpenFAST's MoorDyn v1: ``3 NLines -
  number of line objects``), then a column-name row and a units row that MoorDyn skips
  unread, then one row per entry. Words beyond the columns a row needs are ignored where
  MoorDyn ignores them.
- OPTIONS rows are ``value name [description]``; a row with fewer than two words is skipped
  (MoorDyn-C skips it). OUTPUTS rows are channel names up to ``END``.

The version (v1: MoorDyn-C v1 and MoorDyn-F before OpenFAST 3.3; v2: everything since) is
told by what decides how MoorDyn would read the file: the column order of the LINES table
(v1 ``Line LineType UnstrLen NumSegs NodeAnch NodeFair``, v2 ``ID LineType AttachA AttachB
UnstrLen NumSegs``), from its column names and from its rows, then OpenFAST v1's count rows,
v2-only sections and the width of the LINE TYPES rows. :attr:`MoorDynFile.version_reason`
says which evidence decided, and every refusal names it.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import CaseError

__all__ = ["MoorDynError", "MoorDynFile", "Row", "read_moordyn", "parse_moordyn_text",
           "SECTION_NAMES", "TABLE_SECTIONS", "number_token"]


class MoorDynError(CaseError):
    """A MoorDyn file that cannot be read or mapped: ``field`` is ``FILE:LINE`` (or ``FILE``).

    The message names the column and the value, e.g. ``lines.dat:14: column 'UnstrLen':
    'abc' is not a number``, and, when the file was read as a guessed format version, which
    one and why.
    """

    def __init__(self, file: str, line: int | None, message: str):
        self.file = file
        self.line = line
        super().__init__(f"{file}:{line}" if line else file, message)


#: Section kinds and the names that open them, in the order MoorDyn-F tests them (a header
#: is the first kind one of whose names its upper-cased text contains).
SECTION_NAMES = (
    ("line_types", ("LINE DICTIONARY", "LINE TYPES")),
    ("rod_types", ("ROD DICTIONARY", "ROD TYPES")),
    ("bodies", ("BODIES", "BODY LIST", "BODY PROPERTIES")),
    ("rods", ("RODS", "ROD LIST", "ROD PROPERTIES")),
    ("points", ("POINTS", "POINT LIST", "POINT PROPERTIES", "CONNECTION PROPERTIES",
                "NODE PROPERTIES")),
    ("lines", ("LINES", "LINE LIST", "LINE PROPERTIES")),
    ("EXTERNAL LOADS", ("EXTERNAL LOADS",)),
    ("CONTROL", ("CONTROL",)),
    ("FAILURE", ("FAILURE",)),
    ("syrope_ic", ("SYROPE IC",)),
    ("options", ("OPTIONS",)),
    ("outputs", ("OUTPUT",)),
)
#: Sections whose rows are a table (column names, units, rows).
TABLE_SECTIONS = ("line_types", "rod_types", "bodies", "rods", "points", "lines")
#: Sections kept verbatim (moorsolve has no model of them).
VERBATIM_SECTIONS = ("EXTERNAL LOADS", "CONTROL", "FAILURE")
#: Display titles of the sections.
TITLES = {"line_types": "LINE TYPES", "rod_types": "ROD TYPES", "bodies": "BODIES",
          "rods": "RODS", "points": "POINTS", "lines": "LINES", "options": "OPTIONS",
          "outputs": "OUTPUTS"}

_FORTRAN_EXPONENT = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))[dD]([+-]?\d+)$")
_INTEGER = re.compile(r"^[+-]?\d+$")
_COUNT_WORD = re.compile(r"^N[A-Za-z]+$")


def number_token(token: str):
    """The float a MoorDyn number token means (``1.5e8``, Fortran ``1.5D8``), or None."""
    m = _FORTRAN_EXPONENT.match(token)
    try:
        return float(f"{m.group(1)}e{m.group(2)}" if m else token)
    except ValueError:
        return None


@dataclass
class Row:
    """One data row of a table: its line number and its words (comments removed)."""

    line: int
    values: list


@dataclass
class MoorDynFile:
    """A MoorDyn input file as read.

    ``tables`` maps ``line_types``, ``points``, ``lines`` (and ``bodies``, ``rods``,
    ``rod_types``) to their rows; ``options`` is ``[(name, value, line), ...]`` in file
    order; ``outputs`` the OUTPUTS words; ``sections`` the sections moorsolve does not
    model (ROD TYPES, RODS, FAILURE, CONTROL, EXTERNAL LOADS), verbatim with their column-name
    and units rows; ``header`` the front matter. ``version_reason`` says why the file was read
    as ``version``; ``notes`` list what was tolerated on the way (comments, unknown sections,
    count rows, ...), each with its line number.
    """

    path: str
    version: int
    header: list
    tables: dict
    options: list
    outputs: list
    sections: dict = field(default_factory=dict)
    section_lines: dict = field(default_factory=dict)
    version_reason: str = ""
    notes: list = field(default_factory=list)
    counts: dict = field(default_factory=dict)
    syrope_ic: list = field(default_factory=list)   # [(line, text)] of SYROPE IC's rows

    @property
    def name(self) -> str:
        return os.path.basename(self.path)

    def error(self, line, message: str) -> MoorDynError:
        """A :class:`MoorDynError` at ``line`` that also says how the version was chosen."""
        return MoorDynError(self.name, line, f"{message} (read as MoorDyn v{self.version}: "
                                             f"{self.version_reason})")


def _section_kind(text: str):
    upper = text.upper()
    for kind, names in SECTION_NAMES:
        if any(n in upper for n in names):
            return kind
    return None


def _is_comment(text: str) -> bool:
    stripped = text.lstrip()
    return stripped.startswith(("#", "!"))


def words(text: str) -> list:
    """The words of a row: white space (spaces, tabs) or commas separate them (Fortran's
    list-directed reading takes both); ``#`` or ``!`` ends the row."""
    cut = len(text)
    for mark in "#!":
        i = text.find(mark)
        if i >= 0:
            cut = min(cut, i)
    return text[:cut].replace(",", " ").split()


def _read_text(path: Path) -> str:
    name = path.name
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise MoorDynError(name, None, "MoorDyn file not found") from None
    except IsADirectoryError:
        raise MoorDynError(name, None, "is a directory, not a MoorDyn file") from None
    except OSError as exc:
        raise MoorDynError(name, None, f"cannot read the file: {exc}") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        # Files written on Windows tools are often Latin-1 (a degree sign or a "m³" in a units
        # row); every byte decodes, and MoorDyn reads bytes anyway.
        return data.decode("latin-1")


def read_moordyn(source) -> MoorDynFile:
    """Read a MoorDyn input file (v1 or v2) into its sections.

    Parameters
    ----------
    source : str or pathlib.Path
        The file.

    Raises
    ------
    MoorDynError
        Naming the file and line: unreadable file, a section MoorDyn-C reads only once given
        twice, a table without its column-name and units rows, missing LINE TYPES, POINTS or
        LINES, a LINES table whose column names and rows disagree on the version.
    """
    path = Path(source)
    return parse_moordyn_text(_read_text(path), str(path))


def parse_moordyn_text(text: str, path: str = "moordyn.dat") -> MoorDynFile:
    """:func:`read_moordyn` on text already read (``path`` names it in messages)."""
    name = os.path.basename(path)
    header, blocks, notes, unknown = [], {}, [], []
    current = None              # kind of the open section, "skip" for an unknown one
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.rstrip()
        if "---" in line:
            kind = _section_kind(line)
            if kind is None:
                if not blocks and current is None:
                    header.append(line)          # "---- MoorDyn Input File ----"
                    continue
                title = " ".join(re.sub(r"[^A-Za-z0-9 ]", " ", line).split())
                unknown.append([number, title, 0])
                current = "skip"
                continue
            if kind in blocks:
                first = blocks[kind]["line"]
                raise MoorDynError(name, number, f"a second {TITLES.get(kind, kind)} section "
                                                 f"(the first is at line {first}): MoorDyn-C "
                                                 "reads only the first, MoorDyn-F both; give "
                                                 "one")
            blocks[kind] = {"line": number, "title": line.strip(" -\t"), "lines": []}
            current = kind
            continue
        if current is None:
            header.append(line)
        elif current == "skip":
            if line.strip() and not _is_comment(line):
                unknown[-1][2] += 1
        else:
            blocks[current]["lines"].append((number, line))
    unknown = [(n, t) for n, t, skipped in unknown if skipped]
    for number, title in unknown:
        notes.append(f"line {number}: '---' line {title!r} names no section MoorDyn knows; "
                     "the rows after it, up to the next '---' line, are skipped, as MoorDyn "
                     "skips them")

    # MoorDyn requires no section (a file of rods alone runs); a static case needs lines,
    # and lines need their types.
    missing = [k for k in ("lines", "line_types") if k not in blocks]
    if missing:
        title = TITLES[missing[0]]
        if unknown:
            number, word = unknown[0]
            raise MoorDynError(name, number, f"unknown section {word!r}, and no {title} "
                                             f"section: MoorDyn skips sections it does not "
                                             f"know; name it '---------- {title} ----------'")
        why = (" (MoorDyn runs a file without lines, rods alone for instance, but a static "
               "case is held by its lines)" if missing[0] == "lines" else "")
        raise MoorDynError(name, None, f"missing section {title} (a header line such as "
                                       f"'---------- {title} ----------'){why}")

    tables, counts, sections = {}, {}, {}
    for kind in TABLE_SECTIONS:
        if kind in blocks:
            tables[kind], counts[kind] = _table(name, kind, blocks[kind], notes)
    for kind in ("rod_types", "rods", *VERBATIM_SECTIONS):
        if kind in blocks:
            title = TITLES.get(kind, kind).upper()
            sections[title] = [t for _, t in blocks[kind]["lines"]
                               if t.strip() and not _is_comment(t)]
    options = _options(blocks.get("options"), notes)
    outputs = _outputs(blocks.get("outputs"))
    version, reason = _version(name, blocks, tables, counts)
    md = MoorDynFile(path=path, version=version, header=header, tables=tables,
                     options=options, outputs=outputs, sections=sections,
                     section_lines={k: b["line"] for k, b in blocks.items()},
                     version_reason=reason, notes=notes, counts=counts,
                     syrope_ic=[(n, t) for n, t in blocks.get("syrope_ic", {}).get("lines", [])
                                if t.strip() and not _is_comment(t)])
    _check_counts(md)
    return md


def _numeric_share(values: list) -> int:
    return sum(number_token(v) is not None for v in values)


def _table(name: str, kind: str, block: dict, notes: list) -> tuple:
    """Rows of a table section and its count row (or None)."""
    lines = [(n, t) for n, t in block["lines"] if t.strip() and not _is_comment(t)]
    title = TITLES[kind]
    count = None
    if lines:
        first = words(lines[0][1])
        if (len(first) >= 2 and _INTEGER.match(first[0]) and _COUNT_WORD.match(first[1])):
            count = (int(first[0]), first[1], lines[0][0])
            notes.append(f"line {lines[0][0]}: count row '{first[0]} {first[1]}' (OpenFAST's "
                         "MoorDyn v1 layout)")
            lines = lines[1:]
    if len(lines) < 2:
        raise MoorDynError(name, block["line"], f"section {title} needs a column-name row and a "
                                                "units row before its rows")
    for (number, text), what in zip(lines[:2], ("column-name", "units")):
        values = words(text)
        if values and _numeric_share(values) >= max(2, len(values) // 2):
            raise MoorDynError(name, number, f"{title}: expected the {what} row here, found a "
                                             f"row of values ({text.strip()!r}); MoorDyn skips "
                                             "two rows after the section header, so this row "
                                             "would be lost: add the missing row(s)")
    rows = []
    for number, text in lines[2:]:
        values = words(text)
        if values:
            rows.append(Row(line=number, values=values))
    return rows, count


def _options(block, notes: list) -> list:
    options = []
    if block is None:
        return options
    for number, text in block["lines"]:
        if not text.strip() or _is_comment(text):
            continue
        values = words(text)
        if len(values) < 2:
            notes.append(f"line {number}: option row {text.strip()!r} has no name; skipped, "
                         "as MoorDyn-C skips it")
            continue
        options.append((values[1], values[0], number))
    return options


def _outputs(block) -> list:
    outputs = []
    if block is None:
        return outputs
    for _, text in block["lines"]:
        if _is_comment(text):
            continue
        if text.strip().upper() == "END":
            break
        if text.strip():
            outputs.append(text.strip())
    return outputs


# ---- the version --------------------------------------------------------------------------

_V1_LINE_NAMES = ("ANCH", "FAIR")
_V2_LINE_NAMES = ("ATTACHA", "ATTACHB", "ENDA", "ENDB", "CONNECTA", "CONNECTB", "POINTA",
                  "POINTB")
_ATTACH_WORD = re.compile(r"^(R|ROD|C|CON|P|POINT)\d+[ABab]?$", re.IGNORECASE)


def _is_float_word(token: str) -> bool:
    return number_token(token) is not None and not _INTEGER.match(token)


def _lines_layout(blocks: dict, tables: dict):
    """(version, reason) from the LINES column names and rows, or (None, None)."""
    names_votes = []
    lines = [(n, t) for n, t in blocks["lines"]["lines"] if t.strip() and not _is_comment(t)]
    first = words(lines[0][1]) if lines else []
    if len(first) >= 2 and _INTEGER.match(first[0]) and _COUNT_WORD.match(first[1]):
        lines = lines[1:]                            # OpenFAST v1 count row
    if lines:
        number, text = lines[0]
        upper = [w.upper() for w in words(text)]
        if any(k in w for w in upper for k in _V1_LINE_NAMES):
            names_votes.append((1, f"the LINES column names (line {number}) are v1's "
                                   "(NodeAnch, NodeFair)"))
        elif any(w in _V2_LINE_NAMES for w in upper):
            names_votes.append((2, f"the LINES column names (line {number}) are v2's "
                                   "(AttachA, AttachB)"))
        else:
            length = [i for i, w in enumerate(upper) if "LEN" in w]
            if length == [2]:
                names_votes.append((1, f"the LINES column names (line {number}) put UnstrLen "
                                       "third, as v1 does"))
            elif length == [4]:
                names_votes.append((2, f"the LINES column names (line {number}) put UnstrLen "
                                       "fifth, as v2 does"))
    row_votes = []
    for row in tables["lines"]:
        v = row.values
        if len(v) < 6:
            continue
        if _ATTACH_WORD.match(v[2]) or _ATTACH_WORD.match(v[3]):
            row_votes.append((2, f"the LINES row at line {row.line} names attachments "
                                 f"({v[2]}, {v[3]}) in columns 3 and 4, as v2 does"))
        elif _is_float_word(v[2]) and not _is_float_word(v[4]):
            row_votes.append((1, f"the LINES row at line {row.line} has a length ({v[2]}) "
                                 "in column 3, as v1 does"))
        elif _is_float_word(v[4]) and not _is_float_word(v[2]):
            row_votes.append((2, f"the LINES row at line {row.line} has a length ({v[4]}) "
                                 "in column 5, as v2 does"))
    return names_votes, row_votes


def _version(name: str, blocks: dict, tables: dict, counts: dict) -> tuple:
    names_votes, row_votes = _lines_layout(blocks, tables)
    rows = {v for v, _ in row_votes}
    if len(rows) > 1:
        r1 = next(r for v, r in row_votes if v == 1)
        r2 = next(r for v, r in row_votes if v == 2)
        raise MoorDynError(name, blocks["lines"]["line"], f"the LINES rows disagree on the "
                                                          f"format version: {r1}, but {r2}")
    if row_votes:
        version, reason = row_votes[0]
        if names_votes and names_votes[0][0] != version:
            # MoorDyn never reads the column names: the rows decide.
            names = names_votes[0][1].replace("the LINES column names", "its column names")
            reason += f" ({names}, but MoorDyn reads the columns by position)"
        return version, reason
    if names_votes:
        return names_votes[0]
    count_rows = [c for c in counts.values() if c is not None]
    if count_rows:
        return 1, (f"the count row '{count_rows[0][0]} {count_rows[0][1]}' (line "
                   f"{count_rows[0][2]}) is OpenFAST's MoorDyn v1 layout")
    for kind in ("bodies", "rods", "rod_types", "FAILURE", "CONTROL", "EXTERNAL LOADS"):
        if kind in blocks:
            return 2, (f"the {TITLES.get(kind, kind)} section (line {blocks[kind]['line']}) "
                       "exists only in v2")
    widths = {len(r.values) for r in tables["line_types"]}
    if widths and max(widths) == 9:
        row = tables["line_types"][0]
        return 1, (f"the LINE TYPES rows have 9 columns (line {row.line}), v1's Name Diam "
                   "MassDen EA BA/-zeta Can Cat Cdn Cdt")
    if widths & {10, 11, 13}:
        row = tables["line_types"][0]
        return 2, (f"the LINE TYPES rows have {len(row.values)} columns (line {row.line}), "
                   "as v2's")
    return 2, "nothing in the file tells the versions apart; v2, MoorDyn's current format"


def _check_counts(md: MoorDynFile) -> None:
    """OpenFAST v1 count rows must match the rows that follow (MoorDyn-F reads exactly that
    many)."""
    for kind, count in md.counts.items():
        if count is None:
            continue
        n, word, number = count
        found = len(md.tables[kind])
        if n != found:
            raise md.error(number, f"{word} is {n} but the {TITLES[kind]} section has {found} "
                                   "row(s); MoorDyn v1 reads exactly the given number")
