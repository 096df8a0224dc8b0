"""MoorDyn input files in: read a MoorDyn v1 or v2 file as MoorDyn reads it and map it onto a
moorsolve case, reporting what was read, what was converted and what was ignored.

Reading (:mod:`.moordyn_parse`, :mod:`.moordyn_scene`) follows MoorDyn's own parsers and
refuses only what they refuse (plus words that are not numbers where numbers belong), with
the file, the line, the column and how the format version was told.

The mapping chooses one of two case forms:

- **legs** (``body:`` + ``legs:``): the file is one carrier of fairleads (a Coupled, Fixed or
  Turbine body, or the Coupled/Vessel points, all *held* where the file puts them, as MoorDyn
  and MoorPy hold a coupled body in a static solve) on lines that run, alone or joined end
  to end through free points, from a fixed point up to the carrier. Each such chain is one
  leg named ``L<id>`` after the MoorDyn line at its anchor; a joint's mass and volume become
  a clump. The ``moordyn`` block maps
  every leg back to its MoorDyn lines and points.
- **network** (``bodies``, ``points``, ``lines``):
  everything else (bridles and hubs, lines ending at free points, several carriers or none,
  Free and CoupledPinned bodies, rods with lines): every MoorDyn line becomes ``line<N>`` with
  end A at its AttachA. See :mod:`.moordyn_network`.

Line types keep their names; the submerged weight is ``g (Mass/m - rho pi Diam^2 / 4)``
(Diam is MoorDyn's volume-equivalent diameter), EA the static stiffness. WtrDpth, g and
rho go to the environment (MoorDyn's defaults where absent); every column moorsolve does not
use goes to the ``moordyn`` block (:mod:`moorsolve.model.moordyn_block`) and comes back on
export. The case gets no loads: it solves at rest until loads are added.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from os import PathLike

from ..errors import CaseError
from ..model.fields import MIN_WEIGHT
from .import_report import ImportReport
from .moordyn_graph import Graph, build_graph
from .moordyn_network import body_held, network_case
from .moordyn_parse import MoorDynError, MoorDynFile, Row, read_moordyn
from .moordyn_scene import (DEFAULT_GRAVITY, DEFAULT_WATER_DENSITY, MDScene, read_scene,
                            vertical_force)
from .moordyn_syrope import is_syrope
from .output_files import write_case_yaml

__all__ = ["MoorDynError", "MoorDynFile", "MoorDynImport", "Row", "read_moordyn",
           "moordyn_to_case_data", "convert_moordyn", "read_import", "import_moordyn",
           "scene_case", "line_type_data"]


# ---- line types and the environment -------------------------------------------------------

#: A line type whose weight in water is below this share of its weight in air is taken as
#: neutrally buoyant.
NEUTRAL_SHARE = 1e-6


def line_type_data(scene: MDScene, report: ImportReport,
                   kept: str = "kept in the moordyn block for export") -> tuple:
    """Case line types, their passthrough columns, and a report entry per type."""
    g, rho = scene.gravity, scene.water_density
    types, passthrough = {}, {}
    for lt in scene.line_types.values():
        weight = g * (lt.mass - rho * math.pi * lt.diameter ** 2 / 4.0)
        if weight and abs(weight) < max(MIN_WEIGHT, NEUTRAL_SHARE * g * lt.mass):
            # A line within a millionth of neutral (MoorDyn's pendulum tests: "the same
            # density as water") is neutral: its catenary would carry its weight to no
            # digit that matters, and lose precision doing it.
            report.converted.append(f"line type {lt.name}: weight in water {weight:.3g} N/m, "
                                    f"{abs(weight) / (g * lt.mass):.2g} of its weight in air "
                                    f"(below {NEUTRAL_SHARE:g}, or below the case's "
                                    f"{MIN_WEIGHT:g} N/m): a neutrally buoyant line, taken as 0")
            weight = 0.0
        if lt.stretch is not None:
            entry = {"weight_in_water": weight, "stretch": lt.stretch}
            source = ("the SYROPE rope's static law" if is_syrope(lt.ea_token)
                      else f"EA from the curve file {lt.ea_token.split('|')[0]!r}")
            stiffness = (f"{source}: a table law of {len(lt.stretch['strain'])} rows, "
                         "linear between the rows as MoorDyn reads them")
        else:
            entry = {"weight_in_water": weight, "ea": lt.ea}
            static = (" (the static part of " + repr(lt.ea_token) + ")"
                      if "|" in lt.ea_token else "")
            stiffness = f"EA {lt.ea:g} N{static}"
        if lt.diameter > 0:
            entry["diameter"] = lt.diameter
        types[lt.name] = entry
        passthrough[lt.name] = dict(lt.columns)
        report.converted.append(f"line type {lt.name} (line {lt.line}): weight in water "
                                f"{weight:.6g} N/m = g (Mass/m {lt.mass:g} - rho pi Diam^2/4, "
                                f"Diam {lt.diameter:g} m), {stiffness}")
    dyn = sorted({k for cols in passthrough.values() for k in cols if k != "ea"})
    if dyn:
        report.ignored.append("line-type columns " + ", ".join(dyn) + " (damping, bending, "
                              f"drag, added mass, lift): dynamic only; {kept}")
    return types, passthrough


# ---- the legs form --------------------------------------------------------------------------


def _chains(graph: Graph):
    """Chains of lines through free points that join exactly two lines, as
    ``(first node, [(line id, reversed)], last node)``, or None when a free point joins
    one line or more than two, or lines close a loop."""
    scene = graph.scene
    if any(n.kind == "free" and len(graph.at[k]) != 2 for k, n in graph.nodes.items()):
        return None
    used, chains = set(), []
    for lid in sorted(scene.lines):
        if lid in used:
            continue
        start_line, start = lid, graph.ends(lid)[0]
        seen = {lid}
        while start.kind == "free":
            other = next(i for i in graph.at[start.key] if i != start_line)
            if other in seen:
                return None
            seen.add(other)
            a, b = graph.ends(other)
            start, start_line = (a if b.key == start.key else b), other
        chain, node, current = [], start, start_line
        while True:
            a, b = graph.ends(current)
            reverse = a.key != node.key
            chain.append((current, reverse))
            used.add(current)
            node = a if reverse else b
            if node.kind != "free":
                break
            current = next(i for i in graph.at[node.key] if i != current)
        chains.append((start, chain, node))
    return chains


def _network_reason(graph: Graph, chains) -> str | None:
    """Why the file needs the network form, or None when the legs form holds it."""
    scene = graph.scene
    moving = [c for c in graph.carriers.values() if not c.held]
    if moving:
        c = moving[0]
        what = (f"rod {c.key[1]} is {scene.rods[c.key[1]].word}" if c.key[0] == "rod"
                else f"body {c.key[1]} is {scene.bodies[c.key[1]].word}")
        return f"{what} (it moves in the solve)"
    rods = [n for n in graph.nodes.values() if n.key[0] == "rod"]
    if rods:
        return f"line(s) attach to {rods[0].label}"
    if len(graph.carriers) > 1:
        return "several carriers of fairleads (" + ", ".join(
            c.name for c in graph.carriers.values()) + ")"
    if not graph.carriers:
        # No body: lines between fixed points, whose free points may hang out of any one
        # vertical plane; the network form solves them in three dimensions.
        return "no body carries the lines"
    if chains is None:
        for key, node in graph.nodes.items():
            n = len(graph.at[key])
            if node.kind == "free" and n == 1:
                return f"line {graph.line_label(graph.at[key][0])} ends at free {node.label}"
            if node.kind == "free" and n > 2:
                return (f"free {node.label} joins {n} lines (" + ", ".join(
                    graph.line_label(i) for i in sorted(graph.at[key])) + "): a bridle or hub")
        return "lines close a loop through free points"
    for first, chain, last in chains:
        ids = ", ".join(graph.line_label(i) for i, _ in chain)
        if scene.bathymetry is not None and len(chain) > 1:
            # A grid takes one-segment lines (each its own seabed plane) and free points,
            # not multi-segment legs.
            return (f"line(s) {ids} join through free points on a bathymetry grid "
                    "(a grid takes the free points as points, not as leg joints)")
        kinds = {first.kind, last.kind}
        if kinds == {"carrier"}:
            return f"line(s) {ids} join two fairleads ({first.label}, {last.label})"
        if kinds == {"fixed"}:
            return f"line(s) {ids} join two fixed points ({first.label}, {last.label})"
        if kinds == {"fixed", "carrier"}:
            ground, top = (first, last) if first.kind == "fixed" else (last, first)
            if ground.position[2] > top.position[2]:
                return (f"line(s) {ids} hang from {ground.label} above their fairlead "
                        f"{top.label}")
    return None


def _clump(node, scene: MDScene) -> dict | None:
    point = scene.points[node.key[1]]
    fz = vertical_force(point, scene)
    if scene.gravity == 0 or scene.water_density == 0:
        # Weightless or dry (a MoorDyn test): the clump's net weight, given as such.
        weight = scene.gravity * (point.mass - scene.water_density * point.volume) - fz
        return {"weight": weight} if point.mass or point.volume or fz else None
    volume = point.volume + fz / (scene.water_density * scene.gravity)
    if point.mass or volume:
        return {"mass": point.mass, "volume": volume}
    return None


def case_environment(scene: MDScene, report: ImportReport) -> dict:
    """The case's environment: MoorDyn's g = 0 (weightless) or rho = 0 (dry) tests keep the
    case's defaults, their weights and buoyancies being given as zero where they arise."""
    env = {"depth": scene.depth, "water_density": scene.water_density,
           "gravity": scene.gravity}
    if scene.bathymetry is not None:
        env["seabed"] = {"bathymetry": scene.bathymetry}
    for key, default, what in (("gravity", DEFAULT_GRAVITY, "weightless: every weight is 0"),
                               ("water_density", DEFAULT_WATER_DENSITY,
                                "dry: every buoyancy is 0")):
        if env[key] == 0:
            env[key] = default
            report.converted.append(f"{key.replace('_', ' ')} 0 ({what}; the case keeps "
                                    f"{default:g}, which then weighs nothing)")
    return env


def _legs_data(graph: Graph, chains, report: ImportReport) -> tuple:
    """(legs, leg blocks, the carrier) of the legs form."""
    scene = graph.scene
    oriented = []
    for first, chain, last in chains:
        if first.kind == "carrier":
            first, last = last, first
            chain = [(i, not r) for i, r in reversed(chain)]
        oriented.append((first, chain, last))
    legs, blocks = [], {}
    for first, chain, last in sorted(oriented, key=lambda leg: min(i for i, _ in leg[1])):
        name = graph.line_name(chain[0][0], "L")
        segments, block_lines, block_points = [], [], [_block_point(first, scene)]
        for k, (lid, reverse) in enumerate(chain):
            line = scene.lines[lid]
            if k > 0:
                joint = graph.ends(lid)[1 if reverse else 0]
                clump = _clump(joint, scene)
                if clump is not None:
                    segments.append({"clump": clump})
                entry = _block_point(joint, scene)
                entry["position"] = list(joint.position)
                block_points.append(entry)
            segments.append({"type": line.type.name, "length": line.length})
            block_lines.append({"id": lid, "num_segs": line.num_segs, "outputs": line.outputs,
                                "reversed": reverse})
        block_points.append(_block_point(last, scene))
        legs.append({"name": name, "anchor": list(first.position),
                     "fairlead": list(last.position), "segments": segments})
        blocks[name] = {"lines": block_lines, "points": block_points}
        lines = ", ".join(str(i) for i, _ in chain)
        report.converted.append(f"leg {name}: MoorDyn line(s) {lines} from {first.label} to "
                                f"{last.label}")
    return legs, blocks


def _block_point(node, scene: MDScene) -> dict:
    p = scene.points[node.key[1]]
    columns = dict(p.columns)
    if p.kind != "free":
        columns = {"mass": _token(p.mass), "volume": _token(p.volume), **columns}
    return {"id": p.id, "attachment": p.word, "columns": columns}


def _token(value: float) -> str:
    return repr(value) if value != int(value) else str(int(value))


def _legs_case(graph: Graph, chains, report: ImportReport) -> tuple:
    """(case data, moordyn block additions) of the legs form."""
    scene = graph.scene
    legs, leg_blocks = _legs_data(graph, chains, report)
    block = {"legs": leg_blocks}
    data = {}
    if graph.carriers:
        (carrier,) = graph.carriers.values()
        data["body"] = {"free": []}
        if carrier.key[0] == "body":
            body = scene.bodies[carrier.key[1]]
            x0, y0, z0, r0, p0, yaw = body.pose
            entry = {"id": body.id, "attachment": body.word, "x0": x0, "y0": y0, "z0": z0,
                     "yaw_deg": yaw, "columns": dict(body.columns)}
            if r0 or p0:
                entry.update(r0_deg=r0, p0_deg=p0)
            block["body"] = entry
            report.converted.append(f"body {body.id} ({body.word}, line {body.line}): the "
                                    "case's body, held where the file puts it (free: []); "
                                    "its fairleads in the case are where its points are at "
                                    "that pose")
            report.ignored.append(f"body {body.id}: Mass, CG, I, Volume, CdA, Ca: a held body's "
                                  "own weight and hydrodynamics do not change the line "
                                  "tensions; kept for export")
        else:
            ids = ", ".join(n.label for n in graph.nodes.values() if n.carrier is carrier)
            report.converted.append(f"{carrier.name} ({ids}): fairleads of the case's body, "
                                    "held where the file puts them (free: []); give the body "
                                    "free degrees of freedom and loads to solve its offset")
    data["legs"] = legs
    return data, block


# ---- the whole conversion ---------------------------------------------------------------------


@dataclass
class MoorDynImport:
    """A MoorDyn file mapped onto a case: the case ``data``, the ``report`` of what was read,
    converted and ignored, the ``form`` chosen (``"legs"`` or ``"network"``) and why."""

    file: MoorDynFile
    data: dict
    report: ImportReport
    form: str
    form_reason: str

    def header(self) -> str:
        """The comment block written above the case YAML: provenance and the report."""
        md = self.file
        lines = [f"Imported from the MoorDyn v{md.version} file {md.name} by `moorsolve "
                 "import-moordyn`.",
                 f"Case form: {self.form} ({self.form_reason}).",
                 "The geometry, line types and environment are the file's. MoorDyn cannot hold "
                 "what a static",
                 "analysis adds: the bodies have no loads (the case solves at rest) and the "
                 "lines no MBL; add",
                 "loads, line_types.*.mbl and environment.seabed.friction as needed. The "
                 "`moordyn` block keeps",
                 "what moorsolve does not use; `moorsolve export-moordyn` writes it back.", ""]
        return "\n".join(lines + self.report.lines()) + "\n"

    def write(self, out) -> None:
        """Write the case YAML (atomically), the report as its leading comment."""
        write_case_yaml(self.data, out, self.header())


def convert_moordyn(md: MoorDynFile) -> MoorDynImport:
    """Map a parsed MoorDyn file onto case data and a report (no validation of the case).

    Raises
    ------
    MoorDynError
        Naming the file, the line and the column of what MoorDyn would refuse too, or of what
        a case cannot hold (a horizontal force on a free point, a rod pinned to a moving body).
    """
    scene = read_scene(md)
    report = ImportReport(source=md.name, read=list(scene.read), converted=list(scene.converted),
                          ignored=list(scene.ignored))
    types, type_columns = line_type_data(scene, report)
    form, why, body_data, block = scene_case(scene, report)
    _report_sections(md, scene, report)
    env = case_environment(scene, report)

    block_all = {"version": md.version, "header": list(md.header),
                 "notes": list(report.converted[:1]) + [e for e in report.ignored
                                                        if "friction" in e or "bathymetry" in e
                                                        or "Seafloor" in e],
                 "line_types": {k: v for k, v in type_columns.items() if v}}
    block_all.update(block)
    block_all["options"] = scene.options
    block_all["outputs"] = list(md.outputs)
    if md.sections:
        block_all["sections"] = {k: list(v) for k, v in md.sections.items()}
    stem = os.path.splitext(md.name)[0] or "moordyn"
    data = {"name": f"{stem} (imported from MoorDyn v{md.version})", "environment": env,
            "line_types": types, **body_data, "moordyn": block_all}
    return MoorDynImport(file=md, data=data, report=report, form=form, form_reason=why)


def scene_case(scene: MDScene, report: ImportReport) -> tuple:
    """(form, why, the case's body/legs or bodies/points/lines, the ``moordyn`` block's part)
    of a scene; the report gets what was converted and ignored."""
    graph = build_graph(scene)
    turbines = sorted(c.name for c in graph.carriers.values() if c.key[0] == "turbine")
    if turbines:
        report.converted.append(f"{', '.join(turbines)}: FAST.Farm gives each turbine's "
                                "reference position (not in this file); the Turbine<N> points "
                                "are placed about the origin: set each body's position")
    for p in graph.unused:
        report.ignored.append(f"point {p.id} (line {p.line}, {p.word}): no line uses it")
    chains = _chains(graph)
    reason = _network_reason(graph, chains)
    if reason is None:
        form, why = "legs", "one held carrier of fairleads on anchor-to-fairlead lines"
        body_data, block = _legs_case(graph, chains, report)
    else:
        form, why = "network", reason
        body_data, block = network_case(graph, report)
    report.converted.insert(0, f"case form: {form} ({why})")
    _report_leftovers(graph, report)
    return form, why, body_data, block


def _report_leftovers(graph: Graph, report: ImportReport) -> None:
    scene = graph.scene
    used_bodies = {c.key[1] for c in graph.carriers.values() if c.key[0] == "body"}
    for body in scene.bodies.values():
        if body.id not in used_bodies:
            report.ignored.append(f"body {body.id} (line {body.line}, {body.word}): no line "
                                  "meets it; left out (nothing in a static solve holds a free "
                                  "one, and a held one changes no tension)")
    used_rods = {n.key[1] for n in graph.nodes.values() if n.key[0] == "rod"}
    for rod in scene.rods.values():
        if rod.id in used_rods or (rod.kind == "body" and rod.body in used_bodies
                                   and not body_held(scene, rod.body)):
            continue
        why = ("rigid on a held body, which takes its weight and buoyancy"
               if rod.kind == "body" and body_held(scene, rod.body)
               else "held, so its weight and buoyancy change no tension"
               if rod.kind in ("fixed", "coupled")
               else "nothing holds it in a static solve")
        report.ignored.append(f"rod {rod.id} (line {rod.line}, {rod.word}): no line meets it; "
                              f"{why}; left out")
    if scene.rods:
        report.ignored.append("rod types Cd, Ca, CdEnd, CaEnd and rods' NumSegs, outputs: "
                              "dynamic only (the RODS and ROD TYPES rows are kept for export)")


def _report_sections(md: MoorDynFile, scene: MDScene, report: ImportReport) -> None:
    lines = md.section_lines
    per_line = sorted({ln.num_segs for ln in scene.lines.values()})
    report.ignored.append("LINES NumSegs and outputs: the lumped-mass discretisation and "
                          "output flags of MoorDyn; the lines are exact catenaries here (kept "
                          f"for export; NumSegs {', '.join(per_line)})")
    points_cols = {k for p in scene.points.values() for k in p.columns if k in ("cda", "ca")}
    if points_cols:
        report.ignored.append("POINTS CdA, Ca: drag and added mass, dynamic only (kept for "
                              "export)")
    channels = sum(len(row.split()) for row in md.outputs)
    if channels:
        report.ignored.append(f"OUTPUTS (line {lines['outputs']}): {channels} output "
                              "channel(s); the solve's result has every tension (kept for "
                              "export)")
    for title, what in (("FAILURE", "line failure is an event in time; a damaged case is a "
                                    "case without the line"),
                        ("CONTROL", "line-length control is dynamic"),
                        ("EXTERNAL LOADS", "external loads and damping of MoorDyn objects are "
                                           "not imported; add them as case loads")):
        if title in md.sections:
            key = title if title in lines else title
            report.ignored.append(f"{title} (line {lines.get(key, '?')}): {what}; kept "
                                  "verbatim for export")


def moordyn_to_case_data(md: MoorDynFile) -> dict:
    """Map a parsed MoorDyn file onto a case dictionary (the shape of a case file); see the
    module notes and :func:`convert_moordyn`, which also returns the report."""
    return convert_moordyn(md).data


def _validate(imp: MoorDynImport) -> None:
    from .case_file import load_case
    try:
        load_case(imp.data, keep_source=False)
    except CaseError as exc:
        if imp.form == "network" and exc.field in ("bodies", "points", "lines") and \
                "unknown key" in str(exc):
            imp.report.converted.append("network form: this moorsolve has no network loader "
                                        "yet; the case is written in the contract's form, "
                                        "unvalidated")
            return
        if isinstance(exc, MoorDynError):
            raise
        raise MoorDynError(imp.file.name, None, f"the imported case is not valid: {exc} "
                                                f"(read as MoorDyn v{imp.file.version}: "
                                                f"{imp.file.version_reason})") from None


def read_import(source) -> MoorDynImport:
    """Read a MoorDyn file, map it onto a case and validate the case (nothing is written)."""
    if not isinstance(source, (str, PathLike)):
        raise CaseError("", f"{source!r} is not a path to a MoorDyn file")
    imp = convert_moordyn(read_moordyn(source))
    _validate(imp)
    return imp


def import_moordyn(source, out=None) -> dict:
    """Read a MoorDyn file, map it onto a case, validate it, and optionally write the YAML.

    Parameters
    ----------
    source : str or pathlib.Path
        MoorDyn input file (v1 or v2).
    out : str or pathlib.Path, optional
        Case file to write (atomically, only when everything succeeded), with the import
        report as its leading comment.

    Returns
    -------
    dict
        The case dictionary (``moorsolve.load_case`` accepts it).

    Raises
    ------
    MoorDynError
        The file is malformed the way MoorDyn would refuse it too, or holds what a case
        cannot (see :func:`convert_moordyn`); the message names the file, the line, the
        column, and the format version the file was read as and why.
    """
    imp = read_import(source)
    if out is not None:
        imp.write(out)
    return imp.data
