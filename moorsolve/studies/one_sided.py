"""Stiffness where a weightless line is exactly at its slack point: the two one-sided limits.

An elastic weightless line (a hawser, a tether) whose chord equals its unstretched length
carries nothing and is on the point of being drawn taut: moving its end away stretches it
(axial stiffness ``EA/L``), moving it closer leaves it slack (nothing). The mooring force
is continuous there but its derivative is not; the solver's Jacobian at that point is the
derivative of neither side (the Fischer-Burmeister corner). Its two one-sided limits are
those of the scene with the line taut and with it slack:

- slack side: the line carries nothing on that side, so the scene without it;
- taut side: the scene with the line taut, evaluated with its unstretched length shortened
  by :data:`.kinks.TAUT_STRAIN` of its chord (its tension ``EA * TAUT_STRAIN`` then changes the
  lateral terms ``T/L`` by that fraction of the axial stiffness only, far below any
  tolerance of the derivative).
"""

from __future__ import annotations

import dataclasses
from typing import Optional

import numpy as np

from .kinks import lines_at_slack_point, with_lines
from .stiffness import as_result, held_stiffness


@dataclasses.dataclass(frozen=True)
class OneSidedStiffness:
    """The two one-sided limits of a body's mooring stiffness at a slack point.

    Attributes
    ----------
    lines : tuple of str
        The weightless lines at their slack point.
    taut, slack : numpy.ndarray (6, 6)
        The stiffness with those lines drawn taut and with them slack [SI, as
        :func:`moorsolve.stiffness`]. Displacements that stretch every one of them see
        ``taut``, those that slacken every one ``slack``.
    """

    lines: tuple
    taut: np.ndarray
    slack: np.ndarray


def one_sided_stiffness(result_or_case, body: Optional[str] = None, *,
                        solver: str = "ipopt") -> Optional[OneSidedStiffness]:
    """Both one-sided limits of :func:`moorsolve.stiffness` where weightless lines are at
    their slack point; None where none is (the stiffness is then one matrix)."""

    result = as_result(result_or_case, solver)
    names = lines_at_slack_point(result)
    if not names:
        return None
    return OneSidedStiffness(
        lines=names,
        taut=held_stiffness(with_lines(result.case, names, taut=True), result, body),
        slack=held_stiffness(with_lines(result.case, names, taut=False), result, body))
