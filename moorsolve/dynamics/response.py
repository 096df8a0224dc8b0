"""The frequency-domain response of a linear system and its statistics (plain numpy).

The system is ``[-w^2 M(w) + i w B(w) + K] X(w) = F(w)`` (motion ``Re{X e^{+i w t}}``),
solved at every frequency at once (numpy's batched ``solve``). Response spectra are
one-sided; ``m_n = int w^n S(w) dw`` by the trapezoidal rule on the given points.

Notes
-----
Slow drift by Newman's approximation (J. N. Newman, "Second-order, slowly-varying forces
on vessels in irregular waves", Int. Symp. Dynamics of Marine Vehicles and Structures in
Waves, London, 1974): the difference-frequency force between two wave components is taken
from the mean drift coefficient ``D`` at their mean frequency, so the one-sided force
spectrum is ``S_F(mu) = 8 int S(w) S(w + mu) D(w + mu/2)^2 dw`` (Faltinsen, "Sea Loads on
Ships and Offshore Structures", 1990, eq. 5.48 with Newman's approximation); with several
force components the cross-spectra are ``8 int S S D_i D_j dw``. The mean drift force is
``2 int D(w) S(w) dw``. Statistics follow DNV-RP-C205 3.5.4 and API RP 2SK (2005) 6.4:
``sigma = sqrt(m0)``, ``Tz = 2 pi sqrt(m0 / m2)``, most probable maximum in a storm of
duration ``T``: ``sigma sqrt(2 ln(T / Tz))`` (Rayleigh-distributed peaks of a narrow-band
Gaussian process).
"""

from __future__ import annotations

import math

import numpy as np


def transfer(omega, M, B, K, F=None) -> np.ndarray:
    """``X(w)`` of ``[-w^2 M + i w B + K] X = F`` at every ``omega`` (m,).

    Parameters
    ----------
    omega : array (m,)
        [rad/s]
    M, B : array (m, n, n) or (n, n)
        Inertia (mass plus added mass) and damping per frequency, or constant.
    K : array (n, n)
        Stiffness.
    F : array (m, n) complex, optional
        Force amplitudes; without, the full transfer matrices ``H(w) = Z(w)^-1`` (m, n, n).
    """
    w = np.asarray(omega, dtype=float)[:, None, None]
    Z = -w ** 2 * np.asarray(M) + 1j * w * np.asarray(B) + np.asarray(K)[None, :, :]
    if F is None:
        return np.linalg.inv(Z)
    return np.linalg.solve(Z, np.asarray(F, dtype=complex)[:, :, None])[:, :, 0]


def statistics(omega, S, duration: float) -> dict:
    """``sigma``, ``significant`` (2 sigma), ``tz_s`` and ``max`` (the most probable maximum
    in ``duration`` [s]) of response spectra ``S`` (m,) or (m, k) over ``omega`` (m,).

    ``tz_s`` is inf (and ``max`` is sigma sqrt(2 ln 1) = 0 ... reported as 0) for a response
    without energy; a storm shorter than ``Tz`` has no maximum beyond sigma's scale and
    gives ``max = 0`` with ``ln`` clipped at 0 (never happens for real storms).
    """
    w = np.asarray(omega, dtype=float)
    S = np.asarray(S, dtype=float)
    if S.ndim == 1:
        S = S[:, None]
    m0 = np.trapezoid(S, w, axis=0)
    m2 = np.trapezoid(w[:, None] ** 2 * S, w, axis=0)
    m0 = np.clip(m0, 0.0, None)
    sigma = np.sqrt(m0)
    with np.errstate(divide="ignore", invalid="ignore"):
        tz = np.where(m2 > 0, 2 * math.pi * np.sqrt(m0 / np.where(m2 > 0, m2, 1.0)), np.inf)
        n = np.where(np.isfinite(tz), np.log(np.clip(duration / tz, 1.0, None)), 0.0)
    return {"sigma": sigma, "significant": 2 * sigma, "tz_s": tz,
            "max": sigma * np.sqrt(2 * n)}


def newman_spectrum(mu, omega, density, drift) -> np.ndarray:
    """Newman's slow-drift force cross-spectra ``S_F(mu)`` (len(mu), k, k).

    Parameters
    ----------
    mu : array
        Difference frequencies [rad/s], >= 0.
    omega : array (m,)
        Integration points, increasing (uniform or not), over the range where the wave
        spectrum and ``drift`` are known; for each ``mu`` the trapezoidal rule runs over the
        points with ``w + mu`` still in it.
    density : callable
        The wave spectrum ``S(w)`` [m^2 s/rad].
    drift : callable
        ``w -> D(w)`` (len(w), k): mean drift force per amplitude squared [N/m^2, ...].
    """
    w = np.asarray(omega, dtype=float)
    mu = np.asarray(mu, dtype=float)
    hi = w[-1]
    dx = np.diff(w)
    weights = np.zeros((mu.size, w.size))
    for r, m in enumerate(mu):
        last = int(np.searchsorted(w, hi - m, side="right")) - 1
        if last < 1:
            continue
        weights[r, :last] += 0.5 * dx[:last]
        weights[r, 1:last + 1] += 0.5 * dx[:last]
    S = density(w)
    pair = S[None, :] * density(w[None, :] + mu[:, None]) * weights        # (len(mu), m)
    D = drift((w[None, :] + 0.5 * mu[:, None]).ravel()).reshape(mu.size, w.size, -1)
    return 8.0 * np.einsum("rw,rwi,rwj->rij", pair, D, D, optimize=True)


def mean_drift_force(omega, S, D) -> np.ndarray:
    """``2 int D(w) S(w) dw`` over ``omega`` (m,), ``D`` (m, k): the mean drift force."""
    return 2.0 * np.trapezoid(np.asarray(D) * np.asarray(S)[:, None], omega, axis=0)
