"""Matrices with their degrees of freedom and units: stiffness as text, HTML and JSON.

A bare 3x3 (or 6x6) array does not say which row is which or in what units; an engineer
copying ``K[2, 2]`` into a period estimate needs both. :class:`LabelledMatrix` carries the
row and column labels with units, prints as a table (``repr``), renders as an HTML table in
a notebook (``_repr_html_``) and still behaves as the numpy array (``numpy.asarray``).
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import numpy as np

__all__ = ["DOF_LABELS", "LabelledMatrix", "stiffness_table"]

#: Degree of freedom -> (the generalised force on it, its unit; the displacement's unit).
DOF_LABELS = {
    "surge": ("Fx", "N", "m"), "sway": ("Fy", "N", "m"), "heave": ("Fz", "N", "m"),
    "roll": ("Mx", "N m", "rad"), "pitch": ("My", "N m", "rad"), "yaw": ("Mz", "N m", "rad"),
}


@dataclass(frozen=True)
class LabelledMatrix:
    """A matrix with labelled rows and columns (units in brackets).

    Attributes
    ----------
    matrix : numpy.ndarray
    rows, columns : tuple of str
        Labels with units, e.g. ``"Mz [N m]"`` and ``"yaw [rad]"``.
    title : str
        What the matrix is; the unit of an entry is its row's over its column's.
    dofs : tuple of str
        The degrees of freedom, in order.
    """

    matrix: np.ndarray
    rows: tuple
    columns: tuple
    title: str
    dofs: tuple = ()

    def __array__(self, dtype=None, copy=None):
        return np.array(self.matrix, dtype=dtype, copy=True if copy is None else copy)

    def __getitem__(self, key):
        return self.matrix[key]

    @property
    def shape(self) -> tuple:
        return self.matrix.shape

    def to_frame(self):
        """The matrix as a pandas DataFrame with the labels as index and columns."""
        import pandas as pd
        return pd.DataFrame(self.matrix, index=list(self.rows), columns=list(self.columns))

    def to_dict(self) -> dict:
        return {"title": self.title, "dofs": list(self.dofs), "rows": list(self.rows),
                "columns": list(self.columns), "matrix": self.matrix.tolist()}

    def __repr__(self) -> str:
        width = max(13, *(len(c) + 2 for c in self.columns))
        first = max(len(r) for r in self.rows) + 2
        lines = [self.title, " " * first + "".join(f"{c:>{width}}" for c in self.columns)]
        for label, row in zip(self.rows, self.matrix):
            lines.append(f"{label:<{first}}" + "".join(f"{v:>{width}.4e}" for v in row))
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        head = "".join(f"<th>{html.escape(c)}</th>" for c in self.columns)
        body = "".join(
            f"<tr><th>{html.escape(r)}</th>"
            + "".join(f"<td>{v:.4e}</td>" for v in row) + "</tr>"
            for r, row in zip(self.rows, self.matrix))
        return (f"<table><caption>{html.escape(self.title)}</caption>"
                f"<tr><th></th>{head}</tr>{body}</table>")


def stiffness_table(K, dofs=None) -> LabelledMatrix:
    """The mooring stiffness ``K = -dF/dq`` labelled by degree of freedom and unit.

    Parameters
    ----------
    K : array (n, n)
        From :func:`moorsolve.stiffness`.
    dofs : sequence of str, optional
        The degrees of freedom of its rows and columns, in order; default all six
        (surge, sway, heave, roll, pitch, yaw) for a 6x6 matrix, surge, sway and yaw for a
        3x3 one.

    Returns
    -------
    LabelledMatrix
        Rows are the forces (``Fx [N]``, ..., ``Mz [N m]``), columns the displacements
        (``surge [m]``, ..., ``yaw [rad]``): an entry's unit is its row's over its
        column's (N/m, N/rad, N m/m, N m/rad).
    """
    K = np.asarray(K, dtype=float)
    if dofs is None:
        dofs = tuple(DOF_LABELS) if K.shape == (6, 6) else ("surge", "sway", "yaw")
    dofs = tuple(dofs)
    if K.shape != (len(dofs), len(dofs)):
        raise ValueError(f"K has shape {K.shape}; {len(dofs)} dofs need "
                         f"({len(dofs)}, {len(dofs)})")
    rows = tuple(f"{DOF_LABELS[d][0]} [{DOF_LABELS[d][1]}]" for d in dofs)
    columns = tuple(f"{d} [{DOF_LABELS[d][2]}]" for d in dofs)
    return LabelledMatrix(K, rows, columns,
                          "mooring stiffness K = -dF/dq (entry unit: row unit / column unit)",
                          dofs)
