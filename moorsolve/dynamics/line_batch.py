"""One line's spectral response in many sea states at once (a scatter diagram).

The same equations as :func:`.line_dynamics.line_response` with the spectral (stochastic)
drag linearisation, each sea state with its own linearised drag, solved together: the
line's matrices are block tridiagonal in its nodes (a node couples only with its
neighbours), so every frequency of every sea state is one block Thomas sweep over the
nodes (:func:`.block_thomas.solve_block_tridiagonal`, shared with
:class:`.line_stack.LineStack`), vectorised over all of them (``n_states x n_omega`` 3x3
systems per node) instead of a banded solve per frequency. Constrained degrees of freedom (the ends, nodes held on the
seabed) are kept in the sweep as identity rows with zero right-hand side, their coupling
to the free ones moved to the right-hand side, which is exactly the reduced system.

The tests check the sweep against the banded solve of :mod:`.line_dynamics`.
"""

from __future__ import annotations

import numpy as np

from ..errors import ConvergenceError
from .block_thomas import solve_block_tridiagonal
from .line_dynamics import _SPECTRAL_FACTOR
from .line_model import LineModel
from .line_stack import LineStack, element_blocks

__all__ = ["spectral_tensions"]


def _blocks(model: LineModel):
    """Diagonal and upper blocks of K and M over the nodes (as :class:`.line_stack.LineStack`
    builds them), constrained DOFs removed (identity in K's diagonal, zero elsewhere), the
    free mask ``(n_nodes, 3)``, the free-free mask of a block and the elements' stiffness."""
    stack = LineStack([model])
    mask = ~stack.fixed[0]
    outer = mask[:, :, None] & mask[:, None, :]
    ke = element_blocks(model)
    Kd = np.where(outer, stack.K_diag[0], 0.0) + np.eye(3) * (~mask)[:, :, None]
    Md = np.where(outer, stack.M[0], 0.0)
    Ku = np.where(mask[:-1, :, None] & mask[1:, None, :], -ke, 0.0)
    return Kd, Md, Ku, mask, outer, stack, ke


def spectral_tensions(model: LineModel, omega, motion_b, spectra, *, motion_a=None,
                      tolerance: float = 1e-3, max_iterations: int = 200,
                      relaxation: float = 0.5) -> tuple:
    """Tension transfer functions at both ends of one line in each of several sea states.

    Parameters
    ----------
    model : LineModel
    omega : array_like (n_omega,)
        Frequencies [rad/s], > 0.
    motion_b : array_like (n_states, 3, n_omega) complex
        Fairlead motion per metre of wave amplitude in each sea state [m/m], global.
    spectra : array_like (n_states, n_omega)
        Each sea state's wave spectrum [m^2 s/rad].
    motion_a : array_like (n_states, 3, n_omega) complex, optional
        Motion of end A (None: fixed).
    tolerance, max_iterations, relaxation
        As :func:`.line_dynamics.line_response` (per sea state).

    Returns
    -------
    (tension_a, tension_b, iterations) : (ndarray (n_states, n_omega) complex x 2, int)
        Tension change per metre of wave amplitude [N/m] at end A and end B.
    """
    omega = np.asarray(omega, float)
    S = np.asarray(spectra, float)
    ub = np.swapaxes(np.asarray(motion_b, complex), 1, 2)            # (ns, nw, 3)
    ua = np.zeros_like(ub) if motion_a is None else np.swapaxes(
        np.asarray(motion_a, complex), 1, 2)
    Kd, Md, Ku, mask, outer, stack, ke = _blocks(model)
    n = model.n_elements + 1
    ns, nw = S.shape
    # The prescribed ends couple to their neighbours through the end elements' stiffness
    # (M and B are block diagonal); other held DOFs stay where they lie (no motion).
    rhs = np.zeros((ns, nw, n, 3), complex)
    rhs[:, :, 1] += ua @ ke[0].T
    rhs[:, :, n - 2] += ub @ ke[-1].T
    rhs *= mask
    base = Kd[None, :] - (omega ** 2)[:, None, None, None] * Md[None, :]   # (nw, n, 3, 3)
    qn, qt = model.drag_normal, model.drag_tangential
    Pn = np.where(outer, stack.Pn[0], 0.0)
    Pt = np.where(outer, stack.Pt[0], 0.0)

    N = ns * nw
    rhs_c = rhs.transpose(2, 3, 0, 1).reshape(n, 3, N)
    base_c = base.transpose(1, 2, 3, 0)[:, :, :, None, :]            # (n, 3, 3, 1, nw)
    tangent = model.tangent

    def motion(bn, bt):
        B = bn[:, :, None, None] * Pn + bt[:, :, None, None] * Pt     # (ns, n, 3, 3)
        D = base_c + 1j * omega * B.transpose(1, 2, 3, 0)[..., None]  # (n, 3, 3, ns, nw)
        try:
            # Unrefined: on thousands of systems the sweep's cost is its arithmetic, which
            # refinement doubles, for 6e-9 of the answer (against a dense solve) that the
            # drag linearisation's tolerance dwarfs.
            x = solve_block_tridiagonal(D.reshape(n, 3, 3, N), Ku[..., None],
                                        Ku.transpose(0, 2, 1)[..., None], rhs_c, refine=0)
        except np.linalg.LinAlgError:
            raise ConvergenceError("the line's dynamic stiffness is singular at one of the "
                                   "frequencies") from None
        u = x.reshape(n, 3, ns, nw).transpose(2, 3, 0, 1).copy()
        u[:, :, -1, :] = ub
        u[:, :, 0, :] = ua
        return u                                                       # (ns, nw, n, 3)

    w2S = (omega ** 2 * S)[:, :, None]

    def coefficients(u):
        # |v|^2 = omega^2 |u|^2, split along the (real, unit) tangent t: |v_t|^2 =
        # omega^2 |t . u|^2 and |v_n|^2 = |v|^2 - |v_t|^2.
        ut = np.sum(u * tangent, -1)
        at = ut.real ** 2 + ut.imag ** 2
        an = np.maximum(np.sum(u.real ** 2 + u.imag ** 2, -1) - at, 0.0)
        sn = np.sqrt(np.trapezoid(an * w2S, omega, axis=1))
        st = np.sqrt(np.trapezoid(at * w2S, omega, axis=1))
        return _SPECTRAL_FACTOR * sn * qn, _SPECTRAL_FACTOR * st * qt

    frac = (model.s / model.s[-1])[None, None, :, None]
    bn, bt = coefficients(ua[:, :, None, :] + frac * (ub - ua)[:, :, None, :])
    for it in range(1, max_iterations + 1):
        u = motion(bn, bt)
        bn_new, bt_new = coefficients(u)
        scale = np.maximum(np.maximum(bn_new.max(1), bt_new.max(1)), 1e-300)
        change = np.maximum(np.abs(bn_new - bn).max(1), np.abs(bt_new - bt).max(1))
        if np.all(change <= tolerance * scale):
            u = motion(bn_new, bt_new)
            break
        bn = relaxation * bn_new + (1 - relaxation) * bn
        bt = relaxation * bt_new + (1 - relaxation) * bt
    else:
        raise ConvergenceError(f"line {model.name}: the drag linearisation did not converge "
                               f"in {max_iterations} iterations", iterations=max_iterations)
    du = np.diff(u, axis=2)                                            # (ns, nw, n-1, 3)
    first = model.axial[0] * np.einsum("swi,i->sw", du[:, :, 0], model.direction[0])
    last = model.axial[-1] * np.einsum("swi,i->sw", du[:, :, -1], model.direction[-1])
    t_a = first - 0.5 * model.weight[0] * du[:, :, 0, 2]
    t_b = last + 0.5 * model.weight[-1] * du[:, :, -1, 2]
    return t_a, t_b, it
