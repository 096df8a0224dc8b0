"""Fatigue from tension time series (measured, or simulated in the time domain).

Each line end's record is counted by rainflow (ASTM E1049-85 (2017), the ``rainflow``
package) and its Miner's sum scaled from the record's length to the design life::

    D = (T_life / T_record) sum_j n_j S_j^m / a_D

the record taken as representative of the whole life (a long-term record, or one sea state
whose probability is 1). The curve, design life and design fatigue factor are those of
``checks.fatigue``.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import CaseError
from .damage import rainflow_damage
from .fatigue import ENDS, YEAR_S, EndFatigue, FatigueResult

__all__ = ["series_fatigue"]


def series_fatigue(case, table, spec=None) -> FatigueResult:
    """Fatigue of the line ends a tension table gives.

    Parameters
    ----------
    case : Case
        The scene (line types: diameter, MBL) with its ``checks.fatigue`` unless ``spec``.
    table : mapping of str to array_like
        ``time_s`` [s] and, per line end, a column ``LINE.anchor`` or ``LINE.fairlead`` of
        tension [N] (a pandas DataFrame or a dict of arrays).
    spec : FatigueSpec, optional

    Returns
    -------
    FatigueResult
        Without sea states (``method`` ``"rainflow"``); ``per_state`` holds the end's
        damage over the life.
    """
    if spec is None:
        spec = None if case.checks is None else case.checks.fatigue
    if spec is None:
        raise CaseError("checks.fatigue", "the case gives no fatigue check "
                        "(checks.fatigue: {design_life, sea_states, curve})")
    columns = list(table.keys())
    if "time_s" not in columns:
        raise CaseError("time_s", "a tension table needs a time_s column [s]")
    t = np.asarray(table["time_s"], float)
    if t.size < 2 or not np.all(np.diff(t) > 0):
        raise CaseError("time_s", "times must increase, at least 2 of them")
    record = float(t[-1] - t[0])
    lines = {ln.name: ln for ln in case.lines}
    ends = []
    for col in columns:
        if col == "time_s":
            continue
        name, _, end = col.rpartition(".")
        if name not in lines or end not in ENDS:
            raise CaseError(col, "a tension column is LINE.anchor or LINE.fairlead, LINE one "
                                 f"of {', '.join(lines)}")
        seg = lines[name].segments[0 if end == "anchor" else -1]
        lt = seg.line_type
        curve = spec.curve_for(lt.name)
        try:
            scale = curve.range_per_newton(lt.diameter, lt.mbl)
        except CaseError as err:
            raise CaseError(f"line_types.{lt.name}.{err.field}", err.detail) from None
        x = np.asarray(table[col], float)
        if x.shape != t.shape or not np.all(np.isfinite(x)):
            raise CaseError(col, f"needs {t.size} finite tensions, one per time")
        mean = float(np.mean(x))
        a_d = curve.intercept(mean / lt.mbl if lt.mbl else 0.0)
        d_record = rainflow_damage(x, curve.m, a_d, scale=scale)[0]
        damage = d_record * spec.design_life / record
        life = spec.design_life / YEAR_S / damage if damage > 0 else math.inf
        ends.append(EndFatigue(line=name, end=end, line_type=lt.name, curve=curve,
                               damage=damage, per_state=np.array([damage]), life_y=life,
                               sigma_N=np.array([float(np.std(x))]), mean_N=mean,
                               design_fatigue_factor=spec.design_fatigue_factor))
    if not ends:
        raise CaseError("table", "no tension column (LINE.anchor or LINE.fairlead)")
    return FatigueResult(
        ends=tuple(ends), sea_states=(),
        design_life_s=spec.design_life, design_fatigue_factor=spec.design_fatigue_factor,
        method="rainflow", curves=tuple({id(e.curve): e.curve for e in ends}.values()),
        simulated=("tension_record",), not_simulated=(), time_s=0.0,
        coverage=np.zeros(0))
