"""The line-tension criteria of each standard, read from ``criteria.csv`` (data with citations).

A line passes when ``factor * T <= capacity_factor * MBL`` (DNV with a dynamic part:
``factor T_mean + gamma_dyn T_dyn <= capacity_factor MBL``). API RP 2SK's ``dynamic`` rows
apply where the check runs the lines' dynamics (:mod:`.dynamic`), the ``quasi-static`` rows
otherwise; DNV's factors do not depend on the method.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

#: Standards with a criteria table, as accepted by ``checks.standard`` and ``--standard``.
#: The analysis type of a check without line dynamics.
ANALYSIS = "quasi-static"


@dataclass(frozen=True)
class Criterion:
    """One row of the criteria table.

    Attributes
    ----------
    standard, condition, analysis : str
    consequence_class : int or None
        DNV consequence class; None where the standard has none.
    factor : float
        Factor on the line tension (API: the safety factor; DNV: gamma_mean).
    gamma_dyn : float or None
        DNV factor on the dynamic tension (zero dynamic tension in a quasi-static check).
    capacity_factor : float
        Fraction of the MBL available (DNV: 0.95).
    source, verified : str
    """

    standard: str
    condition: str
    analysis: str
    consequence_class: int | None
    factor: float
    gamma_dyn: float | None
    capacity_factor: float
    source: str
    verified: str

    @property
    def required_safety_factor(self) -> float:
        """The least MBL / tension that passes."""
        return self.factor / self.capacity_factor

    def describe(self, dynamic: bool = False) -> str:
        """The criterion in one line; ``dynamic``: with DNV's factor on the dynamic
        tension."""
        if self.standard == "api-rp-2sk":
            method = "" if self.analysis == "quasi-static" else f" ({self.analysis})"
            return f"{self.standard} {self.condition}{method}: MBL/T >= {self.factor:.2f}"
        dyn = f" + {self.gamma_dyn:.2f} T_dyn" if dynamic and self.gamma_dyn else ""
        return (f"{self.standard} CC{self.consequence_class} "
                f"{'ULS' if self.condition == 'intact' else 'ALS'}: {self.factor:.2f} T_mean"
                f"{dyn} <= {self.capacity_factor:.2f} MBL")


@lru_cache(maxsize=1)
def criteria_table() -> tuple:
    """Every row of ``criteria.csv`` as :class:`Criterion`."""
    text = resources.files(__package__).joinpath("criteria.csv").read_text(encoding="utf-8")
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    rows = []
    for row in csv.DictReader(io.StringIO(body)):
        rows.append(Criterion(
            standard=row["standard"], condition=row["condition"], analysis=row["analysis"],
            consequence_class=int(row["consequence_class"]) if row["consequence_class"] else None,
            factor=float(row["factor"]),
            gamma_dyn=float(row["gamma_dyn"]) if row["gamma_dyn"] else None,
            capacity_factor=float(row["capacity_factor"]), source=row["source"],
            verified=row["verified"]))
    return tuple(rows)


def criterion(standard: str, condition: str, consequence_class: int = 1,
              analysis: str = ANALYSIS) -> Criterion:
    """The criterion for ``standard`` in ``condition`` (``intact`` or ``damaged``).

    Raises
    ------
    KeyError
        No such row in the table.
    """
    for row in criteria_table():
        if (row.standard == standard and row.condition == condition
                and row.analysis == analysis
                and row.consequence_class in (None, consequence_class)):
            return row
    raise KeyError(f"no {analysis} criterion for {standard} {condition} "
                   f"(consequence class {consequence_class})")


def standard_rows(standard: str) -> list:
    """All rows of one standard (for printing the criteria in a report)."""
    return [row for row in criteria_table() if row.standard == standard]
