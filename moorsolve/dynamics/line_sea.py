"""Every line's dynamic tension in a sea state, driven by the bodies' motions.

For each line of a scene whose bodies move in a sea state (:func:`moorsolve.motions`):

* **wave frequency (WF)**: each end on a body follows the point of the body it is attached
  to, ``u(omega) = P X(omega)`` with ``X`` the bodies' coupled response per unit wave
  amplitude (global translations and roll, pitch, yaw angles) and ``P`` (3 x DOFs) the
  point's displacement per unit of each DOF at the mean pose (a unit translation moves it
  by one metre; a unit angle by ``d(R(angles) r)/d angle``, ``r`` the point in the body
  frame). The line's lumped-mass model about its mean profile (:mod:`.line_model`, with
  the dynamic stiffness of a fibre rope) is driven at both ends, its drag linearised on
  the spectral response (:func:`.line_dynamics.line_response`), and the tension spectrum
  at each end is ``|H_T|^2 S``.
* **low frequency (LF)**: the slow drift's periods (one to a few minutes) lie far beyond
  the line's own, so each line follows the slow motion quasi-statically: the tension
  change per unit of each DOF is the line's static stiffness, ``g = dT/du_A P_A + dT/du_B
  P_B``, with ``dT/du`` the lumped-mass model at ``omega = 0`` (the quasi-static tangent
  stiffness, without a fibre rope's dynamic stiffness; held to central differences of
  re-solved statics by the tests). The LF tension spectrum is ``g^T S_q(mu) g``, ``S_q``
  the slow-drift response cross-spectra. The line's own drag at those periods (a small
  extra damping of the slow drift) is left out, which errs on the safe side.

The statistics per end (DNV-OS-E301 (2010) Ch.2 Sec.2 [2.4]; DNV-RP-C205 (2010) 3.5)::

    sigma_T = sqrt(sigma_LF^2 + sigma_WF^2),  T_z = 2 pi sqrt((m0_LF + m0_WF) / (m2_LF + m2_WF))
    T_dyn = sigma_T sqrt(2 ln N),              N = duration / T_z

and each part's significant value ``2 sigma`` and most probable maximum ``sigma sqrt(2 ln
(duration / T_z))`` for API RP 2SK's combination (:mod:`moorsolve.checks.dynamic`).

The wave-frequency line response is computed on a grid of its own, one for all the lines of
the scene (they are solved together): half of it uniform over the band holding all but 1e-6
of the ends' motion energy, half at the quantiles of that energy (so a resonance of the
bodies keeps its points), the motions interpolated onto it. At the default 64 frequencies
the dock's tension sigma is within 1 % of a 256-frequency run (3 % at 48, 8 % at 32).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import CaseError
from ..model import DOFS
from ..model.build_network import rotation
from .line_dynamics import HARMONIC, SPECTRAL, line_responses
from .line_model import line_model
from .line_spectral import STORM_DURATION_S

__all__ = ["EndSeaTension", "LineSeaTension", "line_tensions", "end_motion_map",
           "LINE_FREQUENCIES", "LINE_ELEMENTS"]

#: Frequencies of the wave-frequency line response.
LINE_FREQUENCIES = 64
#: Elements of each line: on the dock the tension sigma is within 0.1 % of a 120-element
#: model's at 40 (0.05 % at 60, for 1.5 times the work), below the frequency grid's 1 %.
LINE_ELEMENTS = 40
#: Energy of the ends' motion left outside the line's wave-frequency band.
_BAND_TAIL = 1e-6
#: Step of the central difference of the rotation matrix [rad].
_ANGLE_STEP = 1e-6
#: Under-relaxation of the drag linearisation: 0.7 converges in about 8 iterations where
#: 0.5 takes 15, to the same answer (1e-8 of sigma on the dock).
_RELAXATION = 0.7
#: The drag coefficients' convergence: 1e-3 of the largest changes sigma by 1e-11 of
#: itself from 1e-4 on the dock, two iterations sooner.
_TOLERANCE = 1e-3


@dataclass(frozen=True)
class EndSeaTension:
    """The dynamic tension at one end of a line in a sea state. Forces [N], periods [s].

    Attributes
    ----------
    sigma_wf_N, tz_wf_s, sigma_lf_N, tz_lf_s : float
        Standard deviation and mean zero-crossing period of the wave-frequency and
        low-frequency parts (periods NaN where the part has no energy).
    sigma_N, tz_s : float
        Of the whole: ``sqrt(sigma_LF^2 + sigma_WF^2)`` and ``2 pi sqrt(m0 / m2)`` with both
        parts' moments added.
    cycles : float
        ``N = duration / T_z``.
    t_dyn_N : float
        ``sigma sqrt(2 ln N)``: DNV-OS-E301's characteristic dynamic tension.
    wf_max_N, lf_max_N : float
        Each part's most probable maximum in the storm, ``sigma sqrt(2 ln(duration /
        T_z))`` (API RP 2SK's "maximum").
    """

    sigma_wf_N: float
    tz_wf_s: float
    sigma_lf_N: float
    tz_lf_s: float
    sigma_N: float
    tz_s: float
    cycles: float
    t_dyn_N: float
    wf_max_N: float
    lf_max_N: float

    @property
    def wf_significant_N(self) -> float:
        return 2.0 * self.sigma_wf_N

    @property
    def lf_significant_N(self) -> float:
        return 2.0 * self.sigma_lf_N

    def to_dict(self) -> dict:
        return {"sigma_wf_N": self.sigma_wf_N, "tz_wf_s": _finite(self.tz_wf_s),
                "sigma_lf_N": self.sigma_lf_N, "tz_lf_s": _finite(self.tz_lf_s),
                "sigma_N": self.sigma_N, "tz_s": _finite(self.tz_s),
                "t_dyn_N": self.t_dyn_N, "wf_max_N": self.wf_max_N,
                "lf_max_N": self.lf_max_N}


def _finite(v):
    return float(v) if math.isfinite(v) else None


@dataclass(frozen=True)
class LineSeaTension:
    """One line's dynamic tension in the sea state: both ends, and the spectra behind them.

    ``omega`` and ``wf_spectrum`` (2 x len(omega): anchor, fairlead) [N^2 s/rad] are the
    wave-frequency tension spectra; ``lf_omega`` and ``lf_spectrum`` the low-frequency
    ones (None without slow drift); ``lf_gradient`` (2 x DOFs) the quasi-static tension
    change of each end per unit of each of the motions' DOFs [N/m, N/rad].
    """

    name: str
    anchor: EndSeaTension
    fairlead: EndSeaTension
    omega: np.ndarray
    wf_spectrum: np.ndarray
    lf_omega: Optional[np.ndarray]
    lf_spectrum: Optional[np.ndarray]
    lf_gradient: np.ndarray
    iterations: int


def end_motion_map(end, motions, result) -> Optional[np.ndarray]:
    """``P`` (3 x DOFs): an end's global displacement per unit of each of the motions'
    DOFs (``motions.labels``) at the mean pose; None for a fixed end.

    Raises
    ------
    CaseError
        An end at a free point (its motion in the sea state is not modelled).
    """
    labels = list(motions.labels)
    if end.body is None:
        if end.point is not None and any(p.name == end.point and p.free
                                         for p in result.case.points):
            raise CaseError("analysis.lines", f"a line ends at the free point {end.point!r}, "
                            "whose motion in the sea state is not modelled: use "
                            "analysis.lines: quasi_static")
        return None
    P = np.zeros((3, len(labels)))
    b = result.body_named(end.body)
    angles = np.radians([b["roll_deg"], b["pitch_deg"], b["yaw_deg"]])
    r = np.asarray(end.position, dtype=float)
    for k, dof in enumerate(DOFS):
        label = f"{end.body}.{dof}"
        if label not in labels:
            continue            # held: it does not move
        col = labels.index(label)
        if k < 3:
            P[k, col] = 1.0
        else:
            step = np.zeros(3)
            step[k - 3] = _ANGLE_STEP
            P[:, col] = (rotation(*(angles + step)) - rotation(*(angles - step))) @ r / (
                2 * _ANGLE_STEP)
    return P


def _line_grid(omega, energy, n: int) -> np.ndarray:
    """Half uniform over the band of ``energy`` (all but ``_BAND_TAIL`` of it), half at
    its quantiles."""
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (energy[1:] + energy[:-1]) * np.diff(omega))])
    total = cum[-1]
    if not total > 0:
        return np.linspace(omega[0], omega[-1], n)
    lo = float(np.interp(_BAND_TAIL * total, cum, omega))
    hi = float(np.interp((1 - _BAND_TAIL) * total, cum, omega))
    half = max(n // 2, 2)
    quantiles = np.interp(np.linspace(0.0, 1.0, n - half + 2)[1:-1] * total, cum, omega)
    return np.unique(np.concatenate([np.linspace(lo, hi, half), quantiles]))


def _interp_complex(x, xp, fp) -> np.ndarray:
    """Linear interpolation of each row of ``fp`` (k, len(xp)) complex at ``x``."""
    return np.array([np.interp(x, xp, f.real) + 1j * np.interp(x, xp, f.imag) for f in fp])


def _part(omega, spectrum, duration) -> tuple:
    """``(m0, m2, sigma, T_z, maximum)`` of one part's tension spectrum."""
    if omega is None:
        return 0.0, 0.0, 0.0, math.nan, 0.0
    m0 = max(float(np.trapezoid(spectrum, omega)), 0.0)
    m2 = max(float(np.trapezoid(omega ** 2 * spectrum, omega)), 0.0)
    sigma = math.sqrt(m0)
    if not (m0 > 0 and m2 > 0):
        return m0, m2, sigma, math.nan, 0.0
    tz = 2 * math.pi * math.sqrt(m0 / m2)
    return m0, m2, sigma, tz, sigma * math.sqrt(2 * math.log(max(duration / tz, 1.0)))


def _end(omega, wf, lf_omega, lf, duration) -> EndSeaTension:
    m0w, m2w, sw, tzw, maxw = _part(omega, wf, duration)
    m0l, m2l, sl, tzl, maxl = _part(lf_omega, lf, duration)
    m0, m2 = m0w + m0l, m2w + m2l
    sigma = math.sqrt(m0)
    if m0 > 0 and m2 > 0:
        tz = 2 * math.pi * math.sqrt(m0 / m2)
        cycles = duration / tz
        if not cycles >= 2:
            raise CaseError("environment.waves.duration",
                            f"{duration:g} s holds {cycles:.3g} tension cycles of T_z = "
                            f"{tz:.4g} s: at least 2 are needed for a most probable maximum")
        t_dyn = sigma * math.sqrt(2 * math.log(cycles))
    else:
        tz, cycles, t_dyn = math.nan, 0.0, 0.0
    return EndSeaTension(sigma_wf_N=sw, tz_wf_s=tzw, sigma_lf_N=sl, tz_lf_s=tzl,
                         sigma_N=sigma, tz_s=tz, cycles=cycles, t_dyn_N=t_dyn,
                         wf_max_N=maxw, lf_max_N=maxl)


def line_tensions(motions, *, n_omega: int = LINE_FREQUENCIES,
                  n_elements: int = LINE_ELEMENTS, lines=None) -> dict:
    """The dynamic tension of every line (or of ``lines``) in the motions' sea state.

    Parameters
    ----------
    motions : moorsolve.dynamics.motions.Motions
        The bodies' motions (not static): its ``result`` is the mean equilibrium the lines
        are linearised about.
    n_omega : int
        Frequencies of the wave-frequency line response (module notes).
    n_elements : int
        Elements of each line's lumped-mass model (:data:`LINE_ELEMENTS`).
    lines : iterable of str, optional
        The lines to compute (default all).

    Returns
    -------
    dict
        Line name to :class:`LineSeaTension`.

    Raises
    ------
    CaseError
        A static ``motions`` (no sea state), a line ending at a free point, a line the
        lumped-mass model refuses (slack, no diameter).
    ConvergenceError
        A line's drag linearisation that does not converge.
    """
    if motions.static:
        raise CaseError("analysis.lines", "dynamic: nothing moves in a sea state here ("
                        + motions.sea.get("reason", "no sea state") + ")")
    result = motions.result
    case = result.case
    duration = case.environment.waves.duration or STORM_DURATION_S
    omega_all = np.asarray(motions.omega, float)
    S_all = np.asarray(motions.spectrum, float)
    X = np.asarray(motions.wf_response)                     # (m, n)
    wanted = None if lines is None else set(lines)
    extra = {"n_elements": int(n_elements)}
    chosen, maps, drives_all = [], [], []
    for line in case.lines:
        if wanted is not None and line.name not in wanted:
            continue
        ends = [end_motion_map(end, motions, result) for end in (line.a, line.b)]
        if ends[0] is None and ends[1] is None:
            continue            # both ends fixed: nothing drives it
        chosen.append(line)
        maps.append(ends)
        drives_all.append([None if P is None else P @ X.T for P in ends])   # (3, m) each
    if not chosen:
        return {}
    # One grid for every line (they are solved together): each line's share of the ends'
    # motion energy, normalised, so that every line's band is covered.
    energy = np.zeros_like(omega_all)
    for drives in drives_all:
        e = sum(np.sum(np.abs(u) ** 2, axis=0) for u in drives if u is not None) * S_all
        total = np.trapezoid(e, omega_all)
        energy += e / total if total > 0 else 0.0
    grid = _line_grid(omega_all, energy, n_omega)
    S = np.interp(grid, omega_all, S_all)
    fixed = np.zeros((3, grid.size), complex)
    waves = [line_model(case, result, line.name, **extra) for line in chosen]
    responses = line_responses(
        waves, grid, [fixed if d[1] is None else _interp_complex(grid, omega_all, d[1])
                      for d in drives_all],
        motions_a=[None if d[0] is None else _interp_complex(grid, omega_all, d[0])
                   for d in drives_all],
        linearisation=SPECTRAL, spectrum=S, relaxation=_RELAXATION, tolerance=_TOLERANCE)
    gradients = _lf_gradients(case, result, chosen, maps, extra, waves)
    out = {}
    for line, r, gradient in zip(chosen, responses, gradients):
        wf = np.vstack([np.abs(r.tension_a) ** 2 * S, np.abs(r.tension_b) ** 2 * S])
        lf_omega, lf = motions.lf_omega, None
        if lf_omega is not None:
            lf = np.real(np.einsum("ei,mij,ej->em", gradient, motions.lf_cross, gradient))
            lf = np.clip(lf, 0.0, None)
        ends = [_end(grid, wf[k], lf_omega, None if lf is None else lf[k], duration)
                for k in range(2)]
        out[line.name] = LineSeaTension(name=line.name, anchor=ends[0], fairlead=ends[1],
                                        omega=grid, wf_spectrum=wf, lf_omega=lf_omega,
                                        lf_spectrum=lf, lf_gradient=gradient,
                                        iterations=r.iterations)
    return out


def _lf_gradients(case, result, chosen, maps, extra, waves) -> list:
    """Per line, ``g`` (2 x DOFs): the quasi-static tension change at end A and end B per
    unit of each DOF: the lumped-mass models at ``omega = 0`` (the quasi-static stiffness
    of a fibre rope, not its dynamic one) driven by a unit motion of end B along x, y and
    z (three "frequencies" of zero) and of end A likewise (three more), solved together."""
    models = [line_model(case, result, line.name, dynamic_stiffness=False, **extra)
              if any(seg.line_type.stiffness_bounds is not None for seg in line.segments)
              else wave for line, wave in zip(chosen, waves)]
    unit = np.eye(3, dtype=complex)
    zero = np.zeros((3, 3), complex)
    drive_b = np.hstack([unit, zero])                 # end B moved, then end A moved
    drive_a = np.hstack([zero, unit])
    rs = line_responses(models, np.zeros(6), [drive_b] * len(models),
                        motions_a=[drive_a] * len(models), linearisation=HARMONIC)
    out = []
    for ends, r in zip(maps, rs):
        n = next(P.shape[1] for P in ends if P is not None)
        g = np.zeros((2, n))
        for k, P in enumerate(ends):
            if P is None:
                continue
            cols = slice(3, 6) if k == 0 else slice(0, 3)
            dT = np.vstack([r.tension_a[cols].real, r.tension_b[cols].real])   # (2, 3)
            g += dT @ P
        out.append(g)
    return out
