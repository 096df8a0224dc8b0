"""The bodies' motions in a sea state, in the frequency domain, about the static equilibrium.

Every free DOF of every body moves together:
``[-w^2 (M + A(w)) + i w (B(w) + B_ext) + K] X(w) = F(w)``, with ``K`` the total tangent
stiffness at the certified equilibrium (mooring, hydrostatics, springs, coupling through
shared lines: :func:`moorsolve.studies.stiffness.coupled_stiffness`), ``M`` each body's
rigid-body mass about its origin (``mass``, ``centre_of_gravity``, ``inertia``), ``A``,
``B`` and ``F`` its hydrodynamics (body frame; no hydrodynamic interaction between
bodies) and ``B_ext`` its extra damping.

The unknowns are the solver's own: global translations and the roll, pitch and yaw
angles, whose rows are generalised forces. The body-frame coefficients are carried to them
by ``J`` (body-frame velocity = ``J q'``: ``R^T`` on the translations, ``R^T E`` on the
angles, ``E`` the axes the angles turn about), ``M_q = J^T M J`` and ``F_q = J^T F``: at a
zero orientation ``J`` is the identity.

Three parts of the sea are simulated, each only where the scene calls for it: the mean
drift force (``2 int D S dw``, added to the static loads and re-solved, in place of a
body's wave-drift load model), the wave-frequency (WF) response, and the slow drift (LF)
by Newman's approximation with ``A`` at the lowest tabulated frequency and the extra damping
only (:mod:`.response`). Statistics per DOF and API RP 2SK's design offset (section 6.4.2:
the larger of ``mean + LF_sig + WF_max`` and ``mean + LF_max + WF_sig``, horizontal, along
the mean offset).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Optional

import numpy as np

from ..errors import CaseError, MoorsolveWarning
from ..model import DOFS
from ..model.build_network import rotation
from .hydro import BodyHydro
from .response import mean_drift_force, statistics
from .system import System, solved_pose as _pose
from .spectra import energy_band, spectrum_of

#: Spectrum energy a frequency range must hold before a warning says what it misses.
COVERAGE_WARNING = 0.99
#: Energy left outside the computed wave-frequency band on each side.
BAND_TAIL = 1e-6
ROTATIONS = (3, 4, 5)
#: A Result body's pose keys in DOF order.
POSE_KEYS = ("x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg")


@dataclasses.dataclass(frozen=True)
class BodyMotions:
    """One body's motions (rotations in degrees, translations in metres).

    Attributes
    ----------
    name : str
    dofs : tuple of str
        Its free DOFs (the others are held and do not move).
    mean : numpy.ndarray
        Mean pose of each free DOF [m, deg] (the static equilibrium with the mean drift).
    wf, lf : dict
        ``sigma``, ``significant``, ``tz_s``, ``max`` per free DOF [m, deg, s].
    design_offset_m : float or None
        API RP 2SK's horizontal design offset (None when neither surge nor sway is free).
    mean_drift : numpy.ndarray
        The mean drift force added to the static loads, global axes, moments about the
        body origin [N, N m] (zeros without mean drift tables).
    rao : numpy.ndarray
        Complex motion per unit wave amplitude, (len(omega), 6) [m/m, deg/m], zeros in held
        DOFs.
    """

    name: str
    dofs: tuple
    mean: np.ndarray
    wf: dict
    lf: dict
    design_offset_m: Optional[float]
    mean_drift: np.ndarray
    rao: np.ndarray
    heading_deg: float = 0.0

    def to_dict(self) -> dict:
        def stats(s):
            return {k: [float(v) for v in s[k]] for k in ("sigma", "significant", "tz_s", "max")}
        return {"name": self.name, "dofs": list(self.dofs),
                "units": ["deg" if DOFS.index(d) in ROTATIONS else "m" for d in self.dofs],
                "mean": [float(v) for v in self.mean], "wf": stats(self.wf),
                "lf": stats(self.lf), "design_offset_m": self.design_offset_m,
                "mean_drift": [float(v) for v in self.mean_drift],
                "wave_heading_deg": self.heading_deg}


@dataclasses.dataclass(frozen=True)
class Motions:
    """The motions of a scene's bodies in its sea state.

    ``sea`` says which parts of the sea were simulated (``simulated``: any of
    ``mean_drift``, ``wave_frequency``, ``slow_drift``; empty, with the ``reason``, when
    the answer is the static one). ``result`` is the static equilibrium the motions are
    about (with the mean drift force when simulated).
    """

    sea: dict
    result: object
    omega: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    bodies: tuple = ()
    spectrum: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    #: Each moving body's hydrodynamics as used (tables; Capytaine's computed ones).
    hydrodynamics: dict = dataclasses.field(default_factory=dict)
    #: The free DOFs of the coupled system, ``"body.dof"`` (the solver's unknowns: global
    #: translations [m] and the roll, pitch, yaw angles [rad]).
    labels: tuple = ()
    #: Wave-frequency response per unit wave amplitude over ``labels``, (len(omega), n)
    #: complex [m/m, rad/m].
    wf_response: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 0)))
    #: Slow-drift difference frequencies [rad/s] and the response cross-spectra over
    #: ``labels`` (len(lf_omega), n, n) [m^2 s/rad, ...]; None without slow drift.
    lf_omega: Optional[np.ndarray] = None
    lf_cross: Optional[np.ndarray] = None

    @property
    def static(self) -> bool:
        return not self.sea.get("simulated")

    def body(self, name: str) -> BodyMotions:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def to_dict(self) -> dict:
        return {"sea": dict(self.sea), "motions": {
            "bodies": [b.to_dict() for b in self.bodies],
            "omega": [float(w) for w in self.omega],
            "rao": {b.name: {"re": b.rao.real.tolist(), "im": b.rao.imag.tolist()}
                    for b in self.bodies}}}


# ---- the scene's parts ------------------------------------------------------------------


def _body_paths(case) -> list:
    if case.form == "legs":
        return [("body", case.body)] if case.body is not None else []
    return [(f"bodies[{i}]", b) for i, b in enumerate(case.bodies)]


def _sea_description(waves) -> dict:
    spec = waves.spectrum
    out = {"hs_m": waves.hs, "tp_s": waves.tp, "toward_deg": waves.toward_deg,
           "duration_s": waves.duration, "spectrum": spec.model}
    if spec.model == "jonswap":
        from .spectra import gamma_dnv
        out["gamma"] = spec.gamma if spec.gamma is not None else gamma_dnv(waves.hs, waves.tp)
    return out


def _static(result, reason: str, sea=None) -> Motions:
    return Motions(sea={**(sea or {}), "simulated": [], "reason": reason}, result=result)


def _moving_bodies(case) -> list:
    """``(path, body)`` of the bodies with hydrodynamics; a free body without them in the
    sea state is refused by name."""
    moving, missing = [], []
    for path, body in _body_paths(case):
        if getattr(body, "hydrodynamics", None) is not None:
            if body.free and body.mass is None:
                raise CaseError(f"{path}.mass", f"body {body.name!r} moves in the sea state: "
                                                "its motions need its mass [kg]")
            if any(DOFS.index(d) in ROTATIONS for d in body.free) and body.inertia is None:
                raise CaseError(f"{path}.inertia",
                                f"body {body.name!r} is free to rotate in the sea state: its "
                                "motions need its moments of inertia [Ixx, Iyy, Izz] [kg m^2]")
            moving.append((path, body))
        elif body.free:
            missing.append((path, body))
    floating = [(p, b) for p, b in missing if b.buoyant]
    if floating or (missing and moving):
        path, body = (floating or missing)[0]
        where = (f"{path}.hydrodynamics" if case.form == "network"
                 else "body (give the scene in the network form, bodies: [...], to add "
                      "hydrodynamics)")
        raise CaseError(where, f"body {body.name!r} floats free in a sea state "
                               "(environment.waves.tp) but has no hydrodynamics to move with: "
                               "give them (source: table or wamit), hold the body, or drop "
                               "tp for the static answer")
    return moving


# ---- the mean drift re-solve --------------------------------------------------------------


def _with_mean_drift(case, result, moving, hydros, grid, density, solver, tol):
    """The static equilibrium with each body's mean drift force added to its loads (its
    wave-drift load model removed), re-solved until the headings settle."""
    from .. import solve as static_solve

    waves = case.environment.waves
    S = density(grid)
    drifted = [(p, b) for p, b in moving if hydros[b.name].has_drift]
    if not drifted:
        return result, {}
    forces = {}
    for _ in range(6):
        bodies = list(case.bodies)
        for path, body in drifted:
            pose = _pose(result, body.name)
            beta = waves.toward_deg - math.degrees(pose[5])
            Fb = mean_drift_force(grid, S, hydros[body.name].drift(grid, beta))
            R = rotation(*pose[3:])
            F = np.concatenate([R @ Fb[:3], R @ Fb[3:]])
            forces[body.name] = F
            own = np.zeros(6) if body.loads.force is None else (
                np.array(body.loads.force, dtype=float) if len(body.loads.force) == 6 else
                np.array([body.loads.force[0], body.loads.force[1], 0, 0, 0,
                          body.loads.force[2]], dtype=float))
            loads = dataclasses.replace(body.loads, wave_drift=None,
                                        force=tuple(float(v) for v in own + F))
            bodies[case.bodies.index(body)] = dataclasses.replace(body, loads=loads)
        drift_case = dataclasses.replace(case, bodies=tuple(bodies))
        new = static_solve(drift_case, solver=solver, tol=tol)
        turned = max(abs(_pose(new, b.name)[5] - _pose(result, b.name)[5]) for _, b in drifted)
        result = new
        if math.degrees(turned) < 1e-3:
            break
    return result, forces


# ---- the motions --------------------------------------------------------------------------


def _grid(hydros, waves, density, n_omega, omega):
    """``(omega, covered, (lo, hi), band)``: the wave frequencies (half over the tables'
    range, half over the part of it where the spectrum's energy is, unless given), the
    fraction of m0 the tables' range holds, that range, and the spectrum's energy band."""
    lo = max(h.omega[0] for h in hydros.values())
    hi = min(h.omega[-1] for h in hydros.values())
    band = energy_band(density, waves.tp or _table_tp(waves), BAND_TAIL)
    fine = np.linspace(min(lo, band[0]), max(hi, band[1]), 20001)
    Sf = density(fine)
    total = np.trapezoid(Sf, fine)
    inside = (fine >= lo) & (fine <= hi)
    covered = float(np.trapezoid(Sf[inside], fine[inside]) / total) if total > 0 else 1.0
    if omega is None:
        a, b = max(lo, band[0]), min(hi, band[1])
        if not b > a:
            raise CaseError("environment.waves", f"the spectrum's energy lies outside the "
                                                 f"hydrodynamics' frequencies [{lo:.4g}, "
                                                 f"{hi:.4g}] rad/s: 0 % of m0 covered")
        half = max(n_omega // 2, 2)
        omega = np.unique(np.concatenate([np.linspace(lo, hi, half),
                                          np.linspace(a, b, max(n_omega - half, 2))]))
    else:
        omega = np.asarray(omega, dtype=float)
        if omega.ndim != 1 or omega.size < 2 or np.any(np.diff(omega) <= 0) \
                or omega[0] < lo - 1e-12 or omega[-1] > hi + 1e-12:
            raise ValueError(f"omega: give increasing frequencies within the hydrodynamics' "
                             f"range [{lo:.4g}, {hi:.4g}] rad/s")
    return omega, covered, (lo, hi), band


def _refined(grid, system, lo, hi) -> np.ndarray:
    """``grid`` with points added round each lightly damped wave-frequency resonance (80
    half-bandwidths either side), so the trapezoidal rule sees its peak."""
    extra = [grid]
    for wn, zeta in system.resonances(lo, hi):
        half = wn * max(zeta, 1e-4)
        extra.append(np.clip(wn + half * np.linspace(-80, 80, 321), lo, hi))
    return np.unique(np.concatenate(extra))


def _table_tp(waves) -> float:
    t = np.asarray(waves.spectrum.table)
    return 2 * math.pi / t[np.argmax(t[:, 1]), 0]


def motions(result_or_case, *, n_omega: int = 400, omega=None, solver: str = "ipopt",
            tol=None) -> Motions:
    """The motions of every body in the scene's sea state.

    Parameters
    ----------
    result_or_case : Result or Case
        A certified static equilibrium, or a case (solved first).
    n_omega : int
        Wave-frequency points over the part of the hydrodynamics' range that holds the
        spectrum's energy.
    omega : array, optional
        The wave frequencies [rad/s] instead (within the hydrodynamics' range).
    solver, tol
        For the static solves (the case, and the re-solve with the mean drift force).

    Returns
    -------
    Motions
        Static (``sea["simulated"]`` empty, with the reason) without a sea state or
        without hydrodynamics in the scene.

    Raises
    ------
    CaseError
        A free body in a sea state without hydrodynamics, a heading the tables do not
        cover, an undamped slow-drift mode, a body without mass or inertia.

    Warns
    -----
    MoorsolveWarning
        When the hydrodynamics' frequencies hold less than 99 % of the spectrum's m0.
    """
    from ..studies.stiffness import as_result, coupled_stiffness

    result = as_result(result_or_case, solver)
    case = result.case
    waves = case.environment.waves
    if waves is None:
        return _static(result, "no waves (environment.waves)")
    if not waves.sea_state:
        return _static(result, "the waves have no period (environment.waves.tp): hs feeds "
                               "the wave-drift load models only")
    sea = _sea_description(waves)
    moving = _moving_bodies(case)
    if not moving:
        return _static(result, "no body has hydrodynamics (bodies[i].hydrodynamics) to move "
                               "in the sea state", sea)
    tables = {b.name: _tables(b, p, case, result) for p, b in moving}
    hydros = {b.name: BodyHydro(tables[b.name], f"{p}.hydrodynamics") for p, b in moving}
    density = spectrum_of(waves)
    given = omega is not None
    grid, covered, (lo, hi), band = _grid(hydros, waves, density, n_omega, omega)
    if covered < COVERAGE_WARNING:
        warnings.warn(MoorsolveWarning(
            f"the hydrodynamics' frequencies [{lo:.4g}, {hi:.4g}] rad/s hold {covered:.1%} of "
            "the spectrum's m0: the motions miss the rest (give the tables over a wider "
            "range)"), stacklevel=2)
    result, forces = _with_mean_drift(case, result, moving, hydros, grid, density, solver, tol)
    K, labels = coupled_stiffness(result)
    system = System(moving, hydros, result, K, labels, waves.toward_deg)
    if not given:
        grid = _refined(grid, system, lo, hi)
    out = _respond(case, result, moving, system, grid, density, forces,
                   {**sea, "coverage": covered, "slow_drift_below_rad_s": band[0]})
    return dataclasses.replace(out, hydrodynamics=tables)


def _tables(body, path, case, result):
    """A body's hydrodynamics as tables: given, or computed with Capytaine at its draft."""
    h = body.hydrodynamics
    if getattr(h, "source", "") != "capytaine":
        return h
    from .bem import capytaine_hydrodynamics
    z = result.body_named(body.name)["z_m"] - case.environment.water_level
    return capytaine_hydrodynamics(body, h, case.environment, z, f"{path}.hydrodynamics")


def _respond(case, result, moving, system, grid, density, forces, sea) -> Motions:
    waves = case.environment.waves
    X = system.response(grid)
    S = density(grid)
    wf_spec = np.abs(X) ** 2 * S[:, None]
    lf_mu, lf_cross = None, None
    if system.has_drift:
        lf_mu, lf_cross = system.slow_drift(grid, density, sea["slow_drift_below_rad_s"])
        lf_spec = np.real(np.einsum("mii->mi", lf_cross))
    duration = waves.duration
    bodies = []
    for path, body in moving:
        idx, cols, _ = system.slots[body.name]
        scale = np.array([math.degrees(1.0) if c in ROTATIONS else 1.0 for c in cols])
        wf = statistics(grid, wf_spec[:, idx] * scale ** 2, duration)
        lf = (statistics(lf_mu, lf_spec[:, idx] * scale ** 2, duration) if lf_mu is not None
              else statistics(np.array([0.0, 1.0]), np.zeros((2, len(idx))), duration))
        b = result.body_named(body.name)
        mean = np.array([b[POSE_KEYS[c]] for c in cols])
        rao = np.zeros((grid.size, 6), dtype=complex)
        rao[:, cols] = X[:, idx] * scale
        design = _design_offset(b, idx, cols, X, S, grid, lf_mu, lf_cross, duration)
        bodies.append(BodyMotions(
            name=body.name, dofs=tuple(body.free), mean=mean, wf=wf, lf=lf,
            design_offset_m=design, mean_drift=forces.get(body.name, np.zeros(6)), rao=rao,
            heading_deg=waves.toward_deg - b["yaw_deg"]))
    simulated = (["mean_drift"] if forces else []) + ["wave_frequency"] + (
        ["slow_drift"] if lf_mu is not None else [])
    return Motions(sea={**sea, "simulated": simulated}, result=result, omega=grid,
                   bodies=tuple(bodies), spectrum=S, labels=tuple(system.labels),
                   wf_response=X, lf_omega=lf_mu, lf_cross=lf_cross)


def _design_offset(b, idx, cols, X, S, grid, lf_mu, lf_cross, duration):
    """API RP 2SK's design offset [m] along the mean horizontal offset (or the waves'
    heading when there is none)."""
    has = [c for c in (0, 1) if c in cols]
    if not has:
        return None
    off = np.array([b["offset"]["x_m"], b["offset"]["y_m"]])
    mean = float(np.hypot(*off))
    if mean > 1e-9:
        u = off / mean
    else:
        u = np.array([1.0, 0.0])
    weights = np.zeros(len(idx))
    for c in has:
        weights[cols.index(c)] = u[c]
    xu = X[:, idx] @ weights
    wf = statistics(grid, np.abs(xu) ** 2 * S, duration)
    if lf_cross is not None:
        sub = lf_cross[:, idx][:, :, idx]
        lf_s = np.real(np.einsum("i,mij,j->m", weights, sub, weights))
        lf = statistics(lf_mu, lf_s, duration)
    else:
        lf = {"sigma": np.zeros(1), "significant": np.zeros(1), "max": np.zeros(1)}
    a = mean + lf["significant"][0] + wf["max"][0]
    c = mean + lf["max"][0] + wf["significant"][0]
    return float(max(a, c))
