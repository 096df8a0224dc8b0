"""Anchor designs for the capacity checks and the cost: what holds each kind of anchor.

``checks.anchors`` gives one design per anchor kind (``drag``, ``suction``, ``pile``,
``deadweight``); each leg uses the design of its anchor's kind (its ``anchor_type``, or
``checks.anchor``). A design may say how deep the padeye sits in the soil (``embedment``):
the line then runs from the mudline, where the catenary meets the seabed, down through
the soil to the padeye, and the checks carry its tension and angle down there
(:mod:`moorsolve.checks.padeye`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

__all__ = ["Embedment", "AnchorDesign", "SOILS"]

#: Soil names a drag anchor's holding-capacity curves are given for.
SOILS = ("soft_clay", "medium_clay", "hard_clay", "sand")


@dataclass(frozen=True)
class Embedment:
    """The embedded part of a line, mudline to padeye, in clay.

    Attributes
    ----------
    padeye_depth : float
        Depth of the padeye below the mudline ``z_a`` [m].
    su0 : float
        Undrained shear strength at the mudline [Pa].
    su_gradient : float
        Its increase with depth ``k`` [Pa/m].
    line_diameter : float or None
        Nominal diameter of the line in the soil [m] (None: the line type's, which must
        then be a catalogue line).
    bearing_factor : float
        ``N_c``, the bearing capacity factor of the line in the soil.
    bearing_width : float
        ``A_b``, the effective bearing width over the nominal diameter (2.5 for chain).
    friction : float
        ``mu``, the ratio of the friction along the line to the normal soil resistance.
    """

    padeye_depth: float
    su0: float
    su_gradient: float
    line_diameter: Optional[float] = None
    bearing_factor: float = 8.5
    bearing_width: float = 2.5
    friction: float = 0.4


@dataclass(frozen=True)
class AnchorDesign:
    """One anchor design: its capacity, its mass (for the cost) and its embedment.

    Attributes
    ----------
    kind : str
        ``drag``, ``suction``, ``pile`` or ``deadweight``.
    capacity : float or None
        Drag anchor: ultimate holding capacity [N] (given, or from the maker's curve).
    soil, design : str or None
        Drag anchor given by its mass: the soil and the anchor design of the curve.
    h_max, v_max : float or None
        Suction anchor, pile: horizontal and vertical capacity at the padeye [N].
    length, diameter : float or None
        Suction anchor: skirt length and diameter [m] (the H-V envelope's exponents).
    mass : float or None
        Mass of the anchor [kg] (the drag anchor's fluke weight; for the cost).
    embedment : Embedment or None
        The padeye's depth and the soil above it; None: the padeye is at the mudline.
    capacity_source : str
        Where the capacity comes from, for reports.
    """

    kind: str
    capacity: Optional[float] = None
    soil: Optional[str] = None
    design: Optional[str] = None
    h_max: Optional[float] = None
    v_max: Optional[float] = None
    length: Optional[float] = None
    diameter: Optional[float] = None
    mass: Optional[float] = None
    embedment: Optional[Embedment] = None
    capacity_source: str = "given in the case"
