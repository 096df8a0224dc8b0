"""A design point as a case: the study's variables applied to the base case, the load-case
scenes and the objective."""

from __future__ import annotations

import math

from ..errors import CaseError
from ..model import Case
from ..model.edit import variant
from ..model.study import Study


def _leg_index(case: Case) -> dict:
    return {leg.name: i for i, leg in enumerate(case.legs)}


def _anchor_line(case: Case, leg, kind: str) -> tuple:
    """``(origin, unit direction)`` in the plane along which an anchor variable moves it."""
    ax, ay = leg.anchor[0], leg.anchor[1]
    ox, oy = (leg.fairlead[0], leg.fairlead[1]) if kind == "anchor_distance" else (0.0, 0.0)
    r = math.hypot(ax - ox, ay - oy)
    return (ox, oy), ((ax - ox) / r, (ay - oy) / r)


def design_edits(case: Case, study: Study, values) -> dict:
    """Case-file edits (dotted path -> value) that put design ``values`` into ``case``.

    In a network case the lines are ``lines[NAME]`` and an anchor is end A (``from``), which
    a design variable may move only where the case gives it as coordinates.
    """
    legs = {leg.name: leg for leg in case.legs}
    network = case.form == "network"
    prefix = "lines" if network else "legs"
    edits = {}
    for var, value in zip(study.variables, values):
        for name in var.legs:
            leg = legs[name]
            if var.kind == "length":
                edits[f"{prefix}[{name}].segments[0].length"] = float(value)
                continue
            if network and not (leg.a.fixed and leg.a.label is None):
                raise CaseError(f"variables.{var.name}.legs",
                                f"line {name!r} starts at a named point or a body: an anchor "
                                "variable moves end A given as coordinates only")
            (ox, oy), (ux, uy) = _anchor_line(case, leg, var.kind)
            key = "from" if network else "anchor"
            edits[f"{prefix}[{name}].{key}"] = [ox + ux * float(value),
                                                 oy + uy * float(value), float(leg.anchor[2])]
    return edits


def design_case(case: Case, study: Study, values) -> Case:
    """``case`` with the design ``values`` (one per study variable) applied."""
    return variant(case, design_edits(case, study, values), "design")


def load_case_scene(design: Case, study: Study, k: int) -> Case:
    """Load case ``k`` of ``study`` applied to the case ``design``."""
    return variant(design, study.load_cases[k].edits, f"load_cases[{k}]")


def objective_value(case: Case, study: Study) -> float:
    """Total line mass [kg] or cost of ``case`` under the study's prices."""
    return _objective(case, study, {leg.name: leg.length for leg in case.legs})


def cost_value(case: Case, study: Study) -> float:
    """Cost of ``case`` (lines and anchors) under the study's prices, whatever its objective."""
    return _objective(case, study, {leg.name: leg.length for leg in case.legs}, "cost")


def _objective(case: Case, study: Study, lengths: dict, what: str | None = None):
    """Mass [kg] or cost (``what``, default the study's objective) of the legs at
    ``lengths`` (numbers or CasADi expressions)."""
    what = what or study.objective
    total = 0
    for leg in case.legs:
        if leg.multi_segment:
            parts = [(seg.line_type.name, seg.length) for seg in leg.segments]
        else:
            parts = [(leg.line_type.name, lengths[leg.name])]
        for lt_name, length in parts:
            if what == "mass":
                total = total + length * study.mass_per_length[lt_name]
            else:
                total = total + length * study.cost_per_length[lt_name]
    if what == "cost":
        total = total + study.anchor_cost * len(case.legs)
    return total


# ---- the optimisation ------------------------------------------------------------------------


