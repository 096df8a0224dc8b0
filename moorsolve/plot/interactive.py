"""An interactive 3-D view of an equilibrium for notebooks (plotly: ``moorsolve[interactive]``).

The same :class:`~.scene.Scene` the static views draw: lines coloured by utilisation (or
tension without an MBL) with their values on hover, anchors and bollards, the bodies' hulls
as prisms, quay walls, piles and fenders, the seabed and the still-water plane. The vertical
scale is exaggerated by the factor in the title, as in :func:`~.views.plot_3d`.
"""

from __future__ import annotations

import numpy as np

from .style import as_scene, line_colours, nice

__all__ = ["plot_3d_interactive"]


def _rgb(colour) -> str:
    r, g, b = (int(round(255 * c)) for c in colour[:3])
    return f"rgb({r},{g},{b})"


def _prism(shape, thin: float):
    """Vertices and triangles (i, j, k) of a body shape's prism (a thin slab when its height
    is not known)."""
    bottom, top = shape.bottom, shape.top
    if top - bottom < thin:
        bottom, top = bottom - thin / 2, top + thin / 2
    ring = shape.ring
    n = len(ring)
    xyz = np.vstack([np.column_stack([ring, np.full(n, bottom)]),
                     np.column_stack([ring, np.full(n, top)])])
    tri = []
    for k in range(1, n - 1):                       # bottom and top: fans (convex rings)
        tri += [(0, k, k + 1), (n, n + k, n + k + 1)]
    for k in range(n):                              # sides
        a, b = k, (k + 1) % n
        tri += [(a, b, n + b), (a, n + b, n + a)]
    return xyz, np.array(tri)


def plot_3d_interactive(result):
    """An interactive 3-D view (a ``plotly.graph_objects.Figure``; show it in a notebook or
    write it with ``fig.write_html``).

    Parameters
    ----------
    result : Result or Scene

    Returns
    -------
    plotly.graph_objects.Figure

    Raises
    ------
    ImportError
        Without plotly (``pip install moorsolve[interactive]``).
    """
    try:
        import plotly.graph_objects as go
    except ImportError as exc:       # an optional extra: say how to get it
        raise ImportError("the interactive view needs plotly: "
                          "pip install 'moorsolve[interactive]'") from exc
    from .plan import FIXED_STYLE
    scene = as_scene(result)
    colour, _, label = line_colours(scene)
    lo, hi = scene.extent()
    pad = 0.04 * max(hi[0] - lo[0], hi[1] - lo[1], 1.0)
    gx = np.linspace(lo[0] - pad, hi[0] + pad, 20)
    gy = np.linspace(lo[1] - pad, hi[1] + pad, 20)
    X, Y = np.meshgrid(gx, gy)
    Z = scene.seabed_z(X, Y)
    zlow, ztop = float(np.min(Z)), max(0.0, float(hi[2]))
    height = ztop - zlow
    horizontal = float(max(gx[-1] - gx[0], gy[-1] - gy[0]))
    gain = max(1.0, nice(0.3 * horizontal / height)) if height > 0 else 1.0
    traces = [go.Surface(x=X, y=Y, z=Z, colorscale=[[0, "#b08d57"], [1, "#b08d57"]],
                         opacity=0.35, showscale=False, name="seabed", hoverinfo="skip"),
              go.Surface(x=X[[0, -1]][:, [0, -1]], y=Y[[0, -1]][:, [0, -1]],
                         z=np.zeros((2, 2)), colorscale=[[0, "#9cc7e6"], [1, "#9cc7e6"]],
                         opacity=0.15, showscale=False, name="still water", hoverinfo="skip")]
    unit = "utilisation" if scene.colour_by == "utilisation" else "kN"
    for line in scene.lines:
        value = (f"{line.utilisation:.2f}" if unit == "utilisation"
                 else f"{line.tension_N / 1e3:.0f} kN")
        traces.append(go.Scatter3d(
            x=line.xyz[:, 0], y=line.xyz[:, 1], z=line.xyz[:, 2], mode="lines",
            line=dict(color=_rgb(colour(line)), width=5, dash="dot" if line.slack else "solid"),
            name=f"{line.name} {value}", hovertemplate=f"{line.name}: {value}<br>"
            "x %{x:.1f} m, y %{y:.1f} m, z %{z:.1f} m<extra></extra>"))
    for kind, symbol in (("anchor", "diamond"), ("bollard", "circle"), ("fixed", "square")):
        ends = [line.xyz[0] for line in scene.lines if line.a_kind == kind]
        ends += [line.xyz[-1] for line in scene.lines if line.b_kind == kind]
        if ends:
            ends = np.array(ends)
            traces.append(go.Scatter3d(x=ends[:, 0], y=ends[:, 1], z=ends[:, 2], mode="markers",
                                       marker=dict(symbol=symbol, size=4, color="black"),
                                       name=FIXED_STYLE[kind]["label"]))
    thin = 0.01 * max(height, 1.0)
    for body in scene.bodies:
        for shape in body.shapes:
            if len(shape.ring) < 3:
                continue
            xyz, tri = _prism(shape, thin)
            traces.append(go.Mesh3d(x=xyz[:, 0], y=xyz[:, 1], z=xyz[:, 2], i=tri[:, 0],
                                    j=tri[:, 1], k=tri[:, 2], color="gray", opacity=0.6,
                                    name=f"{body.name} ({shape.source})"))
    for wall in scene.berth.walls:
        (x0, y0), (x1, y1) = wall.ends
        traces.append(go.Mesh3d(x=[x0, x1, x1, x0], y=[y0, y1, y1, y0],
                                z=[zlow, zlow, wall.top, wall.top], i=[0, 0], j=[1, 2],
                                k=[2, 3], color="lightgray", opacity=0.5,
                                name=f"{wall.name} (wall)"))
    for pile in scene.berth.piles:
        traces.append(go.Scatter3d(x=[pile.xy[0]] * 2, y=[pile.xy[1]] * 2, z=[zlow, pile.top],
                                   mode="lines", line=dict(color="black", width=8),
                                   name=pile.name))
    if scene.berth.fenders:
        f = np.array([x.xyz for x in scene.berth.fenders])
        traces.append(go.Scatter3d(
            x=f[:, 0], y=f[:, 1], z=f[:, 2], mode="markers+text", name="fenders",
            text=[x.name for x in scene.berth.fenders],
            marker=dict(symbol="square", size=5, cmin=0, cmax=1, colorscale="RdYlGn_r",
                        color=[x.utilisation or 0.0 for x in scene.berth.fenders])))
    fig = go.Figure(traces)
    fig.update_layout(
        title=f"{scene.title}: 3-D view (vertical x{gain:g}; lines: {label})",
        scene=dict(xaxis_title="x [m]", yaxis_title="y [m]", zaxis_title="z [m]",
                   aspectmode="manual",
                   aspectratio=dict(x=(gx[-1] - gx[0]) / horizontal,
                                    y=(gy[-1] - gy[0]) / horizontal,
                                    z=gain * height / horizontal)),
        margin=dict(l=0, r=0, t=40, b=0), legend=dict(itemsizing="constant"))
    return fig
