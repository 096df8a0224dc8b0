"""The line-tension check with the lines' own dynamics in the sea state.

For one condition (intact, or one line removed) whose bodies move in a sea state:

1. the motions about that condition's equilibrium, with the mean drift force, and the
   bodies held at API RP 2SK's design offset (:mod:`.design_offset`: the offset, anchor
   uplift and grounded length are checked there);
2. every line's dynamic tension at both ends (:func:`moorsolve.dynamics.line_sea.line_tensions`):
   the wave-frequency part from the line's lumped-mass dynamics driven by the bodies'
   motions at its ends, the low-frequency part from the slow drift through the line's
   quasi-static stiffness;
3. the standard's arithmetic (:mod:`.design_tension`), at the end of larger utilisation:

   * DNV-OS-E301 (2010) Ch.2 Sec.2: ``T_dyn = sigma_T sqrt(2 ln N)`` with ``sigma_T =
     sqrt(sigma_LF^2 + sigma_WF^2)`` and ``N = duration / T_z``; ``gamma_mean T_mean +
     gamma_dyn T_dyn <= 0.95 MBS``, ULS (intact) and ALS (one line removed) by consequence
     class;
   * API RP 2SK (3rd ed., 2005) sections 6.4.2 and 7.4, dynamic method: the larger of
     ``T_mean + T_LF,sig + T_WF,max`` and ``T_mean + T_LF,max + T_WF,sig`` (the
     combination API writes for the offset, applied to the tension's parts; ``sig`` is
     ``2 sigma``, ``max`` the most probable maximum in the storm) against ``MBL / SF``, SF
     1.67 intact and 1.25 damaged.

The damaged condition is the line already broken, the bodies at rest in their new mean
position and moving about it: the transient after the breakage (the overshoot as the body
swings to its new position) is not modelled.
"""

from __future__ import annotations

from .design_tension import DesignTension, design_tension

__all__ = ["METHOD_DYNAMIC", "TRANSIENT_NOTE", "dynamic_tension", "quasi_static_tension"]

#: What the check says it did (text, JSON, report), by standard.
METHOD_DYNAMIC = {
    "dnv-os-e301": ("DNV-OS-E301 with line dynamics: T_dyn = sigma_T sqrt(2 ln N) of each "
                    "line's wave-frequency (lumped-mass line driven by the bodies' motions) "
                    "and low-frequency (slow drift through the line's quasi-static "
                    "stiffness) tension, gamma_mean T_mean + gamma_dyn T_dyn <= 0.95 MBS"),
    "api-rp-2sk": ("API RP 2SK dynamic method: T_max = T_mean + the larger of T_LF,sig + "
                   "T_WF,max and T_LF,max + T_WF,sig from each line's dynamics in the sea "
                   "state, MBL/T_max >= 1.67 intact, 1.25 damaged"),
}
#: The damaged conditions' limit, said wherever they are checked in a sea state.
TRANSIENT_NOTE = ("damaged conditions are the line already broken, the bodies moving about "
                  "their new mean position: the transient after a breakage is not modelled")


def _ends(lr) -> tuple:
    return (("anchor", lr.anchor_tension_N), ("fairlead", lr.fairlead_tension_N))


def end_dynamic_part(sea_end, standard: str) -> float:
    """The dynamic part of one end's tension [N] as ``standard`` combines it: API RP 2SK's
    larger of LF_sig + WF_max and LF_max + WF_sig, DNV's sigma_T sqrt(2 ln N)."""
    if standard == "api-rp-2sk":
        return max(sea_end.lf_significant_N + sea_end.wf_max_N,
                   sea_end.lf_max_N + sea_end.wf_significant_N)
    return sea_end.t_dyn_N


def anchor_t_max(mean_leg, sea, standard: str) -> float:
    """The anchor end's largest tension in the sea state [N]: its mean plus its dynamic
    part (:func:`end_dynamic_part`), the load an anchor check takes with line dynamics."""
    return mean_leg.anchor_tension_N + end_dynamic_part(sea.anchor, standard)


def dynamic_tension(mean_leg, sea, *, standard: str, condition: str,
                    consequence_class: int) -> tuple:
    """``(end, DesignTension, EndSeaTension)`` of one line with its dynamics, at the end
    of larger utilisation.

    Parameters
    ----------
    mean_leg : LegResult
        The line at the mean equilibrium (its end tensions are ``T_mean`` [N]).
    sea : moorsolve.dynamics.line_sea.LineSeaTension
        Its dynamic tension in the sea state.
    standard : {"dnv-os-e301", "api-rp-2sk"}
    condition : {"intact", "damaged"}
    consequence_class : {1, 2}
        DNV's (API has none).
    """
    found = []
    for end, t_mean in _ends(mean_leg):
        s = getattr(sea, end)
        t_dyn = end_dynamic_part(s, standard)
        d = design_tension(standard=standard, condition=condition, t_mean=t_mean,
                           t_dyn=t_dyn, mbl=mean_leg.mbl_N,
                           consequence_class=consequence_class, method="dynamic")
        found.append((end, d, s))
    return max(found, key=lambda e: e[1].utilisation)


def quasi_static_tension(mean_leg, held_leg, *, standard: str, condition: str,
                         consequence_class: int) -> tuple:
    """``(end, DesignTension)`` of one line by the quasi-static method: its tension at the
    design offset, at the end where that is larger, ``T_dyn = T_offset - T_mean`` (no less
    than 0: a line that slackens there is checked at its mean tension, the body swinging
    back through the mean). API: ``SF T_max <= MBL``; DNV: ``gamma_mean T_mean + gamma_dyn
    T_dyn <= 0.95 MBS`` with that ``T_dyn``."""
    mean = dict(_ends(mean_leg))
    end, t_offset = max(_ends(held_leg), key=lambda e: e[1])
    t_mean = mean[end]
    d: DesignTension = design_tension(
        standard=standard, condition=condition, t_mean=t_mean,
        t_dyn=max(t_offset - t_mean, 0.0), mbl=held_leg.mbl_N,
        consequence_class=consequence_class, method="quasi_static")
    return end, d
