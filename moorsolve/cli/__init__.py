"""The ``moorsolve`` command.

Exit status: 0 solved, 1 no equilibrium (reason and best residual on stderr), 2 bad input
(one message naming the field; no traceback). Each module here owns a
group of commands: ``add_commands(sub)`` declares them and binds each to its ``run``.
"""

from __future__ import annotations

import logging
import sys
import warnings

from ..errors import CaseError, ConvergenceError, MoorsolveWarning
from . import bounds, checks, cost, equilibrium, fatigue, moordyn, motions, studies
from .common import EXIT_BAD_INPUT, EXIT_NO_EQUILIBRIUM, EXIT_OK, Parser, bad_input

__all__ = ["main", "EXIT_OK", "EXIT_NO_EQUILIBRIUM", "EXIT_BAD_INPUT"]


def _parser() -> Parser:
    from .._version import __version__
    parser = Parser(prog="moorsolve", description="Static equilibrium of moored bodies.")
    parser.add_argument("--version", action="version", version=f"moorsolve {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for group in (equilibrium, checks, cost, moordyn, studies, bounds, motions, fatigue):
        group.add_commands(sub)
    return parser


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """moorsolve's own warnings as one line each on stderr; others as Python shows them."""
    if issubclass(category, MoorsolveWarning):
        print(f"moorsolve: warning: {message}", file=sys.stderr)
    else:
        sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status.

    The library's log messages at INFO and above (e.g. the one-off compile of a Newton
    kernel) and its warnings (inputs no model uses) go to stderr as ``moorsolve: ...``
    lines, so stdout holds only the command's output.

    Without a command (bare ``moorsolve``) the usage and the list of commands go to stderr
    and the status is 2, as for any other missing argument.
    """
    parser = _parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv:
        parser.print_help(sys.stderr)
        print("moorsolve: error: name a command (moorsolve COMMAND --help for its options)",
              file=sys.stderr)
        return EXIT_BAD_INPUT
    args = parser.parse_args(argv)
    log = logging.getLogger("moorsolve")
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("moorsolve: %(message)s"))
    level = log.level
    log.addHandler(handler)
    log.setLevel(logging.INFO)
    with warnings.catch_warnings():
        # numpy's overflow/invalid-value warnings on absurd input would interleave with the
        # one message the command prints; the certificate and ConvergenceError carry it.
        warnings.simplefilter("ignore", RuntimeWarning)
        warnings.simplefilter("default", MoorsolveWarning)
        warnings.showwarning = _show_warning
        try:
            return args.run(args)
        except CaseError as exc:
            return bad_input(exc)
        except ConvergenceError as exc:
            print(f"moorsolve: {exc}", file=sys.stderr)
            return EXIT_NO_EQUILIBRIUM
        finally:
            log.removeHandler(handler)
            log.setLevel(level)
