"""The arithmetic a stretch law is written in: one set of operations for CasADi graphs,
one for numpy arrays, so each law is written once and evaluated both ways; and the selector
that picks a table piece in either."""

from __future__ import annotations

import casadi as ca
import numpy as np


#: Tension [N] below which a square root of the tension is continued linearly, so that its
#: derivative stays finite at zero tension (a slack Baranov rope); exact above it.
_T_FLOOR = 1e-9


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
