"""The coupled linear system of the moving bodies about a static equilibrium.

Unknowns: every free DOF of every body (global translations, roll, pitch and yaw angles:
the static solver's own, so the stiffness is its tangent matrix as it stands). Each body's
body-frame coefficients reach them through ``J`` (body-frame velocity = ``J q'``):
``M_q = J^T (M + A) J``, ``B_q = J^T (B + B_lin) J``, ``F_q = J^T F``. A fraction of
critical damping of a DOF adds ``2 zeta sqrt(K_ii (M + A(0))_ii)`` on the diagonal. Bodies
interact only through the stiffness (no hydrodynamic interaction between hulls).
"""

from __future__ import annotations

import math

import numpy as np

import warnings

from ..errors import CaseError, MoorsolveWarning
from ..model import DOFS
from ..model.build_network import rotation
from .response import newman_spectrum, transfer


#: A slow mode with less than this fraction of critical damping is refused, and with less
#: than LIGHT_DAMPING it is warned of: its response grows as 1/damping.
UNDAMPED, LIGHT_DAMPING = 1e-6, 1e-3


def velocity_map(pose_rad) -> np.ndarray:
    """``J`` (6x6): body-frame velocity from the rates of (x, y, z, roll, pitch, yaw)."""
    roll, pitch, yaw = pose_rad[3:]
    R = rotation(roll, pitch, yaw)
    cp, sp, cy, sy = math.cos(pitch), math.sin(pitch), math.cos(yaw), math.sin(yaw)
    E = np.array([[cy * cp, -sy, 0.0], [sy * cp, cy, 0.0], [-sp, 0.0, 1.0]])
    J = np.zeros((6, 6))
    J[:3, :3] = R.T
    J[3:, 3:] = R.T @ E
    return J


def solved_pose(result, name: str) -> np.ndarray:
    """A body's pose in a Result ``(x, y, z, roll, pitch, yaw)`` [m, rad]."""
    b = result.body_named(name)
    return np.array([b["x_m"], b["y_m"], b["z_m"], math.radians(b["roll_deg"]),
                     math.radians(b["pitch_deg"]), math.radians(b["yaw_deg"])])


class System:
    """The moving bodies' matrices over the free DOFs ``labels`` (``"body.dof"``).

    Parameters
    ----------
    moving : list of (path, Body)
        The bodies with hydrodynamics.
    hydros : dict
        ``name -> BodyHydro``.
    result : Result
        The equilibrium (poses, for ``J`` and each body's wave heading).
    K : array (n, n)
        Total tangent stiffness over ``labels``.
    toward_deg : float
        Where the waves travel [deg].
    """

    def __init__(self, moving, hydros, result, K, labels, toward_deg: float):
        from ..studies.stiffness import rigid_body_mass

        self.K = np.asarray(K, dtype=float)
        self.labels = list(labels)
        n = self.n = len(labels)
        index = {lab: i for i, lab in enumerate(labels)}
        self.parts = []
        self.M0 = np.zeros((n, n))
        self.B_ext = np.zeros((n, n))
        self.slots = {}
        self._drift_tables = None
        critical = []
        for path, body in moving:
            idx = [index[f"{body.name}.{d}"] for d in body.free]
            cols = [DOFS.index(d) for d in body.free]
            pose = solved_pose(result, body.name)
            J = velocity_map(pose)[:, cols]
            h = hydros[body.name]
            Mb = rigid_body_mass(body.mass or 0.0, body.centre_of_gravity,
                                 body.inertia or (0.0, 0.0, 0.0))
            beta = toward_deg - math.degrees(pose[5])
            ix = np.ix_(idx, idx)
            self.M0[ix] += J.T @ (Mb + h.added_mass_low()) @ J
            if body.damping is not None:
                self.B_ext[ix] += J.T @ np.diag(body.damping.linear) @ J
                critical += [(i, body.damping.critical_fraction[c], path)
                             for i, c in zip(idx, cols)]
            self.slots[body.name] = (idx, cols, path)
            self.parts.append((idx, J, h, beta, Mb))
        for i, zeta, path in critical:
            if zeta > 0:
                if not self.K[i, i] > 0:
                    raise CaseError(f"{path}.damping.critical_fraction",
                                    f"{labels[i]} has no restoring stiffness "
                                    f"({self.K[i, i]:.4g}): a fraction of critical damping "
                                    "needs one; give linear damping instead")
                self.B_ext[i, i] += 2 * zeta * math.sqrt(self.K[i, i] * self.M0[i, i])

    def matrices(self, w):
        """``(M(w), B(w) + B_ext, F(w))`` over the free DOFs at frequencies ``w`` (m,)."""
        w = np.asarray(w, dtype=float)
        m, n = w.size, self.n
        M = np.zeros((m, n, n))
        B = np.zeros((m, n, n))
        F = np.zeros((m, n), dtype=complex)
        for idx, J, h, beta, Mb in self.parts:
            ix = (slice(None),) + np.ix_(idx, idx)
            M[ix] += J.T @ (Mb + h.added_mass(w)) @ J
            B[ix] += J.T @ h.damping(w) @ J
            F[:, idx] = h.excitation(w, beta) @ J
        return M, B + self.B_ext[None], F

    def response(self, w) -> np.ndarray:
        """Motions per unit wave amplitude ``X(w)`` (m, n) complex."""
        M, B, F = self.matrices(w)
        return transfer(w, M, B, self.K, F)

    @property
    def has_drift(self) -> bool:
        return any(h.has_drift for _, _, h, _, _ in self.parts)

    def drift(self, w) -> np.ndarray:
        """Generalised mean drift coefficients (m, n) [N/m^2, ...], linear in frequency
        between the tables' points (each table turned to the DOFs once)."""
        w = np.asarray(w, dtype=float)
        if self._drift_tables is None:
            self._drift_tables = [(idx, h.omega, h.drift(h.omega, beta) @ J)
                                  for idx, J, h, beta, _ in self.parts if h.has_drift]
        out = np.zeros((w.size, self.n))
        for idx, omega, table in self._drift_tables:
            for c, i in enumerate(idx):
                out[:, i] += np.interp(w, omega, table[:, c])
        return out

    def resonances(self, lo: float, hi: float) -> list:
        """``(omega_n, zeta)`` of the wave-frequency modes within ``[lo, hi]``, with the
        added mass and damping at each mode's own frequency (one fixed-point pass)."""
        from scipy.linalg import eig
        out = []
        vals = eig(self.K, self.M0, right=False)
        for lam in vals:
            if not (np.isfinite(lam) and lam.real > 0):
                continue
            wn = math.sqrt(lam.real)
            M, B, _ = self.matrices([min(max(wn, lo), hi)])
            v2, vecs = eig(self.K, M[0])
            k = int(np.argmin(np.abs(v2 - lam)))
            if not (np.isfinite(v2[k]) and v2[k].real > 0):
                continue
            wn = math.sqrt(v2[k].real)
            v = np.real(vecs[:, k])
            mass = v @ M[0] @ v
            zeta = (v @ B[0] @ v) / (2 * wn * mass) if mass > 0 else 0.0
            if lo <= wn <= hi:
                out.append((wn, zeta))
        return out

    def slow_drift(self, grid, density, mu_max: float):
        """Newman's slow drift: ``(mu, cross)``, the response cross-spectra (len(mu), n, n)
        with ``A(0)`` and the extra damping; the force spectra on a coarse grid of
        difference frequencies, the response on a fine one refined round each slow mode."""
        from scipy.linalg import eig

        coarse = np.linspace(0.0, mu_max, 101)
        SF = newman_spectrum(coarse, grid, density, self.drift)
        vals, vecs = eig(self.K, self.M0)
        fine = [np.linspace(0.0, mu_max, 801)]
        for lam, v in zip(vals, vecs.T):
            if not np.isfinite(lam):
                continue
            v = np.real(v)
            if lam.real <= 1e-12 * max(abs(vals[np.isfinite(vals)]).max(), 1e-300):
                # No restoring stiffness: a steady drift force would carry it away.
                S0 = SF[0]
                if v @ S0 @ v > 1e-9 * max(abs(np.trace(S0)), 1e-300) * (v @ v):
                    main = self.labels[int(np.argmax(np.abs(v)))]
                    raise CaseError(f"{self.slots[main.split('.', 1)[0]][2]}.free",
                                    f"the slow drift pushes {main}, which nothing restrains "
                                    "(no stiffness): hold that DOF or moor it")
                continue
            wn = math.sqrt(lam.real)
            if not wn < mu_max:
                continue
            mass = v @ self.M0 @ v
            zeta = (v @ self.B_ext @ v) / (2 * wn * mass) if mass > 0 else 0.0
            Sn = _interp_stack(coarse, SF, np.array([wn]))[0]
            force = v @ Sn @ v
            scale = max(abs(np.trace(Sn)), 1e-300)
            if zeta < LIGHT_DAMPING and force > 1e-9 * scale * (v @ v):
                main = self.labels[int(np.argmax(np.abs(v) * np.sqrt(np.abs(np.diag(self.M0)))))]
                body, dof = main.split(".", 1)
                field = f"{self.slots[body][2]}.damping"
                what = (f"the slow drift excites a mode of period {2 * math.pi / wn:.4g} s "
                        f"(mostly {main}) with {zeta:.2g} of critical damping")
                if zeta < UNDAMPED:
                    raise CaseError(field, f"{what}: it has no damping; give the body's "
                                           f"damping (linear or critical_fraction of {dof})")
                warnings.warn(MoorsolveWarning(
                    f"{field}: {what}: its slow drift grows as 1/damping (slow-drift damping "
                    "is usually a few % of critical)"), stacklevel=4)
            band = wn * max(zeta, 1e-4)
            fine.append(np.clip(wn + band * np.linspace(-40, 40, 801), 0.0, mu_max))
        # From just above zero: a DOF without stiffness and without slow force (a free yaw)
        # leaves K singular at mu = 0 itself.
        mu = np.unique(np.clip(np.concatenate(fine), 1e-6 * mu_max, None))
        H = transfer(mu, self.M0, self.B_ext, self.K)
        cross = H @ _interp_stack(coarse, SF, mu) @ np.conj(np.transpose(H, (0, 2, 1)))
        return mu, cross


def _interp_stack(x, Y, xi) -> np.ndarray:
    k = np.clip(np.searchsorted(x, xi) - 1, 0, x.size - 2)
    t = ((xi - x[k]) / (x[k + 1] - x[k]))[:, None, None]
    return (1 - t) * Y[k] + t * Y[k + 1]
