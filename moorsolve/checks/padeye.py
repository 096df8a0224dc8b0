"""The line's tension and angle carried from the mudline down to an embedded padeye.

Below the mudline a chain cuts an inverse catenary through the soil: the soil's normal
resistance ``Q`` per unit length turns it (``T dtheta/ds = Q``) and the friction along it,
``mu Q``, sheds tension (``dT/ds = -mu Q``). Neubecker & Randolph (1995, "Profile and
frictional capacity of embedded anchor chains", J. Geotech. Eng. 121(11)) integrate these
with small angles and the chain's weight neglected; Randolph & Gourvenec (2011, Offshore
Geotechnical Engineering, section 10.4) write the result as

    T_a / 2 (theta_a^2 - theta_m^2) = z_a Q_av,     T_m / T_a = exp(mu (theta_a - theta_m)),

``theta`` the line's angle below the horizontal (``_m`` at the mudline, ``_a`` at the padeye),
``z_a`` the padeye's depth and ``z_a Q_av = int_0^z_a Q dz``. In clay with an undrained shear
strength ``s_u = s_u0 + k z``, ``Q = A_b d N_c s_u`` (``d`` the nominal diameter, ``A_b`` the
effective bearing width over ``d``: 2.5 for chain; ``N_c`` the bearing factor), so
``z_a Q_av = A_b d N_c (s_u0 z_a + k z_a^2 / 2)``. Eliminating ``T_a``::

    f(theta_a) = T_m (theta_a^2 - theta_m^2) - 2 z_a Q_av exp(mu (theta_a - theta_m)) = 0.

``f`` is negative at ``theta_m``, convex then concave: it has at most one root on
``[theta_m, pi/2]`` where it turns positive, found by bracketing. With no root there the
line reaches the vertical before the padeye (a soil too strong for the tension): the padeye
angle is then 90 deg and the tension bounded by the friction shed on the way down,
``T_m exp(-mu (pi/2 - theta_m))``, which the result flags.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import brentq

__all__ = ["PadeyeLoad", "padeye_load", "clay_resistance"]


@dataclass(frozen=True)
class PadeyeLoad:
    """The load at the padeye.

    Attributes
    ----------
    tension : float
        ``T_a`` [N].
    angle : float
        ``theta_a`` below the horizontal [rad].
    vertical : bool
        The line reached the vertical before the padeye: ``angle`` is pi/2 and ``tension``
        an upper bound.
    """

    tension: float
    angle: float
    vertical: bool = False

    @property
    def horizontal(self) -> float:
        """Horizontal component [N]."""
        return self.tension * math.cos(self.angle)

    @property
    def vertical_force(self) -> float:
        """Upward component [N] (the pull on the anchor)."""
        return self.tension * math.sin(self.angle)


def clay_resistance(depth: float, *, diameter: float, su0: float, su_gradient: float,
                    bearing_factor: float = 8.5, bearing_width: float = 2.5) -> float:
    """``z Q_av = A_b d N_c (s_u0 z + k z^2 / 2)`` [N]: the soil's normal resistance
    integrated from the mudline to ``depth`` [m] (Randolph & Gourvenec 2011, section 10.4).

    Parameters
    ----------
    depth : float
        Padeye depth below the mudline [m].
    diameter : float
        Nominal line diameter [m].
    su0, su_gradient : float
        Undrained shear strength at the mudline [Pa] and its gradient [Pa/m].
    bearing_factor, bearing_width : float
        ``N_c`` and ``A_b`` [-].
    """
    return bearing_width * diameter * bearing_factor * (su0 * depth
                                                        + 0.5 * su_gradient * depth ** 2)


def padeye_load(tension: float, angle: float, resistance: float,
                friction: float) -> PadeyeLoad:
    """The padeye's tension and angle from the mudline's (Neubecker & Randolph 1995).

    Parameters
    ----------
    tension : float
        Line tension at the mudline ``T_m`` [N], >= 0.
    angle : float
        Line angle below the horizontal at the mudline ``theta_m`` [rad], in [0, pi/2].
    resistance : float
        ``z_a Q_av`` [N], >= 0 (:func:`clay_resistance`).
    friction : float
        ``mu`` [-], >= 0.

    Returns
    -------
    PadeyeLoad
    """
    if not (tension >= 0 and 0 <= angle <= math.pi / 2 and resistance >= 0
            and friction >= 0):
        raise ValueError(f"padeye_load: T_m {tension}, theta_m {angle}, z Q_av "
                         f"{resistance}, mu {friction} out of range")
    if tension == 0 or resistance == 0:
        return PadeyeLoad(tension=tension, angle=angle)
    c = 2.0 * resistance

    def f(theta: float) -> float:
        return tension * (theta ** 2 - angle ** 2) - c * math.exp(friction * (theta - angle))

    top = math.pi / 2
    if f(top) <= 0:
        return PadeyeLoad(tension=tension * math.exp(-friction * (top - angle)), angle=top,
                          vertical=True)
    theta = brentq(f, angle, top, xtol=1e-14, rtol=1e-15, maxiter=200)
    return PadeyeLoad(tension=tension * math.exp(-friction * (theta - angle)), angle=theta)
