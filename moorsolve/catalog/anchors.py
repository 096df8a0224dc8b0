"""Drag anchor holding-capacity curves: the maker's charts as ``UHC = a W^b``.

``UHC`` [kN] is the ultimate holding capacity (the load at which the anchor drags), ``W`` the
anchor's mass [t]. The coefficients live in ``anchors.csv`` beside this module, one row per
anchor design and soil, with their source and how they were checked. The shipped curves are
Vryhof's Stevpris Mk6 charts as NREL's MoorPy 1.3 fits them (``MoorProps.getAnchorMass``):
soft clay ``509.96 W^0.93``, medium clay ``701.49 W^0.93``, hard clay and sand
``904.21 W^0.92``. A 10 t Stevpris Mk6 in soft clay holds about 4.3 MN.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from ._table import read_rows

__all__ = ["DragCurve", "drag_curves", "drag_curve", "DEFAULT_DESIGN"]

#: The anchor design used when a case names only the soil.
DEFAULT_DESIGN = "stevpris_mk6"


@dataclass(frozen=True)
class DragCurve:
    """One row of ``anchors.csv``: ``UHC [kN] = a_kN * (mass [t])^b``."""

    design: str
    soil: str
    a_kN: float
    b: float
    source: str
    verified: str

    def capacity_N(self, mass_kg: float) -> float:
        """Ultimate holding capacity [N] of an anchor of ``mass_kg`` [kg]."""
        return 1e3 * self.a_kN * (mass_kg / 1e3) ** self.b

    def mass_kg(self, capacity_N: float) -> float:
        """The anchor mass [kg] whose holding capacity is ``capacity_N`` [N]."""
        return 1e3 * (capacity_N / 1e3 / self.a_kN) ** (1.0 / self.b)


@lru_cache(maxsize=1)
def drag_curves() -> dict:
    """``(design, soil) -> DragCurve`` for every row of ``anchors.csv``."""
    return {(r["design"], r["soil"]): DragCurve(
        design=r["design"], soil=r["soil"], a_kN=float(r["a_kN"]), b=float(r["b"]),
        source=r["source"], verified=r["verified"]) for r in read_rows("anchors.csv")}


def drag_curve(soil: str, design: str = DEFAULT_DESIGN) -> DragCurve:
    """The curve of ``design`` in ``soil``; KeyError when the table has none."""
    return drag_curves()[(design, soil)]
