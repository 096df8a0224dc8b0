"""The environment of a scene: water, seabed, wind, current and waves.

Coordinates: x, y horizontal, z up, z = 0 at the still-water level. ``toward_deg`` is the
direction a wind, current or wave train travels toward, counter-clockwise from +x, whatever
the case file gave (``from_deg``, a compass bearing: :mod:`moorsolve.model.directions`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional


from ..constants import AIR_DENSITY, SEAWATER_DENSITY, STANDARD_GRAVITY
from .bathymetry import Bathymetry
from .directions import Compass


@dataclass(frozen=True)
class Flow:
    """A wind or current: speed [m/s] toward ``toward_deg``.

    A current may carry a ``profile`` that the lines see, z ascending [m], interpolated
    linearly and held constant beyond its ends: rows ``(z, speed)`` with a signed speed
    along ``toward_deg`` [m/s] (negative: the other way), or ``(z, speed, toward_deg)``
    with each row's own heading (a current that turns with depth; the velocity vectors are
    interpolated). ``speed`` is then what the body's load models see. Without a profile the
    lines see ``speed`` at every depth.
    """

    speed: float
    toward_deg: float = 0.0
    profile: Optional[tuple] = None

    @property
    def profile_headings(self) -> bool:
        """The profile gives a heading per row (``(z, speed, toward_deg)`` rows)."""
        return bool(self.profile) and len(self.profile[0]) == 3

    def profile_vectors(self) -> tuple:
        """The profile as ``(z, ux, uy)`` rows [m, m/s] in the global frame."""
        out = []
        for row in self.profile or ():
            heading = math.radians(row[2] if len(row) == 3 else self.toward_deg)
            out.append((row[0], row[1] * math.cos(heading), row[1] * math.sin(heading)))
        return tuple(out)

    def velocity(self, z: float) -> tuple:
        """The current's horizontal velocity ``(ux, uy)`` [m/s] the lines see at height z."""
        if not self.profile:
            heading = math.radians(self.toward_deg)
            return self.speed * math.cos(heading), self.speed * math.sin(heading)
        import numpy     # here: the model is imported by `moorsolve --help`, numpy is not

        rows = self.profile_vectors()
        zs = [r[0] for r in rows]
        return (float(numpy.interp(z, zs, [r[1] for r in rows])),
                float(numpy.interp(z, zs, [r[2] for r in rows])))


@dataclass(frozen=True)
class Waves:
    """An irregular sea: significant height ``hs`` [m] travelling toward ``toward_deg``.

    With a peak period ``tp`` [s] (or a tabulated spectrum) it is a sea state: its
    ``spectrum`` (:class:`~moorsolve.model.sea.Spectrum`) and storm ``duration`` [s] drive
    the bodies' motions (:mod:`moorsolve.dynamics`). Without, only the drift load models
    hear ``hs``.
    """

    hs: float
    toward_deg: float = 0.0
    tp: Optional[float] = None
    spectrum: Optional[object] = None
    duration: float = 3 * 3600.0

    @property
    def sea_state(self) -> bool:
        """Whether the waves are a spectrum (a period or a table given), not only a height."""
        return self.spectrum is not None


@dataclass(frozen=True)
class Seabed:
    """Seabed contact.

    ``friction`` is the Coulomb coefficient for line on seabed (0 = none). ``gradient`` is
    ``(dz/dx, dz/dy)`` of a plane seabed: its height is ``-depth + gx x + gy y``, so
    ``depth`` is the water depth at the origin; ``(0, 0)`` is flat. ``bathymetry`` (a
    :class:`~.bathymetry.Bathymetry` grid, instead of a gradient) gives the seabed's height
    everywhere; ``tolerance`` [m] is then how far below that surface a line may pass (a
    grounded run lies on one plane per line: :mod:`moorsolve.solve.lines.bathymetry`).
    """

    friction: float = 0.0
    gradient: tuple = (0.0, 0.0)
    bathymetry: Optional[Bathymetry] = None
    tolerance: float = 0.1

    @property
    def sloped(self) -> bool:
        return self.bathymetry is not None or any(g != 0.0 for g in self.gradient)

    def slope_at(self, x: float, y: float) -> tuple:
        """``(dz/dx, dz/dy)`` of the seabed at ``(x, y)``."""
        if self.bathymetry is not None:
            return self.bathymetry.gradient(x, y)
        return tuple(self.gradient)


@dataclass(frozen=True)
class Environment:
    """Water, seabed and flows.

    ``water_level`` is the still-water level above the case's datum (a tide) [m]: the
    seabed (at ``-depth`` on the datum), fixed points, walls and piles are given on the datum,
    and floating bodies' hydrostatics act about this level. 0 (the default) puts the still
    water at z = 0. With a bathymetry grid ``depth`` stays the reference depth (the scale
    of tolerances and warnings); the seabed's height is the grid's (:meth:`seabed_z`).
    """

    depth: float
    water_density: float = SEAWATER_DENSITY
    air_density: float = AIR_DENSITY
    gravity: float = STANDARD_GRAVITY
    seabed: Seabed = field(default_factory=Seabed)
    wind: Optional[Flow] = None
    current: Optional[Flow] = None
    waves: Optional[Waves] = None
    #: How the case file measures directions (``toward_deg`` here is always internal).
    compass: Compass = field(default_factory=Compass)
    water_level: float = 0.0

    def seabed_z(self, x: float, y: float) -> float:
        """Height of the seabed [m] at ``(x, y)`` (``-depth`` on a flat seabed); floats or
        numpy arrays."""
        if self.seabed.bathymetry is not None:
            return self.seabed.bathymetry.height(x, y)
        gx, gy = self.seabed.gradient
        return -self.depth + gx * x + gy * y
