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


def stiffness_scale_column(case: Case, n_p: int, line_type: str) -> np.ndarray:
    """``dp/dk``: how the parameter vector moves when every tension of ``line_type``'s
    stretch law is scaled by ``k`` (at ``k = 1``), i.e. the rope made ``k`` times stiffer.

    Hooke: ``1/EA -> 1/(k EA)``; Baranov: ``n -> n / sqrt(k)``; table: each tension
    ``T_i -> k T_i``. Covers the stretch-law block for every segment, and Hooke's
    compliance of one-segment legs (their slot in the leg block).

    Raises
    ------
    ValueError
        A Hooke segment inside a multi-segment or lumped-node leg (its compliance sits in
        the segment block, not mapped here), or a line type no leg uses.
    """
    from .problem import ENV_PARAMS, LEG_PARAMS, segment_parameters
    col = np.zeros(n_p)
    base = len(ENV_PARAMS) + len(LEG_PARAMS) * len(case.legs) + len(segment_parameters(case))
    cursor, used = 0, False
    for i, leg in enumerate(case.legs):
        for seg in leg.segments:
            lt = seg.line_type
            law = lt.stretch
            mine = lt.name == line_type
            used = used or mine
            if law is not None:
                size = len(law.parameters())
                if mine:
                    if law.model == "baranov":
                        col[base + cursor] = -law.n / 2
                    else:
                        rows = law.rows
                        col[base + cursor + rows: base + cursor + 2 * rows] = law.tension
                cursor += size
            elif mine and lt.ea is not None:
                if leg.multi_segment or len(leg.segments) != 1:
                    raise ValueError(f"line_types[{line_type}].stiffness_scale: a Hooke "
                                     f"segment of the multi-segment leg {leg.name} is not "
                                     "mapped (give it a stretch law, or use legs[].ea)")
                col[len(ENV_PARAMS) + i * len(LEG_PARAMS) + LEG_PARAMS.index("ea_inv")] = \
                    -1.0 / lt.ea
    if not used:
        raise ValueError(f"line_types[{line_type}]: no leg uses this line type")
    return col


def baranov_n_column(case: Case, n_p: int, line_type: str) -> np.ndarray:
    """``dp/dn`` for the Baranov coefficient ``n`` of ``line_type`` (every segment of it)."""
    from .problem import ENV_PARAMS, LEG_PARAMS, segment_parameters
    col = np.zeros(n_p)
    base = len(ENV_PARAMS) + len(LEG_PARAMS) * len(case.legs) + len(segment_parameters(case))
    cursor = 0
    for leg in case.legs:
        for seg in leg.segments:
            law = seg.line_type.stretch
            if law is None:
                continue
            if seg.line_type.name == line_type and law.model == "baranov":
                col[base + cursor] = 1.0
            cursor += len(law.parameters())
    if not col.any():
        raise ValueError(f"line_types[{line_type}].n: no leg uses a Baranov line type of "
                         "that name (n is Baranov's coefficient)")
    return col
