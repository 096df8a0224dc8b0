"""What accuracy costs: solve time against error, measured on one case.

Two ladders, each against a tight reference (IPOPT, relative force residual 1e-12, the
full model the case declares):

* solver tolerance, from 1e-4 to 1e-12, for each solver (IPOPT and the Newton fast
  path): median solve time over repeats, iterations, and the error in body offset and
  in the worst line tension;
* model fidelity: the same case with inextensible lines (when it has elastic ones),
  without seabed friction (when it has friction), and, when lines feel a current, with a
  quarter, half and twice the line elements and with analytic legs free of line drag,
  solved at the reference tolerance: the error of the other model and its time.

Times are the solver's own (``Certificate.solve_time_s``: building the problem, the
closed-form start and the result tables excluded), median over ``repeats`` solves from
rest. Nothing here is asserted in tests; it is a measurement to read.
"""

from __future__ import annotations

import dataclasses
import math
import statistics

from ..errors import CaseError, ConvergenceError
from ..model import Case
from ..solve.equilibrium import solve

TOLERANCES = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
REFERENCE_TOL = 1e-12


@dataclasses.dataclass(frozen=True)
class Rung:
    """One setting of the ladder and what it measured.

    ``offset_error_m`` is the horizontal distance between this body position and the
    reference's; ``tension_error_N`` the largest difference of any fairlead or anchor
    tension, and ``tension_error_relative`` that over the reference's largest tension.
    """

    ladder: str                 # "tolerance" or "fidelity"
    setting: str
    solver: str
    tol: float
    time_s: float
    iterations: int
    offset_error_m: float
    yaw_error_deg: float
    tension_error_N: float
    tension_error_relative: float
    note: str = ""

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def accuracy_ladder(case: Case, *, tolerances=TOLERANCES, solvers=("ipopt", "newton"),
                    repeats: int = 7, allow_overload: bool = False) -> list[Rung]:
    """Measure both ladders on ``case``; see the module notes. ``allow_overload`` as for
    :func:`moorsolve.solve` (every solve of the ladder)."""
    if not case.lines:
        raise CaseError("lines", "the accuracy ladder measures line tensions and this scene "
                                 "has no lines (its contacts alone hold it)")
    over = dict(allow_overload=allow_overload)
    reference = solve(case, tol=REFERENCE_TOL, solver="ipopt", **over)
    rungs = []
    for solver in solvers:
        # build and compile outside the timing
        solve(case, tol=tolerances[0], solver=solver, **over)
        for tol in tolerances:
            rungs.append(_measure(case, reference, "tolerance", f"tol {tol:.0e}", solver, tol,
                                  repeats, over))
    for setting, variant in _fidelity_variants(case):
        rungs.append(_measure(variant, reference, "fidelity", setting, "ipopt", 1e-9, repeats,
                              over))
    return rungs


def _fidelity_variants(case: Case):
    yield "as declared", case
    if any(lt.elastic for lt in case.line_types.values()):
        types = {name: dataclasses.replace(lt, ea=None, stretch=None)
                 for name, lt in case.line_types.items()}
        legs = tuple(dataclasses.replace(
            leg, segments=tuple(dataclasses.replace(
                seg, line_type=dataclasses.replace(seg.line_type, ea=None, stretch=None))
                for seg in leg.segments)) for leg in case.legs)
        yield "inextensible lines", dataclasses.replace(case, line_types=types, lines=legs)
    if case.environment.seabed.friction > 0:
        env = dataclasses.replace(case.environment, seabed=dataclasses.replace(
            case.environment.seabed, friction=0.0))
        yield "frictionless seabed", dataclasses.replace(case, environment=env)
    if case.environment.current is not None and any(
            lt.drag is not None for lt in case.line_types.values()):
        # Lines in a current: other element counts, and the analytic legs
        # without the flow force on the lines.
        declared = case.solver.line_elements
        for n in sorted({max(2, declared // 4), max(2, declared // 2), 2 * declared}):
            if n != declared:
                yield f"{n} line elements", dataclasses.replace(
                    case, solver=dataclasses.replace(case.solver, line_elements=n))
        types = {name: dataclasses.replace(lt, drag=None)
                 for name, lt in case.line_types.items()}
        legs = tuple(dataclasses.replace(
            leg, segments=tuple(dataclasses.replace(
                seg, line_type=dataclasses.replace(seg.line_type, drag=None))
                for seg in leg.segments)) for leg in case.legs)
        yield "analytic legs, no line drag", dataclasses.replace(case, line_types=types,
                                                                 lines=legs)


def _measure(case, reference, ladder, setting, solver, tol, repeats, over) -> Rung:
    times = []
    result = None
    try:
        for _ in range(repeats):
            result = solve(case, tol=tol, solver=solver, **over)
            times.append(result.certificate.solve_time_s)
    except ConvergenceError as err:
        return Rung(ladder, setting, solver, tol, math.nan, err.iterations, math.nan, math.nan,
                    math.nan, math.nan, note=err.reason)
    t_ref = max(max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in reference.legs)
    t_err = max(max(abs(a.fairlead_tension_N - b.fairlead_tension_N),
                    abs(a.anchor_tension_N - b.anchor_tension_N))
                for a, b in zip(result.legs, reference.legs))
    if reference.body is not None:
        offset = math.hypot(result.body["x_m"] - reference.body["x_m"],
                            result.body["y_m"] - reference.body["y_m"])
        yaw = abs(result.body["yaw_deg"] - reference.body["yaw_deg"])
    else:
        offset = yaw = 0.0
    note = "" if result.solver == solver else f"solved by {result.solver}"
    return Rung(ladder, setting, solver, tol, statistics.median(times),
                result.certificate.iterations, offset, yaw, t_err, t_err / t_ref, note=note)


def format_ladder(rungs: list[Rung], case_name: str) -> str:
    """The ladders as a fixed-width table."""
    lines = [f"What accuracy costs: {case_name}",
             f"(errors against IPOPT at relative residual {REFERENCE_TOL:.0e}; "
             "time = median solver time from rest)",
             f"{'ladder':<10} {'setting':<22} {'solver':<7} {'time ms':>9} {'iter':>5} "
             f"{'offset err m':>13} {'yaw err deg':>12} {'tension err N':>14} {'rel':>9}"]
    for r in rungs:
        lines.append(
            f"{r.ladder:<10} {r.setting:<22} {r.solver:<7} {r.time_s * 1e3:9.3f} "
            f"{r.iterations:5d} {r.offset_error_m:13.3e} {r.yaw_error_deg:12.3e} "
            f"{r.tension_error_N:14.3e} {r.tension_error_relative:9.1e}"
            + (f"  {r.note}" if r.note else ""))
    return "\n".join(lines)
