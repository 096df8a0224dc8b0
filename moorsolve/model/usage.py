"""Inputs that no model uses: given in the case, ignored by every part of the solve.

A case may say more than its models can hear: waves with no wave-drift model, a current
that neither the body nor any line feels, a body load model without its flow, line drag
without a current, a line type no leg uses. The solve is still right for what it does
model, but a silent drop is how a wrong answer goes unnoticed, so :func:`unused_inputs`
names each such input with what would make it count, and :func:`moorsolve.load_case`
issues each as an :class:`~moorsolve.errors.UnusedInputWarning`.

Inputs kept for other commands are not reported: ``checks`` (``moorsolve check``),
``moordyn`` (export) and a line type's ``diameter`` and ``mbl`` (reports and export).
"""

from __future__ import annotations

from collections.abc import Mapping

from .scene import Case

__all__ = ["unused_inputs"]

_FLOW_MODEL = {"wind": "wind", "current": "current", "waves": "wave_drift"}


def _line_drag(case: Case) -> list[str]:
    """Names of the line types with drag data that some leg uses."""
    used = {seg.line_type.name for leg in case.legs for seg in leg.segments}
    return [name for name, lt in case.line_types.items() if lt.drag is not None and name in used]


def unused_inputs(case: Case) -> list[tuple[str, str]]:
    """Each input of ``case`` that no model uses, as ``(field, message)``.

    Parameters
    ----------
    case : Case
        A validated case; ``case.source`` (the case-file data) adds the checks of keys
        whose default cannot be told from the value (``air_density``,
        ``solver.line_elements``).

    Returns
    -------
    list of (str, str)
        The dotted field and a sentence saying why nothing uses it and what would.
    """
    env = case.environment
    bodies = _bodies(case)
    drag_types = _line_drag(case)
    out = []
    moving = [path for path, body in bodies if getattr(body, "hydrodynamics", None) is not None]
    for flow, model in _FLOW_MODEL.items():
        if getattr(env, flow) is None:
            continue
        if any(getattr(body.loads, model) is not None for _, body in bodies):
            continue
        if flow == "waves" and env.waves.sea_state and moving:
            continue
        if flow == "current" and drag_types:
            continue
        where = bodies[0][0] if len(bodies) == 1 else "bodies[...]"
        what = f"{where}.loads.{model}"
        if flow == "current":
            what += " or a line type with drag (and a diameter)"
        kind = model.replace("_", " ")
        holder = ("there is no body" if not bodies else
                  f"the body declares no {kind} load model" if len(bodies) == 1 else
                  f"no body declares a {kind} load model")
        out.append((f"environment.{flow}",
                    f"given but not used: {holder}; add {what} for it to act"))
    if env.waves is not None and env.waves.sea_state and not moving:
        out.append(("environment.waves.tp" if env.waves.tp is not None
                    else "environment.waves.spectrum",
                    "given but not used by the static solve: no body has hydrodynamics "
                    "(bodies[i].hydrodynamics) to move in the sea state"))
    fatigue = getattr(getattr(case, "checks", None), "fatigue", None) is not None
    for path, body in bodies:
        if getattr(body, "hydrodynamics", None) is not None and not fatigue and (
                env.waves is None or not env.waves.sea_state):
            out.append((f"{path}.hydrodynamics",
                        "given but not used: the environment has no sea state (give "
                        "environment.waves with hs and tp) and checks.fatigue no "
                        "scatter diagram"))
    if env.current is not None and env.current.profile and not drag_types:
        out.append(("environment.current.profile",
                    "given but not used: only lines with drag data see the current profile "
                    "(give a line type drag: {normal: ...} and a diameter)"))
    for path, body in bodies:
        for flow, model in _FLOW_MODEL.items():
            if getattr(body.loads, model) is not None and getattr(env, flow) is None:
                out.append((f"{path}.loads.{model}",
                            f"given but not used: the environment has no {flow} "
                            f"(add environment.{flow})"))
    if env.current is None:
        for name in drag_types:
            out.append((f"line_types.{name}.drag",
                        "given but not used: line drag acts only in a current "
                        "(add environment.current)"))
    used = {seg.line_type.name for leg in case.legs for seg in leg.segments}
    for name in case.line_types:
        if name not in used:
            out.append((f"line_types.{name}", "given but not used by any leg"))
    if env.seabed.friction > 0 and not any(_rests_on_seabed(case, leg) for leg in case.legs):
        out.append(("environment.seabed.friction",
                    "given but not used: no leg has its anchor on the seabed with a line "
                    "that sinks, so no line can lie on it"))
    out += _source_only(case, drag_types)
    return out


def _bodies(case: Case) -> list:
    """``(field path, body)`` of every body: ``body`` in the one-body form of a case,
    ``bodies[i]`` in the network form."""
    if getattr(case, "form", "legs") == "legs":
        return [("body", case.body)] if case.body is not None else []
    return [(f"bodies[{i}]", body) for i, body in enumerate(case.bodies)]


def _rests_on_seabed(case: Case, line) -> bool:
    """Whether a line can lie on the seabed: an end held on it (an anchor) with a sinking
    segment there, or an end at a free point (which may sink onto it)."""
    env = case.environment
    ends = ((getattr(line, "a", None), line.segments[0]),
            (getattr(line, "b", None), line.segments[-1]))
    for end, seg in ends:
        if end is None:
            continue
        if end.point is not None and any(p.name == end.point and p.free for p in case.points):
            return True
        if end.body is None and end.point is None:
            x, y, z = end.position
            if z <= env.seabed_z(x, y) + 1e-9 * max(env.depth, 1.0) \
                    and seg.line_type.weight_in_water > 0:
                return True
    return False


def _source_only(case: Case, drag_types) -> list[tuple[str, str]]:
    """Checks that need the case-file data: keys whose value equals the default."""
    source = case.source
    if not isinstance(source, Mapping):
        return []
    out = []
    env_data = source.get("environment")
    wind_models = case.environment.wind is not None and any(
        body.loads.wind is not None for _, body in _bodies(case))
    if isinstance(env_data, Mapping) and "air_density" in env_data and not wind_models:
        out.append(("environment.air_density",
                    "given but not used: only a wind load model uses it (body.loads.wind "
                    "with environment.wind)"))
    solver_data = source.get("solver")
    discretised = case.environment.current is not None and drag_types
    if isinstance(solver_data, Mapping) and "line_elements" in solver_data \
            and not discretised:
        out.append(("solver.line_elements",
                    "given but not used: only lines with drag data in a current are "
                    "discretised"))
    return out
