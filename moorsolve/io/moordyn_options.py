"""MoorDyn's OPTIONS: the water depth, gravity and water density a file gives (with MoorDyn's
aliases and defaults), and what its other options are (simulation settings, seabed friction
and bathymetry, which the import reports, or names MoorDyn does not know)."""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import CaseError
from .bathymetry import read_bathymetry
from .moordyn_parse import MoorDynFile, number_token

__all__ = ["DEFAULT_GRAVITY", "DEFAULT_WATER_DENSITY", "KNOWN_OPTIONS", "read_environment"]

#: MoorDyn's defaults where a file leaves an option out: MoorDyn-C v2 and OpenFAST (the glue
#: code's g and water density for MoorDyn-F, v1 and v2).
DEFAULT_GRAVITY = 9.80665
DEFAULT_WATER_DENSITY = 1025.0

_DEPTH = ("wtrdpth", "depth", "waterdepth")
_GRAVITY = ("g", "gravity")
_DENSITY = ("rho", "rhow", "wtrdnsty")
#: Every option MoorDyn-C v2, MoorDyn-F v2 or MoorDyn v1 reads (lower case); others draw a
#: warning from MoorDyn and are ignored.
KNOWN_OPTIONS = frozenset(_DEPTH + _GRAVITY + _DENSITY + (
    "dtm", "dt", "cfl", "writelog", "tscheme", "kbot", "kb", "cbot", "cb", "dtic", "icdt",
    "tmaxic", "ictmax", "cdscaleic", "icdfac", "threshic", "icthresh", "gendynamicic",
    "icgendynamic", "fileic", "icfile", "wavekin", "dtwave", "currents", "unifycurrentgrid",
    "writeunits", "frictioncoefficient", "fricdamp", "statdynfricscale", "dtout",
    "seafloorfile", "disableoutput", "disableouttime", "mu_kt", "mu_ka", "mc", "cv",
    "waterkin", "inertialf", "inertialf_rampt", "outswitch", "echo"))
_FRICTION = ("frictioncoefficient", "mu_kt", "mu_ka")


def read_environment(md: MoorDynFile, points: dict, read: list, converted: list,
                     ignored: list) -> tuple:
    """(depth, gravity, density, options) from OPTIONS and MoorDyn's defaults."""
    values, where, options = {}, {}, []
    base = Path(md.path).parent
    dynamic, unknown = [], []
    for opt, token, number in md.options:
        low = opt.lower()
        key = ("depth" if low in _DEPTH else "gravity" if low in _GRAVITY
               else "water_density" if low in _DENSITY else None)
        if key is None:
            options.append([opt, token])
            if low == "seafloorfile":
                values["bathymetry"] = _seafloor(md, base, token, number, converted,
                                                 ignored)
            elif low in _FRICTION:
                ignored.append(f"line {number}: {opt} {token}: MoorDyn's seabed friction is "
                               "dynamic (and MoorPy ignores it); the case's seabed is "
                               "frictionless until environment.seabed.friction is set")
            elif low in KNOWN_OPTIONS:
                dynamic.append(f"{opt} (line {number})")
            else:
                unknown.append(f"{opt} (line {number})")
            continue
        value = number_token(token)
        if key == "depth" and value is None and (base / token).is_file():
            # MoorDyn-F takes a WtrDpth that names a file as its bathymetry grid.
            found = _seafloor(md, base, token, number, converted, ignored)
            values["bathymetry"] = found
            grid_depth = max(max(row) for row in found[1]["depth"])
            values["depth"], where["depth"] = grid_depth, number
            converted.append(f"line {number}: {opt} {token!r} names the grid: the case's "
                             f"reference depth is its deepest node, {grid_depth:g} m")
            options.append([opt, token])
            continue
        if value is None or not math.isfinite(value):
            raise md.error(number, f"option {opt!r}: {token!r} is not a number")
        if value < 0 or (key == "depth" and value == 0):
            raise md.error(number, f"option {opt!r}: {token!r} must be "
                                   f"{'> 0' if key == 'depth' else '>= 0'}")
        if key in where:
            converted.append(f"line {number}: {opt} {token} replaces the {key.replace('_', ' ')} "
                             f"given at line {where[key]} (MoorDyn keeps the last)")
        values[key], where[key] = value, number
        options.append([opt, None])
    if dynamic:
        ignored.append("options for the simulation only: " + ", ".join(dynamic))
    if unknown:
        ignored.append("options MoorDyn does not know (it warns and ignores them): "
                       + ", ".join(unknown))

    depth = values.get("depth", 0.0)
    deepest = None
    for p in points.values():
        z = p.position[2]
        if p.kind != "body" and not p.on_seabed and z < -depth:
            depth, deepest = -z, p
    if "depth" in values:
        converted.append(f"water depth {values['depth']:g} m from {_source(md, 'depth')}")
        if deepest is not None:
            converted.append(f"point {deepest.id} (line {deepest.line}) is below WtrDpth: the "
                             f"water is deepened to it, {depth:g} m (MoorDyn-C's rule)")
    elif deepest is not None:
        converted.append(f"no WtrDpth: water depth {depth:g} m, that of the deepest point "
                         f"({deepest.id}, line {deepest.line}), as MoorDyn sets it")
    if not depth > 0:
        raise md.error(None, "no water depth: give the option WtrDpth (or a fixed point below "
                             "the water line)")
    for key, default, what in (("gravity", DEFAULT_GRAVITY, "g"),
                               ("water_density", DEFAULT_WATER_DENSITY, "rho")):
        if key in values:
            converted.append(f"{key.replace('_', ' ')} {values[key]:g} from "
                             f"{_source(md, key)}")
        else:
            values[key] = default
            converted.append(f"no {what}: MoorDyn's default {key.replace('_', ' ')} "
                             f"{default:g} {'m/s^2' if key == 'gravity' else 'kg/m^3'}")
    return depth, values["gravity"], values["water_density"], options, values.get("bathymetry")


def _seafloor(md: MoorDynFile, base: Path, token: str, number: int, converted: list,
              ignored: list):
    """``(absolute path, grid)`` of the SeafloorFile, read relative to the input file (or,
    as MoorDyn-C does, the working directory); None, reported, when there is no such file
    (a file shared without its grid): the seabed is then flat at the water depth."""
    path = Path(token) if Path(token).is_absolute() else base / token
    if not path.is_file() and Path(token).is_file():
        path = Path(token)      # MoorDyn-C reads it from the working directory
    if not path.is_file():
        ignored.append(f"line {number}: SeafloorFile {token!r}: no such file beside the input "
                       "file (MoorDyn would stop here); the seabed is flat at the water depth")
        return None
    try:
        grid = read_bathymetry(path, field="SeafloorFile")
    except CaseError as exc:
        raise md.error(number, f"SeafloorFile {token!r}: {exc.detail}") from None
    converted.append(f"line {number}: SeafloorFile {token!r}: a bathymetry grid of "
                     f"{len(grid['x'])} x {len(grid['y'])} depths, "
                     f"environment.seabed.bathymetry (interpolated bilinearly, as MoorDyn does)")
    return str(path.resolve()), grid


def _source(md: MoorDynFile, key: str) -> str:
    names = {"depth": _DEPTH, "gravity": _GRAVITY, "water_density": _DENSITY}[key]
    found = [(n, line) for n, _, line in md.options if n.lower() in names]
    name, line = found[-1]
    return f"option {name} (line {line})"
