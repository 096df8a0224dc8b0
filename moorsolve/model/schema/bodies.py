"""Case-file sections: bodies and their loads, points and lines of the network form,
motions, berths."""

from __future__ import annotations

from ...constants import FRICTION_SLIP
from ._base import REQUIRED, Key, section
from .case import ANCHORS, DOFS3, DOFS6, _CENTRE

# ---- the body of the legs form ----------------------------------------------------------

_LOADS = Key("environmental and constant loads", "mapping", section="loads")
_FIXED_TO = Key("what the held pose is relative to", "choice", default="water",
                choices=("water", "seabed"),
                range="water: floats, rises with the tide; seabed: fixed on the datum")
section("body", "body", "The moored body of the legs form (planar: surge, sway, yaw).", {
    "free": Key("degrees of freedom solved for", "list", default=DOFS3, choices=DOFS3),
    "outline": Key("ship hull drawn in the pictures (no effect on the solve)", "mapping",
                   section="outline"),
    "outline_members": Key("vertical cylinders and boxes drawn in the pictures (no effect on "
                           "the solve; hull gives buoyancy)", "list",
                           section="hull_cylinder|hull_box"),
    "loads": _LOADS,
    "fixed_to": _FIXED_TO,
})
section("loads", "body.loads, bodies[i].loads", "Loads on a body.", {
    "force": Key("constant load, global frame", "force",
                 shape="[Fx, Fy, Mz] or (bodies) [Fx, Fy, Fz, Mx, My, Mz]", also=("moment",)),
    "wind": Key("wind load model", "mapping", section="drag_load|hu_tang_wind"),
    "current": Key("current load model", "mapping", section="drag_load|hu_tang_current"),
    "wave_drift": Key("mean wave drift model", "mapping",
                      section="hu_tang_drift|drift_coefficient"),
})
section("drag_load", "loads.wind, loads.current (model: drag)",
        "Quadratic drag F = 1/2 rho C A u^2 on projected areas.", {
            "model": Key("the model", "choice", REQUIRED, choices=("drag",)),
            "area_x": Key("area projected on the y-z plane (flow along x)", "area", REQUIRED,
                          range=">= 0"),
            "area_y": Key("area projected on the x-z plane (flow along y)", "area", REQUIRED,
                          range=">= 0"),
            "cx": Key("drag coefficient along x", "dimensionless", default=1.0, range=">= 0"),
            "cy": Key("drag coefficient along y", "dimensionless", default=1.0, range=">= 0"),
            "table": Key("coefficients by relative heading, instead of cx, cy", "dimensionless",
                         shape="[[heading_deg, cx, cy, cmz], ...]",
                         range=">= 2 rows, headings increasing, span < 360 deg",
                         also=("angle",)),
            "length": Key("reference length of the yaw moment (table cmz)", "length",
                          default=0.0, range=">= 0"),
            "centre": _CENTRE,
        })
section("hu_tang_wind", "loads.wind (model: hu_tang)",
        "Wind on a moored ship by the Hu and Tang areas method.", {
            "model": Key("the model", "choice", REQUIRED, choices=("hu_tang",)),
            "superstructure_area": Key("superstructure frontal area", "area", REQUIRED,
                                       range=">= 0"),
            "hull_area": Key("hull frontal area above water", "area", REQUIRED, range=">= 0"),
            "superstructure_area_lateral": Key("superstructure lateral area (with "
                                               "hull_area_lateral)", "area", range=">= 0"),
            "hull_area_lateral": Key("hull lateral area above water", "area", range=">= 0"),
            "centre": _CENTRE,
        })
section("hu_tang_current", "loads.current (model: hu_tang)",
        "Current on a moored ship from its wetted area.", {
            "model": Key("the model", "choice", REQUIRED, choices=("hu_tang",)),
            "wetted_area": Key("wetted hull area", "area", REQUIRED, range="> 0"),
            "coefficient": Key("current force coefficient", "dimensionless", default=0.18,
                               range="> 0"),
            "centre": _CENTRE,
        })
section("hu_tang_drift", "loads.wave_drift (model: hu_tang)",
        "Mean wave drift on a ship from its beam.", {
            "model": Key("the model", "choice", REQUIRED, choices=("hu_tang",)),
            "beam": Key("ship beam", "length", REQUIRED, range="> 0"),
            "length": Key("ship length (for the bow-on drift)", "length", range="> 0"),
            "k": Key("drift coefficient", "dimensionless", default=0.7, range="> 0"),
            "centre": _CENTRE,
        })
section("drift_coefficient", "loads.wave_drift (model: coefficient)",
        "Mean drift F = 1/8 rho g C L Hs^2 along each axis.", {
            "model": Key("the model", "choice", REQUIRED, choices=("coefficient",)),
            "length_x": Key("width facing waves along x", "length", REQUIRED, range=">= 0"),
            "length_y": Key("width facing waves along y", "length", REQUIRED, range=">= 0"),
            "cx": Key("drift coefficient along x", "dimensionless", default=1.0, range=">= 0"),
            "cy": Key("drift coefficient along y", "dimensionless", default=1.0, range=">= 0"),
            "centre": _CENTRE,
        })

# ---- the network form -------------------------------------------------------------------

section("network_body", "bodies[i]", "A body of the network form (six degrees of freedom).", {
    "name": Key("body name, unique", "text", REQUIRED),
    "position": Key("reference point at the case-file pose, global", "length",
                    default=(0.0, 0.0, 0.0), shape="[x, y, z]"),
    "orientation_deg": Key("roll, pitch, yaw at the case-file pose (z-y-x)", "angle",
                           default=(0.0, 0.0, 0.0), shape="[roll, pitch, yaw]",
                           range="|pitch| < 90 deg"),
    "free": Key("degrees of freedom solved for", "list",
                default="all six with mass and buoyancy, else surge, sway, yaw",
                choices=DOFS6, range="heave, roll, pitch need mass and buoyancy"),
    "mass": Key("mass", "mass", range="> 0"),
    "centre_of_gravity": Key("centre of gravity, body frame", "length",
                             default=(0.0, 0.0, 0.0), shape="[x, y, z]"),
    "hydrostatics": Key("linear hydrostatics (instead of hull)", "mapping",
                        section="hydrostatics"),
    "hull": Key("hull members: exact buoyancy and the drawn outline", "list",
                section="hull_cylinder|hull_box"),
    "outline": Key("ship hull drawn in the pictures (no effect on the solve)", "mapping",
                   section="outline"),
    "outline_members": Key("vertical cylinders and boxes drawn in the pictures (no effect on "
                           "the solve; hull gives buoyancy)", "list",
                           section="hull_cylinder|hull_box"),
    "stiffness": Key("linear spring to the reference pose, 6x6 SI", "dimensionless",
                     shape="6 rows of 6"),
    "added_mass": Key("added mass, 6x6 SI (periods, motions)", "dimensionless",
                      shape="6 rows of 6"),
    "inertia": Key("moments of inertia about the centre of gravity", "moment_of_inertia",
                   shape="[Ixx, Iyy, Izz]", range=">= 0"),
    "loads": _LOADS,
    "fixed_to": _FIXED_TO,
    "hydrodynamics": Key("frequency-domain hydrodynamics (motions)", "mapping",
                         section="hydro_table|hydro_wamit|hydro_capytaine"),
    "damping": Key("extra damping (motions)", "mapping", section="damping"),
})
section("hydrostatics", "bodies[i].hydrostatics", "Linear hydrostatics of a body.", {
    "displaced_volume": Key("displaced volume at the case-file pose", "volume", REQUIRED,
                            range=">= 0"),
    "metacentre": Key("metacentre, body frame", "length", default=(0.0, 0.0, 0.0),
                      shape="[x, y, z]"),
    "waterplane_area": Key("waterplane area (heave stiffness rho g A)", "area", default=0.0,
                           range=">= 0"),
})
_MEMBER = {
    "shape": Key("member shape", "choice", REQUIRED, choices=("cylinder", "box")),
    "bottom": Key("bottom z, body frame", "length", REQUIRED),
    "top": Key("top z, body frame", "length", REQUIRED, range="> bottom"),
}
_AXIS = Key("axis position, body frame", "length", default=(0.0, 0.0), shape="[x, y]")
section("hull_cylinder", "bodies[i].hull[j], outline_members[j] (shape: cylinder)",
        "A vertical cylinder: exact buoyancy, drawn in the pictures.", {
            **_MEMBER,
            "radius": Key("radius", "length", REQUIRED, range="> 0"),
            "centre": _AXIS,
        })
section("hull_box", "bodies[i].hull[j], outline_members[j] (shape: box)",
        "A vertical box: exact buoyancy, drawn in the pictures.", {
            **_MEMBER,
            "length": Key("length along body x", "length", REQUIRED, range="> 0"),
            "width": Key("width along body y", "length", REQUIRED, range="> 0"),
            "centre": _AXIS,
        })
section("outline", "body.outline, bodies[i].outline",
        "A ship-shaped hull for the pictures: plan from length and beam, sides down to the "
        "draft. It draws the ship; its buoyancy and loads are given elsewhere.", {
            "length": Key("length overall", "length", REQUIRED, range="> 0"),
            "beam": Key("beam", "length", REQUIRED, range="> 0"),
            "draft": Key("draft", "length", default=0.0, range=">= 0"),
            "freeboard": Key("height of the deck above the waterline", "length", default=0.0,
                             range=">= 0"),
            "centre": Key("midship on the waterline, body frame", "length",
                          default=(0.0, 0.0), shape="[x, y]"),
            "heading_deg": Key("bow direction in the body frame, from body +x", "angle",
                               default=0.0),
        })
section("point", "points[i]", "A named point: fixed (an anchor, a bollard) or free (a "
        "buoy, a connection).", {
            "name": Key("point name, unique", "text", REQUIRED),
            "position": Key("position ([x, y]: on the seabed); a free point's start",
                            "length", REQUIRED, shape="[x, y] or [x, y, z]"),
            "free": Key("solved for (a connection, a buoy)", "bool", default=False),
            "mass": Key("mass of a free point", "mass", default=0.0, range=">= 0"),
            "volume": Key("displaced volume of a free point", "volume", default=0.0,
                          range=">= 0"),
        })
section("line", "lines[i]", "A line between two ends.", {
    "name": Key("line name, unique", "text", REQUIRED),
    "from": Key("first end: a point name, [x, y] on the seabed, [x, y, z], or {body, at}",
                "end", REQUIRED, section="body_end", also=("length",)),
    "to": Key("second end (same forms)", "end", REQUIRED, section="body_end",
              also=("length",)),
    "segments": Key("segments from the first end, {clump: ...} items between them; "
                    "or one {type, pretension}", "list", REQUIRED,
                    section="segment|clump_item|pretension_segment"),
    "anchor_type": Key("anchor kind for the anchor check", "mapping", section=ANCHORS),
})
section("body_end", "lines[i].from, lines[i].to", "A line end on a body.", {
    "body": Key("body name", "choice", REQUIRED, range="a name of bodies"),
    "at": Key("the point, body frame", "length", REQUIRED, shape="[x, y, z]"),
})

# ---- motions ----------------------------------------------------------------------------

section("hydro_table", "bodies[i].hydrodynamics (source: table)",
        "Hydrodynamic coefficients given in the case, SI, body frame.", {
            "source": Key("where they come from", "choice", REQUIRED, choices=("table",)),
            "omega": Key("frequencies", "dimensionless", REQUIRED, shape="[rad/s, ...]",
                         range=">= 2, increasing, 1e-4 to 100 rad/s"),
            "added_mass": Key("added mass per frequency", "dimensionless", REQUIRED,
                              shape="n 6x6 matrices"),
            "damping": Key("radiation damping per frequency", "dimensionless", REQUIRED,
                           shape="n 6x6 matrices"),
            "excitation": Key("first-order excitation per heading", "list", REQUIRED,
                              section="excitation"),
            "mean_drift": Key("mean drift coefficients per heading", "list",
                              section="mean_drift"),
        })
section("excitation", "hydrodynamics.excitation[k]", "Excitation at one heading.", {
    "heading_deg": Key("wave heading", "angle", REQUIRED, range="increasing, one turn"),
    "re": Key("real part per frequency and DOF", "dimensionless", REQUIRED, shape="n rows of 6"),
    "im": Key("imaginary part", "dimensionless", REQUIRED, shape="n rows of 6"),
})
section("mean_drift", "hydrodynamics.mean_drift[k]", "Mean drift at one heading.", {
    "heading_deg": Key("wave heading", "angle", REQUIRED, range="increasing, one turn"),
    "values": Key("drift force per unit amplitude squared", "dimensionless", REQUIRED,
                  shape="n rows of 6"),
})
section("hydro_wamit", "bodies[i].hydrodynamics (source: wamit)", "WAMIT output files.", {
    "source": Key("where they come from", "choice", REQUIRED, choices=("wamit",)),
    "files": Key("the .1, .3 (and .12d) files, relative to the case file", "file", REQUIRED),
    "ulen": Key("WAMIT length scale", "length", default=1.0, range="> 0"),
    "values": Key("the files' contents (filled in by load_case)", "any"),
})
section("hydro_capytaine", "bodies[i].hydrodynamics (source: capytaine)",
        "Coefficients computed by Capytaine from the hull members.", {
            "source": Key("where they come from", "choice", REQUIRED, choices=("capytaine",)),
            "omega": Key("frequencies", "dimensionless", REQUIRED, shape="[rad/s, ...]",
                         range=">= 2, increasing"),
            "headings_deg": Key("wave headings", "angle", REQUIRED, shape="[deg, ...]",
                                range="increasing, one turn"),
            "panel_size": Key("mesh panel size", "length", range="> 0"),
            "cache": Key("folder to keep the results in", "text"),
        })
section("damping", "bodies[i].damping", "Extra linear damping of the motions.", {
    "linear": Key("damping per DOF [N s/m, N m s/rad]", "dimensionless",
                  default=(0.0,) * 6, shape="[surge, ..., yaw]", range=">= 0"),
    "critical_fraction": Key("fraction of critical per DOF", "mapping",
                             section="critical_fraction"),
})
section("critical_fraction", "bodies[i].damping.critical_fraction",
        "Fraction of critical damping by degree of freedom.", {
            dof: Key(f"{dof} fraction of critical", "dimensionless", default=0.0,
                     range="0 to 2") for dof in DOFS6})

# ---- berths -----------------------------------------------------------------------------

_FRICTION = Key("Coulomb friction coefficient at a contact", "dimensionless", default=0.0,
                range="0 to 10")
_SLIP = Key("slip over which the friction builds up", "length", default=FRICTION_SLIP,
            range="> 0, <= 1 m")
section("wall", "walls[i]", "A plane quay wall.", {
    "name": Key("wall name, unique", "text", REQUIRED),
    "point": Key("a point of the wall's plane", "length", REQUIRED, shape="[x, y, z]"),
    "normal": Key("normal out of the face, toward the water (normalised)",
                  "dimensionless", REQUIRED, shape="[nx, ny, nz]", range="not zero"),
    "friction": _FRICTION,
    "friction_slip": _SLIP,
})
section("pile", "piles[i]", "A vertical pile.", {
    "name": Key("pile name, unique", "text", REQUIRED),
    "position": Key("axis position", "length", REQUIRED, shape="[x, y]"),
    "radius": Key("radius", "length", REQUIRED, range="> 0, <= 100 m"),
    "top": Key("top z (guides must stay below it)", "length"),
    "friction": _FRICTION,
    "friction_slip": _SLIP,
    "bending_stiffness": Key("EI of a pile that bends", "bending_stiffness", range="> 0"),
})
section("fender", "fenders[i]", "A fender between a body and a wall or pile.", {
    "name": Key("fender name, unique", "text", REQUIRED),
    "body": Key("body name", "choice", REQUIRED),
    "at": Key("the fender face, body frame", "length", REQUIRED, shape="[x, y, z]"),
    "reaction": Key("reaction law: rigid, {stiffness: N/m} or {table: [[deflection, "
                    "reaction], ...]}", "any", REQUIRED,
                    also=("force_per_length", "length", "force")),
    "wall": Key("wall it bears on (or pile)", "choice"),
    "pile": Key("pile it bears on (or wall)", "choice"),
    "mounted": Key("where it is fixed", "choice", default="body",
                   choices=("body", "structure")),
    "rated_deflection": Key("maker's rated deflection (table: its last row)", "length",
                            range="> 0; required for a linear law"),
    "height": Key("full compression of a body-mounted fender", "length",
                  range="> rated_deflection"),
})
section("guide", "guides[i]", "A pile guide: a ring on a body around a pile.", {
    "name": Key("guide name, unique", "text", REQUIRED),
    "body": Key("body name", "choice", REQUIRED),
    "at": Key("ring centre, body frame", "length", REQUIRED, shape="[x, y, z]"),
    "pile": Key("pile name", "choice", REQUIRED),
    "clearance": Key("radial gap between ring and pile", "length", REQUIRED,
                     range="0 to 10 m"),
    "pads": Key("contact pads around the ring", "integer", default=8, range="3 to 64"),
})

