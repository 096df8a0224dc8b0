"""WAMIT's non-dimensional hydrodynamic coefficients made dimensional (SI).

WAMIT (User Manual v7, section 4 "Definitions of output quantities") writes, with ``L`` the
length scale ``ULEN``, ``rho`` the water density, ``g`` gravity and ``A`` the wave amplitude:

- added mass ``A_ij = Abar_ij rho L^k`` and damping ``B_ij = Bbar_ij rho L^k omega``, with
  ``k = 3`` for two translations, 4 for a translation and a rotation, 5 for two rotations;
- first-order exciting force ``X_i = Xbar_i rho g A L^m``, ``m = 2`` (force) or 3 (moment);
- mean drift force ``F_i = Fbar_i rho g A^2 L^m``, ``m = 1`` (force) or 2 (moment).

Its time dependence is ``Re{X e^{+i omega t}}``, the tables' own, so phases pass unchanged.
"""

from __future__ import annotations

import numpy as np


def _k(i: int, j: int) -> int:
    return 3 + (i >= 3) + (j >= 3)


#: Exponent of L per entry of a 6x6 coefficient.
K_EXPONENT = np.array([[_k(i, j) for j in range(6)] for i in range(6)])
#: Exponent of L of the exciting force per mode, and of the mean drift force.
X_EXPONENT = np.array([2, 2, 2, 3, 3, 3])
DRIFT_EXPONENT = np.array([1, 1, 1, 2, 2, 2])


def dimensional(values: dict, ulen: float, rho: float, g: float) -> dict:
    """Table-form hydrodynamics (``omega``, ``added_mass``, ``damping``, ``excitation``,
    ``mean_drift``) in SI from WAMIT's non-dimensional ``values`` of the same form."""
    omega = np.asarray(values["omega"], dtype=float)
    scale = rho * float(ulen) ** K_EXPONENT
    out = {"omega": omega.tolist(),
           "added_mass": (np.asarray(values["added_mass"], dtype=float) * scale).tolist(),
           "damping": (np.asarray(values["damping"], dtype=float) * scale
                       * omega[:, None, None]).tolist()}
    xs = rho * g * float(ulen) ** X_EXPONENT
    out["excitation"] = [{"heading_deg": h["heading_deg"],
                          "re": (np.asarray(h["re"], dtype=float) * xs).tolist(),
                          "im": (np.asarray(h["im"], dtype=float) * xs).tolist()}
                         for h in values["excitation"]]
    if values.get("mean_drift"):
        ds = rho * g * float(ulen) ** DRIFT_EXPONENT
        out["mean_drift"] = [{"heading_deg": h["heading_deg"],
                              "values": (np.asarray(h["values"], dtype=float) * ds).tolist()}
                             for h in values["mean_drift"]]
    return out


def non_dimensional(table: dict, ulen: float, rho: float, g: float) -> dict:
    """The inverse of :func:`dimensional` (for writing WAMIT files)."""
    omega = np.asarray(table["omega"], dtype=float)
    scale = rho * float(ulen) ** K_EXPONENT
    out = {"omega": omega.tolist(),
           "added_mass": (np.asarray(table["added_mass"], dtype=float) / scale).tolist(),
           "damping": (np.asarray(table["damping"], dtype=float) / scale
                       / omega[:, None, None]).tolist()}
    xs = rho * g * float(ulen) ** X_EXPONENT
    out["excitation"] = [{"heading_deg": h["heading_deg"],
                          "re": (np.asarray(h["re"], dtype=float) / xs).tolist(),
                          "im": (np.asarray(h["im"], dtype=float) / xs).tolist()}
                         for h in table["excitation"]]
    ds = rho * g * float(ulen) ** DRIFT_EXPONENT
    out["mean_drift"] = [{"heading_deg": h["heading_deg"],
                          "values": (np.asarray(h["values"], dtype=float) / ds).tolist()}
                         for h in table.get("mean_drift") or ()]
    return out
