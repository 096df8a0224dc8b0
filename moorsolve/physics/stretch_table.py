"""The table stretch law: pieces of strain against tension (monotone cubic or linear), with
their exact integrals along a catenary (see :mod:`moorsolve.physics.stretch`)."""

from __future__ import annotations

from .stretch_ops import _T_FLOOR, SYMBOLIC


#: An end slope below this share of its secant is a rigid rope to every digit that matters:
#: the trend is taken instead (see :func:`pchip_slopes`).
_RIGID = 1e-9


def pchip_slopes(T, e, xp=SYMBOLIC):
    """Slopes ``d eps / d T`` at the table's rows: scipy's ``PchipInterpolator``, positive.

    ``T`` and ``e`` strictly increasing, so every secant ``delta_k`` is positive. Interior
    rows: the weighted harmonic mean of the two secants (Fritsch and Butland). End rows:
    the one-sided three-point estimate, as scipy takes it, wherever it is positive (above
    ``1e-9 delta``; for increasing rows scipy's bound of ``3 delta`` never binds). Where
    scipy would set it to zero or nearly (the secants change by a factor of about two or
    more at the end) the slope
    continuing its neighbour's trend, ``delta^2 / d_next`` (at most ``3 delta``, the
    Fritsch-Carlson bound for monotonicity), is taken instead: a zero end slope would make
    the rope rigid beyond the table, where the law continues with that slope. Two rows:
    the secant.
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
        trend = xp.fmin(m0 * m0 / d_next, 3 * m0)
        return xp.where(three_point > _RIGID * m0, three_point, trend)

    d[0] = end(h[0], h[1], delta[0], delta[1], d[1])
    d[-1] = end(h[-1], h[-2], delta[-1], delta[-2], d[-2])
    return d


class _Table:
    """The pieces of a table law, built once per evaluation site from its parameters.

    Piece ``k`` (``0 <= k < rows - 1``) is the Hermite cubic (or, ``linear``, the chord) on
    ``[T_k, T_k+1]``; piece ``rows - 1`` is the linear continuation beyond the last row.
    Local form on a piece: ``eps = e + d t + c2 t^2 + c3 t^3`` with ``t = T - T_k``
    (``c2 = c3 = 0`` on a chord). Below the first row the law continues with the first
    piece's slope at ``T_0``.
    """

    def __init__(self, rows: int, params, xp=SYMBOLIC, linear: bool = False):
        self.xp = xp
        e = list(params[:rows])
        T = list(params[rows:2 * rows])
        self.T, self.e = T, e
        self.local = []
        Q = [0]                   # prefix integrals: Q[k] = int_0^T_k eps
        if linear:
            delta = [(e[k + 1] - e[k]) / (T[k + 1] - T[k]) for k in range(rows - 1)]
            self.d = [delta[0]] + delta          # d[0]: below the table, d[-1]: beyond it
            for k in range(rows - 1):
                self.local.append((e[k], delta[k], 0, 0))
                Q.append(Q[-1] + (T[k + 1] - T[k]) * (e[k] + e[k + 1]) / 2)
        else:
            d = pchip_slopes(T, e, xp)
            self.d = d
            for k in range(rows - 1):
                h = T[k + 1] - T[k]
                delta = (e[k + 1] - e[k]) / h
                c2 = (3 * delta - 2 * d[k] - d[k + 1]) / h
                c3 = (d[k] + d[k + 1] - 2 * delta) / h**2
                self.local.append((e[k], d[k], c2, c3))
                # Hermite: h (e0 + e1)/2 + h^2 (d0 - d1)/12 over the whole piece.
                Q.append(Q[-1] + h * (e[k] + e[k + 1]) / 2 + h**2 * (d[k] - d[k + 1]) / 12)
        self.local.append((e[-1], self.d[-1], 0, 0))
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
