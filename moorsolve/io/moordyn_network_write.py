"""MoorDyn v2 input files out for a network case: bodies, points and lines between any ends.

What each part of the case becomes (MoorDyn-C v2 columns):

- a body held (``free: []``) is a ``Fixed`` body; a body free in all six degrees of freedom
  a ``Free`` body with its mass, centre of gravity, moments of inertia and displaced volume;
  a body free in some of them only is written ``Free`` too (MoorDyn has no partial freedom)
  and the file's front matter says so. MoorDyn-C puts a body's buoyancy at its centre of
  gravity and has no waterplane area: a linear model's metacentre and heave restoring, and
  exact hull members, are not represented (said in the front matter);
- a fixed point a ``Fixed`` point, a free point a ``Free`` point with its mass and volume, a
  body end a ``Body<N>`` point at its body-frame position, a fixed coordinate its own
  ``Fixed`` point;
- a line of several segments is cut at its joints into MoorDyn lines joined by ``Free``
  points carrying the clumps' mass and volume;
- line types as :mod:`.moordyn_write` writes them (the submerged weight exactly the case's).

With a result, bodies and free points are written at their equilibrium pose, so a dynamic
run starts from the static answer.
"""

from __future__ import annotations

from ..errors import CaseError
from ..model import DOFS
from .bathymetry import seafloor_option
from .moordyn_write_types import default_num_segs, line_type_rows
from .moordyn_write_types import number_text as _g  # _g: dense rows

__all__ = ["network_to_moordyn"]

_RULE = "-" * 72


def _section(title: str) -> str:
    return f"{('-' * 20)} {title} {'-' * max(4, 50 - len(title))}"


def network_to_moordyn(case, result=None, *, curves: dict | None = None,
                       curve_prefix: str = "") -> str:
    """The MoorDyn v2 input file of a network case, as text (see the module notes);
    ``curves`` receives the tension-strain curve files of stretch-law line types
    (:func:`moorsolve.io.moordyn_write.case_to_moordyn`)."""
    env = case.environment
    if env.seabed.sloped and env.seabed.bathymetry is None:
        raise CaseError("environment.seabed.gradient", "MoorDyn's seabed is flat or a grid; "
                                                       "a sloped plane cannot be written")
    notes = []
    type_rows, _, _ = line_type_rows(case, {}, 2, curve_prefix, curves)
    poses = {b["name"]: b for b in (result.bodies if result is not None else ())}
    points_found = {p["name"]: p for p in (result.points if result is not None else ())}

    body_rows, body_id = [], {}
    for k, body in enumerate(case.bodies, start=1):
        body_id[body.name] = k
        pose = poses.get(body.name)
        if pose is not None:
            x, y, z = pose["x_m"], pose["y_m"], pose["z_m"]
            r, p, yaw = pose["roll_deg"], pose["pitch_deg"], pose["yaw_deg"]
        else:
            (x, y, z), (r, p, yaw) = body.position, body.orientation_deg
        if not body.free:
            kind = "Fixed"
        else:
            kind = "Free"
            if set(body.free) != set(DOFS):
                notes.append(f"body {body.name} is free in {', '.join(body.free)} only; "
                             "MoorDyn has no partial freedom: written Free")
        hydro = body.hydrostatics
        volume = hydro.displaced_volume if hydro is not None else 0.0
        if hydro is not None and (hydro.waterplane_area or any(hydro.metacentre)):
            notes.append(f"body {body.name}: MoorDyn puts the buoyancy of its Volume at the "
                         "centre of gravity and has no waterplane area; the metacentre and "
                         "heave restoring of the linear model are not represented")
        if body.hull:
            notes.append(f"body {body.name}: its exact hull members are not represented "
                         "(MoorDyn would need rods); Volume 0")
        if body.stiffness is not None:
            notes.append(f"body {body.name}: its extra springs are not represented")
        if any(getattr(body.loads, m) is not None for m in ("wind", "current", "wave_drift")) \
                or body.loads.force is not None:
            notes.append(f"body {body.name}: its loads are not written (MoorDyn takes them "
                         "from its driver)")
        inertia = body.inertia or (0.0, 0.0, 0.0)
        body_rows.append([str(k), kind, _g(x), _g(y), _g(z), _g(r), _g(p), _g(yaw),
                          _g(body.mass or 0.0), "|".join(_g(v) for v in body.centre_of_gravity),
                          "|".join(_g(v) for v in inertia), _g(volume), "0", "0"])

    point_rows, point_id = [], {}

    def add_point(kind, xyz, mass=0.0, volume=0.0) -> int:
        ident = len(point_rows) + 1
        point_rows.append([str(ident), kind, _g(xyz[0]), _g(xyz[1]), _g(xyz[2]), _g(mass),
                           _g(volume), "0", "0"])
        return ident

    for pt in case.points:
        found = points_found.get(pt.name)
        xyz = (found["x_m"], found["y_m"], found["z_m"]) if found else pt.position
        point_id[pt.name] = add_point("Free" if pt.free else "Fixed", xyz,
                                      pt.mass if pt.free else 0.0,
                                      pt.volume if pt.free else 0.0)

    def end_point(end) -> int:
        if end.body is not None:
            return add_point(f"Body{body_id[end.body]}", end.position)
        name = end.point or end.label
        if name is not None and name in point_id:
            return point_id[name]
        return add_point("Fixed", end.position)

    line_rows = []
    for line in case.lines:
        a, b = end_point(line.a), end_point(line.b)
        ids = [a]
        if line.multi_segment:
            # Joints where the case's result put them (else on the chord).
            for j, clump in enumerate(line.joint_clumps):
                mass, volume = 0.0, 0.0
                if clump is not None:
                    mass = (clump.mass if clump.mass is not None
                            else max(clump.weight, 0.0) / env.gravity)
                    volume = clump.volume if clump.volume is not None else max(
                        -clump.weight, 0.0) / (env.gravity * env.water_density)
                xyz = _joint_position(case, line, j, result)
                ids.append(add_point("Free", xyz, mass, volume))
        ids.append(b)
        for k, seg in enumerate(line.segments):
            name = line.name if not line.multi_segment else f"{line.name}_{k + 1}"
            line_rows.append([str(len(line_rows) + 1), seg.line_type.name, str(ids[k]),
                              str(ids[k + 1]), _g(seg.length),
                              str(default_num_segs(seg.length)), "-", f"# {name}"])

    out = ["--------------------- MoorDyn Input File " + "-" * 31,
           f"{case.name} (written by moorsolve export-moordyn, network form)"]
    out += [f"# moorsolve: {n}" for n in notes]
    out.append(_section("LINE TYPES"))
    out.append("TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx")
    out.append("(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)")
    out += [" ".join(row) for row in type_rows]
    if body_rows:
        out.append(_section("BODIES"))
        out.append("ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*")
        out.append("(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)")
        out += [" ".join(row) for row in body_rows]
    out.append(_section("POINTS"))
    out.append("ID Attachment X Y Z Mass Volume CdA Ca")
    out.append("(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)")
    out += [" ".join(row) for row in point_rows]
    out.append(_section("LINES"))
    out.append("ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs")
    out.append("(#) (name) (#) (#) (m) (-) (-)")
    out += [" ".join(row[:7]) + "   " + row[7] for row in line_rows]
    out.append(_section("OPTIONS"))
    out.append(f"{_g(env.gravity)} g")
    out.append(f"{_g(env.water_density)} rho")
    out.append(f"{_g(env.depth)} WtrDpth")
    out += [f"{name} {key}" for key, name in seafloor_option(env, curves, curve_prefix)]
    out.append("0.001 dtM")
    out.append("3.0e6 kBot")
    out.append("3.0e5 cBot")
    out.append(_section("OUTPUTS"))
    out.append("END")
    out.append(_RULE)
    return "\n".join(out) + "\n"


def _joint_position(case, line, j: int, result) -> tuple:
    """Joint ``j`` of a multi-segment line: from the result, else along its chord."""
    if result is not None:
        leg = result.leg(line.name)
        if j < len(leg.joints):
            return tuple(leg.joints[j]["position_m"])
    from ..model.build_network import end_position
    bodies = {b.name: b for b in case.bodies}
    a, b = end_position(line.a, bodies), end_position(line.b, bodies)
    s = sum(seg.length for seg in line.segments[: j + 1]) / line.length
    return tuple(float(a[i] + s * (b[i] - a[i])) for i in range(3))

