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

The free surface
----------------
The still-water level ``z = 0`` bounds a buoyant line as the seabed bounds a sinking one
(REFERENCE.md section 7): where the catenary of a buoyant line would rise above the surface,
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
            parts.append("air")
        if self.law is not None:
            parts.append(self.law.tag)
        return "_".join(parts)


def _suspended_spans(H, Hg, V, VA, w, L, c):
    """Spans ``(X, Z)`` of a fully suspended elastic catenary, free of cancellation.

    ``[asinh(V/H) - asinh(V_A/H)]`` loses ``eps asinh(V/H)`` to cancellation when ``V`` and
    ``V_A`` have the same sign (a nearly taut line: ``H/w`` times that can exceed the span
    tolerance); there it equals ``asinh(w L (V + V_A) / (V T_A + V_A T_F))``, which has
    none. ``[sqrt(H^2+V^2) - sqrt(H^2+V_A^2)]/w`` is written as ``L (V + V_A)/(T_F + T_A)``
    (the denominator is at least ``|w| L``). Square roots carry a 1e-9 N floor so that
    derivatives exist at ``H = V = 0``; it cancels exactly from the difference.
    """
    TF, TA = ca.sqrt(Hg**2 + V**2), ca.sqrt(Hg**2 + VA**2)
    same_side = V * VA > 0
    dasinh = ca.if_else(same_side,
                        ca.asinh(w * L * (V + VA) / ca.if_else(same_side, V * TA + VA * TF, 1)),
                        ca.asinh(V / Hg) - ca.asinh(VA / Hg))
    Xs = (H / w) * dasinh + H * L * c
    Zs = L * (V + VA) / (_hyp(H, V) + _hyp(H, VA)) + L * c * (V - w * L / 2)
    return Xs, Zs


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
    bound = bind(kind.law, law)
    if kind.neutral:
        return _neutral_equations(kind, X, Z, u, V, L, ea_inv, bound=bound)

    Hg = ca.fmax(H, _H_FLOOR)
    VA = V - w * L
    c = ea_inv if kind.elastic and bound is None else 0
    stretch = H * L * c
    Xs, Zs = _suspended_spans(H, Hg, V, VA, w, L, c)
    if bound is not None:
        psi_V, psi_VA = bound.horizontal(Hg, V, VA)
        Xs = Xs + (H / w) * (psi_V - psi_VA)
        Zs = Zs * (1 + bound.mean(_hyp(H, VA), _hyp(H, V)))

    if not kind.contact:
        # No seabed under the line: one catenary whatever the sign of V_A. ``u < 0`` (no
        # physical state of a line with nothing to lie on) continues the span monotonically,
        # so that a line folded straight down (H = 0, X = 0) is an interior root, not a
        # bound the solver must reach.
        loose = ca.fmax(-u, 0) / ca.fabs(w)
        return dict(rX=Xs - X - loose, rZ=Zs - Z, H=H, VF=V, HA=H, VA=VA,
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
                suspended_x=X)


LEG_OUTPUTS = ("rX", "rZ", "H", "VF", "HA", "VA", "grounded", "suspended_x")
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
    return ca.Function(f"leg_{kind.tag}", args, shared([out[k] for k in LEG_OUTPUTS], law),
                       names, list(LEG_OUTPUTS))


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
                       shared([out[n] for n in LEG_OUTPUTS], law), names, list(LEG_OUTPUTS))


# ---- a line end above the water -------------------------------------------------------


def air_part(H, V, z_top, w_air, ea_inv, law=None):
    """The part of a line between the surface and an upper end ``z_top > 0`` above it.

    Above the water the line weighs ``w_air`` per metre (no buoyancy). From the upper end's
    vertical tension ``V`` down to the crossing of the surface, the vertical tension falls
    by ``w_air`` per metre; the rise is ``f(T) - f(T_c) = w_air z_top`` with
    ``f(T) = T + T^2/(2 EA)`` (the elastic catenary's height, Merkin 1980, seed 004, sections
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
    With another stretch law (``law``, a bound :class:`~moorsolve.physics.stretch.Law`) the
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
                             friction: bool = False, between_joints: bool = False,
                             model=None, law=None):
    """A sinking segment whose lower end is ``h >= 0`` above a flat seabed.

    The generalisation of :func:`leg_equations` (contact kind, no friction) to a lower end
    that need not rest on the seabed: a joint lifted by a buoy, an anchor on a pile. Three
    regimes, chosen in the graph:

    - suspended (``V_A >= V1(h)``, or ``V < 0``: no vertex inside the segment): one
      catenary, which may dip below its lower end without reaching the seabed (the S
      between a buoy and a fairlead);
    - two-sided touchdown (``V_A < V1``): the line runs down from the lower end to the seabed
      (vertical force ``V1`` from :func:`descent_force`), lies on it for ``L_B`` and rises to the
      upper end (the U under a buoyed joint, or a line between two points on the seabed);
    - slack (``u < 0``): as in the leg block, ``-u / w`` of loose line lies on the seabed.

    With ``h = 0`` it is the touchdown/suspended leg block (square roots are floored by
    1e-9 N so that derivatives exist at H = V = 0, a grounded joint of a slack leg). With
    ``friction`` (only for a lower end fixed on the seabed, ``h = 0``) the grounded tension
    decays toward the lower end as in :func:`leg_equations`. ``between_joints``: the segment
    joins two free joints of a multi-segment leg, whose span may be negative: loose line is
    then counted only where the line lies, at most all of it. A stretch law other than
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
    bound = bind(model, law) if elastic else None
    c = ea_inv if elastic and bound is None else 0
    VA = V - w * L
    V1 = descent_force(H, h, w, c, bound)
    Xs, Zs = _suspended_spans(H, Hg, V, VA, w, L, c)
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
        Xt = x1 + LB + ground_stretch(bound, H, LB, HA_t, mu * w if friction else None) \
            + x_rise
    loose = ca.fmax(-u, 0) / w
    if between_joints:
        # Between two free joints the span may be negative: loose line is then only where
        # the line lies, and at most all of that, or a slack segment folded back past its
        # upper end (a negative span made of loose line) would be a false root.
        loose = ca.fmin(loose, ca.fmax(LB, 0))
    # Suspended when the line leaves the lower end less steeply than one that just touches
    # the seabed at its vertex, or when it has no vertex inside (still descending at the
    # upper end, V < 0: its lowest point is that end, which the caller puts on or above
    # the seabed). V = 0 with a steep start is a line arriving along the seabed.
    suspended = ca.logic_or(VA >= V1, V < 0)
    return dict(
        rX=(ca.if_else(suspended, Xs, Xt - loose) - X if between_joints
            else ca.if_else(suspended, Xs, Xt) - X - loose),
        rZ=ca.if_else(suspended, Zs, Zt) - Z,
        H=H, VF=V, HA=ca.if_else(suspended, H, HA_t),
        VA=ca.if_else(suspended, VA, V1),
        grounded=ca.if_else(suspended, 0, LB),
        suspended_x=ca.if_else(suspended, Xs, x_rise),
        descent_x=ca.if_else(suspended, 0, x1),
    )


def surface_segment_equations(elastic: bool, X, Z, d, u, V, L, w, ea_inv,
                              between_joints: bool = False, model=None, law=None):
    """A buoyant segment (``w < 0``) whose lower end is ``d >= 0`` below the surface.

    The free surface bounds it as the seabed bounds a sinking segment: this is
    :func:`lifted_segment_equations` on the mirrored line (``w -> -w``, ``Z -> -Z``,
    ``V -> -V``, the seabed at the surface and ``h = d``), its outputs mirrored back. Three
    regimes, chosen in the graph:

    - suspended: one catenary below the surface, which may rise above its lower end;
    - floating: the line rises from the lower end to the surface, reaching it tangentially
      (the suspended part's vertex at ``z = 0``), floats along it at constant tension for
      ``floating`` metres and leaves it tangentially down to the upper end (which may be
      at the surface: then it floats up to it);
    - slack (``u < 0``): ``H = 0``; the line rises vertically to the surface and
      ``-u / |w|`` of it floats loose.

    "Lower end" is the block's start (``Z`` is the other end's height above it, of either
    sign). Returns ``SEGMENT_OUTPUTS`` in the real orientation (``VF`` upward force on the
    upper end of the line, ``VA`` signed upward pull on the lower end), with ``grounded``
    0 and ``floating`` the unstretched length on the surface [m]; ``descent_x`` is the
    horizontal extent of the rise from the lower end to the surface.

    Notes
    -----
    REFERENCE.md section 7 ("Free surface": a buoyant line meets the surface as a chain
    meets the seabed, mirrored). The surface carries the floating part's buoyancy as the
    seabed carries a grounded part's weight; no drag or friction acts along it.
    """
    m = lifted_segment_equations(elastic, X, -Z, d, u, -V, L, -w, ea_inv,
                                 between_joints=between_joints, model=model, law=law)
    return dict(rX=m["rX"], rZ=-m["rZ"], H=m["H"], VF=-m["VF"], HA=m["HA"], VA=-m["VA"],
                grounded=0 * m["H"], floating=m["grounded"], suspended_x=m["suspended_x"],
                descent_x=m["descent_x"])


SURFACE_INPUTS = LEG_INPUTS + ("d",)
SURFACE_OUTPUTS = LEG_OUTPUTS + ("floating", "touchup_x")


def surface_leg_equations(elastic: bool, from_fairlead: bool, X, Z, u, V, L, w, ea_inv,
                          mu, d, model=None, law=None):
    """A buoyant leg from its anchor to its fairlead, bounded by the free surface.

    Parameters as :func:`leg_equations`, plus ``d``, the depth [m] below the surface of
    the end the block starts from: the anchor, or with ``from_fairlead`` the fairlead
    (which then lies at or above the surface: ``d = 0``). With ``from_fairlead`` the unknown
    ``V`` is the upward force the anchor exerts on the line's end there (the block's top
    tension), so that the floating length, next to the fairlead, is at the block's lower end.
    ``mu`` is unused (no friction along the surface).

    Returns
    -------
    dict
        ``SURFACE_OUTPUTS`` in the leg's orientation: ``LEG_OUTPUTS`` (``grounded`` 0) plus
        ``floating``, the unstretched length floating on the surface [m], and
        ``touchup_x``, the horizontal distance from the anchor at which the line first
        reaches the surface [m] (meaningful when ``floating > 0``).
    """
    del mu
    if not from_fairlead:
        o = surface_segment_equations(elastic, X, Z, d, u, V, L, w, ea_inv, model=model,
                                      law=law)
        return dict(rX=o["rX"], rZ=o["rZ"], H=o["H"], VF=o["VF"], HA=o["HA"], VA=o["VA"],
                    grounded=o["grounded"], suspended_x=X - o["descent_x"],
                    floating=o["floating"], touchup_x=o["descent_x"])
    o = surface_segment_equations(elastic, X, -Z, d, u, V, L, w, ea_inv, model=model, law=law)
    # Back to the leg's orientation: the fairlead holds the block's lower end, the anchor
    # its upper end.
    return dict(rX=o["rX"], rZ=-o["rZ"], H=o["H"], VF=-o["VA"], HA=o["HA"], VA=-o["VF"],
                grounded=o["grounded"], suspended_x=X - o["suspended_x"],
                floating=o["floating"], touchup_x=o["suspended_x"])


@lru_cache(maxsize=None)
def surface_leg_function(elastic: bool, from_fairlead: bool,
                         model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`surface_leg_equations` as a ``casadi.Function`` (inputs ``SURFACE_INPUTS``,
    and ``law`` for a stretch law ``model`` other than Hooke's; outputs
    ``SURFACE_OUTPUTS``)."""
    names, args, law = law_inputs(model if elastic else None, SURFACE_INPUTS)
    out = surface_leg_equations(elastic, from_fairlead, *args[:len(SURFACE_INPUTS)],
                                model=model, law=law)
    tag = law_tag(elastic, model) + ("_from_fairlead" if from_fairlead else "")
    return ca.Function(f"leg_surface_{tag}", args,
                       shared([out[k] for k in SURFACE_OUTPUTS], law), names,
                       list(SURFACE_OUTPUTS))


@lru_cache(maxsize=None)
def surface_segment_function(elastic: bool, between_joints: bool = False,
                             model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`surface_segment_equations` as a ``casadi.Function`` (inputs
    ``LIFTED_INPUTS`` with ``h`` the lower end's depth below the surface, and ``law`` for a
    stretch law ``model``; outputs ``SEGMENT_OUTPUTS + ("floating",)``)."""
    names_in, args, law = law_inputs(model if elastic else None, LIFTED_INPUTS)
    X, Z, h, u, V, L, w, ea_inv, _ = args[:len(LIFTED_INPUTS)]
    out = surface_segment_equations(elastic, X, Z, h, u, V, L, w, ea_inv, between_joints,
                                    model=model, law=law)
    names = SEGMENT_OUTPUTS + ("floating",)
    tag = law_tag(elastic, model) + ("_joints" if between_joints else "")
    return ca.Function(f"segment_surface_{tag}", args, shared([out[k] for k in names], law),
                       names_in, list(names))


def evaluate_surface_leg(elastic: bool, from_fairlead: bool, X, Z, u, V, L, w, ea_inv=0.0,
                         d=0.0, model=None, law=None) -> dict:
    """Evaluate :func:`surface_leg_function` on floats; a dict of floats."""
    extra = () if model is None else (list(law),)
    vals = surface_leg_function(elastic, from_fairlead, model)(X, Z, u, V, L, w, ea_inv, 0.0,
                                                               d, *extra)
    return {k: float(v) for k, v in zip(SURFACE_OUTPUTS, vals)}


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
    bound = bind(model, law) if elastic else None
    if bound is not None:
        k = L * (1 + bound.strain(T)) / T
    else:
        k = L * (1 / T + (ea_inv if elastic else 0))
    return dict(rX=H * k - X, rZ=V * k - Z, H=H, VF=V, HA=H, VA=V, grounded=0 * H,
                suspended_x=X, descent_x=0 * H)


@lru_cache(maxsize=None)
def lifted_segment_function(elastic: bool, friction: bool = False,
                            between_joints: bool = False,
                            model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`lifted_segment_equations` as a ``casadi.Function`` (inputs ``LIFTED_INPUTS``,
    and ``law`` for a stretch law ``model`` other than Hooke's)."""
    names, args, law = law_inputs(model if elastic else None, LIFTED_INPUTS)
    out = lifted_segment_equations(elastic, *args[:len(LIFTED_INPUTS)], friction=friction,
                                   between_joints=between_joints, model=model, law=law)
    tag = (law_tag(elastic, model) + ("_friction" if friction else "")
           + ("_joints" if between_joints else ""))
    return ca.Function(f"segment_lifted_{tag}", args,
                       shared([out[k] for k in SEGMENT_OUTPUTS], law), names,
                       list(SEGMENT_OUTPUTS))


STRAIGHT_INPUTS = ("X", "Z", "u", "V", "L", "ea_inv")


@lru_cache(maxsize=None)
def straight_segment_function(elastic: bool,
                              model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`straight_segment_equations` as a ``casadi.Function``."""
    names, args, law = law_inputs(model if elastic else None, STRAIGHT_INPUTS)
    out = straight_segment_equations(elastic, *args[:len(STRAIGHT_INPUTS)], model=model,
                                     law=law)
    return ca.Function(f"segment_straight_{law_tag(elastic, model)}", args,
                       shared([out[k] for k in SEGMENT_OUTPUTS], law), names,
                       list(SEGMENT_OUTPUTS))
