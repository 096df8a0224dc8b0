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
only. DNV-OS-E301's factors need a dynamic tension, which the check does not compute yet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..dynamics.motions import Motions, motions
from ..solve import Result, solve
from ..studies.stiffness import posed_case
from .criteria import Criterion
from .design_tension import DesignTension, design_tension

__all__ = ["DesignOffsetSolve", "METHOD_DESIGN_OFFSET", "MEAN_ONLY", "MEAN_ONLY_DNV",
           "design_offset_solve", "design_offset_tension", "mean_tension", "sea_simulated"]

#: What the check says it did, in the text, the JSON and the HTML report.
METHOD_DESIGN_OFFSET = "API RP 2SK quasi-static method at the design offset"
MEAN_ONLY = ("the mean tension only: no sea state is simulated (waves with a period and "
             "bodies with hydrodynamics), so the standard's factors apply to the mean "
             "tension of the static equilibrium")
MEAN_ONLY_DNV = ("the mean tension only: DNV-OS-E301's dynamic method (a dynamic line "
                 "tension) is not wired into the check yet, so its factors apply to the mean "
                 "tension of the static equilibrium, without the sea state's motions")

#: A mean horizontal offset below this [m] has no direction: the design offset is then
#: taken along global x, as :func:`moorsolve.motions` takes it.
_NO_DIRECTION_M = 1e-9


def sea_simulated(case, standard: str) -> bool:
    """Whether the check tries the quasi-static method: API RP 2SK and a sea state with a
    period (whether a body moves in it is known only once the motions are computed)."""
    waves = case.environment.waves
    return standard == "api-rp-2sk" and waves is not None and bool(waves.sea_state)


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


def design_offset_tension(mean_leg, held_leg, crit: Criterion) -> tuple:
    """``(end, DesignTension)`` of one line by API RP 2SK's quasi-static method: the
    tension at the design offset against ``MBL / SF``, at the end where it is larger.

    A line that slackens at the design offset (leeward of the mean offset) is checked at no
    less than its mean tension: the body swings back through the mean and beyond it, so
    its largest tension in the storm is at least that. ``t_max_N`` is the larger of the
    two and ``t_dyn_N = t_max_N - t_mean_N >= 0``.
    """
    mean = dict(_ends(mean_leg))
    end, t_offset = max(_ends(held_leg), key=lambda e: e[1])
    t_mean = mean[end]
    t_max = max(t_offset, t_mean)
    design = crit.factor * t_max
    capacity = crit.capacity_factor * held_leg.mbl_N
    return end, DesignTension(standard=crit.standard, condition=crit.condition,
                              method="quasi_static", consequence_class=None, t_mean_N=t_mean,
                              t_dyn_N=t_max - t_mean, t_max_N=t_max, design_N=design,
                              capacity_N=capacity, utilisation=design / capacity,
                              criterion=crit)


def mean_tension(leg, crit: Criterion) -> tuple:
    """``(end, DesignTension)`` of one line on its mean tension alone (no dynamic part)."""
    end, t = max(_ends(leg), key=lambda e: e[1])
    return end, design_tension(standard=crit.standard, condition=crit.condition, t_mean=t,
                               t_dyn=0.0, mbl=leg.mbl_N,
                               consequence_class=crit.consequence_class or 1,
                               method="quasi_static")
