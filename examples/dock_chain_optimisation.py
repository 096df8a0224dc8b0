"""Floating dock (Hu & Tang 2004): the least chain that keeps the dock within its checks in
the typhoon from every heading 45 deg apart, as one IPOPT problem.

Run:  python examples/dock_chain_optimisation.py [--out FOLDER]
The study is cases/studies/floating_dock_chain.yaml (breast and end chains, two length groups;
safety factor 2.0, sinker-block uplift 281 kN, offset 3 m). Prints the report and writes
dock_chain_optimisation.png (lengths before and after, constraint utilisation) into FOLDER.
"""

import argparse
import pathlib

import moorsolve
from moorsolve.report.optimise import format_optimisation
from moorsolve.plot import plot_optimisation

HERE = pathlib.Path(__file__).resolve().parent
CASE = HERE.parent / "cases" / "floating_dock.yaml"
STUDY = HERE.parent / "cases" / "studies" / "floating_dock_chain.yaml"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for the plot")
    args = parser.parse_args(argv)
    case = moorsolve.load_case(str(CASE))
    opt = moorsolve.optimise(case, str(STUDY))
    print(format_optimisation(opt))
    saving = opt.objective_start - opt.objective_optimum
    print(f"chain saved: {saving / 1e3:.2f} t of {opt.objective_start / 1e3:.1f} t "
          f"({100 * saving / opt.objective_start:.2f} %), verified: {opt.verified}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ax1, _ = plot_optimisation(opt)
    out = pathlib.Path(args.out) / "dock_chain_optimisation.png"
    ax1.figure.savefig(out, dpi=110)
    plt.close(ax1.figure)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
