"""Exact parametric sensitivities of an equilibrium.

Everything here is derived from the CasADi graph of :mod:`moorsolve.solve.assembly.problem` by
automatic differentiation and the implicit function theorem on the square residual system
``g(x, p) = 0`` of the equilibrium:

    dx/dp = -(dg/dx)^-1 dg/dp

so a derivative costs one factorisation of the Jacobian the solver already used, not a
re-solve. A named parameter maps onto the parameter vector through the layout
(:mod:`moorsolve.solve.assembly.layout`), as the case defines it: an anchor resting on the seabed
follows the seabed when its x or y moves (its height is computed from the seabed in the
graph), so a derivative on a sloped seabed moves it along the slope. The finite-difference
checks live in ``tests/studies/test_sensitivity.py``.
"""

from __future__ import annotations

import dataclasses
import math
import re
import warnings

import casadi as ca
import numpy as np

from ..errors import MoorsolveWarning
from ..model import Case
from ..solve.lines.bathymetry import result_parameters
from ..solve.assembly.cache import get_problem
from ..solve.assembly.problem import LINE_COLUMNS
from ..solve.result.classes import Result
from ..solve.lines.stretch_params import baranov_n_column, stiffness_scale_column
from .stiffness import as_result

#: Line outputs available to :func:`sensitivity`.
LEG_OUTPUTS = ("fairlead_tension_N", "horizontal_tension_N", "fairlead_vertical_N",
               "anchor_tension_N", "anchor_horizontal_N", "anchor_vertical_N",
               "grounded_length_m")
#: The first body's offset from its case pose (the ``legs:`` form's body).
BODY_OUTPUTS = ("x_m", "y_m", "yaw_deg")
#: Every body's absolute pose, as ``bodies[NAME].FIELD``.
POSE_OUTPUTS = ("x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg")

_LEG_PARAMETERS = ("length", "ea", "weight", "anchor_x", "anchor_y", "anchor_z",
                   "fairlead_x", "fairlead_y", "fairlead_z")
_ENV_PARAMETERS = {
    "environment.wind.speed": ("wind", "wind_speed", 1.0),
    "environment.wind.toward_deg": ("wind", "wind_toward", math.pi / 180),
    "environment.current.speed": ("current", "current_speed", 1.0),
    "environment.current.toward_deg": ("current", "current_toward", math.pi / 180),
    "environment.waves.hs": ("waves", "wave_hs", 1.0),
    "environment.waves.toward_deg": ("waves", "wave_toward", math.pi / 180),
}


@dataclasses.dataclass(frozen=True)
class Sensitivity:
    """``matrix[i, j] = d outputs[i] / d parameters[j]`` at an equilibrium (SI units of the
    names: N, m, deg, N/m, m/s)."""

    outputs: tuple
    parameters: tuple
    matrix: np.ndarray

    def __getitem__(self, key) -> float:
        out, par = key
        return float(self.matrix[self.outputs.index(out), self.parameters.index(par)])

    def to_dict(self) -> dict:
        return {o: {p: float(self.matrix[i, j]) for j, p in enumerate(self.parameters)}
                for i, o in enumerate(self.outputs)}


_LEG_PATH = re.compile(r"(?:legs|lines)\[([^\[\]]+)\]\.(\w+)$")
_SEGMENT_PATH = re.compile(r"(?:legs|lines)\[([^\[\]]+)\]\.segments\[(\d+)\]\.length$")
_BODY_PATH = re.compile(r"bodies\[([^\[\]]+)\]\.(\w+)$")
_TYPE_PATH = re.compile(r"line_types\[([^\[\]]+)\]\.(\w+)$")
_FORCE_PATH = re.compile(r"body\.loads\.force\[([0-2])\]$")
_BODY_FORCE_PATH = re.compile(r"bodies\[([^\[\]]+)\]\.loads\.force\[([0-5])\]$")


def _line_index(case: Case, sel: str, name: str) -> int:
    if re.fullmatch(r"\d+", sel):
        i = int(sel)
        if i < len(case.lines):
            return i
    for i, line in enumerate(case.lines):
        if line.name == sel:
            return i
    raise ValueError(f"{name}: no leg {sel!r}; the legs are {[ln.name for ln in case.lines]}")


def _output_row(case: Case, name: str) -> int:
    """Row of ``name`` in the stacked outputs: the first body's offset (3), then per line
    ``LEG_OUTPUTS``, then per body ``POSE_OUTPUTS``."""
    n_lines = len(case.lines)
    if name in BODY_OUTPUTS:
        if not case.bodies:
            raise ValueError(f"{name}: the case has no body")
        return BODY_OUTPUTS.index(name)
    m = _LEG_PATH.match(name)
    if m and m.group(2) in LEG_OUTPUTS:
        return 3 + _line_index(case, m.group(1), name) * len(LEG_OUTPUTS) \
            + LEG_OUTPUTS.index(m.group(2))
    m = _BODY_PATH.match(name)
    if m and m.group(2) in POSE_OUTPUTS:
        names = [b.name for b in case.bodies]
        if m.group(1) not in names:
            raise ValueError(f"{name}: no body {m.group(1)!r}; the bodies are {names}")
        return 3 + n_lines * len(LEG_OUTPUTS) + names.index(m.group(1)) * 6 \
            + POSE_OUTPUTS.index(m.group(2))
    raise ValueError(f"output {name!r}: must be one of {', '.join(BODY_OUTPUTS)}, "
                     f"legs[NAME].FIELD with FIELD in {', '.join(LEG_OUTPUTS)}, or "
                     f"bodies[NAME].FIELD with FIELD in {', '.join(POSE_OUTPUTS)}")


def _parameter_column(case: Case, problem, name: str) -> np.ndarray:
    """``dp/d(name)``: how the problem's parameter vector moves with the named input."""
    layout = problem.layout
    col = np.zeros(problem.n_p)

    def line_slot(i, key):
        return layout.index(f"line[{case.lines[i].name}].{key}")

    env = case.environment
    if name in _ENV_PARAMETERS:
        model, key, factor = _ENV_PARAMETERS[name]
        if getattr(env, model) is None:
            raise ValueError(f"{name}: the case has no {model} (a scene without it builds "
                             f"no {model} model, so there is nothing to differentiate)")
        slots = ("wave_drift",) if model == "waves" else (model,)
        loaded = any(getattr(b.loads, m) is not None for b in case.bodies for m in slots)
        drags = model == "current" and any(k.discrete for k in problem.kinds)
        if not (loaded or drags):
            # The environment acts through nothing in this model.
            return col
        col[layout.index("env." + key)] = factor
        return col
    m = _FORCE_PATH.match(name)
    if m:
        body = case.body
        if body is None or body.loads.force is None:
            raise ValueError(f"{name}: the case has no body.loads.force")
        k = int(m.group(1))
        if case.form == "legs":
            col[layout.index("env." + ("force_x", "force_y", "moment_z")[k])] = 1.0
        else:
            col[layout.slice(f"body[{body.name}].force").start + (0, 1, 5)[k]] = 1.0
        return col
    m = _BODY_FORCE_PATH.match(name)
    if m:
        names = [b.name for b in case.bodies]
        if m.group(1) not in names or case.body_named(m.group(1)).loads.force is None:
            raise ValueError(f"{name}: no body {m.group(1)!r} with loads.force")
        if case.form == "legs":
            raise ValueError(f"{name}: a body + legs case names it body.loads.force[i]")
        col[layout.slice(f"body[{m.group(1)}].force").start + int(m.group(2))] = 1.0
        return col
    if name == "environment.seabed.friction":
        for i, kind in enumerate(problem.kinds):
            if kind.friction:
                col[line_slot(i, "friction")] = 1.0
        if not any(k.friction for k in problem.kinds):
            raise ValueError(f"{name}: the case has no seabed friction (0 builds none)")
        return col
    m = _TYPE_PATH.match(name)
    if m and m.group(2) in ("stiffness_scale", "n"):
        # The stretch law of every segment of the type (solve/lines/stretch_params.py).
        columns = {"stiffness_scale": stiffness_scale_column, "n": baranov_n_column}
        return columns[m.group(2)](case, layout, m.group(1))
    if m:
        field = m.group(2)
        if field not in ("ea", "weight_in_water"):
            raise ValueError(f"{name}: line-type parameters are ea, weight_in_water, n "
                             "(Baranov) and stiffness_scale")
        used = [(i, k, seg) for i, line in enumerate(case.lines)
                for k, seg in enumerate(line.segments) if seg.line_type.name == m.group(1)]
        if not used:
            raise ValueError(f"{name}: no leg uses line type {m.group(1)!r}")
        for i, k, seg in used:
            # Every segment of the type, in every line (a multi-segment or lumped-node
            # line's own segment parameters, else the line's).
            if field == "ea":
                if seg.line_type.ea is None:
                    raise ValueError(f"{name}: line type {m.group(1)!r} "
                                     f"{_no_ea(seg.line_type)}")
                col[_segment_slot(case, problem, i, k, "ea_inv")] += -1.0 / seg.line_type.ea ** 2
            else:
                col[_segment_slot(case, problem, i, k, "weight")] += 1.0
        return col
    m = _SEGMENT_PATH.match(name)
    if m:
        i = _line_index(case, m.group(1), name)
        k = _segment_of_item(case.lines[i], int(m.group(2)), name)
        col[_segment_slot(case, problem, i, k, "length")] += 1.0
        return col
    m = _LEG_PATH.match(name)
    if m and m.group(2) in _LEG_PARAMETERS:
        i = _line_index(case, m.group(1), name)
        line, field = case.lines[i], m.group(2)
        kind = problem.kinds[i]
        if line.multi_segment and field in ("length", "ea", "weight"):
            raise ValueError(f"{name}: leg {line.name} has {len(line.segments)} segments; give "
                             f"legs[{line.name}].segments[K].length, or "
                             "line_types[NAME].ea / .weight_in_water")
        if field in ("length", "ea", "weight") and not kind.single:
            # A one-segment lumped-node line: its segment's own parameters.
            key = "ea_inv" if field == "ea" else field
            if field == "ea" and line.line_type.ea is None:
                raise ValueError(f"{name}: leg {line.name}'s line {_no_ea(line.line_type)}")
            col[_segment_slot(case, problem, i, 0, key)] = (
                -1.0 / line.line_type.ea ** 2 if field == "ea" else 1.0)
            return col
        if field == "fairlead_z" and kind.single and getattr(kind.block, "from_fairlead",
                                                             False):
            raise ValueError(f"{name}: leg {line.name}'s fairlead is at the surface; raised it "
                             "leaves the water (another model), lowered under a floating line "
                             "the line must leave the surface to reach it (its force changes "
                             "like the square root of the depth): there is no derivative")
        if field == "ea":
            if line.line_type.ea is None:
                raise ValueError(f"{name}: leg {line.name}'s line {_no_ea(line.line_type)}")
            col[line_slot(i, "ea_inv")] = -1.0 / line.line_type.ea ** 2
        elif field == "anchor_z" and line.a.on_seabed:
            raise ValueError(f"{name}: leg {line.name}'s anchor lies on the seabed; raising "
                             f"it changes the model (no contact), so there is no derivative")
        elif field.startswith("anchor") and not line.a.fixed or \
                field.startswith("fairlead") and line.b.point is not None:
            raise ValueError(f"{name}: that end of leg {line.name} is a free point; move "
                             "the point, not the line end")
        else:
            key = {"fairlead_x": "fair_x", "fairlead_y": "fair_y",
                   "fairlead_z": "fair_z"}.get(field, field)
            col[line_slot(i, key)] = 1.0
        return col
    raise ValueError(
        f"parameter {name!r}: must be legs[NAME].FIELD with FIELD in "
        f"{', '.join(_LEG_PARAMETERS)}, line_types[NAME].ea, .weight_in_water, .n or "
        ".stiffness_scale, "
        f"{', '.join(_ENV_PARAMETERS)}, environment.seabed.friction, body.loads.force[0-2] "
        "or bodies[NAME].loads.force[0-5]")


def _no_ea(line_type) -> str:
    """Why a line type has no ``ea`` to differentiate by."""
    if line_type.stretch is not None:
        return "follows a stretch law (use line_types[NAME].stiffness_scale)"
    return "is inextensible (no ea)"


def _segment_slot(case: Case, problem, i: int, k: int, key: str) -> int:
    """Slot of segment ``k``'s ``key`` (length, weight, ea_inv) of line ``i``: its own
    segment parameter for a multi-segment or lumped-node line, else the line's."""
    line = case.lines[i]
    name = f"line[{line.name}].segment[{k}].{key}"
    if name in problem.layout.names:
        return problem.layout.index(name)
    return problem.layout.index(f"line[{line.name}].{key}")


def _segment_of_item(line, item: int, name: str) -> int:
    """The segment at ``segments[item]`` of the line's case-file list, where a clump between
    two segments is an item too (as in sweep paths)."""
    k = 0
    for j, clump in enumerate(line.joint_clumps + (None,)):
        if item == 0:
            return k
        item -= 1
        if clump is not None:
            if item == 0:
                raise ValueError(f"{name}: that item of leg {line.name}'s segments is a "
                                 "clump, which has no length")
            item -= 1
        k = j + 1
    raise ValueError(f"{name}: leg {line.name} has no such segment (its case-file list has "
                     f"{len(line.segments) + sum(c is not None for c in line.joint_clumps)} "
                     "items)")


def _reported_anchor(case: Case, problem, i: int, fa, table, cols):
    """The anchor's upward pull and tension as the result reports them: clipped at 0 for
    an anchor lying on the seabed in sloped, multi-segment and lumped-node lines (the seabed
    takes a downward pull; a sloped line's tension stays the whole pull)."""
    kind = problem.kinds[i]
    line = case.lines[i]
    VA, TA = fa[2], ca.norm_2(fa)
    if not line.a.on_seabed or (kind.single and not kind.sloped) or \
            (kind.multi and kind.flipped):
        return VA, TA
    clipped = ca.fmax(VA, 0)
    return clipped, (TA if kind.single else ca.hypot(ca.hypot(fa[0], fa[1]), clipped))


def _sensitivity_function(problem) -> ca.Function:
    with problem.lock:
        f = problem.__dict__.get("_sensitivity_blocks")
        if f is not None:
            return f
        xs = ca.SX.sym("x", problem.n_x)
        ps = ca.SX.sym("p", problem.n_p)
        g = problem.residual(xs, ps)
        table, _, _, poses = problem.report(xs, ps)[:4]
        body = problem.summary(xs, ps)[0]
        rows = [body[0], body[1], body[2] * (180.0 / math.pi)]
        cols = {k: i for i, k in enumerate(LINE_COLUMNS)}
        for i in range(problem.n_legs):
            fa = ca.vertcat(*(table[i, cols[k]] for k in ("FAx", "FAy", "FAz")))
            fb = ca.vertcat(*(table[i, cols[k]] for k in ("FBx", "FBy", "FBz")))
            VA, TA = _reported_anchor(problem.case, problem, i, fa, table, cols)
            rows += [ca.norm_2(fb), ca.hypot(fb[0], fb[1]), -fb[2], TA,
                     ca.hypot(fa[0], fa[1]), VA, table[i, cols["grounded"]]]
        deg = 180.0 / math.pi
        for b in range(len(problem.case.bodies)):
            q = poses[6 * b: 6 * b + 6]
            rows += [q[0], q[1], q[2], q[3] * deg, q[4] * deg, q[5] * deg]
        y = ca.vertcat(*rows)
        f = ca.Function("sensitivity_blocks", [xs, ps],
                        [ca.jacobian(g, xs), ca.jacobian(g, ps),
                         ca.jacobian(y, xs), ca.jacobian(y, ps)])
        problem.__dict__["_sensitivity_blocks"] = f
        return f


def sensitivity(result: Result, outputs, parameters) -> Sensitivity:
    """Exact derivatives of equilibrium outputs by case parameters.

    Parameters
    ----------
    result : Result
        A certified equilibrium from :func:`moorsolve.solve`.
    outputs : str or sequence of str
        ``x_m``, ``y_m``, ``yaw_deg`` (the first body's offset),
        ``bodies[NAME].x_m | y_m | z_m | roll_deg | pitch_deg | yaw_deg`` and
        ``legs[NAME].FIELD`` with FIELD one of ``LEG_OUTPUTS``.
    parameters : str or sequence of str
        ``legs[NAME].length | ea | weight`` (a one-segment line only),
        ``legs[NAME].segments[K].length`` (item K of the case file's segment list, clumps
        counted), ``legs[NAME].anchor_x | anchor_y | anchor_z | fairlead_x | fairlead_y |
        fairlead_z``, ``line_types[NAME].ea`` and ``.weight_in_water`` (every segment of
        the type in every line), ``line_types[NAME].n`` (Baranov's coefficient) and
        ``.stiffness_scale`` (per unit factor on the tension at every strain: a stiffer
        rope; any stretch law or Hooke, every segment of the type),
        ``environment.wind.speed``,
        ``environment.current.speed``, ``environment.waves.hs`` and their
        ``toward_deg``, ``environment.seabed.friction``, ``body.loads.force[0|1|2]``,
        ``bodies[NAME].loads.force[0-5]``.

    Returns
    -------
    Sensitivity
        ``sens[output, parameter]`` in the units of the names (e.g. N per m of length,
        m per (m/s) of current, deg per deg).

    Notes
    -----
    Implicit function theorem on the square residual system ``g(x, p) = 0``:
    ``dx/dp = -(dg/dx)^-1 dg/dp``, then ``dy/dp = y_x dx/dp + y_p`` for each output
    ``y(x, p)``; every block by CasADi automatic differentiation. A named parameter maps
    onto the parameter vector by the chain rule (``ea`` enters as ``1/ea``: ``-1/ea^2``;
    headings in radians: ``pi/180``); an anchor on the seabed moves along it. At a regime
    boundary (touchdown exactly at the anchor, a leg going slack) the derivative is the one
    of the regime the solution is in. The horizontal tension of a line hanging straight
    down has a kink (it grows as the size of the offset on every side): asked for, it comes
    with a :class:`~moorsolve.MoorsolveWarning`.
    """
    result = as_result(result)
    case = result.case
    outputs = (outputs,) if isinstance(outputs, str) else tuple(outputs)
    parameters = (parameters,) if isinstance(parameters, str) else tuple(parameters)
    problem = get_problem(case)
    rows = [_output_row(case, o) for o in outputs]
    C = np.column_stack([_parameter_column(case, problem, q) for q in parameters]) \
        if parameters else np.zeros((problem.n_p, 0))
    G_x, G_p, Y_x, Y_p = (np.asarray(v) for v in
                          _sensitivity_function(problem)(result.state,
                                                         result_parameters(problem, result)))
    dx = -np.linalg.solve(G_x, G_p @ C)
    dy = Y_x[rows] @ dx + Y_p[rows] @ C
    _warn_straight_lines(result, outputs)
    return Sensitivity(outputs=outputs, parameters=parameters, matrix=dy)


#: A line whose ends are within this fraction of its length of one vertical hangs straight.
_STRAIGHT = 1e-6


def _warn_straight_lines(result: Result, outputs) -> None:
    """Say so where an output is the horizontal tension of a line hanging straight down:
    it grows as ``|offset|`` whichever way its end moves (a kink, not a derivative), so the
    derivative given (0) is neither side's; the one-sided ones are ``+-`` the line's
    lateral stiffness times the rate of the offset."""
    for name in outputs:
        m = _LEG_PATH.match(name)
        if not m or m.group(2) not in ("horizontal_tension_N", "anchor_horizontal_N"):
            continue
        leg = result.leg(m.group(1))
        line = next(ln for ln in result.case.lines if ln.name == leg.name)
        span = math.hypot(leg.fairlead[0] - leg.anchor[0], leg.fairlead[1] - leg.anchor[1])
        if span <= _STRAIGHT * line.length:
            warnings.warn(f"{name}: the line hangs straight down, where its horizontal tension "
                          "has a kink (it grows as the offset's size on every side): the "
                          "derivative given is neither side's", MoorsolveWarning,
                          stacklevel=3)
