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


#: Catalogue entry -> the basis item that prices it (entries not here: give a price).
CATALOG_MATERIAL = {
    "studless_r3": "chain", "studless_r3s": "chain", "studless_r4": "chain",
    "studless_r4s": "chain", "studless_r5": "chain", "studless_u2": "chain",
    "studless_u3": "chain", "studlink_r3": "chain_studlink", "studlink_r3s": "chain_studlink",
    "studlink_r4": "chain_studlink", "studlink_r4s": "chain_studlink",
    "studlink_r5": "chain_studlink", "studlink_u2": "chain_studlink",
    "studlink_u3": "chain_studlink", "wire_fibre_core": "wire", "wire_iwrc": "wire",
    "polyester": "polyester", "fibre_polyester": "polyester", "nylon": "nylon",
    "fibre_nylon": "nylon", "fibre_hmpe": "hmpe",
}
#: Steel's density [kg/m^3]: a chain's mass from its submerged weight when nothing else
#: gives it (MoorPy's chain library assumes the same).
STEEL_DENSITY = 7850.0


@dataclass(frozen=True)
class LinePrice:
    """One line type priced from the basis."""

    material: str
    mass_per_length: float | None   # [kg/m]; None where unknown and not needed
    mbl: float | None           # [N]
    cost_per_length: float      # [USD/m]
    basis: str                  # how the mass was had, and the rate's source


def line_price(line_type, material: str | None = None, *, gravity: float,
               water_density: float) -> LinePrice:
    """Price one metre of ``line_type`` (a :class:`moorsolve.model.LineType`).

    ``material`` (an item of the basis) defaults to the catalogue entry's. The mass per
    length is the catalogue's, else the weight in air over ``gravity``, else (a chain) the
    submerged weight of steel.

    Raises
    ------
    KeyError
        No material is known for the line type, or the basis has no such item; the message
        says what to give.
    ValueError
        The material is priced by its MBL and the line type has none.
    """
    from . import entries   # the line catalogue (this package)

    if material is None:
        material = CATALOG_MATERIAL.get(line_type.catalog or "")
        if material is None:
            raise KeyError(f"line type {line_type.name!r}: give its material (one of "
                           f"{', '.join(line_materials())}) or a price per metre")
    rate = cost_rates().get(material)
    if rate is None or rate.kind != "line":
        raise KeyError(f"unknown line material {material!r}; the basis prices "
                       f"{', '.join(line_materials())}")
    if line_type.catalog is not None and line_type.diameter is not None:
        mass = entries()[line_type.catalog].mass_per_length(line_type.diameter)
        how = f"catalogue {line_type.catalog} mass"
    elif getattr(line_type, "weight_in_air", None):
        mass = line_type.weight_in_air / gravity
        how = "weight in air / g"
    elif rate.per_kg:
        mass = line_type.weight_in_water / (gravity * (1.0 - water_density / STEEL_DENSITY))
        how = f"submerged weight as steel ({STEEL_DENSITY:g} kg/m^3)"
    else:
        mass, how = None, "priced by its MBL"
    cost = rate.line_cost_per_length(mass or 0.0, line_type.mbl)
    return LinePrice(material=material, mass_per_length=mass, mbl=line_type.mbl,
                     cost_per_length=cost, basis=f"{how}; {rate.source}")
