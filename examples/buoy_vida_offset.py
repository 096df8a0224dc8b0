"""Buoy Vida (Malacic): offset and chain tensions against wind speed and direction.

Run:  python examples/buoy_vida_offset.py [--out FOLDER]
One sweep covers every wind direction (toward 0, 15, ..., 345 deg) at speeds 0 to 40 m/s.
The table shows the bora (from the NE, blowing toward 225 deg) and the jugo (from the SE,
toward 135 deg) rows: the horizontal pull on each anchor (equal to the chain's horizontal
tension while the chain still lies on the seabed at the anchor; Malacic's 528.5 N at rest)
and which chain goes slack first. Writes buoy_vida_offset.png into FOLDER: polar contours
of the offset and of the largest chain tension over direction (angle) and speed (radius),
with bora and jugo marked.
"""

import argparse
import pathlib

import numpy as np

import moorsolve

CASE = pathlib.Path(__file__).resolve().parent.parent / "cases" / "buoy_vida.yaml"
WINDS = {"bora": 225.0, "jugo": 135.0}           # the direction each blows toward [deg]
DIRECTIONS = list(range(0, 360, 15))
SPEEDS = [0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0]
SLACK_N = 1.0                                    # a chain pulling its anchor less is slack


def offset_study():
    case = moorsolve.load_case(str(CASE))
    table = moorsolve.sweep(case, {"environment.wind.toward_deg": DIRECTIONS,
                                   "environment.wind.speed": SPEEDS})
    if not table["converged"].all():
        raise RuntimeError("some wind has no equilibrium: " + "; ".join(
            set(table.loc[~table["converged"], "reason"])))
    table["offset_m"] = np.hypot(table["x_m"], table["y_m"])
    return case, table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for the plot")
    args = parser.parse_args(argv)
    case, table = offset_study()
    names = [leg.name for leg in case.legs]

    print(f"{'wind':>5} {'speed':>6} {'x m':>7} {'y m':>7}  " +
          "  ".join(f"{name:>10}" for name in names))
    for wind, toward in WINDS.items():
        rows = table[table["environment.wind.toward_deg [deg]"] == toward]
        for speed in (0.0, 10.0, 20.0, 30.0, 40.0):
            row = rows[rows["environment.wind.speed [m/s]"] == speed].iloc[0]
            pulls = [row[f"{n}.anchor_tension_N"] for n in names]
            cells = "  ".join(f"{'slack' if t < SLACK_N else f'{t:7.0f} N':>10}" for t in pulls)
            print(f"{wind:>5} {speed:6.1f} {row['x_m']:7.2f} {row['y_m']:7.2f}  {cells}")

    worst = table.loc[table["offset_m"].idxmax()]
    speed = worst["environment.wind.speed [m/s]"]
    toward = worst["environment.wind.toward_deg [deg]"]
    print(f"largest offset: {worst['offset_m']:.2f} m with {speed:g} m/s wind toward "
          f"{toward:g} deg")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from moorsolve.plot import plot_polar_field

    shape = (len(DIRECTIONS), len(SPEEDS))           # the sweep's product order
    offset = table["offset_m"].to_numpy().reshape(shape)
    tension = table[[f"{n}.fairlead_tension_N" for n in names]].max(axis=1)
    tension = tension.to_numpy().reshape(shape) / 1e3
    fig = plt.figure(figsize=(12, 5.4), layout="constrained")
    for k, (values, label) in enumerate(((offset, "offset [m]"),
                                         (tension, "largest chain tension [kN]"))):
        ax = fig.add_subplot(1, 2, k + 1, projection="polar")
        plot_polar_field(DIRECTIONS, SPEEDS, values, ax=ax, radius_label="wind speed [m/s]",
                         value_label=label, marks=WINDS)
    fig.suptitle("Buoy Vida: wind toward the angle shown (counter-clockwise from east)")
    out = pathlib.Path(args.out) / "buoy_vida_offset.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
