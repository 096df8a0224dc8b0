"""What a check run returns: each condition's items and line figures, and the report.

:class:`ConditionResult` is one condition (intact, or one line removed); :class:`CheckReport`
all of them under one standard, with what the line-tension check covered (its ``method``)
and the notes an engineer must read with it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from ..model import Checks
from ..solve import Result
from .criteria import Criterion
from .design_offset import MEAN_ONLY, METHOD_DESIGN_OFFSET
from .dynamic import METHOD_DYNAMIC, TRANSIENT_NOTE
from .fibre import LOWER_LIMIT_CHECKS
from .items import CheckItem

__all__ = ["ConditionResult", "CheckReport", "damaged_value"]


@dataclass(frozen=True)
class ConditionResult:
    """One condition: intact, or one leg removed.

    Attributes
    ----------
    name : str
        ``intact`` or ``damaged: L3 removed``.
    kind : str
        ``intact`` or ``damaged``.
    removed : str or None
        The removed leg.
    solved : bool
        A certified equilibrium was found.
    reason : str
        Why not, when it was not.
    result : Result or None
        The equilibrium (for overloaded lines too: solved with ``allow_overload``).
    items : list of CheckItem
    criterion : Criterion
    drifting : tuple of dict
        Bodies nothing holds horizontally in this condition (a tanker whose one hawser
        broke): each ``body``, ``dofs``, ``group``, ``lines``, ``load_N``, ``toward_deg``
        and ``message`` (:mod:`.drift`). Such a condition fails; ``result`` is then the
        rest of the mooring solved with those bodies held.
    method : str
        ``mean`` (the factors on the mean tension), ``design offset`` (the quasi-static
        method, :mod:`.design_offset`) or ``dynamic`` (the lines' dynamics,
        :mod:`.dynamic`).
    lines : tuple of dict
        Per line: ``leg``, ``end`` and the figures of
        :class:`~moorsolve.checks.design_tension.DesignTension` (``t_mean_N``, ``t_dyn_N``,
        ``t_max_N``, ``design_N``, ``capacity_N``, ``utilisation``); with the ``dynamic``
        method also ``dynamic``: that end's ``sigma_wf_N``, ``tz_wf_s``, ``sigma_lf_N``,
        ``tz_lf_s``, ``sigma_N``, ``tz_s``, ``t_dyn_N`` (``sigma sqrt(2 ln N)``),
        ``wf_max_N``, ``lf_max_N``.
    design_offset_m : dict
        Body name to its design offset [m] (``design offset`` and ``dynamic`` methods).
    held : Result or None
        The lines with the bodies held at the design offset (same methods).
    sea : DesignOffsetSolve or None
        The motions and the held solve behind them (same methods).
    tensions : dict or None
        Line name to :class:`~moorsolve.dynamics.line_sea.LineSeaTension` (``dynamic``).
    """

    name: str
    kind: str
    removed: str | None
    solved: bool
    reason: str
    result: Result | None
    items: list
    criterion: Criterion
    drifting: tuple = ()
    method: str = "mean"
    lines: tuple = ()
    design_offset_m: dict = field(default_factory=dict)
    held: Result | None = None
    sea: object = field(default=None, repr=False, compare=False)
    tensions: dict | None = field(default=None, repr=False, compare=False)

    @property
    def passed(self) -> bool:
        return self.solved and not self.drifting and all(item.passed for item in self.items)

    def __repr__(self) -> str:
        if self.drifting:
            return (f"<ConditionResult {self.name!r}: FAIL, "
                    f"{'; '.join(d['message'] for d in self.drifting)}>")
        if not self.solved:
            return f"<ConditionResult {self.name!r}: FAIL, no equilibrium: {self.reason}>"
        worst = self.worst()
        tension = "" if worst is None else (f", worst tension {worst.leg} utilisation "
                                             f"{worst.utilisation:.2f}")
        return (f"<ConditionResult {self.name!r}: {'PASS' if self.passed else 'FAIL'}"
                f"{tension}>")

    @property
    def offset_m(self) -> float | None:
        """The body's horizontal offset [m]; with several bodies the largest one's. At the
        design offset where the quasi-static method ran."""
        if self.design_offset_m:
            return max(self.design_offset_m.values())
        if self.result is None:
            return None
        if self.result.body is not None:
            return math.hypot(self.result.body["x_m"], self.result.body["y_m"])
        return max((math.hypot(b["offset"]["x_m"], b["offset"]["y_m"])
                    for b in self.result.bodies), default=None)

    def worst(self, check: str = "tension") -> CheckItem | None:
        items = [i for i in self.items if i.check == check]
        return max(items, key=lambda i: i.utilisation, default=None)

    def to_dict(self) -> dict:
        worst = self.worst()
        return {
            "name": self.name, "kind": self.kind, "removed": self.removed,
            "solved": self.solved, "reason": self.reason, "passed": self.passed,
            "offset_m": self.offset_m,
            "body": None if self.result is None or self.result.body is None
            else dict(self.result.body),
            "max_tension_utilisation": None if worst is None else worst.utilisation,
            "criterion": self.criterion.describe(dynamic=self.method != "mean"),
            "drifting": [dict(d) for d in self.drifting],
            "method": self.method,
            "design_offset_m": dict(self.design_offset_m),
            "lines": [dict(line) for line in self.lines],
            "checks": [item.to_dict() for item in self.items],
        }


@dataclass(frozen=True)
class CheckReport:
    """All conditions of one case under one standard."""

    case_name: str
    standard: str
    consequence_class: int
    checks: Checks
    conditions: list
    criteria: list = field(default_factory=list)
    time_s: float = 0.0
    #: The certified relative force residual every condition was solved to.
    tolerance: float = math.nan
    #: The case has a sea state (waves with a period).
    sea: bool = False
    #: The fatigue check (moorsolve.life.fatigue.FatigueResult) where checks.fatigue is given.
    fatigue: object = None

    def __repr__(self) -> str:
        verdict = "PASS" if self.passed else "FAIL"
        return (f"<CheckReport {self.case_name!r} {self.standard}: {verdict}, "
                f"{sum(c.passed for c in self.conditions)} of {len(self.conditions)} "
                f"conditions pass>")

    def _repr_html_(self) -> str:
        from ..report.notebook import check_html_table
        return check_html_table(self)

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.conditions) and (
            self.fatigue is None or self.fatigue.passed)

    @property
    def failures(self) -> list:
        out = [] if self.fatigue is None else [
            f"fatigue of {e.line} at its {e.end}: DFF x D = {e.utilisation:.3g} > 1 "
            f"(life {e.life_y:.4g} y)" for e in self.fatigue.ends if not e.passed]
        for c in self.conditions:
            out += [f"{c.name}: {d['message']}" for d in c.drifting]
            if not c.solved:
                out.append(f"{c.name}: no equilibrium: {c.reason}")
            out += [f"{c.name}: {i.check}{' of ' + i.leg if i.leg else ''}: "
                    f"{_show(i.value, i.unit)}, no limit to check against: {i.criterion}"
                    if not math.isfinite(i.limit) else
                    f"{c.name}: {i.check}{' of ' + i.leg if i.leg else ''}: "
                    f"{_show(i.value, i.unit)} > limit {_show(i.limit, i.unit)} ({i.criterion})"
                    if i.check not in LOWER_LIMIT_CHECKS else
                    f"{c.name}: {i.check} of {i.leg}: {_show(i.value, i.unit)} < "
                    f"{_show(i.limit, i.unit)}"
                    for i in c.items if not i.passed]
        return out

    @property
    def method(self) -> str:
        """What the line-tension check covers, in one sentence."""
        shown = {"design offset": METHOD_DESIGN_OFFSET.get(self.standard),
                 "dynamic": METHOD_DYNAMIC.get(self.standard)}
        used = [m for m in ("dynamic", "design offset")
                if any(c.method == m for c in self.conditions if c.solved)]
        if not used:
            return MEAN_ONLY
        text = "; ".join(shown[m] for m in used)
        if any(c.solved and c.method == "mean" for c in self.conditions):
            text += (" where a body moves in the sea state ("
                     + ", ".join(c.name for c in self.conditions if c.method in used)
                     + "); elsewhere " + MEAN_ONLY)
        return text

    @property
    def notes(self) -> list:
        """What an engineer must read with the figures (the transient after a breakage,
        where damaged conditions were checked in a sea state)."""
        if any(c.kind == "damaged" and c.method != "mean" for c in self.conditions):
            return [TRANSIENT_NOTE]
        return []

    @property
    def warnings(self) -> list[dict]:
        """Every solved condition's warnings (:attr:`moorsolve.Result.warnings`), each with
        its ``condition``: what no engineer may miss, pass or fail."""
        return [dict(w, condition=c.name) for c in self.conditions if c.result is not None
                for w in c.result.warnings]

    def to_dict(self) -> dict:
        return {
            "case": self.case_name, "standard": self.standard,
            "consequence_class": self.consequence_class, "passed": self.passed,
            "method": self.method, "notes": self.notes,
            "time_s": self.time_s, "tolerance": self.tolerance,
            "limits": {"offset_limit_m": self.checks.offset_limit,
                       "offset_limit_damaged_m": damaged_value(self.checks.offset_limit_damaged,
                                                          self.checks.offset_limit),
                       "min_grounded_length_m": self.checks.min_grounded_length,
                       "min_grounded_length_damaged_m": damaged_value(
                           self.checks.min_grounded_length_damaged,
                           self.checks.min_grounded_length)},
            "criteria": [dataclasses.asdict(c) for c in self.criteria],
            "conditions": [c.to_dict() for c in self.conditions],
            "failures": self.failures,
            "warnings": self.warnings,
            **({} if self.fatigue is None else {"fatigue": self.fatigue.to_dict()}),
        }


def _show(value: float, unit: str) -> str:
    if not math.isfinite(value):
        return "n/a"
    return f"{value / 1e3:.1f} kN" if unit == "N" else f"{value:.2f} {unit}"


def damaged_value(value, fallback):
    """A damaged condition's limit: its own, else the intact one."""
    return fallback if value is None else value


