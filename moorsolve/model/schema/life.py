"""Case-file sections of a mooring's life: corrosion and creep, the anchors' designs and
fatigue (the ``checks`` keys ``corrosion``, ``creep``, ``anchors`` and ``fatigue``)."""

from __future__ import annotations

from ._base import REQUIRED, Key, section

# ---- corrosion and creep ----------------------------------------------------------------

_ZONED = ("rate per year ('0.4 mm/y'), or a mapping of rates by zone", "length")
section("corrosion", "checks.corrosion", "Diameter loss of steel lines (chain, wire).", {
    "rate": Key(_ZONED[0] + " (every steel line type)", _ZONED[1], section="corrosion_zones",
                range=">= 0"),
    "splash_depth": Key("depth below still water down to which a line is in the splash "
                        "zone (needed with rates by zone)", "length", range="0 to 100 m"),
    "line_types": Key("one line type's own rate: {NAME: {rate}}", "mapping",
                      section="corrosion_line_type"),
    "segments": Key("one segment's own rate", "list", section="corrosion_segment"),
})
section("corrosion_zones", "checks.corrosion.rate (by zone)",
        "Corrosion rates by zone, from the surface down.", {
            "splash": Key("rate near the surface", "length", REQUIRED, range=">= 0"),
            "catenary": Key("rate where the line hangs free", "length", REQUIRED,
                            range=">= 0"),
            "bottom": Key("rate where the line lies on the seabed", "length", REQUIRED,
                          range=">= 0"),
        })
section("corrosion_line_type", "checks.corrosion.line_types.NAME",
        "A line type's own corrosion rate.", {
            "rate": Key(*_ZONED, REQUIRED, section="corrosion_zones", range=">= 0"),
        })
section("corrosion_segment", "checks.corrosion.segments[i]",
        "One segment's own corrosion rate.", {
            "line": Key("the line's name", "text", REQUIRED),
            "segment": Key("segment index from end A", "integer", REQUIRED),
            "rate": Key(*_ZONED, REQUIRED, section="corrosion_zones", range=">= 0"),
        })
section("creep", "checks.creep", "Permanent elongation of fibre ropes.", {
    "rate": Key("strain per year ('0.1 %/y', or a plain fraction) of every fibre rope",
                "dimensionless", range=">= 0"),
    "line_types": Key("one line type's own rate: {NAME: {rate}}", "mapping",
                      section="creep_line_type"),
})
section("creep_line_type", "checks.creep.line_types.NAME", "A fibre rope's own creep rate.", {
    "rate": Key("strain per year", "dimensionless", REQUIRED, range=">= 0"),
})

# ---- anchors ----------------------------------------------------------------------------

_EMBEDMENT = Key("the line's path through the soil to an embedded padeye", "mapping",
                 section="embedment")
_MASS = Key("anchor mass (for the cost)", "mass", range="> 0")
section("anchor_designs", "checks.anchors", "The design of each kind of anchor.", {
    "drag": Key("drag anchor", "mapping", section="anchor_design_drag"),
    "suction": Key("suction anchor", "mapping", section="anchor_design_suction"),
    "pile": Key("driven pile", "mapping", section="anchor_design_pile"),
    "deadweight": Key("deadweight anchor", "mapping", section="anchor_design_deadweight"),
})
section("anchor_design_drag", "checks.anchors.drag",
        "A drag anchor: its capacity, or its fluke weight and soil on the maker's curve.", {
            "capacity": Key("ultimate holding capacity", "force", range="> 0"),
            "fluke_weight": Key("fluke weight (with soil)", "mass", range="> 0"),
            "soil": Key("soil of the maker's curve", "choice",
                        choices=("soft_clay", "medium_clay", "hard_clay", "sand")),
            "design": Key("the maker's anchor design", "text"),
            "mass": _MASS,
            "embedment": _EMBEDMENT,
        })
section("anchor_design_suction", "checks.anchors.suction",
        "A suction anchor: its H-V capacity envelope.", {
            "h_max": Key("horizontal capacity", "force", REQUIRED, range="> 0"),
            "v_max": Key("vertical capacity", "force", REQUIRED, range="> 0"),
            "length": Key("skirt length", "length", REQUIRED, range="> 0"),
            "diameter": Key("diameter", "length", REQUIRED, range="> 0"),
            "mass": _MASS,
            "embedment": _EMBEDMENT,
        })
section("anchor_design_pile", "checks.anchors.pile",
        "A driven pile: horizontal and vertical capacity.", {
            "h_max": Key("horizontal capacity", "force", REQUIRED, range="> 0"),
            "v_max": Key("vertical capacity", "force", REQUIRED, range="> 0"),
            "mass": _MASS,
            "embedment": _EMBEDMENT,
        })
section("anchor_design_deadweight", "checks.anchors.deadweight",
        "A deadweight anchor (its uplift limit is the anchor type's).", {
            "mass": Key("anchor mass", "mass", REQUIRED, range="> 0"),
        })
section("embedment", "checks.anchors.KIND.embedment",
        "Clay along an embedded line (Neubecker & Randolph 1995).", {
            "padeye_depth": Key("padeye depth below the mudline", "length", REQUIRED,
                                range="> 0"),
            "su0": Key("undrained shear strength at the mudline", "pressure", REQUIRED,
                       range=">= 0"),
            "su_gradient": Key("its increase with depth", "pressure_per_length", REQUIRED,
                               range=">= 0"),
            "line_diameter": Key("the embedded line's diameter (default: its line type's)",
                                 "length", range="> 0, <= 1 m"),
            "bearing_factor": Key("bearing capacity factor N_c", "dimensionless",
                                  default=8.5, range="> 0"),
            "bearing_width": Key("effective width over diameter A_b", "dimensionless",
                                 default=2.5, range="> 0"),
            "friction": Key("friction coefficient along the line", "dimensionless",
                            default=0.4, range="0 to 2"),
        })

# ---- fatigue ----------------------------------------------------------------------------

section("fatigue", "checks.fatigue", "Fatigue damage of the line ends over their life.", {
    "design_life": Key("years in service (default: checks.design_life)", "time",
                       range="> 0, <= 200 y"),
    "sea_states": Key("the scatter diagram", "mapping", REQUIRED,
                      section="fatigue_sea_states"),
    "spectrum": Key("the sea states' spectrum (default JONSWAP, gamma by DNV's rule)",
                    "mapping", section="spectrum"),
    "curve": Key("T-N or S-N curve of every line: {catalog: NAME} or {m, a_d, basis}",
                 "mapping", section="fatigue_curve_catalog|fatigue_curve"),
    "curves": Key("a line type's own curve: {LINE_TYPE: curve}", "mapping"),
    "design_fatigue_factor": Key("design fatigue factor", "dimensionless", default=5.0,
                                 range=">= 1"),
    "method": Key("damage from the tension spectrum", "choice", default="narrow_band",
                  choices=("narrow_band", "dirlik")),
})
section("fatigue_sea_states", "checks.fatigue.sea_states", "A scatter diagram.", {
    "table": Key("sea states [hs, tp, toward_deg, probability], probabilities summing to 1",
                 "length", REQUIRED, shape="[[hs, tp, toward_deg, probability], ...]",
                 also=("time", "angle", "dimensionless")),
})
section("fatigue_curve_catalog", "checks.fatigue.curve (catalogue)",
        "A curve of the catalogue.", {
            "catalog": Key("curve name (dnv_studless, dnv_studlink, ...)", "text", REQUIRED),
        })
section("fatigue_curve", "checks.fatigue.curve (user)", "A user curve N = a_d S^-m.", {
    "m": Key("inverse slope", "dimensionless", REQUIRED, range="> 0, <= 20"),
    "a_d": Key("intercept", "dimensionless", REQUIRED, range="> 0"),
    "basis": Key("what S is", "choice", default="stress_chain",
                 choices=("stress_chain", "stress_wire", "mbl_ratio")),
})
