"""Read a bathymetry grid file into the ``{x, y, depth}`` mapping the case file takes inline.

Three forms, told apart by the file's suffix:

- ``.nc`` / ``.nc4`` / ``.cdf``: NetCDF read with xarray (optional: ``pip install xarray
  netCDF4``); coordinates ``x`` and ``y`` and a variable ``depth`` on ``(y, x)`` (positive
  down). A variable ``z`` or ``elevation`` (positive up) is accepted instead of ``depth``.
- ``.csv``: columns ``x, y, depth`` with a header row naming them (any order of columns,
  any order of rows); every (x, y) pair of the grid exactly once.
- anything else: MoorDyn's SeafloorFile. MoorDyn-F's and MoorPy's (``readBathymetryFile``)
  form: a header line, ``nGridX N``, ``nGridY M``, a line of N x values, then M lines
  ``y d_1 ... d_N`` of depths positive down; or MoorDyn-C's form (told by a first line of
  two counts ``N M``): the N x values, the M y values, then one ``x y z`` row per node with
  the seabed's height z (negative down).

Every reader raises :class:`~moorsolve.errors.CaseError` naming the case field and the
file's line; the model (:mod:`moorsolve.model.bathymetry`) validates the grid itself.
"""

from __future__ import annotations

import csv
import math
from os import PathLike
from pathlib import Path

from ..errors import CaseError

__all__ = ["read_bathymetry", "read_seafloor_file", "seafloor_text", "seafloor_option",
           "resolve_in_case"]

FIELD = "environment.seabed.bathymetry"


def _number(token: str, where: str, field: str) -> float:
    try:
        v = float(token)
    except ValueError:
        raise CaseError(field, f"{where}: {token!r} is not a number") from None
    if not math.isfinite(v):
        raise CaseError(field, f"{where}: {token!r} is not finite")
    return v


def read_seafloor_file(path: Path, field: str = FIELD) -> dict:
    """MoorDyn's SeafloorFile as ``{x, y, depth}`` (depth rows over y, positive down)."""
    lines = [ln for ln in _text(path, field).splitlines() if ln.strip()]
    name = path.name
    first = lines[0].split() if lines else []
    if len(first) == 2 and all(t.isdigit() for t in first):
        return _moordyn_c(lines, name, field)
    if len(lines) < 4:
        raise CaseError(field, f"{name}: {len(lines)} non-empty lines; a SeafloorFile has a "
                               "header, nGridX N, nGridY M, the x values and M rows")
    counts = []
    for k, key in ((1, "ngridx"), (2, "ngridy")):
        parts = lines[k].split()
        if len(parts) < 2 or parts[0].lower() != key:
            raise CaseError(field, f"{name} line {k + 1}: {lines[k].strip()!r} should be "
                                   f"'{'nGridX' if k == 1 else 'nGridY'} <count>'")
        try:
            n = int(parts[1])
        except ValueError:
            raise CaseError(field, f"{name} line {k + 1}: {parts[1]!r} is not a count") from None
        if n < 1:
            raise CaseError(field, f"{name} line {k + 1}: the count {n} must be >= 1")
        counts.append(n)
    nx, ny = counts
    xs = lines[3].split()
    if len(xs) != nx:
        raise CaseError(field, f"{name} line 4: {len(xs)} x values where nGridX is {nx}")
    x = [_number(t, f"{name} line 4", field) for t in xs]
    rows = lines[4:]
    if len(rows) != ny:
        raise CaseError(field, f"{name}: {len(rows)} rows of depths where nGridY is {ny}")
    y, depth = [], []
    for j, row in enumerate(rows):
        where = f"{name} line {j + 5}"
        parts = row.split()
        if len(parts) != nx + 1:
            raise CaseError(field, f"{where}: {len(parts)} values; a row is y then {nx} depths")
        y.append(_number(parts[0], where, field))
        depth.append([_number(t, where, field) for t in parts[1:]])
    return {"x": x, "y": y, "depth": depth}


def _moordyn_c(lines: list, name: str, field: str) -> dict:
    """MoorDyn-C's form: ``nx ny``, the x values, the y values, then ``x y z`` rows with
    the seabed's height z (negative down), every node once."""
    nx, ny = (int(t) for t in lines[0].split())
    if len(lines) < 3:
        raise CaseError(field, f"{name}: no x and y values after '{nx} {ny}'")
    axes = []
    for k, n, what in ((1, nx, "x"), (2, ny, "y")):
        tokens = lines[k].split()
        if len(tokens) != n:
            raise CaseError(field, f"{name} line {k + 1}: {len(tokens)} {what} values where "
                                   f"line 1 gives {n}")
        axes.append([_number(t, f"{name} line {k + 1}", field) for t in tokens])
    x, y = axes
    nodes = {}
    for k, row in enumerate(lines[3:], start=4):
        parts = row.split()
        where = f"{name} line {k}"
        if len(parts) != 3:
            raise CaseError(field, f"{where}: {len(parts)} values; each row is x, y, z")
        px, py, pz = (_number(t, where, field) for t in parts)
        if px not in x or py not in y:
            raise CaseError(field, f"{where}: ({px:g}, {py:g}) is not a node of the grid")
        nodes[(px, py)] = -pz
    missing = [(a, b) for b in y for a in x if (a, b) not in nodes]
    if missing:
        raise CaseError(field, f"{name}: {len(missing)} grid nodes have no depth, the first "
                               f"({missing[0][0]:g}, {missing[0][1]:g})")
    return {"x": x, "y": y, "depth": [[nodes[(a, b)] for a in x] for b in y]}


def read_csv_grid(path: Path, field: str = FIELD) -> dict:
    """A CSV of ``x, y, depth`` rows forming a complete rectangular grid."""
    name = path.name
    reader = csv.reader(_text(path, field).splitlines())
    try:
        header = [h.strip().lower() for h in next(reader)]
    except StopIteration:
        raise CaseError(field, f"{name} is empty") from None
    if sorted(header) != ["depth", "x", "y"]:
        raise CaseError(field, f"{name} line 1: columns {header}; a bathymetry CSV has the "
                               "three columns x, y, depth (depth positive down) with a header")
    ix, iy, idep = (header.index(k) for k in ("x", "y", "depth"))
    nodes = {}
    for k, row in enumerate(reader, start=2):
        if not row or not any(c.strip() for c in row):
            continue
        where = f"{name} line {k}"
        if len(row) != 3:
            raise CaseError(field, f"{where}: {len(row)} values; each row is x, y, depth")
        x, y, d = (_number(row[i].strip(), where, field) for i in (ix, iy, idep))
        if (x, y) in nodes:
            raise CaseError(field, f"{where}: the node ({x:g}, {y:g}) appears twice")
        nodes[(x, y)] = d
    xs = sorted({x for x, _ in nodes})
    ys = sorted({y for _, y in nodes})
    if len(nodes) != len(xs) * len(ys):
        missing = next((x, y) for y in ys for x in xs if (x, y) not in nodes)
        raise CaseError(field, f"{name}: {len(nodes)} nodes do not fill the {len(xs)} x "
                               f"{len(ys)} grid of their coordinates; ({missing[0]:g}, "
                               f"{missing[1]:g}) is missing")
    return {"x": xs, "y": ys, "depth": [[nodes[(x, y)] for x in xs] for y in ys]}


def read_netcdf_grid(path: Path, field: str = FIELD) -> dict:
    """A NetCDF grid read with xarray: coordinates ``x``, ``y``; ``depth`` (positive down)
    or ``z`` / ``elevation`` (positive up) on ``(y, x)``."""
    try:
        import xarray
    except ImportError:
        raise CaseError(field, f"{path.name}: reading a NetCDF bathymetry needs xarray and a "
                               "NetCDF backend (pip install xarray netCDF4), or give the grid "
                               "as CSV or a MoorDyn SeafloorFile") from None
    if not path.is_file():
        raise CaseError(field, f"{path}: file not found")
    try:
        with xarray.open_dataset(path) as ds:
            ds = ds.load()
    except (ValueError, OSError) as exc:
        raise CaseError(field, f"{path.name}: cannot read as NetCDF ({exc}); a NetCDF "
                               "backend (netCDF4 or scipy) may be missing") from None
    for key in ("x", "y"):
        if key not in ds.coords:
            raise CaseError(field, f"{path.name}: no coordinate {key!r} (has "
                                   f"{sorted(map(str, ds.coords))})")
    if "depth" in ds:
        grid, sign = ds["depth"], 1.0
    elif "z" in ds or "elevation" in ds:
        grid, sign = ds["z" if "z" in ds else "elevation"], -1.0
    else:
        raise CaseError(field, f"{path.name}: no variable 'depth' (positive down) or 'z' / "
                               f"'elevation' (positive up); has {sorted(map(str, ds.data_vars))}")
    if set(grid.dims) != {"x", "y"}:
        raise CaseError(field, f"{path.name}: {grid.name!r} is on {grid.dims}, not (y, x)")
    values = grid.transpose("y", "x").values * sign
    return {"x": [float(v) for v in ds["x"].values], "y": [float(v) for v in ds["y"].values],
            "depth": [[float(v) for v in row] for row in values]}


def read_bathymetry(path, field: str = FIELD) -> dict:
    """The grid in file ``path`` as ``{x, y, depth}``, chosen by its suffix (module notes)."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in (".nc", ".nc4", ".cdf"):
        return read_netcdf_grid(path, field)
    if suffix == ".csv":
        return read_csv_grid(path, field)
    return read_seafloor_file(path, field)


def _text(path: Path, field: str) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise CaseError(field, f"{path}: file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise CaseError(field, f"{path}: cannot read ({exc})") from None


def resolve_in_case(data, base: Path):
    """``data`` (case-file data) with a bathymetry file name read into its grid, and the
    same data with the name made absolute (kept as the case's source); ``data`` itself
    when it names no file. A relative name is taken from ``base`` (the case file's folder)."""
    env = data.get("environment") if hasattr(data, "get") else None
    seabed = env.get("seabed") if hasattr(env, "get") else None
    name = seabed.get("bathymetry") if hasattr(seabed, "get") else None
    if not isinstance(name, (str, PathLike)):
        return data, data
    path = Path(name)
    if not path.is_absolute():
        path = base / path
    grid = {**read_bathymetry(path), "source": str(path)}
    grid_source = {**seabed, "bathymetry": grid}
    named = {**seabed, "bathymetry": str(path)}
    built = {**data, "environment": {**env, "seabed": grid_source}}
    kept = {**data, "environment": {**env, "seabed": named}}
    return built, kept


def seafloor_text(bathymetry) -> str:
    """``bathymetry`` (:class:`~moorsolve.model.bathymetry.Bathymetry`) as MoorDyn-F's
    SeafloorFile (which MoorPy reads too)."""
    rows = ["--- MoorDyn bathymetry input file (written by moorsolve) ---",
            f"nGridX {len(bathymetry.x)}", f"nGridY {len(bathymetry.y)}",
            " ".join(repr(v) for v in bathymetry.x)]
    rows += [" ".join(repr(v) for v in (y, *row)) for y, row in zip(bathymetry.y,
                                                                     bathymetry.depth)]
    return "\n".join(rows) + "\n"


def seafloor_option(env, files, prefix: str = "") -> list:
    """The MoorDyn option ``[SeafloorFile, name]`` of a bathymetry grid (none without one),
    the file's text put into ``files`` (``{name: text}``) for the caller to write beside
    the input file."""
    grid = env.seabed.bathymetry
    if grid is None:
        return []
    name = f"{prefix}seafloor.txt"
    if files is not None:
        files[name] = seafloor_text(grid)
    return [["SeafloorFile", name]]
