"""Start-up time: ``import moorsolve``, ``moorsolve --help`` and a first solve, beside MoorPy.

    python benchmarks/startup.py [--repeats 7]

Each command runs in a fresh interpreter (``sys.executable``) from the repository root;
the best of ``--repeats`` wall times is reported, with a bare ``python -c pass`` for the
interpreter's own start and ``import moorpy`` (the peer, when installed) in the same run.
Returns the rows as a dict (``benchmarks/run.py`` records them in results.json).
"""

from __future__ import annotations

import argparse
import importlib.util
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

COMMANDS = {
    "python -c pass": [sys.executable, "-c", "pass"],
    "import moorsolve": [sys.executable, "-c", "import moorsolve"],
    "moorsolve --help": [sys.executable, "-m", "moorsolve", "--help"],
    "moorsolve solve cases/floating_dock.yaml": [sys.executable, "-m", "moorsolve", "solve",
                                                 "cases/floating_dock.yaml"],
}
PEER = {"import moorpy": [sys.executable, "-c", "import moorpy"]}


def best_time(argv: list, repeats: int) -> float:
    """Best wall time [s] of ``repeats`` runs of ``argv`` in a fresh process."""
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(argv, cwd=ROOT, capture_output=True, check=True)
        best = min(best, time.perf_counter() - t0)
    return best


def measure(repeats: int = 7) -> dict:
    commands = dict(COMMANDS)
    if importlib.util.find_spec("moorpy") is not None:
        commands.update(PEER)
    return {name: best_time(argv, repeats) for name, argv in commands.items()}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args(argv)
    for name, seconds in measure(args.repeats).items():
        print(f"{name:<44} {seconds * 1e3:8.1f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
