"""Stretch laws of a line: how much an element lengthens under its effective tension.

A line element of unstretched length ``ds0`` under tension ``T`` has the stretched length
``ds = (1 + eps(T)) ds0``. Three laws are modelled:

- **Hooke** (steel chain and wire): ``eps = T / EA``, parameter the compliance ``1/EA``;
- **Baranov** (plant-fibre ropes; Alekseev, seed 003, REFERENCE.md section 5):
  ``eps = n sqrt(T)``, parameter ``n`` [N^-1/2];
- **table** (synthetic ropes: polyester, nylon, HMPE): the strain at ``rows`` tensions,
  interpolated by the monotone piecewise-cubic Hermite interpolant of Fritsch and Carlson
  (PCHIP: the interior slopes of ``scipy.interpolate.PchipInterpolator``; end slopes kept
  positive, :func:`pchip_slopes`), continued linearly with the end slopes outside the
  table. The strain is then continuous with its first derivative, so the tangent stiffness
  ``dT/deps`` that Newton's method sees is continuous, and finite everywhere.
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
from functools import cached_property, lru_cache

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

#: Newton steps of the descent equation (see :meth:`Law.descent`) from its midpoint start.
_DESCENT_STEPS = 3


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


class _Symbolic:
    """The operations the laws use, on floats and CasADi SX alike (graph building)."""

    fmax, fmin, sqrt = staticmethod(ca.fmax), staticmethod(ca.fmin), staticmethod(ca.sqrt)
    asinh, cosh = staticmethod(ca.asinh), staticmethod(ca.cosh)
    sign, fabs = staticmethod(ca.sign), staticmethod(ca.fabs)

    @staticmethod
    def where(cond, a, b):
        return ca.if_else(cond, a, b)

    @staticmethod
    def step(cond):
        return ca.if_else(cond, 1, 0)

    def selector(self, x, breaks):
        return _NestedSelector([self.step(x >= b) for b in breaks[1:]])


class _Arrays:
    """The same operations on numpy arrays (profiles and reports: no CasADi calls)."""

    fmax, fmin, sqrt = staticmethod(np.maximum), staticmethod(np.minimum), staticmethod(np.sqrt)
    asinh, cosh = staticmethod(np.arcsinh), staticmethod(np.cosh)
    sign, fabs, where = staticmethod(np.sign), staticmethod(np.abs), staticmethod(np.where)

    @staticmethod
    def step(cond):
        return np.asarray(cond, dtype=float)

    @staticmethod
    def selector(x, breaks):
        return _IndexSelector(x, breaks)


SYMBOLIC, ARRAYS = _Symbolic(), _Arrays()


def _root(T, xp=SYMBOLIC):
    """``sqrt(T)`` for ``T >= 1e-9 N``, continued linearly below (finite derivative at 0)."""
    return T / xp.sqrt(xp.fmax(T, _T_FLOOR))


class _NestedSelector:
    """Picks ``values[j]``, ``j`` the piece of ``x`` among ascending breaks, in a graph: from
    the nested indicators ``x >= breaks[k]`` as a sum of one-hot terms, so that the value is
    picked exactly (a telescoping sum ``v0 + sum (v_k - v_k-1)`` would lose a small value
    beside a large one)."""

    def __init__(self, indicators):
        self.indicators = indicators
        self.index = sum(indicators, 0)

    def __call__(self, values):
        ind = self.indicators
        out = values[0] * (1 - ind[0]) if ind else values[0]
        for k, flag in enumerate(ind, start=1):
            nxt = ind[k] if k < len(ind) else 0
            out = out + (flag - nxt) * values[k]
        return out


class _IndexSelector:
    """The same on numpy arrays, by integer indexing (on floats, by a plain index)."""

    def __init__(self, x, breaks):
        self.scalar = isinstance(x, (float, int)) and all(isinstance(b, (float, int))
                                                          for b in breaks)
        if self.scalar:
            self.index = sum(int(x >= b) for b in breaks[1:])
            return
        x = np.asarray(x, dtype=float)
        self.index = sum((x >= np.asarray(b)).astype(int) for b in breaks[1:]) + 0 * x.astype(int)

    def __call__(self, values):
        if self.scalar:
            return values[self.index]
        if all(isinstance(v, (float, int)) for v in values):
            return np.asarray(values, dtype=float)[self.index]
        stacked = np.stack(np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values)))
        shape = np.broadcast_shapes(stacked.shape[1:], np.shape(self.index))
        pad = (1,) * (len(shape) - stacked.ndim + 1)
        stacked = np.broadcast_to(stacked.reshape(stacked.shape[:1] + pad + stacked.shape[1:]),
                                  stacked.shape[:1] + shape)
        index = np.broadcast_to(self.index, shape)
        return np.take_along_axis(stacked, index[None, ...], axis=0)[0]


# ---- the table law: PCHIP pieces -----------------------------------------------------------


def pchip_slopes(T, e, xp=SYMBOLIC):
    """Slopes ``d eps / d T`` at the table's rows: Fritsch-Carlson (PCHIP), positive ends.

    ``T`` and ``e`` strictly increasing, so every secant ``delta_k`` is positive. Interior
    rows: the weighted harmonic mean of the two secants (Fritsch and Butland; scipy's
    ``PchipInterpolator``). End rows: scipy's one-sided three-point estimate, but kept
    between ``delta^2 / d_next`` (the slope continuing the trend of its neighbour's) and
    ``3 delta`` (Fritsch-Carlson's bound for monotonicity), where scipy would set it to
    zero: a zero end slope would make the rope infinitely stiff beyond the table, where the
    law continues with that slope. Two rows: the secant.
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

    def end(h0, h1, m0, m1, d_next):
        three_point = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
        return xp.fmin(xp.fmax(three_point, m0 * m0 / d_next), 3 * m0)

    d[0] = end(h[0], h[1], delta[0], delta[1], d[1])
    d[-1] = end(h[-1], h[-2], delta[-1], delta[-2], d[-2])
    return d


class _Table:
    """The pieces of a table law, built once per evaluation site from its parameters.

    Piece ``k`` (``0 <= k < rows - 1``) is the Hermite cubic on ``[T_k, T_k+1]``; piece
    ``rows - 1`` is the linear continuation beyond the last row. Local form on a piece:
    ``eps = e + d t + c2 t^2 + c3 t^3`` with ``t = T - T_k``.
    """

    def __init__(self, rows: int, params, xp=SYMBOLIC):
        self.xp = xp
        e = list(params[:rows])
        T = list(params[rows:2 * rows])
        d = pchip_slopes(T, e, xp)
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

    def piece(self, x):
        """The selector of ``x``'s piece, its local coefficients and its first tension."""
        pick = self.xp.selector(x, self.T)
        coef = [pick([c[i] for c in self.local]) for i in range(4)]
        return pick, coef, pick(self.T)

    def strain(self, x):
        _, (e, d, c2, c3), Tk = self.piece(x)
        t = x - Tk
        inside = e + t * (d + t * (c2 + t * c3))
        # Below the first row (compression, lumped-node lines only): the first slope.
        return self.xp.where(x < self.T[0], self.e[0] + self.d[0] * (x - self.T[0]), inside)

    def compliance(self, x):
        _, (e, d, c2, c3), Tk = self.piece(x)
        t = x - Tk
        return self.xp.where(x < self.T[0], self.d[0] + 0 * t, d + t * (2 * c2 + 3 * t * c3))

    @staticmethod
    def _local_mean(coef, ta, tb):
        """Mean of the local cubic over ``[ta, tb]`` (local coordinates), no cancellation."""
        e, d, c2, c3 = coef
        return (e + d * (ta + tb) / 2 + c2 * (ta * ta + ta * tb + tb * tb) / 3
                + c3 * (ta + tb) * (ta * ta + tb * tb) / 4)

    def mean(self, a, b):
        """Mean strain over ``[a, b]`` (``0 <= a <= b``), exact on every piece."""
        pa, ca_, Ta = self.piece(a)
        pb, cb, Tb = self.piece(b)
        ja, jb = pa.index, pb.index
        T_next = pa(self.T[1:] + [self.T[-1]])    # the end of a's piece (a's is not last)
        Q_next = pa(self.Q[1:] + [self.Q[-1]])
        Q_b = pb(self.Q)
        same = self._local_mean(ca_, a - Ta, b - Ta)
        first = (T_next - a) * self._local_mean(ca_, a - Ta, T_next - Ta)
        last = (b - Tb) * self._local_mean(cb, 0, b - Tb)
        width = self.xp.where(b > a, b - a, 1)
        return self.xp.where(ja == jb, same, (first + (Q_b - Q_next) + last) / width)

    def energy(self, x):
        pick, coef, Tk = self.piece(x)
        return pick(self.Q) + (x - Tk) * self._local_mean(coef, 0, x - Tk)

    def horizontal(self, Hg, Tvs):
        """``int_0^asinh(Tv/Hg) eps(Hg cosh th) dth`` at each of ``Tvs`` (odd in ``Tv``)."""
        xp = self.xp
        breaks = [xp.fmax(Tk, Hg) for Tk in self.T]
        glob = [_global(c, Tk) for c, Tk in zip(self.local, self.T)]

        def G(coef, c, tv, th):
            a0, a1, a2, a3 = coef
            return (a0 * th + a1 * tv + a2 * (Hg**2 * th + tv * c) / 2
                    + a3 * (Hg**2 * tv + tv**3 / 3))

        # The antiderivative at every breakpoint above H (a piece below H is empty); the
        # vertical tension there is sqrt(b^2 - H^2), exact above 1e-9 N, and the angle
        # asinh(tv/H).
        tvb, thb = [], []
        for b in breaks:
            x = xp.fmax((b - Hg) * (b + Hg), 0)
            tvb.append(x / xp.sqrt(xp.fmax(x, _T_FLOOR**2)))
            thb.append(xp.asinh(tvb[-1] / Hg))
        # D[j] = int over the pieces below j, less piece j's antiderivative at its start.
        D, total = [], 0
        for k in range(len(breaks)):
            D.append(total - G(glob[k], breaks[k], tvb[k], thb[k]))
            if k + 1 < len(breaks):
                total = total + G(glob[k], breaks[k + 1], tvb[k + 1], thb[k + 1]) \
                    - G(glob[k], breaks[k], tvb[k], thb[k])
        out = []
        for Tv in Tvs:
            a = xp.fabs(Tv)
            T = xp.sqrt(Hg**2 + a**2)
            pick = xp.selector(T, breaks)
            coef = [pick([g[i] for g in glob]) for i in range(4)]
            value = pick(D) + G(coef, T, a, xp.asinh(a / Hg))
            out.append(xp.sign(Tv) * value)
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


# ---- the laws ------------------------------------------------------------------------------


class Law:
    """A stretch law bound to its parameters: build once per block, then evaluate.

    The table's pieces (slopes, cubic coefficients, prefix integrals) are built once here
    and shared by every evaluation, so the graph holds them once.
    """

    def __init__(self, model: StretchModel, params, xp=SYMBOLIC):
        self.model = model
        self.params = list(params)
        self.xp = xp
        if len(self.params) != model.n_params:
            raise ValueError(f"{model.tag} law takes {model.n_params} parameters, "
                             f"got {len(self.params)}")
        self._table = _Table(model.rows, self.params, xp) if model.name == TABLE else None

    def strain(self, T):
        """Strain ``eps(T)`` [-] at effective tension ``T`` [N].

        Negative tensions (a compressed element of a lumped-node line) continue each law
        oddly: Hooke linearly, Baranov as ``-n sqrt(-T)``, a table with its first slope.
        """
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] * T
        if name == BARANOV:
            return p[0] * T / self.xp.sqrt(self.xp.fmax(self.xp.fabs(T), _T_FLOOR))
        return self._table.strain(T)

    def compliance(self, T):
        """Tangent compliance ``d eps / d T`` [1/N]; its inverse is the tangent stiffness."""
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] + 0 * T
        if name == BARANOV:
            return p[0] / (2 * self.xp.sqrt(self.xp.fmax(self.xp.fabs(T), _T_FLOOR)))
        return self._table.compliance(T)

    def energy(self, T):
        """``int_0^T eps(t) dt`` [N] for ``T >= 0``."""
        name, p = self.model.name, self.params
        if name == HOOKE:
            return p[0] * T * T / 2
        if name == BARANOV:
            return 2 * p[0] * self.xp.fmax(T, 0) ** 1.5 / 3
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
            ra, rb = _root(a, self.xp), _root(b, self.xp)
            s = ra + rb
            return 2 * p[0] * (s - ra * rb / self.xp.fmax(s, _T_FLOOR)) / 3
        return self._table.mean(self.xp.fmin(a, b), self.xp.fmax(a, b))

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
            out = [_baranov_horizontal(p[0], Hg, Tv, self.xp) for Tv in Tvs]
        else:
            out = self._table.horizontal(Hg, Tvs)
        return out[0] if len(out) == 1 else tuple(out)

    def descent(self, H, rise):
        """Tension gain ``delta = T - H`` [N] of a catenary rising ``rise / w`` from its vertex.

        Solves ``delta (1 + mean(H, H + delta)) = rise`` (``rise = w h >= 0`` [N]: the
        weight per length times the height). The inextensible gain is ``rise`` itself; the
        stretch makes it smaller. Newton's method, unrolled into the graph, from the
        midpoint estimate ``rise / (1 + eps(H + rise/2))`` (relative error about
        ``eps^2 / 2``); with quadratic convergence three steps reach round-off for strains
        up to 30 %. Hooke has the closed form
        ``delta = 2 rise / ((1 + cH) + sqrt((1 + cH)^2 + 2 c rise))``.
        """
        if self.model.name == HOOKE:
            c = self.params[0]
            return 2 * rise / ((1 + c * H) + self.xp.sqrt((1 + c * H) ** 2 + 2 * c * rise))
        delta = rise / (1 + self.strain(H + rise / 2))
        for _ in range(_DESCENT_STEPS):
            f = delta * (1 + self.mean(H, H + delta)) - rise
            delta = self.xp.fmax(delta - f / (1 + self.strain(H + delta)), 0)
        return delta

    def drop(self, T, rise):
        """Tension drop ``delta = T - T_c`` [N] down a catenary from tension ``T`` over a
        rise of ``rise / w``: ``delta (1 + mean(T - delta, T)) = rise``, with ``0 <= delta
        <= T`` (``T_c = 0`` where the line cannot fall that far). The mirror of
        :meth:`descent` (here the upper end's tension is known), by the same unrolled Newton
        steps from the midpoint estimate; Hooke's closed form is
        ``T_c = 2 r / (1 + sqrt(1 + 2 c r))``, ``r = T + c T^2/2 - rise``.
        """
        if self.model.name == HOOKE:
            c = self.params[0]
            r = self.xp.fmax(T + c * T**2 / 2 - rise, 0)
            return T - 2 * r / (1 + self.xp.sqrt(1 + 2 * c * r))
        return _drop(self, T, rise)


def _drop(law, T, rise):
    """See :meth:`Law.drop`."""
    xp = law.xp
    delta = xp.fmin(xp.fmax(rise / (1 + law.strain(xp.fmax(T - rise / 2, 0))), 0), T)
    for _ in range(_DESCENT_STEPS):
        f = delta * (1 + law.mean(T - delta, T)) - rise
        delta = xp.fmin(xp.fmax(delta - f / (1 + law.strain(T - delta)), 0), T)
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


@lru_cache(maxsize=256)
def _mapped(model: StretchModel, n: int) -> ca.Function:
    return law_function(model).map(n)


def evaluate(model: StretchModel, params, T, T2=None, Tv=0.0, Hg=1.0) -> dict:
    """The law on numpy arrays (broadcast together), for profiles and reports.

    Returns ``strain``, ``compliance`` and ``energy`` at ``T``, ``mean`` over ``[T, T2]``
    (``T2`` defaults to ``T``) and ``horizontal`` at ``(Hg, Tv)``.
    """
    T2 = T if T2 is None else T2
    arrays = np.broadcast_arrays(*(np.asarray(v, float) for v in (T, T2, Tv, Hg)))
    shape = arrays[0].shape
    n = max(arrays[0].size, 1)
    f = _mapped(model, n)
    out = f(*(a.reshape(1, -1) for a in arrays),
            np.repeat(np.asarray(params, float).reshape(-1, 1), n, axis=1))
    return {k: np.asarray(v).reshape(shape) for k, v in zip(_OUTPUTS, out)}


@dataclass(frozen=True)
class NumericLaw:
    """A law with float parameters on numpy arrays (profiles, reports, starts): the same
    expressions as the graph's, evaluated by numpy."""

    model: StretchModel
    params: tuple

    @cached_property
    def _law(self) -> Law:
        return Law(self.model, [float(v) for v in self.params], ARRAYS)

    @cached_property
    def bound(self) -> Law:
        """The law with CasADi operations on its float parameters, for the blocks' own
        functions (:func:`~moorsolve.physics.catenary.air_part`) evaluated on floats."""
        return Law(self.model, [float(v) for v in self.params])

    def _run(self, method, *args):
        if all(isinstance(a, (float, int)) or np.ndim(a) == 0 for a in args):
            args = [float(a) for a in args]
            with np.errstate(all="ignore"):
                return float(getattr(self._law, method)(*args))
        args = [float(a) if np.ndim(a) == 0 else np.asarray(a, dtype=float) for a in args]
        shape = np.broadcast_shapes(*(np.shape(a) for a in args))
        with np.errstate(all="ignore"):           # the branch np.where does not take
            out = getattr(self._law, method)(*args)
        return np.broadcast_to(out, shape) + 0.0

    def strain(self, T):
        return self._run("strain", T)

    def compliance(self, T):
        return self._run("compliance", T)

    def energy(self, T):
        return self._run("energy", T)

    def mean(self, a, b):
        return self._run("mean", a, b)

    def horizontal(self, Hg, Tv):
        return self._run("horizontal", Hg, Tv)

    def descent(self, H: float, rise: float) -> float:
        """:meth:`Law.descent` on floats."""
        return float(self._run("descent", H, rise))

    def secant_ea(self, T: float) -> float:
        """``T / eps(T)`` [N]: the stiffness of a Hooke line that stretches as much at ``T``."""
        return float(T / self.strain(T))
