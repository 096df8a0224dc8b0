"""What a stretch law costs per solve, against Hooke's law on the same scene.

    PYTHONPATH=. python benchmarks/stretch_laws.py [--repeats 20] [--points 360]

Scenes: the shipped FPU on three chain-polyester-chain legs
(``cases/fpu_polyester_table.yaml``) and a buoy on three one-segment polyester legs. The
polyester is, in turn: Hooke (EA the working curve's secant at the pretension), the
case's 9-row table, a 30-row table of the same curve (MoorDyn's largest), and Baranov's law
(n matched at the pretension). Timed, each after a warm-up that builds (and compiles) the
problem: the compiled Newton kernel alone from the rest state to the loaded equilibrium
(``problem.newton().raw``: the solve proper); ``moorsolve.solve`` with IPOPT (the
default) and with the compiled Newton fast path, each with the full Result (51-point
profiles drawn through the law); the best of ``--repeats`` rounds; and the sweep (Newton,
one thread) over ``--points`` headings of the environment, time per point (best of a fifth
as many rounds).
Each round times every law in turn, so that load from other work on a shared machine
does not fall on one law only. Reported: the times and each
law's ratio to Hooke. Results go to ``benchmarks/stretch_results.json``. Timings depend on
the machine and its load; the ratios are what the issue asks for (table law <= 2x Hooke).
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import os
import pathlib
import platform
import sys
import time

import numpy as np
import yaml

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import moorsolve  # noqa: E402
from moorsolve.physics.stretch import NumericLaw, StretchModel  # noqa: E402
from moorsolve.solve.equilibrium import get_problem, rest_point  # noqa: E402
from moorsolve.solve.assembly.prepared import parameter_vector  # noqa: E402

CASE = ROOT / "cases" / "fpu_polyester_table.yaml"
HEADINGS = ("environment.wind.toward_deg", "environment.current.toward_deg")


def _curve(data):
    st = data["line_types"]["polyester160"]["stretch"]
    case = moorsolve.load_case(data)
    law = case.line_types["polyester160"].stretch
    return st, law


def variants(data: dict) -> dict:
    """The scene with its polyester as Hooke, the 9-row table, a 30-row table, Baranov."""
    _, law = _curve(data)
    pretension = 857e3
    numeric = NumericLaw(StretchModel("table", law.rows), law.parameters())
    eps = float(numeric.strain(pretension))
    fine_t = np.linspace(0.0, law.tension[-1], 30)[1:]
    fine_e = numeric.strain(fine_t)
    out = {}
    for name, stretch in (
            ("hooke", {"model": "hooke", "ea": pretension / eps}),
            ("table (9 rows)", None),
            ("table (30 rows)", {"model": "table", "strain": fine_e.tolist(),
                                 "tension": fine_t.tolist()}),
            ("baranov", {"model": "baranov", "n": eps / math.sqrt(pretension)})):
        d = copy.deepcopy(data)
        poly = d["line_types"]["polyester160"]
        poly.pop("stiffness_bounds", None)
        if stretch is not None:
            poly["stretch"] = stretch
        out[name] = d
    return out


def single_leg_scene(data: dict) -> dict:
    """The FPU's polyester alone: three one-segment legs from anchors 900 m out."""
    d = copy.deepcopy(data)
    for leg, angle in zip(d["legs"], (0.0, 120.0, 240.0)):
        a = math.radians(angle)
        leg["anchor"] = [round(903.0 * math.cos(a), 3), round(903.0 * math.sin(a), 3)]
        leg["segments"] = [{"type": "polyester160", "length": 880.0}]
    return d


def measure(variants_data: dict, repeats: int, points: int) -> dict:
    """Best (least) time of each variant, the variants timed in turn in every round, so
    that a busy moment of a shared machine does not fall on one law only."""
    cases = {name: moorsolve.load_case(d) for name, d in variants_data.items()}
    grid = {HEADINGS: [(h, h) for h in np.linspace(0.0, 360.0, points, endpoint=False)]}
    for case in cases.values():                       # build, compile, warm the caches
        moorsolve.solve(case)
        moorsolve.solve(case, solver="newton")
        moorsolve.sweep(case, grid, workers=1)
    best = {name: {"kernel_s": np.inf, "ipopt_solve_s": np.inf, "newton_solve_s": np.inf,
                   "sweep_point_s": np.inf} for name in cases}
    kernels = {}
    for name, case in cases.items():
        problem = get_problem(case)
        kernels[name] = (problem.newton(), rest_point(problem, case, 1e-9),
                         parameter_vector(case, 1.0))
    converged = {}
    for round_ in range(repeats):
        for name, case in cases.items():
            row = best[name]
            kernel, x0, p = kernels[name]
            t0 = time.perf_counter()
            kernel.raw(x0, p, 1e-9)
            row["kernel_s"] = min(row["kernel_s"], time.perf_counter() - t0)
            for key, solver in (("ipopt_solve_s", "ipopt"), ("newton_solve_s", "newton")):
                t0 = time.perf_counter()
                moorsolve.solve(case, solver=solver)
                row[key] = min(row[key], time.perf_counter() - t0)
            if round_ < max(1, repeats // 5):             # sweeps are long: fewer rounds
                t0 = time.perf_counter()
                table = moorsolve.sweep(case, grid, workers=1)
                row["sweep_point_s"] = min(row["sweep_point_s"],
                                           (time.perf_counter() - t0) / points)
                converged[name] = int(table["converged"].sum())
    for name in cases:
        best[name]["sweep_converged"] = converged[name]
    return best


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--points", type=int, default=360)
    args = parser.parse_args(argv)
    base = yaml.safe_load(CASE.read_text())
    scenes = {"FPU, chain-polyester-chain (3 legs)": base,
              "buoy, one-segment polyester (3 legs)": single_leg_scene(base)}
    report = {"machine": {"cores": os.cpu_count(), "python": platform.python_version(),
                          "load_average": os.getloadavg()[0]},
              "repeats": args.repeats, "points": args.points, "scenes": {}}
    for scene, data in scenes.items():
        rows = measure(variants(data), args.repeats, args.points)
        hooke = rows["hooke"]
        for row in rows.values():
            for key in ("kernel_s", "ipopt_solve_s", "newton_solve_s", "sweep_point_s"):
                row[key[:-2] + "_ratio_to_hooke"] = row[key] / hooke[key]
        report["scenes"][scene] = rows
        print(f"\n{scene}")
        print(f"{'law':<18}{'kernel us':>10}{'ratio':>7}{'IPOPT ms':>10}{'ratio':>7}"
              f"{'Newton ms':>11}{'ratio':>7}{'sweep us/pt':>13}{'ratio':>7}")
        for name, row in rows.items():
            print(f"{name:<18}{1e6 * row['kernel_s']:10.1f}{row['kernel_ratio_to_hooke']:7.2f}"
                  f"{1e3 * row['ipopt_solve_s']:10.2f}"
                  f"{row['ipopt_solve_ratio_to_hooke']:7.2f}"
                  f"{1e3 * row['newton_solve_s']:11.2f}{row['newton_solve_ratio_to_hooke']:7.2f}"
                  f"{1e6 * row['sweep_point_s']:13.1f}{row['sweep_point_ratio_to_hooke']:7.2f}")
    (HERE / "stretch_results.json").write_text(json.dumps(report, indent=2) + "\n")
    print(f"\nwrote {HERE / 'stretch_results.json'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
