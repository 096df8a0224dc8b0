"""The fatigue damage of each sea state of the scatter diagram."""

from __future__ import annotations

import numpy as np

from .style import new_axes

__all__ = ["plot_damage_per_sea_state"]


def plot_damage_per_sea_state(fr, ends=None, ax=None):
    """Damage over the design life from each sea state (bars, one group per sea state)
    for the ``ends`` given as ``(line, end)`` pairs (default: the three most damaged), on
    a log scale; each sea state labelled ``Hs/Tp/toward`` with its probability.

    Parameters
    ----------
    fr : moorsolve.life.fatigue.FatigueResult
    ends : list of (str, str), optional
    ax : matplotlib Axes, optional

    Returns
    -------
    Axes
    """
    ax = new_axes(ax)
    if ends is None:
        chosen = sorted(fr.ends, key=lambda e: e.damage, reverse=True)[:3]
    else:
        index = {(e.line, e.end): e for e in fr.ends}
        chosen = [index[tuple(k)] for k in ends]
    n = len(fr.sea_states)
    x = np.arange(n)
    width = 0.8 / max(len(chosen), 1)
    for k, e in enumerate(chosen):
        ax.bar(x + (k - (len(chosen) - 1) / 2) * width, np.maximum(e.per_state, 1e-30),
               width, label=f"{e.line} {e.end}: D = {e.damage:.3g}, {e.life_y:.3g} y")
    labels = [f"{s[0]:g}/{s[1]:g}/{s[2]:g}\np {s[3]:.3g}" for s in fr.sea_states]
    ax.set_xticks(x)
    ax.set_xticklabels(labels, fontsize=7, rotation=90 if n > 12 else 0)
    ax.set_yscale("log")
    positive = [v for e in chosen for v in e.per_state if v > 0]
    if positive:
        ax.set_ylim(min(positive) / 3, max(positive) * 3)
    ax.set_xlabel("sea state: Hs m / Tp s / toward deg, probability")
    ax.set_ylabel(f"damage over {fr.design_life_y:.3g} y")
    ax.set_title(f"Fatigue damage per sea state ({fr.method.replace('_', ' ')}, "
                 f"DFF {fr.design_fatigue_factor:g})")
    ax.legend(fontsize=8)
    return ax
