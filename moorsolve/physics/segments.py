"""The segments of a multi-segment line and the lines bounded by the free surface.

In a line of several segments every joint is a free node (:mod:`moorsolve.solve.lines.blocks`). A
segment whose lower end is the anchor on the seabed is the leg block of
:mod:`.catenary`; the others use the blocks here: a sinking segment whose lower end may be
lifted off the seabed (two-sided touchdown), a buoyant segment or leg held down by the free
surface (the seabed's forms mirrored), and a weightless straight segment. Every regime is
selected inside the symbolic graph, as in :mod:`.catenary`, and every block takes a stretch
law the same way.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Optional

import casadi as ca

from .block_laws import bind, ground_stretch, law_inputs, law_tag, shared
from .catenary import (_H_FLOOR, LEG_INPUTS, LEG_OUTPUTS, _hyp, _suspended_spans,
                       lateral_stiffness, loose_part, taut_part)
from .stretch import StretchModel


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
    (Merkin 1980, section 2.1: ``z = (sqrt(H^2 + T_v^2) - H)/w`` from the vertex).
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
    H = taut_part(u)
    Hg = ca.fmax(H, _H_FLOOR)
    bound = bind(model, law) if elastic else None
    c = ea_inv if elastic and bound is None else 0
    VA = V - w * L
    V1 = descent_force(H, h, w, c, bound)
    Xs, Zs = _suspended_spans(H, Hg, V, VA, w, L, c)
    stretch_term = 0
    s1 = -V1 / w
    x1 = (H / w) * ca.asinh(-V1 / Hg) + H * s1 * c
    LB = L - s1 - V / w
    x_rise = (H / w) * ca.asinh(V / Hg) + H * (V / w) * c
    Xt = x1 + LB * (1 + H * c) + x_rise
    Zt = -h + ca.sign(V) * (_hyp(H, V) - _hyp(H, 0)) / w + c * V * ca.fabs(V) / (2 * w)
    if bound is not None:
        psi_V, psi_VA, psi_1 = bound.horizontal(Hg, V, VA, -V1)
        Xs = Xs + (H / w) * (psi_V - psi_VA)
        stretch_term = (psi_V - psi_VA) / w
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
    loose = loose_part(u) / w
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
        lateral=lateral_stiffness(ca.logic_and(suspended, u >= 0), V, VA, w, L, c,
                                  stretch_term),
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
    (A buoyant line meets the surface as a chain
    meets the seabed, mirrored). The surface carries the floating part's buoyancy as the
    seabed carries a grounded part's weight; no drag or friction acts along it.
    """
    m = lifted_segment_equations(elastic, X, -Z, d, u, -V, L, -w, ea_inv,
                                 between_joints=between_joints, model=model, law=law)
    return dict(rX=m["rX"], rZ=-m["rZ"], H=m["H"], VF=-m["VF"], HA=m["HA"], VA=-m["VA"],
                grounded=0 * m["H"], floating=m["grounded"], suspended_x=m["suspended_x"],
                descent_x=m["descent_x"], lateral=m["lateral"])


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
                    floating=o["floating"], touchup_x=o["descent_x"], lateral=o["lateral"])
    o = surface_segment_equations(elastic, X, -Z, d, u, V, L, w, ea_inv, model=model, law=law)
    # Back to the leg's orientation: the fairlead holds the block's lower end, the anchor
    # its upper end.
    return dict(rX=o["rX"], rZ=-o["rZ"], H=o["H"], VF=-o["VA"], HA=o["HA"], VA=-o["VF"],
                grounded=o["grounded"], suspended_x=X - o["suspended_x"],
                floating=o["floating"], touchup_x=o["suspended_x"], lateral=o["lateral"])


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
    outputs = SURFACE_OUTPUTS + ("lateral",)
    return ca.Function(f"leg_surface_{tag}", args, shared([out[k] for k in outputs], law),
                       names, list(outputs))


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
    names = SEGMENT_OUTPUTS + ("floating", "lateral")
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
    H = taut_part(u)
    T = ca.sqrt(H**2 + V**2 + _H_FLOOR**2)
    bound = bind(model, law) if elastic else None
    if bound is not None:
        k = L * (1 + bound.strain(T)) / T
    else:
        k = L * (1 / T + (ea_inv if elastic else 0))
    return dict(rX=H * k - X, rZ=V * k - Z, H=H, VF=V, HA=H, VA=V, grounded=0 * H,
                suspended_x=X, descent_x=0 * H, lateral=1 / k)


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
    outputs = SEGMENT_OUTPUTS + ("lateral",)
    return ca.Function(f"segment_lifted_{tag}", args,
                       shared([out[k] for k in outputs], law), names, list(outputs))


STRAIGHT_INPUTS = ("X", "Z", "u", "V", "L", "ea_inv")


@lru_cache(maxsize=None)
def straight_segment_function(elastic: bool,
                              model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`straight_segment_equations` as a ``casadi.Function``."""
    names, args, law = law_inputs(model if elastic else None, STRAIGHT_INPUTS)
    out = straight_segment_equations(elastic, *args[:len(STRAIGHT_INPUTS)], model=model,
                                     law=law)
    outputs = SEGMENT_OUTPUTS + ("lateral",)
    return ca.Function(f"segment_straight_{law_tag(elastic, model)}", args,
                       shared([out[k] for k in outputs], law), names, list(outputs))
