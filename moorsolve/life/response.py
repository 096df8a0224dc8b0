"""Line-end tension spectra over a scatter diagram, with the RAOs computed once.

The bodies' wave-frequency motions per metre of wave amplitude depend on the wave heading
only (the equilibrium, the stiffness and the hydrodynamics are the case's), so they are
solved once per distinct heading of the scatter diagram, on one frequency grid covering
every sea state's spectrum. Each line end on a body moves with it,
``u = x + (dR/dtheta R^T r) dtheta`` (``r`` the arm from the body origin, global); an end
on a fixed point does not move. Each line's lumped-mass model is built once; its drag is
linearised on each sea state's own response (the spectral linearisation of
:mod:`moorsolve.dynamics.line_dynamics`, all sea states solved together by
:func:`moorsolve.dynamics.line_batch.spectral_tensions`), so the tension transfer function
is the sea state's.

Simulated: the wave-frequency tension about the case's static equilibrium. Not simulated
(said in the result): the slow-drift (low-frequency) tension and each sea state's own mean
drift offset.
"""

from __future__ import annotations


import numpy as np

import warnings

from ..errors import CaseError, MoorsolveWarning
from ..model import DOFS
from ..model.build_network import rotation

__all__ = ["SeaStateTensions", "scatter_tensions", "end_motion_map"]

#: Frequencies of the common grid, and elements per line: on the dock benchmark's 12 lines
#: and 50 sea states the damage is within 1.1 % of 120 frequencies and 60 elements.
N_OMEGA = 50
N_ELEMENTS = 24
#: A sea state whose spectrum the hydrodynamics' frequencies cover less than this is
#: warned of.
COVERAGE_WARNING = 0.99
#: Energy of each sea state's spectrum left outside the grid, each side.
BAND_TAIL = 1e-5


def end_motion_map(pose_rad, point) -> np.ndarray:
    """``(3, 6)``: the global displacement of ``point`` [m, global] on a body at
    ``pose_rad`` per (x, y, z, roll, pitch, yaw) increment (central differences of the
    rotation, step 1e-6 rad: error ~1e-12)."""
    pose = np.asarray(pose_rad, float)
    arm = np.asarray(point, float) - pose[:3]
    R = rotation(*pose[3:])
    local = R.T @ arm
    out = np.zeros((3, 6))
    out[:, :3] = np.eye(3)
    h = 1e-6
    for k in range(3):
        up, down = pose[3:].copy(), pose[3:].copy()
        up[k] += h
        down[k] -= h
        out[:, 3 + k] = (rotation(*up) - rotation(*down)) @ local / (2 * h)
    return out


class SeaStateTensions:
    """Per sea state and line end, the tension spectrum on the common grid.

    Attributes
    ----------
    omega : ndarray (n_omega,)
        [rad/s].
    lines : list of str
    spectra : ndarray (n_states, n_lines, 2, n_omega)
        Tension spectra [N^2 s/rad], ends A (anchor) and B (fairlead).
    wave_spectra : ndarray (n_states, n_omega)
    coverage : ndarray (n_states,)
        Fraction of each sea state's m0 inside the grid.
    mean_tension : ndarray (n_lines, 2)
        Static tension at each end [N].
    """

    def __init__(self, omega, lines, spectra, wave_spectra, coverage, mean_tension,
                 iterations):
        self.omega = omega
        self.lines = lines
        self.spectra = spectra
        self.wave_spectra = wave_spectra
        self.coverage = coverage
        self.mean_tension = mean_tension
        self.iterations = iterations


def _density(spec, hs, tp):
    from ..dynamics.spectra import jonswap, pierson_moskowitz
    if spec.model == "pierson_moskowitz":
        return lambda w: pierson_moskowitz(w, hs, tp)
    return lambda w: jonswap(w, hs, tp, spec.gamma)


def _grid(states, spectrum, lo, hi, n_omega):
    from ..dynamics.spectra import energy_band
    bands = [energy_band(_density(spectrum, hs, tp), tp, BAND_TAIL) for hs, tp, _, _ in states]
    a = max(lo, min(b[0] for b in bands))
    b = min(hi, max(b[1] for b in bands))
    if not b > a:
        raise CaseError("checks.fatigue.sea_states", f"the sea states' energy lies outside "
                        f"the hydrodynamics' frequencies [{lo:.4g}, {hi:.4g}] rad/s")
    return np.linspace(a, b, n_omega)


def scatter_tensions(result, states, spectrum, *, n_omega: int = N_OMEGA,
                     n_elements: int = N_ELEMENTS,
                     tolerance: float = 1e-2) -> SeaStateTensions:
    """Tension spectra at both ends of every line in every sea state.

    Parameters
    ----------
    result : Result
        The certified static equilibrium of a case whose bodies have hydrodynamics.
    states : sequence of (hs [m], tp [s], toward_deg, probability)
    spectrum : moorsolve.model.sea.Spectrum
        The spectrum's shape (jonswap or pierson_moskowitz).
    n_omega : int
        Frequencies of the common grid.
    n_elements : int
        About how many lumped-mass elements per line.
    tolerance : float
        Drag linearisation tolerance (fraction of the largest coefficient): 1e-2 moves the
        tension's sigma by about 1e-4 from a converged linearisation.
    """
    from ..dynamics.hydro import BodyHydro
    from ..dynamics.line_batch import spectral_tensions
    from ..dynamics.line_model import line_model
    from ..dynamics.motions import _moving_bodies, _tables
    from ..dynamics.system import System, solved_pose
    from ..studies.stiffness import coupled_stiffness

    case = result.case
    moving = _moving_bodies(case)
    if not moving:
        raise CaseError("checks.fatigue", "no body has hydrodynamics "
                        "(bodies[i].hydrodynamics): the line tensions need the bodies' "
                        "motions in each sea state")
    hydros = {b.name: BodyHydro(_tables(b, p, case, result), f"{p}.hydrodynamics")
              for p, b in moving}
    lo = max(h.omega[0] for h in hydros.values())
    hi = min(h.omega[-1] for h in hydros.values())
    grid = _grid(states, spectrum, lo, hi, n_omega)
    K, labels = coupled_stiffness(result)
    names = [ln.name for ln in case.lines]
    legs = {lg.name: lg for lg in result.legs}
    # Each end's motion per unit DOF motion of its body: (label indices, 3 x k map).
    maps = []
    for ln in case.lines:
        ends = []
        for end, where in ((ln.a, legs[ln.name].anchor), (ln.b, legs[ln.name].fairlead)):
            if end.body is None:
                if end.point is not None and any(p.name == end.point and p.free
                                                 for p in case.points):
                    raise CaseError(f"lines.{ln.name}", f"ends on the free point "
                                    f"{end.point!r}: its motion in a sea state is not "
                                    "modelled, so neither is this line's fatigue")
                ends.append(None)
                continue
            body = next((b for _, b in moving if b.name == end.body), None)
            if body is None:
                ends.append(None)                       # a held body: it does not move
                continue
            full = end_motion_map(solved_pose(result, body.name), where)
            cols = [DOFS.index(d) for d in body.free]
            idx = [labels.index(f"{body.name}.{d}") for d in body.free]
            ends.append((idx, full[:, cols]))
        maps.append(ends)
    models = [line_model(case, result, n, n_elements=n_elements) for n in names]
    headings = sorted({s[2] for s in states})
    raos = {}
    for toward in headings:
        system = System(moving, hydros, result, K, labels, toward)
        X = system.response(grid)                         # (n_omega, n_dof)
        raos[toward] = [[None if e is None else (X[:, e[0]] @ e[1].T).T for e in ends]
                        for ends in maps]
    n_s, n_l = len(states), len(names)
    spectra = np.zeros((n_s, n_l, 2, grid.size))
    waves = np.array([_density(spectrum, hs, tp)(grid) for hs, tp, _, _ in states])
    fine = np.linspace(1e-3, 4 * hi, 20001)
    totals = np.array([np.trapezoid(_density(spectrum, hs, tp)(fine), fine)
                       for hs, tp, _, _ in states])
    coverage = np.where(totals > 0, np.trapezoid(waves, grid, axis=1) / np.where(
        totals > 0, totals, 1.0), 1.0)
    short = [i for i, c in enumerate(coverage) if c < COVERAGE_WARNING]
    if short:
        i = min(short, key=lambda k: coverage[k])
        warnings.warn(MoorsolveWarning(
            f"checks.fatigue.sea_states.table[{i}]: the hydrodynamics' frequencies "
            f"[{lo:.4g}, {hi:.4g}] rad/s hold {coverage[i]:.1%} of its spectrum's m0 "
            f"({len(short)} sea state(s) below {COVERAGE_WARNING:.0%}): their tension "
            "misses the rest (give the tables over a wider range)"), stacklevel=3)
    iterations = np.zeros(n_l, int)
    zero = np.zeros((3, grid.size), complex)
    for j, model in enumerate(models):
        per_state = [raos[s[2]][j] for s in states]
        if all(ua is None and ub is None for ua, ub in per_state):
            continue                                      # both ends held: no tension change
        ub = np.array([zero if b is None else b for _, b in per_state])
        ua = np.array([zero if a is None else a for a, _ in per_state])
        t_a, t_b, iterations[j] = spectral_tensions(model, grid, ub, waves, motion_a=ua,
                                                    tolerance=tolerance)
        spectra[:, j, 0] = np.abs(t_a) ** 2 * waves
        spectra[:, j, 1] = np.abs(t_b) ** 2 * waves
    mean = np.array([[legs[n].anchor_tension_N, legs[n].fairlead_tension_N] for n in names])
    return SeaStateTensions(grid, names, spectra, waves, coverage, mean, iterations)
