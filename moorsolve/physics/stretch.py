"""Stretch laws of a line: how much an element lengthens under its effective tension.

A line element of unstretched length ``ds0`` under tension ``T`` has the stretched length
``ds = (1 + eps(T)) ds0``. Three laws are modelled:

- **Hooke** (steel chain and wire): ``eps = T / EA``, parameter the compliance ``1/EA``;
- **Baranov** (plant-fibre ropes; Alekseev, seed 003, REFERENCE.md section 5):
  ``eps = n sqrt(T)``, parameter ``n`` [N^-1/2];
- **table** (synthetic ropes: polyester, nylon, HMPE): the strain at ``rows`` tensions,
  interpolated by the monotone piecewise-cubic Hermite interpolant of Fritsch and Carlson
  (PCHIP, the slopes of ``scipy.interpolate.PchipInterpolator``), continued linearly with
  the end slopes outside the table. The strain is then continuous with its first
  derivative, so the tangent stiffness ``dT/deps`` that Newton's method sees is continuous.
  Parameters: the strains, then the tensions; the number of rows is structure.

Exact along the catenary
------------------------
The stretch of a suspended line is the strain integrated along it, never a mean strain
applied to the length. With the vertical tension ``T_v`` as the variable along a catenary
of horizontal tension ``H`` and weight ``w`` (``ds0 = dT_v / w``, ``T = sqrt(H^2 + T_v^2)``):

- the vertical extent gains ``(1/w) int eps(T) dT`` (because ``T_v dT_v / T = dT``), which
  is ``(T_F - T_A)/w`` times :func:`mean_strain` over ``[T_A, T_F]``;
- the horizontal extent gains ``(H/w) int eps(H cosh th) dth`` (``T_v = H sinh th``), the
  difference of :func:`horizontal` between the two ends.

Each law has these integrals in closed form or to round-off:

- Hooke: ``mean = (a + b)/(2 EA)`` and ``horizontal = T_v / EA``;
- Baranov: ``mean = (2n/3)(a + sqrt(ab) + b)/(sqrt a + sqrt b)``; the horizontal integral
  ``n sqrt(H) int_0^th sqrt(cosh t) dt`` is an elliptic integral, evaluated by 16-point
  Gauss-Legendre quadrature for ``|th| <= 2`` (the integrand's nearest singularity is at
  ``i pi/2``, so the rule is exact to round-off there) and beyond by the convergent series
  ``sqrt(cosh t) = 2^-1/2 e^(t/2) sum_k binom(1/2, k) e^(-2kt)`` integrated term by term;
- table: on each cubic piece ``eps = a0 + a1 T + a2 T^2 + a3 T^3`` and
  ``int eps(H cosh th) dth = a0 th + a1 T_v + a2 (H^2 th + T_v T)/2 + a3 (H^2 T_v + T_v^3/3)``
  (from the antiderivatives of ``cosh^k``), summed over the pieces the tension passes
  through; the piece is selected by comparisons inside the graph.

Every function takes the law's structure (:class:`StretchModel`) and its parameters (a
sequence of floats or CasADi SX scalars) and builds the same expression for floats and
symbols (``casadi.if_else``, never a Python ``if`` on a value), so a law's parameters can be
problem parameters: a sweep, a sensitivity or an optimisation changes them without a rebuild.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import casadi as ca
import numpy as np

__all__ = ["StretchModel", "Law", "HOOKE", "BARANOV", "TABLE", "MODELS", "strain",
           "compliance", "energy", "mean_strain", "horizontal", "descent", "pchip_slopes",
           "law_function", "evaluate", "NumericLaw"]

HOOKE, BARANOV, TABLE = "hooke", "baranov", "table"
MODELS = (HOOKE, BARANOV, TABLE)

#: Tension [N] below which a square root of the tension is continued linearly, so that its
#: derivative stays finite at zero tension (a slack Baranov rope); exact above it.
_T_FLOOR = 1e-9

#: Newton steps of the descent equation (see :func:`descent`): quadratic convergence from a
#: point on the convex side; five steps reach round-off for strains up to 50 %.
_DESCENT_STEPS = 6


@dataclass(frozen=True)
class StretchModel:
    """The structure of a stretch law: which law, and for a table its number of rows.

    Attributes
    ----------
    name : {"hooke", "baranov", "table"}
    rows : int
        Rows of a table law (at least 2; the first is (0, 0)); 0 for the others.
    """

    name: str
    rows: int = 0

    def __post_init__(self):
        if self.name not in MODELS:
            raise ValueError(f"stretch model {self.name!r}: must be one of {', '.join(MODELS)}")
        if (self.name == TABLE) != (self.rows >= 2):
            raise ValueError(f"a table law needs at least 2 rows, other laws none "
                             f"(got {self.name!r} with {self.rows} rows)")

    @property
    def n_params(self) -> int:
        """Length of the parameter vector: 1 (compliance 1/EA, or n), 2 rows for a table."""
        return 2 * self.rows if self.name == TABLE else 1

    @property
    def tag(self) -> str:
        return f"table{self.rows}" if self.name == TABLE else self.name


# ---- helpers -----------------------------------------------------------------------------


def _root(T):
    """``sqrt(T)`` for ``T >= 1e-9 N``, continued linearly below (finite derivative at 0)."""
    return T / ca.sqrt(ca.fmax(T, _T_FLOOR))


def _select(indicators, values):
    """``values[j]`` where ``j`` is the number of true ``indicators`` (nested conditions)."""
    out = values[0]
    for k, ind in enumerate(indicators, start=1):
        out = out + ind * (values[k] - values[k - 1])
    return out


def _step(cond):
    return ca.if_else(cond, 1, 0)


# ---- the table law: PCHIP pieces -----------------------------------------------------------


def pchip_slopes(T, e):
    """Fritsch-Carlson slopes ``d eps / d T`` at the table's rows (``scipy``'s PCHIP).

    ``T`` strictly increasing, ``e`` strictly increasing (so every secant is positive and
    the interior slopes are weighted harmonic means of the secants). Two rows: the secant.
    """
    m = len(T)
    h = [T[k + 1] - T[k] for k in range(m - 1)]
    delta = [(e[k + 1] - e[k]) / h[k] for k in range(m - 1)]
    if m == 2:
        return [delta[0], delta[0]]
    d = [None] * m
    for k in range(1, m - 1):
        w1, w2 = 2 * h[k] + h[k - 1], h[k] + 2 * h[k - 1]
        d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])
    # One-sided three-point ends, kept of the secant's sign (zero otherwise).
    d[0] = ca.fmax(((2 * h[0] + h[1]) * delta[0] - h[0] * delta[1]) / (h[0] + h[1]), 0)
    d[-1] = ca.fmax(((2 * h[-1] + h[-2]) * delta[-1] - h[-1] * delta[-2]) / (h[-1] + h[-2]), 0)
    return d


class _Table:
    """The pieces of a table law, built once per evaluation site from its parameters.

    Piece ``k`` (``0 <= k < rows - 1``) is the Hermite cubic on ``[T_k, T_k+1]``; piece
    ``rows - 1`` is the linear continuation beyond the last row. Local form on a piece:
    ``eps = e + d t + c2 t^2 + c3 t^3`` with ``t = T - T_k``.
    """

    def __init__(self, rows: int, params):
        e = list(params[:rows])
        T = list(params[rows:2 * rows])
        d = pchip_slopes(T, e)
        self.T, self.e, self.d = T, e, d
        self.local = []
        for k in range(rows - 1):
            h = T[k + 1] - T[k]
            delta = (e[k + 1] - e[k]) / h
            c2 = (3 * delta - 2 * d[k] - d[k + 1]) / h
            c3 = (d[k] + d[k + 1] - 2 * delta) / h**2
            self.local.append((e[k], d[k], c2, c3))
        self.local.append((e[-1], d[-1], 0, 0))
        # Integral of each whole piece (Hermite: h (e0 + e1)/2 + h^2 (d0 - d1)/12) and the
        # prefix sums: Q[k] = int_0^T_k eps.
        Q = [0]
        for k in range(rows - 1):
            h = T[k + 1] - T[k]
            Q.append(Q[-1] + h * (e[k] + e[k + 1]) / 2 + h**2 * (d[k] - d[k + 1]) / 12)
        self.Q = Q

    def indicators(self, x, breaks):
        """Nested indicators ``x >= breaks[k]`` for k = 1.. (piece index = their count)."""
        return [_step(x >= b) for b in breaks[1:]]

    def piece(self, x):
        ind = self.indicators(x, self.T)
        coef = [_select(ind, [c[i] for c in self.local]) for i in range(4)]
        return ind, coef, _select(ind, self.T)

    def strain(self, x):
        ind, (e, d, c2, c3), Tk = self.piece(x)
        t = x - Tk
        inside = e + t * (d + t * (c2 + t * c3))
        # Below the first row (compression, lumped-node lines only): the first slope.
        return ca.if_else(x < self.T[0], self.e[0] + self.d[0] * (x - self.T[0]), inside)

    def compliance(self, x):
        ind, (e, d, c2, c3), Tk = self.piece(x)
        t = x - Tk
        return ca.if_else(x < self.T[0], self.d[0], d + t * (2 * c2 + 3 * t * c3))

    @staticmethod
    def _local_mean(coef, ta, tb):
        """Mean of the local cubic over ``[ta, tb]`` (local coordinates), no cancellation."""
        e, d, c2, c3 = coef
        return (e + d * (ta + tb) / 2 + c2 * (ta * ta + ta * tb + tb * tb) / 3
                + c3 * (ta + tb) * (ta * ta + tb * tb) / 4)

    def mean(self, a, b):
        """Mean strain over ``[a, b]`` (``0 <= a <= b``), exact on every piece."""
        ia, ca_, Ta = self.piece(a)
        ib, cb, Tb = self.piece(b)
        ja, jb = sum(ia, 0), sum(ib, 0)
        nxt = self.T[1:] + [self.T[-1]]
        T_next = _select(ia, nxt)              # the end of a's piece (a's piece is not last)
        Q_next = _select(ia, self.Q[1:] + [self.Q[-1]])
        Q_b = _select(ib, self.Q)
        same = self._local_mean(ca_, a - Ta, b - Ta)
        first = (T_next - a) * self._local_mean(ca_, a - Ta, T_next - Ta)
        last = (b - Tb) * self._local_mean(cb, 0, b - Tb)
        width = ca.if_else(b > a, b - a, 1)
        return ca.if_else(ja == jb, same, (first + (Q_b - Q_next) + last) / width)

    def energy(self, x):
        ind, coef, Tk = self.piece(x)
        return _select(ind, self.Q) + (x - Tk) * self._local_mean(coef, 0, x - Tk)

    def horizontal(self, Hg, Tvs):
        """``int_0^asinh(Tv/Hg) eps(Hg cosh th) dth`` at each of ``Tvs`` (odd in ``Tv``)."""
        breaks = [ca.fmax(Tk, Hg) for Tk in self.T]
        glob = [_global(c, Tk) for c, Tk in zip(self.local, self.T)]

        def G(coef, c, tv):
            a0, a1, a2, a3 = coef
            th = ca.asinh(tv / Hg)
            return (a0 * th + a1 * tv + a2 * (Hg**2 * th + tv * c) / 2
                    + a3 * (Hg**2 * tv + tv**3 / 3))

        # The antiderivative at every breakpoint above H (a piece below H is empty); the
        # vertical tension there is sqrt(b^2 - H^2), exact above 1e-9 N.
        tvb = []
        for b in breaks:
            x = ca.fmax((b - Hg) * (b + Hg), 0)
            tvb.append(x / ca.sqrt(ca.fmax(x, _T_FLOOR**2)))
        P = [0]
        for k in range(len(breaks) - 1):
            P.append(P[-1] + G(glob[k], breaks[k + 1], tvb[k + 1])
                     - G(glob[k], breaks[k], tvb[k]))
        starts = [G(g, b, tv) for g, b, tv in zip(glob, breaks, tvb)]
        out = []
        for Tv in Tvs:
            a = ca.fabs(Tv)
            T = ca.sqrt(Hg**2 + a**2)
            ind = self.indicators(T, breaks)
            coef = [_select(ind, [g[i] for g in glob]) for i in range(4)]
            value = _select(ind, P) + G(coef, T, a) - _select(ind, starts)
            out.append(ca.sign(Tv) * value)
        return out


def _global(coef, Tk):
    """Coefficients of ``eps = a0 + a1 T + a2 T^2 + a3 T^3`` from the local form at ``Tk``."""
    e, d, c2, c3 = coef
    return (e - Tk * (d - Tk * (c2 - Tk * c3)), d - Tk * (2 * c2 - 3 * Tk * c3),
            c2 - 3 * Tk * c3, c3)


# ---- Baranov: int sqrt(cosh t) dt ------------------------------------------------------------

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


def _baranov_horizontal(n, Hg, Tv):
    """``n sqrt(H) int_0^theta sqrt(cosh t) dt``, ``theta = asinh(Tv/H)`` (odd in ``Tv``)."""
    a = ca.fabs(Tv)
    T = ca.sqrt(Hg**2 + a**2)
    theta = ca.asinh(a / Hg)
    small = 0
    for xi, wi in zip(_GL_X, _GL_W):
        small = small + float(wi) * ca.sqrt(ca.cosh(ca.fmin(theta, _SWITCH) * (1 + float(xi)) / 2))
    small = ca.sqrt(Hg) * ca.fmin(theta, _SWITCH) / 2 * small
    r2 = (Hg / (T + a)) ** 2                    # e^(-2 theta)
    series = 0
    for b in reversed(_BETA):
        series = series * r2 + b
    large = ca.sqrt(Hg) * _SERIES_CONSTANT + 2 ** -0.5 * ca.sqrt(T + a) * series
    return ca.sign(Tv) * n * ca.if_else(theta <= _SWITCH, small, large)


# ---- the laws ------------------------------------------------------------------------------


class Law:
    """A stretch law bound to its parameters: build once per block, then evaluate.

    The table's pieces (slopes, cubic coefficients, prefix integrals) are built once here
    and shared by every evaluation, so the graph holds them once.
    """

    def __init__(self, model: StretchModel, params):
        self.model = model
        self.params = list(params)
        if len(self.params) != model.n_params:
            raise ValueError(f"{model.tag} law takes {model.n_params} parameters, "
                             f"got {len(self.params)}")
        self._table = _Table(model.rows, self.params) if model.name == TABLE else None

    def strain(self, T):
        """Strain ``eps(T)`` [-] at effective tension ``T`` [N].

        Negative tensions (a compressed element of a lumped-node line) continue each law
        oddly: Hooke linearly, Baranov as ``-n sqrt(-T)``, a table with its first slope.
        """
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] * T
        if name == BARANOV:
            return p[0] * T / ca.sqrt(ca.fmax(ca.fabs(T), _T_FLOOR))
        return self._table.strain(T)

    def compliance(self, T):
        """Tangent compliance ``d eps / d T`` [1/N]; its inverse is the tangent stiffness."""
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] + 0 * T
        if name == BARANOV:
            return p[0] / (2 * ca.sqrt(ca.fmax(ca.fabs(T), _T_FLOOR)))
        return self._table.compliance(T)

    def energy(self, T):
        """``int_0^T eps(t) dt`` [N] for ``T >= 0``."""
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] * T * T / 2
        if name == BARANOV:
            return 2 * p[0] * ca.fmax(T, 0) ** 1.5 / 3
        return self._table.energy(T)

    def mean(self, a, b):
        """Mean strain between tensions ``a, b >= 0``: ``int_a^b eps dT / (b - a)``.

        Symmetric in ``a, b``; written without cancellation, so it is exact also for
        ``|b - a|`` far below ``b``; it is ``eps(a)`` when ``a = b``.
        """
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] * (a + b) / 2
        if name == BARANOV:
            ra, rb = _root(a), _root(b)
            s = ra + rb
            return 2 * p[0] * (s - ra * rb / ca.fmax(s, _T_FLOOR)) / 3
        return self._table.mean(ca.fmin(a, b), ca.fmax(a, b))

    def horizontal(self, Hg, *Tvs):
        """``Psi(T_v) = int_0^asinh(T_v/H) eps(H cosh th) dth`` [-] at each ``T_v``.

        Odd in ``T_v``. The stretch adds ``(H/w) [Psi(T_v2) - Psi(T_v1)]`` to the horizontal
        extent of a catenary between vertical tensions ``T_v1`` and ``T_v2``. ``Hg`` is the
        horizontal tension floored away from zero (the caller multiplies by the exact
        ``H``). Returns one value per ``T_v`` (a tuple when several are given).
        """
        name, p = self.model.name, self.params
        if name == HOOKE:
            out = [p[0] * Tv for Tv in Tvs]
        elif name == BARANOV:
            out = [_baranov_horizontal(p[0], Hg, Tv) for Tv in Tvs]
        else:
            out = self._table.horizontal(Hg, Tvs)
        return out[0] if len(out) == 1 else tuple(out)

    def descent(self, H, rise):
        """Tension gain ``delta = T - H`` [N] of a catenary rising ``rise / w`` from its vertex.

        Solves ``delta (1 + mean(H, H + delta)) = rise`` (``rise = w h >= 0`` [N]: the
        weight per length times the height). The inextensible gain is ``rise`` itself; the
        stretch makes it smaller. Newton's method from ``delta = rise``, where the function
        (increasing, and convex for a stiffening or Hooke rope) lies above its root; the
        steps are unrolled into the graph. Hooke has the closed form
        ``delta = 2 rise / ((1 + cH) + sqrt((1 + cH)^2 + 2 c rise))``.
        """
        if self.model.name == HOOKE:
            c = self.params[0]
            return 2 * rise / ((1 + c * H) + ca.sqrt((1 + c * H) ** 2 + 2 * c * rise))
        delta = rise
        for _ in range(_DESCENT_STEPS):
            f = delta * (1 + self.mean(H, H + delta)) - rise
            delta = ca.fmax(delta - f / (1 + self.strain(H + delta)), 0)
        return delta


def strain(model: StretchModel, T, params):
    """Strain at tension ``T``; see :meth:`Law.strain`."""
    return Law(model, params).strain(T)


def compliance(model: StretchModel, T, params):
    """Tangent compliance at ``T``; see :meth:`Law.compliance`."""
    return Law(model, params).compliance(T)


def energy(model: StretchModel, T, params):
    """``int_0^T eps``; see :meth:`Law.energy`."""
    return Law(model, params).energy(T)


def mean_strain(model: StretchModel, a, b, params):
    """Mean strain over ``[a, b]``; see :meth:`Law.mean`."""
    return Law(model, params).mean(a, b)


def horizontal(model: StretchModel, Hg, Tv, params):
    """The horizontal stretch integral at ``Tv``; see :meth:`Law.horizontal`."""
    return Law(model, params).horizontal(Hg, Tv)


def descent(model: StretchModel, H, rise, params):
    """Tension gain of a catenary rising from its vertex; see :meth:`Law.descent`."""
    return Law(model, params).descent(H, rise)


# ---- numeric evaluation -------------------------------------------------------------------

_OUTPUTS = ("strain", "compliance", "energy", "mean", "horizontal")


@lru_cache(maxsize=None)
def law_function(model: StretchModel) -> ca.Function:
    """``(T, T2, Tv, Hg, p) -> (strain(T), compliance(T), energy(T), mean(T, T2),
    horizontal(Hg, Tv))`` as one ``casadi.Function``."""
    T, T2, Tv, Hg = (ca.SX.sym(n) for n in ("T", "T2", "Tv", "Hg"))
    p = ca.SX.sym("p", model.n_params)
    law = Law(model, ca.vertsplit(p))
    return ca.Function(f"stretch_{model.tag}", [T, T2, Tv, Hg, p],
                       [law.strain(T), law.compliance(T), law.energy(T), law.mean(T, T2),
                        law.horizontal(Hg, Tv)], ["T", "T2", "Tv", "Hg", "p"], list(_OUTPUTS))


def evaluate(model: StretchModel, params, T, T2=None, Tv=0.0, Hg=1.0) -> dict:
    """The law on numpy arrays (broadcast together), for profiles and reports.

    Returns ``strain``, ``compliance`` and ``energy`` at ``T``, ``mean`` over ``[T, T2]``
    (``T2`` defaults to ``T``) and ``horizontal`` at ``(Hg, Tv)``.
    """
    T2 = T if T2 is None else T2
    arrays = np.broadcast_arrays(*(np.asarray(v, float) for v in (T, T2, Tv, Hg)))
    shape = arrays[0].shape
    n = max(arrays[0].size, 1)
    f = law_function(model).map(n)
    out = f(*(a.reshape(1, -1) for a in arrays),
            np.repeat(np.asarray(params, float).reshape(-1, 1), n, axis=1))
    return {k: np.asarray(v).reshape(shape) for k, v in zip(_OUTPUTS, out)}


@dataclass(frozen=True)
class NumericLaw:
    """A law with float parameters, evaluated on numpy arrays (profiles, reports, starts)."""

    model: StretchModel
    params: tuple

    def strain(self, T):
        return evaluate(self.model, self.params, T)["strain"]

    def energy(self, T):
        return evaluate(self.model, self.params, T)["energy"]

    def mean(self, a, b):
        return evaluate(self.model, self.params, a, b)["mean"]

    def horizontal(self, Hg, Tv):
        return evaluate(self.model, self.params, 0.0, Tv=Tv, Hg=Hg)["horizontal"]

    def secant_ea(self, T: float) -> float:
        """``T / eps(T)`` [N]: the stiffness of a Hooke line that stretches as much at ``T``."""
        return float(T / self.strain(T))
