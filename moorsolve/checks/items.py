"""One check of a mooring: a value against its limit (the row every check module makes)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

__all__ = ["CheckItem"]


@dataclass(frozen=True)
class CheckItem:
    """One check: a value against its limit.

    ``utilisation`` is demand over capacity (``<= 1`` passes; ``inf`` when the capacity is
    zero or missing).
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

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)
