"""The peer: a moorsolve Case rebuilt as an NREL MoorPy System, solved and read back.

MoorPy (``pip install moorpy==1.3.0``, the ``bench`` extra) is imported, never copied. Run
anything that uses it with ``PYTHONBREAKPOINT=0``: some of MoorPy's error branches call
``breakpoint()``. :func:`moorpy_system` sets that variable for the current process if it is
unset, which is enough because ``breakpoint()`` reads it at call time.

What is compared, and how each piece maps
-----------------------------------------
* Environment: depth, water density and gravity go to ``System(depth, rho, g)``; the seabed
  is flat at ``z = -depth`` in both tools.
* Line type: MoorPy takes a mass per length ``m`` [kg/m] and a volumetric diameter
  ``d_vol`` [m] and recomputes the submerged weight on every line solve as
  ``w = (m - rho pi/4 d_vol^2) g`` (``Line.staticSolve``). :func:`line_type` picks ``d_vol``
  (the case's ``diameter`` if given, else the diameter of a steel bar of that submerged
  weight) and sets ``m = w/g + rho pi/4 d_vol^2`` so that MoorPy's ``w`` equals the case's
  ``weight_in_water`` to rounding (checked to 1e-12).
* Stiffness: ``EA`` as given. MoorPy has no inextensible line, so an inextensible leg gets
  ``EA = INEXTENSIBLE_EA_FACTOR`` x the largest tension the leg could carry (its MBL, or
  its whole submerged weight plus the largest constant force in the case): its stretch is
  then below about 1e-12 of its length, under any tolerance compared here (1e9 left
  a 3e-8 m offset difference on the Vida buoy; 1e12 leaves 6e-11 m).
* Seabed friction: MoorPy's ``cb`` is passed to ``addLine``, but MoorPy 1.3.0's
  ``Line.staticSolve`` overwrites ``cb`` with the anchor's height above the seabed (0 for a
  seabed anchor) on every solve, so a friction coefficient never reaches its catenary.
  A case with ``seabed.friction > 0`` is therefore rejected rather than compared wrongly.
* Anchors: fixed points (type 1) at the case's anchor position. Fairleads: points fixed on
  one free body (type 0) at the body-frame fairlead position; the body's ``DOFs`` are the
  case's ``body.free`` (surge -> 0, sway -> 1, yaw -> 5); heave, roll and pitch are held.
  Without a body the fairleads are fixed points.
* Loads: only a constant force is compared: ``body.loads.force = [Fx, Fy, Mz]`` (global
  frame, moment about the body origin) becomes the body's ``f6Ext = [Fx, Fy, 0, 0, 0, Mz]``.
  Wind, current and wave-drift models are not converted (MoorPy has no body drag model);
  :func:`with_constant_force` replaces them by a constant force. A case that still carries
  them raises ``ValueError``.
* Legs: one segment each, no clumps, no line drag, a flat seabed (the core problem; these
  are refused, not approximated); fairleads at or below the still-water level (MoorPy
  blends in the weight in air for a line whose end is above water).

Reading back: body offset ``r6[0], r6[1]`` and yaw ``r6[5]``; the fairlead tension is the
line's end-B tension ``TB`` and the anchor tension its end-A tension ``TA``.

MoorPy's convergence test is on the step size only (``solveEquilibrium(tol)``: every step
component below ``tol`` metres, ``tol / radius`` radians). :meth:`MoorPyScene.unbalanced`
measures what that leaves: the net force and moment on the body from its lines plus the
external load, with every line re-solved by MoorPy's own catenary at a 1e-10 m tolerance at
the position MoorPy returned.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import math
import os
import time
import warnings
from dataclasses import dataclass

import numpy as np

from moorsolve.model import DEGREES_OF_FREEDOM, BodyLoads, Case, Environment
from moorsolve.solve.lines.line_kinds import discretised

#: MoorPy release the benchmark was built and checked against.
MOORPY_VERSION = "1.3.0"
#: MoorPy's own default ``solveEquilibrium`` tolerance [m] (step size), in 1.3.0.
MOORPY_DEFAULT_TOL = 0.05
#: Stand-in stiffness for an inextensible line, as a multiple of the largest tension it
#: can carry (stretch below 1/factor of the length).
INEXTENSIBLE_EA_FACTOR = 1e12
#: Density of steel [kg/m^3], for a volumetric diameter when the case gives none.
STEEL_DENSITY = 7850.0
#: Catenary tolerance [m] used to re-evaluate forces at MoorPy's answer.
CHECK_LINE_TOL = 1e-10

_DOF_INDEX = {"surge": 0, "sway": 1, "yaw": 5}


def _import_moorpy():
    os.environ.setdefault("PYTHONBREAKPOINT", "0")
    import moorpy
    return moorpy


def with_constant_force(case: Case, force) -> Case:
    """``case`` with wind, current and waves removed and ``force`` as the only body load.

    Parameters
    ----------
    case : Case
        A scene with a body.
    force : sequence of 3 floats
        ``[Fx N, Fy N, Mz N m]``, global frame, moment about the body origin.
    """
    if case.body is None:
        raise ValueError(f"{case.name}: a constant load needs a body")
    env = dataclasses.replace(case.environment, wind=None, current=None, waves=None)
    body = dataclasses.replace(case.body,
                               loads=BodyLoads(force=tuple(float(f) for f in force)))
    return dataclasses.replace(case, environment=env, bodies=(body,))


def line_type(lt, environment: Environment, ea: float | None = None) -> dict:
    """MoorPy line-type dictionary whose submerged weight equals ``lt.weight_in_water``.

    Parameters
    ----------
    lt : moorsolve.model.LineType
    environment : Environment
        Its water density and gravity are the ones MoorPy will use.
    ea : float, optional
        Stiffness to use for an inextensible line type [N] (required then).

    Returns
    -------
    dict
        ``name, m [kg/m], d_vol [m], w [N/m], EA [N]`` (MoorPy's keys).

    Notes
    -----
    MoorPy 1.3.0, ``Line.staticSolve``: ``w = (m - rho pi/4 d_vol^2) g``. Solved for ``m``.
    """
    rho, g = environment.water_density, environment.gravity
    w = lt.weight_in_water
    if lt.diameter is not None:
        d_vol = lt.diameter
    elif w > 0:
        d_vol = math.sqrt(4.0 * w / (g * (STEEL_DENSITY - rho) * math.pi))
    else:
        raise ValueError(f"line type {lt.name!r}: a buoyant or neutral line needs a diameter "
                         "for MoorPy's mass per length")
    area_rho = rho * math.pi / 4.0 * d_vol**2
    m = w / g + area_rho
    if m <= 0:
        raise ValueError(f"line type {lt.name!r}: weight {w} N/m with diameter {d_vol} m gives "
                         f"a mass per length {m} kg/m <= 0 in MoorPy's model")
    w_moorpy = (m - math.pi / 4.0 * d_vol**2 * rho) * g
    if abs(w_moorpy - w) > 1e-12 * max(abs(w), m * g):
        raise AssertionError(f"line type {lt.name!r}: MoorPy weight {w_moorpy} != {w}")
    stiffness = lt.ea if lt.ea is not None else ea
    if stiffness is None:
        raise ValueError(f"line type {lt.name!r} is inextensible: pass ea")
    return {"name": lt.name, "m": m, "d_vol": d_vol, "w": w, "EA": float(stiffness),
            "material": "moorsolve"}


def _check_convertible(case: Case) -> None:
    env = case.environment
    if env.seabed.friction > 0:
        raise ValueError(f"{case.name}: seabed friction {env.seabed.friction} cannot be compared: "
                         "MoorPy 1.3.0's Line.staticSolve resets cb to 0 for a seabed anchor")
    if case.body is not None:
        loads = case.body.loads
        extra = [k for k in ("wind", "current", "wave_drift") if getattr(loads, k) is not None]
        if extra:
            raise ValueError(f"{case.name}: body loads {extra} are not converted; only a constant "
                             "body.loads.force is compared (see with_constant_force)")
    if env.seabed.sloped:
        raise ValueError(f"{case.name}: sloped seabed {env.seabed.gradient} is not converted; "
                         "the converter builds a flat seabed")
    for leg in case.legs:
        if len(leg.segments) != 1:
            raise ValueError(f"{case.name}: leg {leg.name} has {len(leg.segments)} segments; "
                             "the converter takes one (no clumps)")
        if discretised(case, leg):
            raise ValueError(f"{case.name}: leg {leg.name} feels the current (line drag); "
                             "the converter compares still-water lines only")
        if leg.fairlead[2] > 0:
            raise ValueError(f"{case.name}: leg {leg.name} fairlead z = {leg.fairlead[2]} m is "
                             "above water; MoorPy would blend in the line's weight in air")


def _inextensible_ea(case: Case, leg) -> float:
    lt = leg.line_type
    if lt.mbl:
        cap = lt.mbl
    else:
        force = case.body.loads.force if case.body is not None and case.body.loads.force else (0, 0)
        cap = abs(lt.weight_in_water) * leg.length + math.hypot(force[0], force[1])
    return INEXTENSIBLE_EA_FACTOR * max(cap, 1.0)


@dataclass
class PeerSolution:
    """One MoorPy equilibrium read back in moorsolve's terms."""

    converged: bool
    error: str
    x_m: float
    y_m: float
    yaw_deg: float
    fairlead_tension_N: np.ndarray
    anchor_tension_N: np.ndarray
    solve_time_s: float
    evaluations: int = 0     # force evaluations MoorPy made (one per iteration)


class MoorPyScene:
    """A MoorPy System built from a Case, with solve/reset/read-back helpers.

    Attributes
    ----------
    system : moorpy.System
    body : moorpy.body.Body or None
    tol : float
        Default ``solveEquilibrium`` tolerance [m] for :meth:`solve`.
    leg_names : list of str
        Case order, which is also the order of MoorPy's lines and of the tension arrays.
    free : tuple of str
        The body's free degrees of freedom (moorsolve names).
    """

    def __init__(self, system, body, tol: float, leg_names: list, free: tuple):
        self.system = system
        self.body = body
        self.tol = tol
        self.leg_names = leg_names
        self.free = free

    # -- state ---------------------------------------------------------------------------
    def set_force(self, force) -> None:
        """Replace the constant body load ``[Fx N, Fy N, Mz N m]`` (no rebuild)."""
        fx, fy, mz = (float(f) for f in force)
        self.body.f6Ext = np.array([fx, fy, 0.0, 0.0, 0.0, mz])

    def reset(self) -> None:
        """Body back to the case position, every line re-solved there (its rest state).

        A solve "from rest" then starts from the same information moorsolve's does: the
        body at its case position and each line's state at that position.
        """
        if self.body is not None:
            self.body.setPosition(np.zeros(6))
        for line in self.system.lineList:
            line.HF = line.VF = 0.0
            line.staticSolve(tol=1e-4)

    # -- solving -------------------------------------------------------------------------
    def solve(self, *, tol: float | None = None, from_rest: bool = True,
              max_iter: int = 500) -> PeerSolution:
        """``solveEquilibrium`` at ``tol`` [m]; from rest (see :meth:`reset`) or from the
        current state (warm). The time covers ``solveEquilibrium`` only."""
        tol = self.tol if tol is None else tol
        if from_rest:
            self.reset()
        error = ""
        t0 = time.perf_counter()
        try:
            with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
                warnings.simplefilter("ignore")
                ok = bool(self.system.solveEquilibrium(tol=tol, maxIter=max_iter, no_fail=True))
        except Exception as exc:  # noqa: BLE001  MoorPy raises bare Exception, LineError, ...
            ok, error = False, f"{type(exc).__name__}: {exc}"
        elapsed = time.perf_counter() - t0
        if not ok and not error:
            error = f"no convergence in {max_iter} iterations"
        sol = self.read(ok, error, elapsed)
        sol.evaluations = len(getattr(self.system, "Xs", ()))
        return sol

    def read(self, converged: bool = True, error: str = "", elapsed: float = 0.0) -> PeerSolution:
        lines = self.system.lineList
        r6 = self.body.r6 if self.body is not None else np.zeros(6)
        return PeerSolution(converged=converged, error=error, x_m=float(r6[0]),
                            y_m=float(r6[1]), yaw_deg=math.degrees(r6[5]),
                            fairlead_tension_N=np.array([ln.TB for ln in lines]),
                            anchor_tension_N=np.array([ln.TA for ln in lines]),
                            solve_time_s=elapsed)

    def unbalanced(self) -> tuple[float, float]:
        """Net force [N] and yaw moment [N m] left on the body at MoorPy's current position.

        Lines plus the external load, every line re-solved by MoorPy's catenary at
        ``CHECK_LINE_TOL``. The force is the largest of |Fx|, |Fy| over the free
        translations; the moment is |Mz| when yaw is free, else 0.
        """
        if self.body is None:
            return 0.0, 0.0
        for line in self.system.lineList:
            line.staticSolve(tol=CHECK_LINE_TOL)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            f6 = self.body.getForces(all_DOFs=True)
        force = max((abs(f6[_DOF_INDEX[d]]) for d in self.free if d != "yaw"), default=0.0)
        moment = abs(f6[5]) if "yaw" in self.free else 0.0
        return float(force), float(moment)


def moorpy_system(case: Case, *, tol: float = 1e-4) -> MoorPyScene:
    """Build ``case`` as a MoorPy System (see the module docstring for the mapping).

    Parameters
    ----------
    case : Case
        One segment per leg, no seabed friction, and (with a body) only a constant
        ``body.loads.force``; see :func:`with_constant_force`.
    tol : float
        Default ``solveEquilibrium`` step tolerance [m] for :meth:`MoorPyScene.solve`;
        MoorPy's own default is 0.05 m, the issue's benchmark uses 1e-4 m.

    Returns
    -------
    MoorPyScene
        ``.system`` is the MoorPy System, with the body at its case position.
    """
    mp = _import_moorpy()
    _check_convertible(case)
    env = case.environment
    system = mp.System(depth=env.depth, rho=env.water_density, g=env.gravity)
    body = None
    free = ()
    if case.body is not None:
        free = tuple(d for d in DEGREES_OF_FREEDOM if d in case.body.free)
        force = case.body.loads.force or (0.0, 0.0, 0.0)
        dofs = [_DOF_INDEX[d] for d in free]
        body = system.addBody(0 if dofs else 1, np.zeros(6), DOFs=dofs,
                              f6Ext=np.array([force[0], force[1], 0, 0, 0, force[2]], float))
    for leg in case.legs:
        lt = leg.line_type
        type_name = f"{leg.name}:{lt.name}" if lt.ea is None else lt.name
        if type_name not in system.lineTypes:
            ea = _inextensible_ea(case, leg) if lt.ea is None else None
            system.setLineType(name=type_name, lineType=line_type(lt, env, ea))
        anchor = system.addPoint(1, np.array(leg.anchor, float))
        if body is not None:
            fair = system.addPoint(1, np.array(leg.fairlead, float), body=body.number)
        else:
            fair = system.addPoint(1, np.array(leg.fairlead, float))
        system.addLine(leg.length, type_name, pointA=anchor.number, pointB=fair.number,
                       cb=env.seabed.friction)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system.initialize()
    return MoorPyScene(system, body, tol, [leg.name for leg in case.legs], free)


def compare(case: Case, result, peer: PeerSolution) -> dict:
    """Largest differences between a moorsolve Result and a MoorPy solution of ``case``.

    Returns offsets [m], yaw [deg] and tensions [N] (absolute) and the tension difference
    relative to the largest tension.
    """
    body = result.body or {"x_m": 0.0, "y_m": 0.0, "yaw_deg": 0.0}
    t_fair = np.array([leg.fairlead_tension_N for leg in result.legs])
    t_anch = np.array([leg.anchor_tension_N for leg in result.legs])
    d_fair = np.max(np.abs(t_fair - peer.fairlead_tension_N))
    d_anch = np.max(np.abs(t_anch - peer.anchor_tension_N))
    t_max = max(np.max(t_fair), np.max(t_anch))
    return {
        "offset_m": float(max(abs(body["x_m"] - peer.x_m), abs(body["y_m"] - peer.y_m))),
        "yaw_deg": float(abs(body["yaw_deg"] - peer.yaw_deg)),
        "fairlead_tension_N": float(d_fair),
        "anchor_tension_N": float(d_anch),
        "tension_relative": float(max(d_fair, d_anch) / t_max),
        "max_tension_N": float(t_max),
    }
