"""Sweep throughput (points per second) of the floating dock, locally and on Dask.

    PYTHONPATH=. python benchmarks/sweep_throughput.py [--headings 36] [--speeds 50]
        [--repeats 3] [--scheduler tcp://HOST:PORT] [--no-cluster]

The grid turns the typhoon (wind, current and waves together, one zipped axis) over
``--headings`` headings and sets ``--speeds`` wind speeds from 5 to 50 m/s. Timed: the
in-memory sweep on 1 and 2 local threads, the same writing a CSV file, and a
``distributed.LocalCluster`` of 2 single-threaded worker processes on loopback (started
once; its first sweep, which builds and compiles the problem on each worker, is reported
apart). The best of ``--repeats`` runs is reported. Results go to
``benchmarks/sweep_results.json``. Timings depend on the machine and its load.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import platform
import sys
import tempfile
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import moorsolve  # noqa: E402

HEADING = ("environment.wind.toward_deg", "environment.current.toward_deg",
           "environment.waves.toward_deg")


def grid(n_headings: int, n_speeds: int) -> dict:
    headings = np.linspace(0, 360, n_headings, endpoint=False)
    return {HEADING: [(h, h, h) for h in headings],
            "environment.wind.speed": list(np.linspace(5.0, 50.0, n_speeds))}


def timed(fn, repeats: int) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--headings", type=int, default=36)
    parser.add_argument("--speeds", type=int, default=50)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--scheduler", default=None, help="also time an existing cluster")
    parser.add_argument("--no-cluster", action="store_true", help="skip the LocalCluster")
    args = parser.parse_args(argv)

    case = moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml")
    g = grid(args.headings, args.speeds)
    n = args.headings * args.speeds
    moorsolve.sweep(case, g, workers=1)                      # build and compile once
    rows = {}

    def report(name, seconds, table):
        ok = int(table["converged"].sum())
        rows[name] = {"seconds": seconds, "points_per_s": n / seconds, "converged": ok}
        print(f"{name:<42} {seconds:8.3f} s  {n / seconds:9.0f} points/s  "
              f"({ok}/{n} converged)", flush=True)

    print(f"dock, {args.headings} headings x {args.speeds} wind speeds = {n} points; "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    reference = None
    for workers in (1, 2):
        t, table = timed(lambda: moorsolve.sweep(case, g, workers=workers), args.repeats)
        report(f"local, {workers} thread(s), in memory", t, table)
        reference = table if reference is None else reference
    with tempfile.TemporaryDirectory() as tmp:
        t, table = timed(lambda: moorsolve.sweep(case, g, workers=2, overwrite=True,
                                                 output=pathlib.Path(tmp) / "r.csv"),
                         args.repeats)
        report("local, 2 threads, to CSV (chunks fsynced)", t, table)

    cols = [c for c in reference.columns if c.endswith("tension_N")]

    def remote(name, scheduler):
        t0 = time.perf_counter()
        first = moorsolve.sweep(case, g, scheduler=scheduler)
        rows[name + " (first sweep)"] = {"seconds": time.perf_counter() - t0}
        print(f"{name + ' (first sweep)':<42} {time.perf_counter() - t0:8.3f} s", flush=True)
        t, table = timed(lambda: moorsolve.sweep(case, g, scheduler=scheduler), args.repeats)
        report(name, t, table)
        diff = np.max(np.abs(table[cols].to_numpy() - reference[cols].to_numpy())
                      / np.abs(reference[cols].to_numpy()).max(axis=1, keepdims=True))
        print(f"{'':<42} largest tension difference to local: {diff:.1e} of the largest")
        del first

    if not args.no_cluster:
        from distributed import Client, LocalCluster
        os.environ["PYTHONPATH"] = os.pathsep.join(
            [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          host="127.0.0.1", dashboard_address=None) as cluster, \
                Client(cluster) as client:
            remote("LocalCluster, 2 worker processes", client)
    if args.scheduler:
        remote(f"cluster {args.scheduler}", args.scheduler)

    out = {"machine": {"cores": os.cpu_count(), "python": platform.python_version(),
                       "load_average": os.getloadavg()[0]},
           "grid": {"headings": args.headings, "speeds": args.speeds, "points": n},
           "runs": rows}
    (HERE / "sweep_results.json").write_text(json.dumps(out, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
