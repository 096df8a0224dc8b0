"""``import-moordyn`` / ``export-moordyn`` and ``import-moorpy`` / ``export-moorpy``: MoorDyn
input files and MoorPy's mooring YAML in and out."""

from __future__ import annotations

import sys

from .common import (EXIT_OK, YAML_EXTENSIONS, check_output, overload_option, print_text,
                     solver_option, tolerance_option)


def add_commands(sub) -> None:
    p = sub.add_parser("import-moordyn", help="MoorDyn input file (v1 or v2) to a case file")
    p.add_argument("moordyn", help="MoorDyn input file")
    p.add_argument("-o", "--output", required=True, help="case file to write (YAML)")
    _no_solve(p)
    p.set_defaults(run=run_import)
    p = sub.add_parser("export-moordyn", help="case file to a MoorDyn input file")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("-o", "--output", required=True, help="MoorDyn input file to write")
    p.add_argument("--version", type=int, choices=(1, 2), default=None,
                   help="MoorDyn format (default: the version the case came from, else 2)")
    p.add_argument("--equilibrium", action="store_true",
                   help="solve first and write the equilibrium positions of the fairleads "
                        "and free points")
    tolerance_option(p)
    solver_option(p)
    overload_option(p)
    p.set_defaults(run=run_export)
    p = sub.add_parser("import-moorpy", help="MoorPy (or windIO) mooring YAML to a case file")
    p.add_argument("moorpy", help="MoorPy mooring YAML (water_depth, line_types, points, lines)")
    p.add_argument("-o", "--output", required=True, help="case file to write (YAML)")
    _no_solve(p)
    p.set_defaults(run=run_import_moorpy)
    p = sub.add_parser("export-moorpy", help="case file to MoorPy's mooring YAML")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("-o", "--output", required=True, help="MoorPy YAML to write")
    p.set_defaults(run=run_export_moorpy)


def _no_solve(p) -> None:
    p.add_argument("--no-solve", action="store_true",
                   help="do not solve the imported case at rest to check it for modelling "
                        "slips (anchors off the seabed, lines through it, all lines slack)")


def _import(read, source: str, args) -> int:
    check_output(args.output, "--output", YAML_EXTENSIONS)
    imported = read(source)
    imported.write(args.output)
    print(imported.report.text(), end="")
    print_text(f"wrote {args.output} ({imported.form} form; the report above heads it as a "
               "comment)")
    if not args.no_solve:
        _check_at_rest(imported.data)
    return EXIT_OK


def _check_at_rest(data) -> None:
    """Solve the imported case at rest and print what looks like a modelling slip."""
    from .. import load_case, solve
    from ..checks.modelling import modelling_warnings
    from ..errors import CaseError, ConvergenceError
    try:
        case = load_case(data)
        result = solve(case)
    except CaseError:
        return                  # a form this moorsolve cannot load yet; the report says so
    except ConvergenceError as exc:
        print(f"moorsolve: warning: the imported case has no equilibrium at rest: {exc}",
              file=sys.stderr)
        return
    largest = max(result.legs, key=lambda leg: leg.fairlead_tension_N)
    print(f"solved at rest: largest tension {largest.fairlead_tension_N:.6g} N "
          f"({largest.name})")
    for warning in modelling_warnings(case, result):
        print(f"moorsolve: warning: {warning}", file=sys.stderr)


def run_import(args) -> int:
    from ..io import read_import
    return _import(read_import, args.moordyn, args)


def run_export(args) -> int:
    from ..studies.moordyn_export import export_moordyn
    export_moordyn(args.case, args.output, version=args.version, equilibrium=args.equilibrium,
                   tol=args.tol, solver=args.solver, allow_overload=args.allow_overload)
    print_text(f"wrote {args.output}")
    return EXIT_OK


def run_import_moorpy(args) -> int:
    from ..io import read_moorpy
    return _import(read_moorpy, args.moorpy, args)


def run_export_moorpy(args) -> int:
    from ..io import export_moorpy
    check_output(args.output, "--output", YAML_EXTENSIONS)
    export_moorpy(args.case, args.output)
    print_text(f"wrote {args.output}")
    return EXIT_OK
