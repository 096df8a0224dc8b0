"""The ``moorsolve`` command.

Exit status: 0 solved, 1 no equilibrium (reason and best residual on stderr), 2 bad input
(one message naming the field; no traceback), per CONTRACT.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

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
    from . import load_case, solve
    if args.command == "accuracy":
        return _accuracy(args)
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
        text = to_json(result, profiles=not args.no_profiles) if args.json \
            else format_table(result)
        try:
            print(text)
            sys.stdout.flush()
        except BrokenPipeError:
            # The reader (e.g. `| head`) closed the pipe: not an error of ours.
            sys.stdout = None
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
    text = (json.dumps({"case": case.name, "rungs": [r.to_dict() for r in rungs]}, indent=2)
            if args.json else format_ladder(rungs, case.name))
    try:
        print(text)
        sys.stdout.flush()
    except BrokenPipeError:
        sys.stdout = None
    return EXIT_OK


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

    fig = make_figure()
    folder = os.path.dirname(os.path.abspath(path))
    ext = os.path.splitext(path)[1]
    # Write beside the target and rename, so a failure leaves no half-written file.
    fd, tmp = tempfile.mkstemp(suffix=ext, dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=120)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


if __name__ == "__main__":
    sys.exit(main())
