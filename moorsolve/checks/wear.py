"""Corrosion and creep laws: what a line is at the end of its design life.

Steel (chain, wire) loses diameter at a rate per year; ``c = rate x design_life`` is the
loss at the end of life and ``d_eol = d - c`` the remaining diameter. The steel area goes
with the diameter squared, so the mass, the weight in and out of water and the axial
stiffness scale with ``((d - c)/d)^2``. The breaking load:

* a catalogue line: the catalogue's own formula at ``d - c`` (chain: DNV-OS-E302's
  ``c d^2 (44 - 0.08 d)``, so the ratio is not exactly the square);
* a line type given by its MBL: ``MBL ((d - c)/d)^2``, FAModel's law
  (``Mooring.addCorrosion``).

The fatigue diameter is the nominal one less half the loss over the life
(:func:`fatigue_diameter`): fatigue damage accrues over the whole life, at a diameter
between new and end of life; the CMOE-TUDelft open book on floating structures (mooring
concept design) takes the corrosion allowance 50 % corroded for fatigue.

Fibre ropes creep: a permanent strain ``rate x design_life`` lengthens each segment,
``L_eol = L (1 + rate x life)`` (FAModel's ``Mooring.addCreep``); the rope keeps its mass,
so its weight per unstretched length falls by the same factor; MBL and stiffness stay.

Every law with its source and verification status: ``wear_sources.csv`` beside this
module (:func:`sources`).
"""

from __future__ import annotations

import csv
import dataclasses
import io
from functools import lru_cache
from importlib import resources

from .. import catalog as line_catalog
from ..model.lines import LineType

__all__ = ["corroded_diameter", "area_ratio", "corroded_mbl", "fatigue_diameter",
           "segment_fatigue_diameter", "creep_factor", "corroded_line_type",
           "crept_line_type", "sources"]


def corroded_diameter(diameter: float, rate: float, years: float) -> float:
    """Remaining diameter [m] after ``years`` at ``rate`` [m per year] of diameter loss.

    Raises ValueError when the loss consumes the diameter.
    """
    remaining = diameter - rate * years
    if not remaining > 0:
        raise ValueError(f"a loss of {rate * 1e3:g} mm/y over {years:g} y "
                         f"({rate * years * 1e3:g} mm) consumes the {diameter * 1e3:g} mm "
                         "diameter")
    return remaining


def area_ratio(diameter: float, remaining: float) -> float:
    """Steel area left: ``(remaining / diameter)^2`` [-]."""
    return (remaining / diameter) ** 2


def corroded_mbl(line_type: LineType, remaining: float) -> float | None:
    """The breaking load [N] at diameter ``remaining`` [m]: the catalogue formula for a
    catalogue line (from its nominal diameter, any corrosion allowance replaced by the
    actual loss), else ``MBL (remaining / diameter)^2``; None without an MBL."""
    if line_type.catalog is not None:
        return line_catalog.entries()[line_type.catalog].mbl_N(remaining)
    if line_type.mbl is None:
        return None
    return line_type.mbl * area_ratio(line_type.diameter, remaining)


def nominal_mbl(line_type: LineType) -> float | None:
    """The breaking load [N] of the new line (a catalogue line without its allowance)."""
    if line_type.catalog is not None:
        return line_catalog.entries()[line_type.catalog].mbl_N(line_type.diameter)
    return line_type.mbl


def fatigue_diameter(diameter: float, rate: float, design_life: float) -> float:
    """The diameter [m] for a fatigue analysis over the design life.

    Parameters
    ----------
    diameter : float
        Nominal diameter [m].
    rate : float
        Diameter loss [m per year].
    design_life : float
        [years].

    Returns
    -------
    float
        ``diameter - rate design_life / 2``: half the loss over the life.

    Notes
    -----
    Fatigue damage accrues over the whole life; the CMOE-TUDelft open book (Floating and
    Submerged Structures, mooring concept design) assumes the corrosion allowance 50 %
    corroded for fatigue. For chain the nominal stress area is then
    ``2 pi d_f^2 / 4``.
    """
    return corroded_diameter(diameter, 0.5 * rate, design_life)


def segment_fatigue_diameter(case, line: str, segment: int) -> float | None:
    """The fatigue diameter [m] of segment ``segment`` (from end A) of line ``line`` under
    the case's ``checks.corrosion`` and ``checks.design_life`` (:func:`fatigue_diameter`).

    The nominal diameter where no corrosion applies; None for a line type without a
    diameter. With rates by zone the largest is taken: a line's fatigue is worst at its
    ends (the fairlead in the splash zone, the touchdown on the bottom), so the smallest
    diameter is the safe one. Raises KeyError for an unknown line, IndexError for a
    segment it does not have.
    """
    found = {x.name: x for x in case.lines}[line]
    lt = found.segments[segment].line_type
    if lt.diameter is None:
        return None
    wear = None if case.checks is None else case.checks.wear
    rates = (None if wear is None or wear.corrosion is None
             else wear.corrosion.rates_for(line, segment, lt))
    if rates is None:
        return lt.diameter
    return fatigue_diameter(lt.diameter, max(rates.splash, rates.catenary, rates.bottom),
                            wear.design_life)


def creep_factor(rate: float, design_life: float) -> float:
    """Length at end of life over new unstretched length: ``1 + rate design_life``."""
    return 1.0 + rate * design_life


def corroded_line_type(line_type: LineType, rate: float, design_life: float,
                       name: str) -> LineType:
    """``line_type`` after ``design_life`` years of diameter loss at ``rate`` [m/y].

    Weights and ``ea`` scale with the steel area, the MBL as :func:`corroded_mbl`, the
    diameter (drag, wall tension) with the remaining diameter; any corrosion allowance is
    replaced by the actual loss. A stretch law other than Hooke's is kept (steel lines
    use ``ea``).
    """
    d = line_type.diameter
    remaining = corroded_diameter(d, rate, design_life)
    ratio = area_ratio(d, remaining)
    return dataclasses.replace(
        line_type, name=name, diameter=remaining,
        weight_in_water=line_type.weight_in_water * ratio,
        weight_in_air=(None if line_type.weight_in_air is None
                       else line_type.weight_in_air * ratio),
        ea=None if line_type.ea is None else line_type.ea * ratio,
        mbl=corroded_mbl(line_type, remaining), corrosion_allowance=0.0)


def crept_line_type(line_type: LineType, factor: float, name: str) -> LineType:
    """``line_type`` lengthened by ``factor`` (:func:`creep_factor`): the same mass over
    the longer length."""
    return dataclasses.replace(
        line_type, name=name, weight_in_water=line_type.weight_in_water / factor,
        weight_in_air=(None if line_type.weight_in_air is None
                       else line_type.weight_in_air / factor))


@lru_cache(maxsize=1)
def _source_rows() -> tuple:
    text = resources.files(__package__).joinpath("wear_sources.csv").read_text("utf-8")
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    return tuple(tuple(row.items()) for row in csv.DictReader(io.StringIO(body)))


def sources() -> tuple:
    """The laws and constants used here with their sources (rows of ``wear_sources.csv``:
    ``name``, ``law_or_value``, ``source``, ``status``), fresh dicts on every call."""
    return tuple(dict(row) for row in _source_rows())
