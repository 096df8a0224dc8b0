"""``solve``, ``plot``, ``stiffness`` and ``accuracy``: one case's equilibrium, its mooring
stiffness and what its accuracy costs."""

from __future__ import annotations

import json
import sys

from ..errors import ConvergenceError
from .common import (EXIT_NO_EQUILIBRIUM, EXIT_OK, IMAGE_EXTENSIONS, check_output,
                     overload_option, print_text, save_figure, solver_option, tolerance_option,
                     whole_number)


def add_commands(sub) -> None:
    p = sub.add_parser("solve", help="solve a case and print the equilibrium")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    tolerance_option(p)
    p.add_argument("--no-profiles", action="store_true",
                   help="leave the line profiles out of the JSON")
    solver_option(p)
    overload_option(p)
    p.set_defaults(run=run_solve)
    p = sub.add_parser("plot", help="plan, elevation and 3-D view of the equilibrium")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("-o", "--output", required=True, help="image file to write (.png, .pdf, .svg)")
    tolerance_option(p)
    solver_option(p)
    overload_option(p)
    p.set_defaults(run=run_plot)
    p = sub.add_parser("stiffness", help="the mooring's 6x6 restoring matrix of one body "
                                         "about its solved position")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--body", default=None, help="the body's name (default: the only body)")
    p.add_argument("--json", action="store_true", help="print the matrix as JSON")
    tolerance_option(p)
    solver_option(p)
    overload_option(p)
    p.set_defaults(run=run_stiffness)
    p = sub.add_parser("accuracy", help="solve time against error over tolerances and "
                                        "model fidelity")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--json", action="store_true", help="print the ladder as JSON")
    p.add_argument("--plot", metavar="FILE", default=None,
                   help="also write time against error as an image (.png, .pdf, .svg)")
    p.add_argument("--repeats", type=whole_number("--repeats", 1, 1000), default=7,
                   help="solves per setting; the median time is reported (default 7)")
    overload_option(p)
    p.set_defaults(run=run_accuracy)


def run_solve(args) -> int:
    from .. import load_case, solve
    from ..report.text import format_table, to_json
    from ..checks.modelling import modelling_warnings
    case = load_case(args.case)
    result = solve(case, tol=args.tol, solver=args.solver, allow_overload=args.allow_overload)
    print_text(to_json(result, profiles=not args.no_profiles) if args.json
               else format_table(result))
    for warning in modelling_warnings(case, result):
        print(f"moorsolve: warning: {warning}", file=sys.stderr)
    return EXIT_OK


def run_plot(args) -> int:
    from .. import load_case, solve
    from ..plot import plot_equilibrium
    case = load_case(args.case)
    check_output(args.output, "--output", IMAGE_EXTENSIONS)
    result = solve(case, tol=args.tol, solver=args.solver, allow_overload=args.allow_overload)
    save_figure(lambda: plot_equilibrium(result, depth=case.environment.depth), args.output)
    print_text(f"wrote {args.output}")
    return EXIT_OK


def run_stiffness(args) -> int:
    from .. import load_case, solve
    from ..errors import CaseError
    from ..model import DOFS
    from ..report.matrix import stiffness_table
    from ..report.text import format_stiffness
    from ..studies.one_sided import one_sided_stiffness
    from ..studies.stiffness import stiffness
    case = load_case(args.case)
    names = [b.name for b in case.bodies]
    if args.body is not None and args.body not in names:
        raise CaseError("--body", f"{args.body!r} is not a body of the case; its bodies: "
                                  f"{', '.join(names) or 'none'}")
    if args.body is None and len(names) > 1:
        raise CaseError("--body", f"the case has {len(names)} bodies "
                                  f"({', '.join(names)}); name one")
    result = solve(case, tol=args.tol, solver=args.solver, allow_overload=args.allow_overload)
    # Weightless lines exactly at their slack point: the two sides differ; both are given
    # (the matrix is the taut side's).
    pair = one_sided_stiffness(result, args.body)
    K = pair.taut if pair else stiffness(result, args.body)
    body = args.body or (names[0] if names else None)
    held = [n for n in names if n != body]
    if args.json:
        table = stiffness_table(K, DOFS)
        out = {"body": body, "held_bodies": held, "about": "solved poses", "dofs": list(DOFS),
               "matrix": K.tolist(), "rows": list(table.rows), "columns": list(table.columns)}
        if pair:
            out["one_sided"] = {"lines": list(pair.lines), "taut": pair.taut.tolist(),
                                "slack": pair.slack.tolist()}
        print_text(json.dumps(out, indent=2))
    else:
        text = format_stiffness(K, body, case.name, held)
        if pair:
            text += (f"\n{', '.join(pair.lines)} exactly at their slack point: the matrix "
                     "above is the taut side's (displacements that stretch them); the slack "
                     f"side's (displacements that slacken them):\n"
                     f"{stiffness_table(pair.slack, DOFS)!r}")
        print_text(text)
    return EXIT_OK


def run_accuracy(args) -> int:
    from .. import load_case
    from ..studies.accuracy import accuracy_ladder, format_ladder
    case = load_case(args.case)
    if args.plot:
        check_output(args.plot, "--plot", IMAGE_EXTENSIONS)
    try:
        rungs = accuracy_ladder(case, repeats=args.repeats,
                                allow_overload=args.allow_overload)
    except ConvergenceError as exc:
        print(f"moorsolve: the reference solve failed: {exc}", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    if args.plot:
        from ..plot import plot_accuracy
        save_figure(lambda: plot_accuracy(rungs)[0].figure, args.plot)
    print_text(json.dumps({"case": case.name, "rungs": [r.to_dict() for r in rungs]}, indent=2)
               if args.json else format_ladder(rungs, case.name))
    return EXIT_OK
