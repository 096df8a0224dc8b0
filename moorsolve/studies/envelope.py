"""Offset envelope: the equilibrium for every heading of a given environment.

The environment's wind, current and waves (or a chosen subset) are turned together: the
envelope's heading is the direction the *reference* flow (the first of the turned flows
present: wind, then current, then waves) travels toward, counter-clockwise from +x, and
every other turned flow keeps its angle to it from the case file. An environment whose
flows are aligned therefore travels toward the heading. Flows not turned, and the constant
``body.loads.force``, stay as the case gives them. Speeds and wave heights are unchanged.

All headings are one zipped axis of :func:`moorsolve.sweep` (compiled Newton kernel,
each heading warm-started from its neighbour, IPOPT where the kernel cannot certify).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Optional, Sequence

import numpy as np

from ..errors import CaseError
from ..model import Case
from ..physics.kinematics import wrap_degrees
from ..model.directions import Compass, direction_edit, wrap_deg
from .sweep import sweep

FLOWS = ("wind", "current", "waves")


@dataclasses.dataclass(frozen=True)
class Envelope:
    """Per heading: offset, its direction, yaw and the worst tension with its leg.

    Arrays run over ``heading_deg``. ``offset_m`` is the horizontal displacement of the
    body-frame origin, ``offset_direction_deg`` its direction (counter-clockwise from +x,
    in [0, 360)), ``worst_tension_N`` the largest fairlead or anchor tension of any leg
    and ``worst_leg`` that leg. A heading without equilibrium has ``converged = False``,
    its ``reason`` and NaN values; an equilibrium that overloads a leg keeps its values
    with ``converged = False`` and the overload as ``reason``.

    ``case_heading_deg`` is each heading as the case file writes its reference flow
    (``heading_key``, ``toward_deg`` or ``from_deg``, in the file's compass convention), and
    ``compass`` that convention: the text and HTML tables speak in the file's terms, so a
    nautical case reads "wind from 045" and the offset as a bearing.
    """

    case_name: str
    flows: tuple
    heading_deg: np.ndarray
    offset_m: np.ndarray
    offset_direction_deg: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    yaw_deg: np.ndarray
    worst_tension_N: np.ndarray
    worst_leg: tuple
    converged: np.ndarray
    reason: tuple
    table: object = dataclasses.field(repr=False, compare=False)
    case_heading_deg: Optional[np.ndarray] = None
    heading_key: str = "toward_deg"
    compass: Compass = dataclasses.field(default_factory=Compass)

    def heading_label(self) -> str:
        """The heading column's name in the case file's terms."""
        word = "from" if self.heading_key == "from_deg" else "toward"
        scale = ", clockwise from N" if self.compass.nautical else ""
        return f"{self.flows[0]} {word} [deg{scale}]"

    def file_heading(self, i: int) -> float:
        return float(self.heading_deg[i] if self.case_heading_deg is None
                     else self.case_heading_deg[i])

    def file_direction(self, i: int) -> float:
        """The offset's direction in the file's compass (a bearing when nautical)."""
        return self.compass.file_value(float(self.offset_direction_deg[i]), "toward_deg")

    def __repr__(self) -> str:
        ok = np.isfinite(self.worst_tension_N)
        worst = ""
        if ok.any():        # the heading in the case file's words (a bearing when nautical)
            i = int(np.argmax(np.where(ok, self.worst_tension_N, -np.inf)))
            word = "from" if self.heading_key == "from_deg" else "toward"
            scale = " (compass)" if self.compass.nautical else ""
            worst = (f", worst {self.worst_leg[i]} with {self.flows[0]} {word} "
                     f"{self.file_heading(i):g} deg{scale}")
        return (f"<Envelope {self.case_name!r}: {len(self.heading_deg)} headings, "
                f"{int(ok.sum())} solved{worst}>")

    def _repr_html_(self) -> str:
        from ..report.notebook import envelope_html
        return envelope_html(self)

    def worst(self) -> dict:
        """The heading with the largest worst tension (an overloaded equilibrium counts)."""
        tension = np.where(np.isfinite(self.worst_tension_N), self.worst_tension_N, -np.inf)
        if not np.isfinite(tension).any():
            raise ValueError("no heading has an equilibrium")
        return self.row(int(np.argmax(tension)))

    def largest_offset(self) -> dict:
        """The heading with the largest offset (among those with an equilibrium)."""
        offset = np.where(np.isfinite(self.offset_m), self.offset_m, -np.inf)
        if not np.isfinite(offset).any():
            raise ValueError("no heading has an equilibrium")
        return self.row(int(np.argmax(offset)))

    def row(self, i: int) -> dict:
        return {"heading_deg": float(self.heading_deg[i]),
                "case_heading": {"key": self.heading_key, "deg": self.file_heading(i),
                                 "convention": self.compass.convention},
                "offset_m": _f(self.offset_m[i]),
                "offset_direction_deg": _f(self.offset_direction_deg[i]),
                "x_m": _f(self.x_m[i]), "y_m": _f(self.y_m[i]), "yaw_deg": _f(self.yaw_deg[i]),
                "worst_tension_N": _f(self.worst_tension_N[i]), "worst_leg": self.worst_leg[i],
                "converged": bool(self.converged[i]), "reason": self.reason[i]}

    def to_dict(self) -> dict:
        out = {"case": self.case_name, "flows": list(self.flows),
               "headings": [self.row(i) for i in range(len(self.heading_deg))]}
        if np.isfinite(self.worst_tension_N).any():
            out["worst"] = self.worst()
            out["largest_offset"] = self.largest_offset()
        return out


def _f(value) -> Optional[float]:
    value = float(value)
    return value if math.isfinite(value) else None


def offset_envelope(case: Case, headings_deg: Optional[Sequence[float]] = None, *,
                    step_deg: float = 10.0, flows: Optional[Sequence[str]] = None,
                    solver: str = "newton", tol: Optional[float] = None,
                    workers: Optional[int] = None, body: Optional[str] = None,
                    allow_overload: bool = False) -> Envelope:
    """The equilibrium of ``case`` with its environment turned to every heading.

    Parameters
    ----------
    case : Case
        From :func:`moorsolve.load_case`; its environment is turned, not changed.
    headings_deg : sequence of float, optional
        Headings [deg] the reference flow travels toward; default ``0, step_deg, ...``
        below 360.
    step_deg : float
        Heading step [deg] when ``headings_deg`` is not given; 0 < step <= 180.
    flows : sequence of {"wind", "current", "waves"}, optional
        Which flows turn (default: every one the case has).
    solver, tol, workers, allow_overload
        As for :func:`moorsolve.sweep`.
    body : str, optional
        The body whose offset (from its case pose) and yaw the envelope reports; default
        the only body (a case with several bodies must name one; the worst tension is over
        every line).

    Returns
    -------
    Envelope
    """
    env = case.environment
    if not case.lines:
        raise CaseError("lines", "the envelope reports each heading's worst line tension, and "
                                 "this scene has no lines (its contacts alone hold it): "
                                 "sweep the flows' toward_deg instead (moorsolve sweep)")
    names_b = [b.name for b in case.bodies]
    if body is None and len(names_b) > 1:
        raise CaseError("body", f"the case has {len(names_b)} bodies ({', '.join(names_b)}); "
                                "name the one whose offset the envelope reports")
    if body is not None and body not in names_b:
        raise CaseError("body", f"{body!r} is not a body of the case; its bodies: "
                                f"{', '.join(names_b) or 'none'}")
    present = [f for f in FLOWS if getattr(env, f) is not None]
    if flows is None:
        flows = present
        if not flows:
            raise CaseError("environment", "has no wind, current or waves to turn; an "
                                           "envelope needs at least one")
    else:
        flows = list(flows)
        for f in flows:
            if f not in FLOWS:
                raise CaseError("flows", f"{f!r} is not one of {', '.join(FLOWS)}")
            if f not in present:
                raise CaseError("flows", f"{f!r}: the case has no environment.{f} to turn")
        if not flows or len(set(flows)) != len(flows):
            raise CaseError("flows", f"{flows!r} must name each flow at most once, at least "
                                     f"one")
        flows = [f for f in FLOWS if f in flows]
    if headings_deg is None:
        step = float(step_deg)
        if not 0 < step <= 180:
            raise CaseError("step_deg", f"{step_deg} must be > 0 and <= 180")
        headings_deg = np.arange(0.0, 360.0 - 1e-9, step)
    headings = [float(h) for h in headings_deg]
    if not headings or not all(math.isfinite(h) for h in headings):
        raise CaseError("headings_deg", "must be a non-empty list of finite angles")

    reference = getattr(env, flows[0]).toward_deg
    offsets = [getattr(env, f).toward_deg - reference for f in flows]
    # Each heading as the case file would write it (its key and compass convention).
    edits = [[direction_edit(case, f, wrap_deg(h + d)) for f, d in zip(flows, offsets)]
             for h in headings]
    paths = tuple(path for path, _ in edits[0])
    values = [tuple(value for _, value in row) for row in edits]
    table = sweep(case, {paths: values}, solver=solver, tol=tol, workers=workers,
                  allow_overload=allow_overload)

    names = [leg.name for leg in case.legs]
    tension = np.column_stack(
        [np.fmax(table[f"{n}.fairlead_tension_N"].to_numpy(float),
                 table[f"{n}.anchor_tension_N"].to_numpy(float)) for n in names])
    converged = table["converged"].to_numpy(bool)
    solved = np.isfinite(tension).all(axis=1)          # an overloaded equilibrium too
    worst_index = np.argmax(np.where(np.isfinite(tension), tension, -np.inf), axis=1)
    worst = np.where(solved, tension[np.arange(len(table)), worst_index], np.nan)
    if case.form == "network" and names_b:
        target = case.body_named(body or names_b[0])
        x0, y0, _ = target.position
        yaw0 = target.orientation_deg[2]
        x = np.where(solved, table[f"{target.name}.x_m"].to_numpy(float) - x0, np.nan)
        y = np.where(solved, table[f"{target.name}.y_m"].to_numpy(float) - y0, np.nan)
        yaw = np.where(solved, wrap_degrees(
            table[f"{target.name}.yaw_deg"].to_numpy(float) - yaw0), np.nan)
    elif case.body is not None:
        x = np.where(solved, table["x_m"].to_numpy(float), np.nan)
        y = np.where(solved, table["y_m"].to_numpy(float), np.nan)
        yaw = np.where(solved, table["yaw_deg"].to_numpy(float), np.nan)
    else:
        x = y = yaw = np.where(solved, 0.0, np.nan)
    return Envelope(
        case_name=case.name, flows=tuple(flows), heading_deg=np.array(headings),
        offset_m=np.hypot(x, y),
        offset_direction_deg=np.round(np.degrees(np.arctan2(y, x)), 9) % 360.0,
        x_m=x, y_m=y, yaw_deg=yaw, worst_tension_N=worst,
        worst_leg=tuple(names[k] if ok else "" for k, ok in zip(worst_index, solved)),
        converged=converged, reason=tuple(table["reason"]), table=table,
        case_heading_deg=np.array([row[0][1] for row in edits], dtype=float),
        heading_key=paths[0].rsplit(".", 1)[1], compass=env.compass)


def format_envelope(envelope: Envelope) -> str:
    """The envelope as a fixed-width table, with its worst heading, in the case's terms."""
    e = envelope
    bearing = "brg deg" if e.compass.nautical else "dir deg"
    lines = [f"offset envelope: {e.case_name} ({', '.join(e.flows)} turned together)",
             f"heading: {e.heading_label()}",
             f"{'heading':>7} {'offset m':>9} {bearing:>8} {'yaw deg':>8} {'worst':>8} "
             f"{'T kN':>10}"]
    for i in range(len(e.heading_deg)):
        h = e.file_heading(i)
        if not math.isfinite(e.worst_tension_N[i]):
            lines.append(f"{h:7.1f}  no equilibrium: {e.reason[i]}")
            continue
        # An overload, or a certified but unstable equilibrium: said on its row.
        note = f"  ({e.reason[i]})" if e.reason[i] else ""
        lines.append(f"{h:7.1f} {e.offset_m[i]:9.3f} {e.file_direction(i):8.1f} "
                     f"{e.yaw_deg[i]:8.3f} {e.worst_leg[i]:>8} "
                     f"{e.worst_tension_N[i] / 1e3:10.1f}{note}")
    if np.isfinite(e.worst_tension_N).any():
        w, o = e.worst(), e.largest_offset()
        lines.append(f"worst tension: {w['worst_leg']} {w['worst_tension_N'] / 1e3:.1f} kN "
                     f"with the {e.flows[0]} {e.compass.describe(w['heading_deg'])}")
        lines.append(f"largest offset: {o['offset_m']:.3f} m toward "
                     f"{_direction_words(e, o['offset_direction_deg'])} with the {e.flows[0]} "
                     f"{e.compass.describe(o['heading_deg'])}")
    return "\n".join(lines)


def _direction_words(e: Envelope, toward_deg: float) -> str:
    if e.compass.nautical:
        return f"{e.compass.file_value(toward_deg, 'toward_deg'):05.1f} deg (clockwise from north)"
    return f"{toward_deg:.1f} deg"
