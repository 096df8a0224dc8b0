"""The per-line report table: the layout the solver writes and the audit reads.

Each row of the table a solved point reports (``EquilibriumProblem.report`` in
:mod:`moorsolve.solve.assembly.problem`) is one line; its columns are :data:`LINE_COLUMNS`. The
layout lives here, below both, so that the independent audit (:mod:`moorsolve.audit`) reads
the table without importing the solver.
"""

from __future__ import annotations

__all__ = ["LINE_COLUMNS"]

#: Columns of the lines table of the problem's ``report``: the horizontal and vertical
#: tension at end B (``H``, ``VF``: the upward force B exerts on the line), the horizontal
#: pull on end A and its upward pull (``HA``, ``VA``); the grounded length and the
#: horizontal extent of the part rising to the upper end [m]; the line's mismatch as a force
#: and 0 (multi-segment and lumped lines) or its span residuals [m]; its spans ``X``, ``Z``;
#: end B's global x, y; the horizontal force on end B; the 2x2 block of a single line
#: (column-major); end A's global position and end B's z; the forces on A and B [N].
LINE_COLUMNS = ("H", "VF", "HA", "VA", "grounded", "suspended_x", "rX", "rZ", "X", "Z",
                "bx", "by", "fx", "fy", "J00", "J10", "J01", "J11",
                "ax", "ay", "az", "bz", "FAx", "FAy", "FAz", "FBx", "FBy", "FBz", "floating")
