"""The validated description of a mooring scene.

Frozen dataclasses, SI units throughout, degrees only in names ending ``_deg``. A
:class:`Case` is what every other part of moorsolve consumes; :func:`build_case` makes one
from plain data (a case-file dictionary) and checks it, whatever the source (YAML, a dict,
a MoorDyn file). Nothing here imports CasADi.

Coordinates: x, y horizontal, z up, z = 0 at the still-water level, seabed at z = -depth
(or a plane through that point at the origin, :class:`Seabed`). ``toward_deg`` is the
direction a wind, current or wave train travels toward, counter-clockwise from +x.
"""

from .environment import Environment, Flow, Seabed, Waves
from .bodies import DOFS, PLANAR_DOFS, Body, Hydrostatics, HullMember, Point, ShipOutline
from .lines import ANCHOR_KINDS, AnchorType, Clump, End, Leg, Line, LineDrag, LineType, Segment
from .loads import (BodyLoads, DragLoad, DriftCoefficient, HuTangCurrent, HuTangDrift,
                    HuTangWind)
from .scene import DEGREES_OF_FREEDOM, STANDARDS, Case, Checks, SolverOptions
from .contact import Contacts, Fender, Guide, Pile, ReactionLaw, Wall

__all__ = ["Environment", "Flow", "Seabed", "Waves", "ANCHOR_KINDS", "AnchorType", "Clump",
           "End", "Leg", "Line", "LineDrag", "LineType", "Segment", "DOFS", "PLANAR_DOFS",
           "Body", "Hydrostatics", "HullMember", "Point", "ShipOutline", "BodyLoads", "DragLoad",
           "DriftCoefficient", "HuTangCurrent", "HuTangDrift", "HuTangWind",
           "DEGREES_OF_FREEDOM", "STANDARDS", "Case", "Checks", "SolverOptions",
           "Contacts", "Fender", "Guide", "Pile", "ReactionLaw", "Wall"]

from .._lazy import lazy_exports  # noqa: E402

# Building validates (and may convert units): imported on first use.
__getattr__, __dir__ = lazy_exports(__name__, {"build_case": ".build"}, globals())

__all__ += ["build_case"]


def _with_values(self, assignments, *, keep_source: bool = True) -> Case:
    """This case with each ``path: value`` of ``assignments`` set in its case-file data
    and validated again (:func:`moorsolve.model.edit.with_values`); no file is read."""
    from .edit import with_values
    return with_values(self, assignments, keep_source=keep_source)


# Bound here, above both the data (scene.py) and the builder it needs (edit.py, build.py),
# so that the data's module imports no builder (no import cycle).
_with_values.__name__ = _with_values.__qualname__ = "with_values"
Case.with_values = _with_values
