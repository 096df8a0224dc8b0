"""Dynamic line tension in the frequency domain: one line driven at its fairlead.

The lumped-mass line of :mod:`.line_model` moves about its static profile with complex
amplitudes ``u`` (``x(t) = Re[u e^{i omega t}]``). End B (the fairlead) follows a prescribed
motion ``u_B(omega)``; end A (the anchor) is fixed or, for a line between two bodies,
follows ``u_A(omega)``. The free nodes obey, at every frequency (Hall & Goupee 2015,
*Ocean Engineering* 104, linearised about the static state)::

    [K_ff - omega^2 (M + M_a)_ff + i omega B_ff] u_f = -K_fB u_B - K_fA u_A

with ``K`` the axial plus geometric stiffness, ``M_a`` the normal added mass and ``B`` the
linearised drag. The tension change of element ``e`` is ``(EA_t/l_0) t_e . (u_{e+1} -
u_e)``, at the element's middle; the tension at an end adds the change of the static
gradient ``dT/ds_0 = w dz/ds_0`` over the half element to it (``w`` the submerged weight
per unstretched length), ``delta T_B = delta T_n + w (delta z_B - delta z_{n-1}) / 2``,
so that the end tension converges as the square of the element length.

Drag ``q |v| v`` (``q = 0.5 rho Cd d l`` per node, normal and tangential parts apart) is
replaced by ``b v`` with ``b`` chosen on the response and iterated to convergence:

* one sinusoid of velocity amplitude ``|v|`` (``linearisation="harmonic"``): equal
  dissipation over a cycle, ``b = 8/(3 pi) |v| q`` (Lorentz's equivalent; Borgman 1969,
  *J. Waterways and Harbors Div.* 95(WW2), for the random case);
* a Gaussian response of standard deviation ``sigma_v`` (``"spectral"``): the stochastic
  linearisation ``b = sqrt(8/pi) sigma_v q`` (Borgman 1969; Langley 1984; DNV-RP-C205
  (2010) section 10.2), ``sigma_v^2 = int |v(omega)|^2 S(omega) d omega``.

``|v|`` and ``sigma_v`` are those of the velocity vector normal (or tangential) to the line
at each node, its components' magnitudes added in quadrature: exact for motion along one
direction (the in-plane motion that dominates a catenary), and an upper bound otherwise.
The water is still: waves and current acting on the line itself are not modelled, only the
motion of its ends. Seabed friction is not modelled dynamically: a grounded run slides
freely along the seabed, except where the static solution left it without tension (friction
used it up toward the anchor), which is held where it lies.

At ``omega -> 0`` the tension change per unit fairlead displacement is the line's
quasi-static (tangent) stiffness, the same the static solution has: the tests check it
against central differences of re-solved statics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import CaseError, ConvergenceError
from .line_model import LineModel

__all__ = ["LineResponse", "line_response", "line_responses", "HARMONIC", "SPECTRAL"]

HARMONIC = "harmonic"
SPECTRAL = "spectral"
_HARMONIC_FACTOR = 8.0 / (3.0 * np.pi)
_SPECTRAL_FACTOR = np.sqrt(8.0 / np.pi)


@dataclass(frozen=True)
class LineResponse:
    """The linear response of one line to its fairlead motion.

    Attributes
    ----------
    omega : ndarray (n_omega,)
        Frequencies [rad/s].
    tension_a, tension_b : ndarray (n_omega,) complex
        Tension change at end A (anchor) and end B (fairlead) [N per unit of the drive:
        N for a motion in m, N/m for a motion per metre of wave amplitude].
    tension : ndarray (n_omega, n_elements) complex
        Tension change of every element (at its middle), from end A [same unit].
    s_elements : ndarray (n_elements,)
        Unstretched arc length of each element's middle from end A [m].
    force_b : ndarray (n_omega, 3) complex
        Change of the force the line exerts on end B, global [same unit as the tensions].
    motion : ndarray (n_omega, n_nodes, 3) complex
        Displacement of every node [m per unit of the drive].
    damping_normal, damping_tangential : ndarray
        The converged linear drag coefficients per node [N s/m]: ``(n_nodes,)`` for the
        spectral linearisation, ``(n_omega, n_nodes)`` for the harmonic one.
    iterations : int
        Drag linearisation iterations.
    linearisation : str
        ``"harmonic"`` or ``"spectral"``.
    """

    omega: np.ndarray
    tension_a: np.ndarray
    tension_b: np.ndarray
    tension: np.ndarray
    s_elements: np.ndarray
    force_b: np.ndarray
    motion: np.ndarray
    damping_normal: np.ndarray
    damping_tangential: np.ndarray
    iterations: int
    linearisation: str


def _drive(motion, omega, field="motion") -> np.ndarray:
    u = np.asarray(motion, complex)
    if u.ndim != 2 or u.shape != (3, len(omega)) or not np.all(np.isfinite(u)):
        raise CaseError(field, f"an end motion must be 3 x n_omega (3 x {len(omega)}) "
                        f"finite values, got {u.shape}")
    return u.T


def line_response(model: LineModel, omega, motion, *, linearisation: str = HARMONIC,
                  spectrum=None, motion_a=None, tolerance: float = 1e-4,
                  max_iterations: int = 200, relaxation: float = 0.5) -> LineResponse:
    """Tension transfer functions of one line driven at its fairlead.

    Parameters
    ----------
    model : LineModel
        The line (:func:`moorsolve.dynamics.line_model.line_model`).
    omega : array_like (n_omega,)
        Frequencies [rad/s], > 0 (a frequency of 0 gives the quasi-static response).
    motion : array_like (3, n_omega) complex
        Fairlead displacement (x, y, z, global) at each frequency: the amplitude [m] of a
        sinusoid each (``harmonic``), or per metre of wave amplitude [m/m] (``spectral``).
    linearisation : {"harmonic", "spectral"}
        How drag is linearised (module notes). ``harmonic`` treats each frequency as a
        sinusoid of its own, linearised on its own response.
    motion_a : array_like (3, n_omega) complex, optional
        Motion of end A in the same units (a line between two bodies, a shared line);
        None: end A is fixed (an anchor).
    spectrum : array_like (n_omega,), optional
        Wave spectrum ``S(omega)`` [m^2 s/rad], required by ``spectral``; the variances are
        integrated by the trapezoidal rule over ``omega``.
    tolerance : float
        Converged when no drag coefficient changes by more than this fraction of the
        largest one.
    max_iterations : int
    relaxation : float
        Fraction of the new coefficients taken at each iteration (under-relaxation).

    Returns
    -------
    LineResponse

    Raises
    ------
    ConvergenceError
        When the drag linearisation does not converge.
    """
    (out,) = line_responses([model], omega, [motion], linearisation=linearisation,
                            spectrum=spectrum, motions_a=[motion_a], tolerance=tolerance,
                            max_iterations=max_iterations, relaxation=relaxation)
    return out


def line_responses(models, omega, motions, *, linearisation: str = HARMONIC,
                   spectrum=None, motions_a=None, tolerance: float = 1e-4,
                   max_iterations: int = 200, relaxation: float = 0.5) -> list:
    """:func:`line_response` of several lines at the same frequencies, solved together
    (:class:`~.line_stack.LineStack`): ``motions`` and ``motions_a`` give each line's
    drives (``motions_a`` None, or an entry None, for a fixed end A). Each line's drag is
    linearised on its own response; the iteration stops when every line has converged.
    Returns one :class:`LineResponse` per line."""
    from .line_stack import LineStack

    omega = np.asarray(omega, float).ravel()
    if omega.size == 0 or np.any(omega < 0) or not np.all(np.isfinite(omega)):
        raise CaseError("omega", "frequencies must be finite and >= 0 rad/s")
    models = list(models)
    if motions_a is None:
        motions_a = [None] * len(models)
    u_b = np.array([_drive(m, omega) for m in motions])                # (L, nw, 3)
    u_a = np.array([np.zeros((omega.size, 3), complex) if m is None
                    else _drive(m, omega, "motion_a") for m in motions_a])
    if linearisation not in (HARMONIC, SPECTRAL):
        raise CaseError("linearisation", f"{linearisation!r}: use 'harmonic' or 'spectral'")
    if linearisation == SPECTRAL:
        if spectrum is None:
            raise CaseError("spectrum", "the spectral linearisation needs S(omega)")
        S = np.asarray(spectrum, float).ravel()
        if S.shape != omega.shape or np.any(S < 0):
            raise CaseError("spectrum", f"S(omega) must be {omega.size} values >= 0")
        if omega.size < 2:
            raise CaseError("omega", "the spectral linearisation needs at least 2 frequencies")
    stack = LineStack(models)
    nw, N = omega.size, stack.n_nodes
    qn, qt = stack.qn[:, None, :], stack.qt[:, None, :]

    def coefficients(u):
        vn, vt = stack.split_velocity(1j * omega[None, :, None, None] * u)
        if linearisation == HARMONIC:
            return _HARMONIC_FACTOR * vn * qn, _HARMONIC_FACTOR * vt * qt
        sn = np.sqrt(np.trapezoid(vn ** 2 * S[None, :, None], omega, axis=1))[:, None]
        st = np.sqrt(np.trapezoid(vt ** 2 * S[None, :, None], omega, axis=1))[:, None]
        return (np.broadcast_to(_SPECTRAL_FACTOR * sn * qn, (len(models), nw, N)),
                np.broadcast_to(_SPECTRAL_FACTOR * st * qt, (len(models), nw, N)))

    # Start from each line moving as a straight rod between its ends.
    frac = np.zeros((len(models), N))
    for k, m in enumerate(models):
        frac[k, :m.n_elements + 1] = m.s / m.s[-1]
    bn, bt = coefficients(u_a[:, :, None, :] + frac[:, None, :, None]
                          * (u_b - u_a)[:, :, None, :])
    for it in range(1, max_iterations + 1):
        u = stack.solve(omega, u_a, u_b, bn, bt)
        bn_new, bt_new = coefficients(u)
        scale = np.maximum(np.maximum(bn_new.max(axis=(1, 2)), bt_new.max(axis=(1, 2))),
                           1e-300)
        change = np.maximum(np.abs(bn_new - bn).max(axis=(1, 2)),
                            np.abs(bt_new - bt).max(axis=(1, 2)))
        if np.all(change <= tolerance * scale):
            bn, bt = bn_new, bt_new
            u = stack.solve(omega, u_a, u_b, bn, bt)
            break
        bn = relaxation * bn_new + (1 - relaxation) * bn
        bt = relaxation * bt_new + (1 - relaxation) * bt
    else:
        worst = int(np.argmax(change / scale))
        raise ConvergenceError(
            f"line {models[worst].name}: the drag linearisation did not converge in "
            f"{max_iterations} iterations (last change {change[worst] / scale[worst]:.3g} "
            "of the largest coefficient)", iterations=max_iterations)
    return [_response(m, stack, k, omega, u[k, :, :m.n_elements + 1], bn[k], bt[k], it,
                      linearisation) for k, m in enumerate(models)]


def _response(model, stack, k, omega, u, bn, bt, iterations, linearisation) -> LineResponse:
    """One line's tensions from its node displacements ``u`` (n_omega, nodes, 3)."""
    n = model.n_elements
    du = np.diff(u, axis=1)                                         # (nw, n, 3)
    tension = model.axial[None, :] * np.einsum("wei,ei->we", du, model.direction)
    # The force on end B: its row of the stiffness (the last element, a seabed spring).
    f_b = -np.einsum("ij,wj->wi", stack.ke[k][-1], u[:, n] - u[:, n - 1])
    if model.seabed_spring is not None and model.grounded[n]:
        f_b[:, 2] -= model.seabed_spring[n] * u[:, n, 2]
    bn, bt = bn[:, :n + 1], bt[:, :n + 1]
    if linearisation == SPECTRAL:
        bn, bt = bn[0], bt[0]
    dz = du[:, :, 2]
    t_a = tension[:, 0] - 0.5 * model.weight[0] * dz[:, 0]
    t_b = tension[:, -1] + 0.5 * model.weight[-1] * dz[:, -1]
    return LineResponse(omega=omega, tension_a=t_a, tension_b=t_b,
                        tension=tension, s_elements=0.5 * (model.s[:-1] + model.s[1:]),
                        force_b=f_b, motion=u, damping_normal=np.array(bn),
                        damping_tangential=np.array(bt), iterations=iterations,
                        linearisation=linearisation)
