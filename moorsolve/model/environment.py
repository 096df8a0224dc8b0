"""The environment of a scene: water, seabed, wind, current and waves.

Coordinates: x, y horizontal, z up, z = 0 at the still-water level. ``toward_deg`` is the
direction a wind, current or wave train travels toward, counter-clockwise from +x, whatever
the case file gave (``from_deg``, a compass bearing: :mod:`moorsolve.model.directions`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from ..constants import AIR_DENSITY, SEAWATER_DENSITY, STANDARD_GRAVITY
from .directions import Compass


@dataclass(frozen=True)
class Flow:
    """A wind or current: speed [m/s] toward ``toward_deg``.

    A current may carry a ``profile`` of ``(z, speed)`` rows (z ascending, m and m/s) that
    the lines see, interpolated linearly and held constant beyond its ends; ``speed`` is
    then what the body's load models see. Without a profile the lines see ``speed`` at
    every depth.
    """

    speed: float
    toward_deg: float = 0.0
    profile: Optional[tuple] = None


@dataclass(frozen=True)
class Waves:
    """An irregular sea: significant height ``hs`` [m] travelling toward ``toward_deg``."""

    hs: float
    toward_deg: float = 0.0


@dataclass(frozen=True)
class Seabed:
    """Seabed contact.

    ``friction`` is the Coulomb coefficient for line on seabed (0 = none). ``gradient`` is
    ``(dz/dx, dz/dy)`` of a plane seabed: its height is ``-depth + gx x + gy y``, so
    ``depth`` is the water depth at the origin; ``(0, 0)`` is flat.
    """

    friction: float = 0.0
    gradient: tuple = (0.0, 0.0)

    @property
    def sloped(self) -> bool:
        return any(g != 0.0 for g in self.gradient)


@dataclass(frozen=True)
class Environment:
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

    def seabed_z(self, x: float, y: float) -> float:
        """Height of the seabed [m] at ``(x, y)`` (``-depth`` on a flat seabed)."""
        gx, gy = self.seabed.gradient
        return -self.depth + gx * x + gy * y
