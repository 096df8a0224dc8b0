"""A picture of the direction conventions: one wind, its four case-file spellings."""

from __future__ import annotations

import math

import numpy as np

from ..model.directions import Compass
from .style import new_axes

__all__ = ["plot_directions"]


def plot_directions(ax=None, *, from_bearing: float = 60.0, north_deg: float = 90.0):
    """Draw one flow coming from compass bearing ``from_bearing`` and the four ways a case
    file may give its direction (``toward_deg`` / ``from_deg``, mathematical / nautical).

    Parameters
    ----------
    ax : matplotlib Axes, optional
    from_bearing : float
        Where the flow comes from, clockwise from north [deg].
    north_deg : float
        Where north points, counter-clockwise from +x [deg] (``environment.north_deg``).

    Returns
    -------
    matplotlib Axes
    """
    ax = new_axes(ax, figsize=(7.5, 6.5))
    nautical = Compass("nautical", north_deg)
    toward = nautical.toward_deg(from_bearing, "from_deg")          # internal convention
    maths = Compass()
    r = 1.0
    ax.set_aspect("equal")
    ax.set_xlim(-1.75, 1.75)
    ax.set_ylim(-1.55, 1.6)
    ax.axis("off")
    ax.add_patch(_circle(r))
    for angle, label in ((0.0, "+x (east)"), (90.0, "+y")):
        t = math.radians(angle)
        ax.annotate("", xy=(1.12 * r * math.cos(t), 1.12 * r * math.sin(t)), xytext=(0, 0),
                    arrowprops=dict(arrowstyle="-|>", color="0.35", lw=1))
        ax.text(1.15 * r * math.cos(t) + 0.05, 1.15 * r * math.sin(t), label, ha="left",
                va="center", fontsize=9, color="0.35")
    tn = math.radians(north_deg)
    ax.text(1.4 * math.cos(tn), 1.4 * math.sin(tn), "N", fontsize=13, fontweight="bold",
            ha="center", va="center")
    # The flow: from the rim on its upwind side, through the centre, to the other rim.
    t_from = math.radians(toward + 180.0)
    start = np.array([math.cos(t_from), math.sin(t_from)]) * r
    ax.annotate("", xy=-start, xytext=start,
                arrowprops=dict(arrowstyle="-|>,head_width=0.5,head_length=1.0",
                                color="tab:cyan", lw=3.5))
    ax.text(*(start * 1.12), f"wind from {from_bearing:03.0f}", ha="center", va="center",
            fontsize=10, color="tab:cyan", fontweight="bold")
    # Mathematical: counter-clockwise from +x.
    _arc(ax, 0.0, toward, 0.35, "tab:blue")
    _arc(ax, 0.0, (toward + 180.0) % 360.0, 0.52, "tab:purple")
    # Nautical: clockwise from north.
    _arc(ax, north_deg, north_deg - nautical.file_value(toward, "toward_deg"), 0.70, "tab:red")
    _arc(ax, north_deg, north_deg - from_bearing, 0.86, "tab:orange")
    lines = [
        ("tab:blue", f"toward_deg: {maths.file_value(toward, 'toward_deg'):g}",
         "default: counter-clockwise from +x"),
        ("tab:purple", f"from_deg: {maths.file_value(toward, 'from_deg'):g}",
         "default: counter-clockwise from +x"),
        ("tab:red", f"toward_deg: {nautical.file_value(toward, 'toward_deg'):g}",
         "directions: nautical (clockwise from north)"),
        ("tab:orange", f"from_deg: {nautical.file_value(toward, 'from_deg'):g}",
         "directions: nautical (clockwise from north)"),
    ]
    for k, (colour, key, note) in enumerate(lines):
        ax.text(-1.72, -1.05 - 0.13 * k, key, color=colour, fontsize=10, fontweight="bold",
                family="monospace", va="center")
        ax.text(-0.55, -1.05 - 0.13 * k, note, color="0.2", fontsize=9, va="center")
    ax.set_title("One wind, four ways to write it (north along "
                 f"{'+y' if north_deg == 90 else f'{north_deg:g} deg from +x'})", fontsize=11)
    return ax


def _circle(r):
    from matplotlib.patches import Circle
    return Circle((0, 0), r, fill=False, ec="0.6", lw=0.8, ls=":")


def _arc(ax, start_deg: float, end_deg: float, radius: float, colour: str) -> None:
    """An arc from ``start_deg`` to ``end_deg`` (counter-clockwise from +x), arrow at its
    end, turning the short way for clockwise (decreasing) sweeps."""
    sweep = end_deg - start_deg
    if abs(sweep) > 360.0:
        sweep = math.copysign(abs(sweep) % 360.0, sweep)
    t = np.radians(start_deg + np.linspace(0.0, sweep, 80))
    ax.plot(radius * np.cos(t[:-3]), radius * np.sin(t[:-3]), color=colour, lw=1.8)
    ax.annotate("", xy=(radius * np.cos(t[-1]), radius * np.sin(t[-1])),
                xytext=(radius * np.cos(t[-4]), radius * np.sin(t[-4])),
                arrowprops=dict(arrowstyle="-|>", color=colour, lw=1.8))
