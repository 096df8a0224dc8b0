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

__all__ = ["LineResponse", "line_response", "HARMONIC", "SPECTRAL"]

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


class _System:
    """The matrices of one line as 3x3 blocks per node (a node couples only with its
    neighbours: the dynamic stiffness is block tridiagonal)."""

    def __init__(self, model: LineModel):
        n = model.n_elements
        ndof = 3 * (n + 1)
        N = n + 1
        self.K = model.stiffness()
        t = model.tangent
        self.Pt = t[:, :, None] * t[:, None, :]                    # (n+1, 3, 3)
        self.Pn = np.eye(3) - self.Pt
        self.M_blocks = (model.mass[:, None, None] * np.eye(3)
                         + model.added_mass[:, None, None] * self.Pn)
        fixed = np.zeros(ndof, bool)
        fixed[:3] = True                                           # end A
        fixed[-3:] = True                                          # end B, prescribed
        if model.seabed_spring is None:
            fixed[3 * np.flatnonzero(model.grounded) + 2] = True   # held on the seabed
        # A grounded node between two elements without tension (friction has used the
        # tension up, or the run lies slack) has no stiffness along the seabed: it is held
        # where it lies, as the friction holding it would.
        T = np.concatenate([[0.0], model.tension, [0.0]])
        loose = 1e-9 * max(float(np.max(np.abs(model.tension))), 1.0)
        held = model.grounded & (T[:-1] <= loose) & (T[1:] <= loose)
        for k in range(2):
            fixed[3 * np.flatnonzero(held) + k] = True
        self.fixed = fixed.reshape(N, 3)
        self.end_b = np.arange(ndof - 3, ndof)
        self.n_nodes = N
        self.ndof = ndof
        node = np.arange(N)
        K4 = self.K.reshape(N, 3, N, 3)
        self.K_diag = K4[node, :, node, :].copy()                  # (N, 3, 3)
        self.K_upper = K4[node[:-1], :, node[1:], :].copy()        # row i, column i + 1
        # A prescribed DOF's equation is u = its motion: its row of the blocks is the
        # identity's, so that the system stays block tridiagonal.
        free = (~self.fixed).astype(float)
        self.K_upper *= free[:-1, :, None]
        self.K_lower = np.transpose(K4[node[1:], :, node[:-1], :], (0, 1, 2)).copy()
        self.K_lower *= free[1:, :, None]
        self.free_rows = free

    def solve(self, omega, u_a, u_b, bn, bt):
        """Node displacements ``(n_omega, n_nodes, 3)`` for end motions ``u_a``, ``u_b``
        ``(n_omega, 3)`` and drag coefficients per node ``bn``, ``bt``
        ``(n_omega, n_nodes)``: block Gaussian elimination down the line (the block
        Thomas algorithm), every frequency at once."""
        nw, N = len(omega), self.n_nodes
        w = omega[:, None, None, None]
        B_blocks = bn[:, :, None, None] * self.Pn + bt[:, :, None, None] * self.Pt
        Z = (self.K_diag[None] - w ** 2 * self.M_blocks[None] + 1j * w * B_blocks)
        rows = self.free_rows[None, :, :, None]
        Z = Z * rows + (1 - rows) * np.eye(3)                      # (nw, N, 3, 3)
        rhs = np.zeros((nw, N, 3), complex)
        rhs[:, 0] = u_a
        rhs[:, -1] = u_b
        held = self.fixed[1:-1]
        rhs[:, 1:-1][:, held] = 0.0
        C = np.zeros((nw, N - 1, 3, 3), complex)
        d = np.zeros((nw, N, 3), complex)
        try:
            upper = np.broadcast_to(self.K_upper[0], (nw, 3, 3))
            sol = np.linalg.solve(Z[:, 0], np.concatenate([upper, rhs[:, 0, :, None]], -1))
            C[:, 0], d[:, 0] = sol[..., :3], sol[..., 3]
            for i in range(1, N):
                L = self.K_lower[i - 1]
                den = Z[:, i] - L @ C[:, i - 1]
                r = rhs[:, i] - np.einsum("ij,wj->wi", L, d[:, i - 1])
                if i < N - 1:
                    upper = np.broadcast_to(self.K_upper[i], (nw, 3, 3))
                    sol = np.linalg.solve(den, np.concatenate([upper, r[..., None]], -1))
                    C[:, i], d[:, i] = sol[..., :3], sol[..., 3]
                else:
                    d[:, i] = np.linalg.solve(den, r[..., None])[..., 0]
        except np.linalg.LinAlgError:
            raise ConvergenceError(
                "the line's dynamic stiffness is singular at one of the frequencies (a node "
                "with neither tension nor mass to hold it, or omega = 0 on a line without "
                "tension)") from None
        u = np.empty((nw, N, 3), complex)
        u[:, -1] = d[:, -1]
        for i in range(N - 2, -1, -1):
            u[:, i] = d[:, i] - np.einsum("wij,wj->wi", C[:, i], u[:, i + 1])
        return u

    def split_velocity(self, v):
        """Magnitudes of the normal and tangential parts of node velocities ``v``
        ``(n_omega, n_nodes, 3)``, components added in quadrature."""
        vt = np.einsum("nij,wnj->wni", self.Pt, v)
        vn = v - vt
        return np.sqrt(np.sum(np.abs(vn) ** 2, -1)), np.sqrt(np.sum(np.abs(vt) ** 2, -1))


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
    omega = np.asarray(omega, float).ravel()
    if omega.size == 0 or np.any(omega < 0) or not np.all(np.isfinite(omega)):
        raise CaseError("omega", "frequencies must be finite and >= 0 rad/s")
    u_b = _drive(motion, omega)
    u_a = np.zeros_like(u_b) if motion_a is None else _drive(motion_a, omega, "motion_a")
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
    sys = _System(model)
    nw = len(omega)
    qn, qt = model.drag_normal, model.drag_tangential

    def coefficients(u):
        vn, vt = sys.split_velocity(1j * omega[:, None, None] * u)
        if linearisation == HARMONIC:
            return _HARMONIC_FACTOR * vn * qn, _HARMONIC_FACTOR * vt * qt
        sn = np.sqrt(np.trapezoid(vn ** 2 * S[:, None], omega, axis=0))
        st = np.sqrt(np.trapezoid(vt ** 2 * S[:, None], omega, axis=0))
        return (np.broadcast_to(_SPECTRAL_FACTOR * sn * qn, (nw, sys.n_nodes)),
                np.broadcast_to(_SPECTRAL_FACTOR * st * qt, (nw, sys.n_nodes)))

    # Start from the line moving as a straight rod between its ends.
    frac = (model.s / model.s[-1])[None, :, None]
    bn, bt = coefficients(u_a[:, None, :] + frac * (u_b - u_a)[:, None, :])
    for it in range(1, max_iterations + 1):
        u = sys.solve(omega, u_a, u_b, bn, bt)
        bn_new, bt_new = coefficients(u)
        scale = max(float(np.max(bn_new)), float(np.max(bt_new)), 1e-300)
        change = max(float(np.max(np.abs(bn_new - bn))), float(np.max(np.abs(bt_new - bt))))
        if change <= tolerance * scale:
            bn, bt = bn_new, bt_new
            u = sys.solve(omega, u_a, u_b, bn, bt)
            break
        bn = relaxation * bn_new + (1 - relaxation) * bn
        bt = relaxation * bt_new + (1 - relaxation) * bt
    else:
        raise ConvergenceError(
            f"line {model.name}: the drag linearisation did not converge in "
            f"{max_iterations} iterations (last change {change / scale:.3g} of the largest "
            "coefficient)", iterations=max_iterations)
    du = np.diff(u, axis=1)                                         # (nw, n, 3)
    tension = model.axial[None, :] * np.einsum("wei,ei->we", du, model.direction)
    f_b = -(np.einsum("ij,wj->wi", sys.K[sys.end_b, :], u.reshape(nw, -1)))
    if linearisation == SPECTRAL:
        bn, bt = bn[0], bt[0]
    dz = du[:, :, 2]
    t_a = tension[:, 0] - 0.5 * model.weight[0] * dz[:, 0]
    t_b = tension[:, -1] + 0.5 * model.weight[-1] * dz[:, -1]
    return LineResponse(omega=omega, tension_a=t_a, tension_b=t_b,
                        tension=tension, s_elements=0.5 * (model.s[:-1] + model.s[1:]),
                        force_b=f_b, motion=u, damping_normal=np.array(bn),
                        damping_tangential=np.array(bt), iterations=it,
                        linearisation=linearisation)
