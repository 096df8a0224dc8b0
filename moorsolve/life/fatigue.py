"""Fatigue of every line end over a scatter diagram (``checks.fatigue``).

Per line end, Miner's sum over the sea states of the scatter diagram::

    D = sum_i D_i(p_i T_life),   life = T_life / D,   passes when DFF x D <= 1

with ``D_i(t)`` the damage of sea state ``i`` over a time ``t`` from the end's tension
spectrum (:mod:`.damage`: narrow band, or Dirlik), the tension turned into the curve's
range by its basis (stress on the chain or rope area, or the ratio to MBL:
:mod:`moorsolve.catalog.fatigue`) and the curve of the line type at that end. The design
fatigue factor is the user's (5 by default, DNV-OS-E301's for a line that can be
inspected); DNV's rise of it with the adjacent line's damage is not applied.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..errors import CaseError
# One year [s] (365.25 days, the unit ``y`` of case files) for wear and fatigue alike.
from ..model.build_wear import SECONDS_PER_YEAR as YEAR_S
from .damage import dirlik_damage, narrow_band_damage, spectral_moments

__all__ = ["fatigue", "FatigueResult", "EndFatigue", "YEAR_S"]

ENDS = ("anchor", "fairlead")


@dataclass(frozen=True)
class EndFatigue:
    """Fatigue at one end of one line.

    Attributes
    ----------
    line, end : str
        Line name and ``"anchor"`` (end A) or ``"fairlead"`` (end B).
    line_type : str
    curve : Curve
    damage : float
        Miner's sum over the design life.
    per_state : ndarray (n_states,)
        Each sea state's share of it.
    life_y : float
        Fatigue life [years] (inf without damage).
    sigma_N : ndarray (n_states,)
        Standard deviation of the wave-frequency tension in each sea state [N].
    mean_N : float
        Static tension [N].
    """

    line: str
    end: str
    line_type: str
    curve: object
    damage: float
    per_state: np.ndarray
    life_y: float
    sigma_N: np.ndarray
    mean_N: float
    design_fatigue_factor: float

    @property
    def utilisation(self) -> float:
        """``DFF x D``: at most 1 to pass."""
        return self.design_fatigue_factor * self.damage

    @property
    def passed(self) -> bool:
        return self.utilisation <= 1.0

    def to_dict(self) -> dict:
        return {"line": self.line, "end": self.end, "line_type": self.line_type,
                "curve": self.curve.name, "damage": self.damage,
                "life_y": None if math.isinf(self.life_y) else self.life_y,
                "utilisation": self.utilisation, "passed": self.passed,
                "mean_N": self.mean_N, "sigma_N": self.sigma_N.tolist(),
                "damage_per_state": self.per_state.tolist()}


@dataclass(frozen=True)
class FatigueResult:
    """The fatigue of a case's line ends (:func:`fatigue`)."""

    ends: tuple
    sea_states: tuple
    design_life_s: float
    design_fatigue_factor: float
    method: str
    curves: tuple
    simulated: tuple
    not_simulated: tuple
    time_s: float
    coverage: np.ndarray

    @property
    def passed(self) -> bool:
        return all(e.passed for e in self.ends)

    @property
    def design_life_y(self) -> float:
        return self.design_life_s / YEAR_S

    def worst(self) -> EndFatigue:
        """The end of largest damage."""
        return max(self.ends, key=lambda e: e.damage)

    def to_dict(self) -> dict:
        return {"design_life_y": self.design_life_y,
                "design_fatigue_factor": self.design_fatigue_factor,
                "method": self.method, "passed": self.passed,
                "adjacent_line_rule": "not applied: the design fatigue factor is the given one",
                "sea_states": [{"hs_m": s[0], "tp_s": s[1], "toward_deg": s[2],
                                "probability": s[3], "coverage": float(c)}
                               for s, c in zip(self.sea_states, self.coverage)],
                "curves": [c.to_dict() for c in self.curves],
                "simulated": list(self.simulated), "not_simulated": list(self.not_simulated),
                "ends": [e.to_dict() for e in self.ends], "time_s": self.time_s}

    def __repr__(self) -> str:
        from ..report.fatigue import fatigue_text
        return fatigue_text(self)


def _damage(method, omega, G, duration, m, a_d):
    if method == "dirlik":
        return dirlik_damage(omega, G, duration, m, a_d)
    m0, m2 = spectral_moments(omega, G, (0, 2))
    return narrow_band_damage(m0, m2, duration, m, a_d)


def fatigue(result_or_case, spec=None, *, method=None, solver: str = "ipopt",
            n_omega: int = 50, n_elements: int = 24) -> FatigueResult:
    """Fatigue damage and life of every line end over a scatter diagram.

    Parameters
    ----------
    result_or_case : Result, Case or path
        A solved equilibrium or a case to solve (its bodies need hydrodynamics).
    spec : FatigueSpec, optional
        Default: the case's ``checks.fatigue``.
    method : {"narrow_band", "dirlik"}, optional
        Overrides the spec's.
    solver : str
        Static solver when a case is given.
    n_omega, n_elements : int
        Frequencies of the common grid and about how many elements per line in the line
        dynamics (the defaults hold the damage within about 1 % of 120 and 60).

    Returns
    -------
    FatigueResult

    Raises
    ------
    CaseError
        Without a fatigue spec, without hydrodynamics, or where a curve needs a diameter or
        MBL the line type does not give.
    """
    from ..studies.stiffness import as_result
    from .response import scatter_tensions

    t0 = time.perf_counter()
    result = as_result(result_or_case, solver)
    case = result.case
    if spec is None:
        spec = None if case.checks is None else case.checks.fatigue
    if spec is None:
        raise CaseError("checks.fatigue", "the case gives no fatigue check "
                        "(checks.fatigue: {design_life, sea_states, curve})")
    method = method or spec.method
    if method not in ("narrow_band", "dirlik"):
        raise CaseError("method", f"{method!r}: use 'narrow_band' or 'dirlik'")
    tensions = scatter_tensions(result, spec.sea_states, spec.spectrum, n_omega=n_omega,
                                n_elements=n_elements)
    omega = tensions.omega
    ends, used = [], {}
    for j, line in enumerate(case.lines):
        for k, end in enumerate(ENDS):
            seg = line.segments[0 if k == 0 else -1]
            lt = seg.line_type
            curve = spec.curve_for(lt.name)
            used[curve.name if curve.name != "user" else id(curve)] = curve
            where = f"line_types.{lt.name}"
            try:
                scale = curve.range_per_newton(lt.diameter, lt.mbl)
            except CaseError as err:
                raise CaseError(f"{where}.{err.field}", err.detail) from None
            mean = float(tensions.mean_tension[j, k])
            a_d = curve.intercept(mean / lt.mbl if lt.mbl else 0.0)
            per_state = np.array([
                _damage(method, omega, tensions.spectra[i, j, k] * scale ** 2,
                        s[3] * spec.design_life, curve.m, a_d)
                for i, s in enumerate(spec.sea_states)])
            damage = float(per_state.sum())
            sigma = np.sqrt(np.maximum(np.trapezoid(tensions.spectra[:, j, k], omega,
                                                    axis=-1), 0.0))
            life = spec.design_life / YEAR_S / damage if damage > 0 else math.inf
            ends.append(EndFatigue(line=line.name, end=end, line_type=lt.name, curve=curve,
                                   damage=damage, per_state=per_state, life_y=life,
                                   sigma_N=sigma, mean_N=mean,
                                   design_fatigue_factor=spec.design_fatigue_factor))
    return FatigueResult(
        ends=tuple(ends), sea_states=spec.sea_states, design_life_s=spec.design_life,
        design_fatigue_factor=spec.design_fatigue_factor, method=method,
        curves=tuple(used.values()),
        simulated=("wave_frequency_tension",),
        not_simulated=("low_frequency_tension", "mean_drift_per_sea_state"),
        time_s=time.perf_counter() - t0, coverage=tensions.coverage)
