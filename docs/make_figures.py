"""Draw the pictures the documentation shows: ``python docs/make_figures.py [--out DIR]``.

Every picture is made by moorsolve's own plot functions from a shipped case, so the
documentation shows what a user gets. tests/test_docs.py runs this script.
"""

from __future__ import annotations

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import moorsolve  # noqa: E402
from moorsolve.plot import plot_directions, plot_equilibrium  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default=str(ROOT / "docs"), help="folder for the PNGs")
    out = pathlib.Path(parser.parse_args(argv).out)

    ax = plot_directions()
    ax.figure.savefig(out / "directions.png", dpi=100)
    plt.close(ax.figure)

    result = moorsolve.solve(moorsolve.load_case(ROOT / "cases" / "floating_dock_sloped.yaml"))
    fig = plot_equilibrium(result)
    fig.savefig(out / "equilibrium_dock_sloped.png", dpi=80)
    plt.close(fig)
    print(f"wrote the figures to {out}")


if __name__ == "__main__":
    main()
