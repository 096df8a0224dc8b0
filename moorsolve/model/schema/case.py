"""Case-file sections: the two top-level forms, the environment, line types, legs."""

from __future__ import annotations

from ._base import REQUIRED, Key, section


ANCHORS = "anchor_drag|anchor_deadweight|anchor_pile|anchor_suction"
DOFS6 = ("surge", "sway", "heave", "roll", "pitch", "yaw")
DOFS3 = ("surge", "sway", "yaw")
_DIRECTION = {
    "toward_deg": Key("direction it travels toward (the case's directions convention)",
                      "angle", range="give toward_deg or from_deg, not both"),
    "from_deg": Key("direction it comes from", "angle",
                    range="give toward_deg or from_deg, not both"),
}
_CENTRE = Key("point of action, body frame", "length", default=(0.0, 0.0),
              shape="[x, y] or [x, y, z]")

# ---- the case ---------------------------------------------------------------------------

_COMMON = {
    "name": Key("name of the case", "text", default="the file stem"),
    "environment": Key("water, seabed and metocean conditions", "mapping", REQUIRED,
                       section="environment"),
    "solver": Key("solver settings", "mapping", section="solver"),
    "analysis": Key("what is simulated beyond the statics", "mapping", section="analysis"),
    "checks": Key("mooring-check settings (moorsolve check)", "mapping", section="checks"),
    "moordyn": Key("MoorDyn columns moorsolve does not use, kept for export; the solver "
                   "ignores them", "any"),
}
section("case", "(top level, body + legs form)",
        "One body on anchor-to-fairlead legs.", {
            **_COMMON,
            "line_types": Key("line types by name", "mapping", REQUIRED,
                              section="line_type|catalogue_line_type"),
            "body": Key("the moored body; absent: the fairleads are fixed in space",
                        "mapping", section="body"),
            "legs": Key("the legs, each from its anchor up to its fairlead", "list", REQUIRED,
                        section="leg", range="at least one"),
        })
section("network", "(top level, network form)",
        "Bodies, points and lines between them, with berth contacts.", {
            **_COMMON,
            "line_types": Key("line types by name (required with lines)", "mapping",
                              section="line_type|catalogue_line_type"),
            "bodies": Key("the bodies", "list", section="network_body"),
            "points": Key("named points, fixed or free", "list", section="point"),
            "lines": Key("lines between points, bodies and positions", "list",
                         section="line"),
            "walls": Key("quay walls fenders bear on", "list", section="wall"),
            "piles": Key("piles fenders or guides bear on", "list", section="pile"),
            "fenders": Key("fenders between a body and a wall or pile", "list",
                           section="fender"),
            "guides": Key("pile guides holding a body to a pile", "list", section="guide"),
        })

# ---- environment ------------------------------------------------------------------------

section("environment", "environment", "The water, seabed and metocean conditions.", {
    "depth": Key("water depth at the datum", "length", REQUIRED, range="> 0, <= 12 km"),
    "water_density": Key("sea water density", "density", default=1025.0,
                         range="> 0, <= 1e5 kg/m^3"),
    "air_density": Key("air density (wind loads)", "density", default=1.225,
                       range="> 0, <= 1e5 kg/m^3"),
    "gravity": Key("acceleration of gravity", "acceleration", default=9.80665,
                   range="0.1 to 100 m/s^2"),
    "seabed": Key("seabed friction and shape", "mapping", section="seabed"),
    "directions": Key("convention of every direction in the case", "choice",
                      default="mathematical", choices=("mathematical", "nautical"),
                      range="mathematical: counter-clockwise from +x; nautical: clockwise "
                            "from north"),
    "north_deg": Key("direction of north, counter-clockwise from +x (nautical only)",
                     "angle", default=90.0),
    "wind": Key("steady wind", "mapping", section="wind"),
    "current": Key("steady current, uniform or by depth", "mapping", section="current"),
    "waves": Key("waves: mean drift, and with tp a sea state", "mapping", section="waves"),
    "water_level": Key("still water above the datum (tide)", "length", default=0.0,
                       range="-100 to 100 m, above -depth"),
})
section("seabed", "environment.seabed", "Seabed friction and shape: flat, a plane or a grid.", {
    "friction": Key("Coulomb friction coefficient of grounded line", "dimensionless",
                    default=0.0, range=">= 0"),
    "gradient": Key("plane seabed slope: z = -depth + gx x + gy y", "dimensionless",
                    default=(0.0, 0.0), shape="[dz/dx, dz/dy]", range="slope <= 1 (45 deg)"),
    "bathymetry": Key("a depth grid instead of the plane (file name, or x, y, depth)",
                      "file", section="bathymetry"),
    "tolerance": Key("how far below a grid's surface a line may pass", "length", default=0.1,
                     range="> 0; with a bathymetry grid only"),
})
section("bathymetry", "environment.seabed.bathymetry", "A seabed depth grid.", {
    "x": Key("grid x coordinates, increasing", "length", REQUIRED, shape="[x0, x1, ...]"),
    "y": Key("grid y coordinates, increasing", "length", REQUIRED, shape="[y0, y1, ...]"),
    "depth": Key("depth at each grid node, one row per y", "length", REQUIRED,
                 shape="[[d(x0, y0), d(x1, y0), ...], ...]", range="> 0"),
    "source": Key("where the grid came from (a file name, kept for reports)", "text"),
})
section("wind", "environment.wind", "A steady wind.", {
    "speed": Key("wind speed", "speed", REQUIRED, range="0 to 200 m/s"),
    **_DIRECTION,
})
section("current", "environment.current", "A steady current, uniform or by depth.", {
    "speed": Key("surface speed (the profile's scale when one is given)", "speed", REQUIRED,
                 range="0 to 200 m/s"),
    **_DIRECTION,
    "profile": Key("speed by depth, rows from the seabed up", "length",
                   shape="[[z <= 0, speed], ...] or [[z, speed, toward_deg], ...]",
                   range="z ascending", also=("speed", "angle")),
})
section("waves", "environment.waves", "Waves: mean drift, and with tp a sea state.", {
    "hs": Key("significant wave height", "length", REQUIRED, range="0 to 100 m"),
    **_DIRECTION,
    "tp": Key("peak period; makes the waves a sea state", "time", range="> 0, <= 100 s"),
    "spectrum": Key("wave spectrum (default JONSWAP with DNV gamma when tp is given)",
                    "mapping", section="spectrum|spectrum_table"),
    "duration": Key("storm duration for most probable maxima", "time", default=10800.0,
                    range="> 2 tp, <= 30 days"),
})
section("spectrum", "environment.waves.spectrum", "A parametric wave spectrum.", {
    "model": Key("spectrum model", "choice", REQUIRED,
                 choices=("jonswap", "pierson_moskowitz")),
    "gamma": Key("JONSWAP peak enhancement factor (default from hs and tp, DNV-RP-C205)",
                 "dimensionless", range="1 to 20; jonswap only"),
})
section("spectrum_table", "environment.waves.spectrum", "A tabulated wave spectrum.", {
    "table": Key("spectral density by frequency", "dimensionless", REQUIRED,
                 shape="[[omega rad/s, S m^2 s/rad], ...]",
                 range=">= 3 rows; 4 sqrt(m0) within 5 % of hs"),
})

# ---- line types -------------------------------------------------------------------------

_LINE_TYPE_COMMON = {
    "mbl": Key("minimum breaking load", "force", range="> 0"),
    "sealed": Key("sealed tube: wall tension from the outer area", "bool", default=False,
                  range="needs a diameter"),
    "drag": Key("drag coefficients (in a current)", "mapping", section="line_drag",
                range="needs a diameter"),
    "weight_in_air": Key("weight of the part above the water", "weight",
                         range=">= weight_in_water, > 0"),
    "stretch": Key("stretch law instead of ea", "mapping",
                   section="stretch_hooke|stretch_baranov|stretch_table"),
    "fibre": Key("fibre rope (checked with the fibre-rope rules)", "bool",
                 default="true for a baranov law or a fibre catalogue entry"),
    "min_tension": Key("least tension allowed (fibre ropes: no compression)", "force",
                       range=">= 0"),
    "stiffness_bounds": Key("lower and upper stiffness for the stiffness envelope",
                            "mapping", section="stiffness_bounds"),
}
section("line_type", "line_types.NAME", "A line type given by its properties.", {
    "weight_in_water": Key("submerged weight per length (< 0: buoyant)", "weight", REQUIRED,
                           range="|w| <= 1e6 N/m; 0 or |w| >= 1e-6 N/m"),
    "ea": Key("axial stiffness; absent: inextensible", "force", range="1 N to 1e15 N"),
    "diameter": Key("nominal diameter (drag, sealed lines, reports)", "length", range="> 0"),
    **_LINE_TYPE_COMMON,
})
section("catalogue_line_type", "line_types.NAME (catalog)",
        "A line type from the catalogue, by grade and diameter.", {
            "catalog": Key("catalogue entry", "choice", REQUIRED,
                           range="an entry of moorsolve.catalog.entries()"),
            "diameter": Key("nominal diameter", "length", REQUIRED, range="> 0, <= 1 m"),
            "corrosion_allowance": Key("diameter lost to corrosion (catalogue MBL only)",
                                       "length", default=0.0, range=">= 0, < diameter"),
            "weight_in_water": Key("replaces the catalogue's submerged weight", "weight"),
            "ea": Key("replaces the catalogue's axial stiffness", "force", range="> 0"),
            **_LINE_TYPE_COMMON,
        })
section("line_drag", "line_types.NAME.drag", "Drag coefficients of a line.", {
    "normal": Key("normal drag coefficient Cn", "dimensionless", REQUIRED, range="0 to 10"),
    "tangential": Key("tangential drag coefficient Ct", "dimensionless", default=0.0,
                      range="0 to 10"),
    "side": Key("side (lift) coefficient", "dimensionless", default=0.0, range="-10 to 10"),
})
_LAW = "line_types.NAME.stretch, stiffness_bounds.lower/upper"
section("stretch_hooke", _LAW + " (model: hooke)", "A linear law, the same as ea.", {
    "model": Key("the law", "choice", REQUIRED, choices=("hooke",)),
    "ea": Key("axial stiffness", "force", REQUIRED, range="1 N to 1e15 N"),
})
section("stretch_baranov", _LAW + " (model: baranov)",
        "A fibre rope's strain n sqrt(T) (Baranov).", {
            "model": Key("the law", "choice", REQUIRED, choices=("baranov",)),
            "n": Key("Baranov coefficient [N^-1/2]", "dimensionless", REQUIRED,
                     range="> 0, < 1"),
        })
section("stretch_table", _LAW + " (model: table)", "A measured tension-strain curve.", {
    "model": Key("the law", "choice", REQUIRED, choices=("table",)),
    "strain": Key("strains of the rows", "dimensionless", REQUIRED,
                  shape="[0, e1, e2, ...]", range="from 0, increasing"),
    "tension": Key("tensions of the rows", "force", REQUIRED, shape="[0, T1, T2, ...]",
                   range="from 0, increasing"),
    "interpolation": Key("how the law runs between rows", "choice",
                         default="monotone_cubic", choices=("monotone_cubic", "linear")),
})
section("stiffness_dynamic", "stiffness_bounds.lower/upper (model: dynamic)",
        "A storm-dynamic stiffness EA = alpha MBL + beta T (mean tension T).", {
            "model": Key("the law", "choice", REQUIRED, choices=("dynamic",)),
            "alpha": Key("share of the MBL", "dimensionless", REQUIRED, range="> 0"),
            "beta": Key("share of the mean tension", "dimensionless", REQUIRED, range=">= 0"),
        })
_BOUND = "stretch_hooke|stretch_baranov|stretch_table|stiffness_dynamic"
section("stiffness_bounds", "line_types.NAME.stiffness_bounds",
        "Lower and upper stiffness: an ea [N], a stretch law, or {model: dynamic, alpha, "
        "beta} (EA = alpha MBL + beta T).", {
            "lower": Key("the lower (quasi-static) stiffness: an ea or a law", "force",
                         REQUIRED, section=_BOUND),
            "upper": Key("the upper (storm-dynamic) stiffness: an ea or a law", "force",
                         REQUIRED, section=_BOUND),
        })

# ---- legs, segments, clumps, anchors ----------------------------------------------------

section("leg", "legs[i]", "One leg, from its anchor up to its fairlead.", {
    "name": Key("leg name, unique", "text", REQUIRED),
    "anchor": Key("anchor position ([x, y]: on the seabed)", "length", REQUIRED,
                  shape="[x, y] or [x, y, z]", range="on or above the seabed, z <= 0"),
    "fairlead": Key("fairlead position, body frame at zero offset", "length", REQUIRED,
                    shape="[x, y, z]", range="on or above the seabed, z <= 1000 m"),
    "segments": Key("segments from the anchor up, {clump: ...} items between them", "list",
                    REQUIRED, section="segment|clump_item"),
    "anchor_type": Key("anchor kind for the anchor check", "mapping", section=ANCHORS),
})
section("segment", "legs[i].segments[j]", "One segment of a line.", {
    "type": Key("line type name", "choice", REQUIRED, range="a key of line_types"),
    "length": Key("unstretched length", "length", REQUIRED, range="1 mm to 100 km"),
})
section("pretension_segment", "lines[i].segments[0]",
        "A one-segment weightless elastic line (a hawser) given by its pretension.", {
            "type": Key("line type name (weightless, elastic)", "choice", REQUIRED),
            "pretension": Key("tension at the case-file pose; sets the length", "force",
                              REQUIRED, range=">= 0, < ea"),
        })
section("clump_item", "legs[i].segments[j]", "A clump weight or buoy between two segments.", {
    "clump": Key("the clump", "mapping", REQUIRED, section="clump"),
})
section("clump", "legs[i].segments[j].clump",
        "{mass, volume} (net weight in water) or {weight} (< 0: a buoy).", {
            "mass": Key("mass", "mass", range=">= 0"),
            "volume": Key("displaced volume", "volume", default=0.0, range=">= 0"),
            "weight": Key("net weight in water (< 0: buoyant); instead of mass and volume",
                          "force"),
        })
_ANCHOR = "checks.anchor, legs[i].anchor_type"
_ANCHOR_TYPE = Key("anchor kind", "choice", REQUIRED,
                   choices=("drag", "deadweight", "pile", "suction"))
section("anchor_drag", _ANCHOR + " (type: drag)", "A drag anchor: no uplift allowed.", {
    "type": _ANCHOR_TYPE,
})
section("anchor_deadweight", _ANCHOR + " (type: deadweight)",
        "A deadweight anchor: uplift up to a limit.", {
            "type": _ANCHOR_TYPE,
            "allowed_uplift": Key("vertical load it holds", "force", REQUIRED, range=">= 0"),
        })
section("anchor_pile", _ANCHOR + " (type: pile)", "A pile anchor: a line angle up to a limit.", {
    "type": _ANCHOR_TYPE,
    "allowed_uplift_angle_deg": Key("largest line angle above the horizontal at the anchor",
                                    "angle", REQUIRED, range="0 to < 90 deg"),
})
section("anchor_suction", _ANCHOR + " (type: suction)",
        "A suction anchor: its H-V envelope (checks.anchors.suction) takes the uplift.", {
            "type": _ANCHOR_TYPE,
        })

