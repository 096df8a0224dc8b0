"""MoorDyn input files out: write a case (and optionally its equilibrium) as a MoorDyn v1 or
v2 input file.

Values the case holds come from the case: positions, lengths, the volume-equivalent diameter,
the mass per metre (``Mass/m = w / g + rho pi Diam^2 / 4``, so the submerged weight is
exactly the case's), EA, clump mass and volume, WtrDpth, g and the water density. Everything
else comes from the case file's ``moordyn`` block when the case was imported from MoorDyn
(unchanged), else from the documented defaults below.

Defaults for a case that did not come from MoorDyn (dynamic properties only; they do not
change the static answer):

- Diam: the line type's ``diameter``; for a catalogue line, the volume-equivalent diameter
  of the catalogue's mass and material density (1.80 d for studless chain); without a
  diameter, that of a steel line (7850 kg/m^3) of the given submerged weight.
- chain (a catalogue chain, or a type whose name contains "chain"): Cd 1.333, Ca 1.0,
  CdAx 0.639, CaAx 0.5 on the volume-equivalent diameter (DNV-OS-E301 drag adjusted to the
  volumetric diameter, BV NR493 added mass; the values MoorPy's default property file
  uses); other lines: Cd 1.2, Ca 1.0, CdAx 0.008, CaAx 0 (a smooth cylinder). A line type
  with ``drag`` uses its normal coefficient for Cd and its tangential one over pi for CdAx
  (MoorDyn's CdAx is on the surface area pi d l). BA/-zeta -0.8 (80 % of critical), EI 0.
- NumSegs: one segment per 5 m of line, from 10 to 100; outputs "-".
- options: dtM from the axial wave speed (half the time it takes along the shortest
  segment, rounded down to one digit), kBot 3e6, cBot 3e5, dtIC 1, TmaxIC 60, CdScaleIC 5,
  threshIC 0.001; OUTPUTS the fairlead and anchor tension of every leg.
- A body: v2 writes a Coupled body 1 at the origin with the fairleads as Body1 points
  (body-frame coordinates); v1 writes Vessel points (platform-frame coordinates).
"""

from __future__ import annotations

import logging
import math
from os import PathLike
from pathlib import Path

from ..errors import CaseError
from ..model.moordyn_block import RAW_SECTIONS
from .bathymetry import seafloor_option
from .moordyn_write_types import default_num_segs, line_type_rows
from .moordyn_write_types import number_text as _g  # _g: dense rows
from .output_files import write_text
from .rotations import apply_transpose, moordyn_angles, moordyn_matrix, yawed

__all__ = ["case_to_moordyn", "export_moordyn"]

log = logging.getLogger(__name__)

DEFAULT_OPTIONS = [("kBot", "3.0e6"), ("cBot", "3.0e5"), ("dtIC", "1.0"), ("TmaxIC", "60"),
                   ("CdScaleIC", "5.0"), ("threshIC", "0.001")]

_V1_KEYWORDS = {"FIXED", "FIX", "VESSEL", "VES", "CONNECT", "CON"}
_FIXED = {"FIXED", "FIX", "ANCHOR"}
_FREE = {"FREE", "CONNECT", "CON", "POINT"}
_COUPLED = {"COUPLED", "VESSEL", "VES", "CPLD"}


def _coordinate(value: float, scale: float) -> str:
    """A coordinate: rounding noise below 1e-12 of the scene's size is written as 0."""
    return "0" if abs(value) < 1e-12 * scale else _g(value)


def _keyword(stored: str | None, kind: str, version: int, body_id: int | None = None) -> str:
    """The attachment keyword to write: the stored one when it is valid for the version."""
    if stored is not None:
        word = stored.upper()
        group = {"fixed": _FIXED, "free": _FREE, "coupled": _COUPLED}.get(kind, set())
        if word in group and (version == 2 or word in _V1_KEYWORDS):
            return stored
        if kind == "body" and version == 2 and word == f"BODY{body_id}":
            return stored
    if version == 1:
        return {"fixed": "Fixed", "free": "Connect", "coupled": "Vessel", "body": "Vessel"}[kind]
    return {"fixed": "Fixed", "free": "Free", "coupled": "Coupled"}.get(kind, f"Body{body_id}")


def _rotate(x: float, y: float, angle: float) -> tuple:
    c, s = math.cos(angle), math.sin(angle)
    return c * x - s * y, s * x + c * y


def _clump_columns(clump, env) -> tuple:
    """Mass [kg] and volume [m^3] of a joint's clump (0, 0 for a bare joint)."""
    if clump is None:
        return 0.0, 0.0
    if clump.mass is not None:
        return clump.mass, clump.volume or 0.0
    if clump.weight >= 0:
        return clump.weight / env.gravity, 0.0
    return 0.0, -clump.weight / (env.gravity * env.water_density)


def _assign_ids(items: list, same) -> list:
    """IDs for rows that prefer one: keep each preferred ID once, new IDs after, 1..N.

    ``items`` are ``(preferred id or None, payload)``; rows with the same preferred ID whose
    payloads are ``same`` share it (a point two legs share). Returns the ID of every item.
    If the kept IDs are not 1..N (MoorDyn's rule) everything is renumbered in ID order.
    """
    taken, ids = {}, []
    for pref, payload in items:
        if pref is not None and pref in taken and same(taken[pref], payload):
            ids.append(pref)
        elif pref is not None and pref not in taken:
            taken[pref] = payload
            ids.append(pref)
        else:
            ids.append(None)
    next_id = max(taken, default=0)
    for k, (pref, payload) in enumerate(items):
        if ids[k] is None:
            next_id += 1
            taken[next_id] = payload
            ids[k] = next_id
    unique = sorted(set(ids))
    if unique != list(range(1, len(unique) + 1)):
        log.warning("MoorDyn IDs renumbered to 1..%d; check OUTPUTS that name IDs", len(unique))
        renumber = {old: new for new, old in enumerate(unique, start=1)}
        ids = [renumber[i] for i in ids]
    return ids


def _default_dt(case, masses: dict, num_segs: list, stiffness: dict) -> str:
    """Half the axial-wave transit time of the shortest segment, rounded down to one digit
    (a curve's stiffest part sets its wave speed)."""
    times = []
    for leg, segs in zip(case.legs, num_segs):
        for seg, n in zip(leg.segments, segs):
            lt = seg.line_type
            if masses[lt.name] > 0:
                times.append(seg.length / n * math.sqrt(masses[lt.name] / stiffness[lt.name]))
    dt = 0.5 * min(times) if times else 1e-3
    exponent = math.floor(math.log10(dt))
    return _g(math.floor(dt / 10 ** exponent) * 10 ** exponent)


def case_to_moordyn(case, *, version: int | None = None, result=None,
                    curves: dict | None = None, curve_prefix: str = "") -> str:
    """The MoorDyn input file of a case, as text.

    Parameters
    ----------
    case : moorsolve.Case
        A validated case (its ``moordyn`` block, if any, supplies what the case does not hold).
    version : 1 or 2, optional
        File format; default the version the case was imported from, else 2.
    result : moorsolve.Result, optional
        An equilibrium of this case: the fairleads (body moved by the result's offset and yaw)
        and the joints are then written at their solved positions, so a dynamic run starts
        from the static equilibrium. v2 moves the body's reference pose (BODIES X0, Y0, y0)
        or the Coupled points; v1 keeps the Vessel points in the platform frame and notes
        the platform's pose in the front matter (give it to the driver).
    curves : dict, optional
        Filled with ``{file name: text}`` of the tension-strain curve files that line types
        with a stretch law name in their EA column (:mod:`.moordyn_curves`); the caller
        writes them beside the input file (:func:`export_moordyn` does).
    curve_prefix : str
        Prefix of the curve file names (``<prefix><type>_ea.txt``).

    Raises
    ------
    CaseError
        Something MoorDyn cannot hold: an inextensible line, a buoyant line without a
        diameter, a sloped plane seabed (a bathymetry grid is written as a SeafloorFile,
        ``<prefix>seafloor.txt``, put into ``curves`` to be written beside the file), line
        drag in a current.
    """
    if getattr(case, "form", "legs") == "network":
        if version == 1:
            raise CaseError("--version", "a network case (bodies, points, lines) is written "
                                         "as MoorDyn v2 only; v1 has no bodies")
        from .moordyn_network_write import network_to_moordyn
        return network_to_moordyn(case, result, curves=curves, curve_prefix=curve_prefix)
    block = dict(case.moordyn or {})
    version = version or block.get("version", 2)
    if version not in (1, 2):
        raise CaseError("--version", f"{version!r} must be 1 or 2")
    env = case.environment
    if env.seabed.sloped and env.seabed.bathymetry is None:
        raise CaseError("environment.seabed.gradient", "a sloped seabed cannot be written as "
                                                       "MoorDyn's flat WtrDpth; use a flat "
                                                       "seabed or a bathymetry grid")
    stored_legs = block.get("legs", {})
    type_rows, masses, stiffness = line_type_rows(case, block, version, curve_prefix, curves)
    notes = []

    # ---- the body and where the fairleads are written ----
    body = case.body
    stored_body = block.get("body")
    stored_fair = [stored_legs[leg.name]["points"][-1].get("attachment")
                   for leg in case.legs if leg.name in stored_legs]
    coupled_mode = (body is not None and stored_body is None and stored_fair
                    and all(a is not None and a.upper() in _COUPLED for a in stored_fair))
    pose = (0.0, 0.0, 0.0, 0.0)            # X0, Y0, Z0, yaw [deg]: body reference at rest
    tilt = (0.0, 0.0)                      # r0, p0 [deg]
    if stored_body is not None:
        pose = tuple(float(stored_body.get(k, 0.0)) for k in ("x0", "y0", "z0", "yaw_deg"))
        tilt = tuple(float(stored_body.get(k, 0.0)) for k in ("r0_deg", "p0_deg"))
    turn = moordyn_matrix(tilt[0], tilt[1], pose[3])
    body_id = stored_body["id"] if stored_body is not None else 1
    offset = (0.0, 0.0, 0.0)               # the result's x, y, yaw [deg]
    if result is not None and body is not None:
        offset = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
    new_xy = _rotate(pose[0], pose[1], math.radians(offset[2]))
    new_pose = (new_xy[0] + offset[0], new_xy[1] + offset[1], pose[2], pose[3] + offset[2])
    new_tilt = tilt
    if any(tilt) and offset[2]:
        *new_tilt, yaw = moordyn_angles(yawed(turn, offset[2]))
        new_pose = new_pose[:3] + (yaw,)

    scale = max(1.0, env.depth, *(abs(v) for leg in case.legs for v in leg.anchor + leg.fairlead))

    def fairlead_coordinates(leg) -> list:
        fx, fy, fz = leg.fairlead
        if body is None:
            return [fx, fy, fz]
        if coupled_mode:
            if result is None or version == 1:    # v1 Vessel points: platform frame
                return [fx, fy, fz]
            x, y = _rotate(fx, fy, math.radians(offset[2]))
            return [x + offset[0], y + offset[1], fz]
        if not any(tilt):
            x, y = _rotate(fx - pose[0], fy - pose[1], -math.radians(pose[3]))
            return [x, y, fz - pose[2]]
        return list(apply_transpose(turn, (fx - pose[0], fy - pose[1], fz - pose[2])))

    # ---- points and lines, leg by leg ----
    point_items, line_items, legs_points, legs_lines = [], [], [], []
    num_segs_all = []
    for li, leg in enumerate(case.legs):
        stored = stored_legs.get(leg.name, {})
        sp = stored.get("points", [None] * (len(leg.segments) + 1))
        sl = stored.get("lines", [None] * len(leg.segments))
        joints_solved = None
        if result is not None and leg.multi_segment:
            joints_solved = [j["position_m"] for j in result.leg(leg.name).joints]
        rows = []
        # anchor
        s = sp[0] or {}
        rows.append(("fixed", s, list(leg.anchor), None))
        # joints
        cumulative = 0.0
        for j, clump in enumerate(leg.joint_clumps):
            cumulative += leg.segments[j].length
            s = sp[j + 1] or {}
            if joints_solved is not None:
                pos = list(joints_solved[j])
            elif "position" in s:
                pos = list(s["position"])
            else:
                t = cumulative / leg.length
                pos = [a + t * (f - a) for a, f in zip(leg.anchor, leg.fairlead)]
            rows.append(("free", s, pos, clump))
        # fairlead
        s = sp[-1] or {}
        kind = "fixed" if body is None else ("coupled" if coupled_mode else "body")
        rows.append((kind, s, fairlead_coordinates(leg), None))
        legs_points.append(rows)
        for kind, s, pos, clump in rows:
            key = (kind, tuple(round(v, 6) for v in pos))
            point_items.append((s.get("id"), key))
        segs = []
        for k, seg in enumerate(leg.segments):
            s = sl[k] or {}
            n = s.get("num_segs", str(default_num_segs(seg.length)))
            segs.append(int(n))
            line_items.append((s.get("id"), (li, k)))
        num_segs_all.append(segs)
        legs_lines.append(sl)

    point_ids = _assign_ids(point_items, lambda a, b: a == b)
    line_ids = _assign_ids(line_items, lambda a, b: False)

    point_rows, pi = {}, 0
    leg_point_ids = []
    for rows in legs_points:
        ids = []
        for kind, s, pos, clump in rows:
            pid = point_ids[pi]
            pi += 1
            ids.append(pid)
            if pid in point_rows:
                continue
            cols = dict(s.get("columns", {}))
            word = _keyword(s.get("attachment"), kind, version, body_id)
            if kind == "free":
                mass, volume = _clump_columns(clump, env)
                mass_s, volume_s = _g(mass), _g(volume)
            else:
                mass_s, volume_s = cols.get("mass", "0"), cols.get("volume", "0")
            xyz = [_coordinate(v, scale) for v in pos]
            if version == 1:
                row = [str(pid), word, *xyz, mass_s, volume_s, cols.get("fx", "0"),
                       cols.get("fy", "0"), cols.get("fz", "0"), cols.get("cda", "0"),
                       cols.get("ca", "0")]
            else:
                row = [str(pid), word, *xyz, mass_s, volume_s, cols.get("cda", "0"),
                       cols.get("ca", "0")]
            point_rows[pid] = row
        leg_point_ids.append(ids)

    line_rows, k = {}, 0
    outputs_default = []
    for li, leg in enumerate(case.legs):
        ids = leg_point_ids[li]
        for j, seg in enumerate(leg.segments):
            lid = line_ids[k]
            k += 1
            s = legs_lines[li][j] or {}
            a, b = ids[j], ids[j + 1]
            if s.get("reversed"):
                a, b = b, a
            n = str(num_segs_all[li][j])
            out = s.get("outputs", "-")
            if version == 1:
                row = [str(lid), seg.line_type.name, _g(seg.length), n, str(a), str(b), out]
            else:
                row = [str(lid), seg.line_type.name, str(a), str(b), _g(seg.length), n, out]
            line_rows[lid] = row
            if j == 0:
                outputs_default.append(f"AnchTen{lid}")
            if j == len(leg.segments) - 1:
                outputs_default.append(f"FairTen{lid}")

    # ---- options ----
    env_values = {"depth": env.depth, "gravity": env.gravity, "water_density": env.water_density}
    env_names = {"wtrdpth": "depth", "g": "gravity", "gravity": "gravity", "rho": "water_density",
                 "rhow": "water_density", "wtrdnsty": "water_density"}
    if "options" in block:
        options = [list(o) for o in block["options"]]
    else:
        options = [["dtM", _default_dt(case, masses, num_segs_all, stiffness)]] + \
                  [list(o) for o in DEFAULT_OPTIONS]
    present = set()
    for opt in options:
        key = env_names.get(opt[0].lower())
        if key == "water_density" and version == 1 and opt[0].lower() == "rho":
            opt[0] = "rhoW"                      # v1's name for the water density
        if key is not None:
            opt[1] = _g(env_values[key])
            present.add(key)
    for key, name in (("depth", "WtrDpth"), ("gravity", "g"),
                      ("water_density", "rhoW" if version == 1 else "rho")):
        if key not in present:
            options.append([name, _g(env_values[key])])
    options = [o for o in options if o[0].lower() != "seafloorfile"]
    options += seafloor_option(env, curves, curve_prefix)

    # ---- front matter ----
    header = [h for h in block.get("header", []) if not h.startswith("moorsolve:")]
    if not header:
        header = [f"--------------------- MoorDyn Input File ({case.name}) ---------------------"
                  if version == 2 else f"MoorDyn input file: {case.name}",
                  "written by moorsolve export-moordyn"]
    if body is not None and version == 1 and any(new_pose):
        notes.append(f"moorsolve: Vessel points are in the platform frame; the platform "
                     f"reference is at X {new_pose[0]:.9g} m, Y {new_pose[1]:.9g} m, yaw "
                     f"{new_pose[3]:.9g} deg")
    if result is not None:
        notes.append("moorsolve: positions are the static equilibrium "
                     f"(body offset x {offset[0]:.9g} m, y {offset[1]:.9g} m, yaw "
                     f"{offset[2]:.9g} deg)" if body is not None
                     else "moorsolve: free points are at the static equilibrium")
    if version == 1 and block.get("sections"):
        notes.append("moorsolve: sections " + ", ".join(block["sections"]) + " have no v1 form "
                     "and were left out")

    # ---- the text ----
    def table(title, names, units, rows):
        widths = [max(len(str(r[i])) for r in [names, units, *rows] if i < len(r))
                  for i in range(max(len(r) for r in [names, units, *rows]))]
        out = [f"---------------------- {title} " + "-" * max(4, 60 - len(title))]
        for r in [names, units, *rows]:
            out.append("  ".join(str(v).ljust(widths[i]) for i, v in enumerate(r)).rstrip())
        return out

    text = list(header) + notes
    if version == 1:
        text += table("LINE DICTIONARY",
                      "LineType Diam MassDenInAir EA BA/-zeta Can Cat Cdn Cdt".split(),
                      "(-) (m) (kg/m) (N) (N-s/-) (-) (-) (-) (-)".split(), type_rows)
        text += table("NODE PROPERTIES", "Node Type X Y Z M V FX FY FZ CdA CA".split(),
                      "(-) (-) (m) (m) (m) (kg) (m^3) (kN) (kN) (kN) (m^2) (-)".split(),
                      [point_rows[i] for i in sorted(point_rows)])
        text += table("LINE PROPERTIES",
                      "Line LineType UnstrLen NumSegs NodeAnch NodeFair Flags/Outputs".split(),
                      "(-) (-) (m) (-) (-) (-) (-)".split(),
                      [line_rows[i] for i in sorted(line_rows)])
        text.append("---------------------- SOLVER OPTIONS " + "-" * 44)
    else:
        wide = any(len(r) > 10 for r in type_rows)
        names = "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx".split()
        units = "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)".split()
        if wide:
            names, units = names + ["Cl", "dF", "cF"], units + ["(-)", "(-)", "(-)"]
        text += table("LINE TYPES", names, units, type_rows)
        sections = block.get("sections", {})
        if "ROD TYPES" in sections:
            text += ["---------------------- ROD TYPES " + "-" * 50] + sections["ROD TYPES"]
        if body is not None and not coupled_mode:
            cols = (stored_body or {}).get("columns", {})
            row = [str(body_id), (stored_body or {}).get("attachment", "Coupled"),
                   *(_coordinate(v, scale) for v in new_pose[:3]),
                   *(_g(a) if a else "0" for a in new_tilt), _g(new_pose[3]),
                   *(cols.get(c, "0") for c in ("mass", "cg", "i", "volume", "cda", "ca"))]
            text += table("BODIES", "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* "
                                    "Ca*".split(),
                          "(#) (word) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) "
                          "(m^2) (-)".split(), [row])
        if "RODS" in sections:
            text += ["---------------------- RODS " + "-" * 56] + sections["RODS"]
        text += table("POINTS", "ID Attachment X Y Z Mass Volume CdA Ca".split(),
                      "(#) (word/ID) (m) (m) (m) (kg) (m^3) (m^2) (-)".split(),
                      [point_rows[i] for i in sorted(point_rows)])
        text += table("LINES", "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs".split(),
                      "(#) (name) (#) (#) (m) (-) (-)".split(),
                      [line_rows[i] for i in sorted(line_rows)])
        for title in RAW_SECTIONS[2:]:
            if title in sections:
                text += [f"---------------------- {title} " + "-" * 40] + sections[title]
        text.append("---------------------- OPTIONS " + "-" * 51)
    width = max(len(o[1]) for o in options) if options else 0
    text += [f"{o[1].ljust(width)}  {o[0]}" for o in options]
    outputs = block["outputs"] if "outputs" in block else outputs_default
    text.append("---------------------- OUTPUTS " + "-" * 52)
    text += list(outputs)
    text.append("END")
    text.append("------------------------- need this line " + "-" * 42)
    return "\n".join(text) + "\n"


def export_moordyn(case, out, *, version: int | None = None, solve=None):
    """Write a case as a MoorDyn input file (atomically); returns the Result when solved.

    Parameters
    ----------
    case : str, pathlib.Path, mapping or moorsolve.Case
        The case (a case file is loaded and validated).
    out : str or pathlib.Path
        The MoorDyn file to write.
    version : 1 or 2, optional
        See :func:`case_to_moordyn`.
    solve : callable, optional
        ``solve(case) -> Result``, called once the case and ``out`` are validated: the file
        then holds the equilibrium positions. The caller above io brings the solver
        (:func:`moorsolve.export_moordyn`'s ``equilibrium``); io imports none.

    Raises
    ------
    CaseError
        Bad input (nothing written). Whatever ``solve`` raises (nothing written).
    """
    from ..model import Case
    if not isinstance(case, Case):
        from .case_file import load_case
        case = load_case(case)
    if not isinstance(out, (str, PathLike)):
        raise CaseError("-o", f"{out!r} is not a path")
    out = Path(out)
    folder = out.resolve().parent
    if not folder.is_dir():
        raise CaseError("-o", f"folder {str(folder)!r} does not exist")
    result = None if solve is None else solve(case)
    curves = {}
    text = case_to_moordyn(case, version=version, result=result, curves=curves,
                           curve_prefix=f"{out.stem}_")
    for name, curve in curves.items():
        write_text(out.parent / name, curve)
    write_text(out, text)
    return result
