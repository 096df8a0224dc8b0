"""What contact costs: berthed cases with their fenders against the same cases without them.

    PYTHONPATH=. python benchmarks/berth_contact.py [--loads 60] [--repeats 3]

Two shipped berths, each solved for ``--loads`` seeded random loads (wind speed and heading
near the case's), with its fenders and with them removed (the same scene otherwise: lines,
hawsers, loads):

- ``cases/ship_berth.yaml``: beam winds off the berth (toward 250-290 deg, 5-30 m/s) hold the
  ship on its eight lines; its four fenders open, so both scenes have the same equilibrium
  and the difference is what the contact machinery costs;
- ``cases/dock_quay.yaml``: storm winds onto the quay (toward 70-110 deg, 15-40 m/s): with
  fenders the dock bears on them; without, its chains alone stop it (a different
  equilibrium, metres further, the nearest contact-free scene there is).

Timed per load (median over the loads, best of ``--repeats`` passes; from the solved rest
state each time, as ``solve`` starts): the compiled Newton kernel alone (what a sweep runs per
point), ``solve(solver="newton")`` with its full Result, and ``solve()`` with IPOPT. The
ratio is contact / no contact for each. Results go to ``benchmarks/berth_results.json``.
Timings depend on the machine and its load; the ratios are what to read.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import pathlib
import platform
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import moorsolve  # noqa: E402
from moorsolve.solve.assembly.cache import get_problem  # noqa: E402
from moorsolve.solve.equilibrium import rest_point  # noqa: E402

SCENES = {
    "ship_berth": (ROOT / "cases" / "ship_berth.yaml", (250.0, 290.0), (5.0, 30.0)),
    "dock_quay": (ROOT / "cases" / "dock_quay.yaml", (70.0, 110.0), (15.0, 40.0)),
}


def without_contacts(case):
    """The same scene with its fenders and guides removed."""
    contacts = dataclasses.replace(case.contacts, fenders=(), guides=())
    return dataclasses.replace(case, contacts=contacts, source=None)


def loaded(case, heading: float, speed: float):
    env = case.environment
    wind = dataclasses.replace(env.wind, speed=speed, toward_deg=heading)
    current = dataclasses.replace(env.current, toward_deg=heading)
    return dataclasses.replace(case, environment=dataclasses.replace(
        env, wind=wind, current=current))


def time_scene(cases, repeats: int, tol: float) -> dict:
    """Median times [s] per load of the kernel, solve(newton) and solve(ipopt)."""
    problem = get_problem(cases[0])
    kernel = problem.newton()
    x_rest = rest_point(problem, cases[0], tol)
    params = [problem.parameters(c) for c in cases]
    out = {}
    best = np.inf
    for _ in range(repeats):
        times, ok = [], 0
        for p in params:
            t0 = time.perf_counter()
            raw = kernel.raw(x_rest, p, tol)
            certified = problem.judge(*raw[3], tol=tol)[0]
            times.append(time.perf_counter() - t0)
            ok += certified
        best = min(best, float(np.median(times)))
    out["kernel_s"], out["kernel_certified"] = best, ok
    for solver in ("newton", "ipopt"):
        best = np.inf
        for _ in range(repeats):
            times, fell_back = [], 0
            for c in cases:
                t0 = time.perf_counter()
                r = moorsolve.solve(c, solver=solver, tol=tol)
                times.append(time.perf_counter() - t0)
                fell_back += r.solver != solver
            best = min(best, float(np.median(times)))
        out[f"solve_{solver}_s"], out[f"{solver}_fell_back"] = best, fell_back
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--loads", type=int, default=60)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--tol", type=float, default=1e-9)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(15)
    report = {"machine": platform.platform(), "python": platform.python_version(),
              "loads": args.loads, "repeats": args.repeats, "tol": args.tol, "scenes": {}}
    for name, (path, headings, speeds) in SCENES.items():
        base = moorsolve.load_case(path)
        draws = [(rng.uniform(*headings), rng.uniform(*speeds)) for _ in range(args.loads)]
        with_c = [loaded(base, h, v) for h, v in draws]
        without = [loaded(without_contacts(base), h, v) for h, v in draws]
        # Build and compile both problems before timing (a sweep does it once).
        for c in (with_c[0], without[0]):
            moorsolve.solve(c, solver="newton", tol=args.tol)
            moorsolve.solve(c, solver="ipopt", tol=args.tol)
        a = time_scene(with_c, args.repeats, args.tol)
        b = time_scene(without, args.repeats, args.tol)
        ratios = {k: a[f"{k}_s"] / b[f"{k}_s"] for k in ("kernel", "solve_newton",
                                                         "solve_ipopt")}
        report["scenes"][name] = {"with_contacts": a, "without_contacts": b,
                                  "ratio": ratios}
        print(f"{name}: {args.loads} loads, median per solve (contacts / none = ratio)")
        for key, label in (("kernel", "Newton kernel"), ("solve_newton", "solve(newton)"),
                           ("solve_ipopt", "solve(ipopt)")):
            print(f"  {label:<15} {a[key + '_s'] * 1e3:8.3f} ms / {b[key + '_s'] * 1e3:8.3f} ms"
                  f" = {ratios[key]:5.2f}x")
        print(f"  kernel certified {a['kernel_certified']}/{args.loads} with contacts, "
              f"{b['kernel_certified']}/{args.loads} without; newton fell back "
              f"{a['newton_fell_back']} / {b['newton_fell_back']} times")
    (HERE / "berth_results.json").write_text(json.dumps(report, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
