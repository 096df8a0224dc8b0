"""The physics a scene calls for, named: the ``effects`` a Result lists (simulate only what
the scene calls for, and say which)."""

from __future__ import annotations

from . import body_loads as body_load_models


def scene_effects(case, kinds) -> list:
    """The physics a problem simulates, named as the Result's ``effects`` lists them:
    what its line kinds (``kinds``, one per line) and the case's bodies and loads call for."""
    effects = []
    if any(k.elastic for k in kinds):
        effects.append("elastic")
    if not all(k.elastic for k in kinds):
        effects.append("inextensible")
    if any(seg.line_type.stretch is not None for line in case.lines
           for seg in line.segments):
        effects.append("nonlinear_stretch")
    if any(k.contact for k in kinds):
        effects.append("seabed_contact")
    if any(k.surface for k in kinds):
        effects.append("surface_contact")
    if any(k.friction for k in kinds):
        effects.append("seabed_friction")
    if any(k.sloped for k in kinds):
        effects.append("sloped_seabed")
    if case.environment.seabed.bathymetry is not None:
        effects.append("bathymetry")
    types = [seg.line_type for line in case.lines for seg in line.segments]
    if any(lt.weight_in_water < 0 for lt in types):
        effects.append("buoyant_line")
    if any(k.neutral for k in kinds) or any(
            s.block == "straight" for k in kinds if k.multi for s in k.block.segments):
        effects.append("neutral_line")
    if any(lt.sealed for lt in types):
        effects.append("wall_tension")
    if any(line.multi_segment for line in case.lines):
        effects.append("multi_segment")
    if any(k.discrete for k in kinds):
        effects.append("line_drag")
    if case.free_points:
        effects.append("free_points")
    if len(case.bodies) > 1:
        effects.append("several_bodies")
    if any(b.mass is not None for b in case.bodies):
        effects.append("body_weight")
    if any(b.hydrostatics is not None for b in case.bodies):
        effects.append("hydrostatics")
    if any(b.hull for b in case.bodies):
        effects.append("exact_hydrostatics")
    if any(b.stiffness is not None for b in case.bodies):
        effects.append("springs")
    names = []
    for body in case.bodies:
        for e in body_load_models.effect_names(body.loads, case.environment):
            e = "constant_force" if e == "force" else e
            if e not in names:
                names.append(e)
    return effects + names
