"""Floating dock (Hu & Tang 2004): how the typhoon load shares itself among the 12 chains
as its heading turns, with the worst chain per heading.

Run:  python examples/dock_typhoon_headings.py [--out FOLDER]
Writes dock_typhoon_headings.png (worst tension and offset against heading) into FOLDER.
One built problem serves every heading; each solve warm-starts from the previous one.
"""

import argparse
import dataclasses
import pathlib

import moorsolve

HERE = pathlib.Path(__file__).resolve().parent
CASE = HERE.parent / "cases" / "floating_dock.yaml"


def heading_study(headings_deg):
    case = moorsolve.load_case(str(CASE))
    env = case.environment
    rows, state = [], None
    for heading in headings_deg:
        turned = dataclasses.replace(
            case, environment=dataclasses.replace(
                env,
                wind=dataclasses.replace(env.wind, toward_deg=heading),
                current=dataclasses.replace(env.current, toward_deg=heading),
                waves=dataclasses.replace(env.waves, toward_deg=heading)))
        result = moorsolve.solve(turned, start=state)
        state = result.state
        worst = max(result.legs, key=lambda leg: leg.fairlead_tension_N)
        rows.append(dict(heading_deg=heading, x_m=result.body["x_m"], y_m=result.body["y_m"],
                         yaw_deg=result.body["yaw_deg"], worst_leg=worst.name,
                         worst_tension_kN=worst.fairlead_tension_N / 1e3,
                         residual_N=result.certificate.force_N,
                         iterations=result.iterations))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for the plot")
    args = parser.parse_args(argv)
    rows = heading_study(range(0, 360, 15))
    print(f"{'toward':>7} {'x m':>7} {'y m':>7} {'yaw deg':>8} {'worst':>6} {'T kN':>8} "
          f"{'resid N':>9}")
    for r in rows:
        print(f"{r['heading_deg']:7.0f} {r['x_m']:7.3f} {r['y_m']:7.3f} {r['yaw_deg']:8.4f} "
              f"{r['worst_leg']:>6} {r['worst_tension_kN']:8.1f} {r['residual_N']:9.1e}")
    worst = max(rows, key=lambda r: r["worst_tension_kN"])
    print(f"worst case: load toward {worst['heading_deg']} deg, {worst['worst_leg']} at "
          f"{worst['worst_tension_kN']:.1f} kN")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    h = [r["heading_deg"] for r in rows]
    a1.plot(h, [r["worst_tension_kN"] for r in rows], "o-")
    a1.set_xlabel("typhoon load toward [deg]")
    a1.set_ylabel("worst fairlead tension [kN]")
    a2.plot([r["x_m"] for r in rows], [r["y_m"] for r in rows], "o-")
    a2.set_aspect("equal")
    a2.set_xlabel("surge x [m]")
    a2.set_ylabel("sway y [m]")
    a2.set_title("offset envelope")
    fig.tight_layout()
    out = pathlib.Path(args.out) / "dock_typhoon_headings.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
