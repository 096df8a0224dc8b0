"""The cost basis of mooring components (``costs.csv``), in US dollars of 2024.

A line costs ``per_kg * mass + per_N_m * MBL`` per metre (chain by its mass, ropes by their
breaking load); an anchor ``per_kg * mass``. The figures are those of NREL's MoorPy 1.3 data
files (``MoorProps_default.yaml`` for lines, ``PointProps_default.yaml`` for anchors, the
anchor figures averaged from the IEA Wind Task 49 design basis; Davies, Baca & Hall,
"An updated mooring cost modeling tool set", OMAE2025-156384). Material cost only: the
sources give installation and decommissioning no per-item figure.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from ._table import read_rows

__all__ = ["CostRate", "cost_rates", "line_materials", "anchor_kinds", "CURRENCY"]

#: The currency of the basis.
CURRENCY = "USD"


@dataclass(frozen=True)
class CostRate:
    """One row of ``costs.csv``."""

    item: str
    kind: str          # line | anchor
    per_kg: float      # [USD/kg]
    per_N_m: float     # [USD per N of MBL per m of line]
    source: str
    verified: str

    def line_cost_per_length(self, mass_per_length: float, mbl: float | None) -> float:
        """Cost of one metre [USD/m] of a line of ``mass_per_length`` [kg/m] and ``mbl`` [N].

        Raises
        ------
        ValueError
            The rate needs the MBL and none was given.
        """
        if self.per_N_m and mbl is None:
            raise ValueError(f"{self.item} is priced by its breaking load: it needs an MBL")
        return self.per_kg * mass_per_length + self.per_N_m * (mbl or 0.0)

    def anchor_cost(self, mass: float) -> float:
        """Cost [USD] of an anchor of ``mass`` [kg]."""
        return self.per_kg * mass


@lru_cache(maxsize=1)
def cost_rates() -> dict:
    """``item -> CostRate`` for every row of ``costs.csv``."""
    return {r["item"]: CostRate(item=r["item"], kind=r["kind"], per_kg=float(r["per_kg"]),
                                per_N_m=float(r["per_N_m"]), source=r["source"],
                                verified=r["verified"]) for r in read_rows("costs.csv")}


def line_materials() -> tuple:
    """The line materials the basis prices."""
    return tuple(k for k, r in cost_rates().items() if r.kind == "line")


def anchor_kinds() -> tuple:
    """The anchor kinds the basis prices."""
    return tuple(k for k, r in cost_rates().items() if r.kind == "anchor")
