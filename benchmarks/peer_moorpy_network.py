"""The peer for network scenes: a moorsolve Case (bodies, points, lines) as a MoorPy System.

MoorPy (the ``bench`` extra, pinned 1.3.0) is imported, never copied. The mapping:

* Bodies: ``addBody(0 if any DOF is free else 1, r6, m, v, rCG, AWP, rM, f6Ext, DOFs)``:
  pose (angles in radians), mass, displaced volume, centre of gravity, waterplane area and
  metacentre of the linear hydrostatic model (MoorPy's ``Body.getForces`` is the same
  model: weight at the centre of gravity, buoyancy at the metacentre, heave restoring on
  the origin's height), the constant 6-force of ``loads.force``, and the free DOFs. Extra
  6x6 springs, exact hull members and flow load models have no MoorPy counterpart and are
  refused (:func:`without_extras` drops the springs for a comparison that does not load
  them).
* Points: fixed points (type 1) and free points (type 0, mass and volume); a fixed line
  end given as coordinates becomes its own fixed point; a body end a point attached to the
  body at its body-frame position.
* Lines: one segment each, from end A to end B, the line type mapped as in
  :mod:`peer_moorpy` (MoorPy's submerged weight equals ours to rounding); no clumps, no
  seabed friction (MoorPy 1.3.0 drops it), a flat seabed.

Reading back: each body's ``r6``, each free point's ``r``, and each line's end tensions
``TA`` and ``TB``.
"""

from __future__ import annotations

import contextlib
import io
import math
import os
import warnings

import numpy as np

from moorsolve.model import DOFS, Case

from peer_moorpy import _import_moorpy, line_type


def without_extras(case: Case) -> Case:
    """``case`` with every body's extra springs removed (MoorPy has none)."""
    import dataclasses
    bodies = tuple(dataclasses.replace(b, stiffness=None) for b in case.bodies)
    return dataclasses.replace(case, bodies=bodies, source=None)


def _check(case: Case) -> None:
    env = case.environment
    if env.seabed.friction > 0 or env.seabed.sloped:
        raise ValueError("MoorPy 1.3.0 has no seabed friction and no sloped seabed")
    for body in case.bodies:
        if body.stiffness is not None or body.hull:
            raise ValueError(f"body {body.name}: springs and exact hull members have no "
                             "MoorPy form")
        if any(getattr(body.loads, k) is not None for k in ("wind", "current", "wave_drift")):
            raise ValueError(f"body {body.name}: flow load models have no MoorPy form")
    for line in case.lines:
        if line.multi_segment:
            raise ValueError(f"line {line.name}: one segment per line")
        if line.line_type.ea is None:
            raise ValueError(f"line {line.name}: MoorPy lines are elastic")


class NetworkScene:
    """A MoorPy System built from a network case, with its solve and read-back."""

    def __init__(self, case: Case):
        mp = _import_moorpy()
        _check(case)
        env = case.environment
        self.case = case
        system = mp.System(depth=env.depth, rho=env.water_density, g=env.gravity)
        self.bodies = {}
        for body in case.bodies:
            dofs = [DOFS.index(d) for d in body.free]
            r6 = np.array(list(body.position) + [math.radians(a) for a in
                                                 body.orientation_deg], float)
            force = np.zeros(6)
            if body.loads.force is not None:
                f = body.loads.force
                force = np.array(f if len(f) == 6 else (f[0], f[1], 0, 0, 0, f[2]), float)
            hydro = body.hydrostatics
            self.bodies[body.name] = system.addBody(
                0 if dofs else 1, r6, m=body.mass or 0.0,
                v=hydro.displaced_volume if hydro else 0.0,
                rCG=np.array(body.centre_of_gravity, float),
                AWP=hydro.waterplane_area if hydro else 0.0,
                rM=np.array(hydro.metacentre if hydro else (0, 0, 0), float),
                f6Ext=force, DOFs=dofs)
        self.points = {}
        for point in case.points:
            if point.free:
                self.points[point.name] = system.addPoint(
                    0, np.array(point.position, float), m=point.mass, v=point.volume)
            else:
                self.points[point.name] = system.addPoint(1, np.array(point.position, float))
        self.lines = []
        for line in case.lines:
            lt = line.line_type
            if lt.name not in system.lineTypes:
                system.setLineType(name=lt.name, lineType=line_type(lt, env))
            ends = [self._end(system, end) for end in (line.a, line.b)]
            self.lines.append(system.addLine(line.length, lt.name, pointA=ends[0].number,
                                             pointB=ends[1].number))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            system.initialize()
        self.system = system

    def _end(self, system, end):
        if end.body is not None:
            return system.addPoint(1, np.array(end.position, float),
                                   body=self.bodies[end.body].number)
        name = end.point or end.label
        if name is not None and name in self.points:
            return self.points[name]
        return system.addPoint(1, np.array(end.position, float))

    def solve(self, tol: float = 1e-6, maxIter: int = 500) -> bool:
        """``solveEquilibrium`` with MoorPy's own output silenced; whether it converged."""
        os.environ.setdefault("PYTHONBREAKPOINT", "0")
        with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return bool(self.system.solveEquilibrium(tol=tol, maxIter=maxIter))

    def poses(self) -> dict:
        """Each body's ``r6`` (angles in radians)."""
        return {name: np.array(body.r6, float) for name, body in self.bodies.items()}

    def point_positions(self) -> dict:
        return {name: np.array(p.r, float) for name, p in self.points.items()
                if p.type == 0}

    def tensions(self) -> list:
        """``(TA, TB)`` of every line, in case order."""
        return [(float(line.TA), float(line.TB)) for line in self.lines]
