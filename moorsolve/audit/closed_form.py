"""The audit's per-line checks in closed form, for one-segment catenaries on a flat seabed.

The profile audit (:mod:`.lines`) samples every line's drawn profile. For the common
line (one segment, Hooke or inextensible, sinking, on a flat seabed or clear of it, in the
water) the same questions have closed answers, asked here of the reported end positions
and end forces alone, all lines at once:

- the end forces lie in the line's vertical plane and pull the ends towards each other;
- the fairlead's vertical force carries the weight of the hanging length (the whole line,
  or all but its grounded length, whose anchor end then takes no vertical force);
- the horizontal tension is the same at both ends, less the seabed friction on the
  grounded length at the anchor;
- integrating the elastic catenary from the lower end's reported force over the line's
  unstretched length reaches the other end's reported position (Irvine's closed forms,
  written out here independently of the solver's blocks);
- a grounded line's lower end is on the seabed, and no point of a hanging line is below it
  (the lowest point of a sinking catenary is its lower end or its vertex).

The tolerances are the profile audit's: lengths to ``tol_rel`` of the line's stretched
length (or the depth), forces to ``FORCE_REL + tol_rel`` of its largest tension. Lines of
any other kind, or a nearly vertical line (whose closed forms lose their digits), are left
to the profile audit: :func:`covers` says which scenes this module audits alone.

The checks of one line are one small CasADi function of its reported numbers (these
formulas, none of the solver's blocks), mapped over the lines and compiled into a cached
library (:mod:`moorsolve.compiled`; interpreted until it is ready) for 8, 16, 32, ... lines, the
lines padded up to that: numpy spends more in calling its functions on a dozen lines than
the checks compute. The compiled function reads the report table's rows whole and also
gives the verdict (every check passed, every number finite), so a clean report costs one
copy and one call; only a failed verdict reads the table of ratios, for the sentences.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import casadi as ca
import numpy as np

from ..concurrency import SYMBOLIC_LOCK, LockedLRU
from ..model.line_table import LINE_COLUMNS
from ..physics.stretch import numeric_law
from .bodies import BODY_DATA, BODY_POSE, symbolic_balance
from .lines import FORCE_REL

__all__ = ["covers", "closed_form_findings", "closed_form_check", "table_end_rows",
           "wait_compiled"]

_COL = {name: k for k, name in enumerate(LINE_COLUMNS)}
_A = [_COL[c] for c in ("ax", "ay", "az")]
_B = [_COL[c] for c in ("bx", "by", "bz")]
_FA = [_COL[c] for c in ("FAx", "FAy", "FAz")]
_FB = [_COL[c] for c in ("FBx", "FBy", "FBz")]
_GROUNDED = _COL["grounded"]
#: Both ends' positions, and the forces on them, as table columns (index arrays: a list is
#: converted at every call).
_ENDS, _END_FORCES = np.array(_A + _B), np.array(_FA + _FB)

#: Below this ratio of horizontal to vertical tension the closed forms lose digits (the
#: catenary's parameter H/w shrinks to nothing): such a line is left to the profile audit.
_STEEP = 1e-7

#: One line's inputs (a column): the lower end, the upper end, the forces on them, the
#: grounded length, then the line's data and the tolerances.
_INPUTS = ("lo_x", "lo_y", "lo_z", "up_x", "up_y", "up_z", "flo_x", "flo_y", "flo_z",
           "fup_x", "fup_y", "fup_z", "grounded", "L", "w", "c", "mu", "depth", "tol_rel")
#: Each check's defect over its tolerance (a line fails where one exceeds 1).
_RATIOS = ("side", "push", "weight", "grounded_pull", "friction", "grounded_length",
           "reach", "off_bed", "below")
#: Whether the closed forms hold (a span and a horizontal tension), the larger end tension,
#: the ratios, and what the sentences quote.
_OUTPUTS = ("closed", "t_ends", *_RATIOS, "side_N", "H_lo", "H_up", "unbalanced", "hangs",
            "V_lo", "H_expected", "x_reach", "z_reach", "X", "Z", "off_bed_m", "below_m")


def _closed_kind(kind) -> bool:
    """One segment, sinking, Hooke or inextensible, in the water, on a flat seabed. A line
    whose lower end is off the seabed (``lifted``) qualifies while it hangs clear of it
    (:func:`closed_form_findings` checks its grounded length)."""
    block = kind.block
    return (kind.single and not block.neutral and not block.sloped and not block.surface
            and not block.air and block.law is None)


def _lifted(kind) -> bool:
    return bool(kind.lifted or kind.block.lifted)


def covers(problem, case) -> bool:
    """Whether every line of ``case`` (built as ``problem``) can be audited here: one-segment
    sinking Hooke or inextensible lines in the water, on a flat seabed without a grid."""
    seabed = case.environment.seabed
    # The last answer, while the lines and the seabed are the same objects (a loop).
    last = problem.derived.get("closed_form_covers")
    if last is not None and last[0] is case.lines and last[1] is seabed:
        return last[2]
    key = "closed_form_audit"
    hit = problem.derived.get(key)
    if hit is None:
        hit = problem.derived[key] = all(_closed_kind(k) for k in problem.kinds)
    verdict = (hit and seabed.bathymetry is None and not seabed.sloped
               and bool(case.lines) and _data(case.lines).sinking)
    problem.derived["closed_form_covers"] = (case.lines, seabed, verdict)
    return verdict


@dataclass(frozen=True)
class _Data:
    """What the checks read of the case's lines, made once per lines tuple."""

    names: tuple
    columns: np.ndarray  # per line: L [m], w [N/m], 1/EA [1/N] (0: inextensible)
    sinking: bool        # every line weighs in water and has no stretch law


_DATA = LockedLRU(256)


def _data(lines) -> _Data:
    hit = _DATA.get(id(lines))
    if hit is not None and hit[0] is lines:
        return hit[1]
    types = [line.line_type for line in lines]
    data = _Data(
        names=tuple(line.name for line in lines),
        columns=np.array([[line.length, lt.weight_in_water, 1.0 / lt.ea if lt.ea else 0.0]
                          for line, lt in zip(lines, types)], float).reshape(-1, 3),
        sinking=all(lt.weight_in_water > 0 and numeric_law(lt) is None for lt in types))
    _DATA.put(id(lines), (lines, data))
    return data


def table_end_rows(table: np.ndarray) -> tuple:
    """Every line end's position and the force the line exerts on it, ``(2 n, 3)`` each,
    from the report's line table (:data:`~moorsolve.model.line_table.LINE_COLUMNS`): end
    A of line ``i`` in row ``2 i``, end B in row ``2 i + 1``."""
    return (np.take(table, _ENDS, axis=1).reshape(-1, 3),
            np.take(table, _END_FORCES, axis=1).reshape(-1, 3))


#: Per line, what the compiled checks read besides its row of the report table: its data
#: (the checks' inputs from ``L`` to ``tol_rel``), whether its block integrates from end B
#: (``flipped``), whether its lower end may be off the seabed (``lifted``), and 1 for a
#: line of the scene (0 for the padding up to the mapped size); whether its ends A and B
#: are on the body the verdict balances (:func:`.bodies.symbolic_balance`).
_STATIC = (*_INPUTS[13:], "flipped", "lifted", "line", "on_a", "on_b")


def _columns(problem) -> tuple:
    """Per line, the seabed friction factor of its block (1 or 0), whether it integrates
    from end B, whether its lower end is off the seabed (None where no line's is); the
    mapped checks."""
    hit = problem.derived.get("closed_form_columns")
    if hit is None:
        friction = np.array([1.0 if k.friction else 0.0 for k in problem.kinds])
        flipped = np.array([1.0 if k.flipped else 0.0 for k in problem.kinds])
        lifted = np.array([_lifted(k) for k in problem.kinds], bool)
        hit = problem.derived["closed_form_columns"] = (
            friction, flipped, lifted if lifted.any() else None, _mapped(len(friction)))
    return hit


def _static_columns(problem, case, tol_rel: float, body: str | None) -> np.ndarray:
    """The :data:`_STATIC` columns, one row per line of the mapped checks (the padding
    rows repeat the first line's data, marked no line); the last made is kept in the
    problem (one slot: a loop solves one scene's lines over and over). Never changed once
    made: the compiled checks keep the last one they were given."""
    env = case.environment
    key = (env.seabed.friction, env.depth, tol_rel, body)
    hit = problem.derived.get("closed_form_static")
    if hit is not None and hit[0] is case.lines and hit[1] == key:
        return hit[2]
    friction, flipped, lifted, mapped = _columns(problem)
    k = len(friction)
    static = np.column_stack([_data(case.lines).columns, env.seabed.friction * friction,
                              np.full(k, float(env.depth)), np.full(k, float(tol_rel)),
                              flipped, np.zeros(k) if lifted is None else lifted,
                              np.ones(k),
                              [float(body is not None and line.a.body == body)
                               for line in case.lines],
                              [float(body is not None and line.b.body == body)
                               for line in case.lines]])
    padding = np.repeat(static[:1], mapped.n - k, axis=0)
    padding[:, -3:] = 0.0
    static = np.concatenate([static, padding])
    static.flags.writeable = False
    problem.derived["closed_form_static"] = (case.lines, key, static)
    return static


# ---- the checks of one line, symbolic --------------------------------------------------


def _span(H, V0, s, w, c):
    """Horizontal and vertical reach [m] of an elastic catenary of weight ``w`` [N/m] and
    compliance ``c`` [1/N] over unstretched arc ``s`` from a point where its tension is
    ``(H, V0)`` (H > 0; Irvine 1981, eq. 2.8 with the stretch terms)."""
    a0, a1 = V0 / H, (V0 + w * s) / H
    r0, r1 = ca.sqrt(1.0 + a0 * a0), ca.sqrt(1.0 + a1 * a1)
    k = H / w
    x = k * (ca.asinh(a1) - ca.asinh(a0)) + H * c * s
    # sqrt(1 + a1^2) - sqrt(1 + a0^2) without the cancellation of a taut line's.
    z = k * ((a1 - a0) * (a1 + a0) / (r1 + r0)) + c * s * (V0 + 0.5 * w * s)
    return x, z


def _line_checks() -> ca.Function:
    v = ca.SX.sym("line", len(_INPUTS))
    i = dict(zip(_INPUTS, ca.vertsplit(v)))
    L, w, c, mu = i["L"], i["w"], i["c"], i["mu"]
    bed = -i["depth"]                                   # a flat seabed (covers() says so)
    grounded, tol_rel = i["grounded"], i["tol_rel"]
    dx, dy = i["up_x"] - i["lo_x"], i["up_y"] - i["lo_y"]
    X = ca.sqrt(dx * dx + dy * dy)
    Z = i["up_z"] - i["lo_z"]
    span = ca.fmax(X, 1e-300)
    ux, uy = dx / span, dy / span
    H_lo = i["flo_x"] * ux + i["flo_y"] * uy              # pulls the lower end along +u
    H_up = -(i["fup_x"] * ux + i["fup_y"] * uy)           # pulls the upper end along -u
    side = ca.fmax(ca.fabs(i["flo_x"] * uy - i["flo_y"] * ux),
                   ca.fabs(i["fup_x"] * uy - i["fup_y"] * ux))
    V_lo, V_up = i["flo_z"], -i["fup_z"]
    t_ends = ca.fmax(ca.sqrt(H_lo * H_lo + V_lo * V_lo), ca.sqrt(H_up * H_up + V_up * V_up))
    t_max = ca.fmax(t_ends, w * L)
    closed = ca.logic_and(X > 0, ca.fabs(H_up) > _STEEP * t_max)
    H = ca.if_else(closed, H_up, 1.0)                    # the formulas' H where they hold
    tol = tol_rel * ca.fmax(ca.fmax(L * (1.0 + c * t_max), i["depth"]), 1.0)
    f_tol = (FORCE_REL + tol_rel) * t_max
    on_bed = grounded > 0
    Lg = ca.if_else(on_bed, grounded, 0.0)
    hanging = L - Lg
    # Friction on the grounded length takes up to mu w Lg of the horizontal tension.
    H_anchor = ca.fmax(H_up - mu * w * Lg, 0.0)
    V_start = ca.if_else(on_bed, 0.0, V_lo)
    x_h, z_h = _span(H, V_start, hanging, w, c)
    # The grounded run: straight, stretched by its tension (which friction may end).
    grip = mu * w
    run = ca.if_else(grip > 0, ca.fmin(Lg, H_up / ca.fmax(grip, 1e-300)), Lg)
    x_reach = Lg + c * (H_up * run - 0.5 * grip * run * run) + x_h
    # Lowest point: the lower end, or the vertex of a line leaving it downwards.
    s_v = ca.fmin(ca.fmax(-V_start / w, 0.0), hanging)
    lowest = i["lo_z"] + ca.fmin(_span(H, V_start, s_v, w, c)[1], 0.0)
    below = bed - ca.fmin(lowest, i["up_z"])
    unbalanced = V_up - V_start - w * hanging
    off_bed = i["lo_z"] - bed
    ratios = {
        "side": side / f_tol,
        "push": ca.fmax(-H_lo, -H_up) / f_tol,
        "weight": ca.fabs(unbalanced) / f_tol,
        "grounded_pull": ca.if_else(on_bed, ca.fabs(V_lo), 0.0) / f_tol,
        "friction": ca.fabs(H_lo - H_anchor) / f_tol,
        "grounded_length": ca.fmax(-grounded, grounded - L) / tol,
        "reach": ca.sqrt((x_reach - X) ** 2 + (z_h - Z) ** 2) / tol,
        "off_bed": ca.if_else(on_bed, ca.fabs(off_bed), 0.0) / tol,
        "below": below / tol,
    }
    out = dict(ratios, closed=closed, t_ends=t_ends, side_N=side, H_lo=H_lo, H_up=H_up,
               unbalanced=unbalanced, hangs=w * hanging, V_lo=V_lo, H_expected=H_anchor,
               x_reach=x_reach, z_reach=z_h, X=X, Z=Z, off_bed_m=off_bed, below_m=below)
    return ca.Function("moorsolve_line_audit", [v], [ca.vertcat(*[out[k] for k in _OUTPUTS])])


_SAY = {
    "side": lambda o: f"the end forces leave the line's vertical plane by {o['side_N']:.4g} N",
    "push": lambda o: (f"an end force pushes the end away from the line (horizontal tensions "
                       f"{o['H_lo']:.6g} N and {o['H_up']:.6g} N)"),
    "weight": lambda o: (f"the end forces do not carry the line's weight: "
                         f"{o['unbalanced']:.4g} N of vertical force unbalanced (the line "
                         f"hangs {o['hangs']:.6g} N)"),
    "grounded_pull": lambda o: (f"a grounded line pulls its lower end with {o['V_lo']:.4g} N "
                                "vertically"),
    "friction": lambda o: (f"the horizontal tension changes along the line by more than the "
                           f"seabed friction holds ({o['H_up']:.6g} N at the upper end, "
                           f"{o['H_lo']:.6g} N at the lower, {o['H_expected']:.6g} N "
                           "expected)"),
    "grounded_length": lambda o: (f"the grounded length {o['grounded']:.6g} m is outside the "
                                  f"line's {o['L']:.6g} m"),
    "reach": lambda o: (f"the catenary from the lower end's force reaches "
                        f"({o['x_reach']:.6g}, {o['z_reach']:.6g}) m along and up, not the "
                        f"other end at ({o['X']:.6g}, {o['Z']:.6g}) m"),
    "off_bed": lambda o: (f"the line is grounded but its lower end is {o['off_bed_m']:.3g} m "
                          "off the seabed"),
    "below": lambda o: f"the line passes {o['below_m']:.3g} m below the seabed",
}


# ---- evaluating it over the lines --------------------------------------------------------


class _Mapped:
    """The checks mapped over ``n`` lines: compiled when the library is ready (built in the
    background, :class:`moorsolve.compiled.Library`), else CasADi's interpreter. One call at a time
    (the compiled function's buffers are shared).

    Its inputs are the report table's rows and the :data:`_STATIC` columns; its outputs
    every line's outputs and the verdict: 1 where every line's row is finite, its closed
    forms hold, it is not a lifted line touching down and every ratio is at most 1 (each a
    comparison, so a NaN fails it), and the largest end tension. A clean report costs
    one copy of the table into the inputs and reads two numbers.
    """

    def __init__(self, n: int):
        from ..compiled import Library

        self.n = n
        with SYMBOLIC_LOCK:
            self.function = _verdict_function(n)
        # Its lines are unrolled (the body balance sums over them): past
        # _COMPILE_MAX_LINES the C takes minutes to compile, and the interpreted checks
        # cost little beside a solve of so many lines.
        self._library = Library([self.function], key=f"closed-form line audit/{n}/verdict",
                                label=f"the closed-form audit of {n} lines",
                                mode="off" if n > _COMPILE_MAX_LINES else None)
        self._compiled = None
        self._static = self._data = None   # the inputs last given (they persist)
        self._lock = threading.Lock()

    def __call__(self, table: np.ndarray, static: np.ndarray, pose=None, data=None) -> tuple:
        """``(ok, t_max, out, balanced)``: the verdict, the largest end tension, where not
        ok every line's outputs ``(k, len(_OUTPUTS))`` (None where ok), and whether the
        body given by ``pose`` and ``data`` balances (:func:`.bodies.one_body_inputs`;
        False without them), for the ``k`` rows of ``table`` and the ``n`` rows of
        ``static``."""
        k, n = len(table), self.n
        with self._lock:
            if self._compiled is None and self._library.ready:
                self._compiled = self._library.instances()[0]
            lib = self._compiled
            if lib is None:
                rows = np.zeros((n, len(LINE_COLUMNS)))
                rows[:k] = table
                out, verdict = (np.asarray(v, float) for v in self.function(
                    rows.T, static.T, np.zeros(BODY_POSE) if pose is None else pose,
                    np.zeros(BODY_DATA) if data is None else data))
                out, verdict = out.T, verdict.ravel()
            else:
                lib.inputs[0].reshape(n, -1)[:k] = table
                if self._static is not static:
                    lib.inputs[1].reshape(n, -1)[:] = static
                    self._static = static
                if pose is not None:
                    lib.inputs[2][:] = pose
                    if self._data is not data:
                        lib.inputs[3][:] = data
                        self._data = data
                lib()
                verdict = lib.output_buffer[-3:]
                out = lib.output_buffer[:n * len(_OUTPUTS)].reshape(n, -1)
            balanced = pose is not None and bool(verdict[2] == 1.0)
            if verdict[0] == 1.0:
                return True, float(verdict[1]), None, balanced
            return False, 0.0, out[:k].copy(), balanced


def _verdict_function(n: int) -> ca.Function:
    rows = ca.SX.sym("table", len(LINE_COLUMNS), n)
    static = ca.SX.sym("static", len(_STATIC), n)
    pose, data = ca.SX.sym("pose", BODY_POSE), ca.SX.sym("body", BODY_DATA)
    one = _line_checks()
    first, t_ends = _OUTPUTS.index(_RATIOS[0]), _OUTPUTS.index("t_ends")
    outs, ends, ok, t_max = [], [], 1, 0.0
    for j in range(n):
        row, data_j = rows[:, j], dict(zip(_STATIC, ca.vertsplit(static[:, j])))
        lower = ca.vertcat(*[row[c] for c in _A + _B + _FA + _FB + [_GROUNDED]])
        upper = ca.vertcat(*[row[c] for c in _B + _A + _FB + _FA + [_GROUNDED]])
        out = one(ca.vertcat(ca.if_else(data_j["flipped"], upper, lower),
                             static[:len(_INPUTS) - 13, j]))
        outs.append(out)
        # Finite: a sum of finite numbers is (or overflows, and the caller then decides).
        good = ca.logic_and(out[0] >= 1, ca.fabs(ca.sum1(row)) <= 1.7e308)
        good = ca.logic_and(good, ca.logic_not(ca.logic_and(data_j["lifted"],
                                                            row[_GROUNDED] > 0)))
        for r in range(len(_RATIOS)):
            good = ca.logic_and(good, out[first + r] <= 1.0)
        ok = ca.logic_and(ok, ca.logic_or(data_j["line"] == 0, good))
        t_max = ca.fmax(t_max, ca.if_else(data_j["line"], out[t_ends], 0.0))
        for on, at, pull in (("on_a", _A, _FA), ("on_b", _B, _FB)):
            ends.append((data_j[on], [row[c] for c in at], [row[c] for c in pull]))
    balanced = symbolic_balance(ends, ca.fmax(t_max, 1.0), pose, data)
    return ca.Function("moorsolve_line_audit", [rows, static, pose, data],
                       [ca.horzcat(*outs), ca.vertcat(ok, t_max, balanced)])


_MAPPED: dict = {}
_MAPPED_LOCK = threading.Lock()
#: Most lines whose checks are compiled (1.4 MB of C at 128; 6 MB, 100 s at -O0, at 512).
_COMPILE_MAX_LINES = 128


def _mapped(lines: int) -> _Mapped:
    """The checks mapped over the next power of two of ``lines`` (at least 8): a handful
    of small libraries serve every scene."""
    n = max(8, 1 << (lines - 1).bit_length())
    hit = _MAPPED.get(n)
    if hit is None:
        with _MAPPED_LOCK:
            hit = _MAPPED.get(n)
            if hit is None:
                hit = _MAPPED[n] = _Mapped(n)
    return hit


def wait_compiled(lines: int, timeout: float | None = None) -> bool:
    """Wait for the compile of the checks for ``lines`` lines (started by the first audit
    of so many lines); whether they now run compiled."""
    return _mapped(lines)._library.wait(timeout)


def closed_form_findings(problem, case, table, tol_rel: float):
    """``(findings, t_max)``: the per-line findings (one sentence each, prefixed with the
    leg's name) and the largest end tension [N]; findings None where a line is too steep
    for the closed forms (the profile audit must answer)."""
    return closed_form_check(problem, case, table, tol_rel)[:2]


def closed_form_check(problem, case, table, tol_rel: float, body=None):
    """:func:`closed_form_findings`, and whether the scene's one free body balances by half
    the margin :func:`.bodies.body_findings` allows (False: let it answer), given
    ``body``, the ``(name, pose, data)`` of :func:`.bodies.one_body_inputs`."""
    lifted, mapped = _columns(problem)[2:]
    name, pose, data = (None, None, None) if body is None else body
    static = _static_columns(problem, case, tol_rel, name)
    ok, t_max, out, balanced = mapped(table, static, pose, data)
    if ok:          # the checks below all passed, in the compiled verdict
        return [], t_max, balanced
    # A line from an end off the seabed that touches down between its ends has two arcs:
    # the profile audit's.
    if not np.isfinite(table).all() or (
            lifted is not None and (lifted & (table[:, _GROUNDED] > 0)).any()):
        return None, 0.0, False
    if out[:, 0].min() < 1.0:
        return None, 0.0, False
    found = []
    # A defect is a ratio above 1, or not a number at all (the largest is then NaN).
    if not out[:, 2:2 + len(_RATIOS)].max() <= 1.0:
        bad = ~(out[:, 2:2 + len(_RATIOS)] <= 1.0)
        for i in bad.any(axis=1).nonzero()[0]:
            said = dict(zip(_OUTPUTS, out[i].tolist()), grounded=table[i, _GROUNDED],
                        L=static[i, 0])
            found += [f"leg {case.lines[i].name}: {_SAY[name](said)}"
                      for name, failed in zip(_RATIOS, bad[i]) if failed]
    return found, float(out[:, 1].max()), False
