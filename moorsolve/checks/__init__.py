"""Mooring checks: criteria tables, intact and damaged conditions, the check report data.

``run_checks(case)`` solves the intact condition and every damaged condition (each leg
removed in turn) and checks line tension against the selected standard's factors, anchor
uplift against each anchor type, the grounded length and the body offset.
"""

from ..model.scene import STANDARDS
from .criteria import Criterion, criteria_table, criterion
from .run import CheckItem, CheckReport, ConditionResult, run_checks

__all__ = ["STANDARDS", "CheckItem", "CheckReport", "ConditionResult", "Criterion",
           "criteria_table", "criterion", "run_checks"]
