"""Directions of wind, current and waves as a case file may give them.

Inside moorsolve a flow's direction is always ``toward_deg``: where it travels toward,
counter-clockwise from +x. A case file may instead say where it comes from,
and may measure angles as a compass does:

``toward_deg``
    The direction the flow travels toward.
``from_deg``
    The direction it comes from (``toward = from + 180``): "wind from the north-east".

``environment.directions`` chooses how both are measured:

``mathematical`` (the default)
    Counter-clockwise from +x, as the contract says.
``nautical``
    Clockwise from north, a compass bearing; ``environment.north_deg`` is where north
    points in the scene, counter-clockwise from +x (default 90: +y is north, x east).
    Every flow then gives its direction explicitly.

So with north along +y, ``{from_deg: 60}`` under ``nautical`` is a wind from 060 deg
(east-north-east) blowing toward 240 deg, which is ``toward_deg: 210`` in the default
convention. ``docs/directions.png`` draws this example.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import CaseError

__all__ = ["CONVENTIONS", "DIRECTION_KEYS", "Compass", "flow_direction", "direction_edit",
           "wrap_deg"]

CONVENTIONS = ("mathematical", "nautical")
#: The keys that give a flow's direction; a flow takes at most one of them.
DIRECTION_KEYS = ("toward_deg", "from_deg")


@dataclass(frozen=True)
class Compass:
    """How a case file measures directions (see the module notes)."""

    convention: str = "mathematical"
    north_deg: float = 90.0

    @property
    def nautical(self) -> bool:
        return self.convention == "nautical"

    def toward_deg(self, value: float, key: str) -> float:
        """The internal ``toward_deg`` of ``value`` given under ``key`` [deg]."""
        angle = self.north_deg - value if self.nautical else value
        if key == "from_deg":
            angle += 180.0
        return wrap_deg(angle) if (self.nautical or key == "from_deg") else value

    def file_value(self, toward_deg: float, key: str) -> float:
        """What ``key`` holds in the file for the internal ``toward_deg`` [deg], in [0, 360)."""
        angle = toward_deg - 180.0 if key == "from_deg" else toward_deg
        return wrap_deg(self.north_deg - angle if self.nautical else angle)

    def describe(self, toward_deg: float) -> str:
        """A direction in the file's words: ``toward 70.0 deg`` or, nautical,
        ``from 020 deg (toward 200 deg, clockwise from north)``."""
        if not self.nautical:
            return f"toward {toward_deg:.1f} deg"
        return (f"from {self.file_value(toward_deg, 'from_deg'):05.1f} deg (toward "
                f"{self.file_value(toward_deg, 'toward_deg'):05.1f} deg, clockwise from north)")


def wrap_deg(angle: float) -> float:
    """An angle in [0, 360), rounded so that whole degrees stay whole."""
    return round(angle % 360.0, 10) % 360.0


def flow_direction(m: dict, path: str, compass: Compass, angle) -> float:
    """The internal ``toward_deg`` of a flow mapping ``m`` at ``path``.

    ``angle(raw, field)`` converts one case-file angle to degrees (units allowed). At most
    one of :data:`DIRECTION_KEYS` may be given; none means toward +x, except under the
    nautical convention, where a direction is required.
    """
    given = [k for k in DIRECTION_KEYS if k in m]
    if len(given) > 1:
        raise CaseError(f"{path}.from_deg", "give the direction once: toward_deg (where it "
                                            "travels toward) or from_deg (where it comes "
                                            "from), not both")
    if not given:
        if compass.nautical:
            raise CaseError(f"{path}.from_deg", "environment.directions is nautical: give "
                                                "the direction, from_deg or toward_deg, as a "
                                                "compass bearing (clockwise from north)")
        return 0.0
    key = given[0]
    return compass.toward_deg(angle(m[key], f"{path}.{key}"), key)


def direction_edit(case, flow: str, toward_deg: float) -> tuple[str, float]:
    """The case-file edit ``(path, value)`` that turns ``environment.<flow>`` to travel
    toward ``toward_deg`` (internal convention), in the file's own terms: its key
    (``from_deg`` if the flow gives one) and its convention.

    Parameters
    ----------
    case : Case
        Loaded with its case-file data (``Case.source``).
    flow : {"wind", "current", "waves"}
    toward_deg : float
        Counter-clockwise from +x [deg].
    """
    compass = case.environment.compass
    env = (case.source or {}).get("environment") or {}
    data = env.get(flow) or {}
    key = "from_deg" if "from_deg" in data else "toward_deg"
    if key == "toward_deg" and not compass.nautical:
        return f"environment.{flow}.toward_deg", toward_deg
    return f"environment.{flow}.{key}", compass.file_value(toward_deg, key)
