"""Stretch laws of a line: how much an element lengthens under its effective tension.

A line element of unstretched length ``ds0`` under tension ``T`` has the stretched length
``ds = (1 + eps(T)) ds0``. Three laws are modelled:

- **Hooke** (steel chain and wire): ``eps = T / EA``, parameter the compliance ``1/EA``;
- **Baranov** (plant-fibre ropes; Alekseev):
  ``eps = n sqrt(T)``, parameter ``n`` [N^-1/2];
- **table** (synthetic ropes: polyester, nylon, HMPE): the strain at ``rows`` tensions,
  interpolated by the monotone piecewise-cubic Hermite interpolant of Fritsch and Carlson
  (``monotone_cubic``, PCHIP: the slopes of ``scipy.interpolate.PchipInterpolator``, an
  end slope scipy would set to zero kept positive, :func:`pchip_slopes`) or by straight
  lines between the rows (``linear``, MoorDyn's own reading of a curve file), continued
  linearly with the end slopes outside the table. The cubic strain is continuous with its
  first derivative, so the tangent stiffness ``dT/deps`` that Newton's method sees is
  continuous; the linear one has a kink at every row. Both are finite everywhere.
  Parameters: the strains, then the tensions; the number of rows and the interpolation
  are structure.

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
- table: on each cubic piece (a chord is a cubic of zero ``a2, a3``) ``eps = a0 + a1 T + a2 T^2 + a3 T^3`` and
  ``int eps(H cosh th) dth = a0 th + a1 T_v + a2 (H^2 th + T_v T)/2 + a3 (H^2 T_v + T_v^3/3)``
  (from the antiderivatives of ``cosh^k``), summed over the pieces the tension passes
  through; the piece is selected by comparisons inside the graph.

Every function takes the law's structure (:class:`StretchModel`) and its parameters (a
sequence of floats or CasADi SX scalars) and builds the same expression for floats and
symbols (``casadi.if_else``, never a Python ``if`` on a value), so a law's parameters can be
problem parameters: a sweep, a sensitivity or an optimisation changes them without a rebuild.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import casadi as ca
import numpy as np

from .stretch_baranov import _baranov_horizontal
from .stretch_ops import _T_FLOOR, ARRAYS, SYMBOLIC, _root
from .stretch_table import _Table, pchip_slopes

__all__ = ["StretchModel", "Law", "HOOKE", "BARANOV", "TABLE", "MODELS", "MONOTONE_CUBIC",
           "LINEAR", "INTERPOLATIONS", "strain",
           "compliance", "energy", "mean_strain", "horizontal", "descent", "pchip_slopes",
           "law_function", "evaluate", "NumericLaw", "law_model", "numeric_law"]

HOOKE, BARANOV, TABLE = "hooke", "baranov", "table"
MODELS = (HOOKE, BARANOV, TABLE)
MONOTONE_CUBIC, LINEAR = "monotone_cubic", "linear"
#: How a table law interpolates between its rows.
INTERPOLATIONS = (MONOTONE_CUBIC, LINEAR)

#: Newton steps of the descent equation (see :meth:`Law.descent`) from its midpoint start;
#: one more for a table of chords, whose kinks make a step that crosses a row only linear.
_DESCENT_STEPS = 3


def _descent_steps(model) -> int:
    return _DESCENT_STEPS + (model.name == TABLE and model.interpolation == LINEAR)


@dataclass(frozen=True)
class StretchModel:
    """The structure of a stretch law: which law, and for a table its number of rows.

    Attributes
    ----------
    name : {"hooke", "baranov", "table"}
    rows : int
        Rows of a table law (at least 2; the first is (0, 0)); 0 for the others.
    interpolation : {"monotone_cubic", "linear"}
        How a table law runs between its rows (ignored by the other laws).
    """

    name: str
    rows: int = 0
    interpolation: str = MONOTONE_CUBIC

    def __post_init__(self):
        if self.name not in MODELS:
            raise ValueError(f"stretch model {self.name!r}: must be one of {', '.join(MODELS)}")
        if (self.name == TABLE) != (self.rows >= 2):
            raise ValueError(f"a table law needs at least 2 rows, other laws none "
                             f"(got {self.name!r} with {self.rows} rows)")
        if self.interpolation not in INTERPOLATIONS:
            raise ValueError(f"interpolation {self.interpolation!r}: must be one of "
                             f"{', '.join(INTERPOLATIONS)}")

    @property
    def n_params(self) -> int:
        """Length of the parameter vector: 1 (compliance 1/EA, or n), 2 rows for a table."""
        return 2 * self.rows if self.name == TABLE else 1

    @property
    def tag(self) -> str:
        if self.name != TABLE:
            return self.name
        return f"table{self.rows}" + ("_linear" if self.interpolation == LINEAR else "")


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
        self._table = (_Table(model.rows, self.params, xp, model.interpolation == LINEAR)
                       if model.name == TABLE else None)

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
        up to 30 % (four for a table of chords: a step across a row converges linearly). Hooke has the closed form
        ``delta = 2 rise / ((1 + cH) + sqrt((1 + cH)^2 + 2 c rise))``.
        """
        if self.model.name == HOOKE:
            c = self.params[0]
            return 2 * rise / ((1 + c * H) + self.xp.sqrt((1 + c * H) ** 2 + 2 * c * rise))
        delta = rise / (1 + self.strain(H + rise / 2))
        for _ in range(_descent_steps(self.model)):
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
    for _ in range(_descent_steps(law.model)):
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


def law_model(line_type) -> StretchModel | None:
    """The :class:`StretchModel` of a line type (of :mod:`moorsolve.model`) with a law
    other than Hooke's, else None."""
    law = line_type.stretch
    return None if law is None else law.structure()


def numeric_law(line_type) -> NumericLaw | None:
    """The line type's law as a :class:`NumericLaw` for profiles (None for Hooke lines)."""
    model = law_model(line_type)
    return None if model is None else NumericLaw(model, line_type.stretch.parameters())
