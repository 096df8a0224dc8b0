"""Fatigue damage (Palmgren-Miner) of a Gaussian load process or of a counted series.

A curve ``N = a_D S^-m`` and ranges ``S_i`` counted ``n_i`` times give Miner's sum
``D = sum n_i / N_i = sum n_i S_i^m / a_D``. From the one-sided spectrum ``G(omega)`` of
the load (in the curve's range unit per unit load), with moments
``lambda_n = int omega^n G d omega``:

* narrow band (Rice; DNV-OS-E301 (2010) Ch.2 Sec.2 E): ranges are twice Rayleigh
  amplitudes at the mean up-crossing rate ``nu_0 = sqrt(lambda_2 / lambda_0) / (2 pi)``::

      D = nu_0 T (2 sqrt(2) sigma)^m Gamma(1 + m/2) / a_D,    sigma = sqrt(lambda_0)

* Dirlik (1985, PhD thesis, University of Warwick; the closed form as in Bishop & Sherratt
  1989 and Halfpenny 1999): the rainflow range density, an empirical mix of an exponential
  and two Rayleigh terms fitted to simulations, at the peak rate
  ``E[P] = sqrt(lambda_4 / lambda_2) / (2 pi)``, with ``Z = S / (2 sigma)``::

      x_m = lambda_1/lambda_0 sqrt(lambda_2/lambda_4),  g = lambda_2 / sqrt(lambda_0 lambda_4)
      D1 = 2 (x_m - g^2) / (1 + g^2),   R = (g - x_m - D1^2) / (1 - g - D1 + D1^2)
      D2 = (1 - g - D1 + D1^2) / (1 - R),  D3 = 1 - D1 - D2,  Q = 1.25 (g - D3 - D2 R) / D1
      D = E[P] T (2 sigma)^m / a_D [D1 Q^m Gamma(1+m) + sqrt(2)^m Gamma(1+m/2) (D2 |R|^m + D3)]

  In the narrow-band limit (``g -> 1``: ``D1, D2 -> 0``, ``D3 -> 1``, ``E[P] -> nu_0``) it is
  the narrow-band damage; for a broad band it follows rainflow counting where the narrow
  band over-counts.
* rainflow counting of a series (ASTM E1049-85 (2017) section 5.4.4, by the ``rainflow``
  package): half cycles count one half.

Spectra here are one-sided in circular frequency [unit^2 s/rad]; the dimensionless ratios
are the same in hertz.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import CaseError

__all__ = ["spectral_moments", "narrow_band_damage", "dirlik_damage", "rainflow_damage",
           "DIRLIK_NARROW"]

#: Below this ``1 - g`` (g the irregularity factor) Dirlik's terms are 0/0 and the
#: process is narrow band: the narrow-band form at the peak rate is taken.
DIRLIK_NARROW = 1e-9


def spectral_moments(omega, spectrum, orders=(0, 1, 2, 4)) -> tuple:
    """Moments ``int omega^n G d omega`` (trapezoidal) of a one-sided spectrum."""
    omega = np.asarray(omega, float)
    G = np.asarray(spectrum, float)
    return tuple(float(np.trapezoid(omega ** n * G, omega)) for n in orders)


def _check(duration, m, a_d):
    if not duration >= 0:
        raise CaseError("duration", f"{duration} s must be >= 0")
    if not (m > 0 and a_d > 0):
        raise CaseError("curve", f"m = {m} and a_d = {a_d} must be > 0")


def narrow_band_damage(m0: float, m2: float, duration: float, m: float, a_d: float) -> float:
    """Narrow-band damage of a Gaussian process over ``duration`` [s].

    Parameters
    ----------
    m0, m2 : float
        Zeroth and second moments of the range-unit spectrum [S^2, S^2 rad^2/s^2].
    duration : float
        Exposure [s].
    m, a_d : float
        The curve ``N = a_d S^-m``.
    """
    _check(duration, m, a_d)
    if m0 <= 0:
        return 0.0
    nu0 = math.sqrt(m2 / m0) / (2 * math.pi)
    return nu0 * duration * (2 * math.sqrt(2 * m0)) ** m * math.gamma(1 + m / 2) / a_d


def dirlik_damage(omega, spectrum, duration: float, m: float, a_d: float) -> float:
    """Dirlik's damage of a Gaussian process of one-sided spectrum ``spectrum``
    [S^2 s/rad] on frequencies ``omega`` [rad/s] over ``duration`` [s] (module notes)."""
    _check(duration, m, a_d)
    l0, l1, l2, l4 = spectral_moments(omega, spectrum)
    if l0 <= 0:
        return 0.0
    if not (l2 > 0 and l4 > 0):
        raise CaseError("spectrum", "Dirlik's method needs a spectrum with energy above "
                                    "omega = 0 (second and fourth moments > 0)")
    peaks = math.sqrt(l4 / l2) / (2 * math.pi)
    xm = l1 / l0 * math.sqrt(l2 / l4)
    g = min(l2 / math.sqrt(l0 * l4), 1.0)
    sigma = math.sqrt(l0)
    if 1 - g < DIRLIK_NARROW:
        return peaks * duration * (2 * math.sqrt(2) * sigma) ** m * math.gamma(1 + m / 2) / a_d
    d1 = 2 * (xm - g ** 2) / (1 + g ** 2)
    r = (g - xm - d1 ** 2) / (1 - g - d1 + d1 ** 2)
    d2 = (1 - g - d1 + d1 ** 2) / (1 - r)
    d3 = 1 - d1 - d2
    q = 1.25 * (g - d3 - d2 * r) / d1
    bracket = (d1 * q ** m * math.gamma(1 + m)
               + math.sqrt(2) ** m * math.gamma(1 + m / 2) * (d2 * abs(r) ** m + d3))
    return peaks * duration * (2 * sigma) ** m * bracket / a_d


def rainflow_damage(series, m: float, a_d: float, *, scale: float = 1.0) -> tuple:
    """Miner's sum of a load series counted by rainflow (ASTM E1049).

    Parameters
    ----------
    series : array_like
        The load at successive samples (only its turning points matter).
    m, a_d : float
        The curve ``N = a_d S^-m``.
    scale : float
        Range unit per load unit (e.g. MPa per newton).

    Returns
    -------
    (damage, ranges, counts) : (float, ndarray, ndarray)
        ``ranges`` in the curve's unit, ``counts`` 1 for a full cycle and 0.5 for a half.
    """
    import rainflow

    _check(0.0, m, a_d)
    x = np.asarray(series, float).ravel()
    if x.size < 2 or not np.all(np.isfinite(x)):
        raise CaseError("series", "a load series needs at least 2 finite values")
    cycles = list(rainflow.extract_cycles(x))
    if not cycles:
        return 0.0, np.zeros(0), np.zeros(0)
    ranges = np.array([c[0] for c in cycles]) * scale
    counts = np.array([c[2] for c in cycles])
    return float(np.sum(counts * ranges ** m) / a_d), ranges, counts
