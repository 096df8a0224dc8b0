"""One check of a mooring: a value against its limit (the row every check module makes)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

__all__ = ["CheckItem"]


@dataclass(frozen=True)
class CheckItem:
    """One check: a value against its limit.

    ``utilisation`` is demand over capacity (``<= 1`` passes; ``inf`` when the capacity is
    zero or missing). ``detail`` holds what a check has beyond the one value (an
    anchor's load at the padeye, its capacity and factors).
    """

    condition: str
    leg: str | None
    check: str
    value: float
    limit: float
    unit: str
    utilisation: float
    passed: bool
    criterion: str
    detail: dict = field(default_factory=dict, compare=False)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)
