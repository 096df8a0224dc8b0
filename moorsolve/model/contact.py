"""Berth structures and the contacts of bodies with them: quay walls, piles (dolphins and
guide piles), fenders and pile guides.

A contact joins a point and a surface, one of them on a body; the law (one-sided, with a
rigid, linear or tabulated compliance and Coulomb friction) is
:mod:`moorsolve.physics.contact`. Hawsers are not here: a hawser is a line whose type weighs
nothing in water.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ..constants import FRICTION_SLIP

#: How a fender reacts to compression.
REACTION_KINDS = ("rigid", "linear", "table")
#: What a fender is mounted on: the body (bearing on a wall or pile) or the structure (the
#: wall or pile, bearing on the body's side).
MOUNTINGS = ("body", "structure")


@dataclass(frozen=True)
class Wall:
    """A quay wall: the plane through ``point`` with unit ``normal`` pointing out of the wall
    toward the water, where the bodies are. Contact with it is one-sided.

    Attributes
    ----------
    name : str
    point : tuple of 3 floats
        Any point of the plane [m].
    normal : tuple of 3 floats
        Unit outward normal.
    friction : float
        Coulomb coefficient between the wall (or the fenders on it) and what bears on it.
    friction_slip : float
        Slip [m] over which that friction is mobilised (elastic stick below it;
        :mod:`moorsolve.physics.contact`).
    """

    name: str
    point: tuple
    normal: tuple
    friction: float = 0.0
    friction_slip: float = FRICTION_SLIP


@dataclass(frozen=True)
class Pile:
    """A fixed vertical cylinder: a dolphin or a guide pile, from the seabed up.

    Attributes
    ----------
    name : str
    position : tuple of 2 floats
        Its axis ``(x, y)`` [m].
    radius : float
        [m]
    top : float or None
        Height of its top [m]; a guide must stay below it (None: high enough).
    friction : float
        Coulomb coefficient against what bears on it.
    friction_slip : float
        Slip [m] over which that friction is mobilised.
    bending_stiffness : float or None
        ``E I`` [N m^2]: a pile guide bears on the pile as on a cantilever fixed at the
        seabed, of stiffness ``3 E I / h^3`` at the collar's height ``h`` above it (None:
        rigid).
    """

    name: str
    position: tuple
    radius: float
    top: Optional[float] = None
    friction: float = 0.0
    friction_slip: float = FRICTION_SLIP
    bending_stiffness: Optional[float] = None


@dataclass(frozen=True)
class ReactionLaw:
    """A fender's reaction against its compression.

    ``rigid``: no compression (a rubbing strip, a hull corner); ``linear``: ``R = k d``;
    ``table``: the maker's curve, linear between the rows ``(deflection [m], reaction [N])``
    after the origin, strictly increasing, the last slope continued.
    """

    kind: str
    stiffness: Optional[float] = None
    deflections: tuple = ()
    reactions: tuple = ()

    @property
    def curve(self) -> tuple:
        """``(deflections, reactions)`` of the law as a table (one row for a linear law)."""
        if self.kind == "linear":
            return (1.0,), (self.stiffness,)
        return self.deflections, self.reactions


@dataclass(frozen=True)
class Fender:
    """A fender between a body and a wall or a pile.

    Attributes
    ----------
    name : str
    body : str
        The body it is mounted on, or bears on.
    at : tuple of 3 floats
        The fender's face where it touches: body frame when ``mounted`` on the body, scene
        coordinates when mounted on the structure.
    wall, pile : str or None
        What it bears on (or, mounted on the structure, is mounted on): exactly one.
    mounted : str
        ``body`` (it moves with the body and bears on the wall or pile) or ``structure``
        (fixed on the wall or pile, bearing on the body's side: the plane through its face
        parallel to the wall, or normal to the pile's radius, at the case pose).
    law : ReactionLaw
    rated_deflection : float or None
        The maker's rated deflection [m] (the check's limit). Past it the fender is
        overloaded, as a line past its MBL is.
    height : float or None
        Its full compression [m]: the fender's height from what it is mounted on to its
        face. Compressed that far, the hull bears on the wall or pile behind it (a rigid
        contact). A structure-mounted fender's is its face's distance from its wall or
        pile (unless its face is given on the wall); otherwise it is given (None: not
        known, and not modelled). None for a rigid fender.
    """

    name: str
    body: str
    at: tuple
    law: ReactionLaw
    wall: Optional[str] = None
    pile: Optional[str] = None
    mounted: str = "body"
    rated_deflection: Optional[float] = None
    height: Optional[float] = None


@dataclass(frozen=True)
class Guide:
    """A pile guide: a collar on a body round a pile, holding it horizontally while it rises
    and falls. Its inside is a regular polygon of ``pads`` flat bearing faces (rollers or
    UHMW-PE pads; the first faces body +x), each of which bears on the pile once the collar
    has moved ``clearance`` toward it. With a rigid pile, a collar pushed into a corner
    (two pads bearing) on two guides leaves the share between the guides statically
    indeterminate: give the pile its bending stiffness.

    Attributes
    ----------
    name : str
    body : str
    at : tuple of 3 floats
        The collar's centre, body frame [m].
    pile : str
    clearance : float
        Radial play between the pads and the pile [m].
    pads : int
    """

    name: str
    body: str
    at: tuple
    pile: str
    clearance: float
    pads: int = 8


@dataclass(frozen=True)
class Contacts:
    """Everything a scene's bodies may bear on, and what bears."""

    walls: tuple = ()
    piles: tuple = ()
    fenders: tuple = ()
    guides: tuple = ()

    def __bool__(self) -> bool:
        return bool(self.fenders or self.guides)

    def wall_named(self, name: str) -> Wall:
        return next(w for w in self.walls if w.name == name)

    def pile_named(self, name: str) -> Pile:
        return next(p for p in self.piles if p.name == name)


__all__ = ["Wall", "Pile", "ReactionLaw", "Fender", "Guide", "Contacts", "REACTION_KINDS",
           "MOUNTINGS"]
