"""MoorDyn tension-strain curve files: a line type's EA given as a file name, in and out.

MoorDyn reads a line type's ``EA`` column as a number or, failing that, as the name of a
file of strain and tension (MoorDyn-C v2 ``MoorDyn2::read_curve``: a token that does not
parse as a number; MoorDyn-F: a token holding a letter other than ``e``/``E``), relative to
the input file's folder. v2 may add dynamic-stiffness values after bars (``poly.txt|3e8``).
The file (MoorDyn documentation, "Nonlinear Stiffness (EA) Inputs")::

    ----Polyester----            three header lines
    Strain    Tension
    (-)       (N)
    0.0       0.0                then one row per point: strain [-], tension [N]
    0.01      1.2e5

MoorDyn takes at most 30 points (``nCoef``), splits rows on blanks, and its C reader rejects
an empty line, so a file it reads has no blank line, not even a final newline; the writer
here writes it so. (MoorPy's reader wants the name in quotes and a closing ``---`` line,
which MoorDyn would not read: MoorDyn's form is written.) MoorDyn interpolates linearly
between the rows, so an imported curve is a table law with ``interpolation: linear``: the
same strain at every tension. Beyond the last row MoorDyn holds the last tension (the rope
would stretch without bound); moorsolve continues the last chord, so a statics solve past
the table still has a rope. A monotone-cubic law written out is sampled at up to
``MAX_POINTS`` rows (:func:`sample_cubic`), and its departure reported.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from ..errors import CaseError

__all__ = ["MAX_POINTS", "is_number", "read_curve", "curve_text", "curve_file_name",
           "sample_law", "sample_table", "sample_cubic", "chord_departure"]

#: MoorDyn's ``nCoef``: the most points a curve file may hold.
MAX_POINTS = 30

_FORTRAN_EXPONENT = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))[dD]([+-]?\d+)$")


def _float(token: str) -> float:
    m = _FORTRAN_EXPONENT.match(token)
    return float(f"{m.group(1)}e{m.group(2)}" if m else token)


def is_number(token: str) -> bool:
    """Whether MoorDyn reads an EA token as a number (else it names a curve file)."""
    try:
        return math.isfinite(_float(token))
    except ValueError:
        return False


def read_curve(folder: Path, token: str, error) -> dict:
    """The table law of curve file ``token`` (quotes stripped) in ``folder``.

    ``error(message)`` makes the exception to raise (the MoorDyn file and line). Returns
    ``{"model": "table", "strain": [...], "tension": [...], "interpolation": "linear"}`` as
    a case file holds it: MoorDyn's own linear reading of the rows.
    """
    name = token.strip().strip("'\"")
    path = folder / name
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except FileNotFoundError:
        raise error(f"column 'EA': curve file {name!r} not found in {str(folder)!r} (MoorDyn "
                    "reads it relative to the input file)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise error(f"column 'EA': cannot read curve file {name!r}: {exc}") from None
    strain, tension = [], []
    for number, line in enumerate(lines[3:], start=4):
        words = line.replace(",", " ").split()
        if not words or words[0].startswith("---"):
            break
        try:
            e, t = _float(words[0]), _float(words[1])
        except (ValueError, IndexError):
            raise error(f"column 'EA': curve file {name}:{number}: {line.strip()!r} is not a "
                        "row 'strain tension'") from None
        strain.append(e)
        tension.append(t)
    if len(strain) < 2:
        raise error(f"column 'EA': curve file {name} has {len(strain)} rows after its three "
                    "header lines; MoorDyn needs at least 2 (strain, tension)")
    if len(strain) > MAX_POINTS:
        raise error(f"column 'EA': curve file {name} has {len(strain)} rows; MoorDyn reads at "
                    f"most {MAX_POINTS}")
    return {"model": "table", "strain": strain, "tension": tension, "interpolation": "linear"}


def curve_file_name(prefix: str, line_type: str) -> str:
    """The curve file of a line type: ``<prefix><type>_ea.txt`` (letters, so MoorDyn reads
    it as a name; no folder, so it sits beside the input file)."""
    safe = re.sub(r"[^A-Za-z0-9_.-]", "_", line_type)
    return f"{prefix}{safe}_ea.txt"


def curve_text(title: str, strain, tension) -> str:
    """A MoorDyn curve file: three header lines, then ``strain tension`` rows; no blank
    line and no final newline (MoorDyn-C's reader rejects an empty line)."""
    if len(strain) > MAX_POINTS:
        raise CaseError("stretch", f"{len(strain)} rows; MoorDyn reads at most {MAX_POINTS}")
    rows = [f"---- {title} ----", "Strain Tension", "(-) (N)"]
    rows += [f"{e!r} {t!r}" for e, t in zip(strain, tension)]
    return "\n".join(rows)


def sample_law(law, mbl: float | None) -> tuple:
    """``(strain, tension)`` rows for MoorDyn of a law it has no form for (Baranov's):
    ``MAX_POINTS`` rows evenly spaced in strain, so that MoorDyn's linear interpolation of
    ``T = (eps/n)^2`` errs alike everywhere, up to the MBL (or 20 % strain without one)."""
    eps_max = law.n * math.sqrt(mbl) if mbl else 0.2
    strain = [eps_max * i / (MAX_POINTS - 1) for i in range(MAX_POINTS)]
    return strain, [(e / law.n) ** 2 for e in strain]


def sample_table(law) -> tuple:
    """``(strain, tension)``: a table law of more rows than MoorDyn reads (a SYROPE rope's
    working and original curves together) cut to ``MAX_POINTS`` of its own rows: the row
    that linear interpolation between its neighbours misses least is dropped, one at a time
    (Visvalingam's rule), so kinks (the end of a working curve) and the end rows stay."""
    strain, tension = list(law.strain), list(law.tension)
    while len(strain) > MAX_POINTS:
        def miss(k):
            e0, e1, e2 = strain[k - 1], strain[k], strain[k + 1]
            t0, t2 = tension[k - 1], tension[k + 1]
            return abs(tension[k] - (t0 + (t2 - t0) * (e1 - e0) / (e2 - e0))) / t2
        k = min(range(1, len(strain) - 1), key=miss)
        del strain[k], tension[k]
    return strain, tension


#: Samples per interval when measuring how far MoorDyn's chords depart from a cubic law.
_PROBES = 64


def chord_departure(law, strain, tension) -> float:
    """Largest departure of MoorDyn's chords through ``(strain, tension)`` from ``law``
    (a :class:`~moorsolve.model.stretch.StretchLaw`) up to the last row: the tension
    error at the law's strain, relative to the last row's tension [-]."""
    worst = 0.0
    for k in range(len(strain) - 1):
        T = [tension[k] + (tension[k + 1] - tension[k]) * (i + 1) / (_PROBES + 1)
             for i in range(_PROBES)]
        eps = law.strains(T)
        slope = (tension[k + 1] - tension[k]) / (strain[k + 1] - strain[k])
        chord = tension[k] + slope * (eps - strain[k])
        worst = max(worst, float(max(abs(chord - T))))
    return worst / tension[-1]


def sample_cubic(law) -> tuple:
    """``(strain, tension)`` rows for MoorDyn (which joins rows by chords) of a
    monotone-cubic table law: its own rows (cut to ``MAX_POINTS`` by :func:`sample_table`
    when more), then points of the cubic added one at a time where the chords miss the
    law most (the middle tension of the worst interval), up to ``MAX_POINTS`` rows. The
    chords then depart from the law by about 1/16 of the original intervals' departure
    where the added rows go; :func:`chord_departure` gives what is left."""
    strain, tension = sample_table(law) if law.rows > MAX_POINTS else (list(law.strain),
                                                                       list(law.tension))
    strain, tension = list(strain), list(tension)

    def miss(k):
        return chord_departure(law, strain[k:k + 2], tension[k:k + 2]) * tension[k + 1]

    misses = [miss(k) for k in range(len(strain) - 1)]
    while len(strain) < MAX_POINTS:
        k = max(range(len(misses)), key=misses.__getitem__)
        T = (tension[k] + tension[k + 1]) / 2
        strain.insert(k + 1, float(law.strains([T])[0]))
        tension.insert(k + 1, T)
        misses[k:k + 1] = [miss(k), miss(k + 1)]
    return strain, tension
