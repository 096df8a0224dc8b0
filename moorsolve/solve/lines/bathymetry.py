"""Lines on a bathymetry grid: one seabed plane per line, found by a fixed-point iteration.

A line's block (:mod:`moorsolve.physics.sloped`) lies on a plane seabed. On a grid
(:mod:`moorsolve.model.bathymetry`) each one-segment line gets its own plane, parameters
``line[L].seabed = (depth0, dz/dx, dz/dy)`` (height ``-depth0 + gx x + gy y``), added to the
layout only when the case declares a grid. The plane passes through the seabed point under
the line's lower end (its anchor); along the line it is the chord from there to the seabed
point under the touchdown (the chain's grounded run lies on that chord), across the line the
grid's slope at the chord's middle (it does not enter the line's plane). The touchdown is
not known before the solve, so :func:`solve_on_grid` starts, as MoorPy does, from the chord
to the point under the upper end, solves, moves each plane to the touchdown found and
re-solves warm-started until no touchdown moves more than :data:`TOUCHDOWN_REL` of its
line's length (a few solves; at most :data:`MAX_ROUNDS`). A line that does not touch down
takes the chord over :data:`REACH_REL` of its length from its anchor (the slope where it
leaves the seabed). A grid that samples one plane gives every line that plane: today's
sloped-seabed solution.

Limits: the grounded run is straight on the chord, so where the true surface bends under it
the chain is off the surface by ``seabed_deviation_m`` (reported per line, the largest of the
grounded run's departure from the surface and the suspended part's depth below it); above
:data:`WARN_FRACTION` of ``environment.seabed.tolerance`` it is a note, above the tolerance
the audit fails the solution (a line through the seabed is never certified).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...model.build_network import end_position

__all__ = ["PLANE", "initial_planes", "planes_from_legs", "solve_on_grid", "deviation",
           "point_plane", "point_plane_slices"]

#: The per-line plane's entries in the parameter layout (``line[L].seabed``).
PLANE = ("depth", "gradient_x", "gradient_y")
#: The iteration stops when no touchdown moves more than this fraction of its line's length.
TOUCHDOWN_REL = 1e-6
#: Most solves of the iteration.
MAX_ROUNDS = 12
#: Chord length for a line that does not touch down, as a fraction of its length.
REACH_REL = 1e-3
#: A departure above this fraction of the seabed tolerance is noted.
WARN_FRACTION = 0.1


def chord_plane(env, lower, direction, reach: float) -> tuple:
    """The plane ``(depth0, gx, gy)`` through the grid's seabed under ``lower`` (x, y) with
    the chord's slope over ``reach`` [m] along the unit horizontal ``direction``."""
    ux, uy = direction
    x0, y0 = float(lower[0]), float(lower[1])
    z0 = env.seabed_z(x0, y0)
    x1, y1 = x0 + ux * reach, y0 + uy * reach
    along = (env.seabed_z(x1, y1) - z0) / reach
    gx, gy = env.seabed.slope_at((x0 + x1) / 2, (y0 + y1) / 2)
    across = -gx * uy + gy * ux          # the grid's slope across the line, mid-chord
    gx, gy = along * ux - across * uy, along * uy + across * ux
    return (-(z0 - gx * x0 - gy * y0), gx, gy)


def point_plane(env, x: float, y: float) -> tuple:
    """The plane ``(depth0, gx, gy)`` touching the grid's seabed at ``(x, y)``: what a free
    point resting there lies on."""
    z0 = env.seabed_z(float(x), float(y))
    gx, gy = env.seabed.slope_at(float(x), float(y))
    return (-(z0 - gx * x - gy * y), gx, gy)


def _point_planes(case, positions) -> list:
    return [point_plane(case.environment, x, y) for x, y in positions]


def _direction(lower, upper) -> tuple:
    dx, dy = upper[0] - lower[0], upper[1] - lower[1]
    X = math.hypot(dx, dy)
    return ((dx / X, dy / X), X) if X > 1e-9 else ((1.0, 0.0), 0.0)


def initial_planes(case, kinds) -> np.ndarray:
    """Every line's plane from the chord to the seabed under its upper end (case pose),
    then every free point's, touching the grid under its case position; ``kinds`` are the
    case's line kinds."""
    env = case.environment
    bodies = {b.name: b for b in case.bodies}
    out = []
    for line, kind in zip(case.lines, kinds):
        a, b = end_position(line.a, bodies), end_position(line.b, bodies)
        lower, upper = (b, a) if kind.flipped else (a, b)
        u, X = _direction(lower, upper)
        out.append(chord_plane(env, lower, u, max(X, REACH_REL * line.length)))
    out += _point_planes(case, [pt.position[:2] for pt in case.free_points])
    return np.asarray(out, float).reshape(-1, len(PLANE))


def _touchdown_reach(line, leg) -> float:
    return max(leg.touchdown_from_anchor_m, REACH_REL * line.length)


def planes_from_legs(case, kinds, legs) -> tuple:
    """Every line's plane from the chord to its touchdown in ``legs`` (a solution), and the
    reaches [m] used."""
    env = case.environment
    planes, reaches = [], []
    for line, kind, leg in zip(case.lines, kinds, legs):
        lower, upper = ((leg.fairlead, leg.anchor) if kind.flipped
                        else (leg.anchor, leg.fairlead))
        u, _ = _direction(lower, upper)
        reach = _touchdown_reach(line, leg)
        planes.append(chord_plane(env, lower, u, reach))
        reaches.append(reach)
    return np.asarray(planes, float), np.asarray(reaches, float)


def deviation(env, leg, plane) -> float:
    """How far the grid's surface is from ``leg`` where it matters [m]: the largest
    distance between the grounded run and the surface under it, and the largest depth of
    the suspended part below the surface (0 when it is everywhere above)."""
    prof = leg.profile
    x, y, z = (np.asarray(prof[k], float) for k in ("x_m", "y_m", "z_m"))
    bed = env.seabed_z(x, y)
    on_plane = -plane[0] + plane[1] * x + plane[2] * y
    scale = 1e-9 * max(env.depth, 1.0)
    grounded = np.abs(z - on_plane) <= scale + 1e-9 * np.abs(on_plane)
    worst = float(np.max(np.abs(z - bed)[grounded])) if grounded.any() else 0.0
    below = float(np.max(bed - z)) if z.size else 0.0
    return max(worst, below, 0.0)


def solve_on_grid(case, kinds, solve_once, start=None):
    """Solve ``case`` on its grid: ``solve_once(planes, start)`` solves with the given
    per-line planes (then the free points' planes); the touchdowns and the points' resting
    places decide the next planes (module notes). Returns the last result with each leg's
    plane and deviation, and a note of the rounds."""
    planes = initial_planes(case, kinds)
    lengths = np.array([line.length for line in case.lines])
    settle_points = TOUCHDOWN_REL * max(case.environment.depth, 1.0)
    previous, previous_points = None, None
    iterations, seconds = 0, 0.0
    for rounds in range(1, MAX_ROUNDS + 1):
        used = planes           # the planes of this solve (what its legs lie on)
        result = solve_once(used, start)
        start = result.state
        iterations += result.certificate.iterations
        seconds += result.certificate.solve_time_s
        reach = np.array([_touchdown_reach(line, leg)
                          for line, leg in zip(case.lines, result.legs)])
        points = np.array([(pt["x_m"], pt["y_m"]) for pt in result.points],
                          float).reshape(-1, 2)
        if (previous is not None and np.all(np.abs(reach - previous) <= TOUCHDOWN_REL * lengths)
                and np.all(np.abs(points - previous_points) <= settle_points)):
            break
        new, reach = planes_from_legs(case, kinds, result.legs)
        new = np.concatenate([new.reshape(-1, len(PLANE)),
                              np.asarray(_point_planes(case, points), float).reshape(
                                  -1, len(PLANE))])
        if previous is None and np.all(np.abs(new - planes) <= 1e-12 * (1 + np.abs(planes))):
            break       # the first chord was already the touchdown's (a plane grid)
        previous, previous_points, planes = reach, points, new
    else:
        rounds = -MAX_ROUNDS
    # The certificate is the last solve's; its effort is all of them.
    cert = dataclasses.replace(result.certificate, iterations=iterations, solve_time_s=seconds)
    return finish(case, dataclasses.replace(result, certificate=cert), used, rounds)


def finish(case, result, planes, rounds):
    """``result`` with every leg's plane and seabed deviation, and the notes."""
    env = case.environment
    legs, notes, warnings = [], list(result.notes), list(result.warnings)
    warn = WARN_FRACTION * env.seabed.tolerance
    for leg, plane in zip(result.legs, planes):
        dev = deviation(env, leg, plane)
        z0 = -plane[0]
        legs.append(dataclasses.replace(leg, seabed_plane=(float(z0), float(plane[1]),
                                                                float(plane[2])),
                                        seabed_deviation_m=dev))
        message = (f"leg {leg.name}: the bathymetry departs {dev:.3g} m from the line's "
                   f"seabed plane under it (tolerance {env.seabed.tolerance:g} m): the "
                   "seabed bends under the grounded run")
        if dev > env.seabed.tolerance:
            # Past the user's tolerance the straight grounded run is a modelling slip an
            # engineer must see (a trough the chain bridges or sags into), not a remark.
            warnings.append(dict(code="seabed_departure", leg=leg.name, message=message))
        elif dev > warn:
            notes.append(message)
    if rounds < 0:
        notes.append(f"the seabed planes did not settle in {-rounds} solves: the touchdowns "
                     "still move; the last planes are reported")
    else:
        notes.append(f"bathymetry: each line's seabed plane settled in {rounds} solve(s)")
    return dataclasses.replace(result, legs=tuple(legs), notes=tuple(notes),
                               warnings=tuple(warnings))


def plane_slices(problem) -> list:
    """Where each line's plane sits in ``problem``'s parameters, in line order (a problem
    is shared by scenes of one structure, whatever their lines are called)."""
    return [problem.layout.slice(f"line[{line.name}].seabed") for line in problem.case.lines]


def point_plane_slices(problem) -> list:
    """Where each free point's plane sits in ``problem``'s parameters, in point order."""
    return [problem.layout.slice(f"point[{pt.name}].seabed")
            for pt in problem.case.free_points]


def result_parameters(problem, result, case=None) -> np.ndarray:
    """``problem``'s parameters for ``case`` (default ``result.case``) with each line's
    seabed plane where ``result``'s solve left it: what the stiffness and sensitivities
    of a solution on a grid are taken at (a plain parameter vector holds the first planes)."""
    case = result.case if case is None else case
    p = problem.parameters(case)
    if case.environment.seabed.bathymetry is None:
        return p
    for where, leg in zip(plane_slices(problem), result.legs):
        if leg.seabed_plane is not None:
            z0, gx, gy = leg.seabed_plane
            p[where] = (-z0, gx, gy)
    # A free point's plane touches the grid where it rests (the last solve's plane, to the
    # iteration's tolerance on the point's movement).
    for where, pt in zip(point_plane_slices(problem), result.points):
        p[where] = point_plane(case.environment, pt["x_m"], pt["y_m"])
    return p
