"""The ``moorsolve`` command.

Exit status: 0 solved, 1 no equilibrium (reason and best residual on stderr), 2 bad input
(one message naming the field; no traceback), per CONTRACT.md. Each module here owns a
group of commands: ``add_commands(sub)`` declares them and binds each to its ``run``.
"""

from __future__ import annotations

import sys
import warnings

from ..errors import CaseError, ConvergenceError
from . import bounds, checks, equilibrium, moordyn, studies
from .common import EXIT_BAD_INPUT, EXIT_NO_EQUILIBRIUM, EXIT_OK, Parser, bad_input

__all__ = ["main", "EXIT_OK", "EXIT_NO_EQUILIBRIUM", "EXIT_BAD_INPUT"]


def _parser() -> Parser:
    parser = Parser(prog="moorsolve", description="Static equilibrium of moored bodies.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for group in (equilibrium, checks, moordyn, studies, bounds):
        group.add_commands(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = _parser().parse_args(argv)
    with warnings.catch_warnings():
        # numpy's overflow/invalid-value warnings on absurd input would interleave with the
        # one message the command prints; the certificate and ConvergenceError carry it.
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            return args.run(args)
        except CaseError as exc:
            return bad_input(exc)
        except ConvergenceError as exc:
            print(f"moorsolve: {exc}", file=sys.stderr)
            return EXIT_NO_EQUILIBRIUM
