"""One mooring leg: the elastic catenary with seabed contact, friction, uplift and slack.

The leg lies in the vertical plane through its anchor (end A) and fairlead (end F). Given the
spans ``X`` (horizontal) and ``Z`` (vertical, fairlead above anchor) it is described by two
unknowns: a signed tension variable ``u`` and the vertical tension at the fairlead ``V``.
``H = max(u, 0)`` is the horizontal tension; ``-u / w`` (when ``u < 0``) is the length of line
lying loose on the seabed, so that ``H * loose = 0`` holds exactly and the slack state (H = 0:
the line hangs straight down from the fairlead and the rest lies on the seabed) is one
branch of a single continuous model instead of a case the solver must guess.

Every regime (suspended, touchdown, slack) is selected inside the symbolic graph with
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

The free surface
----------------
The still-water level ``z = 0`` bounds a buoyant line as the seabed bounds a sinking one:
where the catenary of a buoyant line would rise above the surface,
the line reaches it tangentially (vertical tension zero: the vertex of the suspended part is
at ``z = 0``), floats along it with constant tension (its buoyancy taken by the surface, no
drag along it) and, if its far end is below the surface, leaves it tangentially again. That
is exactly the seabed model mirrored in ``z`` (``w -> -w``, ``z -> -z``, vertical forces
change sign), so :func:`surface_segment_equations` *is* :func:`lifted_segment_equations`
called on the mirrored arguments: one model, one set of regimes (suspended, a two-sided
contact, slack with loose line floating), the same signed unknown ``u``. A leg whose
fairlead is at the surface is solved from the fairlead end (``LegKind.from_fairlead``), so
the floating length sits at the block's lower end as the grounded length does in the leg
block, where the equations stay well conditioned (a line arriving along a boundary at the
end whose vertical tension is the unknown has a span insensitive to it: ``Z ~ V|V|``).

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

from .block_laws import bind, ground_stretch, law_inputs, law_tag, shared
from .contact import fischer_burmeister
from .stretch import StretchModel

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
        The anchor rests on a sloped seabed
        (:func:`~moorsolve.physics.sloped.sloped_leg_equations`; needs ``contact``).
    lifted : bool
        A sinking line whose anchor is above a flat seabed: the seabed still bounds it
        (:func:`lifted_segment_equations` with the anchor's height above the seabed).
    air : bool
        The upper end is above the water and the line type gives its weight in air: the
        part above the surface is the catenary of :func:`air_part`.
    air_ends : bool
        With ``air``: the lower end is above the water too (not an anchor), so the line
        may hang in air throughout or dip into the water between two parts in air
        (:func:`moorsolve.physics.air.air_line`).
    surface : bool
        A buoyant line bounded by the free surface (:func:`surface_leg_equations`).
    from_fairlead : bool
        With ``surface``: the fairlead is at (or above) the surface, so the block is solved
        from the fairlead end and the unknown ``V`` is the vertical force at the anchor end
        (see the module notes).
    law : StretchModel or None
        The stretch law of an elastic line other than Hooke's (its parameters are then the
        block's input ``law``); None: Hooke, with the compliance ``ea_inv``.
    """

    elastic: bool
    contact: bool
    friction: bool = False
    neutral: bool = False
    sloped: bool = False
    lifted: bool = False
    surface: bool = False
    from_fairlead: bool = False
    air: bool = False
    law: Optional[StretchModel] = None
    air_ends: bool = False

    @property
    def bounded(self) -> bool:
        """The line can lie on a boundary (seabed or surface): ``u < 0`` is a loose line."""
        return self.contact or self.lifted or self.surface

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
        elif self.lifted:
            parts.append("lifted")
        elif self.surface:
            parts.append("surface_from_fairlead" if self.from_fairlead else "surface")
        else:
            parts.append("suspended")
        if self.air:
            parts.append("air_ends" if self.air_ends else "air")
        if self.law is not None:
            parts.append(self.law.tag)
        return "_".join(parts)


def taut_part(u):
    """``max(u, 0)``: the horizontal tension carried by the signed unknown ``u`` [N].

    Written so that its derivative at ``u = 0`` is the taut side's (1), not an average of
    the two branches: ``u = 0`` with the line's span still positive is reached only from
    the taut side (a line hanging straight down, X -> 0+), and where a line genuinely
    turns slack there (touchdown branch) the taut side's derivative of ``H(X)`` tends to 0
    as the slack side's does.
    """
    return ca.if_else(u >= 0, u, 0)


def loose_part(u):
    """``max(-u, 0)``: the slack measure of ``u`` [N], zero derivative at ``u = 0`` (the taut
    side, as :func:`taut_part`)."""
    return ca.if_else(u >= 0, 0, -u)


def _hyp(a, b):
    """``sqrt(a^2 + b^2)`` floored by 1e-9 N so that its derivative exists at (0, 0)."""
    return ca.sqrt(a**2 + b**2 + _H_FLOOR**2)


def _span_factor(Hg, V, VA, w, L):
    """``asinh(V/H) - asinh(V_A/H)`` free of cancellation (see :func:`_suspended_spans`)."""
    TF, TA = ca.sqrt(Hg**2 + V**2), ca.sqrt(Hg**2 + VA**2)
    same_side = V * VA > 0
    return ca.if_else(same_side,
                      ca.asinh(w * L * (V + VA) / ca.if_else(same_side, V * TA + VA * TF, 1)),
                      ca.asinh(V / Hg) - ca.asinh(VA / Hg))


def _suspended_spans(H, Hg, V, VA, w, L, c):
    """Spans ``(X, Z)`` of a fully suspended elastic catenary, free of cancellation.

    ``[asinh(V/H) - asinh(V_A/H)]`` loses ``eps asinh(V/H)`` to cancellation when ``V`` and
    ``V_A`` have the same sign (a nearly taut line: ``H/w`` times that can exceed the span
    tolerance); there it equals ``asinh(w L (V + V_A) / (V T_A + V_A T_F))``, which has
    none. ``[sqrt(H^2+V^2) - sqrt(H^2+V_A^2)]/w`` is written as ``L (V + V_A)/(T_F + T_A)``
    (the denominator is at least ``|w| L``). Square roots carry a 1e-9 N floor so that
    derivatives exist at ``H = V = 0``; it cancels exactly from the difference.
    """
    Xs = (H / w) * _span_factor(Hg, V, VA, w, L) + H * L * c
    Zs = L * (V + VA) / (_hyp(H, V) + _hyp(H, VA)) + L * c * (V - w * L / 2)
    return Xs, Zs


def lateral_stiffness(taut_suspended, V, VA, w, L, c, stretch=0):
    """``H / X`` [N/m] of a line hanging straight down: the coefficient of its horizontal
    pull ``H e = (H/X) offset`` (``offset`` the horizontal vector between its ends) near
    ``X = 0``, where ``H/X`` itself is ``0/0``.

    A suspended taut catenary has ``X = H G(H, V)`` with ``G = [asinh(V/H) -
    asinh(V_A/H)]/w + L/EA``, smooth and even in ``H``; as the line hangs straight down
    (``H, X -> 0``) ``H/X -> 1/G(0, V) = 1 / (ln(V/V_A)/w + L/EA)`` (written
    ``log1p(w L/V_A)/w``: for ``w -> 0`` it is ``L/T``, the taut string). Within the range
    the caller uses it (``X`` below 1e-6 of the length) ``G(H, V)`` and ``G(0, V)`` differ
    by ``O((H/V)^2)``, and ``G(0, V)`` has no derivative by ``H`` (so it adds little to the
    Jacobian). ``stretch``: a stretch law's own term ``[Psi(V) - Psi(V_A)]/w``. A line that is
    not ``taut_suspended`` hangs straight only slack, or with all its length but a
    vanishing part lifted off the boundary: ``H/X`` tends to 0 there.
    """
    ratio = w * L / ca.if_else(VA != 0, VA, 1)
    G = ca.log1p(ca.if_else(ratio > -1, ratio, 0)) / w + L * c + stretch
    return ca.if_else(taut_suspended, 1 / ca.if_else(G > 0, G, 1), 0)


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
    After Merkin 1980, sections 2.1 and 2.3, and Malacic. Suspended (``V_A = V - w L >= 0``)::

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
    H = taut_part(u)
    bound = bind(kind.law, law)
    if kind.neutral:
        return _neutral_equations(kind, X, Z, u, V, L, ea_inv, bound=bound)

    Hg = ca.fmax(H, _H_FLOOR)
    VA = V - w * L
    c = ea_inv if kind.elastic and bound is None else 0
    stretch = H * L * c
    Xs, Zs = _suspended_spans(H, Hg, V, VA, w, L, c)
    stretch_term = 0
    if bound is not None:
        psi_V, psi_VA = bound.horizontal(Hg, V, VA)
        Xs = Xs + (H / w) * (psi_V - psi_VA)
        stretch_term = (psi_V - psi_VA) / w
        Zs = Zs * (1 + bound.mean(_hyp(H, VA), _hyp(H, V)))

    if not kind.contact:
        # No seabed under the line: one catenary whatever the sign of V_A. ``u < 0`` (no
        # physical state of a line with nothing to lie on) continues the span monotonically,
        # so that a line folded straight down (H = 0, X = 0) is an interior root, not a
        # bound the solver must reach.
        loose = loose_part(u) / ca.fabs(w)
        return dict(rX=Xs - X - loose, rZ=Zs - Z, H=H, VF=V, HA=H, VA=VA,
                    grounded=0 * H, suspended_x=Xs,
                    lateral=lateral_stiffness(u >= 0, V, VA, w, L, c, stretch_term))

    loose = loose_part(u) / w
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
        Xt = LB + ground_stretch(bound, H, LB, HA_t, mu * w if kind.friction else None) \
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
        lateral=lateral_stiffness(ca.logic_and(suspended, u >= 0), V, VA, w, L, c,
                                  stretch_term),
    )


def _neutral_equations(kind, X, Z, u, V, L, ea_inv, stiffness=1.0, smoothing=0.0,
                       bound=None):
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
    if bound is not None:
        stretched = L * (1 + bound.strain(ca.fmax(T, 0)))
    else:
        stretched = L * (1 + T * ea_inv) if kind.elastic else L
    opening = stretched - D
    H = T * X / ca.fmax(D, _H_FLOOR)
    rX = fischer_burmeister(T / stiffness, opening, smoothing)
    return dict(rX=rX, rZ=(V * D - T * Z) / stiffness, H=H, VF=V, HA=H, VA=V, grounded=0 * T,
                suspended_x=X, lateral=T / ca.fmax(D, _H_FLOOR))


LEG_OUTPUTS = ("rX", "rZ", "H", "VF", "HA", "VA", "grounded", "suspended_x")
#: The leg and weightless blocks add ``lateral`` (:func:`lateral_stiffness`) [N/m].
LATERAL_OUTPUTS = LEG_OUTPUTS + ("lateral",)
LEG_INPUTS = ("X", "Z", "u", "V", "L", "w", "ea_inv", "mu")


@lru_cache(maxsize=None)
def leg_function(kind: LegKind) -> ca.Function:
    """The leg block for ``kind`` as one ``casadi.Function``, built once and reused.

    Inputs ``(X, Z, u, V, L, w, ea_inv, mu)`` and, for a line with ``kind.law``, ``law``
    (its parameters); outputs ``LEG_OUTPUTS``; see :func:`leg_equations`. Call it on
    SX/MX symbols to embed it, or on floats.
    """
    names, args, law = law_inputs(kind.law, LEG_INPUTS)
    out = leg_equations(kind, *args[:len(LEG_INPUTS)], law=law)
    return ca.Function(f"leg_{kind.tag}", args, shared([out[k] for k in LATERAL_OUTPUTS], law),
                       names, list(LATERAL_OUTPUTS))


def evaluate_leg(kind: LegKind, X, Z, u, V, L, w, ea_inv=0.0, mu=0.0, law=None) -> dict:
    """Evaluate the leg block on floats; returns a dict of floats (``LEG_OUTPUTS``)."""
    extra = () if kind.law is None else (list(law),)
    vals = leg_function(kind)(X, Z, u, V, L, w, ea_inv, mu, *extra)
    return {k: float(v) for k, v in zip(LEG_OUTPUTS, vals)}


WEIGHTLESS_INPUTS = ("X", "Z", "u", "V", "L", "ea_inv", "k", "eps")


@lru_cache(maxsize=None)
def weightless_line_function(elastic: bool,
                             model: Optional[StretchModel] = None) -> ca.Function:
    """The weightless line block as a ``casadi.Function``: inputs :data:`WEIGHTLESS_INPUTS`
    (``k`` the contact stiffness scale [N/m], ``eps`` the Jacobian smoothing [m]) and, for a
    stretch law ``model`` other than Hooke's, ``law``; outputs :data:`LEG_OUTPUTS`; see
    :func:`_neutral_equations`."""
    model = model if elastic else None
    names, args, law = law_inputs(model, WEIGHTLESS_INPUTS)
    X, Z, u, V, L, ea_inv, k, eps = args[:len(WEIGHTLESS_INPUTS)]
    out = _neutral_equations(LegKind(elastic, contact=False, neutral=True), X, Z, u, V, L,
                             ea_inv, k, eps, bound=bind(model, law))
    return ca.Function(f"weightless_{law_tag(elastic, model)}", args,
                       shared([out[n] for n in LATERAL_OUTPUTS], law), names,
                       list(LATERAL_OUTPUTS))


# ---- a line end above the water -------------------------------------------------------


def air_part(H, V, z_top, w_air, ea_inv, law=None):
    """The part of a line between the surface and an upper end ``z_top > 0`` above it.

    Above the water the line weighs ``w_air`` per metre (no buoyancy). From the upper end's
    vertical tension ``V`` down to the crossing of the surface, the vertical tension falls
    by ``w_air`` per metre; the rise is ``f(T) - f(T_c) = w_air z_top`` with
    ``f(T) = T + T^2/(2 EA)`` (the elastic catenary's height, Merkin 1980, sections
    2.1 and 2.3, written in the tensions ``T``, ``T_c`` at the two ends), so the tension at
    the crossing is closed form: ``T_c = 2 r / (1 + sqrt(1 + 2 r/EA))``, ``r = f(T) - w_air
    z_top``, and ``V_c = sqrt(T_c^2 - H^2)`` (continued as ``-sqrt(H^2 - T_c^2)`` where the
    line could not reach the surface: no root there).

    With another stretch law (``law``, a bound :class:`~moorsolve.physics.stretch.Law`) the
    tension drop ``T - T_c`` solves ``(T - T_c)(1 + mean_strain(T_c, T)) = w_air z_top``
    (:meth:`~moorsolve.physics.stretch.Law.drop`) and the horizontal extent gains
    ``(H/w_air)[Psi(V) - Psi(V_c)]``.

    Returns
    -------
    dict
        ``V`` the vertical tension at the crossing [N], ``length`` the unstretched length in
        air [m], ``x`` its horizontal extent [m].
    """
    T = _hyp(H, V)
    if law is not None:
        Tc = T - law.drop(T, w_air * z_top)
        q = Tc**2 - H**2
        Vc = ca.sign(q) * ca.sqrt(ca.fabs(q) + _H_FLOOR**2) - ca.sign(q) * _H_FLOOR
        Hg = ca.fmax(H, _H_FLOOR)
        psi_V, psi_c = law.horizontal(Hg, V, Vc)
        x = (H / w_air) * (ca.asinh(V / Hg) - ca.asinh(Vc / Hg) + psi_V - psi_c)
        return dict(V=Vc, length=(V - Vc) / w_air, x=x)
    r = ca.fmax(T + ea_inv * T**2 / 2 - w_air * z_top, 0)
    Tc = 2 * r / (1 + ca.sqrt(1 + 2 * ea_inv * r))
    q = Tc**2 - H**2
    Vc = ca.sign(q) * ca.sqrt(ca.fabs(q) + _H_FLOOR**2) - ca.sign(q) * _H_FLOOR
    Hg = ca.fmax(H, _H_FLOOR)
    length = (V - Vc) / w_air
    x = (H / w_air) * (ca.asinh(V / Hg) - ca.asinh(Vc / Hg)) + H * length * ea_inv
    return dict(V=Vc, length=length, x=x)
