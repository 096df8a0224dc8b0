"""Every batch form of one structure beside MoorPy 1.3 in the same run, as ratios.

    PYTHONBREAKPOINT=0 python benchmarks/batches.py [--loads 400] [--rows 100000]
        [--out benchmarks/batches_results.json]

The dock (12 chains) with a constant force and no flows, under seeded random loads that
moorsolve certifies. Each moorsolve figure is a full, audited Newton ``Result`` (or a
sweep's row, which carries the certificate, the stability and the tensions):

1. a Python loop over ``case.with_values({"body.loads.force": f})`` and ``solve``;
2. a loop over cases loaded separately (``load_case(d)`` of a new dict each, loaded before
   the loop) and ``solve``; the same with ``load_case`` inside the loop; the same with IPOPT;
3. a grid ``sweep(case, {"body.loads.force": [[Fx, Fy, Mz], ...]})`` against a load table
   of the same loads (``sweep(case, table=...)``), two threads;
4. the whole command ``moorsolve sweep CASE --table LOADS -o OUT`` on ``--rows`` rows, CSV
   and Parquet, in a fresh process (start-up, reading and writing included): wall time,
   CPU time (user + system: above the wall time when both threads work) and peak RSS.

MoorPy's ``solveEquilibrium`` at 1e-4 m is timed on the same loads before and after the
moorsolve columns (a drift of a shared machine's speed falls on both); ratios are MoorPy's
median per load over moorsolve's time per point. Wall and CPU ratios are both given: on
a loaded machine the wall time also holds what other processes took.
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("PYTHONBREAKPOINT", "0")
HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path[:0] = [str(HERE), str(ROOT)]

import numpy as np  # noqa: E402
import yaml  # noqa: E402

import moorsolve  # noqa: E402
from peer_moorpy import with_constant_force  # noqa: E402
from speed import Clock, dock_for_tables, dock_table, time_moorpy, wait_steady  # noqa: E402

SEED = 23


def random_loads(n: int, rng) -> list:
    out = []
    while len(out) < n:
        f, a = rng.uniform(0.1, 1.0) * 9e6, rng.uniform(0, 2 * math.pi)
        out.append([f * math.cos(a), f * math.sin(a), rng.uniform(-1, 1) * 5e7])
    return out


def per_item(fn, n: int) -> dict:
    """Wall and CPU seconds per item of ``fn()``, which does ``n`` items."""
    w, c = time.perf_counter(), time.process_time()
    fn()
    return {"wall_s": (time.perf_counter() - w) / n, "cpu_s": (time.process_time() - c) / n}


def ratio(peer: dict, ours: dict) -> dict:
    return {"wall": peer["wall_s"] / ours["wall_s"], "cpu": peer["cpu_s"] / ours["cpu_s"]}


def moorpy_per_load(case, loads) -> dict:
    clock = Clock()
    time_moorpy(with_constant_force(case, (0, 0, 0)), with_constant_force,
                [tuple(f) for f in loads], "legs", clock)
    return clock.medians()


def loops(case, loads) -> dict:
    source = copy.deepcopy(dict(case.source))

    def data(f):
        d = copy.deepcopy(source)
        d["body"]["loads"]["force"] = list(f)
        return d

    dicts = [data(f) for f in loads]
    cases = [moorsolve.load_case(d) for d in dicts]
    out = {}

    def with_values():
        for f in loads:
            moorsolve.solve(case.with_values({"body.loads.force": f}), solver="newton")

    def separately_loaded():
        for c in cases:
            moorsolve.solve(c, solver="newton")

    def load_inside():
        for d in dicts:
            moorsolve.solve(moorsolve.load_case(d), solver="newton")

    def ipopt():
        for c in cases[:100]:
            moorsolve.solve(c, solver="ipopt")

    out["with_values + solve (newton)"] = per_item(with_values, len(loads))
    out["separately loaded cases, solve (newton)"] = per_item(separately_loaded, len(loads))
    out["solve(load_case(d)) (newton)"] = per_item(load_inside, len(loads))
    out["separately loaded cases, solve (ipopt)"] = per_item(ipopt, min(100, len(loads)))
    return out


def grids(case, loads) -> dict:
    import pandas as pd
    table = pd.DataFrame({f"body.loads.force[{i}]": [f[i] for f in loads] for i in range(3)})
    out = {}
    out["grid, one vector axis of forces (2 threads)"] = per_item(
        lambda: moorsolve.sweep(case, {"body.loads.force": loads}, workers=2), len(loads))
    out["load table of the same loads (2 threads)"] = per_item(
        lambda: moorsolve.sweep(case, table=table, workers=2), len(loads))
    return out


def command(rows: int, suffix: str, folder: Path) -> dict:
    """The sweep command on ``rows`` rows in a fresh process: wall, CPU and peak RSS."""
    case_file = folder / "dock.yaml"
    case_file.write_text(yaml.safe_dump(dict(dock_for_tables().source)))
    loads = folder / f"loads{suffix}"
    table = dock_table(rows, seed=SEED)
    if suffix == ".csv":
        table.to_csv(loads, index=False)
    else:
        table.to_parquet(loads, index=False)
    out = folder / f"out{suffix}"
    argv = [sys.executable, "-c",
            "import resource, sys, time; from moorsolve.cli import main; "
            "c = time.process_time(); s = main(sys.argv[1:]); "
            "u = resource.getrusage(resource.RUSAGE_SELF); "
            "print('STATS', u.ru_utime + u.ru_stime, u.ru_maxrss); sys.exit(s)",
            "sweep", str(case_file), "--table", str(loads), "-o", str(out), "--overwrite",
            "--quiet"]
    t0 = time.perf_counter()
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    cpu, rss = next(line.split()[1:] for line in done.stdout.splitlines()
                    if line.startswith("STATS"))
    return {"rows": rows, "wall_s": wall, "cpu_s": float(cpu), "peak_rss_MB":
            int(rss) / 1024, "per_row_wall_s": wall / rows, "per_row_cpu_s": float(cpu) / rows,
            "threads_busy": float(cpu) / wall}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--loads", type=int, default=400)
    parser.add_argument("--rows", type=int, default=100_000)
    parser.add_argument("--out", default=str(HERE / "batches_results.json"))
    args = parser.parse_args(argv)

    case = dock_for_tables()
    rng = np.random.default_rng(SEED)
    loads = random_loads(args.loads, rng)
    # Build, compile and reach the steady state first (as speed.py does).
    moorsolve.sweep(case, {"body.loads.force": loads[:70]})
    moorsolve.solve(case.with_values({"body.loads.force": loads[0]}), solver="ipopt")
    wait_steady(case)
    print(f"dock, {len(loads)} loads; {os.cpu_count()} cores, load average "
          f"{os.getloadavg()[0]:.1f}", flush=True)

    peer_loads = loads[:40]
    before = moorpy_per_load(case, peer_loads)
    ours = {**loops(case, loads), **grids(case, loads)}
    after = moorpy_per_load(case, peer_loads)
    peer = {k: statistics.mean([before[k], after[k]]) for k in ("wall_s", "cpu_s")}
    print(f"  MoorPy 1.3.0 at 1e-4 m: {peer['wall_s'] * 1e3:.1f} ms a load "
          f"(before {before['wall_s'] * 1e3:.1f}, after {after['wall_s'] * 1e3:.1f})")
    rows = {}
    for name, t in ours.items():
        rows[name] = {**t, "ratio": ratio(peer, t)}
        print(f"  {name:<46} {t['wall_s'] * 1e6:8.0f} us  {rows[name]['ratio']['wall']:6.0f}x "
              f"wall  {rows[name]['ratio']['cpu']:6.0f}x cpu", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for suffix in (".csv", ".parquet"):
            c = command(args.rows, suffix, Path(tmp))
            c["ratio_per_row"] = {"wall": peer["wall_s"] / c["per_row_wall_s"],
                                  "cpu": peer["cpu_s"] / c["per_row_cpu_s"]}
            rows[f"moorsolve sweep --table ({suffix[1:]})"] = c
            print(f"  command, {args.rows} rows {suffix[1:]:<8} {c['wall_s']:6.2f} s wall "
                  f"({c['per_row_wall_s'] * 1e6:.0f} us a row: {c['ratio_per_row']['wall']:.0f}x"
                  f" MoorPy), {c['cpu_s']:.2f} s CPU ({c['ratio_per_row']['cpu']:.0f}x), "
                  f"{c['threads_busy']:.2f} threads busy, peak RSS {c['peak_rss_MB']:.0f} MB",
                  flush=True)
    result = {"machine": {"platform": platform.platform(), "cores": os.cpu_count(),
                          "load_average": os.getloadavg()[0]},
              "moorpy_per_load": peer, "rows": rows}
    Path(args.out).write_text(json.dumps(result, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
