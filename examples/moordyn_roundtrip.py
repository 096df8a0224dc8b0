"""The floating dock to MoorDyn and back.

1. Export cases/floating_dock.yaml as a MoorDyn v2 file, import it again, put back what
   MoorDyn cannot hold (the typhoon and the dock's load models), solve both: the offsets and
   every chain tension agree.
2. Export it at its static equilibrium (``--equilibrium``): the body's reference pose in
   BODIES is the solved offset and yaw. Imported with the body held there, the chains carry
   the equilibrium tensions, so a dynamic run from that file starts in balance.

    python examples/moordyn_roundtrip.py [--out FOLDER]
"""

import argparse
import pathlib
import tempfile

import moorsolve

CASE = pathlib.Path(__file__).resolve().parent.parent / "cases" / "floating_dock.yaml"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="folder for the files (default: temporary)")
    args = parser.parse_args()
    folder = pathlib.Path(args.out or tempfile.mkdtemp(prefix="moordyn_"))
    folder.mkdir(parents=True, exist_ok=True)

    case = moorsolve.load_case(CASE)
    original = moorsolve.solve(case)

    # 1. Plain round trip.
    dat = folder / "floating_dock.dat"
    moorsolve.export_moordyn(case, dat)
    data = moorsolve.import_moordyn(dat, folder / "floating_dock_from_moordyn.yaml")
    data["environment"].update({k: case.source["environment"][k]
                                for k in ("wind", "current", "waves")})
    data["body"]["loads"] = case.source["body"]["loads"]
    data["body"]["free"] = list(case.body.free)
    back = moorsolve.solve(moorsolve.load_case(data))

    # 2. The equilibrium export, imported with the body held at that pose.
    dat_eq = folder / "floating_dock_equilibrium.dat"
    moorsolve.export_moordyn(case, dat_eq, equilibrium=True)
    held = moorsolve.import_moordyn(dat_eq)
    at_rest = moorsolve.solve(moorsolve.load_case(held))

    print(f"files in {folder}: {dat.name}, {dat_eq.name}")
    print(f"{'':10s}{'x m':>12s}{'y m':>12s}{'yaw deg':>12s}")
    for label, r in (("original", original), ("via .dat", back)):
        b = r.body
        print(f"{label:10s}{b['x_m']:12.6f}{b['y_m']:12.6f}{b['yaw_deg']:12.6f}")
    print(f"{'leg':6s}{'original kN':>14s}{'via .dat kN':>14s}{'eq. file kN':>14s}")
    worst = 0.0
    for a, b, c in zip(original.legs, back.legs, at_rest.legs):
        print(f"{a.name:6s}{a.fairlead_tension_N / 1e3:14.4f}{b.fairlead_tension_N / 1e3:14.4f}"
              f"{c.fairlead_tension_N / 1e3:14.4f}")
        worst = max(worst, abs(a.fairlead_tension_N - b.fairlead_tension_N),
                    abs(a.fairlead_tension_N - c.fairlead_tension_N))
    offset = max(abs(original.body[k] - back.body[k]) for k in ("x_m", "y_m"))
    print(f"largest difference: offset {offset:.2e} m, tension {worst:.2e} N")


if __name__ == "__main__":
    main()
