"""``import-moordyn`` and ``export-moordyn``: MoorDyn input files in and out."""

from __future__ import annotations

from .common import (EXIT_OK, YAML_EXTENSIONS, check_output, overload_option, solver_option,
                     tolerance)


def add_commands(sub) -> None:
    p = sub.add_parser("import-moordyn", help="MoorDyn input file (v1 or v2) to a case file")
    p.add_argument("moordyn", help="MoorDyn input file")
    p.add_argument("-o", "--output", required=True, help="case file to write (YAML)")
    p.set_defaults(run=run_import)
    p = sub.add_parser("export-moordyn", help="case file to a MoorDyn input file")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("-o", "--output", required=True, help="MoorDyn input file to write")
    p.add_argument("--version", type=int, choices=(1, 2), default=None,
                   help="MoorDyn format (default: the version the case came from, else 2)")
    p.add_argument("--equilibrium", action="store_true",
                   help="solve first and write the equilibrium positions of the fairleads "
                        "and free points")
    p.add_argument("--tol", type=tolerance, default=None)
    solver_option(p)
    overload_option(p)
    p.set_defaults(run=run_export)


def run_import(args) -> int:
    from ..io import import_moordyn
    check_output(args.output, "--output", YAML_EXTENSIONS)
    import_moordyn(args.moordyn, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK


def run_export(args) -> int:
    from ..io import export_moordyn
    export_moordyn(args.case, args.output, version=args.version, equilibrium=args.equilibrium,
                   tol=args.tol, solver=args.solver, allow_overload=args.allow_overload)
    print(f"wrote {args.output}")
    return EXIT_OK
