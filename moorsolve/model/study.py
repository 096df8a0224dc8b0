"""A design study: what an optimisation may change, what it minimises and what it must keep.

Frozen, validated dataclasses (built by :func:`moorsolve.io.study_file.load_study`); no
casadi here. SI units throughout.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Optional

#: Kinds of design variable.
#:
#: ``length``: the unstretched length [m] of one-segment legs;
#: ``anchor_distance``: horizontal distance [m] from the fairlead (body at its case
#: position) to the anchor, the anchor moving along the leg's heading;
#: ``anchor_radius``: horizontal distance [m] of the anchor from the body origin (the
#: global origin without a body), the anchor moving along its bearing from that origin.
VARIABLE_KINDS = ("length", "anchor_distance", "anchor_radius")
OBJECTIVES = ("mass", "cost")


@dataclass(frozen=True)
class DesignVariable:
    """One continuous design variable shared by a group of legs.

    Attributes
    ----------
    name : str
    kind : str
        One of :data:`VARIABLE_KINDS`.
    legs : tuple of str
        The legs that share the value.
    lower, upper : float
        Bounds [m].
    start : float
        Starting value [m]: the legs' common case value unless the study gives one.
    """

    name: str
    kind: str
    legs: tuple
    lower: float
    upper: float
    start: float


@dataclass(frozen=True)
class Limits:
    """Design constraints; None leaves a constraint out.

    Attributes
    ----------
    safety_factor : float or None
        Least MBL / largest line tension (fairlead tension of a sinking line, anchor
        tension of a buoyant one).
    max_anchor_uplift : float or None
        Largest upward pull on an anchor resting on the seabed [N]; 0 for drag anchors (the
        line must arrive along the seabed).
    min_grounded_length : float or None
        Least unstretched length on the seabed [m] in legs whose anchor rests on it.
    offset_limit : float or None
        Largest horizontal offset of the body origin [m].
    """

    safety_factor: Optional[float] = None
    max_anchor_uplift: Optional[float] = None
    min_grounded_length: Optional[float] = None
    offset_limit: Optional[float] = None


@dataclass(frozen=True)
class LoadCase:
    """One condition the design must survive: edits of the base case and its limits.

    ``edits`` maps dotted case paths (:mod:`moorsolve.model.paths`) to case-file values.
    """

    name: str
    edits: Mapping = field(default_factory=dict)
    limits: Limits = field(default_factory=Limits)


@dataclass(frozen=True)
class Study:
    """A design optimisation of one case.

    Attributes
    ----------
    name : str
    objective : str
        ``mass`` (line mass in air [kg]) or ``cost``.
    variables : tuple of DesignVariable
    load_cases : tuple of LoadCase
        Expanded: a load case given over several headings is one entry per heading.
    mass_per_length : dict
        Line type name -> mass in air [kg/m] (catalogue lines need none).
    cost_per_length : dict
        Line type name -> cost per unstretched metre (``cost`` objective).
    anchor_cost : float
        Cost per anchor (``cost`` objective; a constant in the total).
    currency : str
        Label of the cost unit.
    max_cost : float or None
        Largest cost of the whole design (lines and anchors, priced as for the ``cost``
        objective, in ``currency``); a design-wide constraint, not one per load case.
    tol : float
        IPOPT's optimality tolerance (scaled problem).
    max_iter : int
    """

    name: str
    objective: str
    variables: tuple
    load_cases: tuple
    mass_per_length: Mapping = field(default_factory=dict)
    cost_per_length: Mapping = field(default_factory=dict)
    anchor_cost: float = 0.0
    currency: str = "EUR"
    max_cost: Optional[float] = None
    tol: float = 1e-8
    max_iter: int = 500
