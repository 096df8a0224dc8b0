"""Draw the pictures the documentation shows: ``python docs/make_figures.py [--out DIR]``.

Every picture is drawn by moorsolve itself: the walkthrough's pictures are the files its
own commands write (its blocks run by :mod:`run_blocks`), the others come from shipped
cases. tests/test_docs.py runs this script into a temporary folder.
"""

from __future__ import annotations

import argparse
import pathlib
import shutil
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import moorsolve  # noqa: E402
from moorsolve.plot import plot_directions, plot_equilibrium  # noqa: E402

DOCS = pathlib.Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS))

import run_blocks  # noqa: E402

#: Walkthrough output -> documentation picture.
WALKTHROUGH = {"pontoon.png": "walkthrough_pontoon.png"}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(DOCS), help="folder for the PNGs")
    parser.add_argument("--skip-walkthrough", action="store_true",
                        help="do not run the walkthrough for its pictures")
    args = parser.parse_args(argv)
    out = pathlib.Path(args.out)

    ax = plot_directions()
    ax.figure.savefig(out / "directions.png", dpi=100)
    plt.close(ax.figure)

    result = moorsolve.solve(moorsolve.load_case(ROOT / "cases" / "floating_dock_sloped.yaml"))
    fig = plot_equilibrium(result)
    fig.savefig(out / "equilibrium_dock_sloped.png", dpi=80)
    plt.close(fig)

    if args.skip_walkthrough:
        print(f"wrote the figures to {out} (not the walkthrough's)")
        return
    with tempfile.TemporaryDirectory() as tmp:
        run_blocks.run(DOCS / "walkthrough.md", pathlib.Path(tmp), log=lambda *_: None)
        for made, name in WALKTHROUGH.items():
            shutil.copyfile(pathlib.Path(tmp) / made, out / name)
    print(f"wrote the figures to {out}")


if __name__ == "__main__":
    main()
