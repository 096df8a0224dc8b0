"""Stretch-law parameters of a case: the last block of the problem's parameter vector.

A line type with a stretch law other than Hooke's (Baranov, a tension-strain table) gives
its values (:meth:`~moorsolve.model.stretch.StretchLaw.parameters`) to every segment of that
type. They close the parameter vector (:mod:`.layout`, block 8, named
``line[NAME].law[k]``), segment by segment in case order (lines, then their
segments from end A), and only for segments with such a law; Hooke lines keep their
compliance in the line and segment blocks.
The law's structure (which law, the table's number of rows) is part of the leg kind, so a
sweep, a sensitivity or an optimisation may change the values without a rebuild.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ...model import Case
from ...physics.stretch import law_model, numeric_law

__all__ = ["law_model", "stretch_parameters", "law_slot", "line_laws", "numeric_law",
           "start_ea", "stiffness_scale_column", "baranov_n_column"]


def stretch_parameters(case: Case) -> np.ndarray:
    """The stretch-law block of the parameter vector (empty when every line is Hooke's)."""
    values = [v for line in case.lines for seg in line.segments
              if seg.line_type.stretch is not None
              for v in seg.line_type.stretch.parameters()]
    return np.asarray(values, dtype=float)


def law_slot(line, k: int) -> str:
    """The layout name of segment ``k``'s law parameters (:mod:`.layout`)."""
    return f"line[{line.name}].law[{k}]"


def line_laws(case: Case, layout, p) -> list:
    """The law parameters of every segment, ``[line][segment]`` (lists of scalars of the
    symbolic ``p``; None for a Hooke or inextensible segment), from end A."""
    return [[list(ca.vertsplit(p[layout.slice(law_slot(line, k))]))
             if seg.line_type.stretch is not None else None
             for k, seg in enumerate(line.segments)] for line in case.lines]


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


def stiffness_scale_column(case: Case, layout, line_type: str) -> np.ndarray:
    """``dp/dk``: how the parameter vector moves when every tension of ``line_type``'s
    stretch law is scaled by ``k`` (at ``k = 1``), i.e. the rope made ``k`` times stiffer.

    Hooke: ``1/EA -> 1/(k EA)`` (a one-segment line's compliance, or a segment's);
    Baranov: ``n -> n / sqrt(k)``; table: each tension ``T_i -> k T_i``. Every segment of
    the type, in every line.

    Raises
    ------
    ValueError
        No line uses the type, or it is inextensible.
    """
    col = np.zeros(layout.size)
    used = False
    for line in case.lines:
        for k, seg in enumerate(line.segments):
            lt = seg.line_type
            if lt.name != line_type:
                continue
            used = True
            law = lt.stretch
            if law is not None:
                s = layout.slice(law_slot(line, k))
                if law.model == "baranov":
                    col[s.start] = -law.n / 2
                else:
                    col[s.start + law.rows: s.stop] = law.tension
            elif lt.ea is not None:
                name = f"line[{line.name}].segment[{k}].ea_inv"
                slot = name if name in layout.names else f"line[{line.name}].ea_inv"
                col[layout.index(slot)] = -1.0 / lt.ea
            else:
                raise ValueError(f"line_types[{line_type}].stiffness_scale: the line type "
                                 "is inextensible")
    if not used:
        raise ValueError(f"line_types[{line_type}]: no line uses this line type")
    return col


def baranov_n_column(case: Case, layout, line_type: str) -> np.ndarray:
    """``dp/dn`` for the Baranov coefficient ``n`` of ``line_type`` (every segment of it)."""
    col = np.zeros(layout.size)
    for line in case.lines:
        for k, seg in enumerate(line.segments):
            law = seg.line_type.stretch
            if seg.line_type.name == line_type and law is not None and law.model == "baranov":
                col[layout.slice(law_slot(line, k)).start] = 1.0
    if not col.any():
        raise ValueError(f"line_types[{line_type}].n: no line uses a Baranov line type of "
                         "that name (n is Baranov's coefficient)")
    return col
