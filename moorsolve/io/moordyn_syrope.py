"""MoorDyn's SYROPE polyester-rope model, read as the static stretch law it implies.

A MoorDyn v2 line type whose EA is ``SYROPE:<config>|EA_Dc|EA_D_Lm`` (MoorDyn documentation,
"Syrope Model for Polyester Lines") names a config file of four rows ``value name``: ``OWC``
(a curve file of the original working curve, strain against tension, read as any EA curve
file, relative to the main input file), ``WCType`` (``LINEAR``, ``QUADRATIC`` or ``EXP``),
``k1`` and ``k2``. The ``SYROPE IC`` section gives each SYROPE line ``Tmax0`` (the highest
mean tension the rope has seen) and ``Tmean0`` (its initial mean tension).

At rest MoorDyn's slow-strain state is settled (its rate vanishes), so the rope's strain is
the working curve's at its tension (MoorDyn ``Line::getStateDeriv``). Below ``Tmax0`` that
is the working curve of ``Tmax0`` (``Line::setWorkingCurve``): ``nEApointsWC`` = 30 points
evenly spaced in strain from ``eps_min`` to ``eps_max``, where ``eps_max`` is the original
curve's strain at ``Tmax0`` and ``eps_min = eps_0 + k1 (eps_max - eps_0)`` (``eps_0`` the
curve's first strain), or ``eps_max - Tmax0/k1`` for a linear curve with ``k1 >= 1``; the
tension at ``xi = (eps - eps_min)/(eps_max - eps_min)`` is ``Tmax0 xi`` (linear),
``Tmax0 xi (k2 xi + 1 - k2)`` (quadratic) or ``Tmax0 (1 - e^(k2 xi))/(1 - e^k2)`` (exp).
Above ``Tmax0`` the rope is back on the original curve (and ``Tmax`` follows it up). The two
meet at ``(eps_max, Tmax0)``, so the static law is one table: the working curve's points,
then the original curve's beyond ``Tmax0``, interpolated linearly as MoorDyn does.

The working curve carries no tension below ``eps_min``: a rope once loaded keeps a permanent
stretch. A case's table law starts at (0, 0), so each SYROPE line becomes its own line type
over the permanently stretched length ``L (1 + eps_min)``, with the strain measured from it
(``(eps - eps_min)/(1 + eps_min)``) and the mass and displaced volume per metre divided by
``1 + eps_min``: the same rope, weight and stretch element by element. ``Tmean0`` and the
dynamic stiffness ``EA_Dc|EA_D_Lm`` only start MoorDyn's simulation: reported, not used.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

from .moordyn_curves import read_curve

__all__ = ["WC_POINTS", "SyropeType", "is_syrope", "read_syrope", "syrope_conditions",
           "static_law", "apply_syrope"]

#: MoorDyn's ``nEApointsWC``: points of a working curve.
WC_POINTS = 30
_FORMS = ("linear", "quadratic", "exp")


@dataclass(frozen=True)
class SyropeType:
    """A SYROPE line type's static data: the original working curve and the formula."""

    config: str
    owc_strain: tuple
    owc_tension: tuple
    form: str
    k1: float
    k2: float


def is_syrope(ea_token: str) -> bool:
    return ea_token.upper().startswith("SYROPE:")


def read_syrope(folder: Path, ea_token: str, error) -> SyropeType:
    """The SYROPE data of EA token ``SYROPE:<config>|EA_Dc|EA_D_Lm``; ``error(message)``
    makes the exception (the MoorDyn file and line)."""
    parts = ea_token.split("|")
    if len(parts) != 3:
        raise error(f"column 'EA': {ea_token!r}: a SYROPE line type takes 3 '|'-separated "
                    "values, SYROPE:<config>|EA_Dc|EA_D_Lm (MoorDyn refuses others)")
    config = parts[0][len("SYROPE:"):].strip().strip("'\"")
    try:
        rows = (folder / config).read_text(encoding="utf-8").splitlines()
    except FileNotFoundError:
        raise error(f"column 'EA': SYROPE config file {config!r} not found in "
                    f"{str(folder)!r} (MoorDyn reads it relative to the input file)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise error(f"column 'EA': cannot read SYROPE config file {config!r}: {exc}") from None
    values = {}
    for row in rows:
        words = row.split()
        if len(words) >= 2:
            values[words[1].lower()] = words[0]      # "value name description"
    missing = [k for k in ("owc", "wctype", "k1", "k2") if k not in values]
    if missing:
        raise error(f"column 'EA': SYROPE config {config!r} gives no {', '.join(missing)} "
                    "(rows 'value name': OWC, WCType, k1, k2)")
    form = values["wctype"].lower()
    if form not in _FORMS:
        raise error(f"column 'EA': SYROPE config {config!r}: WCType {values['wctype']!r} must "
                    "be LINEAR, QUADRATIC or EXP")
    k = []
    for name in ("k1", "k2"):
        try:
            k.append(float(values[name]))
        except ValueError:
            raise error(f"column 'EA': SYROPE config {config!r}: {name} {values[name]!r} is "
                        "not a number") from None
    owc = read_curve(folder, values["owc"], error)
    return SyropeType(config=config, owc_strain=tuple(owc["strain"]),
                      owc_tension=tuple(owc["tension"]), form=form, k1=k[0], k2=k[1])


def syrope_conditions(md) -> dict:
    """``{line id: (Tmax0, Tmean0, file line)}`` from the SYROPE IC section's rows
    ``Line(s) Tmax0 Tmean0`` (line ids comma-separated, as MoorDyn splits them)."""
    out = {}
    for number, text in md.syrope_ic:
        entries = text.split()
        if not entries or not entries[0][0].isdigit():
            continue                                  # the column-name and units rows
        if len(entries) < 3:
            raise md.error(number, f"SYROPE IC row {text.strip()!r} has {len(entries)} "
                                   "fields; MoorDyn requires 3 (Line(s) Tmax0 Tmean0)")
        try:
            ids = [int(i) for i in entries[0].split(",") if i]
            tmax, tmean = float(entries[1]), float(entries[2])
        except ValueError:
            raise md.error(number, f"SYROPE IC row {text.strip()!r}: expected line numbers "
                                   "and two tensions") from None
        for ident in ids:
            out[ident] = (tmax, tmean, number)
    return out


def _interp(x, xs, ys) -> float:
    """MoorDyn's ``interp``: linear, held constant beyond the table's ends."""
    if x <= xs[0]:
        return ys[0]
    for k in range(1, len(xs)):
        if x <= xs[k]:
            return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1])
    return ys[-1]


def static_law(rope: SyropeType, tmax: float, error) -> tuple:
    """``(eps_min, strain, tension)``: the permanent strain and the static law's rows
    (measured from the permanently stretched length, from (0, 0))."""
    T0, T1 = rope.owc_tension[0], rope.owc_tension[-1]
    if not T0 <= tmax <= T1:
        raise error(f"Tmax0 {tmax:g} N is outside the original working curve's tensions "
                    f"[{T0:g}, {T1:g}] N (MoorDyn refuses it)")
    eps_max = _interp(tmax, rope.owc_tension, rope.owc_strain)
    eps_0 = rope.owc_strain[0]
    eps_min = eps_0 + rope.k1 * (eps_max - eps_0)
    if rope.form == "linear" and rope.k1 >= 1.0:
        eps_min = eps_max - tmax / rope.k1               # k1 is the curve's stiffness [N]
    strain, tension = [], []
    for i in range(WC_POINTS):
        xi = i / (WC_POINTS - 1)
        strain.append(eps_min + (eps_max - eps_min) * xi)
        if rope.form == "linear":
            tension.append(tmax * xi)
        elif rope.form == "quadratic":
            tension.append(tmax * xi * (rope.k2 * xi + (1.0 - rope.k2)))
        else:
            tension.append(tmax * (1.0 - math.exp(rope.k2 * xi)) / (1.0 - math.exp(rope.k2)))
    for e, t in zip(rope.owc_strain, rope.owc_tension):
        if t > tmax:
            strain.append(e)
            tension.append(t)
    if not (eps_min > -1.0 and all(b > a for a, b in zip(strain, strain[1:]))
            and all(b > a for a, b in zip(tension, tension[1:]))):
        raise error(f"its working curve at Tmax0 {tmax:g} N ({rope.form}, k1 {rope.k1:g}, "
                    f"k2 {rope.k2:g}) does not rise strictly in strain and tension: no static "
                    "law")
    scale = 1.0 + eps_min
    return eps_min, [(e - eps_min) / scale for e in strain], tension


def apply_syrope(md, types: dict, lines: dict, converted: list, ignored: list) -> tuple:
    """Types and lines with every SYROPE line on its own table-law type over its
    permanently stretched length (see the module notes)."""
    syrope_lines = [ln for ln in lines.values() if ln.type.syrope is not None]
    conditions = syrope_conditions(md) if md.syrope_ic else {}
    if md.syrope_ic and not any(t.syrope is not None for t in types.values()):
        raise md.error(md.section_lines["syrope_ic"], "a SYROPE IC section, but no line type "
                                                      "is a SYROPE rope (MoorDyn refuses it)")
    for ident, (_, _, number) in conditions.items():
        if ident not in lines:
            raise md.error(number, f"SYROPE IC names line {ident}; the file has lines "
                                   f"{', '.join(map(str, sorted(lines)))} (MoorDyn refuses it)")
        if lines[ident].type.syrope is None:
            ignored.append(f"line {number}: SYROPE IC names line {ident}, which is not a "
                           "SYROPE rope; ignored, as MoorDyn ignores it with a warning")
    used = {ln.type.name for ln in syrope_lines}
    types, lines = dict(types), dict(lines)
    for line in syrope_lines:
        lt = line.type
        if line.id not in conditions:
            raise md.error(line.line, f"line {line.id} is a SYROPE rope ({lt.name}) without a "
                                      "row in a SYROPE IC section: its Tmax0 sets its working "
                                      "curve (MoorDyn needs it too)")
        tmax, tmean, number = conditions[line.id]
        eps_min, strain, tension = static_law(
            lt.syrope, tmax, lambda message, n=number: md.error(n, f"line {line.id}: {message}"))
        scale = 1.0 + eps_min
        name = f"{lt.name}_line{line.id}"
        types[name] = replace(lt, name=name, mass=lt.mass / scale,
                              diameter=lt.diameter / math.sqrt(scale), syrope=None,
                              stretch={"model": "table", "strain": strain, "tension": tension,
                                       "interpolation": "linear"},
                              columns={k: v for k, v in lt.columns.items() if k != "ea"})
        lines[line.id] = replace(line, type=types[name], length=line.length * scale)
        converted.append(
            f"line {line.id} (line {line.line}): SYROPE rope {lt.name} ({lt.syrope.form} "
            f"working curve, k1 {lt.syrope.k1:g}, k2 {lt.syrope.k2:g}, Tmax0 {tmax:g} N from "
            f"line {number}): the working curve below Tmax0 and the original curve "
            f"{lt.syrope.config!r} above, as line type {name}; its permanent strain "
            f"{eps_min:.6g} makes it {line.length:g} m -> {line.length * scale:.6g} m with "
            f"mass and volume per metre / {scale:.6g}")
        ignored.append(f"line {line.id}: SYROPE Tmean0 {tmean:g} N and dynamic stiffness "
                       f"{'|'.join(lt.ea_token.split('|')[1:])}: MoorDyn's initial dynamic "
                       "state; the static tension is solved")
    for name, lt in list(types.items()):
        if lt.syrope is not None:
            del types[name]                       # every line of it has its own type now
            if name not in used:
                ignored.append(f"line type {name} (line {lt.line}): a SYROPE type no line "
                               "uses")
    return types, lines
