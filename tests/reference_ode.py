"""Independent reference for one mooring leg: integrate the line's static equilibrium ODE.

Written from the equilibrium of a flexible, elastic line element (Merkin 1980, seed 004,
sections 2.1 and 2.3) and deliberately shares nothing with ``moorsolve.physics``: no closed
forms, no asinh, no regime switches copied from the leg block. The test compares the two.

Along the unstretched arc length ``s`` (0 at the anchor, ``L`` at the fairlead) the state
is the position ``(x, z)`` relative to the anchor and the effective tension ``(Tx, Tz)``
that the line beyond ``s`` (toward the fairlead) exerts on the line before it.

Suspended element (weight ``w`` per unstretched metre, Hooke's law with stiffness ``EA``, or
any strain law ``eps(T)`` given as a plain Python function: then ``1 + eps(T)`` replaces
``1 + T/EA`` below)::

    dTx/ds = 0,   dTz/ds = w,
    dx/ds = (1 + T/EA) Tx/T,   dz/ds = (1 + T/EA) Tz/T,   T = sqrt(Tx^2 + Tz^2)

Grounded element (lying on a flat seabed at the anchor's level, which carries its weight)::

    z = 0,  Tz = 0,  dx/ds = 1 + Tx/EA,
    dTx/ds = mu w while Tx > 0   (Coulomb friction fully mobilised toward the anchor)
    Tx = 0 beyond                 (the rest lies unloaded)

The fairlead end forces ``(H, V)`` are the given state, so the problem is an initial-value
problem from the fairlead end; it is integrated with ``s`` running from ``L`` down to 0
(still measured from the anchor) and the anchor-end state is read off at ``s = 0``. From the
anchor end the same problem is not an initial-value problem: where a grounded, friction-
relieved line starts to carry tension is fixed by the fairlead, not by the anchor.

Touchdown is where ``Tz`` falls to zero going down the line (contact legs only). Because
``Tz`` is linear in ``s`` its zero is a known breakpoint; the integration is split there and
at the catenary's vertex so that the sharp turn of a nearly slack line (width ``H/w``) sits
at the end of an interval, where the step-size control resolves it.

A slack line (``H = 0``) hangs straight down to touchdown; what lies on the seabed has no
tension and no definite shape, so the reference lays it straight: ``x`` at the anchor is
then the laid length, and the loose part is the caller's business.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicHermiteSpline, PchipInterpolator

RTOL = 1e-13


def _stretch_factor(ea, strain):
    """``T -> ds/ds0``: Hooke's ``1 + T/EA`` (1 without EA), or ``1 + strain(T)``."""
    if strain is not None:
        return lambda t: 1.0 + strain(t)
    c = 0.0 if ea is None else 1.0 / ea
    return lambda t: 1.0 + t * c


def _suspended_rhs(w, ea, strain=None):
    factor = _stretch_factor(ea, strain)

    def rhs(s, y):
        x, z, tx, tz = y
        t = math.hypot(tx, tz)
        stretch = factor(t)
        if t == 0.0:
            return [0.0, 0.0, 0.0, w]
        return [stretch * tx / t, stretch * tz / t, 0.0, w]
    return rhs


def _integrate(rhs, s0, s1, y0, scale):
    """Integrate from s0 to s1 (either direction) at tight tolerance; returns the end state."""
    if s0 == s1:
        return np.array(y0, float)
    atol = np.array([1e-16 * scale[0], 1e-16 * scale[0], 1e-16 * scale[1], 1e-16 * scale[1]])
    sol = solve_ivp(rhs, (s0, s1), y0, method="DOP853", rtol=RTOL, atol=atol,
                    first_step=min(abs(s1 - s0), 1e-9 * scale[0]) or None)
    if sol.status != 0:
        raise RuntimeError(f"ODE integration failed: {sol.message}")
    return sol.y[:, -1]


def integrate_leg(*, H, V, L, w, ea=None, mu=0.0, contact=True, strain=None,
                  strain_max=None, tension_breaks=()):
    """Integrate one leg from its fairlead end forces down to the anchor.

    Parameters
    ----------
    H, V : float
        Horizontal (>= 0) and vertical tension at the fairlead [N].
    L : float
        Unstretched length [m].
    w : float
        Submerged weight per unstretched metre [N/m]; negative for a buoyant line.
    ea : float or None
        Axial stiffness [N]; None for an inextensible line.
    mu : float
        Seabed friction coefficient (contact legs only).
    contact : bool
        The anchor lies on the seabed and the line may rest on it (needs w > 0).
    strain : callable, optional
        A strain law ``T [N] -> eps [-]`` replacing Hooke's (``ea`` is then unused).
    strain_max : float, optional
        The largest strain on the line (for the integrator's length scale) when ``strain``
        is given.
    tension_breaks : sequence of float
        Tensions [N] where the strain law's higher derivatives jump (a table's rows): the
        integration is split where the suspended line's tension passes them.

    Returns
    -------
    dict
        ``X``, ``Z``: fairlead position relative to the anchor [m] (for a slack line X is
        measured with the grounded part laid straight); ``HA``, ``VA``: tension components
        at the anchor [N] (VA is the upward pull on the anchor, signed); ``grounded``:
        unstretched length on the seabed [m].
    """
    t_scale = max(math.hypot(H, V), abs(w) * L, 1e-300)
    if strain is not None:
        stretch_max = strain_max if strain_max is not None else strain(t_scale + abs(w) * L)
    else:
        stretch_max = 0.0 if ea is None else (t_scale + abs(w) * L) / ea
    scale = (L * (1.0 + stretch_max), t_scale)
    rhs = _suspended_rhs(w, ea, strain)
    factor = _stretch_factor(ea, strain)
    # Fairlead at the origin of this local frame; the anchor end's coordinates are
    # relative to it and the span is minus them at the end.
    y = np.array([0.0, 0.0, float(H), float(V)])

    touch = None
    if contact and w > 0 and V < w * L:
        touch = L - V / w            # Tz(s) = V - w (L - s) reaches 0 here
    s_end = 0.0 if touch is None else max(touch, 0.0)

    # Breakpoints: the vertex of the catenary (Tz = 0) inside the suspended interval.
    breaks = [L]
    if w != 0.0:
        vertex = L - V / w
        if s_end < vertex < L:
            breaks.append(vertex)
        # Tz(s) = V - w (L - s); the tension passes T_k where Tz = +-sqrt(T_k^2 - H^2).
        for tk in tension_breaks:
            if tk > H:
                for tz in (math.sqrt(tk * tk - H * H), -math.sqrt(tk * tk - H * H)):
                    s_k = L - (V - tz) / w
                    if s_end < s_k < L:
                        breaks.append(s_k)
    breaks = sorted(set(breaks), reverse=True)
    if breaks[-1] != s_end:
        breaks.append(s_end)
    for a, b in zip(breaks[:-1], breaks[1:]):
        y = _integrate(rhs, a, b, y, scale)
    # Exact values for the force components (their equations are trivially integrable;
    # this just removes the integrator's round-off from the comparison).
    y[2] = H
    y[3] = V - w * (L - s_end)

    grounded = 0.0
    if touch is not None:
        grounded = s_end
        tx = float(H)
        if grounded > 0:
            if mu > 0 and tx > 0:
                # Friction: Tx falls by mu w per metre toward the anchor until it is zero.
                def ground_rhs(s, yy):
                    return [factor(max(yy[1], 0.0)), mu * w]

                atol = [1e-16 * scale[0], 1e-16 * scale[1]]
                # The tension falls linearly along the seabed, so where it is used up is
                # known: s_zero (at or below 0: it reaches the anchor). The integration
                # stops there rather than find it as an event: a step across the kink of
                # max(T, 0) loses digits (4e-6 m of 14 m, seen by a hypothesis run). It is
                # also split where the tension passes the strain law's breakpoints (a
                # table's rows), as above.
                s_zero = grounded - tx / (mu * w)
                stop = max(s_zero, 0.0)
                cuts = [grounded] + sorted(
                    (grounded - (tx - tk) / (mu * w) for tk in tension_breaks
                     if 0.0 < tk < tx and stop < grounded - (tx - tk) / (mu * w) < grounded),
                    reverse=True) + [stop]
                state = [y[0], tx]
                for a, b in zip(cuts[:-1], cuts[1:]):
                    sol = solve_ivp(ground_rhs, (a, b), state, method="DOP853",
                                    rtol=RTOL, atol=atol)
                    state = [sol.y[0, -1], sol.y[1, -1]]
                if s_zero > 0:                # tension used up before the anchor
                    y[0] = state[0] - s_zero  # the rest lies unloaded, unstretched
                    tx = 0.0
                else:
                    y[0] = state[0]
                    tx = max(state[1], 0.0)
            else:
                def ground_rhs(s, yy):
                    return [factor(tx)]
                sol = solve_ivp(ground_rhs, (grounded, 0.0), [y[0]], method="DOP853",
                                rtol=RTOL, atol=[1e-16 * scale[0]])
                y[0] = sol.y[0, -1]
        y[2], y[3] = tx, 0.0
    return dict(X=-y[0], Z=-y[1], HA=y[2], VA=y[3], grounded=grounded)


def integrate_from_anchor(*, HA, VA, L, w, ea=None, float_length=0.0, n=0, strain=None,
                          strain_max=None, tension_breaks=()):
    """Integrate a line from its anchor end, for a line that may lie along a boundary.

    Written for lines bounded by the free surface (a buoyant line, ``w < 0``), and general:
    at the anchor the line pulls the anchor with ``(HA, VA)`` (``VA`` upward positive), so
    the tension the rest of the line exerts at ``s = 0`` is ``(Tx, Tz) = (HA, VA)``; along a
    suspended element ``dTz/ds = w`` as in :func:`integrate_leg`. Where ``Tz`` reaches zero
    (the vertex, ``s_v = -VA / w``) and ``float_length > 0``, the line lies along a horizontal
    boundary at the vertex's height for ``float_length`` (unstretched) metres: ``Tz = 0``,
    ``dx/ds = 1 + Tx/EA``, ``Tx`` constant (no friction); then it is suspended again, with
    ``Tz = w (s - s_v - float_length)``. A slack line (``HA = 0``) is laid straight along the
    boundary (the loose part is the caller's business, as in :func:`integrate_leg`).
    ``strain``, ``strain_max``, ``tension_breaks``: a strain law as in :func:`integrate_leg`.

    From the anchor this is an initial-value problem for a buoyant line: whether the vertex
    lies on the surface is what the caller checks (it sets the anchor's depth to the
    vertex height for a floating line).

    Returns
    -------
    dict
        ``X``, ``Z``: the far end relative to the anchor [m]; ``HF``, ``VF``: the force the
        far end exerts on the line (``(Tx, Tz)`` at ``s = L``) [N]; ``z_vertex``,
        ``x_vertex``: where ``Tz`` first vanishes (None if it does not within the line);
        ``z_max``, ``z_min``: the highest and lowest heights reached; with ``n > 0`` also
        ``s``, ``x``, ``z`` sampled at ``n`` points.
    """
    t_scale = max(math.hypot(HA, VA), abs(w) * L, 1e-300)
    if strain is not None:
        stretch_max = strain_max if strain_max is not None else strain(t_scale + abs(w) * L)
    else:
        stretch_max = 0.0 if ea is None else (t_scale + abs(w) * L) / ea
    scale = (L * (1.0 + stretch_max), t_scale)
    factor = _stretch_factor(ea, strain)
    rhs = _suspended_rhs(w, ea, strain)
    s_v = -VA / w if w != 0.0 else math.inf
    has_vertex = 0.0 < s_v < L
    s_f = min(s_v + float_length, L) if has_vertex and float_length > 0.0 else s_v

    def tz(s):
        """The vertical tension, exactly (it is linear between the breakpoints)."""
        if not has_vertex or s <= s_v:
            return VA + w * s
        return 0.0 if s <= s_f else w * (s - s_f)

    breaks = [0.0] + ([s_v, s_f] if has_vertex else []) + [L]
    # Where the suspended line's tension passes a law's breakpoint T_k (Tz = +-sqrt(T_k^2 -
    # HA^2)): before the vertex Tz = VA + w s, after the boundary Tz = w (s - s_f).
    runs = [(0.0, s_v if has_vertex else L, lambda t_z: (t_z - VA) / w)]
    if has_vertex:
        runs.append((s_f, L, lambda t_z: s_f + t_z / w))
    for tk in tension_breaks:
        if tk > HA and w != 0.0:
            r = math.sqrt(tk * tk - HA * HA)
            breaks += [at(t_z) for lo, hi, at in runs for t_z in (r, -r) if lo < at(t_z) < hi]
    breaks = sorted(set(breaks))
    samples = np.linspace(0.0, L, n) if n else np.zeros(0)
    xs, zs = np.full(samples.shape, np.nan), np.full(samples.shape, np.nan)
    y = np.array([0.0, 0.0, float(HA), float(VA)])
    heights = [0.0]
    vertex = None
    for s0, s1 in zip(breaks[:-1], breaks[1:]):
        if s1 <= s0:
            continue
        inside = (samples >= s0) & (samples <= s1)
        if has_vertex and s0 == s_v and s1 == s_f:
            # On the boundary: horizontal, constant tension.
            x0 = y[0]
            xs[inside] = x0 + (samples[inside] - s0) * factor(HA)
            zs[inside] = y[1]
            y = np.array([x0 + (s1 - s0) * factor(HA), y[1], float(HA), 0.0])
            continue
        if inside.any():
            sol = solve_ivp(rhs, (s0, s1), y, method="DOP853", rtol=RTOL,
                            atol=[1e-16 * scale[0]] * 2 + [1e-16 * scale[1]] * 2,
                            t_eval=samples[inside])
            xs[inside], zs[inside] = sol.y[0], sol.y[1]
        y = _integrate(rhs, s0, s1, y, scale)
        y[2], y[3] = HA, tz(s1)
        # Tz keeps its sign inside a piece, so the height is monotone there: the extremes
        # are at the breakpoints.
        heights.append(y[1])
        if has_vertex and s1 == s_v:
            vertex = (y[0], y[1])
    out = dict(X=y[0], Z=y[1], HF=float(HA), VF=tz(L), z_max=max(heights),
               z_min=min(heights), x_vertex=None if vertex is None else vertex[0],
               z_vertex=None if vertex is None else vertex[1])
    if n:
        out.update(s=samples, x=xs, z=zs)
    return out


def integrate_to_slope(*, H, V, L, w, t, ea=None, mu=0.0):
    """A sinking leg whose anchor lies on a seabed of slope ``t`` (rise per metre along the
    leg, anchor toward fairlead), integrated from the fairlead end forces ``(H, V)``.

    The suspended part runs down from the fairlead until its direction is the seabed's
    (``Tz = H t``): there it touches down, tangentially, and the rest lies on the slope. Along
    the slope the tension changes by ``w (sin(theta) + mu cos(theta))`` per metre toward the
    anchor (weight along the slope, friction fully mobilised toward the anchor), never below
    zero; the line stretches by ``T/EA``.

    Returns ``X``, ``Z`` (fairlead relative to the anchor), ``TA`` (anchor tension, along the
    slope), ``grounded`` and the touchdown point ``x_td``, ``z_td`` relative to the anchor.
    """
    c = 0.0 if ea is None else 1.0 / ea
    rhs = _suspended_rhs(w, ea)
    t_scale = max(math.hypot(H, V), abs(w) * L)
    scale = (L * (1.0 + t_scale * c), t_scale)
    s_td = L - (V - H * t) / w            # Tz = V - w (L - s) reaches H t here
    y = _integrate(rhs, L, max(s_td, 0.0), [0.0, 0.0, float(H), float(V)], scale)
    grounded = max(s_td, 0.0)
    sec = math.sqrt(1.0 + t * t)
    cos_t, sin_t = 1.0 / sec, t / sec
    k = w * (sin_t + mu * cos_t)
    T = H * sec if grounded > 0 else math.hypot(H, V - w * L)

    def ground(s, yy):
        tension = max(yy[1], 0.0)
        return [1.0 + tension * c, k]

    if grounded > 0:
        sol = solve_ivp(ground, (grounded, 0.0), [0.0, T], method="DOP853", rtol=RTOL,
                        atol=[1e-16 * scale[0], 1e-16 * scale[1]], max_step=grounded / 50)
        along, T = -sol.y[0, -1], max(sol.y[1, -1], 0.0)
    else:
        along = 0.0
    # Fairlead relative to the touchdown is minus the end state; the touchdown relative to
    # the anchor is ``along`` metres up the slope.
    x_td, z_td = along * cos_t, along * sin_t
    return dict(X=x_td - y[0], Z=z_td - y[1], TA=T, grounded=grounded, x_td=x_td, z_td=z_td)


def integrate_in_current(*, H, V, L, w, ea, diameter, rho, normal, tangential, velocity,
                         z_fairlead):
    """A line in a current in its vertical plane, integrated from the fairlead end forces.

    ``velocity(z)`` is the current's speed along +x at height ``z`` (signed: a current
    that reverses with depth). Per unstretched metre the line carries its weight ``w`` and
    the flow force on its stretched length ``(1 + T/EA)``: ``(rho d/2)(C_n |U_n| U_n +
    C_t |U_t| U_t)`` (Merkin 1980, seed 004, chapter 5). With ``T(s)`` the force the line
    beyond ``s`` exerts, ``dT/ds = -q``; ``dr/ds = (1 + T/EA) T/|T|``. Integrated from
    ``s = L`` (the fairlead, at height ``z_fairlead``) to 0; returns the fairlead's position
    relative to the anchor ``X``, ``Z`` and the anchor force ``HA``, ``VA`` (the line's pull).
    """
    c = 0.0 if ea is None else 1.0 / ea
    q = rho * diameter / 2

    def rhs(s, y):
        x, z, tx, tz = y
        T = math.hypot(tx, tz)
        ex, ez = tx / T, tz / T
        u = velocity(z_fairlead + z)
        along = u * ex
        un = (u - along * ex, -along * ez)
        un_mag = math.hypot(*un)
        stretch = 1.0 + T * c
        fx = q * (normal * un_mag * un[0] + tangential * abs(along) * along * ex) * stretch
        fz = q * (normal * un_mag * un[1] + tangential * abs(along) * along * ez) * stretch
        return [stretch * ex, stretch * ez, -fx, -(fz - w)]

    sol = solve_ivp(rhs, (L, 0.0), [0.0, 0.0, float(H), float(V)], method="DOP853",
                    rtol=1e-12, atol=1e-12 * max(L, math.hypot(H, V)))
    if sol.status != 0:
        raise RuntimeError(f"ODE integration failed: {sol.message}")
    x, z, tx, tz = sol.y[:, -1]
    return dict(X=-x, Z=-z, HA=tx, VA=tz)


def integrate_through_surface(*, H, V, L, w_water, w_air, z_top, ea=None, strain=None):
    """A suspended line whose upper end is ``z_top`` above the still-water level: weight
    ``w_air`` per unstretched metre above z = 0 and ``w_water`` below, integrated from the
    upper end's forces ``(H, V)`` down the whole length (no seabed). The crossing of the
    surface is found as an event and the integration restarted there with the other weight.

    Returns ``X``, ``Z`` (the upper end relative to the lower) and ``VA`` (the line's upward
    pull on its lower end); where the line crosses the surface also ``air_length`` (its
    unstretched length above it), ``x_air`` (the horizontal extent of that part) and
    ``V_surface`` (the vertical tension at the crossing). ``strain``: a strain law as in
    :func:`integrate_leg` (``ea`` is then unused).
    """
    factor = _stretch_factor(ea, strain)

    def rhs_for(w):
        def rhs(s, y):
            x, z, tx, tz = y
            T = math.hypot(tx, tz)
            return [factor(T) * tx / T, factor(T) * tz / T, 0.0, w]
        return rhs

    def crossing(s, y):
        return y[1]
    crossing.terminal = True
    y0 = [0.0, float(z_top), float(H), float(V)]
    scale = max(L, abs(z_top))
    sol = solve_ivp(rhs_for(w_air), (L, 0.0), y0, method="DOP853", rtol=RTOL,
                    atol=[1e-16 * scale] * 2 + [1e-16 * max(abs(V), H)] * 2, events=crossing)
    crossed = {}
    if sol.status == 1:
        s_c = sol.t_events[0][0]
        y_c = sol.y_events[0][0]
        crossed = dict(air_length=L - s_c, x_air=-y_c[0], V_surface=y_c[3])
        sol = solve_ivp(rhs_for(w_water), (s_c, 0.0), y_c, method="DOP853", rtol=RTOL,
                        atol=[1e-16 * scale] * 2 + [1e-16 * max(abs(V), H)] * 2)
    x, z, tx, tz = sol.y[:, -1]
    return dict(X=-x, Z=z_top - z, VA=tz, **crossed)


def integrate_air_and_water(*, H, V, L, w_water, w_air, z_top, ea=None, strain=None):
    """A suspended line from its upper end, ``z_top`` above the still-water level, down its
    whole length: weight ``w_air`` per unstretched metre wherever the line is above z = 0
    and ``w_water`` below, however often it crosses (each crossing is an event; the
    integration restarts there with the other weight). No seabed.

    Returns ``X``, ``Z`` (the upper end relative to the lower), ``VA`` (the line's upward
    pull on its lower end), ``crossings`` (the unstretched arc lengths from the upper end
    where the line crosses z = 0) and ``air_length`` (its unstretched length above it).
    """
    factor = _stretch_factor(ea, strain)

    def rhs_for(w):
        def rhs(s, y):
            x, z, tx, tz = y
            T = math.hypot(tx, tz)
            return [factor(T) * tx / T, factor(T) * tz / T, 0.0, w]
        return rhs

    y = [0.0, float(z_top), float(H), float(V)]
    s, above, crossings, air = L, z_top > 0, [], 0.0
    scale = max(L, abs(z_top))
    atol = [1e-16 * scale] * 2 + [1e-16 * max(abs(V), H)] * 2
    while s > 0:
        def crossing(t, yy):
            return yy[1]
        crossing.terminal = True
        # Integrating toward s = 0: from above the water z falls through 0, from below it
        # rises (the restart at z = 0 is not a crossing of the sought direction).
        crossing.direction = -1 if above else 1
        sol = solve_ivp(rhs_for(w_air if above else w_water), (s, 0.0), y, method="DOP853",
                        rtol=RTOL, atol=atol, events=crossing)
        if sol.status == 1 and sol.t_events[0][0] < s:
            s_c = sol.t_events[0][0]
            y = list(sol.y_events[0][0])
            y[1] = 0.0
            air += (s - s_c) if above else 0.0
            crossings.append(L - s_c)
            s, above = s_c, not above
        else:
            air += s if above else 0.0
            y = list(sol.y[:, -1])
            s = 0.0
    x, z, tx, tz = y
    return dict(X=-x, Z=z_top - z, VA=tz, crossings=crossings, air_length=air)


# ---- a tension-strain table as a plain function ---------------------------------------------


def reference_interpolant(strain, tension):
    """The table law by scipy: PCHIP's slopes, taken as they are wherever positive; an end
    slope scipy sets to 0 or nearly (below 1e-9 of its secant) is
    ``min(delta^2 / d_next, 3 delta)`` instead (moorsolve's documented rule, so that the
    rope is not rigid beyond the table)."""
    T, e = np.asarray(tension, float), np.asarray(strain, float)
    d = PchipInterpolator(T, e).derivative()(T)
    if len(T) > 2:
        delta = np.diff(e) / np.diff(T)
        for i, (m0, dn) in ((0, (delta[0], d[1])), (-1, (delta[-1], d[-2]))):
            if not d[i] > 1e-9 * m0:
                d[i] = min(m0 * m0 / dn, 3 * m0)
    return CubicHermiteSpline(T, e, d)


def linear_table_reference(strain, tension):
    """A table joined by chords (MoorDyn's reading of a curve file) as a plain function:
    ``numpy.interp`` inside, the last chord continued beyond the last row."""
    slope = (strain[-1] - strain[-2]) / (tension[-1] - tension[-2])

    def f(T):
        if T <= tension[-1]:
            return float(np.interp(T, tension, strain))
        return strain[-1] + slope * (T - tension[-1])
    return f


def table_reference(strain, tension):
    """The table law as a plain function: the interpolant, linear beyond the last row."""
    spline = reference_interpolant(strain, tension)
    slope = float(spline.derivative()(tension[-1]))

    def f(T):
        if T <= tension[-1]:
            return float(spline(T))
        return strain[-1] + slope * (T - tension[-1])
    return f
