"""The upper- and lower-bound stiffness analysis that offshore standards ask for fibre ropes.

A fibre rope's stiffness is not one number: it grows with the mean load and with the
loading rate, and a new rope is softer than one that has been worked. API RP 2SM and
DNV-OS-E301 (Ch.2 Sec.2) ask for the mooring to be analysed with a lower and an upper bound
of the rope's stiffness and the worse answer taken for each quantity: the lower bound
(quasi-static, post-installation) usually gives the largest offset, the upper bound
(dynamic, storm) the largest line tension.

:func:`stiffness_bounds` solves the case twice, every line type that gives
``stiffness_bounds`` (line-type key, or a catalogue fibre rope) swapped for its lower and then
its upper bound, and reports per bound the offset, the yaw and every leg's tensions, and the
governing bound for the offset and for the tension. A bound may be an EA, a stretch law, or
a dynamic stiffness ``EA = (alpha + beta L_m) MBL`` at the mean load ``L_m`` (% of MBL): that
one is found by fixed-point iteration, the mean load being the largest tension of that line
type in the equilibrium solved with it (one stiffness per line type, taken at its most
loaded segment: the stiffer choice, conservative for tension).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from ..errors import CaseError
from ..model import Case
from ..model.stretch import DynamicStiffness, StretchLaw
from ..solve.equilibrium import solve
from ..solve.result.classes import Result

__all__ = ["BoundSolution", "BoundsResult", "stiffness_bounds", "BOUNDS"]

BOUNDS = ("lower", "upper")
#: Fixed-point iterations on the mean load of a dynamic stiffness, and their tolerance on
#: the stiffness (relative).
_MAX_ITER = 30
_REL_TOL = 1e-9


@dataclass(frozen=True)
class BoundSolution:
    """The equilibrium with every bounded line type at one bound.

    Attributes
    ----------
    bound : {"lower", "upper"}
    result : Result
    stiffness : dict
        Per bounded line type, what was used: ``{"ea_N": ...}`` for a Hooke bound (with
        ``mean_load_N`` and ``mean_load_pct_mbl`` for a dynamic one) or
        ``{"law": "table of 8 rows ..."}``.
    iterations : int
        Fixed-point iterations on the mean load (0 without a dynamic stiffness).
    """

    bound: str
    result: Result
    stiffness: dict
    iterations: int = 0

    @property
    def offset_m(self) -> float:
        body = self.result.body
        return math.hypot(body["x_m"], body["y_m"]) if body else 0.0

    @property
    def max_tension(self) -> tuple:
        """``(tension [N], leg name)`` of the most loaded leg (fairlead or anchor)."""
        return max(((max(leg.fairlead_tension_N, leg.anchor_tension_N), leg.name)
                    for leg in self.result.legs), default=(0.0, ""))

    def to_dict(self) -> dict:
        T, leg = self.max_tension
        body = self.result.body
        return {"bound": self.bound, "offset_m": self.offset_m,
                "body": None if body is None else dict(body),
                "max_tension_N": T, "max_tension_leg": leg,
                "stiffness": self.stiffness, "iterations": self.iterations,
                "legs": [{"name": leg.name, "fairlead_tension_N": leg.fairlead_tension_N,
                          "anchor_tension_N": leg.anchor_tension_N,
                          "fibre_grounded_length_m": leg.fibre_grounded_m}
                         for leg in self.result.legs]}


@dataclass(frozen=True)
class BoundsResult:
    """Both bounds and the worse of them for offset and for tension."""

    case_name: str
    lower: BoundSolution
    upper: BoundSolution
    line_types: tuple = field(default=())

    @property
    def solutions(self) -> tuple:
        return (self.lower, self.upper)

    @property
    def governing_offset(self) -> BoundSolution:
        """The bound with the larger offset (the lower one on ties)."""
        return max(self.solutions, key=lambda s: s.offset_m)

    @property
    def governing_tension(self) -> BoundSolution:
        """The bound with the larger line tension (the lower one on ties)."""
        return max(self.solutions, key=lambda s: s.max_tension[0])

    def to_dict(self) -> dict:
        offset, tension = self.governing_offset, self.governing_tension
        T, leg = tension.max_tension
        return {"case": self.case_name, "line_types": list(self.line_types),
                "bounds": [s.to_dict() for s in self.solutions],
                "governing": {"offset": {"bound": offset.bound, "offset_m": offset.offset_m},
                              "tension": {"bound": tension.bound, "tension_N": T,
                                          "leg": leg}}}


def _with_line_types(case: Case, types: dict) -> Case:
    """``case`` with the line types named in ``types`` replaced (every segment of them)."""
    lines = tuple(dataclasses.replace(line, segments=tuple(
        dataclasses.replace(seg, line_type=types.get(seg.line_type.name, seg.line_type))
        for seg in line.segments)) for line in case.lines)
    line_types = {name: types.get(name, lt) for name, lt in case.line_types.items()}
    # The case-file data no longer describes the scene: drop it (as the checks do).
    extra = {"source": None} if "source" in {f.name for f in dataclasses.fields(case)} else {}
    return dataclasses.replace(case, line_types=line_types, lines=lines, **extra)


def _at(lt, spec, ea_dynamic: float | None):
    """Line type ``lt`` at bound ``spec``; a dynamic bound at the stiffness ``ea_dynamic``."""
    if isinstance(spec, StretchLaw):
        return dataclasses.replace(lt, ea=None, stretch=spec), {"law": spec.describe()}
    ea = float(ea_dynamic if isinstance(spec, DynamicStiffness) else spec)
    return dataclasses.replace(lt, ea=ea, stretch=None), {"ea_N": ea}


def _mean_loads(case: Case, result: Result, names) -> dict:
    """The largest tension [N] of each named line type in ``result`` (its mean load)."""
    loads = dict.fromkeys(names, 0.0)
    for leg, lr in zip(case.lines, result.legs):
        if lr.segments:
            for seg, s in zip(leg.segments, lr.segments):
                if seg.line_type.name in loads:
                    loads[seg.line_type.name] = max(loads[seg.line_type.name],
                                                    s["top_tension_N"], s["bottom_tension_N"])
        elif leg.line_type.name in loads:
            loads[leg.line_type.name] = max(loads[leg.line_type.name], lr.fairlead_tension_N,
                                            lr.anchor_tension_N)
    return loads


def _solve_bound(case: Case, bound: str, bounded: dict, start: Result, **kwargs):
    """The equilibrium at one bound. A dynamic stiffness ``EA = g(EA)`` (its mean load
    depends on the stiffness through the equilibrium) is solved for its fixed point by the
    secant method on ``g(EA) - EA``, from ``g`` at the mean load of ``start``."""
    specs = {name: getattr(lt.stiffness_bounds, bound) for name, lt in bounded.items()}
    dynamic = {name: spec for name, spec in specs.items() if isinstance(spec, DynamicStiffness)}
    loads = _mean_loads(case, start, dynamic)
    x = {name: spec.ea(bounded[name].mbl, loads[name]) for name, spec in dynamic.items()}
    history, iterations = [], 0
    while True:
        chosen = {name: _at(lt, specs[name], x.get(name)) for name, lt in bounded.items()}
        scene = _with_line_types(case, {name: c[0] for name, c in chosen.items()})
        result = solve(scene, start=start.state, **kwargs)
        if not dynamic:
            break
        loads = _mean_loads(scene, result, dynamic)
        f = {n: spec.ea(bounded[n].mbl, loads[n]) - x[n] for n, spec in dynamic.items()}
        for n, spec in dynamic.items():
            chosen[n][1].update(mean_load_N=loads[n],
                                mean_load_pct_mbl=100 * loads[n] / bounded[n].mbl,
                                alpha=spec.alpha, beta=spec.beta)
        if all(abs(f[n]) <= _REL_TOL * x[n] for n in dynamic):
            break
        if iterations >= _MAX_ITER:
            n = next(iter(dynamic))
            raise CaseError(f"line_types.{n}.stiffness_bounds.{bound}",
                            f"the mean load of the dynamic stiffness did not settle in "
                            f"{_MAX_ITER} iterations (EA {x[n]:.6g} N, off by {f[n]:.3g} N)")
        history.append((dict(x), f))
        step = {}
        for n in dynamic:
            if len(history) > 1 and history[-1][1][n] != history[-2][1][n]:
                (x0, f0), (x1, f1) = history[-2], history[-1]
                step[n] = -f1[n] * (x1[n] - x0[n]) / (f1[n] - f0[n])
            else:
                step[n] = f[n]
        x = {n: x[n] + step[n] for n in dynamic}
        iterations += 1
        start = result
    return BoundSolution(bound=bound, result=result,
                         stiffness={name: c[1] for name, c in chosen.items()},
                         iterations=iterations)


def stiffness_bounds(case: Case, *, tol: float | None = None,
                     solver: str = "ipopt") -> BoundsResult:
    """Solve ``case`` at the lower and at the upper bound of its ropes' stiffness.

    Parameters
    ----------
    case : Case
        Some line type must give ``stiffness_bounds`` (or be a catalogue fibre rope).
    tol, solver
        As for :func:`moorsolve.solve`.

    Returns
    -------
    BoundsResult
        Both equilibria; ``governing_offset`` and ``governing_tension`` name the worse bound
        for each (see the module notes).

    Raises
    ------
    CaseError
        No line type has stiffness bounds, a dynamic bound without an MBL, or a mean load
        that does not settle.
    ConvergenceError
        A bound has no equilibrium (the lines may break at the upper bound: the solve is
        run with ``allow_overload`` so that the tension is still reported).
    """
    bounded = {name: lt for name, lt in case.line_types.items()
               if lt.stiffness_bounds is not None}
    used = {seg.line_type.name for line in case.lines for seg in line.segments}
    bounded = {name: lt for name, lt in bounded.items() if name in used}
    if not bounded:
        raise CaseError("line_types", "no line type in use gives stiffness_bounds (a "
                                      "catalogue fibre rope has them; or give "
                                      "stiffness_bounds: {lower: ..., upper: ...})")
    for name, lt in bounded.items():
        for bound in BOUNDS:
            if isinstance(getattr(lt.stiffness_bounds, bound), DynamicStiffness) and not lt.mbl:
                raise CaseError(f"line_types.{name}.mbl", "a dynamic stiffness bound is "
                                                          "a multiple of the MBL; give mbl")
    kwargs = dict(tol=tol, solver=solver, allow_overload=True)
    start = solve(case, **kwargs)
    lower = _solve_bound(case, "lower", bounded, start, **kwargs)
    upper = _solve_bound(case, "upper", bounded, start, **kwargs)
    return BoundsResult(case_name=case.name, lower=lower, upper=upper,
                        line_types=tuple(bounded))
