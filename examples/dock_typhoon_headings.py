"""Floating dock (Hu & Tang 2004): how the typhoon load shares itself among the 12 chains
as its heading turns, with the worst chain per heading and the worst heading overall.

Run:  python examples/dock_typhoon_headings.py [--out FOLDER] [--step DEG]
The case's typhoon (wind, current and waves together, toward 70 deg in the case file) is
turned round the compass by moorsolve.offset_envelope: one sweep, each heading warm-started
from its neighbour. Writes dock_typhoon_headings.png (polar plots of offset and worst
tension against heading, the case file's heading marked) into FOLDER.
"""

import argparse
import pathlib

import moorsolve

HERE = pathlib.Path(__file__).resolve().parent
CASE = HERE.parent / "cases" / "floating_dock.yaml"


def heading_study(step_deg=5.0):
    case = moorsolve.load_case(str(CASE))
    return case, moorsolve.offset_envelope(case, step_deg=step_deg)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for the plot")
    parser.add_argument("--step", type=float, default=5.0, help="heading step [deg]")
    args = parser.parse_args(argv)
    case, env = heading_study(args.step)
    mbl = {leg.name: leg.line_type.mbl for leg in case.legs}

    print(f"{'toward':>7} {'x m':>7} {'y m':>7} {'yaw deg':>8} {'worst':>6} {'T kN':>8} "
          f"{'T/MBL':>6}")
    for i, heading in enumerate(env.heading_deg):
        leg = env.worst_leg[i]
        print(f"{heading:7.0f} {env.x_m[i]:7.3f} {env.y_m[i]:7.3f} {env.yaw_deg[i]:8.4f} "
              f"{leg:>6} {env.worst_tension_N[i] / 1e3:8.1f} "
              f"{env.worst_tension_N[i] / mbl[leg]:6.3f}")
    worst = env.worst()
    print(f"worst case: load toward {worst['heading_deg']:g} deg, {worst['worst_leg']} at "
          f"{worst['worst_tension_N'] / 1e3:.1f} kN "
          f"(safety factor {mbl[worst['worst_leg']] / worst['worst_tension_N']:.2f})")
    far = env.largest_offset()
    print(f"largest offset: {far['offset_m']:.3f} m with the load toward "
          f"{far['heading_deg']:g} deg")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from moorsolve.plot import plot_envelope

    axes = plot_envelope(env, marks={"case file": case.environment.wind.toward_deg})
    fig = axes[0].figure
    fig.suptitle("Floating dock, typhoon turned round the compass")
    out = pathlib.Path(args.out) / "dock_typhoon_headings.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
