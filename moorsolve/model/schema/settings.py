"""Case-file sections: solver settings and the mooring checks' settings."""

from __future__ import annotations

from ._base import Key, section
from .case import ANCHORS

# ---- solver and checks ------------------------------------------------------------------

section("solver", "solver", "Solver settings; the CLI's --tol overrides tol.", {
    "tol": Key("certified force residual relative to the largest line tension",
               "dimensionless", default=1e-9, range="(0, 1)"),
    "max_iter": Key("most solver iterations", "integer", default=200,
                    range=f"1 to {2**31 - 1}"),
    "max_time_s": Key("most wall time of one solve", "time", default=5.0, range="> 0"),
    "line_elements": Key("elements of a discretised line (in a current with drag)",
                         "integer", default=20, range="2 to 400"),
})
section("checks", "checks", "Settings of moorsolve check.", {
    "standard": Key("design standard", "choice", default="api-rp-2sk",
                    choices=("api-rp-2sk", "dnv-os-e301")),
    "consequence_class": Key("DNV-OS-E301 consequence class", "integer", default=1,
                             choices=(1, 2)),
    "offset_limit": Key("largest offset, intact", "length", range="> 0"),
    "offset_limit_damaged": Key("largest offset, one line broken", "length", range="> 0"),
    "min_grounded_length": Key("least line length on the seabed, intact", "length",
                               range=">= 0, < the longest leg"),
    "min_grounded_length_damaged": Key("least grounded length, one line broken", "length",
                                       range=">= 0, < the longest leg"),
    "anchor": Key("anchor kind of every leg without its own anchor_type", "mapping",
                  section=ANCHORS),
    "damaged": Key("also check each one-line-broken condition", "bool", default=True),
    "method": Key("how the line tension's dynamic part is had in a sea state (default: "
                  "analysis.lines)", "choice", choices=("quasi_static", "dynamic")),
    "design_life": Key("years in service, for wear and fatigue ('20 y'; a plain number is "
                       "years)", "time", range="> 0, <= 200 y"),
    "corrosion": Key("diameter loss of steel lines over the design life", "mapping",
                     section="corrosion"),
    "creep": Key("permanent elongation of fibre ropes over the design life", "mapping",
                 section="creep"),
    "anchors": Key("the anchors' designs, for their capacity checks and cost", "mapping",
                   section="anchor_designs"),
    "fatigue": Key("fatigue damage of the line ends over a scatter diagram", "mapping",
                   section="fatigue"),
})
section("analysis", "analysis", "What the scene simulates beyond the statics.", {
    "lines": Key("the lines in a sea state: their own dynamics (default where a sea state and "
                 "a body with hydrodynamics exist) or following the bodies statically",
                 "choice", choices=("dynamic", "quasi_static")),
})
