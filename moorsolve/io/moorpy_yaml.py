"""MoorPy's YAML mooring description in and out: a second door into moorsolve.

MoorPy (``System(file="x.yaml")``, ``System.parseYAML``) and the tools built on it (RAFT's
``mooring:`` section, WEIS) describe a mooring as::

    water_depth: 200                  # [m]
    rho: 1025                         # water density [kg/m^3] (or water_density)
    line_types:
      - {name: chain, diameter: 0.15, mass_density: 140, stiffness: 6e8,   # d_vol [m],
         breaking_load: 7e6, cost: .., transverse_drag: .., ...}           # kg/m in air, EA
    points:
      - {name: anchor1, type: fixed, location: [x, y, z]}    # fixed / anchor
      - {name: fair1, type: vessel, location: [x, y, z]}     # vessel / fairlead (the body)
      - {name: buoy, type: free, location: [...], mass: 500, volume: 2}   # free / connect
    lines:
      - {name: line1, endA: anchor1, endB: fair1, type: chain, length: 850}

and the windIO/WEIS ontology spells the same ``nodes`` (``name, node_type: fixed | vessel |
connection, location, node_mass, node_volume``) and ``lines`` (``name, line_type,
unstretched_length, node1, node2``). A ``file:`` entry names a MoorDyn input file that
MoorPy loads instead; so does this reader. A top-level ``mooring:`` mapping (RAFT's design
files) is read the same way.

Meaning, as MoorPy gives it: the submerged weight is ``g (mass_density - rho pi d^2 / 4)``,
with MoorPy's default ``g = 9.81`` (the YAML has no gravity; this package writes and reads a
``gravity:`` key that MoorPy ignores); vessel points ride one body, *held* where the file
puts them (MoorPy makes it a free body without mass; moorsolve holds it, as a static solve
of a coupled body does), unless a ``bodies:`` entry gives that body in the keyword
arguments of MoorPy's ``System.addBody`` (``type, r6, DOFs, m, rCG, v, rM, AWP, f6Ext``,
and ``stiffness``, the extra 6x6 springs MoorPy has no argument for): then the vessel
points are in its body frame and it is free in its DOFs with its mass and hydrostatics.
MoorPy 1.3's own YAML reader skips ``bodies`` (the export's header says how to load it).
Lines take the legs form when the file is one body on anchor-to-fairlead chains, else the
network form, named as in the file.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from os import PathLike
from pathlib import Path

import numpy as np
import yaml

from ..errors import CaseError
from .import_report import ImportReport
from .moordyn import line_type_data, read_import, scene_case
from .moordyn_scene import MDLine, MDPoint, MDScene
from .moordyn_types import MDLineType
from .moordyn_write_types import export_diameter
from .moorpy_bodies import moorpy_body, number as _float, with_body
from .output_files import write_text

__all__ = ["MoorPyImport", "read_moorpy", "import_moorpy", "case_to_moorpy", "export_moorpy",
           "moorpy_body", "MOORPY_GRAVITY"]

#: MoorPy's ``System`` default gravity [m/s^2]; its YAML cannot set another.
MOORPY_GRAVITY = 9.81

_FIXED = ("anch", "fix")
_VESSEL = ("fair", "ves", "couple")
_FREE = ("con", "free")


class _Source:
    """Errors that name the YAML file and the entry (``x.yaml: points[3].location``)."""

    def __init__(self, name: str):
        self.name = name
        self.version = "MoorPy YAML"

    def error(self, where, message: str) -> CaseError:
        return CaseError(f"{self.name}: {where}" if where else self.name, message)


def _get(src, entry: dict, path: str, *keys, required=True, default=None):
    for key in keys:
        if key in entry:
            return entry[key]
    if required:
        raise src.error(path, f"missing {keys[0]!r}")
    return default


def _list(src, data: dict, key: str) -> list:
    items = data.get(key)
    if not isinstance(items, list):
        raise src.error(key, f"must be a list of entries, not {type(items).__name__}")
    for i, item in enumerate(items):
        if not isinstance(item, dict):
            raise src.error(f"{key}[{i}]", f"{item!r} is not a mapping")
    return items


def _location(src, value, path: str) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise src.error(path, f"{value!r} must be [x, y, z] [m]")
    return tuple(_float(src, v, f"{path}[{i}]") for i, v in enumerate(value))


_KNOWN = {"water_depth", "rho", "water_density", "gravity", "g", "line_types", "points",
          "lines", "nodes", "bodies", "file", "name", "anchor_types", "rods", "rod_types"}


def _scene(src, data: dict, report: ImportReport) -> tuple:
    depth = _float(src, _get(src, data, "water_depth", "water_depth"), "water_depth", gt=0)
    rho = _float(src, _get(src, data, "rho", "rho", "water_density", required=False,
                           default=1025.0), "rho", gt=0)
    g_given = _get(src, data, "gravity", "gravity", "g", required=False)
    gravity = MOORPY_GRAVITY if g_given is None else _float(src, g_given, "gravity", gt=0)
    report.converted.append(f"water depth {depth:g} m, water density {rho:g} kg/m^3, gravity "
                            f"{gravity:g} m/s^2" + (" (MoorPy's default: its YAML has none)"
                                                     if g_given is None else ""))
    windio = "nodes" in data
    types, mbl = {}, {}
    for i, t in enumerate(_list(src, data, "line_types")):
        path = f"line_types[{i}]"
        name = str(_get(src, t, path, "name"))
        if name in types:
            raise src.error(f"{path}.name", f"line type {name!r} is defined twice")
        d = _float(src, _get(src, t, path, "diameter"), f"{path}.diameter", ge=0)
        m = _float(src, _get(src, t, path, "mass_density"), f"{path}.mass_density", ge=0)
        ea = _float(src, _get(src, t, path, "stiffness"), f"{path}.stiffness", gt=0)
        columns = {}
        for key, col in (("transverse_drag", "cd"), ("tangential_drag", "cdax"),
                         ("transverse_added_mass", "ca"), ("tangential_added_mass", "caax")):
            if key in t:
                columns[col] = str(t[key])
        types[name] = MDLineType(name=name, line=path, diameter=d, mass=m, ea=ea,
                                 ea_token=repr(ea), columns=columns, layout=2)
        if "breaking_load" in t:
            mbl[name] = _float(src, t["breaking_load"], f"{path}.breaking_load", gt=0)
        extra = sorted(set(t) - {"name", "diameter", "mass_density", "stiffness",
                                 "breaking_load", "transverse_drag", "tangential_drag",
                                 "transverse_added_mass", "tangential_added_mass"})
        if extra:
            report.ignored.append(f"{path} ({name}): {', '.join(extra)}: not used by the "
                                  "statics")
    if not types:
        raise src.error("line_types", "no line types")

    points, ids = {}, {}
    key_points = "nodes" if windio else "points"
    for i, p in enumerate(_list(src, data, key_points)):
        path = f"{key_points}[{i}]"
        name = str(_get(src, p, path, "name", "node_id"))
        if name in ids:
            raise src.error(f"{path}.name", f"point {name!r} is defined twice")
        word = str(_get(src, p, path, "node_type" if windio else "type", "type", "node_type"))
        low = word.lower()
        if any(k in low for k in _FIXED):
            kind = "fixed"
        elif any(k in low for k in _VESSEL):
            kind = "coupled"
        elif any(k in low for k in _FREE):
            kind = "free"
        else:
            raise src.error(f"{path}.type", f"unknown point type {word!r}; MoorPy knows fixed "
                                             "(anchor), vessel (fairlead), free (connect); "
                                             "body<N> needs bodies, which its YAML lacks")
        location = _get(src, p, path, "location")
        if isinstance(location, (list, tuple)) and len(location) == 3 and \
                isinstance(location[2], str) and "seabed" in location[2].lower():
            location = list(location[:2]) + [-depth]
        xyz = _location(src, location, f"{path}.location")
        mass = _float(src, _get(src, p, path, "mass", "node_mass", required=False, default=0),
                      f"{path}.mass", ge=0)
        volume = _float(src, _get(src, p, path, "volume", "node_volume", required=False,
                                  default=0), f"{path}.volume", ge=0)
        pid = i + 1
        ids[name] = pid
        points[pid] = MDPoint(id=pid, line=path, kind=kind, word=word, body=None,
                              position=xyz, on_seabed=False, mass=mass, volume=volume,
                              force=(0.0, 0.0, 0.0), columns={})
    lines, names = {}, {}
    for i, ln in enumerate(_list(src, data, "lines")):
        path = f"lines[{i}]"
        tname = str(_get(src, ln, path, "type", "line_type"))
        if tname not in types:
            raise src.error(f"{path}.type", f"unknown line type {tname!r}; known: "
                                             f"{', '.join(types)}")
        ends = []
        for key, alt in (("endA", "node1"), ("endB", "node2")):
            end = str(_get(src, ln, path, key, alt))
            if end not in ids:
                raise src.error(f"{path}.{key}", f"unknown point {end!r}; points: "
                                                  f"{', '.join(ids)}")
            ends.append(("point", ids[end], None))
        if ends[0] == ends[1]:
            raise src.error(path, "starts and ends at the same point")
        length = _float(src, _get(src, ln, path, "length", "unstretched_length"),
                        f"{path}.length", gt=0)
        lid = i + 1
        if "name" in ln:
            names[lid] = str(ln["name"])
        lines[lid] = MDLine(id=lid, line=path, type=types[tname], ends=tuple(ends),
                            length=length, num_segs="", outputs="", tokens=())
    if not lines:
        raise src.error("lines", "no lines")
    for key in ("rods", "rod_types", "anchor_types"):
        if data.get(key):
            report.ignored.append(f"{key}: MoorPy's YAML reader does not read them either")
    extra = sorted(set(data) - _KNOWN)
    if extra:
        report.ignored.append("keys MoorPy does not read: " + ", ".join(map(str, extra)))
    report.read.append(f"{len(types)} line types, {len(points)} points, {len(lines)} lines"
                       + (" (windIO nodes)" if windio else ""))
    scene = MDScene(file=src, depth=depth, gravity=gravity, water_density=rho,
                    line_types=types, rod_types={}, bodies={}, rods={}, points=points,
                    lines=lines, options=[],
                    point_names={pid: name for name, pid in ids.items()}, line_names=names)
    return scene, mbl


@dataclass
class MoorPyImport:
    """A MoorPy YAML mapped onto a case: ``data``, the ``report`` and the ``form``."""

    source: str
    data: dict
    report: ImportReport
    form: str
    form_reason: str

    def header(self) -> str:
        lines = [f"Imported from the MoorPy YAML {self.source} by `moorsolve import-moorpy`.",
                 f"Case form: {self.form} ({self.form_reason}). The bodies have no loads: add "
                 "them.", ""]
        return "\n".join(lines + self.report.lines()) + "\n"

    def write(self, out) -> None:
        from .output_files import write_case_yaml
        write_case_yaml(self.data, out, self.header())


def read_moorpy(source) -> MoorPyImport:
    """Read a MoorPy (or windIO) mooring YAML and map it onto a validated case.

    Raises
    ------
    CaseError
        Naming the file and the entry (``moor.yaml: lines[2].endB: unknown point 'x'``).
    """
    if not isinstance(source, (str, PathLike)):
        raise CaseError("", f"{source!r} is not a path to a MoorPy YAML file")
    path = Path(source)
    src = _Source(path.name)
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise src.error(None, "MoorPy YAML file not found") from None
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        raise src.error(None, f"cannot read the YAML: {exc}") from None
    outer_name = data.get("name") if isinstance(data, dict) else None
    if isinstance(data, dict) and isinstance(data.get("mooring"), dict):
        data = dict(data["mooring"])
        if outer_name is not None:
            data.setdefault("name", outer_name)
    if not isinstance(data, dict):
        raise src.error(None, "the file holds no mapping of MoorPy keys")
    report = ImportReport(source=path.name)
    if data.get("file"):
        target = path.parent / str(data["file"])
        imp = read_import(target)
        imp.report.read.insert(0, f"{path.name}: 'file' names the MoorDyn file {target.name}, "
                                  "which MoorPy loads instead")
        return MoorPyImport(source=path.name, data=imp.data, report=imp.report, form=imp.form,
                            form_reason=imp.form_reason)
    report.read.append(f"MoorPy YAML ({'windIO nodes' if 'nodes' in data else 'points'} form)")
    scene, mbl = _scene(src, data, report)
    types, _ = line_type_data(scene, report, "not used by the statics")
    for tname, value in mbl.items():
        types[tname]["mbl"] = value
        report.converted.append(f"line type {tname}: breaking_load {value:g} N as its MBL")
    form, why, body_data, _ = scene_case(scene, report)
    if data.get("bodies"):
        form, why, body_data = with_body(src, data["bodies"], body_data, form, why, report)
    stem = os.path.splitext(path.name)[0] or "moorpy"
    name = str(data["name"]) if "name" in data else f"{stem} (imported from MoorPy YAML)"
    case = {"name": name,
            "environment": {"depth": scene.depth, "water_density": scene.water_density,
                            "gravity": scene.gravity},
            "line_types": types, **body_data}
    imp = MoorPyImport(source=path.name, data=case, report=report, form=form, form_reason=why)
    from .case_file import load_case
    try:
        load_case(case, keep_source=False)
    except CaseError as exc:
        if not (form == "network" and exc.field in ("bodies", "points", "lines")):
            raise CaseError(path.name, f"the imported case is not valid: {exc}") from None
        report.converted.append("network form: this moorsolve has no network loader yet; "
                                "the case is written in the contract's form, unvalidated")
    return imp


def import_moorpy(source, out=None) -> dict:
    """Read a MoorPy YAML, map it onto a case, validate it and optionally write the case YAML
    (with the import report as its leading comment); returns the case dictionary."""
    imp = read_moorpy(source)
    if out is not None:
        imp.write(out)
    return imp.data


# ---- out -----------------------------------------------------------------------------------


def case_to_moorpy(case) -> dict:
    """A case (either form) as MoorPy's YAML mapping.

    Every line becomes one MoorPy line per segment, joined by a ``free`` point per joint
    (with its clump's mass and volume; ``<line>_joint<k>``). Its ends: a case point keeps
    its name and type (``fixed``, or ``free`` with mass and volume); a fixed end given as
    coordinates becomes a ``fixed`` point, a body end a ``vessel`` point at its place in the
    body frame (``<line>_A``, ``<line>_B``; MoorPy's YAML holds one vessel, so at most one
    body may carry lines), and that body a ``bodies`` entry (:func:`moorpy_body`). Line
    types get MoorPy's volume-equivalent diameter and the mass per metre that gives the case's weight in water with the case's gravity
    (written as ``gravity:``, which MoorPy does not read: create its System with that
    ``g``).

    Raises
    ------
    CaseError
        An inextensible line (MoorPy needs EA), a buoyant line without a diameter, lines on
        more than one body.
    """
    from ..model.build_network import end_position
    env = case.environment
    g, rho = env.gravity, env.water_density
    types = []
    for name, lt in case.line_types.items():
        if lt.stretch is not None:
            raise CaseError(f"line_types.{name}.stretch",
                            f"a {lt.stretch.model} stretch law cannot be written to MoorPy's "
                            "YAML, which takes one stiffness number; export it to MoorDyn "
                            "(its EA column names a tension-strain file)")
        if lt.ea is None:
            raise CaseError(f"line_types.{name}.ea", "an inextensible line cannot be written "
                                                     "for MoorPy, which needs EA; give ea [N]")
        d = export_diameter(lt, env)
        entry = {"name": name, "diameter": d,
                 "mass_density": lt.weight_in_water / g + rho * math.pi * d ** 2 / 4.0,
                 "stiffness": lt.ea}
        if lt.mbl is not None:
            entry["breaking_load"] = lt.mbl
        types.append(entry)
    bodies = {b.name: b for b in case.bodies}
    carriers = sorted({end.body for line in case.lines for end in (line.a, line.b)
                       if end.body is not None})
    if len(carriers) > 1:
        raise CaseError("bodies", f"lines end on {len(carriers)} bodies ({', '.join(carriers)}); "
                                  "MoorPy's YAML holds one vessel")
    points, lines, written = [], [], {}
    for p in case.points:
        entry = {"name": p.name, "type": "free" if p.free else "fixed",
                 "location": list(p.position)}
        if p.free:
            entry.update(mass=p.mass, volume=p.volume)
        points.append(entry)
        written[p.name] = entry

    def end_name(line, end, tag: str) -> str:
        if end.point is not None:
            return end.point
        name = end.label if end.fixed and end.label else f"{line.name}_{tag}"
        if name not in written:
            kind = "fixed" if end.fixed else "vessel"
            # A vessel point's location is in the body frame (MoorPy attaches it to the
            # body at that relative position); a fixed one's in the scene.
            where = [float(v) for v in (end.position if end.body is not None
                                        else end_position(end, bodies))]
            written[name] = {"name": name, "type": kind, "location": where}
            points.append(written[name])
        return name

    for line in case.lines:
        names = [end_name(line, line.a, "A")]
        a, b = (np.asarray(end_position(e, bodies), dtype=float) for e in (line.a, line.b))
        for k, clump in enumerate(line.joint_clumps, start=1):
            t = sum(s.length for s in line.segments[:k]) / line.length
            entry = {"name": f"{line.name}_joint{k}", "type": "free",
                     "location": [float(v) for v in a + t * (b - a)]}
            if clump is not None:
                mass = clump.mass if clump.mass is not None else max(clump.weight, 0.0) / g
                volume = (clump.volume or 0.0) if clump.mass is not None else \
                    max(-clump.weight, 0.0) / (g * rho)
                entry.update(mass=mass, volume=volume)
            points.append(entry)
            names.append(entry["name"])
        names.append(end_name(line, line.b, "B"))
        for k, seg in enumerate(line.segments):
            lines.append({"name": f"{line.name}_{k + 1}" if len(line.segments) > 1 else line.name,
                          "endA": names[k], "endB": names[k + 1], "type": seg.line_type.name,
                          "length": seg.length})
    data = {"name": case.name, "water_depth": env.depth, "rho": rho, "gravity": g,
            "line_types": types, "points": points, "lines": lines}
    if carriers:
        data["bodies"] = [moorpy_body(bodies[carriers[0]])]
    return data


def export_moorpy(case, out) -> dict:
    """Write :func:`case_to_moorpy` of a case (or a case file) to ``out`` (atomically), with a
    comment on gravity and the body; returns the mapping."""
    from .case_file import load_case
    if isinstance(case, (str, PathLike)):
        case = load_case(case)
    if case.environment.seabed.bathymetry is not None:
        raise CaseError("environment.seabed.bathymetry", "MoorPy's YAML has no bathymetry "
                        "entry (MoorPy takes a grid as System(bathymetry=<SeafloorFile>)); "
                        "export-moordyn writes the grid as a SeafloorFile")
    if case.environment.seabed.sloped:
        raise CaseError("environment.seabed.gradient", "MoorPy's YAML has a flat water_depth; "
                                                       "use a flat seabed")
    for i, body in enumerate(case.bodies):
        if body.hull:
            raise CaseError(f"bodies[{i}].hull", "MoorPy has no exact hull members; give the "
                            "body the linear hydrostatics (displaced_volume, metacentre, "
                            "waterplane_area) to export it")
    data = case_to_moorpy(case)
    header = (f"# MoorPy mooring YAML of the moorsolve case {case.name!r}.\n"
              f"# gravity {case.environment.gravity:g} m/s^2: MoorPy does not read the "
              f"'gravity' key; create the System with g={case.environment.gravity:g}.\n")
    for body in data.get("bodies", []):
        model = case.body_named(body["name"])
        flows = [k for k in ("wind", "current", "wave_drift")
                 if getattr(model.loads, k) is not None]
        header += (
            f"# 'bodies' holds the body {body['name']!r} as MoorPy's System.addBody arguments "
            "(MoorPy 1.3's YAML reader skips 'bodies'); its vessel points are in its body "
            "frame. Load the whole scene with\n"
            "#   d = yaml.safe_load(open(FILE)); ms = moorpy.System(depth=d['water_depth'], "
            "rho=d['rho'], g=d['gravity'])\n"
            "#   b = d['bodies'][0]; ms.addBody(b['type'], b['r6'], m=b.get('m', 0), "
            "v=b.get('v', 0), rCG=b.get('rCG', [0, 0, 0]), AWP=b.get('AWP', 0), "
            "rM=b.get('rM', [0, 0, 0]), f6Ext=b.get('f6Ext', [0] * 6), DOFs=b['DOFs'])\n"
            "#   ms.parseYAML(d); ms.initialize(); ms.solveEquilibrium()\n"
            "# (System(file=FILE) alone makes a free body without mass at the origin.)\n")
        if "stiffness" in body:
            header += ("# 'stiffness' (extra 6x6 springs) has no MoorPy argument: MoorPy "
                       "solves without it.\n")
        if flows:
            header += (f"# Not written (no MoorPy form): the {', '.join(flows)} load model"
                       f"{'s' if len(flows) > 1 else ''}.\n")
    text = header + yaml.safe_dump(data, sort_keys=False, default_flow_style=None)
    write_text(out, text)
    return data

