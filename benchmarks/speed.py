"""Speed where users feel it, beside MoorPy in the same run, as ratios.

    PYTHONBREAKPOINT=0 python benchmarks/speed.py [--quick] [--skip dask scaling]
        [--out benchmarks/speed_results.json]

Needs the ``bench`` extra (MoorPy 1.3.0). Every moorsolve number is a *full* ``solve()``
returning a ``Result`` (certificate, stability, legs and profiles on demand) from the rest
state, as a user calls it; MoorPy's is ``solveEquilibrium`` at 1e-4 m from the case
position, on the same loads. Each time is taken as wall time and as the process's CPU time
(``time.process_time``): on a shared machine the CPU time is what one process spends, the
wall time also what the others took from it. Medians; ratios are MoorPy / moorsolve.

Sections:

1. start-up: ``import moorsolve``, ``moorsolve --help`` and a first CLI solve against
   ``python -c pass`` and ``import moorpy`` (benchmarks/startup.py);
2. single solves, seeded random constant loads, per scene: the 12-chain dock, the
   OC4-DeepCwind semi and the IEA-15 MW VolturnUS-S (surge, sway, yaw), the OC3 spar (six
   DOFs) and the OC3 spar held (only its three lines solved); columns Newton and IPOPT, each
   with the audit (the default) and without (``audit=False``), and the compiled kernel alone;
   timed in rounds that interleave MoorPy and every column (:data:`ROUNDS`);
3. a load table: 10,000 distinct constant loads on the dock through
   ``moorsolve.sweep(case, table=...)`` on two threads, per point against MoorPy per load;
   peak memory in a fresh process;
4. Dask: the same table on a ``distributed.LocalCluster`` of two single-threaded workers
   against one and two local threads (where a cluster starts to pay);
5. scaling: one body on N lines round a circle, N up to 500: the first solve (problem build
   included, the kernel's compile in the background), a solve afterwards (interpreted, and
   compiled where the compile finished within the budget), the compile itself, peak memory
   of a fresh process, and MoorPy per solve.

Timings on a shared two-core machine are noisy: quote the ratios, and re-run before quoting.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

os.environ.setdefault("PYTHONBREAKPOINT", "0")
HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path[:0] = [str(HERE), str(ROOT)]

import numpy as np  # noqa: E402

import moorsolve  # noqa: E402
from moorsolve.model import BodyLoads  # noqa: E402
from peer_moorpy import moorpy_system, with_constant_force  # noqa: E402
from peer_moorpy_network import NetworkScene, without_extras  # noqa: E402

MOORPY_TOL = 1e-4
SEED = 16


# ---- timing --------------------------------------------------------------------------------


class Clock:
    """Wall and CPU time of each timed call."""

    def __init__(self):
        self.wall, self.cpu = [], []

    def __enter__(self):
        self._w, self._c = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc):
        self.wall.append(time.perf_counter() - self._w)
        self.cpu.append(time.process_time() - self._c)

    def medians(self) -> dict:
        return {"wall_s": statistics.median(self.wall), "cpu_s": statistics.median(self.cpu),
                "n": len(self.wall)}


def ratios(peer: dict, ours: dict) -> dict:
    return {"wall": peer["wall_s"] / ours["wall_s"], "cpu": peer["cpu_s"] / ours["cpu_s"]}


# ---- scenes ---------------------------------------------------------------------------------


def _six(case, force):
    body = dataclasses.replace(case.bodies[0], loads=BodyLoads(force=tuple(force)))
    return dataclasses.replace(case, bodies=(body,), source=None)


def scenes() -> dict:
    """name -> (base case, load maker, loads maker, peer kind)."""
    dock = moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml")
    oc4 = moorsolve.load_case(ROOT / "cases" / "oc4_semi.yaml")
    volt = moorsolve.load_case(ROOT / "cases" / "volturnus_s.yaml")
    spar = without_extras(moorsolve.load_case(ROOT / "cases" / "oc3_spar.yaml"))
    held = dataclasses.replace(spar, bodies=(dataclasses.replace(spar.bodies[0], free=()),))

    def planar(max_force, max_moment):
        def draw(rng):
            f, a = rng.uniform(0.1, 1.0) * max_force, rng.uniform(0, 2 * math.pi)
            return (f * math.cos(a), f * math.sin(a), rng.uniform(-1, 1) * max_moment)
        return draw

    def turbine(rng):     # thrust, side force and yaw moment, as benchmarks/network.py
        return (rng.uniform(2e5, 1.5e6), rng.uniform(-3e5, 3e5), 0.0, 0.0, 0.0,
                rng.uniform(-3e6, 3e6))

    return {
        "dock": (with_constant_force(dock, (0, 0, 0)), with_constant_force,
                 planar(9e6, 5e7), "legs"),
        "oc4_semi": (with_constant_force(oc4, (0, 0, 0)), with_constant_force,
                     planar(1.5e6, 5e6), "legs"),
        "volturnus_s": (with_constant_force(volt, (0, 0, 0)), with_constant_force,
                        planar(4e6, 2e7), "legs"),
        "oc3_spar": (spar, _six, turbine, "network"),
        "oc3_spar_held": (held, _six, turbine, "network"),
    }


def draw_loads(case, make, draw, n, rng) -> list:
    """``n`` loads moorsolve finds a certified equilibrium for (others are redrawn)."""
    loads = []
    while len(loads) < n:
        load = draw(rng)
        try:
            moorsolve.solve(make(case, load), solver="newton", audit=False)
        except moorsolve.ConvergenceError:
            continue
        loads.append(load)
    return loads


COLUMNS = {
    "newton": {"solver": "newton"},
    "newton, no audit": {"solver": "newton", "audit": False},
    "ipopt": {"solver": "ipopt"},
    "ipopt, no audit": {"solver": "ipopt", "audit": False},
}


def time_solves(case, make, loads, options, clock: Clock) -> None:
    cases = [make(case, load) for load in loads]
    for c in cases:
        with clock:
            moorsolve.solve(c, **options)


def time_kernel(case, make, loads, clock: Clock) -> None:
    from moorsolve.solve.assembly.cache import get_problem
    from moorsolve.solve.equilibrium import rest_point
    cases = [make(case, load) for load in loads]
    problem = get_problem(cases[0])
    kernel = problem.newton()
    kernel.wait_compiled()
    x0 = rest_point(problem, cases[0], 1e-9, kernel)
    params = [problem.parameters(c) for c in cases]
    for p in params:
        with clock:
            kernel.raw(x0, p, 1e-9)


def time_moorpy(case, make, loads, kind, clock: Clock) -> None:
    if kind == "legs":
        peer = moorpy_system(make(case, loads[0]), tol=MOORPY_TOL)
        for load in loads:
            peer.set_force(load)
            peer.reset()
            with clock:
                peer.solve(from_rest=False)
    else:
        for load in loads:
            scene = NetworkScene(make(case, load))
            with clock:
                scene.solve(tol=MOORPY_TOL, maxIter=2000)


def wait_steady(case) -> None:
    """The steady state of a process that solves the scene repeatedly: the Newton kernel,
    IPOPT's functions (a process compiles them after a few solves) and the closed-form
    audit's checks compiled."""
    from moorsolve.audit import closed_form as audit_closed_form
    from moorsolve.solve.assembly.cache import get_problem
    problem = get_problem(case)
    if problem._newton is not None:
        problem._newton.wait_compiled()
    problem.ipopt_solvers.wait_compiled()
    audit_closed_form.wait_compiled(len(case.lines))


#: Rounds of a scene's single solves: each times MoorPy, the kernel and every column on
#: every ROUNDS-th load, so a drift of the machine's speed (tens of per cent within a minute
#: on a shared machine) falls on the peer and on moorsolve alike.
ROUNDS = 6


def single_solves(n_loads: int) -> dict:
    out = {}
    rng = np.random.default_rng(SEED)
    for name, (case, make, draw, kind) in scenes().items():
        loads = draw_loads(case, make, draw, n_loads, rng)
        for options in COLUMNS.values():                 # build (and compile) first
            moorsolve.solve(make(case, loads[0]), **options)
        wait_steady(make(case, loads[0]))
        clocks = {column: Clock() for column in ("moorpy", "kernel", *COLUMNS)}
        for k in range(ROUNDS):
            part = loads[k::ROUNDS]
            time_moorpy(case, make, part, kind, clocks["moorpy"])
            time_kernel(case, make, part, clocks["kernel"])
            for column, options in COLUMNS.items():
                time_solves(case, make, part, options, clocks[column])
        row = {column: clock.medians() for column, clock in clocks.items()}
        row["loads"] = len(loads)
        for column in ("kernel", *COLUMNS):
            row[column]["ratio"] = ratios(row["moorpy"], row[column])
        out[name] = row
        print(f"  {name:14s} MoorPy {row['moorpy']['cpu_s'] * 1e3:8.2f} ms cpu  " + "  ".join(
            f"{c} {row[c]['cpu_s'] * 1e3:.3f} ms ({row[c]['ratio']['cpu']:.0f}x, wall "
            f"{row[c]['ratio']['wall']:.0f}x)" for c in ("kernel", *COLUMNS)), flush=True)
    return out


# ---- load tables ----------------------------------------------------------------------------


def dock_table(n: int, seed: int = SEED):
    import pandas as pd
    rng = np.random.default_rng(seed)
    force = rng.uniform(0.1, 1.0, n) * 9e3            # kN
    heading = rng.uniform(0, 2 * math.pi, n)
    return pd.DataFrame({"body.loads.force[0] [kN]": force * np.cos(heading),
                         "body.loads.force[1] [kN]": force * np.sin(heading),
                         "body.loads.force[2] [kN*m]": rng.uniform(-5e4, 5e4, n)})


def dock_for_tables():
    """The dock with a constant force (and no flows) as case-file data, so that a table
    edits it by path."""
    import yaml
    data = yaml.safe_load((ROOT / "cases" / "floating_dock.yaml").read_text())
    for flow in ("wind", "current", "waves"):
        data["environment"].pop(flow, None)
    data["body"]["loads"] = {"force": [0.0, 0.0, 0.0]}
    return moorsolve.load_case(data)


TABLE_MEMORY = textwrap.dedent("""
    import sys
    sys.path[:0] = {paths!r}
    import speed
    case = speed.dock_for_tables()
    table = speed.dock_table({n})
    moorsolve = speed.moorsolve
    moorsolve.sweep(case, table=table.head(64))           # build and compile
    speed.wait_steady(case)
    import time
    t0 = time.perf_counter()
    result = moorsolve.sweep(case, table=table, workers=2)
    elapsed = time.perf_counter() - t0
    with open("/proc/self/status") as f:
        peak = next(int(l.split()[1]) for l in f if l.startswith("VmHWM:"))
    import json
    print(json.dumps({{"elapsed_s": elapsed, "peak_rss_kB": peak,
                      "converged": int(result["converged"].sum()),
                      "newton": int((result["solver"] == "newton").sum())}}))
""")


def load_table(n_rows: int, n_peer: int) -> dict:
    case = dock_for_tables()
    table = dock_table(n_rows)
    moorsolve.sweep(case, table=table.head(64))
    wait_steady(case)
    runs = {}
    for workers in (1, 2):
        t0 = time.perf_counter()
        c0 = time.process_time()
        result = moorsolve.sweep(case, table=table, workers=workers)
        runs[workers] = {"wall_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
                         "converged": int(result["converged"].sum()),
                         "newton": int((result["solver"] == "newton").sum())}
    loads = [tuple(1e3 * v for v in row) for row in table.head(n_peer).itertuples(index=False)]
    base = with_constant_force(case, (0, 0, 0))
    clock = Clock()
    time_moorpy(base, with_constant_force, loads, "legs", clock)
    peer = clock.medians()
    mem = _subprocess_json(TABLE_MEMORY.format(paths=[str(HERE), str(ROOT)], n=n_rows))
    out = {"rows": n_rows, "threads": runs, "moorpy_per_load": peer, "memory": mem}
    per_point = runs[2]["wall_s"] / n_rows
    out["ratio_per_point_wall"] = peer["wall_s"] / per_point
    out["ratio_per_point_cpu"] = peer["cpu_s"] / (runs[2]["cpu_s"] / n_rows)
    print(f"  {n_rows} rows: 1 thread {runs[1]['wall_s']:.2f} s, 2 threads "
          f"{runs[2]['wall_s']:.2f} s ({per_point * 1e6:.0f} us a point; MoorPy "
          f"{peer['wall_s'] * 1e3:.1f} ms a load: {out['ratio_per_point_wall']:.0f}x wall, "
          f"{out['ratio_per_point_cpu']:.0f}x cpu); peak RSS "
          f"{mem['peak_rss_kB'] / 1024:.0f} MB in a fresh process", flush=True)
    return out


def dask_table(n_rows: int) -> dict:
    from distributed import Client, LocalCluster
    case = dock_for_tables()
    table = dock_table(n_rows)
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    out = {"rows": n_rows}
    t0 = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster, Client(cluster) as client:
        out["cluster_start_s"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        moorsolve.sweep(case, table=table, scheduler=client)
        out["first_sweep_s"] = time.perf_counter() - t0     # each worker builds, compiles
        t0 = time.perf_counter()
        moorsolve.sweep(case, table=table, scheduler=client)
        out["sweep_s"] = time.perf_counter() - t0
    local = {}
    for workers in (1, 2):
        t0 = time.perf_counter()
        moorsolve.sweep(case, table=table, workers=workers)
        local[workers] = time.perf_counter() - t0
    out["local_s"] = local
    print(f"  {n_rows} rows: LocalCluster (2 workers) start {out['cluster_start_s']:.1f} s, "
          f"first sweep {out['first_sweep_s']:.2f} s, then {out['sweep_s']:.2f} s; local "
          f"threads 1: {local[1]:.2f} s, 2: {local[2]:.2f} s", flush=True)
    return out


# ---- scaling --------------------------------------------------------------------------------

SCALING_PROBE = textwrap.dedent("""
    import json, os, sys, time
    sys.path[:0] = {paths!r}
    t0 = time.perf_counter()
    import moorsolve
    from run import ring_case
    from moorsolve.solve.assembly.cache import get_problem
    case = ring_case({n})
    t1 = time.perf_counter()
    first = moorsolve.solve(case, solver="newton", audit=False)
    t2 = time.perf_counter()
    from moorsolve.solve.kernels.newton import COMPILE_MAX_UNKNOWNS
    kernel = get_problem(case).newton()
    compiles = get_problem(case).n_x <= COMPILE_MAX_UNKNOWNS
    compiled_at_first = kernel.compiled
    times = []
    for _ in range(5):
        t = time.perf_counter(); moorsolve.solve(case, solver="newton", audit=False)
        times.append(time.perf_counter() - t)
    interpreted = sorted(times)[2] if not compiled_at_first else None
    t3 = time.perf_counter()
    ready = kernel.wait_compiled({budget}) if compiles else False
    compile_wait = time.perf_counter() - t3
    compiled = None
    if ready:
        times = []
        for _ in range(5):
            t = time.perf_counter(); moorsolve.solve(case, solver="newton", audit=False)
            times.append(time.perf_counter() - t)
        compiled = sorted(times)[2]
    with open("/proc/self/status") as f:
        peak = next(int(l.split()[1]) for l in f if l.startswith("VmHWM:"))
    print(json.dumps(dict(lines={n}, import_s=t1 - t0, first_solve_s=t2 - t1,
                          solver=first.solver, cached_library=compiled_at_first,
                          compiles=compiles,
                          interpreted_s=interpreted, compiled_s=compiled, ready=ready,
                          compile_wait_s=compile_wait, peak_rss_kB=peak)))
""")


def scaling(sizes, budget_s: float, moorpy_max: int) -> list:
    from run import ring_case
    rows = []
    for n in sizes:
        with tempfile.TemporaryDirectory() as cache:
            row = _subprocess_json(SCALING_PROBE.format(paths=[str(HERE), str(ROOT)], n=n,
                                                        budget=budget_s),
                                   env={"MOORSOLVE_CACHE_DIR": cache,
                                        "MOORSOLVE_COMPILE": "background"})
        if n <= moorpy_max:
            case = ring_case(n)
            force = case.body.loads.force
            loads = [tuple(f * (0.6 + 0.4 * k / 2) for f in force) for k in range(3)]
            clock = Clock()
            time_moorpy(case, with_constant_force, loads, "legs", clock)
            row["moorpy_s"] = clock.medians()["wall_s"]
        rows.append(row)
        compile_note = (f"{_ms(row['compiled_s'])} compiled (compile ready {row['ready']} "
                        f"after {row['compile_wait_s']:.1f} s more)" if row["compiles"]
                        else "never compiled (past COMPILE_MAX_UNKNOWNS)")
        print(f"  {n:4d} lines: first solve {row['first_solve_s']:.2f} s (build included"
              f"{', kernel compiling in the background' if row['compiles'] else ''}), then "
              f"{_ms(row['interpreted_s'])} interpreted, {compile_note}, "
              f"peak RSS {row['peak_rss_kB'] / 1024:.0f} MB"
              + (f"; MoorPy {row['moorpy_s'] * 1e3:.0f} ms" if "moorpy_s" in row else ""),
              flush=True)
    return rows


def _ms(t):
    return "-" if t is None else f"{t * 1e3:.2f} ms"


def _subprocess_json(code: str, env: dict | None = None) -> dict:
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                          text=True, env={**os.environ, **(env or {})}, check=False)
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr[-3000:])
    return json.loads(proc.stdout.strip().splitlines()[-1])


def plot_scaling(rows, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = [r["lines"] for r in rows]
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.loglog(n, [r["first_solve_s"] for r in rows], "o-", label="first solve (build incl.)")
    a.loglog(n, [r["interpreted_s"] or np.nan for r in rows], "s-",
             label="solve, kernel interpreted")
    a.loglog(n, [r["compiled_s"] or np.nan for r in rows], "^-", label="solve, kernel compiled")
    a.loglog(n, [r.get("moorpy_s", np.nan) for r in rows], "x--", label="MoorPy 1.3.0 solve")
    a.loglog(n, [rows[-1]["first_solve_s"] * k / n[-1] for k in n], ":", color="grey",
             label="linear")
    a.set_xlabel("lines")
    a.set_ylabel("time [s]")
    a.legend(fontsize=8)
    a.grid(True, which="both", alpha=0.3)
    b.plot(n, [r["peak_rss_kB"] / 1024 for r in rows], "o-")
    b.set_xlabel("lines")
    b.set_ylabel("peak RSS of the process [MB]")
    b.grid(True, alpha=0.3)
    fig.suptitle("One body on N lines: time and memory (benchmarks/speed.py)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


# ---- main -----------------------------------------------------------------------------------


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="20 loads per scene, a 2,000-row table, scaling to 192 lines")
    parser.add_argument("--skip", nargs="*", default=[],
                        choices=["startup", "solves", "table", "dask", "scaling"])
    parser.add_argument("--out", default=str(HERE / "speed_results.json"))
    args = parser.parse_args(argv)
    n_loads = 20 if args.quick else 60
    n_rows = 2_000 if args.quick else 10_000
    sizes = (12, 48, 192) if args.quick else (12, 48, 96, 192, 384, 500)
    import moorpy
    out = {"machine": f"{platform.machine()}, {os.cpu_count()} cpus",
           "python": platform.python_version(),
           "moorpy": getattr(moorpy, "__version__", "1.3.0"),
           "load_average_at_start": os.getloadavg(), "moorpy_tol_m": MOORPY_TOL}
    if "startup" not in args.skip:
        print("== start-up (best of 7, fresh interpreters)")
        import startup
        out["startup"] = startup.measure()
        for name, seconds in out["startup"].items():
            print(f"  {name:<44} {seconds * 1e3:8.1f} ms")
    if "solves" not in args.skip:
        print(f"== single solves, full Result, from rest, median of {n_loads} loads")
        out["solves"] = single_solves(n_loads)
    if "table" not in args.skip:
        print("== load table (dock, constant loads)")
        out["table"] = load_table(n_rows, 30)
    if "dask" not in args.skip:
        print("== the table on a Dask LocalCluster against local threads")
        out["dask"] = dask_table(n_rows)
    if "scaling" not in args.skip:
        print("== scaling: one body on N lines")
        out["scaling"] = scaling(sizes, budget_s=300.0, moorpy_max=192)
        plot_scaling(out["scaling"], ROOT / "docs" / "scaling.png")
    Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
