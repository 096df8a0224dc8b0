"""Mooring checks: criteria tables, intact and damaged conditions, the check report data.

``run_checks(case)`` solves the intact condition and every damaged condition (each leg
removed in turn) and checks line tension against the selected standard's factors, anchor
uplift against each anchor type, the grounded length and the body offset;
``run_end_of_life(case)`` runs them on the mooring after its design life of corrosion and
creep (:mod:`.end_of_life`). Names are
imported on first use (:mod:`moorsolve._lazy`).
"""

from __future__ import annotations

from .._lazy import lazy_exports
from ..model.scene import STANDARDS

_NAMES = {"Criterion": ".criteria", "criteria_table": ".criteria", "criterion": ".criteria",
          "CheckItem": ".items", "CheckReport": ".outcome", "ConditionResult": ".outcome",
          "run_checks": ".run", "EndOfLifeReport": ".end_of_life",
          "end_of_life_case": ".end_of_life", "run_end_of_life": ".end_of_life",
          "fatigue_diameter": ".wear"}
__getattr__, __dir__ = lazy_exports(__name__, _NAMES, globals())

__all__ = ["STANDARDS", "CheckItem", "CheckReport", "ConditionResult", "Criterion",
           "EndOfLifeReport", "criteria_table", "criterion", "end_of_life_case",
           "fatigue_diameter", "run_checks", "run_end_of_life"]
