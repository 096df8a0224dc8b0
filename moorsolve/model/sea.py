"""The sea state and a body's hydrodynamics as a case file gives them.

A wave train with a period is a sea state: a spectrum (:class:`Spectrum`) of significant
height ``hs`` and peak period ``tp``, travelling toward ``toward_deg``, lasting
``duration`` (for the most probable maxima). A body that moves in it carries its
frequency-dependent hydrodynamics (:class:`Hydrodynamics`) and may add damping
(:class:`ExtraDamping`). The spectra and the motions themselves are computed in
:mod:`moorsolve.dynamics`; here they are only described and checked.

Conventions: circular frequency ``omega`` [rad/s]; 6-vectors and 6x6 matrices in the order
surge, sway, heave, roll, pitch, yaw, body frame, about the body-frame origin; excitation
per unit wave amplitude with the phase of ``Re{F e^{+i omega t}}``; a wave heading
``heading_deg`` is the direction the waves travel toward relative to the body's x axis.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

#: Spectrum models a case file may name.
SPECTRUM_MODELS = ("jonswap", "pierson_moskowitz")
#: Default storm duration for most probable maxima [s] (3 hours).
DEFAULT_DURATION = 3 * 3600.0


@dataclass(frozen=True)
class Spectrum:
    """A wave spectrum's shape: a parametric ``model`` (``jonswap``: DNV-RP-C205 form with
    peak enhancement ``gamma``, None = DNV's rule from Tp/sqrt(Hs);
    ``pierson_moskowitz``) or ``table`` rows ``(omega [rad/s], S [m^2 s/rad])``."""

    model: str = "jonswap"
    gamma: Optional[float] = None
    table: Optional[tuple] = None


@dataclass(frozen=True)
class ExcitationTable:
    """First-order wave force per unit amplitude for one heading: ``re``, ``im`` per omega,
    6 each [N/m, N m/m], body frame."""

    heading_deg: float
    re: tuple
    im: tuple


@dataclass(frozen=True)
class DriftTable:
    """Mean drift force per unit amplitude squared for one heading: ``values`` per omega,
    6 each [N/m^2, N m/m^2], body frame."""

    heading_deg: float
    values: tuple


@dataclass(frozen=True)
class Hydrodynamics:
    """A body's frequency-dependent hydrodynamic coefficients.

    Attributes
    ----------
    omega : tuple of float
        Frequencies [rad/s], strictly increasing.
    added_mass, damping : tuple of 6x6 per omega
        Added mass [kg, kg m, kg m^2] and radiation damping [N s/m, N m s, N m s/rad].
    excitation : tuple of ExcitationTable
        Per heading, ascending.
    mean_drift : tuple of DriftTable
        Per heading, ascending; empty when not given (no slow drift, no mean drift force).
    source : str
        Where the values came from: ``table`` or ``wamit``.
    """

    omega: tuple
    added_mass: tuple
    damping: tuple
    excitation: tuple
    mean_drift: tuple = ()
    source: str = "table"


@dataclass(frozen=True)
class ExtraDamping:
    """Damping added to the radiation damping: ``linear`` 6 values [N s/m, N m s/rad] (body
    frame) and ``critical_fraction`` per DOF name (of ``2 sqrt(K (M + A(0)))`` of that DOF)."""

    linear: tuple = (0.0,) * 6
    critical_fraction: tuple = (0.0,) * 6


@dataclass(frozen=True)
class CapytaineHull:
    """Hydrodynamics to compute with Capytaine (BEM) from the body's ``hull`` members at
    frequencies ``omega`` [rad/s] and wave headings ``headings_deg`` (toward, relative to
    body x), panels of about ``panel_size`` [m] (None: a sixth of the smallest member
    dimension), cached in ``cache`` (a folder; None: the user's cache folder)."""

    omega: tuple
    headings_deg: tuple
    panel_size: Optional[float] = None
    cache: Optional[str] = None
    source: str = "capytaine"
