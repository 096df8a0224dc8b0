"""Stretch-law parameters of a case: a block of the problem's parameter vector.

A line type with a stretch law other than Hooke's (Baranov, a tension-strain table) gives
its values (:meth:`~moorsolve.model.stretch.StretchLaw.parameters`) to every segment of that
type. They follow the environment, leg and segment blocks of the parameter vector, segment
by segment in case order (legs, then their segments from the anchor), and only for
segments with such a law; Hooke lines keep their compliance in the leg and segment blocks.
The law's structure (which law, the table's number of rows) is part of the leg kind, so a
sweep, a sensitivity or an optimisation may change the values without a rebuild.
"""

from __future__ import annotations

import numpy as np

from ..model import Case
from ..physics.stretch import BARANOV, TABLE, NumericLaw, StretchModel

__all__ = ["law_model", "stretch_parameters", "split_stretch_parameters", "numeric_law",
           "start_ea"]


def law_model(line_type) -> StretchModel | None:
    """The :class:`StretchModel` of a line type with a law other than Hooke's, else None."""
    law = line_type.stretch
    if law is None:
        return None
    if law.model == "baranov":
        return StretchModel(BARANOV)
    return StretchModel(TABLE, law.rows)


def stretch_parameters(case: Case) -> np.ndarray:
    """The stretch-law block of the parameter vector (empty when every line is Hooke's)."""
    values = [v for leg in case.legs for seg in leg.segments
              if seg.line_type.stretch is not None
              for v in seg.line_type.stretch.parameters()]
    return np.asarray(values, dtype=float)


def split_stretch_parameters(case: Case, block) -> list:
    """Cut the block (a sequence of scalars, e.g. SX) into ``[leg][segment]`` parameter
    lists (None for a Hooke or inextensible segment), in :func:`stretch_parameters` order."""
    out, cursor = [], 0
    for leg in case.legs:
        row = []
        for seg in leg.segments:
            model = law_model(seg.line_type)
            if model is None:
                row.append(None)
                continue
            row.append(list(block[cursor: cursor + model.n_params]))
            cursor += model.n_params
        out.append(row)
    return out


def numeric_law(line_type) -> NumericLaw | None:
    """The line type's law as a :class:`NumericLaw` for profiles (None for Hooke lines)."""
    model = law_model(line_type)
    return None if model is None else NumericLaw(model, line_type.stretch.parameters())


def start_ea(line_type) -> float | None:
    """A Hooke stiffness [N] for closed-form start points: the line's EA, or for another law
    its secant stiffness (a table's at its last row; Baranov's at a third of the MBL, or
    at 1 % strain without an MBL). None for an inextensible line."""
    law = line_type.stretch
    if law is None:
        return line_type.ea
    if law.model == "table":
        return law.secant_ea()
    T = line_type.mbl / 3 if line_type.mbl else (0.01 / law.n) ** 2
    return law.secant_ea(T)
