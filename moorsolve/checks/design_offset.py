"""API RP 2SK's quasi-static method: each body held at its design offset, the lines re-solved.

Where the scene has a sea state (``environment.waves`` with ``tp``) and bodies with
hydrodynamics, the check of one condition (intact, or one line removed) is:

1. the motions about that condition's equilibrium (:func:`moorsolve.motions`): the mean
   drift force added and re-solved (the *mean* equilibrium), the wave-frequency and
   slow-drift responses, and API RP 2SK's design offset of each body (3rd ed., 2005,
   section 6.4.2: the larger of ``mean + LF_sig + WF_max`` and ``mean + LF_max + WF_sig``,
   horizontal, along the mean offset);
2. every moving body held at its design offset: its mean pose moved horizontally along the
   mean offset direction until its horizontal offset from the case pose is the design
   offset (heave and the rotations at their mean values); all moving bodies are held there
   together;
3. the lines and free points re-solved with the bodies held (a static solve,
   :func:`moorsolve.studies.stiffness.posed_case`), and the tension of every line end at
   the design offset checked as ``SF T <= MBL`` (section 7.4: SF 2.00 intact, 1.43
   damaged, the quasi-static rows of ``criteria.csv``), anchor uplift and grounded length
   taken from that solve.

Without a sea state (or without a body that moves in it) the check covers the mean tension
only. With ``checks.method: dynamic`` (the default where the lines' dynamics run) the
tension comes from the lines' dynamics instead (:mod:`.dynamic`); the offset, anchor uplift
and grounded length are still checked at the design offset.

The design offset is along each condition's own mean offset: in a damaged condition the
body's mean position has moved away from the lost line's anchor (the side that lost its
restoring), and the design offset follows it there, not the intact direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..dynamics.motions import Motions, motions
from ..solve import Result, solve
from ..studies.stiffness import posed_case
from .design_tension import design_tension

__all__ = ["DesignOffsetSolve", "METHOD_DESIGN_OFFSET", "MEAN_ONLY", "design_offset_solve",
           "mean_tension", "sea_method"]

#: What the check says it did, in the text, the JSON and the HTML report.
METHOD_DESIGN_OFFSET = {
    "api-rp-2sk": "API RP 2SK quasi-static method at the design offset",
    "dnv-os-e301": ("DNV-OS-E301 with a quasi-static line tension: T_dyn = the tension at "
                    "the design offset less the mean, gamma_mean T_mean + gamma_dyn T_dyn "
                    "<= 0.95 MBS"),
}
MEAN_ONLY = ("the mean tension only: no sea state is simulated (waves with a period and "
             "bodies with hydrodynamics), so the standard's factors apply to the mean "
             "tension of the static equilibrium")
#: A mean horizontal offset below this [m] has no direction: the design offset is then
#: taken along global x, as :func:`moorsolve.motions` takes it.
_NO_DIRECTION_M = 1e-9


def sea_method(case, checks) -> str | None:
    """How the check of ``case`` takes the dynamic part of the line tension: None without
    a sea state (waves with a period: the mean tension only), else ``checks.method``, or
    the line model of ``analysis.lines`` where the case does not say (whether a body moves
    in the sea state is known once the motions are computed)."""
    waves = case.environment.waves
    if waves is None or not waves.sea_state:
        return None
    return checks.method or case.analysis.lines_in(case)


@dataclass(frozen=True)
class DesignOffsetSolve:
    """One condition's motions and its lines with the bodies held at the design offset.

    Attributes
    ----------
    motions : Motions
    mean : Result
        The mean equilibrium (with the mean drift force where the tables give one).
    held : Result
        The lines and free points with every moving body held at its design offset.
    design_offset_m : dict
        Body name to its design offset [m] (horizontal, from the case pose).
    poses : dict
        Body name to its held pose ``(x, y, z, roll, pitch, yaw)`` [m, rad].
    direction : dict
        Body name to the unit horizontal direction ``(ux, uy)`` of the offset.
    """

    motions: Motions
    mean: Result
    held: Result
    design_offset_m: dict
    poses: dict
    direction: dict


def _pose(entry: dict) -> np.ndarray:
    return np.array([entry["x_m"], entry["y_m"], entry["z_m"],
                     math.radians(entry["roll_deg"]), math.radians(entry["pitch_deg"]),
                     math.radians(entry["yaw_deg"])])


def design_offset_solve(result: Result, *, tol=None) -> DesignOffsetSolve | None:
    """The motions about ``result`` and the lines with each moving body held at its design
    offset; None where nothing moves in the sea state (a mean-only check).

    Raises
    ------
    ConvergenceError
        The mean equilibrium (with the mean drift) or the held solve has no certified
        solution.
    CaseError
        As :func:`moorsolve.motions` (a free body without hydrodynamics, ...).
    """
    m = motions(result, tol=tol)
    if m.static:
        return None
    mean = m.result
    poses = {b["name"]: _pose(b) for b in mean.bodies}
    offsets, directions = {}, {}
    for body in m.bodies:
        if body.design_offset_m is None:
            continue        # neither surge nor sway free: nothing to offset
        entry = mean.body_named(body.name)
        off = np.array([entry["offset"]["x_m"], entry["offset"]["y_m"]])
        r = float(np.hypot(*off))
        u = off / r if r > _NO_DIRECTION_M else np.array([1.0, 0.0])
        pose = poses[body.name].copy()
        pose[:2] += (body.design_offset_m - r) * u
        poses[body.name] = pose
        offsets[body.name] = body.design_offset_m
        directions[body.name] = (float(u[0]), float(u[1]))
    if not offsets:
        return None
    held = solve(posed_case(mean.case, poses), tol=tol, allow_overload=True, stability=False)
    return DesignOffsetSolve(motions=m, mean=mean, held=held, design_offset_m=offsets,
                             poses=poses, direction=directions)


def _ends(lr) -> tuple:
    return (("anchor", lr.anchor_tension_N), ("fairlead", lr.fairlead_tension_N))


def mean_tension(leg, crit) -> tuple:
    """``(end, DesignTension)`` of one line on its mean tension alone (no dynamic part)."""
    end, t = max(_ends(leg), key=lambda e: e[1])
    return end, design_tension(standard=crit.standard, condition=crit.condition, t_mean=t,
                               t_dyn=0.0, mbl=leg.mbl_N,
                               consequence_class=crit.consequence_class or 1,
                               method="quasi_static")
