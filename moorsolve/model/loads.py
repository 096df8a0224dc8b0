"""Load models a body may declare: drag, the Hu & Tang forms, wave drift, constant force.

Each model acts at ``centre`` (body frame, m), which sets its moment. The flow heading
relative to the body, theta = toward_deg - yaw, is taken in the body frame.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

@dataclass(frozen=True)
class DragLoad:
    """General quadratic drag ``0.5 rho C A V^2`` for wind or current.

    Without a ``table`` the coefficients are constant and each body axis sees the flow
    component along it: ``Fx = 0.5 rho cx area_x V^2 cos(theta)|cos(theta)|`` and
    ``Fy = 0.5 rho cy area_y V^2 sin(theta)|sin(theta)|`` (body axes).
    With a ``table`` of rows ``(heading_deg, cx, cy, cmz)`` (relative heading, interpolated
    linearly and periodically) the coefficients carry their own sign:
    ``Fx = q cx(theta) area_x``, ``Fy = q cy(theta) area_y``,
    ``Mz = q cmz(theta) area_y length`` with ``q = 0.5 rho V^2``.

    Attributes
    ----------
    area_x, area_y : float
        Projected areas [m^2] facing a flow along body x and along body y.
    cx, cy : float
        Drag coefficients [-] (used without a table).
    table : tuple of (heading_deg, cx, cy, cmz) or None
    length : float
        Reference length [m] for the table's yaw-moment coefficient.
    centre : tuple of 2 floats
        Centre of pressure [m], body frame.
    """

    area_x: float
    area_y: float
    cx: float = 1.0
    cy: float = 1.0
    table: Optional[tuple] = None
    length: float = 0.0
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class HuTangWind:
    """Hu & Tang (2004) wind resistance ``R1 = 0.006 rho_a V^2 (F' + 0.31 F)`` [kN].

    ``superstructure_area`` (F') and ``hull_area`` (F, hull above water) are projected on the
    midship section, i.e. they face a flow along body x. Given alone, the force acts along
    the wind with that magnitude whatever the heading (the paper's use). With the lateral
    areas too, body x sees ``R1(frontal) cos|cos|`` and body y ``R1(lateral) sin|sin|``.
    """

    superstructure_area: float
    hull_area: float
    superstructure_area_lateral: Optional[float] = None
    hull_area_lateral: Optional[float] = None
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class HuTangCurrent:
    """Hu & Tang (2004) current resistance ``R2 = 0.01 f Omega v^1.83`` [kN], along the flow.

    ``wetted_area`` is Omega [m^2], ``coefficient`` is f (0.18 in the paper).
    """

    wetted_area: float
    coefficient: float = 0.18
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class HuTangDrift:
    """Hu & Tang (2004) wave drift ``R3 = 0.75 k rho g B (Hs/4)^2 cos(alpha) 1e-2`` [kN].

    ``beam`` B [m] gives the drift along body x (``cos alpha`` with alpha the wave heading
    relative to the bow); an optional ``length`` gives the beam-sea drift along body y the same
    way with ``sin alpha``. ``k`` is the paper's coefficient (0.7).
    """

    beam: float
    length: Optional[float] = None
    k: float = 0.7
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class DriftCoefficient:
    """Mean wave drift in a general coefficient form.

    ``Fx = rho g cx length_x (Hs/4)^2 cos(theta)`` and ``Fy = rho g cy length_y (Hs/4)^2
    sin(theta)``: drift scales with the wave height squared (Hs/4 is the standard deviation
    of the surface elevation; Hu & Tang write their formula with it) and with the waterline
    breadth facing the waves.
    """

    length_x: float
    length_y: float
    cx: float = 1.0
    cy: float = 1.0
    centre: tuple = (0.0, 0.0)


@dataclass(frozen=True)
class BodyLoads:
    """The load models a body declares; each one present is simulated.

    ``force`` is a constant [Fx N, Fy N, Mz N m] in the global frame.
    """

    force: Optional[tuple] = None
    wind: Optional[object] = None        # DragLoad | HuTangWind
    current: Optional[object] = None     # DragLoad | HuTangCurrent
    wave_drift: Optional[object] = None  # HuTangDrift | DriftCoefficient
