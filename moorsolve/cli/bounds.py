"""``moorsolve bounds``: the upper- and lower-bound stiffness analysis of fibre ropes."""

from __future__ import annotations

import json

from .common import EXIT_OK, print_text, solver_option, tolerance_option


def add_commands(sub) -> None:
    p = sub.add_parser("bounds", help="solve with the lower and the upper bound of the fibre "
                                      "ropes' stiffness; report the worst offset and tension")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--json", action="store_true", help="print both bounds as JSON")
    solver_option(p)
    tolerance_option(p)
    p.set_defaults(run=run_bounds)


def run_bounds(args) -> int:
    from .. import load_case
    from ..report.bounds import format_bounds
    from ..studies.bounds import stiffness_bounds
    bounds = stiffness_bounds(load_case(args.case), tol=args.tol, solver=args.solver)
    print_text(json.dumps(bounds.to_dict(), indent=2) if args.json else format_bounds(bounds))
    return EXIT_OK
