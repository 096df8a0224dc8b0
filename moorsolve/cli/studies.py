"""Design studies: ``sweep`` (a grid of case edits to CSV or parquet), ``envelope`` (offset and
worst tension for every heading) and ``optimise`` (least line over a set of load cases)."""

from __future__ import annotations

import json
import sys

from ..errors import CaseError, ConvergenceError
from .common import (EXIT_INTERRUPTED, EXIT_NO_EQUILIBRIUM, EXIT_OK, IMAGE_EXTENSIONS,
                     YAML_EXTENSIONS, bad_input, check_output, heading_step, overload_option,
                     print_text, save_figure, solver_option, tolerance_option, whole_number)


def add_commands(sub) -> None:
    from ..model.paths import SET_SYNTAX
    p = sub.add_parser("sweep", help="solve a grid of case edits or a table of load cases; "
                                     "results to CSV or parquet")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--set", action="append", dest="sets", metavar="PATH=VALUES",
                   help=f"one axis of the grid (repeat for more): {SET_SYNTAX}")
    p.add_argument("--table", metavar="FILE", default=None,
                   help="a load table (.csv or .parquet) instead of --set: one load case per "
                        "row, columns named by case paths with an optional unit in brackets "
                        "('environment.wind.speed [kn]')")
    p.add_argument("-o", "--output", required=True, help="results file (.csv or .parquet)")
    solver_option(p, default="newton")
    tolerance_option(p)
    p.add_argument("--workers", type=whole_number("--workers", 1, 1024), default=None,
                   help="local threads (default: the number of cores)")
    p.add_argument("--resume", action="store_true",
                   help="finish the points missing from an interrupted run's output")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output")
    p.add_argument("--scheduler", default=None, metavar="tcp://HOST:PORT",
                   help="run on an existing dask.distributed cluster")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    overload_option(p)
    p.set_defaults(run=run_sweep)
    p = sub.add_parser("envelope", help="offset and worst tension for every heading of the "
                                        "environment")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--step", type=heading_step, default=10.0,
                   help="heading step in degrees (default 10: 0, 10, ..., 350)")
    p.add_argument("--flows", default=None,
                   help="which flows turn, comma separated (default: every one the case "
                        "has of wind, current, waves)")
    p.add_argument("--plot", metavar="FILE", default=None,
                   help="write polar plots of offset and worst tension (.png, .pdf, .svg)")
    p.add_argument("--json", action="store_true", help="print the envelope as JSON")
    p.add_argument("--body", default=None,
                   help="the body whose offset is reported (a case with several bodies)")
    solver_option(p, default="newton")
    tolerance_option(p)
    overload_option(p)
    p.set_defaults(run=run_envelope)
    p = sub.add_parser("optimise", help="least line mass or cost over a set of load cases "
                                        "(design study file)")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--study", required=True, help="design study file (YAML)")
    p.add_argument("--json", action="store_true", help="print the optimisation as JSON")
    p.add_argument("-o", "--output", default=None,
                   help="write the optimised case file (.yaml) when the optimum is verified")
    p.add_argument("--all-constraints", action="store_true",
                   help="list every constraint, not only the tightest per load case")
    p.set_defaults(run=run_optimise)


def run_sweep(args) -> int:
    from .. import load_case, sweep
    from ..model.paths import parse_assignment
    from ..io.sweep_output import check_output_path
    if args.resume and args.overwrite:
        return bad_input("--resume and --overwrite exclude each other")
    if bool(args.sets) == bool(args.table):
        return bad_input("sweep: give --set PATH=VALUES (a grid) or --table FILE (load cases)")
    try:
        check_output_path(args.output, "--output")
        grid, loads = None, None
        if args.table:
            from ..io.table_file import read_table
            loads = read_table(args.table)
        else:
            grid = {}
            for text in args.sets:
                path, values = parse_assignment(text)
                if path in grid:
                    raise CaseError(f"--set {path}", "given twice; one --set per path")
                grid[path] = values
        case = load_case(args.case)
        progress = sys.stderr if (not args.quiet and sys.stderr.isatty()) else False
        table = sweep(case, grid, table=loads, solver=args.solver, tol=args.tol,
                      workers=args.workers, output=args.output, resume=args.resume,
                      overwrite=args.overwrite, scheduler=args.scheduler, progress=progress,
                      allow_overload=args.allow_overload)
    except CaseError as exc:
        return bad_input(_set_field(exc))
    except KeyboardInterrupt:
        print(f"moorsolve: interrupted; the finished points are in {args.output} and "
              f"--resume completes it", file=sys.stderr)
        return EXIT_INTERRUPTED
    print_text(f"wrote {args.output}: {len(table)} points")
    failed = int((~table["converged"].astype(bool)).sum())
    if failed:
        # The file is complete (failed points are rows with their reason), but a script
        # must not mistake the sweep for a clean one: status 1, as for one failed solve.
        print(f"moorsolve: {failed} of {len(table)} points have no certified equilibrium; "
              f"see the reason column", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    unstable = int((table["converged"].astype(bool) & ~table["stable"].astype(bool)).sum())
    if unstable:
        # Certified, but a small disturbance moves the body away: not a clean sweep either.
        print(f"moorsolve: {unstable} of {len(table)} points are unstable equilibria (no "
              f"stable one was found); see the stable and reason columns", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    return EXIT_OK


def _set_field(exc: CaseError) -> str:
    """A grid error told in the command line's words (``--set PATH``)."""
    text = str(exc)
    if exc.field.startswith("grid['") and exc.field.endswith("']"):
        return f"--set {exc.field[6:-2]}" + text[len(exc.field):]
    if exc.field.startswith("table"):
        return "--table " + text
    if exc.field in ("output", "resume", "scheduler"):
        return f"--{exc.field}" + text[len(exc.field):]
    return text


def run_envelope(args) -> int:

    from .. import load_case
    from ..studies.envelope import format_envelope, offset_envelope
    try:
        if args.plot:
            check_output(args.plot, "--plot", IMAGE_EXTENSIONS)
        case = load_case(args.case)
        flows = None if args.flows is None else [f.strip() for f in args.flows.split(",")]
        envelope = offset_envelope(case, step_deg=args.step, flows=flows, solver=args.solver,
                                   tol=args.tol, body=args.body,
                                   allow_overload=args.allow_overload)
    except CaseError as exc:
        text = str(exc)
        if exc.field in ("flows", "step_deg", "body"):
            text = "--" + exc.field.split("_")[0] + text[len(exc.field):]
        return bad_input(text)
    if args.plot:
        from ..plot import plot_envelope
        save_figure(lambda: plot_envelope(envelope)[0].figure, args.plot)
    print_text(json.dumps(envelope.to_dict(), indent=2) if args.json
           else format_envelope(envelope))
    if args.plot and not args.json:
        print_text(f"wrote {args.plot}")
    import numpy as np

    missing = ~np.isfinite(envelope.worst_tension_N)
    if missing.any():
        print(f"moorsolve: no equilibrium at {int(missing.sum())} of "
              f"{len(missing)} headings", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    table = envelope.table
    unstable = int((table["converged"].astype(bool) & ~table["stable"].astype(bool)).sum())
    if unstable:
        print(f"moorsolve: only an unstable equilibrium at {unstable} of {len(missing)} "
              "headings", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    return EXIT_OK


def run_optimise(args) -> int:
    from .. import load_case
    from ..report.optimise import format_optimisation, optimisation_json
    from ..io.output_files import write_edited_case_yaml
    from ..io.study_file import load_study
    from ..studies.optimise import optimise
    case = load_case(args.case)
    if args.output is not None:
        check_output(args.output, "--output", YAML_EXTENSIONS)
    study = load_study(args.study, case)
    try:
        opt = optimise(case, study)
    except ConvergenceError as exc:
        print(f"moorsolve: {exc.reason} ({exc.iterations} iterations, IPOPT status "
              f"{exc.status or 'n/a'})", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    print_text(optimisation_json(opt) if args.json
           else format_optimisation(opt, every_constraint=args.all_constraints))
    if not opt.verified:
        print("moorsolve: the optimum did not pass the independent re-solve of every load "
              "case; no case file written", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    if args.output is not None:
        data = dict(opt.optimised_data)
        data["name"] = f"{case.name} (optimised)"
        # The case file itself, edited: its comments and layout stay.
        write_edited_case_yaml(args.case, case.source, data, args.output, header=(
            f"{case.name}: optimised by moorsolve optimise --study {args.study}\n"
            f"{opt.objective} {opt.objective_start:,.0f} -> {opt.objective_optimum:,.0f} "
            f"{opt.unit}"))
        if not args.json:
            print_text(f"wrote {args.output}")
    return EXIT_OK

