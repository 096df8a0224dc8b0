"""Berth checks: hawsers against the working load limit industry guidance sets for
ships' mooring lines, fenders against their rated deflection, pile guides against the top of
their pile. The criteria are data (``berth_criteria.csv``) with their sources.

A hawser (a line whose type weighs nothing in water) is checked against OCIMF MEG4's working
load limit: 55 % of the MBL for a steel wire rope (a catalogue ``wire_*`` line type), 50 % for
every other line, MEG4's value for synthetic cordage, and the lower of the two where the
material is not known. The line type's ``mbl`` stands for MEG4's ship design MBL.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from ..model import LineType


@dataclass(frozen=True)
class BerthCriterion:
    """One row of ``berth_criteria.csv``."""

    element: str
    rule: str
    material: str
    limit: float
    source: str
    verified: str


@lru_cache(maxsize=1)
def berth_criteria() -> tuple:
    """Every row of ``berth_criteria.csv``."""
    text = resources.files(__package__).joinpath("berth_criteria.csv").read_text(
        encoding="utf-8")
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    return tuple(BerthCriterion(element=r["element"], rule=r["rule"], material=r["material"],
                                limit=float(r["limit"]), source=r["source"],
                                verified=r["verified"])
                 for r in csv.DictReader(io.StringIO(body)))


def _row(element: str, material: str = "") -> BerthCriterion:
    return next(r for r in berth_criteria() if r.element == element and r.material == material)


def hawser_material(line_type: LineType) -> str:
    """``steel_wire`` for a catalogue wire rope, else ``synthetic`` (MEG4's lower limit)."""
    return "steel_wire" if (line_type.catalog or "").startswith("wire") else "synthetic"


def hawser_criterion(line_type: LineType) -> BerthCriterion:
    """The working load limit row for a hawser of ``line_type``."""
    return _row("hawser", hawser_material(line_type))


def fender_criterion() -> BerthCriterion:
    return _row("fender")


def guide_criterion() -> BerthCriterion:
    return _row("guide")


def is_hawser(line) -> bool:
    """A hawser: a one-segment line whose type weighs nothing in water."""
    return not line.multi_segment and line.line_type.weight_in_water == 0


__all__ = ["BerthCriterion", "berth_criteria", "hawser_criterion", "fender_criterion",
           "guide_criterion", "hawser_material", "is_hawser"]
