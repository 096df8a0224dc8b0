"""The body of MoorPy's YAML: written and read as MoorPy's ``System.addBody`` arguments.

MoorPy 1.3's YAML reader skips ``bodies:`` (its branch is empty) and hangs ``vessel`` points
on a massless free body at the origin; ``System.addBody(type, r6, m, v, rCG, AWP, rM, f6Ext,
DOFs)`` is how MoorPy itself is given a body. The export writes the one body that carries
lines as those arguments (with its ``name`` and, MoorPy having no argument for them, its
extra 6x6 ``stiffness``), the vessel points in its frame; the import reads it back. MoorPy's
model is moorsolve's linear hydrostatics: weight ``m g`` at ``rCG``, buoyancy ``rho g v`` at
the metacentre ``rM`` (both body frame), heave restoring ``-rho g AWP z`` of the origin, and
``f6Ext`` a constant force and moment in the global frame.
"""

from __future__ import annotations

import math

from ..model import DOFS, PLANAR_DOFS

__all__ = ["moorpy_body", "with_body", "number"]


def number(src, value, path: str, *, ge=None, gt=None) -> float:
    """``value`` as a finite float within the bounds, or the file's error naming ``path``."""
    if isinstance(value, bool):
        raise src.error(path, f"{value!r} is not a number")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise src.error(path, f"{value!r} is not a number") from None
    if not math.isfinite(x):
        raise src.error(path, f"{value!r} is not a finite number")
    if ge is not None and x < ge:
        raise src.error(path, f"{value!r} must be >= {ge:g}")
    if gt is not None and not x > gt:
        raise src.error(path, f"{value!r} must be > {gt:g}")
    return x


def moorpy_body(body) -> dict:
    """A body as the keyword arguments of MoorPy 1.3's ``System.addBody`` (with its
    ``name``): ``type`` (0 free, 1 held), ``r6`` (the case pose: x, y, z [m], roll, pitch,
    yaw [rad]), ``DOFs`` (the free ones, 0 = surge .. 5 = yaw); where the case has them,
    ``m`` [kg] and ``rCG`` [m, body frame], the linear hydrostatics ``v`` [m^3], ``rM``
    [m, body frame] and ``AWP`` [m^2], and ``f6Ext``, the constant force [N, N m, global].
    ``stiffness`` (6x6, SI) carries the body's extra springs, which MoorPy has no argument
    for."""
    entry = {"name": body.name, "type": 0 if body.free else 1,
             "r6": [float(v) for v in body.position]
             + [math.radians(a) for a in body.orientation_deg],
             "DOFs": [DOFS.index(d) for d in body.free]}
    if body.mass is not None:
        entry.update(m=float(body.mass), rCG=[float(v) for v in body.centre_of_gravity])
    hydro = body.hydrostatics
    if hydro is not None:
        entry.update(v=float(hydro.displaced_volume),
                     rM=[float(v) for v in hydro.metacentre],
                     AWP=float(hydro.waterplane_area))
    force = body.loads.force
    if force is not None:
        entry["f6Ext"] = [float(v) for v in (force if len(force) == 6 else
                                             (force[0], force[1], 0.0, 0.0, 0.0, force[2]))]
    if body.stiffness is not None:
        entry["stiffness"] = [[float(v) for v in row] for row in body.stiffness]
    return entry


def _vector(src, value, path: str, n: int) -> list:
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise src.error(path, f"{value!r} must be a list of {n} numbers")
    return [number(src, v, f"{path}[{i}]") for i, v in enumerate(value)]


_BODY_KEYS = ("name", "type", "r6", "DOFs", "m", "rCG", "v", "rM", "AWP", "f6Ext", "stiffness")


def with_body(src, bodies, body_data: dict, form: str, why: str, report) -> tuple:
    """Apply the file's ``bodies`` entry (:func:`moorpy_body`'s keys, MoorPy's
    ``System.addBody`` arguments) to the body its vessel points ride; returns the case's
    form, why, and its body/legs or bodies/points/lines data."""
    if not isinstance(bodies, list) or len(bodies) != 1 or not isinstance(bodies[0], dict):
        raise src.error("bodies", "must be a list of one body (MoorPy's YAML rides its vessel "
                                  "points on one body)")
    b, path = bodies[0], "bodies[0]"
    extra = sorted(set(b) - set(_BODY_KEYS))
    if extra:
        raise src.error(f"{path}.{extra[0]}", f"unknown key; known: {', '.join(_BODY_KEYS)}")
    name = str(b.get("name", "body"))
    kind = b.get("type", 1)
    if kind not in (-1, 0, 1):
        raise src.error(f"{path}.type", f"{kind!r} must be 0 (free), 1 (fixed) or -1 (coupled)")
    r6 = _vector(src, b.get("r6", [0.0] * 6), f"{path}.r6", 6)
    dofs = b.get("DOFs", list(range(6)))
    if not isinstance(dofs, list) or any(not isinstance(d, int) or isinstance(d, bool)
                                         or not 0 <= d <= 5 for d in dofs):
        raise src.error(f"{path}.DOFs", f"{dofs!r} must list DOF indices 0 (surge) to 5 (yaw)")
    free = [DOFS[i] for i in sorted(set(dofs))] if kind == 0 else []
    body = {"name": name, "position": r6[:3],
            "orientation_deg": [math.degrees(a) for a in r6[3:]], "free": free}
    mass = number(src, b.get("m", 0.0), f"{path}.m", ge=0)
    if mass > 0:
        body["mass"] = mass
        body["centre_of_gravity"] = _vector(src, b.get("rCG", [0.0] * 3), f"{path}.rCG", 3)
    volume = number(src, b.get("v", 0.0), f"{path}.v", ge=0)
    area = number(src, b.get("AWP", 0.0), f"{path}.AWP", ge=0)
    if volume > 0 or area > 0:
        rm = b.get("rM", [0.0] * 3)
        rm = [0.0, 0.0, rm] if isinstance(rm, (int, float)) and not isinstance(rm, bool) else rm
        body["hydrostatics"] = {"displaced_volume": volume,
                                "metacentre": _vector(src, rm, f"{path}.rM", 3),
                                "waterplane_area": area}
    if "stiffness" in b:
        k = b["stiffness"]
        if not isinstance(k, list) or len(k) != 6:
            raise src.error(f"{path}.stiffness", "must be a 6x6 matrix [SI]")
        body["stiffness"] = [_vector(src, row, f"{path}.stiffness[{i}]", 6)
                             for i, row in enumerate(k)]
    force = _vector(src, b.get("f6Ext", [0.0] * 6), f"{path}.f6Ext", 6)
    report.converted.append(f"{path} ({name}): MoorPy's body (type {kind}, "
                            f"{'free in ' + ', '.join(free) if free else 'held'}) with "
                            + ", ".join(k for k in ("m", "rCG", "v", "rM", "AWP", "f6Ext",
                                                    "stiffness") if k in b) + "; its vessel "
                            "points are in its body frame")
    planar = (set(free) <= set(PLANAR_DOFS) and not any(force[2:5]) and r6 == [0.0] * 6
              and set(body) == {"name", "position", "orientation_deg", "free"})
    if form == "legs" and planar:
        data = dict(body_data, body={"free": free})
        if any(force):
            data["body"]["loads"] = {"force": [force[0], force[1], force[5]]}
        return form, why, data
    if any(force):
        body["loads"] = {"force": force}
    if form == "legs":
        lines = []
        for leg in body_data["legs"]:
            line = {k: v for k, v in leg.items() if k not in ("anchor", "fairlead")}
            line.update({"from": leg["anchor"], "to": {"body": name, "at": leg["fairlead"]}})
            lines.append(line)
        data = {k: v for k, v in body_data.items() if k not in ("body", "legs")}
        data.update(bodies=[body], lines=lines)
        return "network", "a body with mass, hydrostatics, springs or a pose", data
    carriers = body_data.get("bodies", [])
    if len(carriers) != 1:
        raise src.error("bodies", f"the vessel points ride {len(carriers)} bodies; one expected")
    old = carriers[0]["name"]
    for line in body_data.get("lines", []):
        for key in ("from", "to"):
            end = line[key]
            if isinstance(end, dict) and end.get("body") == old:
                end["body"] = name
    return form, why, dict(body_data, bodies=[body])
