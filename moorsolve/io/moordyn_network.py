"""A MoorDyn file in the network form of a case: ``bodies``, ``points``, ``lines``.

Every MoorDyn line becomes ``line<N>`` (N its number in the file) with end A (``from``) at
its AttachA (v1: NodeAnch) and end B (``to``) at its AttachB (NodeFair); one segment of its
line type and unstretched length. Its ends are named as follows.

=========================  ===================================================================
MoorDyn                    case
=========================  ===================================================================
Fixed point N              point ``point<N>`` at its position
Free point N               point ``point<N>``, ``free: true``, its mass and volume (a steady
                           vertical force FZ adds ``FZ / (rho g)`` to the volume)
Coupled / Vessel point     ``{body: vessel, at: [x, y, z]}``: one held body ``vessel`` at the
                           origin carries them (MoorDyn v1's platform)
Turbine<N> point           ``{body: turbine<N>, at: ...}``, a held body
Body<N> point              ``{body: body<N>, at: [x, y, z] in the body frame]}``
end A/B of a Fixed rod     point ``rod<N>A`` / ``rod<N>B`` at the end
end of a Coupled rod       ``{body: vessel, at: ...}``
end of a Body<N> rod       ``{body: body<N>, at: the end in the body frame}``
end of a pinned/free rod   ``{body: rod<N>, at: [0, 0, zA]`` or ``[0, 0, zB]``}`` (its own frame)
=========================  ===================================================================

Bodies: ``body<N>`` at X0 Y0 Z0 and r0 p0 y0 (converted to the case's z-y-x angles, see
:mod:`.rotations`). Coupled, Fixed and Turbine bodies are held (``free: []``). A Free body
is free in all six degrees of freedom; a CoupledPinned body in roll, pitch and yaw (held in
translation). Yaw is left out when every line meets the body on its vertical axis (nothing
would hold it; the report says so). A moving body gets MoorDyn's Mass at its CG and its
Volume with the buoyancy at the CG too (MoorDyn-C puts both at ``rCG``; MoorPy puts the
buoyancy at the body origin), plus its rigid rods.

Rods: a rod rigid on a body (``Body<N>``) adds its weight (Mass/m times length, at its
middle) and its buoyancy (the submerged part of its cylinder, at that part's middle) to the
body. A pinned rod (``Pinned``, ``CoupledPinned``, ``Body<N>Pinned`` on a held body) becomes a
body ``rod<N>`` whose origin is end A (the pin), held in translation and free in its two
tilts; a Free rod is also free in surge, sway and heave, its origin where it crosses the
water line (else end A). A rod steeper than 45 deg gets its z axis along the rod (tilts:
roll, pitch), a flatter one its x axis (tilts: pitch, yaw), so that the spin about its own
axis (no degree of freedom) is the held angle and the z-y-x angles stay far from their
singular pitch. Fixed and Coupled rods are held: their ends are fixed points or vessel
points, their weight and buoyancy taken by what holds them.

Buoyancy of a moving body or rod: when it is all rods upright in the body's frame (a rod's
own frame, or vertical columns of a body without a Volume of its own), they become ``hull``
cylinders, whose submerged volume the solve integrates exactly at every pose, as MoorDyn
does along a rod. Otherwise the case's linear model (buoyancy ``rho g V`` at the
metacentre, heave restoring ``-rho g A_wp z``): ``V`` and the centre of buoyancy exact at the
file's pose; a rod crossing the water line adds its waterplane (area ``pi d^2 / 4 / |cos
tilt|``) and, to the metacentre's height above the centre of buoyancy, ``I / V`` with ``I``
the mean of the waterplane's second moments about x and y through the body origin (the
report notes when they differ). ``V`` is shifted by ``A_wp z0`` so that the buoyancy at the
file's pose is exact when the origin is off the water line; a body held in translation
(pinned) gets no waterplane (its heave restoring would only load the pin). Exact for
submerged bodies; the usual small-angle model for surface-piercing ones.
"""

from __future__ import annotations

import math

from .import_report import ImportReport
from .moordyn_graph import Carrier, Graph, carrier_angles, rod_ends_global
from .moordyn_scene import DEFAULT_GRAVITY, DEFAULT_WATER_DENSITY, vertical_force

__all__ = ["network_case", "body_held"]

SIX = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
#: The mass [kg] of a body in a weightless (g = 0) MoorDyn file: the case needs a mass for
#: a body free in heave, roll or pitch; this one weighs 1e-8 N, below any line tension.
WEIGHTLESS_MASS = 1e-9


def _end(graph: Graph, node) -> object:
    if node.kind in ("fixed", "free"):
        return graph.point_name(node)
    return {"body": node.carrier.name, "at": [float(v) for v in node.local]}


def _points(graph: Graph, report: ImportReport) -> list:
    scene = graph.scene
    out = []
    for node in sorted(graph.nodes.values(), key=lambda n: (n.key[0] != "point", n.key[1:])):
        if node.kind == "fixed":
            out.append({"name": graph.point_name(node), "position": list(node.position)})
        elif node.kind == "free" and node.key[0] == "rod":
            # A zero-length free rod: MoorDyn's massless point-like connector.
            out.append({"name": node.name, "position": list(node.position), "free": True,
                        "mass": 0.0, "volume": 0.0})
            report.converted.append(f"{node.label} (line {node.line}): a free connector, point "
                                    f"{node.name}")
        elif node.kind == "free":
            p = scene.points[node.key[1]]
            fz = vertical_force(p, scene)
            g, rho = scene.gravity, scene.water_density
            if g == 0 or rho == 0:
                # A weightless or dry MoorDyn test: the net weight as mass or volume.
                net = g * (p.mass - rho * p.volume) - fz
                mass, volume = max(net, 0.0) / DEFAULT_GRAVITY, \
                    max(-net, 0.0) / (DEFAULT_GRAVITY * DEFAULT_WATER_DENSITY)
            else:
                mass, volume = p.mass, p.volume + fz / (rho * g)
                if fz:
                    report.converted.append(f"point {p.id}: FZ {fz:g} N as "
                                            f"{volume - p.volume:.6g} m^3 of extra buoyancy "
                                            "volume")
            out.append({"name": graph.point_name(node), "position": list(node.position),
                        "free": True, "mass": mass, "volume": volume})
            report.converted.append(f"point {p.id} (line {p.line}, {p.word}): free point "
                                    f"{graph.point_name(node)} joining line(s) "
                                    + ", ".join(map(str, sorted(graph.at[node.key]))))
    return out


def _rod_buoyancy(a, b, diameter: float) -> tuple:
    """(volume, centre, waterplane area, own waterplane second moment) of the submerged part
    of a cylinder from ``a`` to ``b`` (global, z up, water line z = 0)."""
    area = math.pi * diameter ** 2 / 4.0
    length = math.dist(a, b)
    za, zb = a[2], b[2]
    if za <= 0 and zb <= 0:
        t0, t1 = 0.0, 1.0
    elif za > 0 and zb > 0:
        return 0.0, a, 0.0, 0.0
    else:
        ts = za / (za - zb)
        t0, t1 = (0.0, ts) if za <= 0 else (ts, 1.0)
    volume = area * length * (t1 - t0)
    tm = 0.5 * (t0 + t1)
    centre = tuple(p + tm * (q - p) for p, q in zip(a, b))
    if (za < 0 < zb) or (zb < 0 < za):
        cos_tilt = abs(zb - za) / length
        return volume, centre, area / cos_tilt, math.pi * diameter ** 4 / 64.0 / cos_tilt
    return volume, centre, 0.0, 0.0


def _mass_properties(graph: Graph, carrier: Carrier, report: ImportReport) -> dict:
    """Mass, CG and buoyancy of a moving carrier (see the module notes): ``hull`` members
    when its buoyancy is all rods upright in its frame (exact), else ``hydrostatics``."""
    scene = graph.scene
    masses, buoy = [], []               # (mass, global point), (V, centre, A_wp, I, at)
    if carrier.key[0] == "body":
        body = scene.bodies[carrier.key[1]]
        cg = carrier.to_global(carrier.from_file(body.cg))
        masses.append((body.mass, cg))
        if body.volume:
            buoy.append((body.volume, cg, 0.0, 0.0, cg))
        rods = [r for r in scene.rods.values() if r.kind == "body" and r.body == body.id]
    else:
        body = None
        rods = [scene.rods[carrier.key[1]]]
    hull = []
    for rod in rods:
        a, b = rod_ends_global(scene, rod)
        mid = tuple(0.5 * (p + q) for p, q in zip(a, b))
        masses.append((rod.type.mass * rod.length, mid))
        v, c, awp, inertia = _rod_buoyancy(a, b, rod.type.diameter)
        if v:
            buoy.append((v, c, awp, inertia, c))
        la, lb = carrier.to_local(a), carrier.to_local(b)
        if abs(la[0] - lb[0]) < 1e-9 and abs(la[1] - lb[1]) < 1e-9 and rod.type.diameter > 0:
            hull.append({"shape": "cylinder", "radius": rod.type.diameter / 2.0,
                         "bottom": min(la[2], lb[2]), "top": max(la[2], lb[2]),
                         "centre": [la[0], la[1]]})
        if carrier.key[0] == "body":
            report.converted.append(f"rod {rod.id} (line {rod.line}): rigid on body "
                                    f"{carrier.key[1]}: {rod.type.mass * rod.length:.6g} kg "
                                    f"and {v:.6g} m^3 added to it")
    total = sum(m for m, _ in masses)
    out = {}
    if total > 0:
        g_cg = tuple(sum(m * p[i] for m, p in masses) / total for i in range(3))
        out["mass"] = total
        out["centre_of_gravity"] = _local(carrier, g_cg)
    if scene.gravity == 0 or scene.water_density == 0:
        # A weightless or dry MoorDyn test: no buoyancy; and without gravity no weight,
        # which the case can only say with a negligible mass (it needs one for a body free
        # in heave, roll or pitch).
        if scene.gravity == 0:
            out["mass"] = WEIGHTLESS_MASS
            out.pop("centre_of_gravity", None)
            report.converted.append(f"{carrier.name}: weightless (g 0): mass "
                                    f"{WEIGHTLESS_MASS:g} kg")
        out["hydrostatics"] = {"displaced_volume": 0.0, "metacentre": [0.0, 0.0, 0.0],
                               "waterplane_area": 0.0}
        return out
    volume = sum(v for v, *_ in buoy)
    if len(hull) == len(rods) and rods and not (body is not None and body.volume):
        out["hull"] = hull
        report.converted.append(f"{carrier.name}: buoyancy of its {len(hull)} upright "
                                f"cylinder(s) integrated exactly (hull); {volume:.6g} m^3 "
                                "submerged at the file's pose")
        return out
    if volume > 0:
        out["hydrostatics"] = _linear_hydrostatics(scene, carrier, buoy, volume, report)
    else:
        out["hydrostatics"] = {"displaced_volume": 0.0, "metacentre": [0.0, 0.0, 0.0],
                               "waterplane_area": 0.0}
    return out


def _linear_hydrostatics(scene, carrier: Carrier, buoy: list, volume: float,
                         report: ImportReport) -> dict:
    centre = tuple(sum(v * c[i] for v, c, *_ in buoy) / volume for i in range(3))
    area = sum(a for _, _, a, _, _ in buoy)
    ox, oy, oz = carrier.origin
    ix = sum(i + a * (c[1] - oy) ** 2 for _, _, a, i, c in buoy)
    iy = sum(i + a * (c[0] - ox) ** 2 for _, _, a, i, c in buoy)
    inertia = 0.5 * (ix + iy)
    if area and abs(ix - iy) > 1e-3 * inertia:
        report.converted.append(f"{carrier.name}: waterplane second moments {ix:.6g} (x) "
                                f"and {iy:.6g} (y) m^4 differ; the metacentre uses their mean")
    metacentre = (centre[0], centre[1], centre[2] + inertia / volume)
    pinned = (scene.rods[carrier.key[1]].kind != "free" if carrier.key[0] == "rod"
              else scene.bodies[carrier.key[1]].kind == "pinned")
    if pinned:
        # Held in translation: the heave restoring force would only load the pin.
        area = 0.0
    displaced = volume + area * oz
    if displaced <= 0:
        raise scene.file.error(carrier.line, f"{carrier.name}: its origin is {oz:g} m from the "
                                             "water line; the linear hydrostatic model cannot "
                                             "hold its surface-piercing rods (move the body "
                                             "origin to the water line)")
    report.converted.append(f"{carrier.name}: displaced volume {volume:.6g} m^3 (buoyancy "
                            f"{scene.water_density * scene.gravity * volume:.6g} N), waterplane "
                            f"{area:.6g} m^2 (linear hydrostatics)")
    return {"displaced_volume": displaced, "metacentre": _local(carrier, metacentre),
            "waterplane_area": area}


def _local(carrier: Carrier, point) -> list:
    return list(carrier.to_local(point))


def _free_dofs(graph: Graph, carrier: Carrier, report: ImportReport) -> list:
    scene = graph.scene
    if carrier.key[0] == "rod":
        rod = scene.rods[carrier.key[1]]
        if rod.kind == "body_pinned" and not body_held(scene, rod.body):
            raise scene.file.error(rod.line, f"rod {rod.id} is pinned to body {rod.body}, "
                                             "which moves: a case has no joint between two "
                                             "moving bodies")
        tilts = ["roll", "pitch"] if carrier.axis == "z" else ["pitch", "yaw"]
        free = (["surge", "sway", "heave"] + tilts if rod.kind == "free" else tilts)
        where = ("end A (the pin)" if rod.kind != "free" else
                 "its water-line crossing" if carrier.origin != rod_ends_global(scene, rod)[0]
                 else "end A")
        report.converted.append(f"rod {rod.id} (line {rod.line}, {rod.word}): body "
                                f"{carrier.name}, origin at {where}, {carrier.axis} along the "
                                f"rod, free {', '.join(free)}")
        return free
    body = scene.bodies[carrier.key[1]]
    free = list(SIX) if body.kind == "free" else ["roll", "pitch", "yaw"]
    nodes = [n for n in graph.nodes.values() if n.carrier is carrier]
    if all(abs(n.local[0]) < 1e-9 and abs(n.local[1]) < 1e-9 for n in nodes):
        free.remove("yaw")
        report.converted.append(f"body {body.id}: every line meets it on its vertical axis, "
                                "so nothing holds its yaw: yaw left out of free")
    report.converted.append(f"body {body.id} (line {body.line}, {body.word}): body "
                            f"{carrier.name}, free {', '.join(free)}")
    return free


def body_held(scene, ident: int) -> bool:
    return scene.bodies[ident].kind in ("fixed", "coupled", "turbine")


def _bodies(graph: Graph, report: ImportReport) -> list:
    scene = graph.scene
    order = {"vessel": 0, "turbine": 1, "body": 2, "rod": 3}
    out = []
    for carrier in sorted(graph.carriers.values(), key=lambda c: (order[c.key[0]], c.key[1:])):
        entry = {"name": carrier.name, "position": list(carrier.origin)}
        angles = carrier_angles(carrier)
        if any(angles):
            entry["orientation_deg"] = list(angles)
        if carrier.held:
            entry["free"] = []
            if carrier.key[0] == "body":
                body = scene.bodies[carrier.key[1]]
                report.converted.append(f"body {body.id} (line {body.line}, {body.word}): body "
                                        f"{carrier.name}, held where the file puts it")
                report.ignored.append(f"body {body.id}: Mass, CG, Volume: a held body's weight "
                                      "and buoyancy do not change the line tensions")
            else:
                what = ("Coupled (Vessel) points and Coupled rods" if carrier.key[0] == "vessel"
                        else f"Turbine{carrier.key[1]} points")
                report.converted.append(f"{carrier.name}: a held body at the origin carrying "
                                        f"the {what}")
        else:
            entry["free"] = _free_dofs(graph, carrier, report)
            entry.update(_mass_properties(graph, carrier, report))
        out.append(entry)
    return out


def network_case(graph: Graph, report: ImportReport) -> tuple:
    """(``{bodies, points, lines}``, the ``moordyn`` block's ``network`` entry)."""
    scene = graph.scene
    bodies = _bodies(graph, report)
    points = _points(graph, report)
    lines, block_lines = [], {}
    for line in sorted(scene.lines.values(), key=lambda ln: ln.id):
        a, b = graph.ends(line.id)
        name = graph.line_name(line.id)
        lines.append({"name": name, "from": _end(graph, a), "to": _end(graph, b),
                      "segments": [{"type": line.type.name, "length": line.length}]})
        block_lines[name] = {"id": line.id, "num_segs": line.num_segs, "outputs": line.outputs}
    report.converted.append(f"{len(lines)} MoorDyn line(s) as line<N>, end A at AttachA")
    for rod in scene.rods.values():
        ends = sorted(n.name for n in graph.nodes.values()
                      if n.key[0] == "rod" and n.key[1] == rod.id)
        if ends and rod.kind in ("fixed", "coupled"):
            where = ("fixed point(s) " + ", ".join(ends) if rod.kind == "fixed"
                     else "points of the held body vessel")
            report.converted.append(f"rod {rod.id} (line {rod.line}, {rod.word}): held; the "
                                    f"ends lines meet are {where}")
    block_points = {}
    for node in graph.nodes.values():
        if node.key[0] == "point":
            p = scene.points[node.key[1]]
            block_points[node.name] = {"id": p.id, "attachment": p.word,
                                       "columns": dict(p.columns)}
    block_bodies = {f"body{b.id}": {"id": b.id, "attachment": b.word,
                                    "columns": dict(b.columns)}
                    for b in scene.bodies.values()}
    data = {}
    if bodies:
        data["bodies"] = bodies
    if points:
        data["points"] = points
    data["lines"] = lines
    return data, {"network": {"lines": block_lines, "points": block_points,
                              "bodies": block_bodies}}
