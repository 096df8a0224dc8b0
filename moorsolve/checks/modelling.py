"""Warnings that catch modelling slips in a solved case: the answer is an equilibrium, but of
a model that is probably not the one meant.

What is looked for (each warning carries its figure and the limit it broke):

- ``anchor_above_seabed``: a fixed line end (an anchor) hovering above the seabed by more
  than 5 % of the depth (and 0.5 m) while its own line rests on the seabed below it. A
  MoorDyn file without WtrDpth takes the depth from its deepest point, so anchors metres
  above the chain lying under them usually mean a wrong depth, not a rock.
- ``below_seabed``: a line passing below the seabed by more than 0.1 % of the depth
  (and 1 cm). Lines whose anchor is above the seabed, and buoyant lines, are suspended
  catenaries without seabed contact; sagging into the ground means the line is too long
  for that model or the depth is wrong.
- ``all_slack``: every line is slack (no horizontal tension): the mooring holds nothing
  horizontally and the equilibrium is degenerate (lines longer than their span, or anchors
  misplaced).
- ``drift``: a body displaced horizontally by more than the water depth: loads, units or
  line lengths are likely wrong (a mooring designed to hold a body keeps its offset to a
  fraction of the depth).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["ModellingWarning", "modelling_warnings"]

#: An anchor higher than this fraction of the depth above the seabed is flagged ...
ANCHOR_HEIGHT_FRACTION = 0.05
#: ... and higher than this [m].
ANCHOR_HEIGHT_MIN = 0.5
#: A line lower than this fraction of the depth below the seabed is flagged ...
BELOW_SEABED_FRACTION = 1e-3
#: ... and lower than this [m].
BELOW_SEABED_MIN = 0.01
#: A body displaced by more than this multiple of the water depth is flagged.
DRIFT_DEPTHS = 1.0


@dataclass(frozen=True)
class ModellingWarning:
    """One suspected modelling slip: ``code`` (see the module notes), the ``subject`` (a leg
    or body name), the ``value`` found and the ``limit`` it passed [m], and a ``message``
    that says both and what to check."""

    code: str
    subject: str
    value: float
    limit: float
    message: str

    def __str__(self) -> str:
        return self.message


def _anchors(case, result, depth: float) -> list:
    out = []
    env = case.environment
    limit = max(ANCHOR_HEIGHT_MIN, ANCHOR_HEIGHT_FRACTION * depth)
    for line, leg in zip(case.lines, result.legs):
        if not leg.grounded_length_m > 0:
            continue
        for end, (x, y, z) in ((line.a, leg.anchor), (line.b, leg.fairlead)):
            height = z - env.seabed_z(x, y)
            if end.fixed and height > limit:
                where = f" ({end.label})" if end.label else ""
                out.append(ModellingWarning(
                    "anchor_above_seabed", leg.name, height, limit,
                    f"line {leg.name}: its fixed end{where} is {height:.3g} m above the seabed "
                    f"(depth {depth:.6g} m; flagged above {limit:.3g} m) while the line rests "
                    f"on the seabed below it: is the water depth right? A MoorDyn file "
                    "without WtrDpth takes the depth of its deepest point"))
    return out


def _below_seabed(case, result, depth: float) -> list:
    out = []
    env = case.environment
    limit = max(BELOW_SEABED_MIN, BELOW_SEABED_FRACTION * depth)
    for leg in result.legs:
        p = leg.profile
        if not p or "z_m" not in p:
            continue
        xs, ys, zs = (np.asarray(p[k], dtype=float) for k in ("x_m", "y_m", "z_m"))
        bed = np.array([env.seabed_z(x, y) for x, y in zip(xs, ys)])
        dip = bed - zs
        k = int(np.argmax(dip))
        if dip[k] > limit:
            out.append(ModellingWarning(
                "below_seabed", leg.name, float(dip[k]), limit,
                f"leg {leg.name}: the line passes {dip[k]:.3g} m below the seabed (at x "
                f"{xs[k]:.6g} m, y {ys[k]:.6g} m, z {zs[k]:.6g} m; seabed {bed[k]:.6g} m): a "
                "suspended line without seabed contact; check the depth and the line length"))
    return out


def _slack(result) -> list:
    legs = list(result.legs)
    if legs and all(leg.slack for leg in legs):
        heaviest = max(leg.fairlead_tension_N for leg in legs)
        return [ModellingWarning(
            "all_slack", "mooring", 0.0, 0.0,
            f"all {len(legs)} lines are slack (no horizontal tension; the largest tension "
            f"{heaviest:.6g} N is hanging weight): the mooring holds nothing horizontally; "
            "check the line lengths against the anchor spacing")]
    return []


def _drift(case, result, depth: float) -> list:
    limit = DRIFT_DEPTHS * depth
    # Network results give each body's absolute pose and, under "offset", its displacement;
    # a legs-form result its body's displacement.
    poses = [(b.get("name", "body"), b.get("offset", b))
             for b in getattr(result, "bodies", None) or ()]
    if not poses and getattr(result, "body", None):
        poses.append(("body", result.body))
    out = []
    for name, pose in poses:
        offset = math.hypot(pose.get("x_m", 0.0), pose.get("y_m", 0.0))
        if offset <= limit:
            continue
        held = _held_where(case, result, name)
        if held is not None and held <= limit:
            continue        # it turned about where its lines hold it (a turret), no slip
        out.append(ModellingWarning(
            "drift", name, offset, limit,
            f"{name}: displaced {offset:.6g} m horizontally, more than the water depth "
            f"{depth:.6g} m: check the loads, their units and the line lengths"))
    return out


def _held_where(case, result, name: str):
    """The least horizontal displacement [m] of the body's line ends from their case-pose
    places (None without lines on it): a ship weathervaning about its turret swings its
    origin far while the turret, where the mooring holds it, barely moves."""
    from ..model.build_network import end_position
    bodies = {b.name: b for b in getattr(case, "bodies", ())}
    if len(bodies) == 1 and name == "body":
        name = next(iter(bodies))
    moved = []
    for line, leg in zip(getattr(case, "lines", ()), result.legs):
        for end, now in ((line.a, leg.anchor), (line.b, leg.fairlead)):
            if end.body == name and end.body in bodies:
                before = end_position(end, bodies)
                moved.append(math.hypot(now[0] - before[0], now[1] - before[1]))
    return min(moved) if moved else None


def modelling_warnings(case, result) -> list:
    """The suspected modelling slips of a solved case (see the module notes).

    Parameters
    ----------
    case : moorsolve.Case
        The case that was solved.
    result : moorsolve.Result
        Its equilibrium.

    Returns
    -------
    list of ModellingWarning
        Empty when nothing looks wrong.
    """
    depth = case.environment.depth
    return (_anchors(case, result, depth) + _below_seabed(case, result, depth)
            + _slack(result) + _drift(case, result, depth))
