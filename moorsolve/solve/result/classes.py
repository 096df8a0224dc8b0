"""The outcome of a solve: the equilibrium, every leg's state and the certificate."""

from __future__ import annotations

import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Optional

import numpy as np


class _Deferred:
    """A value made by ``make()`` on first use, once, under a lock (many threads may ask)."""

    __slots__ = ("_make", "_value", "_lock")

    def __init__(self, make):
        self._make, self._value, self._lock = make, None, threading.Lock()

    def value(self):
        if self._make is not None:
            with self._lock:
                if self._make is not None:
                    self._value, self._make = self._make(), None
        return self._value


class LazyProfile(Mapping):
    """A line's profile (``x_m``, ``y_m``, ``z_m``, ``tension_N``, ...), drawn from the
    solved end forces on first access: the same numbers as drawing it at once, paid for
    only by a caller that reads it (a plot, a report, ``to_dict()``)."""

    __slots__ = ("_data",)

    def __init__(self, draw):
        self._data = _Deferred(draw)

    def __getitem__(self, key):
        return self._data.value()[key]

    def __iter__(self):
        return iter(self._data.value())

    def __len__(self) -> int:
        return len(self._data.value())

    def __repr__(self) -> str:
        return f"LazyProfile({sorted(self)})"

    def as_dict(self) -> dict:
        """The drawn profile itself (drawn now if it was not): read it, do not change it."""
        return self._data.value()


class LegList(Sequence):
    """The legs of a Result, made from the solved arrays on first access (all at once)."""

    __slots__ = ("_legs",)

    def __init__(self, make):
        self._legs = _Deferred(lambda: list(make()))

    def __getitem__(self, index):
        return self._legs.value()[index]

    def __len__(self) -> int:
        return len(self._legs.value())

    def __eq__(self, other) -> bool:
        return isinstance(other, Sequence) and list(self) == list(other)

    def __repr__(self) -> str:
        return repr(self._legs.value())


@dataclass(frozen=True)
class Certificate:
    """Evidence that the forces balance, recomputed from the solution itself.

    Attributes
    ----------
    force_N : float
        Largest unbalanced force [N]: on a free body degree of freedom, on a free point, or
        at a line end, where a line's span mismatch is converted to the force that would
        close it.
    moment_Nm : float
        Largest unbalanced moment [N m] about a free rotation axis of any body (0 when no
        rotation is solved).
    relative : float
        ``force_N`` divided by the largest line tension.
    tolerance : float
        The relative residual the solve had to reach.
    status : str
        IPOPT's return status of the last solve.
    iterations : int
        IPOPT iterations over all stages (rest state, load steps), plus Newton polish steps.
    solve_time_s : float
        Wall time of the solve, building excluded [s].
    penetration_m : float or None
        Largest penetration of a contact beyond what its reaction compresses it [m] (None
        in a scene without contacts).
    complementarity_N : float or None
        Largest complementarity residual of a contact: a reaction acting across an open gap,
        or a pulling one [N] (None without contacts).
    """

    force_N: float
    moment_Nm: float
    relative: float
    tolerance: float
    status: str
    iterations: int
    solve_time_s: float
    penetration_m: Optional[float] = None
    complementarity_N: Optional[float] = None

    @property
    def certified(self) -> bool:
        return bool(np.isfinite(self.relative) and self.relative <= self.tolerance)


@dataclass(frozen=True)
class LegResult:
    """One leg at equilibrium. Forces [N], lengths [m], angles [deg]; the JSON of ``solve --json`` names them.

    A multi-segment leg adds ``segments`` (per segment, from the anchor: type, length, top
    and bottom tension, horizontal tension, grounded length, largest tension, T/MBL)
    and ``joints`` (per joint: position, height above the seabed, seabed reaction, clump
    weight); ``mbl_N`` is then the weakest segment's and ``t_over_mbl`` the largest
    segment's. ``t_over_mbl`` is the largest tension over the MBL, a property of the line
    alone; the utilisation against a standard's allowable tension is the check's
    (:func:`moorsolve.checks.run_checks`). ``fairlead_force`` and ``anchor_force`` are the forces [N] the
    line exerts on its ends B and A, global ``(Fx, Fy, Fz)``: in the line's vertical plane
    for an analytic line, with a sideways part for a line in a current.
    ``floating_length_m`` is the unstretched length floating on the free surface (a buoyant
    line, the analogue of ``grounded_length_m``) and ``touchup_from_anchor_m`` the horizontal
    distance from end A at which the line first reaches the surface (0 when nothing floats).
    ``fibre_grounded_m`` is the length of fibre rope lying on the seabed [m] (None for a
    line without fibre rope).
    """

    name: str
    fairlead_tension_N: float
    horizontal_tension_N: float
    fairlead_vertical_N: float
    anchor_tension_N: float
    anchor_horizontal_N: float
    anchor_vertical_N: float
    grounded_length_m: float
    touchdown_from_anchor_m: float
    uplift: bool
    slack: bool
    uplift_angle_deg: float
    fairlead_angle_deg: float
    anchor: tuple
    fairlead: tuple
    touchdown_point: Optional[tuple]
    mbl_N: Optional[float]
    profile: dict = field(repr=False)
    segments: tuple = ()
    joints: tuple = ()
    fairlead_force: Optional[tuple] = None
    anchor_force: Optional[tuple] = None
    fibre_grounded_m: Optional[float] = None
    floating_length_m: float = 0.0
    touchup_from_anchor_m: float = 0.0
    #: On a bathymetry grid: the line's seabed plane ``(z0, dz/dx, dz/dy)``, height
    #: ``z0 + gx x + gy y`` (:mod:`.bathymetry`), and how far the grid's surface departs
    #: from the line where it matters [m] (None on a plane seabed).
    seabed_plane: Optional[tuple] = None
    seabed_deviation_m: Optional[float] = None

    def __repr__(self) -> str:
        from ...report.notebook import leg_repr
        return leg_repr(self)

    @property
    def t_over_mbl(self) -> Optional[float]:
        """Largest tension over the minimum breaking load (None without an MBL); 1 is the
        breaking load, not a standard's limit (that is the check's ``utilisation``)."""
        if self.segments:
            values = [s["t_over_mbl"] for s in self.segments if s["t_over_mbl"] is not None]
            return max(values) if values else None
        if not self.mbl_N:
            return None
        return max(self.fairlead_tension_N, self.anchor_tension_N) / self.mbl_N

    @property
    def utilisation(self) -> Optional[float]:
        """Deprecated name of :attr:`t_over_mbl` (``utilisation`` is the check's design
        tension over the standard's allowable tension)."""
        import warnings
        warnings.warn("LegResult.utilisation is renamed t_over_mbl (largest tension over "
                      "MBL); the utilisation against a standard is moorsolve check's",
                      DeprecationWarning, stacklevel=2)
        return self.t_over_mbl

    def to_dict(self, profile: bool = True) -> dict:
        d = {
            "name": self.name,
            "fairlead_tension_N": self.fairlead_tension_N,
            "horizontal_tension_N": self.horizontal_tension_N,
            "fairlead_vertical_N": self.fairlead_vertical_N,
            "anchor_tension_N": self.anchor_tension_N,
            "anchor_horizontal_N": self.anchor_horizontal_N,
            "anchor_vertical_N": self.anchor_vertical_N,
            "grounded_length_m": self.grounded_length_m,
            "touchdown_from_anchor_m": self.touchdown_from_anchor_m,
            "floating_length_m": self.floating_length_m,
            "touchup_from_anchor_m": self.touchup_from_anchor_m,
            "uplift": self.uplift,
            "slack": self.slack,
            "uplift_angle_deg": self.uplift_angle_deg,
            "fairlead_angle_deg": self.fairlead_angle_deg,
            "anchor_m": list(self.anchor),
            "fairlead_m": list(self.fairlead),
            "touchdown_point_m": None if self.touchdown_point is None
            else list(self.touchdown_point),
            "mbl_N": self.mbl_N,
            "t_over_mbl": self.t_over_mbl,
        }
        if self.fairlead_force is not None:
            d["fairlead_force_N"] = [float(v) for v in self.fairlead_force]
        if self.anchor_force is not None:
            d["anchor_force_N"] = [float(v) for v in self.anchor_force]
        if self.seabed_plane is not None:
            d["seabed_plane"] = [float(v) for v in self.seabed_plane]
        if self.seabed_deviation_m is not None:
            d["seabed_deviation_m"] = self.seabed_deviation_m
        if self.fibre_grounded_m is not None:
            d["fibre_grounded_length_m"] = self.fibre_grounded_m
        if self.segments:
            d["segments"] = [dict(s) for s in self.segments]
            d["joints"] = [dict(j) for j in self.joints]
        if profile:
            d["profile"] = {k: (v.tolist() if isinstance(v, np.ndarray) else v)
                            for k, v in self.profile.items()}
        return d


#: The vector fields of a leg's dict and their columns in :meth:`Result.to_frame`.
_FRAME_VECTORS = {
    **{f"{stem}_{unit}": tuple(f"{stem}_{axis}_{unit}" for axis in "xyz")
       for stem, unit in (("anchor", "m"), ("fairlead", "m"), ("touchdown_point", "m"),
                          ("fairlead_force", "N"), ("anchor_force", "N"))},
    "seabed_plane": ("seabed_plane_z0_m", "seabed_plane_dz_dx", "seabed_plane_dz_dy"),
}


@dataclass(frozen=True)
class Stability:
    """Static stability of an equilibrium, from the total tangent stiffness.

    Attributes
    ----------
    stable : bool
        Every eigenvalue of the condensed stiffness ``K = -dQ/dq`` of the free body DOFs has
        a positive real part (zero ones decided by finite perturbations).
    min_eigenvalue : float
        The smallest real part [mixed units: N/m and N m/rad].
    unstable_dofs : tuple of str
        ``"body.dof"`` most involved in each unstable mode.
    neutral_dofs : tuple of str
        DOFs with a zero eigenvalue whose restoring force at finite perturbation is zero
        (indifferent: nothing restrains or loads them); they keep their given value.
    eigenvalues : tuple of complex
    dofs : tuple of str
    """

    stable: bool
    min_eigenvalue: float
    unstable_dofs: tuple = ()
    neutral_dofs: tuple = ()
    eigenvalues: tuple = ()
    dofs: tuple = ()

    def to_dict(self) -> dict:
        return {"stable": self.stable, "min_eigenvalue": self.min_eigenvalue,
                "unstable_dofs": list(self.unstable_dofs),
                "neutral_dofs": list(self.neutral_dofs)}


class DeferredStability(Stability):
    """A :class:`Stability` decided stable by the compiled kernel's test, whose
    eigenvalues (of the homogenised stiffness ``Kh``) are computed when first read."""

    def __init__(self, Kh, dofs):
        for name, value in (("stable", True), ("unstable_dofs", ()), ("neutral_dofs", ()),
                            ("dofs", tuple(dofs))):
            object.__setattr__(self, name, value)
        object.__setattr__(self, "_values", _Deferred(
            lambda: np.linalg.eigvals(Kh).astype(complex)))

    @property
    def eigenvalues(self) -> tuple:
        return tuple(self._values.value().tolist())

    @property
    def min_eigenvalue(self) -> float:
        return float(self._values.value().real.min())


@dataclass(frozen=True)
class Result:
    """A certified equilibrium.

    Attributes
    ----------
    converged : bool
    solver : str
    certificate : Certificate
    effects : list of str
        The physical effects the problem simulated.
    body : dict or None
        ``x_m``, ``y_m`` displacement of the body origin and ``yaw_deg``; None without body
        (the ``legs:`` form; a network case with one body also fills it).
    legs : list of LegResult
        Every line (end A as ``anchor_*``, end B as ``fairlead_*``); also ``lines``.
    loads : dict
        Each simulated body load, ``name -> [Fx N, Fy N, Mz N m]`` in the global frame.
    case_name : str
    state : numpy.ndarray
        The solution vector (scaled), for warm starts.
    case : Case or None
        The case solved, for the study functions (:mod:`moorsolve.studies`).
    """

    converged: bool
    solver: str
    certificate: Certificate
    effects: list
    body: Optional[dict]
    legs: list
    loads: dict
    case_name: str = ""
    state: Optional[np.ndarray] = field(default=None, repr=False, compare=False)
    notes: tuple = ()
    case: Optional[object] = field(default=None, repr=False, compare=False)
    #: Per body: name, pose (``x_m`` ... ``yaw_deg``, absolute in the scene) and the
    #: displacement from its case pose (``offset``).
    bodies: tuple = ()
    #: Per free point: name and position ``x_m``, ``y_m``, ``z_m``, and its seabed reaction.
    points: tuple = ()
    stability: Optional[Stability] = None
    form: str = "legs"
    #: What an engineer must not miss (wall compression, line floating, an end in air):
    #: dicts ``{"code", "leg", "message"}`` from :func:`moorsolve.audit.result_warnings`.
    warnings: tuple = ()
    #: Per fender: in_contact, compression_m, reaction_N, friction_N, stick, slip_m,
    #: energy_J, utilisation (compression over rated deflection), overloaded (past it),
    #: height_m (full compression), hull_bears (fully compressed: the hull bears on the
    #: wall), hull_reaction_N, hull_force_N, hull_gap_m, force_N, contact_point_m
    #: (:mod:`.contact.results`).
    fenders: tuple = ()
    #: Per pile guide: in_contact, reaction_N, force_N, offset_m, height_m, on_pile,
    #: pile_moment_Nm and its pads.
    guides: tuple = ()
    #: Per hawser (weightless one-segment line): tension_N, slack, t_over_mbl, length_m.
    hawsers: tuple = ()

    def fender(self, name: str) -> dict:
        for f in self.fenders:
            if f["name"] == name:
                return f
        raise KeyError(name)

    def guide(self, name: str) -> dict:
        for g in self.guides:
            if g["name"] == name:
                return g
        raise KeyError(name)

    @property
    def lines(self) -> list:
        return self.legs

    def body_named(self, name: str) -> dict:
        for b in self.bodies:
            if b["name"] == name:
                return b
        raise KeyError(name)

    def __repr__(self) -> str:
        from ...report.notebook import result_repr
        return result_repr(self)

    def _repr_html_(self) -> str:
        from ...report.notebook import result_html
        return result_html(self)

    @property
    def iterations(self) -> int:
        return self.certificate.iterations

    @property
    def solve_time_s(self) -> float:
        return self.certificate.solve_time_s

    def leg(self, name: str) -> LegResult:
        for leg in self.legs:
            if leg.name == name:
                return leg
        raise KeyError(name)

    def to_frame(self):
        """The lines as a pandas DataFrame: one row per line, indexed by name, SI columns.

        The columns are the scalar fields of ``to_dict()["legs"]`` (forces [N], lengths [m],
        angles [deg], ``t_over_mbl``); a vector field ``<name>_m`` or ``<name>_N`` becomes
        one column per component (``anchor_x_m``, ``fairlead_force_z_N``). Profiles,
        segments and joints stay in :meth:`to_dict`.
        """
        import pandas as pd
        rows = []
        for leg in self.legs:
            row = {}
            for key, value in leg.to_dict(profile=False).items():
                if key in ("segments", "joints"):
                    continue
                columns = _FRAME_VECTORS.get(key)
                if columns is None:
                    row[key] = value
                else:               # a vector, or None where the line has none (NaN)
                    values = [np.nan] * 3 if value is None else value
                    row.update(zip(columns, values))
            rows.append(row)
        return pd.DataFrame(rows).set_index("name")

    def to_dict(self, profiles: bool = True) -> dict:
        """The result as JSON-ready data (the ``solve --json`` document)."""
        c = self.certificate
        out = {
            "converged": self.converged,
            "solver": self.solver,
            "iterations": c.iterations,
            "solve_time_s": c.solve_time_s,
            "residual": {"force_N": c.force_N, "moment_Nm": c.moment_Nm,
                         "relative": c.relative, "tolerance": c.tolerance,
                         "status": c.status},
            "effects": list(self.effects),
            "body": None if self.body is None else dict(self.body),
            "legs": [leg.to_dict(profile=profiles) for leg in self.legs],
            "loads": {k: list(v) for k, v in self.loads.items()},
            "notes": list(self.notes),
            # Always present, with or without profiles: empty means none.
            "warnings": [dict(w) for w in self.warnings],
            "case": self.case_name,
        }
        if self.form == "network" or len(self.bodies) > 1 or self.points:
            out["bodies"] = [dict(b) for b in self.bodies]
            out["points"] = [dict(pt) for pt in self.points]
        if c.penetration_m is not None:
            out["residual"]["penetration_m"] = c.penetration_m
            out["residual"]["complementarity_N"] = c.complementarity_N
        for key in ("fenders", "guides", "hawsers"):
            if getattr(self, key):
                out[key] = [dict(item) for item in getattr(self, key)]
        if self.stability is not None:
            out["stability"] = self.stability.to_dict()
        return out
