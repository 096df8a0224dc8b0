"""The outcome of a design optimisation: variables, constraints, verification, report words."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from ..model import Case

ACTIVE_TOL = 1e-5
#: A verified value may exceed its limit by this fraction of the limit's scale.
VERIFY_TOL = 1e-6

#: Per constraint kind: unit of value and limit, the step used to put a multiplier into
#: words, the direction that relaxes the limit (+1: raise it) and its description.
_KINDS = {
    "safety_factor": ("-", 0.1, -1, "safety factor"),
    "anchor_uplift": ("N", 10e3, +1, "anchor uplift limit"),
    "grounded_length": ("m", 1.0, -1, "minimum grounded length"),
    "offset": ("m", 1.0, +1, "offset limit"),
    # Unit and step of the cost cap are the study's currency and 1 % of the cap.
    "cost": ("cost", 1.0, +1, "cost cap (max_cost)"),
}
#: The load case named by the design-wide cost cap (it holds over every load case at once).
DESIGN_WIDE = "whole design"


# ---- result --------------------------------------------------------------------------------


@dataclass(frozen=True)
class VariableResult:
    """One design variable at the optimum [m]."""

    name: str
    kind: str
    legs: tuple
    start: float
    optimum: float
    lower: float
    upper: float
    at_bound: str          # "", "lower" or "upper"
    saving_per_m: float    # objective saved per metre of relaxing the active bound

    @property
    def change(self) -> float:
        return self.optimum - self.start

    def to_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["legs"] = list(self.legs)
        d["change"] = self.change
        return d


@dataclass(frozen=True)
class ConstraintResult:
    """One design constraint in one load case at the optimum.

    ``value`` and ``limit`` in ``unit`` (the safety factor achieved for ``safety_factor``);
    ``margin`` is positive when satisfied; ``saving`` is the objective saved by relaxing
    the limit by ``step`` (linear estimate from the multiplier).
    """

    load_case: str
    kind: str
    leg: str | None
    value: float
    limit: float
    unit: str
    margin: float
    active: bool
    multiplier: float
    saving: float
    step: float

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class Verification:
    """The independent re-solve of one load case at the optimum design."""

    load_case: str
    certified: bool
    residual_N: float
    offset_m: float | None
    position_difference_m: float
    violations: tuple
    reason: str = ""

    def to_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["violations"] = list(self.violations)
        return d


@dataclass(frozen=True)
class Optimisation:
    """The outcome of :func:`optimise`.

    Attributes
    ----------
    objective : str
        ``mass`` or ``cost``; ``unit`` is ``kg`` or the study's currency.
    objective_start, objective_optimum : float
        Total line mass [kg] or cost at the starting and optimum designs (all legs).
    variables : list of VariableResult
    constraints : list of ConstraintResult
    verification : list of Verification
    status : str
        IPOPT's return status; ``iterations`` its iteration count.
    solve_time_s, total_time_s : float
        IPOPT's time, and everything (start solves, build, verification).
    optimised_case : Case
    optimised_data : dict
        Case-file data of the optimised design (for writing a case file).
    cost : float or None
        The optimum design's cost (lines and anchors, in ``currency``)
        when the study prices it (cost objective or ``max_cost``).
    currency : str or None
        The study's currency when it prices the design.
    max_cost : float or None
        The study's cost cap; ``cost_utilisation`` is ``cost / max_cost``.
    """

    study_name: str
    case_name: str
    objective: str
    unit: str
    objective_start: float
    objective_optimum: float
    variables: list
    constraints: list
    verification: list
    status: str
    iterations: int
    solve_time_s: float
    total_time_s: float
    optimised_case: Case = field(repr=False)
    optimised_data: dict = field(repr=False)
    notes: tuple = ()
    cost: float | None = None
    max_cost: float | None = None
    currency: str | None = None

    @property
    def cost_utilisation(self) -> float | None:
        """The design's cost over the cap (1: at the cap), None without a cap."""
        if self.max_cost is None or self.cost is None:
            return None
        return self.cost / self.max_cost

    @property
    def cost_within_cap(self) -> bool:
        """The optimum's cost, priced again from its case, is within the cap (or no cap)."""
        return self.max_cost is None or self.cost <= self.max_cost * (1 + VERIFY_TOL)

    @property
    def verified(self) -> bool:
        """Every load case re-solved, certified and within every limit, and the design's
        cost within the cap."""
        return self.cost_within_cap and all(v.certified and not v.violations
                                            for v in self.verification)

    @property
    def active(self) -> list:
        return [c for c in self.constraints if c.active]

    def plain_words(self) -> list:
        """The active constraints and bounds and what relaxing them is worth."""
        return _plain_words(self)

    def to_dict(self) -> dict:
        return {
            "study": self.study_name, "case": self.case_name,
            "objective": self.objective, "unit": self.unit,
            "objective_start": self.objective_start,
            "objective_optimum": self.objective_optimum,
            "saving": self.objective_start - self.objective_optimum,
            "status": self.status, "iterations": self.iterations,
            "solve_time_s": self.solve_time_s, "total_time_s": self.total_time_s,
            "verified": self.verified,
            "cost": self.cost, "max_cost": self.max_cost,
            "cost_utilisation": self.cost_utilisation,
            "currency": self.currency,
            "variables": [v.to_dict() for v in self.variables],
            "constraints": [c.to_dict() for c in self.constraints],
            "active": self.plain_words(),
            "verification": [v.to_dict() for v in self.verification],
            "notes": list(self.notes),
        }


# ---- design edits ----------------------------------------------------------------------------


def _plain_words(opt: Optimisation) -> list:
    what = "of line" if opt.objective == "mass" else ""
    lines = []
    for c in opt.active:
        unit, step, relax, label = _KINDS[c.kind]
        where = f" on leg {c.leg}" if c.leg else ""
        verb = "relaxing it" if relax > 0 else "lowering it"
        if c.kind == "cost":
            limit, by = f"{label} of {_amount(c.limit, c.unit)}", _amount(c.step, c.unit)
            verb = "raising it"
        elif c.kind == "safety_factor":
            limit = f"{label} of {c.limit:g}"
            by = f"{step:g}"
        elif c.kind == "anchor_uplift":
            limit = f"{label} of {c.limit / 1e3:g} kN"
            by = f"{step / 1e3:g} kN"
        else:
            limit = f"{label} of {c.limit:g} m"
            by = f"{step:g} m"
        scope = ("on the whole design" if c.kind == "cost"
                 else f"in load case {c.load_case!r}")
        lines.append(f"the {limit}{where} {scope} is active; {verb} by "
                     f"{by} would save {_amount(c.saving, opt.unit)} {what}".rstrip())
    by_kind: dict = {}
    for c in opt.active:
        by_kind.setdefault(c.kind, []).append(c)
    for kind, group in by_kind.items():
        if len(group) > 1 and kind != "cost":
            unit, step, relax, label = _KINDS[kind]
            by = f"{step / 1e3:g} kN" if unit == "N" else f"{step:g}" + (" m" if unit == "m"
                                                                          else "")
            cases = len({c.load_case for c in group})
            lines.append(f"together: {'relaxing' if relax > 0 else 'lowering'} the {label} "
                         f"by {by} wherever it is active ({len(group)} constraints in {cases} "
                         f"load case{'s' if cases > 1 else ''}) would save "
                         f"{_amount(sum(c.saving for c in group), opt.unit)} {what}".rstrip())
    for v in opt.variables:
        if v.at_bound:
            bound = v.lower if v.at_bound == "lower" else v.upper
            move = "lowering" if v.at_bound == "lower" else "raising"
            lines.append(f"the {v.at_bound} bound {bound:g} m of variable {v.name!r} "
                         f"({v.kind}) is active; {move} it by 1 m would save "
                         f"{_amount(v.saving_per_m, opt.unit)} {what}".rstrip())
    return lines


def _amount(value: float, unit: str) -> str:
    if unit == "kg":
        return f"{value:,.0f} kg" if abs(value) >= 10 else f"{value:.3g} kg"
    return f"{value:,.0f} {unit}" if abs(value) >= 10 else f"{value:.3g} {unit}"
