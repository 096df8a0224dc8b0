"""Why a solve failed, and the checks that make a converged point a refusal.

:func:`diagnose` turns a point that did not certify into the reasons an engineer can act
on (a line that cannot reach, one that would break, a load the lines cannot balance, a
solver that stopped, a segment lying along a boundary, a line too light to resolve);
:func:`over_mbl` lists the lines above their breaking load; :func:`pulled_straight` the
inextensible lines whose sag double precision no longer holds; :func:`unbalanced_force` the
residual reached.
"""

from __future__ import annotations

import math

import numpy as np

from ...model import Case
from ...audit import audit_findings
from ...model.restraint import drifting_bodies
from ..kernels.newton import CONVERGED, STATUS_TEXT
from ..assembly.prepared import line_facts
from ..assembly.problem import LINE_COLUMNS
from .classes import Result
from ..kernels.start import end_positions
from ..stability.weathervane import WALKED

__all__ = ["diagnose", "over_mbl", "over_rated", "pulled_straight", "unbalanced_force",
           "SUCCESS_STATUSES"]

#: The status of a scene with nothing free whose lines' remembered state certifies as it
#: stands (:func:`~.equilibrium.rest_point`): there is nothing for a solver to do.
START_CERTIFIED = ("nothing free: the lines' remembered state certifies as it stands; no "
                   "solver called")
SUCCESS_STATUSES = ("Solve_Succeeded", "Solved_To_Acceptable_Level", "Feasible_Point_Found",
                    STATUS_TEXT[CONVERGED], START_CERTIFIED, WALKED)


def unbalanced_force(problem, x, p) -> float:
    """The largest unbalanced force [N] on a free translation of a body or a free point."""
    unbalanced = np.asarray(problem.report(x, p)[1], dtype=float).ravel()
    values, k = [], 0
    for body_index, body in enumerate(problem.case.bodies):
        values += [abs(v) for v in unbalanced[6 * body_index: 6 * body_index + 3]]
        k = 6 * (body_index + 1)
    values += [abs(v) for v in unbalanced[k:]]
    finite = [v for v in values if math.isfinite(v)]
    return max(finite, default=math.inf)


_FA = LINE_COLUMNS.index("FAx")
_FB = LINE_COLUMNS.index("FBx")
assert _FB == _FA + 3


def over_mbl(result: Result, problem=None, post=None) -> list:
    """``"leg NAME would break ..."`` for every line above its minimum breaking load; a line
    whose unstretched length is shorter than the distance between its ends at the case-file
    pose (neither end a free point) says it cannot reach, with the shortfall in metres.

    ``problem`` and ``post`` (the arrays the result was made from) let one-segment lines
    be judged from their end forces without making the legs.
    """
    if problem is not None and post is not None and problem.all_single:
        facts = line_facts(result.case)
        if not facts.any_mbl:
            return []
        mbl = facts.mbl
        # The larger end tension, as max(|FA|, |FB|) (the root commutes with the max),
        # summing each end's squares in the same order; a row of end forces per column.
        sq = np.square(post["lines"].T[_FA: _FA + 6])
        tension = np.sqrt(np.maximum(sq[0] + sq[1] + sq[2], sq[3] + sq[4] + sq[5]))
        over_mask = tension > mbl
        if not over_mask.any():
            return []
        lines = result.case.lines
        over = [(lines[i].name, tension[i], mbl[i]) for i in np.flatnonzero(over_mask)]
    else:
        over = [(leg.name, max(leg.fairlead_tension_N, leg.anchor_tension_N), leg.mbl_N)
                for leg in result.legs if leg.t_over_mbl is not None and leg.t_over_mbl > 1]
    out = []
    rest = _rest_chords(result.case) if (over and result.case is not None) else {}
    for name, tension_N, mbl_N in over:
        tension = f"{tension_N / 1e3:.1f} kN > MBL {mbl_N / 1e3:.1f} kN"
        length, chord = rest.get(name, (math.inf, 0.0))
        if chord > length:
            out.append(f"leg {name} cannot reach its fairlead: it is "
                       f"{chord - length:.2f} m short (unstretched length {length:.2f} m, "
                       f"anchor to fairlead {chord:.2f} m at rest); stretched to reach, "
                       f"it would break: tension {tension}")
        else:
            out.append(f"leg {name} would break: tension {tension}")
    return out


def over_rated(result: Result) -> list:
    """``"fender NAME is compressed ..."`` for every fender past its rated deflection, the
    fender's overload as a line's is its MBL; where it is fully compressed, that the hull
    bears on the wall (or pile) behind it."""
    out = []
    for f in result.fenders:
        if not f.get("overloaded"):
            continue
        text = (f"fender {f['name']} is compressed {f['compression_m']:.3f} m, past its rated "
                f"deflection {f['rated_deflection_m']:.3f} m (reaction "
                f"{f['reaction_N'] / 1e3:.1f} kN)")
        if f["hull_bears"]:
            text += (f", and fully compressed: the hull of {f['body']} bears on "
                     f"{f['bears_on']} behind it with {f['hull_reaction_N'] / 1e3:.1f} kN")
        out.append(text)
    return out


#: Below this sag (length less chord, relative to the length) an inextensible line's shape
#: is straight to within a few hundred units in the last place of its coordinates.
STRAIGHT_SAG = 1e-13
#: A chord steeper than this (horizontal span over length) hangs straight by itself.
_VERTICAL = 1e-3
_H, _X = LINE_COLUMNS.index("H"), LINE_COLUMNS.index("X")


def pulled_straight(problem, case, post) -> list:
    """``"leg NAME is pulled straight ..."`` for every one-segment inextensible line, not
    hanging vertically, whose sag at the reported horizontal tension (its length less its
    chord, ``w^2 X^4 / (24 H^2 L)`` for span X: Irvine's catenary to leading order) is
    below :data:`STRAIGHT_SAG` of its length.

    Such a line would need an unbounded tension to be straight: its tension is set by
    digits double precision does not hold, so a point the certificate accepts there (by
    the luck of the round-off) is not an answer (``tests/data/hard_cases/cannot_reach``).
    """
    # Which lines can be is the problem's structure (the kinds say elastic and neutral).
    candidates = problem.derived.get("inextensible_lines")
    if candidates is None:
        candidates = problem.derived["inextensible_lines"] = [
            i for i, kind in enumerate(problem.kinds)
            if kind.single and not kind.block.elastic and not kind.block.neutral]
    if not candidates:
        return []
    table = np.atleast_2d(post["lines"])
    out = []
    for i in candidates:
        line = case.lines[i]
        H, X = abs(float(table[i, _H])), abs(float(table[i, _X]))
        L, w = line.length, line.line_type.weight_in_water
        if H <= 0 or X <= _VERTICAL * L:
            continue
        excess = (w * X * X / H) ** 2 / (24.0 * L)          # length less chord
        if excess < STRAIGHT_SAG * L:
            out.append(f"leg {line.name} is pulled straight: at {H / 1e3:.4g} kN its "
                       f"{L:.6g} m would exceed its chord by {excess:.2g} m, below what "
                       "double precision resolves; an inextensible line would need an "
                       "unbounded tension; give the line type an ea")
    return out


def _rest_chords(case: Case) -> dict:
    """``name -> (unstretched length, end-to-end distance at the case-file pose)`` of every
    line whose ends are both fixed in the scene or on a body."""
    free = {p.name for p in case.points if p.free}
    out = {}
    for line in case.lines:
        if line.a.point in free or line.b.point in free:
            continue
        a, b = end_positions(case, line)
        out[line.name] = (line.length, math.dist(a, b))
    return out


def diagnose(problem, case, result) -> str:
    """The physical reason an equilibrium was not found, at the best point reached."""
    reasons = []
    rest = None
    ran_away = []           # (name, chord at the best point, length) of lines that span at rest
    for line, lr in zip(case.lines, result.legs):
        lt = line.line_type
        chord = math.dist(lr.anchor, lr.fairlead)
        fixed = line.a.fixed and (line.b.fixed or line.b.body is not None)
        if fixed and not any(s.line_type.elastic for s in line.segments) \
                and chord > line.length * (1 + 1e-9):
            rest = _rest_chords(case) if rest is None else rest
            if rest.get(line.name, (line.length, math.inf))[1] <= line.length:
                ran_away.append((line.name, chord, line.length))
                continue
            reasons.append(f"leg {line.name} cannot reach: anchor-fairlead distance "
                           f"{chord:.2f} m exceeds its inextensible length {line.length:.2f} m "
                           f"by {chord - line.length:.2f} m")
        elif fixed and not lt.elastic and chord > line.length * (1 - 1e-4):
            reasons.append(f"leg {line.name} is pulled straight (chord {chord:.3f} m of "
                           f"{line.length:.3f} m): an inextensible line would need an "
                           f"unbounded tension; give the line type an ea")
    if ran_away:
        names = [name for name, _, _ in ran_away]
        listed = (f"legs {', '.join(names[:-1])} and {names[-1]}" if len(names) > 1
                  else f"leg {names[0]}")
        chords = [chord for _, chord, _ in ran_away]
        lengths = sorted({f"{length:.2f} m" for _, _, length in ran_away})
        reasons.append(
            f"{listed} cannot reach at the best point reached ({min(chords):.2f} to "
            f"{max(chords):.2f} m between their ends, beyond their inextensible lengths, "
            f"{', '.join(lengths)}), though each spans its ends at the case's pose: the "
            "solver ran away, most likely pulled toward a straight inextensible line, whose "
            "tension double precision cannot resolve; give the line types an ea")
    reasons += over_mbl(result) + over_rated(result)
    drifts = drifting_bodies(case)
    # A body no line path holds has no equilibrium under a horizontal load: name it
    # rather than blame the lines that hold the others.
    reasons += [f"{d.describe()}: {d.restores}, so no equilibrium exists under a "
                "horizontal load on it" for d in drifts]
    if result.bodies and problem.load_names and not drifts:
        total = np.sum([v[:2] for v in result.loads.values()], axis=0)
        if np.hypot(*total) > 0:
            heading = round(math.degrees(math.atan2(total[1], total[0]))) % 360
            reasons.append(f"the legs could not balance the body load of "
                           f"{np.hypot(*total) / 1e3:.1f} kN toward {heading:d} deg "
                           f"(the lines may be too weak, too short or all on one side)")
    if not reasons:
        found = audit_findings(result, case, boundaries_only=True)
        cert = result.certificate
        short = (f", but its point is not certified: relative residual {cert.relative:.2g} "
                 f"above the tolerance {cert.tolerance:.2g}"
                 if cert.status in SUCCESS_STATUSES and math.isfinite(cert.relative) else "")
        reasons.append(f"the solver stopped with status {cert.status}{short}"
                       + (f"; at the best point reached: {'; '.join(found)}" if found else "")
                       + _along_a_boundary(case, result) + _near_neutral(case, result))
    return "; ".join(reasons)


def _near_neutral(case, result) -> str:
    """Name a line whose whole weight in water is below a millionth of the largest tension:
    its catenary loses precision (``x ~ (H/w) asinh``, a difference of nearly equal terms)
    for a weight that changes no reported digit."""
    tensions = [max(lr.fairlead_tension_N, lr.anchor_tension_N) for lr in result.legs]
    top = max((t for t in tensions if math.isfinite(t)), default=0.0)
    for line in case.lines:
        weight = sum(abs(s.line_type.weight_in_water) * s.length for s in line.segments)
        if 0 < weight < 1e-5 * top:
            return (f" (line {line.name} weighs {weight:.3g} N in water, under 1e-5 of "
                    f"the {top:.4g} N it carries: a catenary that light cannot be resolved to "
                    "the certificate's digits; give its line type weight_in_water 0, a "
                    "neutrally buoyant line)")
    return ""


def _along_a_boundary(case, result) -> str:
    """Name a segment lying along the seabed or the surface over its whole length between
    two ends both on it: its height equation is degenerate there (``Z ~ V|V|`` at ``V = 0``),
    which limits how closely its state can be certified."""
    for line, lr in zip(case.lines, result.legs):
        for k, seg in enumerate(lr.segments):
            lying = max(seg.get("grounded_length_m", 0.0), seg.get("floating_length_m", 0.0))
            if lying >= seg["length_m"] * (1 - 1e-9):
                where = "surface" if seg.get("floating_length_m", 0.0) > 0 else "seabed"
                return (f" (leg {line.name}: segment {k + 1} lies along the {where} over its "
                        "whole length between two ends on it, where its height equation is "
                        "degenerate: join it with the segment beside it, or move an end off "
                        f"the {where})")
    return ""
