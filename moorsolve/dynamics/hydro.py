"""A body's hydrodynamic coefficients as functions of frequency and wave heading.

The case gives them at tabulated frequencies and headings
(:class:`~moorsolve.model.sea.Hydrodynamics`); here they are interpolated linearly, in
frequency within the table (never extrapolated: the motions are computed on the table's
range) and in heading between the two nearest given headings (the real and imaginary parts
of the excitation separately). A heading outside the given ones is refused by name, unless
the table goes round the compass at its own spacing (the gap from its last heading back to
its first is no wider than its widest step), when it is interpolated across 360 deg.
"""

from __future__ import annotations

import numpy as np

from ..errors import CaseError


class BodyHydro:
    """Numpy arrays of one body's hydrodynamics, with interpolation.

    Parameters
    ----------
    hydro : moorsolve.model.sea.Hydrodynamics
    path : str
        The case-file path of the body's ``hydrodynamics`` (for messages).
    """

    def __init__(self, hydro, path: str):
        self.path = path
        self.omega = np.asarray(hydro.omega, dtype=float)
        self.A = np.asarray(hydro.added_mass, dtype=float)
        self.B = np.asarray(hydro.damping, dtype=float)
        self.x_headings = np.array([e.heading_deg for e in hydro.excitation])
        self.X = np.array([np.asarray(e.re) + 1j * np.asarray(e.im) for e in hydro.excitation])
        self.d_headings = np.array([d.heading_deg for d in hydro.mean_drift])
        self.D = (np.array([np.asarray(d.values, dtype=float) for d in hydro.mean_drift])
                  if hydro.mean_drift else None)

    @property
    def has_drift(self) -> bool:
        return self.D is not None

    def _in_omega(self, w):
        return np.clip(np.asarray(w, dtype=float), self.omega[0], self.omega[-1])

    def _interp_omega(self, table, w):
        """``table`` (n, ...) at frequencies ``w`` (m,) -> (m, ...), linear."""
        w = self._in_omega(w)
        k = np.clip(np.searchsorted(self.omega, w) - 1, 0, self.omega.size - 2)
        t = (w - self.omega[k]) / (self.omega[k + 1] - self.omega[k])
        t = t.reshape((-1,) + (1,) * (table.ndim - 1))
        return (1 - t) * table[k] + t * table[k + 1]

    def added_mass(self, w) -> np.ndarray:
        """A(w) [kg, kg m, kg m^2], shape (m, 6, 6)."""
        return self._interp_omega(self.A, w)

    def damping(self, w) -> np.ndarray:
        """B(w) [N s/m, ...], shape (m, 6, 6)."""
        return self._interp_omega(self.B, w)

    def added_mass_low(self) -> np.ndarray:
        """A at the lowest tabulated frequency: the slow drift's A(0)."""
        return self.A[0]

    def _heading_weights(self, headings, beta: float, field: str) -> list:
        """``[(index, weight), ...]`` interpolating the headings at ``beta`` [deg]."""
        h = headings
        b = (beta - h[0]) % 360.0 + h[0]          # beta in [h0, h0 + 360)
        near = np.isclose(h, b, atol=1e-9) | np.isclose(h + 360.0, b, atol=1e-9)
        if near.any():
            return [(int(np.argmax(near)), 1.0)]
        if h.size > 1 and b <= h[-1]:
            k = int(np.searchsorted(h, b)) - 1
            t = (b - h[k]) / (h[k + 1] - h[k])
            return [(k, 1 - t), (k + 1, t)]
        gap = h[0] + 360.0 - h[-1]
        if h.size > 1 and gap <= np.max(np.diff(h)) + 1e-9:
            t = (b - h[-1]) / gap
            return [(h.size - 1, 1 - t), (0, t)]
        given = ", ".join(f"{v:g}" for v in h)
        raise CaseError(f"{self.path}.{field}",
                        f"the waves travel toward {beta % 360.0:.4g} deg relative to the "
                        f"body's x axis, outside the headings given ({given} deg); give "
                        "that heading (or headings either side of it)")

    def excitation(self, w, beta_deg: float) -> np.ndarray:
        """First-order force per unit amplitude at ``w`` for waves travelling toward
        ``beta_deg`` relative to body x, shape (m, 6) complex [N/m, N m/m]."""
        out = 0
        for k, t in self._heading_weights(self.x_headings, beta_deg, "excitation"):
            out = out + t * self._interp_omega(self.X[k], w)
        return out

    def drift(self, w, beta_deg: float) -> np.ndarray:
        """Mean drift force per amplitude squared, shape (m, 6) [N/m^2, N m/m^2]; zeros
        without a ``mean_drift`` table."""
        if self.D is None:
            return np.zeros((np.size(w), 6))
        out = 0
        for k, t in self._heading_weights(self.d_headings, beta_deg, "mean_drift"):
            out = out + t * self._interp_omega(self.D[k], w)
        return out


def table_mapping(omega, added_mass, damping, excitation: dict, mean_drift: dict | None = None,
                  digits: int = 6) -> dict:
    """A body's ``hydrodynamics: {source: table, ...}`` case-file mapping from arrays (the
    inverse of what :class:`BodyHydro` reads), each number to ``digits`` significant digits.

    Parameters
    ----------
    omega : array_like (n,)
        Frequencies [rad/s].
    added_mass, damping : array_like (n, 6, 6)
        Per frequency [kg, kg m, kg m^2] and [N s/m, ...].
    excitation : dict
        Heading [deg] to the complex first-order force per unit amplitude (n, 6) [N/m, N m/m],
        phase ``e^{+i w t}``.
    mean_drift : dict, optional
        Heading [deg] to the mean drift force per amplitude squared (n, 6) [N/m^2].
    """
    def rows(arr) -> list:
        # "+ 0.0" turns a -0.0 into 0.0 (a case file reads better without signed zeros).
        return [[float(f"{v:.{digits}g}") + 0.0 for v in row] for row in np.atleast_2d(arr)]

    out = {"source": "table", "omega": [round(float(v), digits) for v in omega],
           "added_mass": [rows(m) for m in np.asarray(added_mass, float)],
           "damping": [rows(m) for m in np.asarray(damping, float)],
           "excitation": [{"heading_deg": float(h), "re": rows(np.real(x)),
                           "im": rows(np.imag(x))} for h, x in excitation.items()]}
    if mean_drift:
        out["mean_drift"] = [{"heading_deg": float(h), "values": rows(d)}
                             for h, d in mean_drift.items()]
    return out
