"""One mooring leg: the elastic catenary with seabed contact, friction, uplift and slack.

The leg lies in the vertical plane through its anchor (end A) and fairlead (end F). Given the
spans ``X`` (horizontal) and ``Z`` (vertical, fairlead above anchor) it is described by two
unknowns: a signed tension variable ``u`` and the vertical tension at the fairlead ``V``.
``H = max(u, 0)`` is the horizontal tension; ``-u / w`` (when ``u < 0``) is the length of line
lying loose on the seabed, so that ``H * loose = 0`` holds exactly and the slack state (H = 0:
the line hangs straight down from the fairlead and the rest lies on the seabed) is one
branch of a single continuous model instead of a case the solver must guess.

Every regime of REFERENCE.md section 1 is selected inside the symbolic graph with
``casadi.if_else``, never a Python ``if`` on a value, so one CasADi function serves every leg
and every solve and evaluates on floats for post-processing.

Seabed friction assumption
--------------------------
Coulomb friction with coefficient ``mu`` is taken *fully mobilised toward the anchor* on
the whole grounded length (the line has been dragged taut, as after pretensioning): the
tension on the seabed falls off as ``H - mu w s`` from the touchdown point, reaching the
anchor as ``H_A = max(H - mu w L_B, 0)``. It changes the anchor load and the elastic
stretch of the grounded part; an inextensible line's shape does not depend on it. The
opposite "as laid" assumption (no friction relief) is ``mu = 0``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import casadi as ca
import numpy as np

from .contact import fischer_burmeister

#: Horizontal tension [N] below which asinh arguments are capped; H itself stays exact.
_H_FLOOR = 1e-9


@dataclass(frozen=True)
class LegKind:
    """Which physics a leg needs: decided by the case at build time.

    Attributes
    ----------
    elastic : bool
        The line has an axial stiffness; otherwise the inextensible equations are built.
    contact : bool
        The line can rest on the seabed (sinking line, anchor on the seabed).
    friction : bool
        Seabed friction acts on the grounded length (needs ``contact``).
    neutral : bool
        Neutrally buoyant line (w = 0): straight when taut, loose otherwise.
    sloped : bool
        The anchor rests on a sloped seabed (:func:`sloped_leg_equations`; needs ``contact``).
    """

    elastic: bool
    contact: bool
    friction: bool = False
    neutral: bool = False
    sloped: bool = False

    @property
    def tag(self) -> str:
        parts = ["elastic" if self.elastic else "inextensible"]
        if self.neutral:
            parts.append("neutral")
        elif self.contact:
            parts.append("contact")
            if self.friction:
                parts.append("friction")
            if self.sloped:
                parts.append("sloped")
        else:
            parts.append("suspended")
        return "_".join(parts)


def leg_equations(kind: LegKind, X, Z, u, V, L, w, ea_inv, mu):
    """Residuals and end forces of one leg, symbolic or numeric.

    Parameters
    ----------
    kind : LegKind
        Physics to build (a Python-level choice: structure, not values).
    X, Z : float or casadi symbol
        Horizontal and vertical span from anchor to fairlead [m].
    u : float or casadi symbol
        Signed tension variable [N]: ``H = max(u, 0)``; ``u < 0`` is slack.
    V : float or casadi symbol
        Vertical tension at the fairlead [N] (upward force the fairlead exerts on the line).
    L : float or symbol
        Unstretched length [m].
    w : float or symbol
        Submerged weight per unstretched length [N/m] (negative: buoyant).
    ea_inv : float or symbol
        Compliance 1/EA [1/N] (unused for inextensible kinds).
    mu : float or symbol
        Seabed friction coefficient [-] (unused without friction).

    Returns
    -------
    dict
        ``rX``, ``rZ``: span residuals [m] (zero at a solution); ``H`` horizontal tension
        at the fairlead [N]; ``V`` vertical tension at the fairlead [N]; ``HA``, ``VA``
        horizontal and vertical (upward pull, signed) force on the anchor [N];
        ``grounded`` unstretched length on the seabed [m]; ``suspended_x`` horizontal
        extent of the suspended part [m].

    Notes
    -----
    REFERENCE.md section 1 (after Merkin 1980, seed 004, sections 2.1 and 2.3; Malacic,
    seed 002). Suspended (``V_A = V - w L >= 0``)::

        X = (H/w)[asinh(V/H) - asinh(V_A/H)] + H L/EA
        Z = [sqrt(H^2+V^2) - sqrt(H^2+V_A^2)]/w + (L/EA)(V - w L/2)

    Touchdown (``V_A < 0``), grounded length ``L_B = L - V/w``::

        X = L_B + (H/w) asinh(V/H) + H L/EA + friction term
        Z = sgn(V)[sqrt(H^2+V^2) - H]/w + V|V|/(2 EA w)

    The ``sgn(V)`` form removes the mirrored false root at ``V = -w L_s`` that the even
    textbook form has once ``H = 0`` is admitted.
    """
    H = ca.fmax(u, 0)
    if kind.neutral:
        return _neutral_equations(kind, X, Z, u, V, L, ea_inv)

    Hg = ca.fmax(H, _H_FLOOR)
    VA = V - w * L
    stretch = H * L * ea_inv if kind.elastic else 0

    # asinh(V/H) - asinh(VA/H) loses eps*asinh(V/H) to cancellation when V and VA have the
    # same sign (a nearly taut line: H/w times that can exceed the span tolerance); there
    # it equals asinh(w L (V + VA) / (V T_A + VA T_F)), which has none.
    TF, TA = ca.sqrt(Hg**2 + V**2), ca.sqrt(Hg**2 + VA**2)
    same_side = V * VA > 0
    dasinh = ca.if_else(same_side,
                        ca.asinh(w * L * (V + VA) / ca.if_else(same_side, V * TA + VA * TF, 1)),
                        ca.asinh(V / Hg) - ca.asinh(VA / Hg))
    Xs = (H / w) * dasinh + stretch
    # [sqrt(H^2+V^2) - sqrt(H^2+VA^2)]/w without the cancellation that loses eps*H/w
    # on a nearly taut line (V - VA = w L); the denominator is at least |w| L.
    Zs = L * (V + VA) / (ca.sqrt(H**2 + V**2) + ca.sqrt(H**2 + VA**2))
    if kind.elastic:
        Zs = Zs + L * ea_inv * (V - w * L / 2)

    if not kind.contact:
        # No seabed under the line: one catenary whatever the sign of V_A.
        return dict(rX=Xs - X, rZ=Zs - Z, H=H, VF=V, HA=H, VA=VA,
                    grounded=0 * H, suspended_x=Xs)

    loose = ca.fmax(-u, 0) / w
    LB = L - V / w
    Xsusp_t = (H / w) * ca.asinh(V / Hg)
    Xt = LB + Xsusp_t + stretch
    # sgn(V)[sqrt(H^2+V^2) - H]/w, written without cancellation for V << H.
    Zt = V * ca.fabs(V) / (w * ca.fmax(ca.sqrt(H**2 + V**2) + H, _H_FLOOR))
    if kind.elastic:
        Zt = Zt + ea_inv * V * ca.fabs(V) / (2 * w)
        Xsusp_t = Xsusp_t + H * (V / w) * ea_inv
    if kind.friction:
        # Tension decays by mu*w per metre along the grounded length, from H at touchdown.
        # Where it would reach zero before the anchor (L_B > H/(mu w)) the rest is unloaded.
        excess = LB - H / (mu * w)
        if kind.elastic:
            Xt = Xt + (mu * w * ea_inv / 2) * (-LB**2 + excess * ca.fmax(excess, 0))
        HA_t = ca.fmax(H - mu * w * LB, 0)
    else:
        HA_t = H

    suspended = VA >= 0
    Xc = ca.if_else(suspended, Xs, Xt)
    Zc = ca.if_else(suspended, Zs, Zt)
    return dict(
        rX=Xc - X - loose,
        rZ=Zc - Z,
        H=H,
        VF=V,
        HA=ca.if_else(suspended, H, HA_t),
        VA=ca.fmax(VA, 0),
        grounded=ca.if_else(suspended, 0, LB),
        suspended_x=ca.if_else(suspended, Xs, Xsusp_t),
    )


def _neutral_equations(kind, X, Z, u, V, L, ea_inv, stiffness=1.0, smoothing=0.0):
    """A weightless line (a hawser): straight at tension ``T = u`` when taut, loose otherwise.

    The tension and the slack are complementary (:mod:`moorsolve.physics.contact`)::

        T >= 0,   b = L (1 + T/EA) - D >= 0,   T b = 0

    (``D`` the chord), imposed by the Fischer-Burmeister residual ``rX = phi(T/k, b)`` [m]
    with ``k = stiffness`` [N/m]. The tension is the unknown, not a signed variable whose
    negative half is the slack: a body held only by slack hawsers then still feels them, so
    a load draws them taut (the signed form left the body's balance independent of every
    unknown while slack, and the solvers stopped there). ``rZ = (V D - T Z) / k`` [m] makes
    the end force lie along the chord. ``smoothing`` is the Jacobian smoothing ``eps`` [m]
    of the solvers (0: exact).
    """
    T = u
    D = ca.sqrt(X**2 + Z**2)
    stretched = L * (1 + T * ea_inv) if kind.elastic else L
    opening = stretched - D
    H = T * X / ca.fmax(D, _H_FLOOR)
    rX = fischer_burmeister(T / stiffness, opening, smoothing)
    return dict(rX=rX, rZ=(V * D - T * Z) / stiffness, H=H, VF=V, HA=H, VA=V, grounded=0 * T,
                suspended_x=X)


LEG_OUTPUTS = ("rX", "rZ", "H", "VF", "HA", "VA", "grounded", "suspended_x")
LEG_INPUTS = ("X", "Z", "u", "V", "L", "w", "ea_inv", "mu")


@lru_cache(maxsize=None)
def leg_function(kind: LegKind) -> ca.Function:
    """The leg block for ``kind`` as one ``casadi.Function``, built once and reused.

    Inputs ``(X, Z, u, V, L, w, ea_inv, mu)``, outputs ``LEG_OUTPUTS``; see
    :func:`leg_equations`. Call it on SX/MX symbols to embed it, or on floats.
    """
    args = [ca.SX.sym(n) for n in LEG_INPUTS]
    out = leg_equations(kind, *args)
    return ca.Function(f"leg_{kind.tag}", args, [out[k] for k in LEG_OUTPUTS],
                       list(LEG_INPUTS), list(LEG_OUTPUTS))


def evaluate_leg(kind: LegKind, X, Z, u, V, L, w, ea_inv=0.0, mu=0.0) -> dict:
    """Evaluate the leg block on floats; returns a dict of floats (``LEG_OUTPUTS``)."""
    vals = leg_function(kind)(X, Z, u, V, L, w, ea_inv, mu)
    return {k: float(v) for k, v in zip(LEG_OUTPUTS, vals)}


WEIGHTLESS_INPUTS = ("X", "Z", "u", "V", "L", "ea_inv", "k", "eps")


@lru_cache(maxsize=None)
def weightless_line_function(elastic: bool) -> ca.Function:
    """The weightless line block as a ``casadi.Function``: inputs :data:`WEIGHTLESS_INPUTS`
    (``k`` the contact stiffness scale [N/m], ``eps`` the Jacobian smoothing [m]), outputs
    :data:`LEG_OUTPUTS`; see :func:`_neutral_equations`."""
    args = [ca.SX.sym(n) for n in WEIGHTLESS_INPUTS]
    X, Z, u, V, L, ea_inv, k, eps = args
    out = _neutral_equations(LegKind(elastic, contact=False, neutral=True), X, Z, u, V, L,
                             ea_inv, k, eps)
    return ca.Function(f"weightless_{'elastic' if elastic else 'inextensible'}", args,
                       [out[n] for n in LEG_OUTPUTS], list(WEIGHTLESS_INPUTS),
                       list(LEG_OUTPUTS))


# ---- starting point of a leg (floats) ---------------------------------------------------


def _bisect(f, lo, hi, iters=200):
    """Root of an increasing function on [lo, hi] by bisection in log space."""
    flo = f(lo)
    if flo > 0:
        return lo
    for _ in range(iters):
        mid = np.sqrt(lo * hi)
        if f(mid) > 0:
            hi = mid
        else:
            lo = mid
        if hi / lo < 1 + 1e-10:
            break
    return np.sqrt(lo * hi)


def initial_state(kind: LegKind, X: float, Z: float, L: float, w: float,
                  ea: float | None) -> tuple[float, float]:
    """A starting ``(u, V)`` for one leg from the inextensible closed forms.

    Slack when the line is long enough to hang straight down and reach the anchor along the
    seabed; touchdown when a grounded length remains; suspended otherwise; a straight
    stretched line when the chord exceeds the length.
    """
    D = float(np.hypot(X, Z))
    if kind.neutral:
        # The tension of a straight line: stretched when the chord exceeds the length,
        # otherwise slack (zero; an inextensible line just reaching starts at D - L).
        if D >= L and ea:
            T = ea * (D / L - 1)
            return T, T * Z / max(D, 1e-12)
        return max(D - L, 0.0), 0.0
    aw = abs(w)
    if D >= L * (1 - 1e-9):
        # Taut: straight stretched line carrying half its weight at each end.
        T = (ea * (D / L - 1) if ea else 0.0) + aw * L
        return T * X / max(D, 1e-12), T * Z / max(D, 1e-12) + w * L / 2
    if kind.contact and X <= L - Z:
        return -w * (L - Z - X), w * Z
    if kind.contact:
        # Touchdown: find H with L_B + suspended span = X, while the suspended part fits in L.
        def span(H):
            Ls = np.sqrt(Z**2 + 2 * Z * H / w)
            return L - Ls + (H / w) * np.arcsinh(w * Ls / H) - X
        H_max = w * (L**2 - Z**2) / (2 * Z)
        if span(H_max) >= 0:
            H = _bisect(span, 1e-9 * w * L, H_max)
            return H, w * np.sqrt(Z**2 + 2 * Z * H / w)
    # Suspended: sqrt(L^2 - Z^2) = 2 (H/|w|) sinh(|w| X / (2 H)) for the chord's sag.
    target = np.sqrt(max(L**2 - Z**2, 0.0))
    if X <= 0:
        return 0.0, w * L if w > 0 else 0.0

    def chord(H):
        return target - 2 * (H / aw) * np.sinh(min(aw * X / (2 * H), 700))
    H = _bisect(chord, 1e-12 * aw * L + 1e-12, 1e3 * aw * L + aw * X)
    V = (w / 2) * (Z / np.tanh(w * X / (2 * H)) + L)
    return H, V


# ---- profile along the line (floats) ----------------------------------------------------


def leg_profile(kind: LegKind, *, H: float, V: float, L: float, w: float,
                ea: float | None, mu: float, X: float, Z: float = 0.0,
                n: int = 101) -> dict:
    """Points and tension along a solved leg, in its vertical plane, from the anchor.

    Parameters
    ----------
    kind : LegKind
    H, V : float
        Horizontal and vertical tension at the fairlead [N] (the solved state).
    L, w, ea, mu : float
        Length [m], submerged weight [N/m], stiffness [N] (None: inextensible), friction.
    X, Z : float
        Horizontal and vertical span [m]: where a slack line's loose part ends, and the
        chord of a weightless line.
    n : int
        Number of points.

    Returns
    -------
    dict of numpy arrays
        ``s`` unstretched arc length from the anchor [m], ``x`` horizontal distance from the
        anchor [m], ``z`` height above the anchor [m], ``tension`` effective tension [N].

    Notes
    -----
    With ``T_v(s)`` the vertical tension at arc length s, the suspended part follows
    ``x = (H/w)[asinh(T_v/H) - asinh(T_v0/H)] + H s/EA`` and
    ``z = [sqrt(H^2+T_v^2) - sqrt(H^2+T_v0^2)]/w + (T_v0 s + w s^2/2)/EA``
    (Merkin 1980, seed 004, section 2.3, integrated from the lowest suspended point).
    """
    c = 1.0 / ea if ea else 0.0
    s = np.linspace(0.0, L, n)
    if kind.neutral:
        # Straight along the chord when taut; a loose weightless line has no definite
        # shape, so it is drawn along the chord as well.
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    if not kind.contact or VA >= 0:
        return _hanging_profile(s, H, VA, w, c)
    LB = L - V / w
    grounded = s <= LB
    Tv = np.where(grounded, 0.0, w * (s - LB))
    sg = np.minimum(s, LB)
    # Tension on the seabed: H at touchdown, decaying by friction toward the anchor.
    Tg = np.maximum(H - mu * w * (LB - sg), 0.0) if mu > 0 else np.full_like(s, H)
    if H > 0:
        stretch_g = _grounded_stretch(H, w, mu, LB, sg, c)
        x_td = sg + stretch_g
        xs = (H / w) * np.arcsinh(Tv / H) + H * (s - sg) * c
        zs = (np.hypot(H, Tv) - H) / w + Tv**2 / (2 * w) * c
        x_touch = LB + _grounded_stretch(H, w, mu, LB, np.array([LB]), c)[0]
        x = np.where(grounded, x_td, x_touch + xs)
        z = np.where(grounded, 0.0, zs)
        tension = np.where(grounded, Tg, np.hypot(H, Tv))
    else:
        # Slack: the hanging part is vertical under the fairlead, the rest lies loose
        # (buckled) between anchor and the fairlead's foot: shown straight along the seabed.
        x = np.where(grounded, np.minimum(sg, X), X)
        z = np.where(grounded, 0.0, Tv / w + Tv**2 / (2 * w) * c)
        tension = np.where(grounded, 0.0, Tv)
    return dict(s=s, x=x, z=z, tension=tension)


def _grounded_stretch(H, w, mu, LB, sg, c):
    """Elastic stretch accumulated from the anchor to arc length ``sg`` on the seabed."""
    if c == 0:
        return np.zeros_like(sg)
    if mu <= 0:
        return H * sg * c
    # T(s) = max(H - mu w (LB - s), 0); integrate T/EA from 0 to sg.
    s0 = max(LB - H / (mu * w), 0.0)            # where the tension starts to rise
    a = np.clip(sg, s0, None)
    integral = np.where(sg > s0, (H - mu * w * LB) * (a - s0) + mu * w * (a**2 - s0**2) / 2, 0.0)
    return integral * c


# ---- segments of a multi-segment leg ----------------------------------------------------
#
# In a leg of several segments every joint is a free node. The horizontal tension is the same
# in every segment (joints carry only vertical loads: a clump, a buoy, the seabed's reaction),
# so one signed variable ``u`` serves the whole leg and each segment adds its top vertical
# tension ``V``. A segment whose lower end is the anchor on the seabed is the leg block above;
# the others use the blocks below.

#: Square of a vertical force [N^2] under which the descent force is taken through its
#: linear form, so that derivatives stay finite at a lower end resting on the seabed.
_T_FLOOR = 1e-24

LIFTED_INPUTS = ("X", "Z", "h", "u", "V", "L", "w", "ea_inv", "mu")
SEGMENT_OUTPUTS = ("rX", "rZ", "H", "VF", "HA", "VA", "grounded", "suspended_x", "descent_x")


def descent_force(H, h, w, ea_inv):
    """Vertical force at a lifted end whose line runs down to touch a flat seabed.

    A line that leaves its lower end (``h`` above the seabed) downward reaches the seabed
    tangentially where its vertical tension is zero; over the descent the vertical tension
    rises linearly by ``w`` per metre from ``V1`` (negative) to 0. With Hooke stretch the drop
    is ``h = (sqrt(H^2 + V1^2) - H)/w + V1^2/(2 w EA)``, a quadratic in ``V1^2``; its root
    (written without cancellation) is returned as ``V1 = -sqrt(t)`` [N].

    Notes
    -----
    With ``d = w h (w h + 2 H)``, ``a = w h + H`` and ``c = 1/EA``:
    ``t = 2 d / (1 + a c + sqrt(1 + 2 a c + c^2 H^2))``, which is ``d`` when ``c = 0``
    (Merkin 1980, seed 004, section 2.1: ``z = (sqrt(H^2 + T_v^2) - H)/w`` from the vertex).
    """
    d = w * h * (w * h + 2 * H)
    a = w * h + H
    c = ea_inv
    t = 2 * d / (1 + a * c + ca.sqrt(1 + 2 * a * c + c**2 * H**2))
    return -t / ca.sqrt(ca.fmax(t, _T_FLOOR))


def _hyp(a, b):
    """``sqrt(a^2 + b^2)`` floored by 1e-9 N so that its derivative exists at (0, 0)."""
    return ca.sqrt(a**2 + b**2 + _H_FLOOR**2)


def lifted_segment_equations(elastic: bool, X, Z, h, u, V, L, w, ea_inv, mu=0,
                             friction: bool = False):
    """A sinking segment whose lower end is ``h >= 0`` above a flat seabed.

    The generalisation of :func:`leg_equations` (contact kind, no friction) to a lower end
    that need not rest on the seabed: a joint lifted by a buoy, an anchor on a pile. Three
    regimes, chosen in the graph:

    - suspended (``V_A >= V1(h)``): one catenary, which may dip below its lower end without
      reaching the seabed (the S between a buoy and a fairlead);
    - two-sided touchdown (``V_A < V1``): the line runs down from the lower end to the seabed
      (vertical force ``V1`` from :func:`descent_force`), lies on it for ``L_B`` and rises to the
      upper end (the U under a buoyed joint, or a line between two points on the seabed);
    - slack (``u < 0``): as in the leg block, ``-u / w`` of loose line lies on the seabed.

    With ``h = 0`` it is the touchdown/suspended leg block (square roots are floored by
    1e-9 N so that derivatives exist at H = V = 0, a grounded joint of a slack leg). With
    ``friction`` (only for a lower end fixed on the seabed, ``h = 0``) the grounded tension
    decays toward the lower end as in :func:`leg_equations`.

    Returns
    -------
    dict
        ``SEGMENT_OUTPUTS``: span residuals ``rX``, ``rZ`` [m]; ``H``; ``VF`` the top vertical
        tension; ``HA`` and ``VA`` the horizontal and (signed, upward positive) vertical pull
        on the lower end [N]; ``grounded`` [m]; ``suspended_x`` horizontal extent of the part
        rising to the upper end [m]; ``descent_x`` horizontal extent of the descent [m].
    """
    H = ca.fmax(u, 0)
    Hg = ca.fmax(H, _H_FLOOR)
    c = ea_inv if elastic else 0
    VA = V - w * L
    V1 = descent_force(H, h, w, c)
    Xs = (H / w) * (ca.asinh(V / Hg) - ca.asinh(VA / Hg)) + H * L * c
    Zs = (_hyp(H, V) - _hyp(H, VA)) / w + L * c * (V - w * L / 2)
    s1 = -V1 / w
    x1 = (H / w) * ca.asinh(-V1 / Hg) + H * s1 * c
    LB = L - s1 - V / w
    x_rise = (H / w) * ca.asinh(V / Hg) + H * (V / w) * c
    Xt = x1 + LB * (1 + H * c) + x_rise
    Zt = -h + ca.sign(V) * (_hyp(H, V) - _hyp(H, 0)) / w + c * V * ca.fabs(V) / (2 * w)
    HA_t = H
    if friction:
        excess = LB - H / (mu * w)
        if elastic:
            Xt = Xt + (mu * w * c / 2) * (-LB**2 + excess * ca.fmax(excess, 0))
        HA_t = ca.fmax(H - mu * w * LB, 0)
    loose = ca.fmax(-u, 0) / w
    suspended = VA >= V1
    return dict(
        rX=ca.if_else(suspended, Xs, Xt) - X - loose,
        rZ=ca.if_else(suspended, Zs, Zt) - Z,
        H=H, VF=V, HA=ca.if_else(suspended, H, HA_t),
        VA=ca.if_else(suspended, VA, V1),
        grounded=ca.if_else(suspended, 0, LB),
        suspended_x=ca.if_else(suspended, Xs, x_rise),
        descent_x=ca.if_else(suspended, 0, x1),
    )


def straight_segment_equations(elastic: bool, X, Z, u, V, L, ea_inv):
    """A weightless segment inside a multi-segment leg: straight, ``H = max(u, 0)``.

    Its tension ``T = sqrt(H^2 + V^2)`` is the same at both ends and its direction is the
    chord's: ``X = H L (1/T + 1/EA)``, ``Z = V L (1/T + 1/EA)``. With ``H = 0`` it hangs
    vertical under the joint loads. (A weightless segment with no tension at all has no
    definite shape; the model does not represent it.)
    """
    H = ca.fmax(u, 0)
    T = ca.sqrt(H**2 + V**2 + _H_FLOOR**2)
    k = L * (1 / T + (ea_inv if elastic else 0))
    return dict(rX=H * k - X, rZ=V * k - Z, H=H, VF=V, HA=H, VA=V, grounded=0 * H,
                suspended_x=X, descent_x=0 * H)


@lru_cache(maxsize=None)
def lifted_segment_function(elastic: bool, friction: bool = False) -> ca.Function:
    """:func:`lifted_segment_equations` as a ``casadi.Function`` (inputs ``LIFTED_INPUTS``)."""
    args = [ca.SX.sym(n) for n in LIFTED_INPUTS]
    out = lifted_segment_equations(elastic, *args, friction=friction)
    tag = ("elastic" if elastic else "inextensible") + ("_friction" if friction else "")
    return ca.Function(f"segment_lifted_{tag}", args,
                       [out[k] for k in SEGMENT_OUTPUTS], list(LIFTED_INPUTS),
                       list(SEGMENT_OUTPUTS))


@lru_cache(maxsize=None)
def straight_segment_function(elastic: bool) -> ca.Function:
    """:func:`straight_segment_equations` as a ``casadi.Function``."""
    names = ("X", "Z", "u", "V", "L", "ea_inv")
    args = [ca.SX.sym(n) for n in names]
    out = straight_segment_equations(elastic, *args)
    return ca.Function(f"segment_straight_{'elastic' if elastic else 'inextensible'}", args,
                       [out[k] for k in SEGMENT_OUTPUTS], list(names), list(SEGMENT_OUTPUTS))


def segment_profile(*, H: float, V: float, L: float, w: float, ea: float | None, h: float,
                    X: float, Z: float, n: int = 51) -> dict:
    """Points and tension along one segment from its lower end, in the leg's plane.

    Covers every regime of :func:`lifted_segment_equations` (``h`` may be 0) and of a
    suspended or weightless segment (``w <= 0``); see :func:`leg_profile` for the output.
    The vertical tension is ``T_v(s) = V_A + w s`` on a suspended segment; on a two-sided
    touchdown it runs from ``V1`` to 0 on the descent, is 0 on the seabed and rises from 0.
    """
    c = 1.0 / ea if ea else 0.0
    s = np.linspace(0.0, L, n)
    if w == 0:
        frac = s / L
        return dict(s=s, x=frac * X, z=frac * Z, tension=np.full_like(s, np.hypot(H, V)))
    VA = V - w * L
    V1 = float(descent_force(H, h, w, c)) if w > 0 else -np.inf
    if VA >= V1:
        return _hanging_profile(s, H, VA, w, c)
    s1 = -V1 / w
    LB = L - s1 - V / w
    s2 = s1 + LB
    Tv = np.where(s < s1, V1 + w * s, np.where(s <= s2, 0.0, w * (s - s2)))
    if H > 0:
        x_desc = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(V1 / H)) + H * s * c
        x1 = (H / w) * np.arcsinh(-V1 / H) + H * s1 * c
        x_ground = x1 + (s - s1) * (1 + H * c)
        x2 = x1 + LB * (1 + H * c)
        x_rise = x2 + (H / w) * np.arcsinh(Tv / H) + H * (s - s2) * c
    else:
        x_desc = np.zeros_like(s)
        x_ground = np.minimum(s - s1, X)
        x_rise = np.full_like(s, X)
    z_desc = (np.hypot(H, Tv) - np.hypot(H, V1)) / w + (V1 * s + w * s**2 / 2) * c
    z_rise = -h + (np.hypot(H, Tv) - H) / w + Tv**2 / (2 * w) * c
    x = np.where(s < s1, x_desc, np.where(s <= s2, x_ground, x_rise))
    z = np.where(s < s1, z_desc, np.where(s <= s2, -h, z_rise))
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))


# ---- a leg on a sloped seabed -------------------------------------------------------------

SLOPED_INPUTS = LEG_INPUTS + ("t",)


def sloped_leg_equations(elastic: bool, friction: bool, X, Z, u, V, L, w, ea_inv, mu, t):
    """A sinking leg whose anchor is on a seabed of slope ``t = tan(theta)`` in its plane.

    ``t`` is the seabed's rise per metre along the leg's horizontal direction (anchor toward
    fairlead), so the seabed in the leg's vertical plane is ``z = t x`` from the anchor.
    Regimes, chosen in the graph:

    - suspended (``V_A >= H t``): the line leaves the anchor at least as steeply as the
      seabed; the ordinary elastic catenary;
    - touchdown (``V_A < H t``): ``L_B = L - (V - H t)/w`` lies on the slope; the line
      leaves it tangentially, where the vertical tension is ``H t`` and the tension
      ``H sqrt(1 + t^2)``;
    - slack (``u < 0``): ``H = 0``; the line hangs vertically from the fairlead onto the
      slope and ``-u/w`` of it lies loose on the slope.

    On the slope the tension falls from the touchdown toward the anchor by
    ``k = w (sin(theta) + mu cos(theta))`` per metre (the weight's component along the slope,
    and fully mobilised friction), down to zero at most: ``T_A = max(H sqrt(1+t^2) - k L_B,
    0)``; with ``theta < 0`` (seabed falling toward the fairlead) and little friction the
    tension grows toward the anchor instead. The anchor force is ``T_A`` along the slope.

    Notes
    -----
    Suspended part from the touchdown (Merkin 1980, seed 004, sections 2.1, 2.3, integrated
    from the vertical tension ``H t`` instead of 0)::

        X_s = (H/w)[asinh(V/H) - asinh(t)] + H L_s/EA,   L_s = (V - H t)/w
        Z_s = [sqrt(H^2+V^2) - H sqrt(1+t^2)]/w + (V^2 - H^2 t^2)/(2 w EA)

    The grounded part adds ``(L_B + stretch)(cos, sin)(theta)`` with the stretch
    ``int T/EA ds`` over the slope. With ``t = 0`` this is :func:`leg_equations`.
    The cross-slope component of the seabed's reaction (when the seabed's gradient is not in
    the leg's plane) is assumed taken by the soil; it does not enter the leg's plane.
    """
    H = ca.fmax(u, 0)
    Hg = ca.fmax(H, _H_FLOOR)
    c = ea_inv if elastic else 0
    sec = ca.sqrt(1 + t**2)
    cos_t, sin_t = 1 / sec, t / sec
    VA = V - w * L
    Xs = (H / w) * (ca.asinh(V / Hg) - ca.asinh(VA / Hg)) + H * L * c
    Zs = (_hyp(H, V) - _hyp(H, VA)) / w + L * c * (V - w * L / 2)

    Vtd = H * t
    loose = ca.fmax(-u, 0) / w
    LB = L - (V - Vtd) / w
    Ls = L - LB
    x_susp = (H / w) * (ca.asinh(V / Hg) - ca.asinh(t)) + H * Ls * c
    # Rise of the suspended part; below V = Vtd (a negative suspended length, outside the
    # regime) a monotone continuation, so that no false root appears there (for H = 0 it
    # is the sgn(V) form of the leg block).
    z_susp = ca.if_else(V >= Vtd,
                        (_hyp(H, V) - _hyp(H, Vtd)) / w + c * (V**2 - Vtd**2) / (2 * w),
                        (V - Vtd) / w + c * (V * ca.fabs(V) - Vtd * ca.fabs(Vtd)) / (2 * w))
    k = w * (sin_t + (mu * cos_t if friction else 0))
    T_td = H * sec
    TA_raw = T_td - k * LB
    if elastic:
        # Stretch of the grounded part: the tension is max(TA_raw + k s, 0) along it.
        k_pos = ca.fmax(k, 1e-300)
        s0 = ca.if_else(k > 0, ca.fmin(ca.fmax(-TA_raw / k_pos, 0), LB), 0)
        ground_stretch = c * (TA_raw * (LB - s0) + k * (LB**2 - s0**2) / 2)
    else:
        ground_stretch = 0
    on_ground = LB - loose + ground_stretch
    Xt = on_ground * cos_t + x_susp
    Zt = on_ground * sin_t + z_susp
    TA = ca.fmax(TA_raw, 0)
    suspended = VA >= Vtd
    return dict(
        rX=ca.if_else(suspended, Xs, Xt) - X,
        rZ=ca.if_else(suspended, Zs, Zt) - Z,
        H=H, VF=V,
        HA=ca.if_else(suspended, H, TA * cos_t),
        VA=ca.if_else(suspended, VA, TA * sin_t),
        grounded=ca.if_else(suspended, 0, LB),
        suspended_x=ca.if_else(suspended, Xs, x_susp),
    )


@lru_cache(maxsize=None)
def sloped_leg_function(elastic: bool, friction: bool) -> ca.Function:
    """:func:`sloped_leg_equations` as a ``casadi.Function`` (inputs ``SLOPED_INPUTS``)."""
    args = [ca.SX.sym(n) for n in SLOPED_INPUTS]
    out = sloped_leg_equations(elastic, friction, *args)
    tag = ("elastic" if elastic else "inextensible") + ("_friction" if friction else "")
    return ca.Function(f"leg_sloped_{tag}", args, [out[k] for k in LEG_OUTPUTS],
                       list(SLOPED_INPUTS), list(LEG_OUTPUTS))


def sloped_leg_profile(*, H: float, V: float, L: float, w: float, ea: float | None,
                       mu: float, t: float, X: float, Z: float, n: int = 101) -> dict:
    """Points and tension along a solved leg on a sloped seabed (see :func:`leg_profile`)."""
    c = 1.0 / ea if ea else 0.0
    s = np.linspace(0.0, L, n)
    sec = np.sqrt(1 + t * t)
    cos_t, sin_t = 1 / sec, t / sec
    VA = V - w * L
    if VA >= H * t:
        return _hanging_profile(s, H, VA, w, c)
    LB = L - (V - H * t) / w
    k = w * (sin_t + mu * cos_t)
    TA_raw = H * sec - k * LB
    sg = np.minimum(s, LB)
    Tg = np.maximum(TA_raw + k * sg, 0.0)
    if c:
        # Cumulative stretch along the slope, by the trapezoid rule on a fine grid.
        fine = np.linspace(0.0, LB, 2001)
        Tf = np.maximum(TA_raw + k * fine, 0.0)
        cum = np.concatenate([[0.0], np.cumsum((Tf[1:] + Tf[:-1]) / 2 * np.diff(fine))]) * c
        stretch = np.interp(sg, fine, cum)
        stretch_td = cum[-1]
    else:
        stretch = np.zeros_like(s)
        stretch_td = 0.0
    if H > 0:
        Tv = H * t + w * (s - LB)
        xs = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(t)) + H * (s - LB) * c
        zs = (np.hypot(H, Tv) - H * sec) / w + (Tv**2 - (H * t) ** 2) / (2 * w) * c
        ground = s <= LB
        x = np.where(ground, (sg + stretch) * cos_t, (LB + stretch_td) * cos_t + xs)
        z = np.where(ground, (sg + stretch) * sin_t, (LB + stretch_td) * sin_t + zs)
        tension = np.where(ground, Tg, np.hypot(H, Tv))
    else:
        # Slack: loose on the slope up to below the fairlead, then hanging straight.
        foot = X / cos_t
        ground = s <= LB
        along = np.minimum(sg, foot)
        hang = np.maximum(s - LB, 0.0)
        x = np.where(ground, along * cos_t, X)
        z = np.where(ground, along * sin_t, X * t + hang + w * hang**2 / 2 * c)
        tension = np.where(ground, 0.0, w * hang)
    return dict(s=s, x=x, z=z, tension=tension)


def _hanging_profile(s, H, VA, w, c) -> dict:
    """Points of a fully suspended elastic catenary from its lower end, where the vertical
    force is ``VA``; ``c`` is the compliance 1/EA. ``H = 0`` is a vertical line, which
    folds where the vertical force changes sign (the integral of its sign)."""
    Tv = VA + w * s
    if H > 0:
        x = (H / w) * (np.arcsinh(Tv / H) - np.arcsinh(VA / H)) + H * s * c
        z = (np.hypot(H, Tv) - np.hypot(H, VA)) / w + (VA * s + w * s**2 / 2) * c
    else:
        x = np.zeros_like(s)
        z = (np.abs(Tv) - abs(VA)) / w * np.sign(Tv) + (VA * s + w * s**2 / 2) * c
    return dict(s=s, x=x, z=z, tension=np.hypot(H, Tv))
