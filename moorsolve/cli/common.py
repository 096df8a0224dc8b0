"""What every command shares: exit codes, option types, output checks, printing, figures."""

from __future__ import annotations

import argparse
import os
import sys

from ..errors import CaseError

EXIT_OK, EXIT_NO_EQUILIBRIUM, EXIT_BAD_INPUT = 0, 1, 2
EXIT_INTERRUPTED = 130

IMAGE_EXTENSIONS = (".png", ".pdf", ".svg")
YAML_EXTENSIONS = (".yaml", ".yml")


class Parser(argparse.ArgumentParser):
    def error(self, message):
        # argparse's own errors are bad input too: one line, status 2.
        self.exit(EXIT_BAD_INPUT, f"moorsolve: error: {message}\n")


def _number(option: str, text: str, kind, what: str):
    try:
        return kind(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{option}: {text!r} is not {what}") from None


def tolerance(text: str) -> float:
    value = _number("--tol", text, float, "a number")
    if not 0 < value < 1:
        raise argparse.ArgumentTypeError(f"--tol: {text} must be > 0 and < 1")
    return value


def whole_number(option: str, low: int, high: int):
    """An argparse type for a whole number from ``low`` to ``high``."""
    def parse(text: str) -> int:
        value = _number(option, text, int, "a whole number")
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{option}: {text} must be from {low} to {high}")
        return value
    return parse


def heading_step(text: str) -> float:
    value = _number("--step", text, float, "a number")
    if not 0 < value <= 180:
        raise argparse.ArgumentTypeError(f"--step: {text} must be > 0 and <= 180 deg")
    return value


#: Why two commands default to another solver, said in every ``--solver`` help.
_SOLVER_DEFAULTS = ("Commands that solve once default to ipopt, the reference; sweep and "
                    "envelope, which solve many warm-started points, default to newton for "
                    "speed. Both certify the same residual (--tol).")


def solver_option(p, default: str = "ipopt") -> None:
    """``--solver``: the same choices and the same explanation of the defaults everywhere."""
    here = ("default here: ipopt" if default == "ipopt" else "default here: newton")
    p.add_argument("--solver", choices=("ipopt", "newton"), default=default,
                   help=f"ipopt (interior point, the reference) or newton (compiled fast "
                        f"path; falls back to ipopt where it cannot certify); {here}. "
                        + _SOLVER_DEFAULTS)


def tolerance_option(p) -> None:
    """``--tol``: one definition for every command that solves."""
    p.add_argument("--tol", type=tolerance, default=None,
                   help="certified force residual relative to the largest line tension, "
                        "> 0 and < 1 (default 1e-9)")


def overload_option(p) -> None:
    """``--allow-overload``: report an equilibrium in which a line exceeds its MBL, or a
    fender its rated deflection, instead of exiting 1 (``allow_overload=True`` in Python)."""
    p.add_argument("--allow-overload", action="store_true",
                   help="accept an equilibrium in which a line exceeds its minimum breaking "
                        "load or a fender its rated deflection (it is still reported) "
                        "instead of exiting 1")


def check_output(path: str, option: str, extensions: tuple, describe: str | None = None) -> None:
    """Refuse, before any work, an output path with the wrong extension or no folder."""
    if os.path.splitext(path)[1].lower() not in extensions:
        allowed = describe or (", ".join(extensions[:-1]) + " or " + extensions[-1])
        raise CaseError(option, f"{path!r} must end in {allowed}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise CaseError(option, f"folder {folder!r} does not exist")


def print_text(text: str) -> None:
    try:
        print(text)
        sys.stdout.flush()
    except BrokenPipeError:
        # The reader (e.g. `| head`) closed the pipe: not an error of ours.
        sys.stdout = None


def bad_input(text) -> int:
    print(f"moorsolve: bad input: {text}", file=sys.stderr)
    return EXIT_BAD_INPUT


def save_figure(make_figure, path: str) -> None:
    """Draw with ``make_figure()`` and write it to ``path`` atomically."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..io.output_files import replacing

    fig = make_figure()
    try:
        with replacing(path) as tmp:
            fig.savefig(tmp, dpi=120)
    finally:
        plt.close(fig)
