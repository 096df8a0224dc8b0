"""A leg whose anchor rests on a sloped seabed: the elastic catenary touching down on a slope.

The seabed in the leg's vertical plane rises ``t`` per metre from the anchor toward the
fairlead; the line touches it tangentially where its vertical tension is ``H t`` and lies
along it below, its tension changed by the weight along the slope and friction. The block
follows the conventions of :mod:`moorsolve.physics.catenary` (inputs, outputs, the signed
unknown ``u``, stretch laws through :mod:`moorsolve.physics.block_laws`).
"""

from __future__ import annotations

from functools import lru_cache
from typing import Optional

import casadi as ca

from .block_laws import bind, law_inputs, law_tag, shared
from .catenary import (_H_FLOOR, LATERAL_OUTPUTS, LEG_INPUTS, _hyp, lateral_stiffness,
                       loose_part, taut_part)
from .stretch import StretchModel

__all__ = ["SLOPED_INPUTS", "sloped_leg_equations", "sloped_leg_function"]

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
    Suspended part from the touchdown (Merkin 1980, sections 2.1, 2.3, integrated
    from the vertical tension ``H t`` instead of 0)::

        X_s = (H/w)[asinh(V/H) - asinh(t)] + H L_s/EA,   L_s = (V - H t)/w
        Z_s = [sqrt(H^2+V^2) - H sqrt(1+t^2)]/w + (V^2 - H^2 t^2)/(2 w EA)

    The grounded part adds ``(L_B + stretch)(cos, sin)(theta)`` with the stretch
    ``int T/EA ds`` over the slope. With ``t = 0`` this is :func:`~.catenary.leg_equations`. Another
    stretch law (``model`` with parameters ``law``) enters as there: the suspended part
    from ``T_v = H t``, the grounded part the loaded length times the mean strain between
    the anchor's and the touchdown's tension.
    The cross-slope component of the seabed's reaction (when the seabed's gradient is not in
    the leg's plane) is assumed taken by the soil; it does not enter the leg's plane.
    """
    H = taut_part(u)
    Hg = ca.fmax(H, _H_FLOOR)
    bound = bind(model, law) if elastic else None
    c = ea_inv if elastic and bound is None else 0
    sec = ca.sqrt(1 + t**2)
    cos_t, sin_t = 1 / sec, t / sec
    VA = V - w * L
    Xs = (H / w) * (ca.asinh(V / Hg) - ca.asinh(VA / Hg)) + H * L * c
    stretch_term = 0
    Zs = (_hyp(H, V) - _hyp(H, VA)) / w + L * c * (V - w * L / 2)

    Vtd = H * t
    loose = loose_part(u) / w
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
        stretch_term = (psi_V - psi_VA) / w
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
        lateral=lateral_stiffness(ca.logic_and(suspended, u >= 0), V, VA, w, L, c,
                                  stretch_term),
    )


@lru_cache(maxsize=None)
def sloped_leg_function(elastic: bool, friction: bool,
                        model: Optional[StretchModel] = None) -> ca.Function:
    """:func:`sloped_leg_equations` as a ``casadi.Function`` (inputs ``SLOPED_INPUTS``,
    and ``law`` for a stretch law ``model`` other than Hooke's)."""
    names, args, law = law_inputs(model if elastic else None, SLOPED_INPUTS)
    out = sloped_leg_equations(elastic, friction, *args[:len(SLOPED_INPUTS)], model=model,
                               law=law)
    tag = law_tag(elastic, model) + ("_friction" if friction else "")
    return ca.Function(f"leg_sloped_{tag}", args,
                       shared([out[k] for k in LATERAL_OUTPUTS], law), names,
                       list(LATERAL_OUTPUTS))
