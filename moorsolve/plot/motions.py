"""Pictures of a sea state and the motions in it: spectra, A(w), B(w), |X(w)| and RAOs.

Each function takes a :class:`moorsolve.dynamics.motions.Motions`, an optional body name
(default the first moving body) and an optional Axes, and returns the Axes.
"""

from __future__ import annotations

import math

import numpy as np

from .style import new_axes

__all__ = ["plot_wave_spectrum", "plot_response_spectra", "plot_added_mass", "plot_damping",
           "plot_excitation", "plot_rao", "motions_figure"]

_UNITS = {"surge": "m", "sway": "m", "heave": "m", "roll": "deg", "pitch": "deg", "yaw": "deg"}
_DOFS = tuple(_UNITS)


def _body(m, body):
    return m.bodies[0] if body is None else m.body(body)


def _hydro(m, body):
    from ..dynamics.hydro import BodyHydro
    b = _body(m, body)
    return b, BodyHydro(m.hydrodynamics[b.name], b.name)


def plot_wave_spectrum(m, ax=None):
    """The sea state's spectrum S(w) [m^2 s/rad] over the computed frequencies."""
    ax = new_axes(ax)
    ax.plot(m.omega, m.spectrum, color="tab:blue")
    ax.fill_between(m.omega, m.spectrum, color="tab:blue", alpha=0.15)
    sea = m.sea
    title = f"{sea['spectrum']} Hs {sea['hs_m']:.3g} m"
    if sea.get("tp_s"):
        ax.axvline(2 * math.pi / sea["tp_s"], color="0.5", lw=0.8, ls="--")
        title += f", Tp {sea['tp_s']:.3g} s"
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("omega [rad/s]")
    ax.set_ylabel("S [m² s/rad]")
    return ax


def plot_response_spectra(m, body=None, ax=None):
    """Wave-frequency response spectra |X|^2 S of a body's free DOFs (translations [m^2
    s/rad] solid, rotations [deg^2 s/rad] dashed)."""
    ax = new_axes(ax)
    b = _body(m, body)
    for dof in b.dofs:
        k = _DOFS.index(dof)
        resp = np.abs(b.rao[:, k]) ** 2 * m.spectrum
        ax.plot(m.omega, resp, ls="--" if _UNITS[dof] == "deg" else "-",
                label=f"{dof} [{_UNITS[dof]}²s/rad]")
    ax.set_title(f"{b.name}: wave-frequency response spectra", fontsize=10)
    ax.set_xlabel("omega [rad/s]")
    ax.legend(fontsize=7)
    return ax


def _diagonal(ax, omega, values, title, unit):
    for k, dof in enumerate(_DOFS):
        v = values[:, k, k]
        if np.any(v != 0):
            ax.plot(omega, v, ls="--" if k >= 3 else "-", label=f"{dof} [{unit[k >= 3]}]")
    ax.set_yscale("symlog", linthresh=max(1.0, 1e-3 * float(np.abs(values).max() or 1)))
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("omega [rad/s]")
    ax.legend(fontsize=7)
    return ax


def plot_added_mass(m, body=None, ax=None):
    """The diagonal of A(w) as tabulated (translations [kg], rotations [kg m^2])."""
    ax = new_axes(ax)
    b, h = _hydro(m, body)
    return _diagonal(ax, h.omega, h.A, f"{b.name}: added mass A(w)", ("kg", "kg m²"))


def plot_damping(m, body=None, ax=None):
    """The diagonal of the radiation damping B(w) as tabulated."""
    ax = new_axes(ax)
    b, h = _hydro(m, body)
    return _diagonal(ax, h.omega, h.B, f"{b.name}: radiation damping B(w)",
                     ("N s/m", "N m s/rad"))


def plot_excitation(m, body=None, ax=None):
    """|X(w)|: the first-order wave force per unit amplitude at the body's heading."""
    ax = new_axes(ax)
    b, h = _hydro(m, body)
    X = h.excitation(h.omega, b.heading_deg)
    for k, dof in enumerate(_DOFS):
        if np.any(X[:, k] != 0):
            ax.plot(h.omega, np.abs(X[:, k]), ls="--" if k >= 3 else "-",
                    label=f"{dof} [{'N m/m' if k >= 3 else 'N/m'}]")
    ax.set_yscale("log")
    ax.set_title(f"{b.name}: |X(w)| at {b.heading_deg:.3g} deg", fontsize=10)
    ax.set_xlabel("omega [rad/s]")
    ax.legend(fontsize=7)
    return ax


def plot_rao(m, body=None, ax=None):
    """Response amplitude operators |X/A| of a body's free DOFs [m/m, deg/m]."""
    ax = new_axes(ax)
    b = _body(m, body)
    for dof in b.dofs:
        k = _DOFS.index(dof)
        ax.plot(m.omega, np.abs(b.rao[:, k]), ls="--" if k >= 3 else "-",
                label=f"{dof} [{_UNITS[dof]}/m]")
    ax.set_title(f"{b.name}: RAOs (waves at {b.heading_deg:.3g} deg)", fontsize=10)
    ax.set_xlabel("omega [rad/s]")
    ax.legend(fontsize=7)
    return ax


def motions_figure(m, body=None):
    """One figure: wave spectrum, response spectra, A(w), B(w), |X(w)| and RAOs."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 2, figsize=(11, 11), layout="constrained")
    plot_wave_spectrum(m, axes[0, 0])
    plot_response_spectra(m, body, axes[0, 1])
    plot_added_mass(m, body, axes[1, 0])
    plot_damping(m, body, axes[1, 1])
    plot_excitation(m, body, axes[2, 0])
    plot_rao(m, body, axes[2, 1])
    return fig
