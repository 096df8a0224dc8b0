"""The cost of a mooring: every line and anchor priced from a cited basis.

Lines are priced per metre of unstretched length from their material
(:mod:`moorsolve.catalog.costs`: chain by mass, ropes by breaking load), anchors by their
mass (``checks.anchors``: a drag anchor's fluke weight, any design's ``mass``). The basis is
NREL's MoorPy 1.3 data (``MoorProps_default.yaml``, ``PointProps_default.yaml``; the anchor
rates averaged from the IEA Wind Task 49 design basis), in US dollars of 2024, material only.
A price per metre given by the caller replaces the basis for that line type.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from ..catalog import costs as basis
from ..errors import CaseError
from ..model import Case

__all__ = ["CostItem", "MooringCost", "mooring_cost", "cost"]


@dataclass(frozen=True)
class CostItem:
    """One priced item: a segment of a line or an anchor."""

    name: str           # ``L1`` or ``L1 segment 2`` or ``L1 anchor``
    kind: str           # line | anchor
    material: str       # the basis item (or ``given``)
    quantity: float     # length [m] or mass [kg]
    unit: str           # m | kg
    rate: float         # cost per unit [USD/m or USD/kg]
    cost: float         # [USD]
    source: str

    def to_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass(frozen=True)
class MooringCost:
    """The priced mooring: ``total = lines + anchors`` over ``items``.

    ``unpriced`` names what could not be priced (an anchor with no mass): the total leaves
    it out, and says so.
    """

    items: tuple
    currency: str = basis.CURRENCY
    unpriced: tuple = field(default_factory=tuple)

    @property
    def lines(self) -> float:
        return math.fsum(i.cost for i in self.items if i.kind == "line")

    @property
    def anchors(self) -> float:
        return math.fsum(i.cost for i in self.items if i.kind == "anchor")

    @property
    def total(self) -> float:
        return self.lines + self.anchors

    @property
    def complete(self) -> bool:
        return not self.unpriced

    def per_leg(self) -> dict:
        """Leg name -> its line and anchor cost."""
        out = {}
        for item in self.items:
            leg = item.name.split(" ")[0]
            out[leg] = out.get(leg, 0.0) + item.cost
        return out

    def to_dict(self) -> dict:
        return {"currency": self.currency, "total": self.total, "lines": self.lines,
                "anchors": self.anchors, "complete": self.complete,
                "unpriced": list(self.unpriced), "per_leg": self.per_leg(),
                "items": [i.to_dict() for i in self.items]}

    def __repr__(self) -> str:
        note = "" if self.complete else f", not priced: {', '.join(self.unpriced)}"
        return (f"<MooringCost {self.total:,.0f} {self.currency}: lines {self.lines:,.0f}, "
                f"anchors {self.anchors:,.0f}{note}>")


def mooring_cost(case: Case, *, materials: Mapping | None = None,
                 prices: Mapping | None = None) -> MooringCost:
    """Price every line and anchor of ``case``.

    Parameters
    ----------
    case : Case
    materials : mapping, optional
        Line type name -> basis material (``chain``, ``chain_studlink``, ``wire``,
        ``polyester``, ``nylon``, ``hmpe``); catalogue lines need none.
    prices : mapping, optional
        Line type name -> cost per metre [USD/m], replacing the basis.

    Returns
    -------
    MooringCost

    Raises
    ------
    CaseError
        A line type with no material nor price (field ``materials.NAME``), or an unknown
        material.
    """
    materials, prices = dict(materials or {}), dict(prices or {})
    env = case.environment
    per_type = {}
    for name in sorted({seg.line_type.name for leg in case.legs for seg in leg.segments}):
        lt = case.line_types[name]
        if name in prices:
            value = float(prices[name])
            if not (math.isfinite(value) and value >= 0):
                raise CaseError(f"prices.{name}", f"{prices[name]!r} must be a cost per metre "
                                                  ">= 0")
            per_type[name] = ("given", value, "price given by the caller")
            continue
        try:
            price = basis.line_price(lt, materials.get(name), gravity=env.gravity,
                                     water_density=env.water_density)
        except (KeyError, ValueError) as exc:
            raise CaseError(f"materials.{name}", str(exc).strip("'\"")) from None
        per_type[name] = (price.material, price.cost_per_length, price.basis)
    items, unpriced = [], []
    checks = case.checks
    for leg in case.legs:
        many = len(leg.segments) > 1
        for k, seg in enumerate(leg.segments):
            material, rate, source = per_type[seg.line_type.name]
            items.append(CostItem(name=f"{leg.name} segment {k + 1}" if many else leg.name,
                                  kind="line", material=material, quantity=seg.length,
                                  unit="m", rate=rate, cost=rate * seg.length, source=source))
        if not leg.a.on_seabed:
            continue
        kind = (leg.anchor_type or (checks.anchor if checks else None))
        kind = "drag" if kind is None else kind.kind
        design = None if checks is None else checks.anchor_design(kind)
        if design is None or design.mass is None:
            unpriced.append(f"{leg.name} anchor ({kind}: give checks.anchors.{kind}.mass)")
            continue
        rate = basis.cost_rates()[kind]
        items.append(CostItem(name=f"{leg.name} anchor", kind="anchor", material=kind,
                              quantity=design.mass, unit="kg", rate=rate.per_kg,
                              cost=rate.anchor_cost(design.mass), source=rate.source))
    return MooringCost(items=tuple(items), unpriced=tuple(unpriced))


def cost(case, **options) -> MooringCost:
    """``moorsolve.cost(case)``: :func:`mooring_cost` of a Case (or a case-file dict)."""
    if isinstance(case, Mapping):
        from ..io.case_file import load_case
        case = load_case(case)
    return mooring_cost(case, **options)
