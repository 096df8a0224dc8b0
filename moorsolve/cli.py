"""The ``moorsolve`` command.

Exit status: 0 solved, 1 no equilibrium (reason and best residual on stderr), 2 bad input
(one message naming the field; no traceback), per CONTRACT.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings

from .errors import CaseError, ConvergenceError

EXIT_OK, EXIT_NO_EQUILIBRIUM, EXIT_BAD_INPUT = 0, 1, 2


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        # argparse's own errors are bad input too: one line, status 2.
        self.exit(EXIT_BAD_INPUT, f"moorsolve: error: {message}\n")


def _tolerance(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--tol: {text!r} is not a number") from None
    if not 0 < value < 1:
        raise argparse.ArgumentTypeError(f"--tol: {text} must be > 0 and < 1")
    return value


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="moorsolve", description="Static equilibrium of moored bodies.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    p = sub.add_parser("solve", help="solve a case and print the equilibrium")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--tol", type=_tolerance, default=None,
                   help="force residual relative to the largest tension (default 1e-9)")
    p.add_argument("--no-profiles", action="store_true",
                   help="leave the line profiles out of the JSON")
    _solver_option(p)
    p = sub.add_parser("plot", help="plan and elevation views of the equilibrium")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("-o", "--output", required=True, help="image file to write (.png, .pdf, .svg)")
    p.add_argument("--tol", type=_tolerance, default=None)
    _solver_option(p)
    p = sub.add_parser("accuracy", help="solve time against error over tolerances and "
                                        "model fidelity")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--json", action="store_true", help="print the ladder as JSON")
    p.add_argument("--plot", metavar="FILE", default=None,
                   help="also write time against error as an image (.png, .pdf, .svg)")
    p.add_argument("--repeats", type=_count, default=7,
                   help="solves per setting; the median time is reported (default 7)")
    _add_check_commands(sub)
    p = sub.add_parser("import-moordyn", help="MoorDyn input file (v1 or v2) to a case file")
    p.add_argument("moordyn", help="MoorDyn input file")
    p.add_argument("-o", "--output", required=True, help="case file to write (YAML)")
    p = sub.add_parser("export-moordyn", help="case file to a MoorDyn input file")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("-o", "--output", required=True, help="MoorDyn input file to write")
    p.add_argument("--version", type=int, choices=(1, 2), default=None,
                   help="MoorDyn format (default: the version the case came from, else 2)")
    p.add_argument("--equilibrium", action="store_true",
                   help="solve first and write the equilibrium positions of the fairleads "
                        "and free points")
    p.add_argument("--tol", type=_tolerance, default=None)
    _solver_option(p)
    p = sub.add_parser("optimise", help="least line mass or cost over a set of load cases "
                                        "(design study file)")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--study", required=True, help="design study file (YAML)")
    p.add_argument("--json", action="store_true", help="print the optimisation as JSON")
    p.add_argument("-o", "--output", default=None,
                   help="write the optimised case file (.yaml) when the optimum is verified")
    p.add_argument("--all-constraints", action="store_true",
                   help="list every constraint, not only the tightest per load case")
    _add_study_commands(sub)
    return parser


def _solver_option(p) -> None:
    p.add_argument("--solver", choices=("ipopt", "newton"), default="ipopt",
                   help="ipopt (default, the reference) or newton (compiled fast path, "
                        "falls back to ipopt)")


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--repeats: {text!r} is not a whole number") from None
    if not 1 <= value <= 1000:
        raise argparse.ArgumentTypeError(f"--repeats: {text} must be from 1 to 1000")
    return value


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = _parser().parse_args(argv)
    if args.command in _CHECK_COMMANDS:
        return _CHECK_COMMANDS[args.command](args)
    if args.command in _STUDY_COMMANDS:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            return _STUDY_COMMANDS[args.command](args)
    if args.command in ("import-moordyn", "export-moordyn"):
        return _moordyn(args)
    from . import load_case, solve
    if args.command == "accuracy":
        return _accuracy(args)
    if args.command == "optimise":
        return _optimise(args)
    with warnings.catch_warnings():
        # numpy's overflow/invalid-value warnings on absurd input would interleave with the
        # one message the command prints; the certificate and ConvergenceError carry it.
        warnings.simplefilter("ignore", RuntimeWarning)
        return _run(args, load_case, solve)


def _run(args, load_case, solve) -> int:
    try:
        case = load_case(args.case)
        if args.command == "plot":
            _check_output(args.output)
        result = solve(case, tol=args.tol, solver=args.solver)
    except CaseError as exc:
        print(f"moorsolve: bad input: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ConvergenceError as exc:
        print(f"moorsolve: {exc}", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    if args.command == "solve":
        from .io.results import format_table, to_json
        _print(to_json(result, profiles=not args.no_profiles) if args.json
               else format_table(result))
        return EXIT_OK
    return _write_plot(result, case, args.output)


def _accuracy(args) -> int:
    import json

    from . import load_case
    from .solve.accuracy import accuracy_ladder, format_ladder
    try:
        case = load_case(args.case)
        if args.plot:
            _check_output(args.plot, "--plot")
    except CaseError as exc:
        print(f"moorsolve: bad input: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        rungs = accuracy_ladder(case, repeats=args.repeats)
    except ConvergenceError as exc:
        print(f"moorsolve: the reference solve failed: {exc}", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    if args.plot:
        from .plot import plot_accuracy
        _save_figure(lambda: plot_accuracy(rungs)[0].figure, args.plot)
    _print(json.dumps({"case": case.name, "rungs": [r.to_dict() for r in rungs]}, indent=2)
           if args.json else format_ladder(rungs, case.name))
    return EXIT_OK


def _optimise(args) -> int:
    from . import load_case
    from .io.optimise_report import format_optimisation, optimisation_json
    from .io.study_file import load_study, write_case_file
    from .solve.optimise import optimise
    try:
        case = load_case(args.case)
        if args.output is not None:
            _check_case_output(args.output)
        study = load_study(args.study, case)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            opt = optimise(case, study)
    except CaseError as exc:
        print(f"moorsolve: bad input: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ConvergenceError as exc:
        print(f"moorsolve: {exc.reason} ({exc.iterations} iterations, IPOPT status "
              f"{exc.status or 'n/a'})", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    _print(optimisation_json(opt) if args.json
           else format_optimisation(opt, every_constraint=args.all_constraints))
    if not opt.verified:
        print("moorsolve: the optimum did not pass the independent re-solve of every load "
              "case; no case file written", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    if args.output is not None:
        data = dict(opt.optimised_data)
        data["name"] = f"{case.name} (optimised)"
        write_case_file(data, args.output, header=(
            f"{case.name}: optimised by moorsolve optimise --study {args.study}\n"
            f"{opt.objective} {opt.objective_start:,.0f} -> {opt.objective_optimum:,.0f} "
            f"{opt.unit}"))
        if not args.json:
            print(f"wrote {args.output}")
    return EXIT_OK


def _check_case_output(path: str) -> None:
    if os.path.splitext(path)[1].lower() not in (".yaml", ".yml"):
        raise CaseError("--output", f"{path!r} must end in .yaml or .yml")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise CaseError("--output", f"folder {folder!r} does not exist")


def _check_output(path: str, option: str = "--output") -> None:
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".png", ".pdf", ".svg"):
        raise CaseError(option, f"{path!r} must end in .png, .pdf or .svg")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise CaseError(option, f"folder {folder!r} does not exist")


def _write_plot(result, case, path: str) -> int:
    from .plot import plot_equilibrium
    _save_figure(lambda: plot_equilibrium(result, depth=case.environment.depth), path)
    print(f"wrote {path}")
    return EXIT_OK


def _save_figure(make_figure, path: str) -> None:
    """Draw with ``make_figure()`` and write it to ``path`` atomically."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .io.output_files import replacing

    fig = make_figure()
    try:
        with replacing(path) as tmp:
            fig.savefig(tmp, dpi=120)
    finally:
        plt.close(fig)


# ---- moorsolve check and the inverse problems (issue 5) ------------------------------------


def _add_check_commands(sub) -> None:
    from .checks import STANDARDS
    p = sub.add_parser("check", help="mooring checks: intact and damaged conditions")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--standard", choices=STANDARDS, default=None,
                   help="criteria table (default: the case's checks.standard, else api-rp-2sk)")
    p.add_argument("--json", action="store_true", help="print the check as JSON")
    p.add_argument("--report", default=None, help="write a self-contained HTML report")
    p.add_argument("--no-damaged", action="store_true", help="intact condition only")
    p.add_argument("--tol", type=_tolerance, default=None)
    inverse_help = {
        "anchor-distance": "least anchor distance with no anchor uplift (Hu & Tang Tables 1, 2, 4)",
        "chain-length": "least chain for a load keeping a grounded length",
        "uplift": "anchor uplift force and angle at a given anchor distance (Hu & Tang Table 3)",
    }
    for name, text in inverse_help.items():
        p = sub.add_parser(name, help=text)
        p.add_argument("--height", required=True,
                       help="fairlead above the anchor, e.g. '20.85 m' (the water depth)")
        p.add_argument("--weight", required=True,
                       help="submerged weight per length, e.g. '0.13 t/m' or '1275 N/m'")
        load = p.add_mutually_exclusive_group(required=True)
        load.add_argument("--tension", help="fairlead tension, e.g. '1623.5 kN'")
        load.add_argument("--horizontal-tension", help="horizontal tension, e.g. '372 kN'")
        p.add_argument("--ea", default=None, help="axial stiffness (default inextensible)")
        p.add_argument("--gravity", default="9.80665",
                       help="for weights given as mass per length (Hu & Tang use 10)")
        if name == "chain-length":
            p.add_argument("--grounded", required=True, help="length to keep on the seabed")
            p.add_argument("--inboard", default="0", help="inboard length added to the order")
        if name == "uplift":
            p.add_argument("--distance", required=True, help="anchor distance, e.g. '121.06 m'")
        p.add_argument("--json", action="store_true", help="print the answer as JSON")


def _print(text: str) -> None:
    try:
        print(text)
        sys.stdout.flush()
    except BrokenPipeError:
        # The reader (e.g. `| head`) closed the pipe: not an error of ours.
        sys.stdout = None


def _run_check(args) -> int:
    from . import load_case
    from .checks import run_checks
    try:
        case = load_case(args.case)
        if args.report is not None:
            _check_report_path(args.report)
    except CaseError as exc:
        print(f"moorsolve: bad input: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    report = run_checks(case, standard=args.standard, tol=args.tol,
                        damaged=False if args.no_damaged else None)
    from .io.check_report import check_json, format_check_table, write_html_report
    if args.report is not None:
        write_html_report(report, case, args.report)
    _print(check_json(report) if args.json else format_check_table(report))
    if args.report is not None and not args.json:
        print(f"wrote {args.report}")
    return EXIT_OK if report.passed else EXIT_NO_EQUILIBRIUM


def _check_report_path(path: str) -> None:
    if os.path.splitext(path)[1].lower() not in (".html", ".htm"):
        raise CaseError("--report", f"{path!r} must end in .html")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise CaseError("--report", f"folder {folder!r} does not exist")


def _run_inverse(args) -> int:
    import json

    from .io.units import to_si, weight_per_length_to_si
    from .solve import inverse
    try:
        gravity = to_si(args.gravity, "acceleration", "--gravity")
        if not gravity > 0:
            raise CaseError("--gravity", f"{args.gravity} must be > 0")
        kwargs = {
            "height": to_si(args.height, "length", "--height"),
            "weight": weight_per_length_to_si(args.weight, gravity, "--weight"),
            "ea": None if args.ea is None else to_si(args.ea, "force", "--ea"),
        }
        if args.tension is not None:
            kwargs["fairlead_tension"] = to_si(args.tension, "force", "--tension")
        else:
            kwargs["horizontal_tension"] = to_si(args.horizontal_tension, "force",
                                                 "--horizontal-tension")
        if args.command == "chain-length":
            kwargs["grounded_length"] = to_si(args.grounded, "length", "--grounded")
            kwargs["inboard_length"] = to_si(args.inboard, "length", "--inboard")
            function = inverse.required_chain_length
        elif args.command == "uplift":
            kwargs["anchor_distance"] = to_si(args.distance, "length", "--distance")
            function = inverse.uplift_at_distance
        else:
            function = inverse.minimum_anchor_distance
        answer = function(**kwargs)
    except ValueError as exc:      # CaseError is a ValueError too
        print(f"moorsolve: bad input: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ConvergenceError as exc:
        print(f"moorsolve: {exc}", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    if args.json:
        _print(json.dumps(answer.to_dict(), indent=2))
        return EXIT_OK
    a = answer
    _print("\n".join([
        f"anchor distance      {a.anchor_distance_m:12.4f} m",
        f"fairlead height      {a.height_m:12.4f} m",
        f"horizontal tension   {a.horizontal_tension_N / 1e3:12.4f} kN",
        (f"fairlead tension     {a.fairlead_tension_N / 1e3:12.4f} kN at "
         f"{a.fairlead_angle_deg:.5f} deg"),
        (f"line length          {a.length_m:12.4f} m (suspended {a.suspended_length_m:.4f}, "
         f"grounded {a.grounded_length_m:.4f})"),
        (f"anchor uplift        {a.anchor_vertical_N / 1e3:12.4f} kN at "
         f"{a.uplift_angle_deg:.5f} deg"),
    ] + ([f"order length         {a.order_length_m:12.4f} m"]
         if args.command == "chain-length" else [])))
    return EXIT_OK


def _moordyn(args) -> int:
    from .io import export_moordyn, import_moordyn
    try:
        if args.command == "import-moordyn":
            if os.path.splitext(args.output)[1].lower() not in (".yaml", ".yml"):
                raise CaseError("--output", f"{args.output!r} must end in .yaml or .yml")
            import_moordyn(args.moordyn, args.output)
        else:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                export_moordyn(args.case, args.output, version=args.version,
                               equilibrium=args.equilibrium, tol=args.tol, solver=args.solver)
    except CaseError as exc:
        print(f"moorsolve: bad input: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ConvergenceError as exc:
        print(f"moorsolve: {exc}", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    print(f"wrote {args.output}")
    return EXIT_OK


_CHECK_COMMANDS = {"check": _run_check, "anchor-distance": _run_inverse,
                   "chain-length": _run_inverse, "uplift": _run_inverse}


# ---- sweeps and envelopes (issue 6) ---------------------------------------------------------


def _workers(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--workers: {text!r} is not a whole number") from None
    if not 1 <= value <= 1024:
        raise argparse.ArgumentTypeError(f"--workers: {text} must be from 1 to 1024")
    return value


def _add_study_commands(sub) -> None:
    from .io.paths import SET_SYNTAX
    p = sub.add_parser("sweep", help="solve a grid of case edits; results to CSV or parquet")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--set", action="append", required=True, dest="sets", metavar="PATH=VALUES",
                   help=f"one axis of the grid (repeat for more): {SET_SYNTAX}")
    p.add_argument("-o", "--output", required=True, help="results file (.csv or .parquet)")
    p.add_argument("--solver", choices=("newton", "ipopt"), default="newton",
                   help="newton (default: compiled fast path, IPOPT where it cannot "
                        "certify) or ipopt for every point")
    p.add_argument("--tol", type=_tolerance, default=None)
    p.add_argument("--workers", type=_workers, default=None,
                   help="local threads (default: the number of cores)")
    p.add_argument("--resume", action="store_true",
                   help="finish the points missing from an interrupted run's output")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output")
    p.add_argument("--scheduler", default=None, metavar="tcp://HOST:PORT",
                   help="run on an existing dask.distributed cluster")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p = sub.add_parser("envelope", help="offset and worst tension for every heading of the "
                                        "environment")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--step", type=_step, default=10.0,
                   help="heading step in degrees (default 10: 0, 10, ..., 350)")
    p.add_argument("--flows", default=None,
                   help="which flows turn, comma separated (default: every one the case "
                        "has of wind, current, waves)")
    p.add_argument("--plot", metavar="FILE", default=None,
                   help="write polar plots of offset and worst tension (.png, .pdf, .svg)")
    p.add_argument("--json", action="store_true", help="print the envelope as JSON")
    p.add_argument("--solver", choices=("newton", "ipopt"), default="newton")
    p.add_argument("--tol", type=_tolerance, default=None)


def _step(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--step: {text!r} is not a number") from None
    if not 0 < value <= 180:
        raise argparse.ArgumentTypeError(f"--step: {text} must be > 0 and <= 180 deg")
    return value


def _run_envelope(args) -> int:
    import json

    import numpy as np

    from . import load_case
    from .solve.envelope import format_envelope, offset_envelope
    try:
        if args.plot:
            _check_output(args.plot, "--plot")
        case = load_case(args.case)
        flows = None if args.flows is None else [f.strip() for f in args.flows.split(",")]
        envelope = offset_envelope(case, step_deg=args.step, flows=flows, solver=args.solver,
                                   tol=args.tol)
    except CaseError as exc:
        text = str(exc)
        if exc.field in ("flows", "step_deg"):
            text = "--" + exc.field.split("_")[0] + text[len(exc.field):]
        print(f"moorsolve: bad input: {text}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if args.plot:
        from .plot import plot_envelope
        _save_figure(lambda: plot_envelope(envelope)[0].figure, args.plot)
    _print(json.dumps(envelope.to_dict(), indent=2) if args.json
           else format_envelope(envelope))
    if args.plot and not args.json:
        print(f"wrote {args.plot}")
    missing = ~np.isfinite(envelope.worst_tension_N)
    if missing.any():
        print(f"moorsolve: no equilibrium at {int(missing.sum())} of "
              f"{len(missing)} headings", file=sys.stderr)
        return EXIT_NO_EQUILIBRIUM
    return EXIT_OK


def _run_sweep(args) -> int:
    from . import load_case, sweep
    from .io.paths import parse_assignment
    from .io.sweep_output import check_output_path
    if args.resume and args.overwrite:
        print("moorsolve: bad input: --resume and --overwrite exclude each other",
              file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        check_output_path(args.output, "--output")
        grid = {}
        for text in args.sets:
            path, values = parse_assignment(text)
            if path in grid:
                raise CaseError(f"--set {path}", "given twice; one --set per path")
            grid[path] = values
        case = load_case(args.case)
        progress = sys.stderr if (not args.quiet and sys.stderr.isatty()) else False
        table = sweep(case, grid, solver=args.solver, tol=args.tol, workers=args.workers,
                      output=args.output, resume=args.resume, overwrite=args.overwrite,
                      scheduler=args.scheduler, progress=progress)
    except CaseError as exc:
        print(f"moorsolve: bad input: {_set_field(exc)}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print(f"moorsolve: interrupted; the finished points are in {args.output} and "
              f"--resume completes it", file=sys.stderr)
        return 130
    failed = int((~table["converged"].astype(bool)).sum())
    note = f" ({failed} without equilibrium: see the reason column)" if failed else ""
    _print(f"wrote {args.output}: {len(table)} points{note}")
    return EXIT_OK


def _set_field(exc: CaseError) -> str:
    """A grid error told in the command line's words (``--set PATH``)."""
    text = str(exc)
    if exc.field.startswith("grid['") and exc.field.endswith("']"):
        return f"--set {exc.field[6:-2]}" + text[len(exc.field):]
    if exc.field in ("output", "resume", "scheduler"):
        return f"--{exc.field}" + text[len(exc.field):]
    return text


_STUDY_COMMANDS = {"sweep": _run_sweep, "envelope": _run_envelope}


if __name__ == "__main__":
    sys.exit(main())
