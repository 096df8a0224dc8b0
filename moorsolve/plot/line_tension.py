"""Pictures of the lines' dynamic tension in a sea state: the tension spectra of every line
at its larger end, wave frequency and low frequency, beside the sea and the body's RAOs.

Each function takes a condition's line tensions (``ConditionResult.tensions``: line name to
:class:`moorsolve.dynamics.line_sea.LineSeaTension`) and an optional Axes, and returns the
Axes.
"""

from __future__ import annotations

import numpy as np

from .style import new_axes

__all__ = ["plot_tension_spectra", "sea_check_figure"]


def _end(t) -> int:
    """0 (anchor) or 1 (fairlead): the end with the larger tension sigma."""
    return int(t.fairlead.sigma_N >= t.anchor.sigma_N)


def plot_tension_spectra(tensions: dict, ax=None, *, part: str = "wf"):
    """Tension spectra [kN^2 s/rad] of every line at its end of larger sigma: ``wf`` the
    wave-frequency part, ``lf`` the low-frequency (slow-drift) part."""
    ax = new_axes(ax)
    for name, t in tensions.items():
        k = _end(t)
        if part == "wf":
            omega, spectrum = t.omega, t.wf_spectrum[k]
        elif t.lf_omega is not None:
            omega, spectrum = t.lf_omega, t.lf_spectrum[k]
        else:
            continue
        ax.plot(omega, np.asarray(spectrum) / 1e6, lw=1.0,
                label=f"{name} ({'fairlead' if k else 'anchor'})")
    what = "wave-frequency" if part == "wf" else "low-frequency"
    ax.set_title(f"line tension spectra, {what}", fontsize=10)
    ax.set_xlabel("omega [rad/s]")
    ax.set_ylabel("S_T [kN² s/rad]")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=6, ncol=2)
    return ax


def sea_check_figure(condition, body=None):
    """One figure of a condition checked with line dynamics: the wave spectrum, the body's
    RAOs and the lines' wave- and low-frequency tension spectra."""
    import matplotlib.pyplot as plt

    from .motions import plot_rao, plot_wave_spectrum
    m = condition.sea.motions
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), layout="constrained")
    plot_wave_spectrum(m, axes[0, 0])
    plot_rao(m, body, axes[0, 1])
    plot_tension_spectra(condition.tensions, axes[1, 0], part="wf")
    plot_tension_spectra(condition.tensions, axes[1, 1], part="lf")
    fig.suptitle(f"{condition.name}: sea state, motions and line tension", fontsize=11)
    return fig
