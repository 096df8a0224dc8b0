"""``moorsolve motions``: the bodies' motions in the case's sea state."""

from __future__ import annotations

import json

from .common import (EXIT_OK, IMAGE_EXTENSIONS, check_output, print_text, save_figure,
                     solver_option, tolerance_option)


def add_commands(sub) -> None:
    p = sub.add_parser("motions", help="motions of the bodies in the sea state (frequency "
                                       "domain: wave frequency, slow drift, design offset)")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--json", action="store_true", help="print the motions as JSON")
    p.add_argument("--plot", metavar="FILE", help="draw spectra, A(w), B(w), |X(w)| and RAOs "
                                                  "(.png, .pdf or .svg)")
    solver_option(p)
    tolerance_option(p)
    p.set_defaults(run=run_motions)


def run_motions(args) -> int:
    from .. import load_case, solve
    from ..dynamics.motions import motions
    from ..report.motions import format_motions

    if args.plot:
        check_output(args.plot, "--plot", IMAGE_EXTENSIONS)
    case = load_case(args.case)
    result = solve(case, solver=args.solver, tol=args.tol)
    m = motions(result, solver=args.solver, tol=args.tol)
    if args.plot:
        from ..plot.motions import motions_figure
        if m.static:
            from ..errors import CaseError
            raise CaseError("--plot", f"nothing to draw: {m.sea['reason']}")
        save_figure(lambda: motions_figure(m), args.plot)
    print_text(json.dumps(m.to_dict(), indent=2) if args.json else format_motions(m))
    return EXIT_OK
