"""Baranov's law along a catenary: ``int sqrt(cosh t) dt`` by Gauss-Legendre quadrature
and, past the switch angle, by its convergent series (see :mod:`moorsolve.physics.stretch`)."""

from __future__ import annotations

import math

import numpy as np

from .stretch_ops import SYMBOLIC


_SWITCH = 2.0                                  # |theta| above which the series is used
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)
_SERIES = 10


def _binom_half(k: int) -> float:
    out = 1.0
    for i in range(k):
        out *= (0.5 - i) / (i + 1)
    return out


_BETA = [_binom_half(k) / (0.5 - 2 * k) for k in range(_SERIES)]


def _sqrt_cosh_integral_reference(theta: float) -> float:
    """``int_0^theta sqrt(cosh t) dt`` by 60-point Gauss-Legendre (floats, ``|theta| <= 2``)."""
    x, wts = np.polynomial.legendre.leggauss(60)
    return float(theta / 2 * np.sum(wts * np.sqrt(np.cosh(theta * (1 + x) / 2))))


#: ``G(theta) - 2^-1/2 e^(theta/2) sum_k beta_k e^(-2 k theta)`` for theta >= 2: constant,
#: fixed at the switch point from the quadrature.
_SERIES_CONSTANT = _sqrt_cosh_integral_reference(_SWITCH) - 2 ** -0.5 * math.exp(_SWITCH / 2) \
    * sum(b * math.exp(-2 * k * _SWITCH) for k, b in enumerate(_BETA))


def _baranov_horizontal(n, Hg, Tv, xp=SYMBOLIC):
    """``n sqrt(H) int_0^theta sqrt(cosh t) dt``, ``theta = asinh(Tv/H)`` (odd in ``Tv``)."""
    a = xp.fabs(Tv)
    T = xp.sqrt(Hg**2 + a**2)
    theta = xp.asinh(a / Hg)
    clipped = xp.fmin(theta, _SWITCH)
    small = 0
    for xi, wi in zip(_GL_X, _GL_W):
        small = small + float(wi) * xp.sqrt(xp.cosh(clipped * (1 + float(xi)) / 2))
    small = xp.sqrt(Hg) * clipped / 2 * small
    r2 = (Hg / (T + a)) ** 2                    # e^(-2 theta)
    series = 0
    for b in reversed(_BETA):
        series = series * r2 + b
    large = xp.sqrt(Hg) * _SERIES_CONSTANT + 2 ** -0.5 * xp.sqrt(T + a) * series
    return xp.sign(Tv) * n * xp.where(theta <= _SWITCH, small, large)
