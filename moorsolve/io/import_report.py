"""What an import read, converted and ignored: one list per kind, printed by the import
commands and kept as a comment at the top of the written case file."""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["ImportReport"]


@dataclass
class ImportReport:
    """Three lists of one-line entries, in file order.

    ``read``: what the file holds (sections, counts, the format version and why);
    ``converted``: what became which part of the case, with the figures computed on the way
    (weights in water, defaults applied, the chosen case form); ``ignored``: what has no
    static meaning or no place in a case, and why (dynamic coefficients, output channels,
    line failures), each naming its line numbers or columns.
    """

    source: str
    read: list = field(default_factory=list)
    converted: list = field(default_factory=list)
    ignored: list = field(default_factory=list)

    def lines(self) -> list:
        """The report as text lines (headings and indented entries)."""
        out = [f"{self.source}:"]
        for title, entries in (("read", self.read), ("converted", self.converted),
                               ("ignored", self.ignored)):
            out.append(f"  {title}:")
            out += [f"    - {e}" for e in entries] if entries else ["    (nothing)"]
        return out

    def text(self) -> str:
        return "\n".join(self.lines()) + "\n"
