"""A condition that leaves a body held by nothing: name the body, say why, check the rest.

Removing a line can leave a body with no horizontal restoring (a tanker on its one hawser to
a CALM buoy; :func:`moorsolve.model.restraint.drifting_bodies`). No equilibrium exists then
under any horizontal load, and a solver's "no equilibrium" would hide what happened. The
check instead reports the body as lost, with the environmental load that carries it away,
and solves the rest of the mooring with the lost bodies held where the case puts them (they
no longer act on it: no line joins them to it), so the remaining lines are still checked.
"""

from __future__ import annotations

import dataclasses
import math

from ..model import Case
from ..model.restraint import Drift

__all__ = ["hold_drifting", "drift_findings"]

_LOAD_WORDS = {"force": "the constant force", "wind": "the wind", "current": "the current",
               "wave_drift": "the wave drift"}


def hold_drifting(scene: Case, drifts: list) -> Case:
    """``scene`` with every drifting body held at its case pose (nothing else changes)."""
    lost = {d.body for d in drifts}
    bodies = tuple(dataclasses.replace(b, free=()) if b.name in lost else b
                   for b in scene.bodies)
    return dataclasses.replace(scene, bodies=bodies, source=None)


def drift_findings(drifts: list[Drift], loads: dict | None) -> tuple:
    """One dict per drifting body: ``body``, ``dofs``, ``group``, ``lines``, the horizontal
    environmental load on it ``load_N`` [N] and its direction ``toward_deg`` (None without
    a load), and the ``message``.

    ``loads`` is :attr:`moorsolve.Result.loads` of the scene with the bodies held (``None``
    when it has no solve).
    """
    out = []
    for d in drifts:
        fx = fy = 0.0
        names = []
        for key, value in (loads or {}).items():
            body, _, model = key.rpartition(".")
            if body != d.body or math.hypot(value[0], value[1]) == 0.0:
                continue
            fx, fy = fx + value[0], fy + value[1]
            names.append(_LOAD_WORDS.get(model, model))
        load = math.hypot(fx, fy)
        toward = None
        if load > 0:
            toward = round(math.degrees(math.atan2(fy, fx)), 1) % 360.0
            push = " and ".join([", ".join(names[:-1]), names[-1]] if len(names) > 1 else names)
            message = (f"{d.describe()} and drifts off: {d.restores}, and {push} "
                       f"push{'es' if len(names) == 1 else ''} it {load / 1e3:.1f} kN toward "
                       f"{round(toward) % 360:d} deg")
        else:
            message = (f"{d.describe()}: {d.restores}; it drifts off under any horizontal "
                       "load (none acts on it in this condition)")
        out.append({"body": d.body, "dofs": list(d.dofs), "group": list(d.group),
                    "lines": list(d.lines), "load_N": load if load > 0 else None,
                    "toward_deg": toward, "message": message})
    return tuple(out)
