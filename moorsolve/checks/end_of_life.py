"""The end-of-life check: the mooring as it will be after its design life, checked again.

With ``checks.corrosion`` or ``checks.creep`` (:mod:`moorsolve.model.build_wear`) the case
describes what its lines lose in service. :func:`end_of_life_case` builds that mooring:

1. the new mooring is solved once (intact, the mean equilibrium) and each part of each line
   is given its zone, ``splash``, ``catenary`` or ``bottom`` (:mod:`.wear_zones`); the
   corrosion happened where the line lay, so the zones are the new mooring's;
2. each segment is split where its rate changes with the zone, and each part gets a line
   type corroded at its rate over the design life (diameter, weights, ``ea`` and MBL:
   :mod:`.wear`);
3. fibre ropes creep: each segment of a creeping line type is lengthened by
   ``1 + rate x design_life`` with its weight per length reduced by the same factor.

:func:`run_end_of_life` runs every check (intact and damaged) on that mooring
(:func:`~moorsolve.checks.run_checks`): the MBL in every tension check is the end-of-life
one. Its report says the age and every segment's diameters, MBL, weight and length, new
and at the end of life, with the fatigue diameter (:func:`.wear.fatigue_diameter`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from ..errors import CaseError, ConvergenceError
from ..model import Case
from ..model.build_wear import Wear
from ..model.lines import Segment
from ..solve import solve
from .run import CheckReport, run_checks
from .wear import (corroded_line_type, creep_factor, crept_line_type, fatigue_diameter,
                   nominal_mbl, sources)
from .wear_zones import line_zones, segment_runs, zone_lengths

__all__ = ["EndOfLifeReport", "end_of_life_case", "run_end_of_life"]


@dataclass(frozen=True)
class EndOfLifeReport:
    """The checks of the mooring at the end of its design life.

    Attributes
    ----------
    design_life_y : float
        The age [years].
    report : CheckReport
        Every check, run on the end-of-life mooring.
    segments : tuple of dict
        Per segment of every worn line (:func:`end_of_life_case`).
    splash_depth_m : float or None
    case : Case
        The end-of-life mooring.
    """

    design_life_y: float
    report: CheckReport
    segments: tuple
    splash_depth_m: float | None
    case: Case = field(repr=False, compare=False)

    @property
    def passed(self) -> bool:
        return self.report.passed

    def to_dict(self) -> dict:
        return {**self.report.to_dict(),
                "end_of_life": {"design_life_y": self.design_life_y,
                                "splash_depth_m": self.splash_depth_m,
                                "zones_from": "the new mooring's intact mean equilibrium",
                                "segments": [dict(s) for s in self.segments],
                                "sources": [dict(s) for s in sources()]}}


def _wear(case: Case) -> Wear:
    wear = None if case.checks is None else case.checks.wear
    if wear is None:
        raise CaseError("checks.corrosion", "the end-of-life check needs what the lines "
                        "lose: give checks.design_life with checks.corrosion (e.g. "
                        "{rate: '0.4 mm/y'}) and/or checks.creep")
    return wear


def _zones(case: Case, wear: Wear, tol) -> dict:
    """Per line name, its segments' zone runs (None for a line with a pretensioned
    segment, whose length the solve sets)."""
    try:
        result = solve(case, tol=tol, allow_overload=True)
    except ConvergenceError as exc:
        raise ConvergenceError(
            "the new mooring, solved to find where each line lies (its corrosion zones): "
            f"{exc.reason}", residual_N=exc.residual_N, residual_Nm=exc.residual_Nm,
            status=exc.status, iterations=exc.iterations, result=exc.result) from exc
    by_name = {lr.name: lr for lr in result.legs}
    depth = wear.corrosion.splash_depth if wear.corrosion is not None else None
    out = {}
    for line in case.lines:
        if any(s.pretension is not None for s in line.segments) or line.name not in by_name:
            out[line.name] = None
            continue
        out[line.name] = segment_runs(line, line_zones(line, by_name[line.name],
                                                       case.environment, depth))
    return out


def end_of_life_case(case: Case, *, tol=None) -> tuple:
    """The mooring of ``case`` after its design life, and what changed.

    Returns
    -------
    (Case, tuple of dict)
        The end-of-life case (its line types named ``TYPE@eol`` or ``TYPE@eol:ZONE``) and,
        per worn segment: ``line``, ``segment``, ``line_type``, ``zones`` (length [m] per
        zone), ``length_m`` and ``length_eol_m``, ``creep_strain`` and ``parts`` (per part
        of one rate: ``zone``, ``length_m``, ``rate_mm_per_y``, ``diameter_m``,
        ``diameter_eol_m``, ``fatigue_diameter_m``, ``mbl_N``, ``mbl_eol_N``,
        ``weight_N_per_m``, ``weight_eol_N_per_m``).

    Raises
    ------
    CaseError
        No ``checks.corrosion`` or ``checks.creep``, or a loss that consumes a diameter.
    ConvergenceError
        The new mooring has no equilibrium to take the zones from.
    """
    wear = _wear(case)
    life = wear.design_life
    _check_diameters(case, wear)
    zones = _zones(case, wear, tol) if wear.corrosion is not None else {}
    types = dict(case.line_types)
    lines, rows = [], []
    for line in case.lines:
        segments, clumps = [], []
        joint = line.joint_clumps
        runs_of = zones.get(line.name)
        for j, seg in enumerate(line.segments):
            if j:
                clumps.append(joint[j - 1])
            lt = seg.line_type
            rates = (None if wear.corrosion is None
                     else wear.corrosion.rates_for(line.name, j, lt))
            creep = None if wear.creep is None else wear.creep.rate_for(lt)
            if (rates is None and creep is None) or seg.pretension is not None:
                segments.append(seg)
                continue
            factor = 1.0 if creep is None else creep_factor(creep, life)
            runs = runs_of[j] if runs_of is not None else [("whole", seg.length)]
            parts = _parts(runs, rates, runs_of is None)
            if len(parts) > 1 and case.environment.seabed.sloped:
                raise CaseError(
                    "checks.corrosion.rate",
                    f"rates by zone split line {line.name!r} segment {j} into "
                    f"{len(parts)} parts, but on a sloped seabed or a bathymetry grid a line "
                    "takes one segment; give one rate for all zones (or a flat seabed)")
            for k, (zone, length, rate) in enumerate(parts):
                new = _worn_type(lt, rate, factor, life, zone if len(parts) > 1 else None,
                                 line, j, types)
                types[new.name] = new
                if k:
                    clumps.append(None)
                segments.append(Segment(line_type=new, length=length * factor))
            rows.append(_row(line, j, seg, None if runs_of is None else runs, parts, factor,
                             creep, life, types))
        lines.append(dataclasses.replace(line, segments=tuple(segments),
                                         clumps=tuple(clumps)))
    eol = dataclasses.replace(case, name=f"{case.name} (end of life, {life:g} y)",
                              lines=tuple(lines), line_types=types, source=None)
    return eol, tuple(rows)


def _parts(runs: list, rates, unknown: bool) -> list:
    """``[(zone, length, rate), ...]``: the runs with their rate [m/y], consecutive runs of
    one rate merged (their zone names joined). Where the zones are unknown (a line with a
    pretensioned segment) the largest zone rate is taken."""
    out = []
    for zone, length in runs:
        rate = (None if rates is None
                else max(rates.splash, rates.catenary, rates.bottom) if unknown
                else rates.at(zone))
        if out and out[-1][2] == rate:
            z, l0, _ = out[-1]
            out[-1] = (z if zone in z.split("+") else f"{z}+{zone}", l0 + length, rate)
        else:
            out.append((zone, length, rate))
    return out


def _worn_type(lt, rate, factor, life, zone, line, j, types):
    name = f"{lt.name}@eol" + ("" if zone is None else f":{zone}")
    new = lt if rate is None else corroded_line_type(lt, rate, life, name)
    if factor != 1.0:
        new = crept_line_type(new, factor, name)
    new = dataclasses.replace(new, name=name)
    if name in types and types[name] != new:
        # The same type worn differently elsewhere (its own segment rate): name it apart.
        new = dataclasses.replace(new, name=f"{name}:{line.name}[{j}]")
    return new


def _check_diameters(case: Case, wear: Wear) -> None:
    """Bad input before any solve: a loss over the life that consumes a diameter."""
    if wear.corrosion is None:
        return
    for line in case.lines:
        for j, seg in enumerate(line.segments):
            lt = seg.line_type
            rates = wear.corrosion.rates_for(line.name, j, lt)
            if rates is None:
                continue
            rate = max(rates.splash, rates.catenary, rates.bottom)
            if not rate * wear.design_life < lt.diameter:
                raise CaseError("checks.corrosion",
                                f"a loss of {rate * 1e3:g} mm/y over {wear.design_life:g} y "
                                f"consumes the {lt.diameter * 1e3:g} mm diameter of line "
                                f"{line.name!r} segment {j} ({lt.name}); give a smaller "
                                "rate or design_life")


def _row(line, j, seg, runs, parts, factor, creep, life, types) -> dict:
    lt = seg.line_type
    out = []
    for zone, length, rate in parts:
        name = f"{lt.name}@eol" + ("" if len(parts) == 1 else f":{zone}")
        new = types.get(f"{name}:{line.name}[{j}]", types[name])
        d = lt.diameter
        out.append({
            "zone": zone, "length_m": length, "length_eol_m": length * factor,
            "rate_mm_per_y": None if rate is None else rate * 1e3,
            "diameter_m": d, "diameter_eol_m": new.diameter,
            "fatigue_diameter_m": (None if rate is None or d is None
                                   else fatigue_diameter(d, rate, life)),
            "mbl_N": nominal_mbl(lt), "mbl_eol_N": new.mbl,
            "weight_N_per_m": lt.weight_in_water,
            "weight_eol_N_per_m": new.weight_in_water})
    return {"line": line.name, "segment": j, "line_type": lt.name,
            "zones": None if runs is None else zone_lengths(runs), "length_m": seg.length,
            "length_eol_m": seg.length * factor,
            "creep_strain": None if creep is None else factor - 1.0, "parts": out}


def run_end_of_life(case: Case, *, standard: str | None = None, tol: float | None = None,
                    damaged: bool | None = None) -> EndOfLifeReport:
    """Every check of ``case`` run on its mooring at the end of the design life.

    Parameters as :func:`~moorsolve.checks.run_checks`; raises CaseError without
    ``checks.corrosion`` or ``checks.creep`` and ConvergenceError when the new mooring
    (solved for the zones) has no equilibrium.
    """
    wear = _wear(case)
    eol, rows = end_of_life_case(case, tol=tol)
    report = run_checks(eol, standard=standard, tol=tol, damaged=damaged)
    depth = None if wear.corrosion is None else wear.corrosion.splash_depth
    return EndOfLifeReport(design_life_y=wear.design_life, report=report, segments=rows,
                           splash_depth_m=depth, case=eol)
