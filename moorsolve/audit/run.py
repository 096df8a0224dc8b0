"""An independent audit of every result, and the warnings an engineer must see.

The certificate says the solver's residuals vanish. The audit asks a different question:
do the quantities *reported* make a physically consistent equilibrium? It reads only the
result (each line's profile, end forces, joints; the body position and loads) and the case
data (weights, lengths, stiffness, the seabed), and recomputes everything with its own
numpy and CasADi formulas: none of the solver's blocks, residuals or profile functions.
A result that fails it is an error (:class:`~moorsolve.errors.ConvergenceError` naming
what failed), never a note: an answer that is certified and wrong is the worst defect a
solver can have.

Per line:

- the profile is finite and starts at the anchor and ends at the fairlead;
- it is continuous: no step between two profile points is longer than the stretched arc
  between them;
- it lies between the seabed and the surface (a point above the water only where an end
  is above it);
- its tension at the ends is the reported end tension;
- where the line leaves an end through the water, the profile's direction there is the end
  force's (to within the turning of the line over one profile step);
- a line that no current drags: the vertical forces at its ends carry the weight of the
  part the seabed or the surface does not support (found from the profile: the runs lying
  on a boundary), with every joint's clump and reaction; a frictionless line on a flat
  seabed has the same horizontal tension at both ends;
- a joint the seabed or the surface pushes is on it.

No body is inside a quay wall or pile: the hull behind each fender, where its height is
known, and a rigid fender's face (:func:`.bodies.wall_findings`).

Per free body, in every free degree of freedom of six: the reported end forces at their
reported positions, the reported forces of its fenders and pile guides at their contact
points, the reported loads, the weight, the hydrostatics (recomputed here: the linear model,
and hull members by quadrature rather than the solver's closed form) and the springs balance.
A scene of one-segment lines is first screened at half that margin, compiled with the
line checks (:mod:`.closed_form`); only a failed screen runs the plain balance.

Warnings (:func:`result_warnings`) are facts that do not make a result wrong but that no
engineer may miss: compression in a sealed line's wall (Sukhanov),
line floating on the surface, an end above the water (the line there is taken with its
weight in water unless the line type gives its weight in air).
"""

from __future__ import annotations

import numpy as np

from ..errors import ConvergenceError
from .bodies import body_findings, one_body_inputs, wall_findings
from .closed_form import closed_form_check, covers, table_end_rows
from .lines import is_lumped, line_findings

__all__ = ["audit", "audit_findings", "result_warnings", "AuditFailure"]

#: Relative tolerance of geometric checks (of the line's length or the water depth): far
#: above the round-off of a certified solution, far below any defect worth the name.
GEOMETRY_REL = 1e-6


class AuditFailure(ConvergenceError):
    """A certified solution whose reported quantities are not a consistent equilibrium."""


def audit(result, case, problem=None, post=None, full: bool = False) -> list[str]:
    """Check ``result`` (of ``case``) independently; raise :class:`AuditFailure` on a defect.

    Given the ``problem`` and its report arrays ``post`` at the result, a scene of
    one-segment lines on a flat seabed is audited in closed form from the reported end
    positions and forces (:mod:`.closed_form`), without drawing a profile; ``full``
    also runs the profile audit. Returns the names of the lines audited.
    """
    problems = (None if problem is None or post is None
                else closed_form_audit(result, case, problem, post))
    if problems is None or full:
        problems = (problems or []) + audit_findings(result, case)
    if case.contacts.fenders:
        problems = problems + wall_findings(result, case)
    if problems:
        c = result.certificate
        raise AuditFailure(
            "the solution certified but its reported quantities fail the independent audit: "
            + "; ".join(problems) + air_hint(case, result.legs), residual_N=c.force_N,
            residual_Nm=c.moment_Nm, status=c.status, iterations=c.iterations, result=result)
    return [line.name for line in case.lines]


def air_hint(case, legs) -> str:
    """What the user can change when lines with an end above the water are modelled with
    their weight in water there (no ``weight_in_air``, or a multi-segment or lumped-node
    line): a sentence to close an audit failure's message, or ``""``."""
    level = case.environment.water_level
    named = {leg.name for leg in legs}
    hints = []
    for leg_case in case.lines:
        if leg_case.name not in named:
            continue
        leg = next(leg for leg in legs if leg.name == leg_case.name)
        if not (leg.fairlead[2] > level or leg.anchor[2] > level):
            continue
        types = [seg.line_type for seg in leg_case.segments]
        if all(lt.weight_in_water == 0 and lt.weight_in_air is None for lt in types):
            continue
        if any(lt.weight_in_air is None for lt in types):
            hints.append(f"line {leg_case.name} has an end above the water and no "
                         "weight_in_air: give its line type(s) one")
        elif leg_case.multi_segment or is_lumped(case, leg_case):
            hints.append(f"line {leg_case.name} has an end above the water but, as a "
                         "multi-segment or lumped-node line, weighs its weight in water "
                         "there: give it as one segment (its own line type) or keep its "
                         "ends below the water")
    return (" (" + "; ".join(hints) + ")") if hints else ""


def audit_findings(result, case, boundaries_only: bool = False) -> list[str]:
    """What the audit finds wrong with ``result``, one sentence each (empty: nothing).

    With ``boundaries_only`` only where lines and joints sit against the seabed and the
    surface: read at the best point of a solve that did not certify (whose forces need not
    balance), it says what the model could not represent there (a joint pulled out of the
    water, a line through the seabed, loose line on a slope).
    """
    tol_rel = max(GEOMETRY_REL, 100.0 * result.certificate.tolerance)
    problems = line_findings(case, result.legs, tol_rel, boundaries_only)
    if boundaries_only:
        return problems
    legs = result.legs
    # Both ends of every line, interleaved: end A of line i in row 2 i, end B in 2 i + 1.
    positions = np.array([(leg.anchor, leg.fairlead) for leg in legs], float).reshape(-1, 3)
    forces = np.array([[f if f is not None else (0.0,) * 3
                        for f in (leg.anchor_force, leg.fairlead_force)] for leg in legs],
                      float).reshape(-1, 3)
    t_lines = max([1.0] + [max(leg.fairlead_tension_N, leg.anchor_tension_N)
                           for leg in legs])
    return problems + body_findings(result, case, positions, forces, t_lines)


def closed_form_audit(result, case, problem, post) -> list[str] | None:
    """The audit's findings from the report arrays, or None where the closed forms do not
    cover the scene (:func:`.closed_form.covers`)."""
    if not covers(problem, case):
        return None
    table = np.atleast_2d(np.asarray(post["lines"], float))
    tol_rel = max(GEOMETRY_REL, 100.0 * result.certificate.tolerance)
    problems, t_lines, balanced = closed_form_check(problem, case, table, tol_rel,
                                                    one_body_inputs(problem, result, case))
    if problems is None:
        return None
    # The one free body's balance with half the margin, compiled with the line checks;
    # else (a failed screen, or a scene it does not cover) the plain balance decides, and
    # words what it finds.
    if balanced or not (case.free_points or any(body.free for body in case.bodies)):
        return problems
    positions, forces = table_end_rows(table)
    return problems + body_findings(result, case, positions, forces, max(t_lines, 1.0))


# ---- warnings ---------------------------------------------------------------------------


def result_warnings(result, case) -> list[dict]:
    """What an engineer must not miss in ``result``: a list of ``{"code", "leg",
    "message"}`` (codes ``wall_compression``, ``floating``, ``end_in_air``; on a bathymetry
    grid :func:`.bathymetry.finish` adds ``seabed_departure``)."""
    out = []
    for leg_case, leg in zip(case.lines, result.legs):
        # Only a sealed line's profile has a wall tension (and a profile costs its drawing).
        sealed = any(seg.line_type.sealed for seg in leg_case.segments)
        prof = leg.profile if sealed else {}
        wall = prof.get("wall_tension_N")
        if wall is not None and np.any(np.asarray(wall) < 0):
            k = int(np.argmin(wall))
            out.append(dict(code="wall_compression", leg=leg.name, message=(
                f"leg {leg.name}: the wall tension of the sealed line is compressive, down to "
                f"{float(wall[k]) / 1e3:.4g} kN at z = {float(prof['z_m'][k]):.1f} m (the "
                "effective tension is positive there; the wall may buckle)")))
        if leg.floating_length_m > 0:
            out.append(dict(code="floating", leg=leg.name, message=(
                f"leg {leg.name}: {leg.floating_length_m:.2f} m of line floats on the surface "
                f"(from {leg.touchup_from_anchor_m:.2f} m from the anchor)")))
        level = case.environment.water_level
        for end, z in (("fairlead", leg.fairlead[2] - level), ("anchor", leg.anchor[2] - level)):
            lt = leg_case.segments[-1 if end == "fairlead" else 0].line_type
            if lt.weight_in_water == 0 and lt.weight_in_air is None:
                continue        # a hawser: weightless by definition, in air as in water
            if z > 0:
                how = (f"with its weight in air, {lt.weight_in_air:.4g} N/m"
                       if lt.weight_in_air is not None and not leg_case.multi_segment
                       and not is_lumped(case, leg_case) else
                       "with its weight in water (give the line type a weight_in_air)"
                       if lt.weight_in_air is None else
                       "with its weight in water (a multi-segment or lumped-node line)")
                out.append(dict(code="end_in_air", leg=leg.name, message=(
                    f"leg {leg.name}: the {end} is {z:.2f} m above the water; the line above "
                    f"the surface is taken {how}")))
    return out
