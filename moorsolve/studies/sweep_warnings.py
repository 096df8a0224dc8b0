"""Which sweep points the compiled kernel certified might carry a Result warning.

A full solve words its warnings (``Result.warnings``: a line afloat, a line end above the
water, a sealed line's wall in compression); the kernel's rows have no Result. A row that
might carry one is left for the full solve. The screen decides from the case where it can
(one-segment sinking lines of unsealed types, no free points: only the heights of the line
ends on bodies can change), from the kernel's body poses where bodies heave, roll or pitch,
and only otherwise from the kernel's report at the point (one more compiled call a row).
"""

from __future__ import annotations

import numpy as np

from ..solve.assembly.prepared import line_facts
from ..solve.assembly.problem import LINE_COLUMNS

#: What the screen needs: nothing, the body poses, or the report at the point.
NONE, POSE, POST = "none", "pose", "post"
_LIFTING = ("heave", "roll", "pitch")


class WarningScreen:
    """The screen of one problem (cached in ``problem.derived``: :func:`screen`)."""

    def __init__(self, problem):
        case = self.case = problem.case
        self.problem = problem
        self.level = case.environment.water_level
        self.mode = self._mode()

    def _mode(self) -> str:
        problem, case = self.problem, self.case
        # As Result.warnings: a weightless line without a weight in air (a hawser) is not
        # warned about for an end in air; only a buoyant segment can float.
        self.counts = np.array([[_counts(line.segments[0].line_type),
                                 _counts(line.segments[-1].line_type)]
                                for line in case.lines], dtype=bool).reshape(-1, 2)
        sinking = all(seg.line_type.weight_in_water >= 0 for line in case.lines
                      for seg in line.segments)
        points_free = any(owner != "body" for owner, _, _ in problem.nodes)
        lifts = any(owner == "body" and dof in _LIFTING for owner, _, dof in problem.nodes)
        if (not problem.all_single or line_facts(case).sealed or not sinking or points_free
                or (lifts and case.form != "network")):
            return POST
        bodies = {b.name: k for k, b in enumerate(case.bodies)}
        points = {pt.name: pt for pt in case.points}
        fixed_z, ends = [], []        # fixed heights; (body index, attachment) of body ends
        for line, counts in zip(case.lines, self.counts):
            for end, count in zip((line.a, line.b), counts):
                if not count:
                    continue
                if end.body is not None:
                    if end.body not in bodies:
                        return POST
                    ends.append((bodies[end.body], np.asarray(end.position, float)))
                elif end.point is not None:
                    position = points[end.point].position
                    fixed_z.append(position[2] if len(position) > 2 else -np.inf)
                elif not end.on_seabed:
                    fixed_z.append(end.position[2])
        if any(z > self.level for z in fixed_z):
            return POST             # an end always above the water: the full solve words it
        self.body_index = np.array([k for k, _ in ends], dtype=int)
        self.attachment = np.array([a for _, a in ends], dtype=float).reshape(-1, 3)
        if lifts:
            return POSE
        # Surge, sway and yaw do not change a height: the case pose decides for every row.
        rest = np.array([[*b.position, *np.radians(b.orientation_deg)] for b in case.bodies],
                        dtype=float).reshape(1, -1, 6)
        return POST if self._above(rest)[0] else NONE

    def _above(self, poses: np.ndarray) -> np.ndarray:
        """Per row of ``poses`` (rows, bodies, 6: x y z roll pitch yaw [m, rad]): whether
        any body end is above the water."""
        if self.body_index.size == 0:
            return np.zeros(len(poses), bool)
        q = poses[:, self.body_index, :]                     # rows, ends, 6
        roll, pitch = q[..., 3], q[..., 4]
        px, py, pz = self.attachment.T
        # z of R p, R = Rz(yaw) Ry(pitch) Rx(roll): yaw does not change heights.
        z = (q[..., 2] - np.sin(pitch) * px + np.cos(pitch) * np.sin(roll) * py
             + np.cos(pitch) * np.cos(roll) * pz)
        return (z > self.level).any(axis=1)

    def rows(self, kernel, X, P, body) -> np.ndarray:
        """Whether each certified kernel row (points ``X``, parameters ``P``, the kernel's
        ``body`` output) might carry a warning."""
        n = len(P)
        if self.mode == NONE:
            return np.zeros(n, bool)
        if self.mode == POSE:
            poses = np.asarray(body, float)[:, 3:].reshape(n, -1, 6)
            return self._above(poses)
        out = np.zeros(n, bool)
        cols = [LINE_COLUMNS.index(c) for c in ("floating", "az", "bz")]
        sealed = line_facts(self.problem.case).sealed
        for k in range(n):
            if sealed:
                out[k] = True
                continue
            post = kernel.post(X[k], P[k]) if kernel.compiled else self.problem.post(X[k], P[k])
            table = np.asarray(post["lines"]).reshape(-1, len(LINE_COLUMNS))
            out[k] = bool((table[:, cols[0]] > 0).any()
                          or ((table[:, cols[1:]] > min(0.0, self.level)) & self.counts).any())
        return out


def _counts(line_type) -> bool:
    """Whether an end of a line of this type in air is warned about."""
    return not (line_type.weight_in_water == 0 and line_type.weight_in_air is None)


def screen(problem) -> WarningScreen:
    """The :class:`WarningScreen` of ``problem``, built once."""
    found = problem.derived.get("sweep_warning_screen")
    if found is None:
        found = problem.derived["sweep_warning_screen"] = WarningScreen(problem)
    return found
