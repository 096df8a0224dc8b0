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

Stretch laws
------------
Hooke's law (``ea_inv = 1/EA``) has its own closed forms below. A line following another law
of :mod:`moorsolve.physics.stretch` (Baranov, a tension-strain table) gives its
:class:`~moorsolve.physics.stretch.StretchModel` in the kind (``law``) and its parameters as
the block's extra input ``law``; the stretch is then integrated exactly along the line: on
a catenary with vertical tension ``T_v`` as the variable (``ds0 = dT_v/w``) the vertical
extent gains ``(T_F - T_A)/w`` times the mean strain over the tensions passed, the horizontal
extent ``(H/w) [Psi(V) - Psi(V_A)]`` (:meth:`~moorsolve.physics.stretch.Law.horizontal`); on
the seabed the tension falls linearly (friction) or stays ``H``, so the grounded stretch is
the loaded length times the mean strain between the anchor's and the touchdown's tension.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Optional

import casadi as ca
import numpy as np

from .stretch import Law, StretchModel

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
    law : StretchModel or None
        The stretch law of an elastic line other than Hooke's (its parameters are then the
        block's input ``law``); None: Hooke, with the compliance ``ea_inv``.
    """

    elastic: bool
    contact: bool
    friction: bool = False
    neutral: bool = False
    sloped: bool = False
    law: Optional[StretchModel] = None

    @property
    def tag(self) -> str:
        parts = ["elastic" if self.elastic else "inextensible"]
        if self.law is not None:
            parts.append(self.law.tag)
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


def leg_equations(kind: LegKind, X, Z, u, V, L, w, ea_inv, mu, law=None):
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
    law : sequence, optional
        Parameters of ``kind.law`` (floats or symbols), when the line is not Hooke's.

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

    Another stretch law (``kind.law``): the terms ``H L/EA`` and ``(L/EA)(V - w L/2)`` become
    ``(H/w)[Psi(V) - Psi(V_A)]`` and ``Z_0 mean_strain(T_A, T_F)`` (``Z_0`` the inextensible
    rise); on touchdown the grounded length stretches by ``L_B eps(H)`` (with friction: the
    loaded length ``min(L_B, H/(mu w))`` times the mean strain between ``H_A`` and ``H``) and
    the suspended part by ``(H/w) Psi(V)`` and ``Z_0 mean_strain(H, T_F)``
    (:mod:`moorsolve.physics.stretch`).
    """
    H = ca.fmax(u, 0)
    bound = _bind(kind, law)
    if kind.neutral:
        return _neutral_equations(kind, X, Z, u, V, L, ea_inv, bound)

    Hg = ca.fmax(H, _H_FLOOR)
    VA = V - w * L
    if bound is not None:
        psi_V, psi_VA = bound.horizontal(Hg, V, VA)
        stretch = (H / w) * (psi_V - psi_VA)
    else:
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
    if bound is not None:
        Zs = Zs * (1 + bound.mean(ca.sqrt(H**2 + VA**2), ca.sqrt(H**2 + V**2)))
    elif kind.elastic:
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
    if bound is not None:
        Zt = Zt * (1 + bound.mean(H, ca.sqrt(H**2 + V**2)))
        Xsusp_t = Xsusp_t + (H / w) * psi_V
    elif kind.elastic:
        Zt = Zt + ea_inv * V * ca.fabs(V) / (2 * w)
        Xsusp_t = Xsusp_t + H * (V / w) * ea_inv
    if kind.friction:
        # Tension decays by mu*w per metre along the grounded length, from H at touchdown.
        # Where it would reach zero before the anchor (L_B > H/(mu w)) the rest is unloaded.
        excess = LB - H / (mu * w)
        if kind.elastic and bound is None:
            Xt = Xt + (mu * w * ea_inv / 2) * (-LB**2 + excess * ca.fmax(excess, 0))
        HA_t = ca.fmax(H - mu * w * LB, 0)
    else:
        HA_t = H
    if bound is not None:
        Xt = LB + _ground_stretch(bound, H, LB, HA_t, mu * w if kind.friction else None) \
            + Xsusp_t

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


def _bind(kind, law):
    """The stretch law of ``kind`` bound to its parameters ``law`` (None for Hooke)."""
    model = getattr(kind, "law", None)
    if model is None:
        return None
    if law is None:
        raise ValueError(f"a {model.tag} line needs its law parameters (input 'law')")
    return Law(model, law if isinstance(law, (list, tuple)) else ca.vertsplit(law))


def _ground_stretch(bound, H, LB, HA, decay):
    """Stretch of ``LB`` of line lying on a flat seabed with tension ``H`` at touchdown.

    Without friction (``decay`` None) the tension is ``H`` throughout: ``LB eps(H)``. With
    friction it falls by ``decay = mu w`` per metre toward the anchor, to ``HA`` there (or
    to zero at ``H/decay`` from touchdown): the loaded length times the mean strain.
    """
    if decay is None:
        return LB * bound.strain(H)
    return ca.fmin(LB, H / decay) * bound.mean(HA, H)


def _neutral_equations(kind, X, Z, u, V, L, ea_inv, bound=None):
    """A weightless line: straight at tension T = max(u, 0) when taut, loose otherwise.

    The chord must equal the stretched length while taut; ``-u`` [N] measures, at one metre
    per newton, how much longer than the chord a loose line is.
    """
    T = ca.fmax(u, 0)
    D = ca.sqrt(X**2 + Z**2)
    if bound is not None:
        stretched = L * (1 + bound.strain(T))
    else:
        stretched = L * (1 + T * ea_inv) if kind.elastic else L
    loose = ca.fmax(-u, 0)
    H = T * X / ca.fmax(D, _H_FLOOR)
    return dict(rX=stretched - loose - D, rZ=V * D - T * Z, H=H, VF=V, HA=H, VA=V,
                grounded=0 * T, suspended_x=X)


LEG_OUTPUTS = ("rX", "rZ", "H", "VF", "HA", "VA", "grounded", "suspended_x")
LEG_INPUTS = ("X", "Z", "u", "V", "L", "w", "ea_inv", "mu")


def _shared(outputs, law):
    """A block's outputs with common subexpressions merged when it has a stretch law (the
    law's pieces are picked at the same tension by several terms); Hooke's graph as built."""
    return outputs if law is None else ca.cse(outputs)


def _law_inputs(kind, names):
    """Input names and symbols of a block: ``names``, plus ``law`` for a non-Hooke line."""
    model = getattr(kind, "law", None)
    args = [ca.SX.sym(n) for n in names]
    if model is None:
        return list(names), args, None
    law = ca.SX.sym("law", model.n_params)
    return list(names) + ["law"], args + [law], ca.vertsplit(law)


@lru_cache(maxsize=None)
def leg_function(kind: LegKind) -> ca.Function:
    """The leg block for ``kind`` as one ``casadi.Function``, built once and reused.

    Inputs ``(X, Z, u, V, L, w, ea_inv, mu)`` and, for a line with ``kind.law``, ``law``
    (its parameters); outputs ``LEG_OUTPUTS``; see :func:`leg_equations`. Call it on
    SX/MX symbols to embed it, or on floats.
    """
    names, args, law = _law_inputs(kind, LEG_INPUTS)
    out = leg_equations(kind, *args[:len(LEG_INPUTS)], law=law)
    return ca.Function(f"leg_{kind.tag}", args, _shared([out[k] for k in LEG_OUTPUTS], law),
                       names, list(LEG_OUTPUTS))


def evaluate_leg(kind: LegKind, X, Z, u, V, L, w, ea_inv=0.0, mu=0.0, law=None) -> dict:
    """Evaluate the leg block on floats; returns a dict of floats (``LEG_OUTPUTS``)."""
    extra = () if kind.law is None else (list(law),)
    vals = leg_function(kind)(X, Z, u, V, L, w, ea_inv, mu, *extra)
    return {k: float(v) for k, v in zip(LEG_OUTPUTS, vals)}


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
        if D >= L and ea:
            return ea * (D / L - 1), 0.0
        return -(L - D), 0.0
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


# Profiles along a solved line (floats): moorsolve.physics.profiles.


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


def descent_force(H, h, w, ea_inv, law=None):
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
    With another stretch law ``law`` (a bound :class:`~moorsolve.physics.stretch.Law`) the
    tension gain ``delta = T_1 - H`` solves ``delta (1 + mean_strain(H, H + delta)) = w h``
    (:meth:`~moorsolve.physics.stretch.Law.descent`) and ``t = delta (delta + 2 H)``.
    """
    if law is not None:
        delta = law.descent(H, w * h)
        t = delta * (delta + 2 * H)
        return -t / ca.sqrt(ca.fmax(t, _T_FLOOR))
    d = w * h * (w * h + 2 * H)
    a = w * h + H
    c = ea_inv
    t = 2 * d / (1 + a * c + ca.sqrt(1 + 2 * a * c + c**2 * H**2))
    return -t / ca.sqrt(ca.fmax(t, _T_FLOOR))


def _hyp(a, b):
    """``sqrt(a^2 + b^2)`` floored by 1e-9 N so that its derivative exists at (0, 0)."""
    return ca.sqrt(a**2 + b**2 + _H_FLOOR**2)


def lifted_segment_equations(elastic: bool, X, Z, h, u, V, L, w, ea_inv, mu=0,
                             friction: bool = False, model=None, law=None):
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
    decays toward the lower end as in :func:`leg_equations`. A stretch law other than
    Hooke's (``model``, a :class:`~moorsolve.physics.stretch.StretchModel`, with parameters
    ``law``) enters as in :func:`leg_equations`.

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
    bound = _bind(_Kind(model), law) if elastic else None
    c = ea_inv if elastic and bound is None else 0
    VA = V - w * L
    V1 = descent_force(H, h, w, c, bound)
    Xs = (H / w) * (ca.asinh(V / Hg) - ca.asinh(VA / Hg)) + H * L * c
    Zs = (_hyp(H, V) - _hyp(H, VA)) / w + L * c * (V - w * L / 2)
    s1 = -V1 / w
    x1 = (H / w) * ca.asinh(-V1 / Hg) + H * s1 * c
    LB = L - s1 - V / w
    x_rise = (H / w) * ca.asinh(V / Hg) + H * (V / w) * c
    Xt = x1 + LB * (1 + H * c) + x_rise
    Zt = -h + ca.sign(V) * (_hyp(H, V) - _hyp(H, 0)) / w + c * V * ca.fabs(V) / (2 * w)
    if bound is not None:
        psi_V, psi_VA, psi_1 = bound.horizontal(Hg, V, VA, -V1)
        Xs = Xs + (H / w) * (psi_V - psi_VA)
        Zs = Zs * (1 + bound.mean(_hyp(H, VA), _hyp(H, V)))
        x1 = x1 + (H / w) * psi_1
        x_rise = x_rise + (H / w) * psi_V
        Zt = -h + (Zt + h) * (1 + bound.mean(_hyp(H, 0), _hyp(H, V)))
    HA_t = H
    if friction:
        excess = LB - H / (mu * w)
        if elastic and bound is None:
            Xt = Xt + (mu * w * c / 2) * (-LB**2 + excess * ca.fmax(excess, 0))
        HA_t = ca.fmax(H - mu * w * LB, 0)
    if bound is not None:
        Xt = x1 + LB + _ground_stretch(bound, H, LB, HA_t, mu * w if friction else None) \
            + x_rise
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


def straight_segment_equations(elastic: bool, X, Z, u, V, L, ea_inv, model=None, law=None):
    """A weightless segment inside a multi-segment leg: straight, ``H = max(u, 0)``.

    Its tension ``T = sqrt(H^2 + V^2)`` is the same at both ends and its direction is the
    chord's: ``X = H L (1/T + 1/EA)``, ``Z = V L (1/T + 1/EA)``; with another stretch law
    (``model`` and its parameters ``law``) ``1/EA`` becomes ``eps(T)/T``. With ``H = 0`` it
    hangs vertical under the joint loads. (A weightless segment with no tension at all has
    no definite shape; the model does not represent it.)
    """
    H = ca.fmax(u, 0)
    T = ca.sqrt(H**2 + V**2 + _H_FLOOR**2)
    bound = _bind(_Kind(model), law) if elastic else None
    if bound is not None:
        k = L * (1 + bound.strain(T)) / T
    else:
        k = L * (1 / T + (ea_inv if elastic else 0))
    return dict(rX=H * k - X, rZ=V * k - Z, H=H, VF=V, HA=H, VA=V, grounded=0 * H,
                suspended_x=X, descent_x=0 * H)


@dataclass(frozen=True)
class _Kind:
    """The stretch law of a block that has no kind of its own (segments, sloped legs)."""

    law: Optional[StretchModel] = None


def _law_tag(elastic: bool, model) -> str:
    return ("elastic" if elastic else "inextensible") + (
        f"_{model.tag}" if elastic and model is not None else "")


@lru_cache(maxsize=None)
def lifted_segment_function(elastic: bool, friction: bool = False,
                            model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`lifted_segment_equations` as a ``casadi.Function`` (inputs ``LIFTED_INPUTS``,
    and ``law`` for a stretch law ``model`` other than Hooke's)."""
    names, args, law = _law_inputs(_Kind(model if elastic else None), LIFTED_INPUTS)
    out = lifted_segment_equations(elastic, *args[:len(LIFTED_INPUTS)], friction=friction,
                                   model=model, law=law)
    tag = _law_tag(elastic, model) + ("_friction" if friction else "")
    return ca.Function(f"segment_lifted_{tag}", args,
                       _shared([out[k] for k in SEGMENT_OUTPUTS], law), names,
                       list(SEGMENT_OUTPUTS))


STRAIGHT_INPUTS = ("X", "Z", "u", "V", "L", "ea_inv")


@lru_cache(maxsize=None)
def straight_segment_function(elastic: bool,
                              model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`straight_segment_equations` as a ``casadi.Function``."""
    names, args, law = _law_inputs(_Kind(model if elastic else None), STRAIGHT_INPUTS)
    out = straight_segment_equations(elastic, *args[:len(STRAIGHT_INPUTS)], model=model,
                                     law=law)
    return ca.Function(f"segment_straight_{_law_tag(elastic, model)}", args,
                       _shared([out[k] for k in SEGMENT_OUTPUTS], law), names,
                       list(SEGMENT_OUTPUTS))


# ---- a leg on a sloped seabed -------------------------------------------------------------

SLOPED_INPUTS = LEG_INPUTS + ("t",)


def sloped_leg_equations(elastic: bool, friction: bool, X, Z, u, V, L, w, ea_inv, mu, t,
                         model=None, law=None):
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
    ``int T/EA ds`` over the slope. With ``t = 0`` this is :func:`leg_equations`. Another
    stretch law (``model`` with parameters ``law``) enters as there: the suspended part
    from ``T_v = H t``, the grounded part the loaded length times the mean strain between
    the anchor's and the touchdown's tension.
    The cross-slope component of the seabed's reaction (when the seabed's gradient is not in
    the leg's plane) is assumed taken by the soil; it does not enter the leg's plane.
    """
    H = ca.fmax(u, 0)
    Hg = ca.fmax(H, _H_FLOOR)
    bound = _bind(_Kind(model), law) if elastic else None
    c = ea_inv if elastic and bound is None else 0
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
    if bound is None:
        rise = (_hyp(H, V) - _hyp(H, Vtd)) / w + c * (V**2 - Vtd**2) / (2 * w)
        below = (V - Vtd) / w + c * (V * ca.fabs(V) - Vtd * ca.fabs(Vtd)) / (2 * w)
    else:
        psi_V, psi_VA, psi_td = bound.horizontal(Hg, V, VA, Vtd)
        Xs = Xs + (H / w) * (psi_V - psi_VA)
        Zs = Zs * (1 + bound.mean(_hyp(H, VA), _hyp(H, V)))
        x_susp = x_susp + (H / w) * (psi_V - psi_td)
        rise = (_hyp(H, V) - _hyp(H, Vtd)) / w * (1 + bound.mean(_hyp(H, Vtd), _hyp(H, V)))

        def signed_energy(v):
            return ca.sign(v) * bound.energy(ca.fabs(v))
        below = (V - Vtd + signed_energy(V) - signed_energy(Vtd)) / w
    z_susp = ca.if_else(V >= Vtd, rise, below)
    k = w * (sin_t + (mu * cos_t if friction else 0))
    T_td = H * sec
    TA_raw = T_td - k * LB
    if elastic:
        # Stretch of the grounded part: the tension is max(TA_raw + k s, 0) along it.
        k_pos = ca.fmax(k, 1e-300)
        s0 = ca.if_else(k > 0, ca.fmin(ca.fmax(-TA_raw / k_pos, 0), LB), 0)
        if bound is None:
            ground_stretch = c * (TA_raw * (LB - s0) + k * (LB**2 - s0**2) / 2)
        else:
            ground_stretch = (LB - s0) * bound.mean(ca.fmax(TA_raw, 0), T_td)
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
def sloped_leg_function(elastic: bool, friction: bool,
                        model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`sloped_leg_equations` as a ``casadi.Function`` (inputs ``SLOPED_INPUTS``,
    and ``law`` for a stretch law ``model`` other than Hooke's)."""
    names, args, law = _law_inputs(_Kind(model if elastic else None), SLOPED_INPUTS)
    out = sloped_leg_equations(elastic, friction, *args[:len(SLOPED_INPUTS)], model=model,
                               law=law)
    tag = _law_tag(elastic, model) + ("_friction" if friction else "")
    return ca.Function(f"leg_sloped_{tag}", args, _shared([out[k] for k in LEG_OUTPUTS], law),
                       names, list(LEG_OUTPUTS))


