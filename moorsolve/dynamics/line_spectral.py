"""Line tension statistics in an irregular sea: the spectral driver of the line dynamics.

Given the fairlead's motion per metre of wave amplitude ``X(omega)`` (3 x n_omega, complex,
from the body motions) and the wave spectrum ``S(omega)``, the line's response is solved
with its drag linearised on the spectral standard deviation of each node's velocity
(:func:`~.line_dynamics.line_response`, ``"spectral"``). At each end the tension spectrum
and its statistics follow (DNV-OS-E301 (2010) Ch.2 Sec.2 [2.4]; DNV-RP-C205 (2010) section
3.5.3 for the moments)::

    S_T(omega) = |H_T(omega)|^2 S(omega)
    m_n = int omega^n S_T(omega) d omega,  sigma = sqrt(m_0),  T_z = 2 pi sqrt(m_0 / m_2)
    T_dyn = sigma sqrt(2 ln N),            N = duration / T_z

``T_dyn`` is the most probable largest of ``N`` Rayleigh-distributed peaks of a narrow-band
Gaussian process, DNV-OS-E301's characteristic dynamic tension for a short-term sea state
(3 hours unless said otherwise). A spectrum that spans both wave-frequency and low-frequency
motion gives ``sigma^2 = sigma_LF^2 + sigma_WF^2`` over the whole range; the narrow-band
maximum of a bimodal spectrum is then approximate (DNV-OS-E301 gives a combination of
the two maxima for that case, not applied here).

Integrals are trapezoidal over the given frequencies: the grid must cover the spectrum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import CaseError
from .line_dynamics import SPECTRAL, LineResponse, line_response
from .line_model import LineModel

__all__ = ["EndStatistics", "LineTensionStatistics", "spectral_statistics",
           "characteristic_dynamic_tension", "tension_statistics", "STORM_DURATION_S"]

#: DNV-OS-E301's short-term sea state: 3 hours [s].
STORM_DURATION_S = 3 * 3600.0


@dataclass(frozen=True)
class EndStatistics:
    """Tension statistics at one end of a line.

    Attributes
    ----------
    spectrum : ndarray (n_omega,)
        Tension spectrum ``S_T(omega)`` [N^2 s/rad].
    sigma_N : float
        Standard deviation of the dynamic tension [N].
    tz_s : float
        Mean zero up-crossing period [s] (NaN when sigma is 0).
    cycles : float
        ``N = duration / T_z``.
    t_dyn_N : float
        Characteristic dynamic tension ``sigma sqrt(2 ln N)`` [N].
    """

    spectrum: np.ndarray
    sigma_N: float
    tz_s: float
    cycles: float
    t_dyn_N: float


@dataclass(frozen=True)
class LineTensionStatistics:
    """A line's dynamic tension in one sea state: both ends and the response behind them."""

    name: str
    duration_s: float
    anchor: EndStatistics
    fairlead: EndStatistics
    response: LineResponse


def spectral_statistics(omega, spectrum) -> tuple:
    """``(sigma, T_z)`` of a one-sided spectrum [unit^2 s/rad] on frequencies ``omega``
    [rad/s]: ``sqrt(m_0)`` and ``2 pi sqrt(m_0 / m_2)`` (trapezoidal moments)."""
    omega = np.asarray(omega, float)
    spectrum = np.asarray(spectrum, float)
    m0 = float(np.trapezoid(spectrum, omega))
    m2 = float(np.trapezoid(omega ** 2 * spectrum, omega))
    sigma = math.sqrt(max(m0, 0.0))
    tz = 2 * math.pi * math.sqrt(m0 / m2) if m0 > 0 and m2 > 0 else float("nan")
    return sigma, tz


def characteristic_dynamic_tension(sigma: float, tz: float,
                                   duration: float = STORM_DURATION_S) -> tuple:
    """``(T_dyn, N)``: the most probable maximum ``sigma sqrt(2 ln N)`` [N] of ``N =
    duration / T_z`` cycles (DNV-OS-E301 (2010) Ch.2 Sec.2).

    Raises CaseError when the duration holds fewer than 2 cycles (no maximum to speak of);
    a zero ``sigma`` gives 0.
    """
    if not duration > 0:
        raise CaseError("duration", f"{duration} s must be > 0")
    if sigma == 0:
        return 0.0, 0.0
    cycles = duration / tz
    if not cycles >= 2:
        raise CaseError("duration", f"{duration:g} s holds {cycles:.3g} tension cycles of "
                        f"T_z = {tz:.4g} s: at least 2 are needed for a most probable "
                        "maximum")
    return sigma * math.sqrt(2 * math.log(cycles)), cycles


def _end(transfer, omega, S, duration) -> EndStatistics:
    spectrum = np.abs(transfer) ** 2 * S
    sigma, tz = spectral_statistics(omega, spectrum)
    t_dyn, cycles = characteristic_dynamic_tension(sigma, tz, duration)
    return EndStatistics(spectrum=spectrum, sigma_N=sigma, tz_s=tz, cycles=cycles,
                         t_dyn_N=t_dyn)


def tension_statistics(model: LineModel, omega, fairlead_rao, spectrum, *,
                       anchor_rao=None, duration: float = STORM_DURATION_S,
                       **solver) -> LineTensionStatistics:
    """Dynamic tension of one line in a sea state.

    Parameters
    ----------
    model : LineModel
        The line (:func:`~.line_model.line_model`).
    omega : array_like (n_omega,)
        Frequencies [rad/s], covering the spectrum.
    fairlead_rao : array_like (3, n_omega) complex
        Fairlead displacement per metre of wave amplitude [m/m], global x, y, z.
    spectrum : array_like (n_omega,)
        Wave spectrum ``S(omega)`` [m^2 s/rad].
    anchor_rao : array_like (3, n_omega) complex, optional
        Motion of end A per metre of wave amplitude (a line between two bodies); None:
        end A is fixed.
    duration : float
        Duration of the sea state [s] for the characteristic maximum (3 h).
    **solver
        Passed to :func:`~.line_dynamics.line_response` (tolerance, iterations).

    Returns
    -------
    LineTensionStatistics
    """
    S = np.asarray(spectrum, float).ravel()
    r = line_response(model, omega, fairlead_rao, linearisation=SPECTRAL, spectrum=S,
                      motion_a=anchor_rao, **solver)
    return LineTensionStatistics(name=model.name, duration_s=float(duration),
                                 anchor=_end(r.tension_a, r.omega, S, duration),
                                 fairlead=_end(r.tension_b, r.omega, S, duration),
                                 response=r)
