"""A design point as a case: the study's variables applied to the base case, the load-case
scenes and the objective."""

from __future__ import annotations

import math


from ..model import Case
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
    """Case-file edits (dotted path -> value) that put design ``values`` into ``case``."""
    legs = {leg.name: leg for leg in case.legs}
    edits = {}
    for var, value in zip(study.variables, values):
        for name in var.legs:
            leg = legs[name]
            if var.kind == "length":
                edits[f"legs[{name}].segments[0].length"] = float(value)
            else:
                (ox, oy), (ux, uy) = _anchor_line(case, leg, var.kind)
                edits[f"legs[{name}].anchor"] = [ox + ux * float(value), oy + uy * float(value),
                                                 float(leg.anchor[2])]
    return edits


def design_case(case: Case, study: Study, values) -> Case:
    """``case`` with the design ``values`` (one per study variable) applied."""
    from ..io.study_file import load_case_variant
    return load_case_variant(case, design_edits(case, study, values), "design")


def load_case_scene(design: Case, study: Study, k: int) -> Case:
    """Load case ``k`` of ``study`` applied to the case ``design``."""
    from ..io.study_file import load_case_variant
    return load_case_variant(design, study.load_cases[k].edits, f"load_cases[{k}]")


def objective_value(case: Case, study: Study) -> float:
    """Total line mass [kg] or cost of ``case`` under the study's prices."""
    return _objective(case, study, {leg.name: leg.length for leg in case.legs})


def _objective(case: Case, study: Study, lengths: dict):
    total = 0
    for leg in case.legs:
        if leg.multi_segment:
            parts = [(seg.line_type.name, seg.length) for seg in leg.segments]
        else:
            parts = [(leg.line_type.name, lengths[leg.name])]
        for lt_name, length in parts:
            if study.objective == "mass":
                total = total + length * study.mass_per_length[lt_name]
            else:
                total = total + length * study.cost_per_length[lt_name]
    if study.objective == "cost":
        total = total + study.anchor_cost * len(case.legs)
    return total


# ---- the optimisation ------------------------------------------------------------------------


