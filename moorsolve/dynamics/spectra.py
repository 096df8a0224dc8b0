"""Wave spectra: JONSWAP in the DNV-RP-C205 form, Pierson-Moskowitz, and a table.

One-sided spectral densities ``S(omega)`` [m^2 s/rad] of the sea surface elevation over the
circular frequency ``omega`` [rad/s], with ``hs`` the significant wave height [m] and ``tp``
the spectral peak period [s]: the names and the parametrisation of the ``wavespectra``
package's ``jonswap`` / ``pierson_moskowitz`` constructors (``hs``, ``gamma``, ``sigma_a``,
``sigma_b``), in circular frequency rather than Hz (``S(omega) = S(f) / (2 pi)``).

Notes
-----
DNV-RP-C205 (2010), section 3.5.5:

- Pierson-Moskowitz (eq. 3.5.5.1):
  ``S_PM(w) = 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (w/wp)^-4)``, ``wp = 2 pi / Tp``; its zeroth
  moment is exactly ``Hs^2 / 16``;
- JONSWAP (3.5.5.2): ``S_J(w) = A_gamma S_PM(w) gamma^exp(-0.5 ((w - wp) / (sigma wp))^2)``
  with ``sigma = 0.07`` (``w <= wp``) or ``0.09`` (``w > wp``) and the normalising factor
  ``A_gamma = 1 - 0.287 ln(gamma)``, an approximation: ``m0`` is then ``Hs^2 / 16`` to
  within 0.3 % for gamma from 1 to 5 and 1.8 % at gamma = 7;
- the peak enhancement factor when it is not given (3.5.5.5): ``gamma = 5`` for
  ``Tp / sqrt(Hs) <= 3.6``, ``exp(5.75 - 1.15 Tp / sqrt(Hs))`` up to 5, and 1 beyond
  (``Tp`` [s], ``Hs`` [m]).
"""

from __future__ import annotations

import math

import numpy as np

#: DNV-RP-C205's spectral width parameters below and above the peak.
SIGMA_A, SIGMA_B = 0.07, 0.09


def gamma_dnv(hs: float, tp: float) -> float:
    """DNV-RP-C205 3.5.5.5's peak enhancement factor from ``tp / sqrt(hs)`` [s / m^0.5]."""
    if hs <= 0:
        return 1.0
    r = tp / math.sqrt(hs)
    if r <= 3.6:
        return 5.0
    if r < 5.0:
        return math.exp(5.75 - 1.15 * r)
    return 1.0


def pierson_moskowitz(omega, hs: float, tp: float) -> np.ndarray:
    """Pierson-Moskowitz spectrum [m^2 s/rad] at ``omega`` [rad/s] (DNV-RP-C205 3.5.5.1)."""
    w = np.asarray(omega, dtype=float)
    wp = 2 * math.pi / tp
    out = np.zeros_like(w)
    pos = w > 0
    wr = w[pos] / wp
    out[pos] = 5.0 / 16.0 * hs ** 2 / wp * wr ** -5 * np.exp(-1.25 * wr ** -4)
    return out


def jonswap(omega, hs: float, tp: float, gamma=None, sigma_a: float = SIGMA_A,
            sigma_b: float = SIGMA_B) -> np.ndarray:
    """JONSWAP spectrum [m^2 s/rad] at ``omega`` [rad/s] in the DNV-RP-C205 form
    (3.5.5.2), ``gamma`` None: DNV's rule (:func:`gamma_dnv`)."""
    g = gamma_dnv(hs, tp) if gamma is None else float(gamma)
    w = np.asarray(omega, dtype=float)
    wp = 2 * math.pi / tp
    sigma = np.where(w <= wp, sigma_a, sigma_b)
    peak = g ** np.exp(-0.5 * ((w - wp) / (sigma * wp)) ** 2)
    return (1.0 - 0.287 * math.log(g)) * pierson_moskowitz(w, hs, tp) * peak


def tabulated(omega, table) -> np.ndarray:
    """A spectrum given as rows ``(omega [rad/s], S [m^2 s/rad])``, interpolated linearly,
    zero outside the table."""
    t = np.asarray(table, dtype=float)
    return np.interp(np.asarray(omega, dtype=float), t[:, 0], t[:, 1], left=0.0, right=0.0)


def spectrum_of(waves):
    """The spectral density function ``omega -> S`` of a case's
    :class:`~moorsolve.model.environment.Waves` (a sea state)."""
    spec = waves.spectrum
    if spec is None:
        raise ValueError("these waves have no spectrum (give environment.waves.tp)")
    if spec.table is not None:
        return lambda w: tabulated(w, spec.table)
    if spec.model == "pierson_moskowitz":
        return lambda w: pierson_moskowitz(w, waves.hs, waves.tp)
    return lambda w: jonswap(w, waves.hs, waves.tp, spec.gamma)


def spectral_moment(omega, S, n: int = 0) -> float:
    """``m_n = int omega^n S d omega`` by the trapezoidal rule over the given points."""
    w = np.asarray(omega, dtype=float)
    return float(np.trapezoid(w ** n * np.asarray(S, dtype=float), w))


def energy_band(density, tp=None, fraction: float = 1e-4) -> tuple:
    """``(w_lo, w_hi)`` [rad/s] outside which a spectrum holds less than ``fraction`` of its
    energy on each side (found on a fine grid up to 20 peak frequencies)."""
    wp = 2 * math.pi / tp if tp else 1.0
    w = np.linspace(1e-3 * wp, 20 * wp, 20001)
    S = density(w)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (S[1:] + S[:-1]) * np.diff(w))])
    if cum[-1] <= 0:
        return float(w[0]), float(w[-1])
    cum /= cum[-1]
    return (float(np.interp(fraction, cum, w)), float(np.interp(1 - fraction, cum, w)))
