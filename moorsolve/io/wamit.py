"""WAMIT output files in and out: ``.1`` (added mass and damping), ``.3`` (exciting force)
and the mean drift force (``.8`` momentum, ``.9`` pressure integration, or the diagonal of
the ``.12d`` difference-frequency QTF).

Rows are whitespace-separated numbers, the first column the wave period [s] (WAMIT's
default output, IPEROUT = 1); rows with a period <= 0 (zero and infinite frequency) are
skipped. Values stay non-dimensional here: :mod:`moorsolve.model.wamit_scale` makes them
dimensional with the case's ULEN, density and gravity.

- ``.1``:   ``PER I J Abar Bbar``
- ``.3``:   ``PER BETA I |X| phase Re Im``
- ``.8/.9``: ``PER BETA1 BETA2 I |F| phase Re Im`` (rows with BETA1 = BETA2 kept)
- ``.12d``: ``PER1 PER2 BETA1 BETA2 I |F| phase Re Im`` (PER1 = PER2, BETA1 = BETA2 kept)
"""

from __future__ import annotations

import math
from os import PathLike
from pathlib import Path

import numpy as np

from ..errors import CaseError

SUFFIXES = (".1", ".3", ".8", ".9", ".12d")
_DRIFT = (".8", ".9", ".12d")


def _rows(path: Path, width: int) -> np.ndarray:
    try:
        text = path.read_text()
    except OSError as exc:
        raise CaseError(str(path), f"cannot read the WAMIT file: {exc.strerror or exc}") from None
    rows = []
    for n, line in enumerate(text.splitlines(), start=1):
        parts = line.split()
        if not parts:
            continue
        try:
            values = [float(p.replace("D", "E").replace("d", "e")) for p in parts]
        except ValueError:
            raise CaseError(str(path), f"line {n}: {line.strip()!r} is not a row of numbers") \
                from None
        if len(values) < width:
            raise CaseError(str(path), f"line {n}: {len(values)} columns; a row of this file "
                                       f"has {width}")
        rows.append(values[:width])
    if not rows:
        raise CaseError(str(path), "holds no rows")
    return np.array(rows)


def _omega_index(periods: np.ndarray):
    per = np.unique(periods[periods > 0])
    omega = np.sort(2 * math.pi / per)
    return omega, lambda p: np.searchsorted(omega, 2 * math.pi / p)


def read_wamit(files) -> dict:
    """Non-dimensional hydrodynamics in table form from WAMIT files (one ``.1``, one ``.3``,
    at most one drift file), keyed like a case file's ``hydrodynamics`` table."""
    by_suffix = {}
    for f in files:
        path = Path(f)
        suffix = path.suffix.lower()
        if suffix not in SUFFIXES:
            raise CaseError(str(path), f"unknown WAMIT file type {suffix!r}; give "
                                       f"{', '.join(SUFFIXES)}")
        if suffix in by_suffix or (suffix in _DRIFT and any(s in by_suffix for s in _DRIFT)):
            raise CaseError(str(path), "one file of each kind (one .1, one .3 and at most one "
                                       "drift file .8, .9 or .12d)")
        by_suffix[suffix] = path
    for need in (".1", ".3"):
        if need not in by_suffix:
            raise CaseError("files", f"a WAMIT {need} file is required")
    _rows(by_suffix[".1"], 4)          # checks every row (PER I J Abar at least)
    five = np.array([r for r in _read_all(by_suffix[".1"]) if r[0] > 0])
    if five.size == 0:
        raise CaseError(str(by_suffix[".1"]), "holds no row with a period > 0")
    omega, index = _omega_index(five[:, 0])
    n = omega.size
    A = np.zeros((n, 6, 6))
    B = np.zeros((n, 6, 6))
    for per, i, j, a, b in five:
        k = index(per)
        A[k, int(i) - 1, int(j) - 1] = a
        B[k, int(i) - 1, int(j) - 1] = b
    three = _rows(by_suffix[".3"], 7)
    three = three[three[:, 0] > 0]
    excitation = _per_heading(three, omega, index, heading_col=1, mode_col=2, re_col=5)
    out = {"omega": omega.tolist(), "added_mass": A.tolist(), "damping": B.tolist(),
           "excitation": [{"heading_deg": h, "re": v.real.tolist(), "im": v.imag.tolist()}
                          for h, v in excitation]}
    drift = [s for s in _DRIFT if s in by_suffix]
    if drift:
        suffix = drift[0]
        if suffix == ".12d":
            rows = _rows(by_suffix[suffix], 9)
            rows = rows[(rows[:, 0] > 0) & (rows[:, 0] == rows[:, 1]) & (rows[:, 2] == rows[:, 3])]
            rows = rows[:, [0, 2, 3, 4, 5, 6, 7, 8]]
        else:
            rows = _rows(by_suffix[suffix], 8)
            rows = rows[(rows[:, 0] > 0) & (rows[:, 1] == rows[:, 2])]
        values = _per_heading(rows, omega, index, heading_col=1, mode_col=3, re_col=6)
        out["mean_drift"] = [{"heading_deg": h, "values": v.real.tolist()} for h, v in values]
    return out


def _read_all(path: Path) -> list:
    """Rows of a ``.1`` file padded to 5 columns (zero/infinite-frequency rows lack Bbar)."""
    rows = []
    for line in path.read_text().splitlines():
        parts = [float(p.replace("D", "E").replace("d", "e")) for p in line.split()]
        if parts:
            rows.append((parts + [0.0] * 5)[:5])
    return rows


def _per_heading(rows, omega, index, *, heading_col, mode_col, re_col) -> list:
    out = []
    headings = np.unique(rows[:, heading_col])
    for h in headings:
        v = np.zeros((omega.size, 6), dtype=complex)
        seen = np.zeros(omega.size, dtype=bool)
        for r in rows[rows[:, heading_col] == h]:
            k = index(r[0])
            v[k, int(r[mode_col]) - 1] = r[re_col] + 1j * r[re_col + 1]
            seen[k] = True
        out.append((float(h), v))
    return out


def resolve_in_case(data, base: Path):
    """``data`` with each body's ``hydrodynamics: {source: wamit, files}`` read (names taken
    from ``base``, the case file's folder), and the same data with the names made absolute."""
    bodies = data.get("bodies") if hasattr(data, "get") else None
    if not isinstance(bodies, list):
        return data, data
    built, kept, changed = [], [], False
    for i, body in enumerate(bodies):
        hydro = body.get("hydrodynamics") if hasattr(body, "get") else None
        if not (hasattr(hydro, "get") and hydro.get("source") == "wamit"
                and isinstance(hydro.get("files"), list)
                and all(isinstance(f, (str, PathLike)) for f in hydro["files"])):
            built.append(body)
            kept.append(body)
            continue
        paths = [Path(f) if Path(f).is_absolute() else base / f for f in hydro["files"]]
        try:
            values = read_wamit(paths)
        except CaseError as exc:
            raise CaseError(f"bodies[{i}].hydrodynamics.files",
                            f"{exc.field}: {exc.detail}") from None
        names = [str(p) for p in paths]
        built.append({**body, "hydrodynamics": {**hydro, "files": names, "values": values}})
        kept.append({**body, "hydrodynamics": {**hydro, "files": names}})
        changed = True
    if not changed:
        return data, data
    return {**data, "bodies": built}, {**data, "bodies": kept}


def write_wamit(prefix, table: dict, *, ulen: float = 1.0, rho: float = 1025.0,
                g: float = 9.80665, drift: str = ".9") -> list:
    """Write SI table-form hydrodynamics as WAMIT files ``prefix.1``, ``prefix.3`` and (with
    a ``mean_drift``) ``prefix`` + ``drift``; returns the paths written."""
    from ..model.wamit_scale import non_dimensional

    nd = non_dimensional(table, ulen, rho, g)
    omega = np.asarray(nd["omega"])
    per = 2 * math.pi / omega
    prefix = str(prefix)
    paths = [Path(prefix + ".1"), Path(prefix + ".3")]
    A, B = np.asarray(nd["added_mass"]), np.asarray(nd["damping"])
    lines = [f"{per[k]:.8E} {i + 1} {j + 1} {A[k, i, j]:.8E} {B[k, i, j]:.8E}"
             for k in range(omega.size) for i in range(6) for j in range(6)]
    paths[0].write_text("\n".join(lines) + "\n")
    lines = []
    for h in nd["excitation"]:
        X = np.asarray(h["re"]) + 1j * np.asarray(h["im"])
        for k in range(omega.size):
            for i in range(6):
                x = X[k, i]
                lines.append(f"{per[k]:.8E} {h['heading_deg']:.6f} {i + 1} {abs(x):.8E} "
                             f"{math.degrees(np.angle(x)):.6f} {x.real:.8E} {x.imag:.8E}")
    paths[1].write_text("\n".join(lines) + "\n")
    if nd["mean_drift"]:
        path = Path(prefix + drift)
        modes = (0, 1, 5) if drift == ".8" else range(6)
        lines = []
        for h in nd["mean_drift"]:
            D = np.asarray(h["values"])
            b = f"{h['heading_deg']:.6f}"
            for k in range(omega.size):
                for i in modes:
                    d = D[k, i]
                    pre = f"{per[k]:.8E} {per[k]:.8E}" if drift == ".12d" else f"{per[k]:.8E}"
                    lines.append(f"{pre} {b} {b} {i + 1} {abs(d):.8E} "
                                 f"{0.0 if d >= 0 else 180.0:.6f} {d:.8E} {0.0:.8E}")
        path.write_text("\n".join(lines) + "\n")
        paths.append(path)
    return paths
