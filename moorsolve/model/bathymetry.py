"""A seabed given as a grid of depths: validation, bilinear interpolation and its gradient.

The grid holds depths (positive down, from the case's datum) at the nodes of a rectangular
grid, ``depth[j][i]`` at ``(x[i], y[j])`` (rows run over y, as in MoorDyn's SeafloorFile).
Between nodes the surface is bilinear in each cell, as MoorDyn and MoorPy interpolate it;
beyond the grid's edges the depth of the nearest edge holds (the surface is extended
horizontally outward, so a point past a corner takes the corner's depth). A grid that
samples a plane reproduces the plane exactly inside the grid.

The files (MoorDyn's SeafloorFile, CSV, NetCDF) are read in :mod:`moorsolve.io.bathymetry`,
which hands this module the same ``{x, y, depth}`` mapping a case file may give inline.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from ..errors import CaseError
from .fields import MAX_DEPTH, check_list, check_mapping, field_path
from .units import show_value

__all__ = ["Bathymetry", "bathymetry_from_mapping"]

#: Most grid nodes accepted (a 2000 x 2000 survey); a larger grid is better decimated.
MAX_NODES = 4_000_000


@dataclass(frozen=True)
class Bathymetry:
    """A rectangular grid of seabed depths [m, positive down] and where it came from.

    ``x`` and ``y`` strictly increasing [m]; ``depth[j][i]`` at ``(x[i], y[j])``.
    ``source`` names the file (or ``"inline"``) for reports.
    """

    x: tuple
    y: tuple
    depth: tuple
    #: Not compared: the same grid read from another file is the same seabed.
    source: str = field(default="inline", compare=False)

    def __post_init__(self):
        import numpy as np  # here: the model is imported by `moorsolve --help`, numpy is not

        # The arrays the interpolation reads, made once (read-only: safe across threads).
        arrays = {k: np.array(getattr(self, k), float) for k in ("x", "y", "depth")}
        for a in arrays.values():
            a.setflags(write=False)
        object.__setattr__(self, "_arrays", arrays)

    def __repr__(self) -> str:
        # A survey grid has thousands of depths: the shape and the range, not the values.
        flat = [d for row in self.depth for d in row]
        return (f"Bathymetry({len(self.x)} x {len(self.y)} nodes, x {self.x[0]:g} to "
                f"{self.x[-1]:g} m, y {self.y[0]:g} to {self.y[-1]:g} m, depth {min(flat):g} "
                f"to {max(flat):g} m, {self.source})")

    def __hash__(self) -> int:
        # The axes and the outer rows: cheap for a large grid (equality still compares all).
        return hash((self.x, self.y, self.depth[0], self.depth[-1]))

    def _cell(self, v, axis):
        import numpy as np

        v = np.clip(np.asarray(v, float), axis[0], axis[-1])
        if axis.size == 1:
            return np.zeros(v.shape, int), np.zeros(v.shape), v, 1.0
        k = np.clip(np.searchsorted(axis, v, side="right") - 1, 0, axis.size - 2)
        width = axis[k + 1] - axis[k]
        return k, (v - axis[k]) / width, v, width

    def _corners(self, x, y):
        import numpy as np

        grid = self._arrays
        d = grid["depth"]
        i, fx, _, wx = self._cell(x, grid["x"])
        j, fy, _, wy = self._cell(y, grid["y"])
        i1 = np.minimum(i + 1, d.shape[1] - 1)
        j1 = np.minimum(j + 1, d.shape[0] - 1)
        return (d[j, i], d[j, i1], d[j1, i], d[j1, i1]), fx, fy, wx, wy

    def height(self, x, y):
        """Seabed height z [m] (negative below the datum) at ``(x, y)``, bilinear.

        Works on floats (returns a float) and on numpy arrays of one shape.
        """
        import numpy as np

        (d00, d10, d01, d11), fx, fy, _, _ = self._corners(x, y)
        d = (d00 * (1 - fx) * (1 - fy) + d10 * fx * (1 - fy) + d01 * (1 - fx) * fy
             + d11 * fx * fy)
        z = -d
        return float(z) if np.ndim(z) == 0 else z

    def gradient(self, x: float, y: float) -> tuple:
        """``(dz/dx, dz/dy)`` of the surface at ``(x, y)`` (0 across a held edge; on a
        cell boundary, the cell above it)."""
        import numpy as np

        (d00, d10, d01, d11), fx, fy, wx, wy = self._corners(x, y)
        gx = -((d10 - d00) * (1 - fy) + (d11 - d01) * fy) / wx
        gy = -((d01 - d00) * (1 - fx) + (d11 - d10) * fx) / wy
        # Held constant beyond the edges: no slope out there.
        if len(self.x) == 1 or not self.x[0] <= x <= self.x[-1]:
            gx = 0.0
        if len(self.y) == 1 or not self.y[0] <= y <= self.y[-1]:
            gy = 0.0
        return float(np.asarray(gx)), float(np.asarray(gy))

    @property
    def spacing(self) -> float:
        """The smallest node spacing [m] (inf for a single node)."""
        gaps = [b - a for axis in (self.x, self.y) for a, b in zip(axis, axis[1:])]
        return min(gaps) if gaps else math.inf


def _axis(raw, path: str, name: str) -> tuple:
    items = check_list(raw, path, f"a list of {name} coordinates [m]")
    values = []
    for k, v in enumerate(items):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise CaseError(field_path(path, k), f"{show_value(v)} is not a finite number [m]")
        values.append(float(v))
    if not values:
        raise CaseError(path, "is empty; a grid needs at least one node on each axis")
    for k in range(1, len(values)):
        if values[k] <= values[k - 1]:
            raise CaseError(field_path(path, k),
                            f"{values[k]:g} follows {values[k - 1]:g}: the {name} coordinates "
                            "must be strictly increasing")
    return tuple(values)


def bathymetry_from_mapping(raw, path: str, source: str = "inline") -> Bathymetry:
    """The validated :class:`Bathymetry` of ``{x: [...], y: [...], depth: [[...], ...]}``
    (and an optional ``source``, the grid's origin for reports).

    ``depth`` has one row per y value, each with one depth per x value, every depth finite,
    positive (below the datum) and at most :data:`~.fields.MAX_DEPTH`.
    """
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a grid: give a file name (a MoorDyn "
                              "SeafloorFile, .csv or .nc) or {x: [...], y: [...], "
                              "depth: [[...], ...]}")
    m = check_mapping(raw, path, section="bathymetry")
    if "source" in m:
        # Where the grid came from (the file the case named), for reports.
        if not isinstance(m["source"], str):
            raise CaseError(field_path(path, "source"), f"{show_value(m['source'])} is not "
                                                        "a text naming the grid's origin")
        source = m["source"]
    xs = _axis(m["x"], field_path(path, "x"), "x")
    ys = _axis(m["y"], field_path(path, "y"), "y")
    if len(xs) * len(ys) > MAX_NODES:
        raise CaseError(path, f"{len(xs)} x {len(ys)} nodes: at most {MAX_NODES} are accepted; "
                              "decimate the grid")
    dpath = field_path(path, "depth")
    rows = check_list(m["depth"], dpath, "one row of depths per y value")
    if len(rows) != len(ys):
        raise CaseError(dpath, f"has {len(rows)} rows for {len(ys)} y values; give one row "
                               "per y value")
    depth = []
    for j, row in enumerate(rows):
        rpath = field_path(dpath, j)
        values = check_list(row, rpath, "one depth per x value")
        if len(values) != len(xs):
            raise CaseError(rpath, f"has {len(values)} depths for {len(xs)} x values")
        out = []
        for i, v in enumerate(values):
            vpath = field_path(rpath, i)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise CaseError(vpath, f"{show_value(v)} is not a finite depth [m]")
            if not 0 < v <= MAX_DEPTH:
                raise CaseError(vpath, f"depth {v:g} m must be > 0 (below the datum, positive "
                                       f"down) and <= {MAX_DEPTH:g} m")
            out.append(float(v))
        depth.append(tuple(out))
    return Bathymetry(x=xs, y=ys, depth=tuple(depth), source=source)


def check_scene(environment, lines, points, contacts, network: bool) -> None:
    """Refuse what a bathymetry grid does not model yet, naming the field.

    Each one-segment line gets its own seabed plane, and each free point the plane touching
    the grid where it rests (:mod:`moorsolve.solve.lines.bathymetry`); multi-segment and
    lumped-node lines and piles read one seabed plane for the whole scene, which a grid
    does not give.
    """
    if environment.seabed.bathymetry is None:
        return
    key = "lines" if network else "legs"
    for line in lines:
        where = f"{key}[{line.name}]"
        if len(line.segments) > 1:
            raise CaseError(field_path(where, "segments"),
                            f"{len(line.segments)} segments on a bathymetry seabed: a grid "
                            "takes one-segment lines (give environment.seabed.gradient for "
                            "a plane, or split the line at a fixed point)")
        if environment.current is not None and line.line_type.drag is not None:
            raise CaseError(field_path(where, "segments"),
                            "a line with drag data in a current is a lumped-node line, which "
                            "a bathymetry seabed does not take yet (remove the drag data or "
                            "the current)")
    if contacts.piles:
        raise CaseError(f"piles[{contacts.piles[0].name}]", "piles on a bathymetry seabed are "
                        "not modelled yet (give environment.seabed.gradient for a plane)")
