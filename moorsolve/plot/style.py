"""What every view of an equilibrium shares: the line colouring (T/MBL or tension),
its colour bar, marker styles and number formats."""

from __future__ import annotations

import math

import numpy as np

from .scene import Scene, scene_of

__all__ = ["LOAD_COLOURS", "POINT_STYLE", "SEABED", "WATER", "as_scene", "line_colours",
           "colour_bar", "new_axes", "nice", "si_force", "kn", "line_label"]

LOAD_COLOURS = {"wind": "tab:cyan", "current": "tab:green", "wave_drift": "tab:blue",
                 "force": "tab:purple", "total": "black"}
POINT_STYLE = {"clump": dict(marker="s", color="0.25", ms=6, label="clump weight"),
                "buoy": dict(marker="o", color="gold", mec="0.3", ms=7, label="buoy"),
                "joint": dict(marker=".", color="0.3", ms=6, label="joint"),
                "free": dict(marker="D", color="tab:purple", ms=6, label="free point")}
SEABED = "#b08d57"
WATER = "#dcecf7"


def as_scene(obj) -> Scene:
    return obj if isinstance(obj, Scene) else scene_of(obj)


def line_colours(scene: Scene):
    """``(colour_of(line), ScalarMappable, label)``: the colouring every view shares.

    T/MBL runs from 0 to the larger of 1 and the worst line, so an overloaded line
    is on the bar (never clipped to its end) and 1 (the MBL) is marked on it: green to red
    up to the MBL, red to dark purple beyond.
    """
    import matplotlib as mpl
    if scene.colour_by == "t_over_mbl":
        top = max([1.0] + [line.t_over_mbl for line in scene.lines])
        safe = mpl.colormaps["RdYlGn_r"]
        if top > 1.0:
            # Green to red up to the MBL, then red to dark purple beyond it: a line near
            # its MBL looks the same whatever the worst overload is.
            over = mpl.colors.LinearSegmentedColormap.from_list(
                "over", [safe(1.0), "#3b0030"])
            cmap = mpl.colors.ListedColormap(
                np.vstack([safe(np.linspace(0, 1, 128)), over(np.linspace(0, 1, 128))]),
                name="t_over_mbl")
            norm = mpl.colors.TwoSlopeNorm(vmin=0.0, vcenter=1.0, vmax=top)
        else:
            norm, cmap = mpl.colors.Normalize(0.0, 1.0), safe
        label = "T/MBL: largest tension / MBL"

        def value(line):
            return line.t_over_mbl
    else:
        top = max([1.0] + [line.tension_N / 1e3 for line in scene.lines])
        norm, cmap = mpl.colors.Normalize(0.0, top), mpl.colormaps["viridis"]
        label = "largest tension [kN]"

        def value(line):
            return line.tension_N / 1e3
    mappable = mpl.cm.ScalarMappable(norm=norm, cmap=cmap)
    return (lambda line: cmap(norm(value(line)))), mappable, label


def colour_bar(ax, scene: Scene, **kwargs):
    """The shared colour bar beside ``ax``; T/MBL marks the MBL at 1."""
    _, mappable, label = line_colours(scene)
    bar = ax.figure.colorbar(mappable, ax=ax, label=label, **kwargs)
    if scene.colour_by == "t_over_mbl":
        bar.ax.axhline(1.0, color="k", lw=1.5)
        bar.ax.text(0.5, 1.0, "MBL", transform=bar.ax.get_yaxis_transform(), ha="center",
                    va="bottom", fontsize=7)
    return bar


def new_axes(ax, projection=None, figsize=(8, 6)):
    import matplotlib.pyplot as plt
    if ax is not None:
        return ax
    fig = plt.figure(figsize=figsize, layout="constrained")
    return fig.add_subplot(projection=projection)


def nice(value: float) -> float:
    """The 1-2-5 number at or below ``value``."""
    if value <= 0:
        return 1.0
    exp = math.floor(math.log10(value))
    for m in (5, 2, 1):
        if m * 10**exp <= value:
            return m * 10**exp
    return 10**exp


def si_force(value_N: float) -> str:
    return f"{value_N / 1e6:g} MN" if value_N >= 1e6 else (
        f"{value_N / 1e3:g} kN" if value_N >= 1e3 else f"{value_N:g} N")


def kn(value_N: float) -> str:
    """A force in kN to three significant figures (thousands separated)."""
    kn = value_N / 1e3
    return f"{kn:,.0f} kN" if abs(kn) >= 100 else f"{kn:.3g} kN"


def line_label(line, scene: Scene) -> str:
    if scene.colour_by == "t_over_mbl":
        return f"{line.name}\n{line.t_over_mbl:.2f}"
    return f"{line.name}\n{line.tension_N / 1e3:.0f} kN"


