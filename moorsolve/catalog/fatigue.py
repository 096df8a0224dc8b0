"""Fatigue resistance curves of mooring line components (S-N and T-N), as data.

A curve gives the cycles to failure at a constant range ``S``: ``N = a_D S^-m``. What ``S``
is depends on its basis (``fatigue_curves.csv`` holds the catalogue, with each row's source and
how it was checked):

* ``stress_chain``: stress range [MPa] on the nominal area of the link's two bars,
  ``2 pi d^2 / 4`` (DNV-OS-E301's chain curves);
* ``stress_wire``: stress range [MPa] on the rope's nominal area ``pi d^2 / 4``;
* ``mbl_ratio``: the tension range over the minimum breaking load, ``R = dT / MBL``
  (API RP 2SK's ``N R^M = K``; for its wire ropes ``log10 K = log10 a_d - b L_m`` with
  ``L_m`` the mean tension over MBL).

A user curve ``{m, a_d}`` is a stress curve on the chain area unless it names its basis.
"""

from __future__ import annotations

import csv
import functools
import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import CaseError

__all__ = ["Curve", "catalog", "BASES", "MPA"]

BASES = ("stress_chain", "stress_wire", "mbl_ratio")
#: Pascals in a megapascal.
MPA = 1.0e6


@dataclass(frozen=True)
class Curve:
    """``N = a_D S^-m``.

    Attributes
    ----------
    m : float
        Inverse slope.
    a_d : float
        Intercept ``a_D`` [cycles MPa^m, or cycles for ``mbl_ratio``]; for a curve with a
        mean-load slope, its value at zero mean load.
    basis : str
        One of :data:`BASES`.
    mean_load_slope : float
        ``b`` in ``a_D = a_d 10^(-b L_m)`` (API's wire ropes), else 0.
    name, source, verified : str
        Catalogue name (``"user"`` for a given curve), the published source and how the
        numbers were checked.
    """

    m: float
    a_d: float
    basis: str = "stress_chain"
    mean_load_slope: float = 0.0
    name: str = "user"
    source: str = "given by the user"
    verified: str = ""

    def intercept(self, mean_over_mbl: float = 0.0) -> float:
        """``a_D`` at a mean tension of ``mean_over_mbl`` x MBL."""
        return self.a_d * 10.0 ** (-self.mean_load_slope * mean_over_mbl)

    def range_per_newton(self, diameter, mbl) -> float:
        """``S`` per newton of tension range: [MPa/N] for a stress basis, [1/N] for
        ``mbl_ratio``. Raises CaseError naming what the basis needs and is missing."""
        if self.basis == "mbl_ratio":
            if not mbl:
                raise CaseError("mbl", f"the {self.name} curve is on the tension range over "
                                       "MBL: the line type needs its mbl")
            return 1.0 / mbl
        if not diameter:
            raise CaseError("diameter", f"the {self.name} curve is on the stress range: the "
                                        "line type needs its nominal diameter")
        bars = 2.0 if self.basis == "stress_chain" else 1.0
        return 1.0 / (bars * math.pi * diameter ** 2 / 4.0 * MPA)

    def cycles(self, s, mean_over_mbl: float = 0.0):
        """Cycles to failure at range ``s`` (in the basis' unit)."""
        return self.intercept(mean_over_mbl) * s ** (-self.m)

    def to_dict(self) -> dict:
        return {"name": self.name, "m": self.m, "a_d": self.a_d, "basis": self.basis,
                "mean_load_slope": self.mean_load_slope, "source": self.source,
                "verified": self.verified}


@functools.lru_cache(maxsize=1)
def catalog() -> dict:
    """``name -> Curve`` of the catalogue shipped with moorsolve (``fatigue_curves.csv``)."""
    rows = (line for line in (Path(__file__).with_name("fatigue_curves.csv")
                              .read_text().splitlines()) if not line.startswith("#"))
    out = {}
    for row in csv.DictReader(rows):
        out[row["name"]] = Curve(m=float(row["m"]), a_d=float(row["a_d"]), basis=row["basis"],
                                 mean_load_slope=float(row["mean_load_slope"]),
                                 name=row["name"], source=row["source"],
                                 verified=row["verified"])
    return out
