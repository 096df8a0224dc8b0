"""The line catalogue: chain, wire rope and fibre rope properties from a nominal diameter.

The coefficients live in ``lines.csv`` beside this module, one row per entry with the
published source of each formula. Formulas (``d`` nominal diameter in mm):

chain (studless and studlink; offshore grades R3-R5, ship grades U2, U3)::

    MBL [kN]    = c d^2 (44 - 0.08 d)         DNV-OS-E302 (R grades), IACS UR W18 (U grades)
    mass [kg/m] = m d^2                        0.0199 studless, 0.0219 studlink
    EA [kN]     = e d^2                        85.4 studless, 101.0 studlink (OrcaFlex wizard)

rope (steel wire, polyester, nylon, polypropylene; static stiffness)::

    MBL [kN] = c d^2,  mass [kg/m] = m d^2,  EA [kN] = e d^2

fibre (mooring ropes of polyester, nylon, HMPE with quasi-static and dynamic stiffness;
NREL's MoorPy property library, fits to manufacturer catalogues)::

    MBL [kN] = c d^2 + c3 d^3,  mass [kg/m] = m d^2
    EA_static = Krs MBL                        quasi-static: the lower bound
    EA_dynamic = (Krd_alpha + Krd_beta L_m) MBL   L_m the mean load in % of MBL: the upper

A fibre-rope entry gives its line type both stiffnesses as ``stiffness_bounds`` for the
bound analysis offshore standards ask for fibre ropes (``moorsolve bounds``); its ``ea`` is
the quasi-static one. The ``fibre`` column marks fibre ropes (the old ``rope`` entries of
polyester, nylon and polypropylene too).

The submerged weight follows from the mass, the material density and the case's water
density and gravity: ``w = mass g (1 - rho_water / rho_material)``.

A corrosion and wear allowance reduces the diameter used for the breaking load only
(``MBL(d - allowance)``); mass, weight and stiffness stay at the nominal diameter, the
usual practice for strength checks of a corroded line (DNV-OS-E301 Ch.2 Sec.2: the
strength check uses the corroded diameter).

Hu & Tang (2004, section 3) check their AM2 (grade U2) 48 mm chain with a
breaking load of 1270 kN: ``0.01373 * 48^2 * (44 - 0.08*48) = 1270.4 kN``, which confirms
the IACS grade-2 coefficient.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from typing import Optional

from ..constants import SEAWATER_DENSITY, STANDARD_GRAVITY

__all__ = ["CatalogEntry", "LineProperties", "entries", "line_properties"]


@dataclass(frozen=True)
class CatalogEntry:
    """One row of ``lines.csv``; coefficients for ``d`` in mm (see the module docstring)."""

    name: str
    family: str
    description: str
    mbl_coeff: float
    mass_coeff: float
    ea_coeff: Optional[float]
    material_density: float
    hydro_factor: float
    mbl_source: str
    mass_ea_source: str
    fibre: bool = False
    mbl_coeff3: float = 0.0
    krs: Optional[float] = None
    krd_alpha: Optional[float] = None
    krd_beta: Optional[float] = None
    stiffness_source: str = ""

    def mbl_N(self, diameter_m: float) -> float:
        """Minimum breaking load [N] at ``diameter_m`` [m]."""
        d = diameter_m * 1e3
        if self.family == "chain":
            return self.mbl_coeff * d**2 * (44.0 - 0.08 * d) * 1e3
        return (self.mbl_coeff * d**2 + self.mbl_coeff3 * d**3) * 1e3

    def mass_per_length(self, diameter_m: float) -> float:
        """Mass in air per length [kg/m]."""
        return self.mass_coeff * (diameter_m * 1e3) ** 2

    def ea_N(self, diameter_m: float) -> float:
        """Axial (static, for fibre ropes quasi-static) stiffness [N]."""
        if self.krs is not None:
            return self.krs * self.mbl_N(diameter_m)
        return self.ea_coeff * (diameter_m * 1e3) ** 2 * 1e3

    def dynamic_ea_N(self, diameter_m: float, mean_load: float) -> Optional[float]:
        """Dynamic stiffness [N] at mean load ``mean_load`` [N] (fibre ropes; else None)."""
        if self.krd_alpha is None:
            return None
        mbl = self.mbl_N(diameter_m)
        return (self.krd_alpha + self.krd_beta * 100.0 * mean_load / mbl) * mbl


@dataclass(frozen=True)
class LineProperties:
    """A catalogue line at one diameter, in SI units.

    Attributes
    ----------
    entry : CatalogEntry
    diameter : float
        Nominal diameter [m].
    corrosion_allowance : float
        Diameter reduction [m] applied to the breaking load.
    mass_per_length : float
        Mass in air [kg/m] at the nominal diameter.
    weight_in_water : float
        Submerged weight [N/m] (negative for a buoyant rope).
    ea : float
        Axial stiffness [N].
    mbl : float
        Minimum breaking load [N] at ``diameter - corrosion_allowance``.
    hydrodynamic_diameter : float
        Outer diameter for drag [m].
    """

    entry: CatalogEntry
    diameter: float
    corrosion_allowance: float
    mass_per_length: float
    weight_in_water: float
    ea: float
    mbl: float
    hydrodynamic_diameter: float

    @property
    def fibre(self) -> bool:
        return self.entry.fibre

    @property
    def dynamic_stiffness(self) -> Optional[tuple]:
        """``(alpha, beta)`` of the dynamic stiffness ``(alpha + beta L_m) MBL`` [-, per %
        MBL], or None; ``MBL`` is the nominal one (``entry.mbl_N(diameter)``)."""
        e = self.entry
        return None if e.krd_alpha is None else (e.krd_alpha, e.krd_beta)

    @property
    def nominal_mbl(self) -> float:
        """MBL [N] at the nominal diameter (the stiffness coefficients' reference)."""
        return self.entry.mbl_N(self.diameter)

    @property
    def source(self) -> str:
        text = f"MBL: {self.entry.mbl_source}; mass and EA: {self.entry.mass_ea_source}"
        if self.entry.stiffness_source:
            text += f"; stiffness: {self.entry.stiffness_source}"
        return text


def _number(row: dict, key: str, line: int) -> float:
    try:
        return float(row[key])
    except (TypeError, ValueError):
        raise ValueError(f"lines.csv line {line}: {key} = {row[key]!r} is not a number") from None


def _optional(row: dict, key: str, line: int) -> Optional[float]:
    return None if not row.get(key) else _number(row, key, line)


@lru_cache(maxsize=1)
def entries() -> dict:
    """All catalogue entries by name (read once from ``lines.csv``)."""
    text = resources.files(__package__).joinpath("lines.csv").read_text(encoding="utf-8")
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    out = {}
    for i, row in enumerate(csv.DictReader(io.StringIO(body)), start=2):
        out[row["name"]] = CatalogEntry(
            name=row["name"], family=row["family"], description=row["description"],
            mbl_coeff=_number(row, "mbl_coeff", i), mass_coeff=_number(row, "mass_coeff", i),
            ea_coeff=_optional(row, "ea_coeff", i),
            material_density=_number(row, "material_density", i),
            hydro_factor=_number(row, "hydro_factor", i),
            mbl_source=row["mbl_source"], mass_ea_source=row["mass_ea_source"],
            fibre=row["fibre"] == "1", mbl_coeff3=_optional(row, "mbl_coeff3", i) or 0.0,
            krs=_optional(row, "krs", i), krd_alpha=_optional(row, "krd_alpha", i),
            krd_beta=_optional(row, "krd_beta", i), stiffness_source=row["stiffness_source"])
    return out


def line_properties(name: str, diameter: float, *, water_density: float = SEAWATER_DENSITY,
                    gravity: float = STANDARD_GRAVITY,
                    corrosion_allowance: float = 0.0) -> LineProperties:
    """Properties of catalogue line ``name`` at nominal ``diameter`` [m].

    Parameters
    ----------
    name : str
        A catalogue entry, e.g. ``"studless_r3"`` (see :func:`entries`).
    diameter : float
        Nominal diameter [m] (chain: bar diameter of the link).
    water_density : float
        [kg/m^3], for the submerged weight.
    gravity : float
        [m/s^2].
    corrosion_allowance : float
        Diameter reduction [m] for the breaking load; must be smaller than ``diameter``.

    Raises
    ------
    KeyError
        Unknown entry.
    ValueError
        A non-positive diameter or an allowance that consumes it.
    """
    entry = entries()[name]
    if not diameter > 0:
        raise ValueError(f"diameter {diameter} m must be > 0")
    if not 0 <= corrosion_allowance < diameter:
        raise ValueError(f"corrosion allowance {corrosion_allowance} m must be >= 0 and "
                         f"smaller than the diameter {diameter} m")
    mass = entry.mass_per_length(diameter)
    weight = mass * gravity * (1.0 - water_density / entry.material_density)
    return LineProperties(entry=entry, diameter=diameter,
                          corrosion_allowance=corrosion_allowance, mass_per_length=mass,
                          weight_in_water=weight, ea=entry.ea_N(diameter),
                          mbl=entry.mbl_N(diameter - corrosion_allowance),
                          hydrodynamic_diameter=entry.hydro_factor * diameter)
