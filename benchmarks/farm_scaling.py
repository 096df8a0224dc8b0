"""Wind farms of 4 to 100 bodies against NREL MoorPy: time per full equilibrium, one run.

    PYTHONBREAKPOINT=0 python benchmarks/farm_scaling.py [--quick] [--out FILE.json]

Needs the ``bench`` extra (MoorPy 1.3.0). The farms are ``n`` x ``n`` grids of
VolturnUS-S-like semis free in six DOFs, three chains each and shared lines between
neighbours (:mod:`farm`). For each size: the first solve in the process (the problem built
from nothing: graph, kernel or sparse path, post function; a compile of the dense kernel,
which only the 4-body farm takes, runs in the background and is waited for before the
timed solves), then the median full ``moorsolve.solve(solver="newton")`` Result (certificate,
stability verdict, audit) over seeded thrusts from rest, wall and CPU time, beside
MoorPy's ``solveEquilibrium`` at 1e-4 m from rest on the same thrusts; agreement of the
two at a tight tolerance on the small farms; and the growth exponent of the time between
9 and 100 bodies. Writes ``benchmarks/farm_results.json``. Timings on a shared 2-core
machine are noisy: read the ratios.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import os
import statistics
import sys
import time
import warnings
from pathlib import Path

os.environ.setdefault("PYTHONBREAKPOINT", "0")
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
from farm import farm_dict
from peer_moorpy_network import NetworkScene

import moorsolve

HERE = Path(__file__).resolve().parent
MOORPY_TOL = 1e-4
SEED = 5
SIZES = (2, 3, 4, 6, 10)


def thrust_cases(n: int, count: int, rng) -> list:
    """``count`` farms of ``n`` x ``n`` with every platform under its own thrust of 1 to
    2 MN toward -30..30 deg."""
    out = []
    for _ in range(count):
        data = farm_dict(n)
        for body in data["bodies"]:
            size, angle = rng.uniform(1.0e6, 2.0e6), math.radians(rng.uniform(-30, 30))
            body["loads"]["force"] = [size * math.cos(angle), size * math.sin(angle),
                                      0.0, 0.0, 0.0, 0.0]
        out.append(moorsolve.load_case(data))
    return out


def wait_steady(case) -> None:
    """The steady state of a process that solves the farm repeatedly: the dense Newton
    kernel (the 4-body farm's; larger farms take the sparse path, nothing to compile) and
    the closed-form audit's checks (up to 128 lines) compiled. IPOPT is not used."""
    from moorsolve.audit import closed_form as audit_closed_form
    from moorsolve.solve.assembly.cache import get_problem
    problem = get_problem(case)
    problem.newton().wait_compiled()
    audit_closed_form.wait_compiled(len(case.lines))


def time_moorsolve(cases) -> dict:
    t0 = time.perf_counter()
    first = moorsolve.solve(cases[0], solver="newton")
    first_s = time.perf_counter() - t0
    wait_steady(cases[0])
    wall, cpu, ok = [], [], 0
    for case in cases:
        t0, c0 = time.perf_counter(), time.process_time()
        result = moorsolve.solve(case, solver="newton")
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        ok += bool(result.converged and result.solver == "newton"
                   and result.stability.stable)
    return {"first_s": first_s, "median_wall_s": statistics.median(wall),
            "median_cpu_s": statistics.median(cpu), "ok": ok, "n": len(cases),
            "iterations": first.iterations}


def time_moorpy(cases) -> dict:
    wall, cpu, ok = [], [], 0
    for case in cases:
        scene = NetworkScene(case)
        t0, c0 = time.perf_counter(), time.process_time()
        ok += scene.solve(tol=MOORPY_TOL, maxIter=2000)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return {"median_wall_s": statistics.median(wall), "median_cpu_s": statistics.median(cpu),
            "ok": ok, "n": len(cases)}


def agreement(case) -> dict:
    """Largest pose and relative tension difference, both solved tightly."""
    result = moorsolve.solve(case, solver="newton", tol=1e-12)
    peer = NetworkScene(case)
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        peer.solve(tol=1e-9, maxIter=2000)
    poses = peer.poses()
    worst = 0.0
    for b in result.bodies:
        ours = np.array([b["x_m"], b["y_m"], b["z_m"]] + [math.radians(b[k]) for k in
                                                         ("roll_deg", "pitch_deg", "yaw_deg")])
        worst = max(worst, float(np.max(np.abs(ours - poses[b["name"]]))))
    t_max = max(leg.fairlead_tension_N for leg in result.legs)
    worst_t = max(max(abs(lr.anchor_tension_N - ta), abs(lr.fairlead_tension_N - tb))
                  for lr, (ta, tb) in zip(result.legs, peer.tensions()))
    return {"pose": worst, "tension_relative": worst_t / t_max}


def growth(rows: dict, key: str, a: int = 9, b: int = 100) -> float | None:
    """The exponent ``k`` of ``time ~ bodies^k`` between ``a`` and ``b`` bodies."""
    if str(a) not in rows or str(b) not in rows:
        return None
    ta, tb = rows[str(a)][key], rows[str(b)][key]
    return math.log(tb / ta) / math.log(b / a)


def farm_table(n: int, rows: int, rng):
    """A load table of ``rows`` rows over an ``n`` x ``n`` farm: every platform's thrust
    (x and y) per row."""
    import pandas as pd
    case = moorsolve.load_case(farm_dict(n))
    columns = {}
    for body in case.bodies:
        size = rng.uniform(1.0e3, 2.0e3, rows)
        angle = np.radians(rng.uniform(-30, 30, rows))
        columns[f"bodies[{body.name}].loads.force[0] [kN]"] = size * np.cos(angle)
        columns[f"bodies[{body.name}].loads.force[1] [kN]"] = size * np.sin(angle)
    return case, pd.DataFrame(columns)


def dask_farm_table(n: int, rows: int, rng) -> dict:
    """The farm's load table on a ``distributed.LocalCluster`` of two single-threaded
    worker processes against one and two local threads."""
    from distributed import Client, LocalCluster
    case, table = farm_table(n, rows, rng)
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [str(HERE.parent)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep)
                              if p])
    out = {"bodies": n * n, "rows": rows}
    t0 = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster, Client(cluster) as client:
        out["cluster_start_s"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        first = moorsolve.sweep(case, table=table, scheduler=client)
        out["first_sweep_s"] = time.perf_counter() - t0     # each worker builds the problem
        t0 = time.perf_counter()
        moorsolve.sweep(case, table=table, scheduler=client)
        out["sweep_s"] = time.perf_counter() - t0
    out["converged"] = int(first["converged"].sum())
    out["stable"] = int(first["stable"].sum())
    local = {}
    moorsolve.sweep(case, table=table.head(2), workers=1)    # build in this process
    for workers in (1, 2):
        t0 = time.perf_counter()
        moorsolve.sweep(case, table=table, workers=workers)
        local[str(workers)] = time.perf_counter() - t0
    out["local_s"] = local
    print(f"  {n * n}-body farm, {rows} rows: LocalCluster (2 workers) start "
          f"{out['cluster_start_s']:.1f} s, first sweep {out['first_sweep_s']:.2f} s, then "
          f"{out['sweep_s']:.2f} s ({out['converged']} converged, {out['stable']} stable); "
          f"local threads 1: {local['1']:.2f} s, 2: {local['2']:.2f} s", flush=True)
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="3 loads a size, not 7")
    parser.add_argument("--out", default=str(HERE / "farm_results.json"))
    parser.add_argument("--dask", type=int, default=0, metavar="ROWS",
                        help="also a 36-body farm's load table of ROWS rows on a Dask "
                             "LocalCluster (2 workers) against local threads")
    parser.add_argument("--sizes", type=int, nargs="*", default=list(SIZES),
                        help="farm sides n (n x n bodies)")
    args = parser.parse_args(argv)
    count = 3 if args.quick else 7
    rng = np.random.default_rng(SEED)
    rows = {}
    print(f"{'bodies':>6} {'unknowns':>8} {'first':>8} {'moorsolve':>10} {'MoorPy':>9} "
          f"{'ratio':>7}  agreement (pose, tension)")
    for n in args.sizes:
        cases = thrust_cases(n, count, rng)
        ours = time_moorsolve(cases)
        peer = time_moorpy(cases[:max(1, count if n < 10 else 2)])
        from moorsolve.solve.assembly.cache import get_problem
        problem = get_problem(cases[0])
        row = {"bodies": n * n, "lines": len(cases[0].lines), "unknowns": problem.n_x,
               "path": type(problem.newton()).__name__, **{f"moorsolve_{k}": v
                                                           for k, v in ours.items()},
               **{f"moorpy_{k}": v for k, v in peer.items()}}
        row["ratio_cpu"] = peer["median_cpu_s"] / ours["median_cpu_s"]
        row["ratio_wall"] = peer["median_wall_s"] / ours["median_wall_s"]
        if n <= 3:
            row["agreement"] = agreement(cases[0])
        rows[str(n * n)] = row
        agree = row.get("agreement")
        print(f"{n * n:>6} {problem.n_x:>8} {ours['first_s']:>7.2f}s "
              f"{ours['median_cpu_s'] * 1e3:>8.1f}ms {peer['median_cpu_s'] * 1e3:>7.0f}ms "
              f"{row['ratio_cpu']:>6.0f}x  "
              + (f"{agree['pose']:.1e} m, {agree['tension_relative']:.1e}" if agree else ""),
              flush=True)
    summary = {"growth_moorsolve_9_100": growth(rows, "moorsolve_median_cpu_s"),
               "growth_moorpy_9_100": growth(rows, "moorpy_median_cpu_s")}
    if summary["growth_moorsolve_9_100"] is not None:
        print(f"time ~ bodies^k from 9 to 100 bodies: moorsolve k = "
              f"{summary['growth_moorsolve_9_100']:.2f}, MoorPy k = "
              f"{summary['growth_moorpy_9_100']:.2f}")
    if args.dask:
        summary["dask"] = dask_farm_table(6, args.dask, rng)
    elif Path(args.out).exists():
        # A run without --dask keeps the table's figures of the last run that had it.
        last = json.loads(Path(args.out).read_text()).get("dask")
        if last is not None:
            summary["dask"] = last
    Path(args.out).write_text(json.dumps({"moorpy_tol_m": MOORPY_TOL, "loads": count,
                                          "sizes": rows, **summary}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
