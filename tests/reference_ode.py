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

                def exhausted(s, yy):
                    return yy[1]
                exhausted.terminal = True
                atol = [1e-16 * scale[0], 1e-16 * scale[1]]
                sol = solve_ivp(ground_rhs, (grounded, 0.0), [y[0], tx], method="DOP853",
                                rtol=RTOL, atol=atol, events=exhausted)
                if sol.status == 1:           # tension used up before the anchor
                    s_zero = sol.t_events[0][0]
                    x_zero = sol.y_events[0][0][0]
                    y[0] = x_zero - s_zero    # the rest lies unloaded, unstretched
                    tx = 0.0
                else:
                    y[0] = sol.y[0, -1]
                    tx = max(sol.y[1, -1], 0.0)
            else:
                def ground_rhs(s, yy):
                    return [factor(tx)]
                sol = solve_ivp(ground_rhs, (grounded, 0.0), [y[0]], method="DOP853",
                                rtol=RTOL, atol=[1e-16 * scale[0]])
                y[0] = sol.y[0, -1]
        y[2], y[3] = tx, 0.0
    return dict(X=-y[0], Z=-y[1], HA=y[2], VA=y[3], grounded=grounded)
