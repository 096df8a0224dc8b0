"""How a line type stretches: the ``stretch`` and ``stiffness_bounds`` keys of a line type.

Case-file forms::

    stretch: {model: hooke, ea: 5.6e8}              same as ``ea: 5.6e8``
    stretch: {model: baranov, n: 2.0e-4}            strain n sqrt(T), n in N^-1/2
    stretch: {model: table, strain: [0, 0.01, ...], tension: [0, 1.2e5, ...],
              interpolation: monotone_cubic}   # or linear; monotone_cubic by default

A table gives the tension at each strain (or the strain at each tension: the same rows),
both strictly increasing from the row (0, 0); when the first row is not (0, 0) it is
added. The solver interpolates the strain between rows by the monotone cubic of Fritsch
and Carlson (the default) or by straight lines (``interpolation: linear``, MoorDyn's
reading of a curve file: a MoorDyn import keeps it) and continues it linearly beyond the
last row (:mod:`moorsolve.physics.stretch`).

Offshore standards ask for a fibre rope to be analysed with an upper and a lower bound of
its stiffness. ``stiffness_bounds: {lower: SPEC, upper: SPEC}`` gives them, each SPEC an
axial stiffness (``"1.2e8 N"``), a stretch mapping as above, or
``{model: dynamic, alpha: 11.6, beta: 0.40}``: the dynamic stiffness
``EA = (alpha + beta L_m) MBL`` at the line's mean load ``L_m`` in % of its MBL (found by
:func:`moorsolve.studies.bounds.stiffness_bounds`). Catalogue fibre ropes come with both.

This module is data and validation only (no CasADi): the physics is in
:mod:`moorsolve.physics.stretch`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Optional, Union

from ..errors import CaseError
from .fields import (MAX_EA, MIN_EA, check_bounds, check_list, check_mapping, field_path,
                     quantity)
from .units import show_value

__all__ = ["StretchLaw", "DynamicStiffness", "StiffnessBounds", "parse_stretch",
           "parse_stiffness_bounds", "line_type_fields", "LINE_TYPE_KEYS", "MAX_TABLE_ROWS"]

#: How a table law may run between its rows (:mod:`moorsolve.physics.stretch`).
INTERPOLATIONS = ("monotone_cubic", "linear")
#: Rows a tension-strain table may have (after the (0, 0) row is added): the solver builds
#: one cubic piece per row, so a much finer table only slows it down.
MAX_TABLE_ROWS = 200
#: Largest strain accepted [-]: no rope stretches to twice its length and keeps holding.
MAX_STRAIN = 1.0
#: Baranov's n at which a rope would double its length under 1 N [N^-1/2]: a unit slip.
MAX_BARANOV_N = 1.0


@dataclass(frozen=True)
class StretchLaw:
    """A stretch law other than Hooke's (Hooke lines keep ``LineType.ea``).

    Attributes
    ----------
    model : {"baranov", "table"}
    n : float or None
        Baranov's coefficient [N^-1/2]: strain ``n sqrt(T)``.
    strain, tension : tuple of float
        The table's rows [-], [N], strictly increasing, the first (0, 0).
    interpolation : {"monotone_cubic", "linear"}
        How a table runs between its rows.
    """

    model: str
    n: Optional[float] = None
    strain: tuple = ()
    tension: tuple = ()
    interpolation: str = "monotone_cubic"

    @property
    def rows(self) -> int:
        return len(self.strain)

    def parameters(self) -> tuple:
        """The law's values as the solver takes them: ``(n,)``, or strains then tensions."""
        if self.model == "baranov":
            return (self.n,)
        return tuple(self.strain) + tuple(self.tension)

    def strain_at(self, T: float) -> float:
        """Strain at tension ``T`` [N] as the solver has it: Baranov's law, or the table's
        interpolant (:mod:`moorsolve.physics.stretch`, evaluated on floats)."""
        from ..physics.stretch import NumericLaw
        return float(NumericLaw(self.structure(), self.parameters()).strain(max(float(T),
                                                                                0.0)))

    def strains(self, T):
        """:meth:`strain_at` on an array of tensions ``T >= 0`` [N] (a numpy array)."""
        import numpy as np

        from ..physics.stretch import NumericLaw
        return np.asarray(NumericLaw(self.structure(), self.parameters()).strain(
            np.maximum(np.asarray(T, dtype=float), 0.0)), dtype=float)

    def structure(self):
        """The law's :class:`~moorsolve.physics.stretch.StretchModel` (which law, the
        table's rows and interpolation)."""
        from ..physics.stretch import BARANOV, TABLE, StretchModel
        if self.model == "baranov":
            return StretchModel(BARANOV)
        return StretchModel(TABLE, self.rows, self.interpolation)

    def secant_ea(self, T: Optional[float] = None) -> float:
        """``T / strain(T)`` [N]: the Hooke stiffness that stretches as much at ``T``
        (a table's last row when ``T`` is not given; Baranov needs ``T``)."""
        if T is None:
            if self.model == "baranov":
                raise ValueError("a Baranov law has no secant stiffness without a tension")
            return self.tension[-1] / self.strain[-1]
        return T / self.strain_at(T)

    def describe(self) -> str:
        if self.model == "baranov":
            return f"Baranov, n = {self.n:.4g} N^-1/2"
        how = " (linear between rows)" if self.interpolation == "linear" else ""
        return (f"table of {self.rows} rows{how} up to {self.strain[-1]:.4g} strain at "
                f"{self.tension[-1] / 1e3:.6g} kN")


@dataclass(frozen=True)
class DynamicStiffness:
    """Load-dependent dynamic stiffness ``EA = (alpha + beta L_m) MBL``, ``L_m`` the mean
    load in % of MBL (the form of fibre-rope data sheets and MoorDyn's ``EA_D`` column)."""

    alpha: float
    beta: float

    def ea(self, mbl: float, mean_load: float) -> float:
        """Dynamic EA [N] at mean load ``mean_load`` [N]."""
        return (self.alpha + self.beta * 100.0 * mean_load / mbl) * mbl


Spec = Union[float, StretchLaw, DynamicStiffness]


@dataclass(frozen=True)
class StiffnessBounds:
    """The lower and upper bound of a line's stiffness: each an EA [N], a
    :class:`StretchLaw` or a :class:`DynamicStiffness`."""

    lower: Spec
    upper: Spec
    source: Optional[str] = None


def _strictly_increasing(values, path, what):
    for i in range(1, len(values)):
        if not values[i] > values[i - 1]:
            raise CaseError(field_path(path, i),
                            f"{what} {values[i]:.6g} is not above the previous row's "
                            f"{values[i - 1]:.6g}; a table's {what}s must increase strictly "
                            f"(a monotonic tension-strain curve)")


def _table(m: dict, path: str) -> StretchLaw:
    spath, tpath = field_path(path, "strain"), field_path(path, "tension")
    strain_raw = check_list(m["strain"], spath, "a list of strains [-]")
    tension_raw = check_list(m["tension"], tpath, "a list of tensions [N]")
    if len(strain_raw) != len(tension_raw):
        raise CaseError(tpath, f"{len(tension_raw)} tensions for {len(strain_raw)} strains; "
                               "give one tension per strain")
    strain = [quantity(v, field_path(spath, i), "dimensionless", ge=0, le=MAX_STRAIN)
              for i, v in enumerate(strain_raw)]
    tension = [quantity(v, field_path(tpath, i), "force", ge=0)
               for i, v in enumerate(tension_raw)]
    if strain and (strain[0] == 0) != (tension[0] == 0):
        which = tpath if strain[0] == 0 else spath
        raise CaseError(field_path(which, 0),
                        f"the first row ({strain[0]:.6g}, {tension[0]:.6g} N) has zero "
                        f"{'strain' if strain[0] == 0 else 'tension'} but not zero "
                        f"{'tension' if strain[0] == 0 else 'strain'}; a rope without "
                        "tension is unstretched: start at (0, 0) or with both positive")
    if not strain or strain[0] > 0:
        strain, tension = [0.0] + strain, [0.0] + tension
    if len(strain) < 2:
        raise CaseError(spath, "a table needs at least one row besides (0, 0)")
    if len(strain) > MAX_TABLE_ROWS:
        raise CaseError(spath, f"{len(strain)} rows; a table may have at most "
                               f"{MAX_TABLE_ROWS} (the solver builds one cubic per row)")
    _strictly_increasing(strain, spath, "strain")
    _strictly_increasing(tension, tpath, "tension")
    secant = tension[-1] / strain[-1]
    check_bounds(None, secant, "force", tpath, ge=MIN_EA, le=MAX_EA)
    interpolation = m.get("interpolation", "monotone_cubic")
    if interpolation not in INTERPOLATIONS:
        raise CaseError(field_path(path, "interpolation"),
                        f"{show_value(interpolation)} is not a table interpolation; allowed: "
                        f"{', '.join(INTERPOLATIONS)} (monotone_cubic by default; linear is "
                        "MoorDyn's reading of a curve file)")
    return StretchLaw(model="table", strain=tuple(strain), tension=tuple(tension),
                      interpolation=interpolation)


def _ea(raw, path: str) -> float:
    ea = quantity(raw, path, "force", gt=0, le=MAX_EA)
    return check_bounds(raw, ea, "force", path, ge=MIN_EA)


def parse_stretch(raw, path: str, *, dynamic: bool = False):
    """Validate a ``stretch`` mapping: returns ``(ea, law)``, one of them None.

    ``{model: hooke, ea}`` gives ``(ea, None)``; Baranov and table give ``(None, law)``.
    With ``dynamic`` (a stiffness bound) ``{model: dynamic, alpha, beta}`` is accepted too
    and returned as ``(None, DynamicStiffness)``.
    """
    models = ("hooke", "baranov", "table") + (("dynamic",) if dynamic else ())
    if not isinstance(raw, Mapping):
        raise CaseError(path, f"{show_value(raw)} is not a mapping; give {{model: ...}} with "
                              f"model one of {', '.join(models)}")
    model = raw.get("model")
    if model not in models:
        what = ("required key 'model' is missing" if "model" not in raw
                else f"unknown model {show_value(model)}")
        raise CaseError(field_path(path, "model"),
                        f"{what}; allowed models: {', '.join(models)}")
    if model == "hooke":
        m = check_mapping(raw, path, section="stretch_hooke")
        return _ea(m["ea"], field_path(path, "ea")), None
    if model == "baranov":
        m = check_mapping(raw, path, section="stretch_baranov")
        npath = field_path(path, "n")
        n = quantity(m["n"], npath, "dimensionless", gt=0)
        if n >= MAX_BARANOV_N:
            raise CaseError(npath, f"{n:.6g} N^-1/2 would stretch a rope by {n:.3g} (x100 %) "
                                   f"under 1 N; n must be < {MAX_BARANOV_N:g} N^-1/2 (strain "
                                   "n sqrt(T) with T in N: a unit slip?)")
        return None, StretchLaw(model="baranov", n=n)
    if model == "dynamic":
        m = check_mapping(raw, path, section="stiffness_dynamic")
        alpha = quantity(m["alpha"], field_path(path, "alpha"), "dimensionless", gt=0)
        beta = quantity(m["beta"], field_path(path, "beta"), "dimensionless", ge=0)
        return None, DynamicStiffness(alpha=alpha, beta=beta)
    m = check_mapping(raw, path, section="stretch_table")
    return None, _table(m, path)


def _bound(raw, path: str) -> Spec:
    if isinstance(raw, Mapping):
        ea, law = parse_stretch(raw, path, dynamic=True)
        return ea if law is None else law
    return _ea(raw, path)


def parse_stiffness_bounds(raw, path: str) -> StiffnessBounds:
    """Validate ``stiffness_bounds: {lower: SPEC, upper: SPEC}`` (see the module notes)."""
    m = check_mapping(raw, path, section="stiffness_bounds")
    return StiffnessBounds(lower=_bound(m["lower"], field_path(path, "lower")),
                           upper=_bound(m["upper"], field_path(path, "upper")))


#: Line-type keys handled here, beside ``ea``.
LINE_TYPE_KEYS = ("stretch", "fibre", "min_tension", "stiffness_bounds")


def line_type_fields(m: dict, path: str, ea: Optional[float], *, catalogue=None) -> dict:
    """The stiffness fields of a line type: ``ea``, ``stretch``, ``fibre``, ``min_tension``
    and ``stiffness_bounds`` for :class:`~moorsolve.model.LineType`.

    ``m`` is the line type's mapping (its keys already checked), ``ea`` its ``ea`` key (or
    the catalogue's EA), ``catalogue`` the catalogue's
    :class:`~moorsolve.catalog.LineProperties` of a catalogue line. A catalogue fibre rope
    keeps the catalogue's bounds (quasi-static and dynamic stiffness) unless its stiffness
    is overridden; ``fibre`` defaults to a catalogue fibre rope or Baranov's law.
    """
    law = None
    catalogue_bounds = None
    if catalogue is not None and catalogue.dynamic_stiffness is not None:
        catalogue_bounds = StiffnessBounds(
            lower=catalogue.ea, upper=DynamicStiffness(*catalogue.dynamic_stiffness),
            source=catalogue.entry.stiffness_source)
    if m.get("stretch") is not None:
        spath = field_path(path, "stretch")
        if m.get("ea") is not None:
            raise CaseError(spath, "both ea and stretch are given; give one (stretch: "
                                   "{model: hooke, ea: ...} is the same as ea: ...)")
        ea, law = parse_stretch(m["stretch"], spath)
        catalogue_bounds = None
    elif m.get("ea") is not None:
        catalogue_bounds = None
    fibre = (catalogue is not None and catalogue.fibre) or (law is not None
                                                             and law.model == "baranov")
    if "fibre" in m:
        fibre = m["fibre"]
        if not isinstance(fibre, bool):
            raise CaseError(field_path(path, "fibre"), f"{show_value(fibre)} is not true or "
                                                       "false")
    min_tension = None
    if m.get("min_tension") is not None:
        min_tension = quantity(m["min_tension"], field_path(path, "min_tension"), "force", ge=0)
    bounds = catalogue_bounds
    if m.get("stiffness_bounds") is not None:
        bpath = field_path(path, "stiffness_bounds")
        if ea is None and law is None:
            raise CaseError(bpath, "an inextensible line has no stiffness to bound; give ea "
                                   "or stretch")
        bounds = parse_stiffness_bounds(m["stiffness_bounds"], bpath)
    return dict(ea=ea, stretch=law, fibre=fibre, min_tension=min_tension,
                stiffness_bounds=bounds)
