"""Buoy Vida (Malacic, seed 002): offset and chain tensions against bora and jugo wind speed.

Run:  python examples/buoy_vida_offset.py
Bora blows from the NE (toward 225 deg), jugo from the SE (toward 135 deg); the table shows
which chain goes slack first.
"""

import dataclasses
import pathlib

import moorsolve

CASE = pathlib.Path(__file__).resolve().parent.parent / "cases" / "buoy_vida.yaml"


def main():
    case = moorsolve.load_case(str(CASE))
    print(f"{'wind':>5} {'speed':>6} {'x m':>7} {'y m':>7}  " +
          "  ".join(f"{leg.name:>10}" for leg in case.legs))
    for name, toward in (("bora", 225.0), ("jugo", 135.0)):
        state = None
        for speed in (0.0, 10.0, 20.0, 30.0, 40.0):
            env = dataclasses.replace(case.environment, wind=moorsolve.model.Flow(speed, toward))
            result = moorsolve.solve(dataclasses.replace(case, environment=env), start=state)
            state = result.state
            cells = "  ".join(
                f"{'slack' if leg.slack else f'{leg.horizontal_tension_N:7.0f} N':>10}"
                for leg in result.legs)
            print(f"{name:>5} {speed:6.1f} {result.body['x_m']:7.2f} {result.body['y_m']:7.2f}  "
                  f"{cells}")


if __name__ == "__main__":
    main()
