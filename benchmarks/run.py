"""moorsolve against NREL MoorPy: time per equilibrium, same scenes, same loads, one process.

    PYTHONBREAKPOINT=0 python benchmarks/run.py [--quick] [--out benchmarks/results.json]

Needs the ``bench`` extra (``pip install -e ".[bench]"``, MoorPy 1.3.0). Sections:

1. Agreement: each scene under one fixed constant load, moorsolve (tol 1e-12) against MoorPy
   at a tight step tolerance (1e-9 m): offsets and every fairlead and anchor tension; and the
   force MoorPy leaves unbalanced at its default tolerance (0.05 m).
2. Timing: per scene (the 12-chain dock, and the 3-chain Vida buoy with an elastic chain,
   see ``VIDA_CHAIN_EA``; both with their wind, current and drift replaced by a constant
   force) 100 random constant loads (seeded; any load moorsolve reports as an overload or
   without equilibrium is dropped and redrawn).
   Every column solves every load, from rest (body back at its case position) and warm
   (from the previous load's solution); the table gives the median time per solve and the
   ratio MoorPy(1e-4 m) / column in the same start mode. MoorPy's residual is the force it
   leaves unbalanced (its own catenary re-solved at 1e-10 m at its answer).
3. Scaling: one body on N = 3, 12, 48, 192 legs evenly spread round a circle.
4. Memory: peak RSS of a 10,000-point ``moorsolve.sweep`` in a fresh subprocess (Linux).

Adding a moorsolve column is one entry in ``COLUMNS`` (a name, a start mode, a function
``(bench_scene, loads, warm) -> Column``): e.g. ``solver="newton"`` is
``functools.partial(time_moorsolve, solve_kwargs={"solver": "newton"})``.

Timings on a shared 2-core machine are noisy: read the ratios, and re-run before quoting.
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import textwrap
import time
from dataclasses import dataclass, field
from pathlib import Path

os.environ.setdefault("PYTHONBREAKPOINT", "0")
# Run from a checkout without installing: this checkout's moorsolve, and the peer module.
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
import peer_moorpy
from peer_moorpy import compare, moorpy_system, with_constant_force

import moorsolve

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

#: MoorPy tolerance the issue's targets are stated at [m, step size].
MOORPY_TOL = 1e-4
#: MoorPy tolerance for the agreement check [m].
TIGHT_TOL = 1e-9
#: moorsolve's certified relative residual for the agreement check.
REFERENCE_TOL = 1e-12
SEED = 20240603


# ---- scenes and loads -----------------------------------------------------------------


@dataclass
class BenchScene:
    """A scene to time: the base case (constant force only) and its load envelope.

    ``max_force`` [N] and ``max_moment`` [N m] bound the random loads; ``check_load`` is
    the fixed load of the agreement check.
    """

    name: str
    case: moorsolve.Case
    max_force: float
    max_moment: float
    check_load: tuple

    def with_load(self, load) -> moorsolve.Case:
        return with_constant_force(self.case, load)


def _polar(force, toward_deg, moment=0.0):
    a = math.radians(toward_deg)
    return (force * math.cos(a), force * math.sin(a), moment)


#: Vida's chain as an elastic line for the timing runs: 25.4 kg/m in air is a studless
#: chain of nominal diameter about 35.7 mm (19.9 d^2 kg/m, d in mm), EA = 0.854e11 d^2 N
#: (the stiffness rule floating_dock.yaml uses) = 1.09e8 N. MoorPy has no inextensible
#: line: with the converter's near-rigid stand-in, its step-size test stops with residuals
#: up to ~1e10 N once a chain is pulled nearly straight , which
#: would time a different, failing problem.
VIDA_CHAIN_EA = 0.854e11 * 0.0357**2


def scenes() -> list[BenchScene]:
    """The timed scenes, each with its wind, current and drift replaced by a constant force."""
    dock = moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml")
    buoy = moorsolve.load_case(ROOT / "cases" / "buoy_vida.yaml")
    chain = dataclasses.replace(buoy.line_types["chain"], ea=VIDA_CHAIN_EA)
    elastic_buoy = dataclasses.replace(
        buoy, name=buoy.name + ", elastic chain (EA 1.09e8 N)",
        line_types={"chain": chain},
        lines=tuple(dataclasses.replace(leg, segments=tuple(
            dataclasses.replace(seg, line_type=chain) for seg in leg.segments))
            for leg in buoy.legs))
    return [
        # 1 MN toward 70 deg (the typhoon's heading) and a 20 MN m yaw moment; random
        # loads up to 12 MN and 100 MN m: past about 9-10 MN (heading-dependent) a chain
        # exceeds its 4.83 MN MBL and moorsolve's overload drops the load.
        BenchScene("dock", with_constant_force(dock, (0, 0, 0)), 12e6, 1e8,
                   _polar(1e6, 70, 2e7)),
        # 3 kN toward 225 deg (the bora's heading); the buoy has no yaw.
        BenchScene("buoy", with_constant_force(elastic_buoy, (0, 0, 0)), 6e4, 0.0,
                   _polar(3e3, 225)),
    ]


def agreement_scenes() -> list[BenchScene]:
    """The timed scenes plus the shipped (inextensible) Vida buoy."""
    buoy = moorsolve.load_case(ROOT / "cases" / "buoy_vida.yaml")
    return [*scenes(), BenchScene("buoy_inextensible", with_constant_force(buoy, (0, 0, 0)),
                                  0.0, 0.0, _polar(3e3, 225))]


def random_loads(scene: BenchScene, n: int, seed: int = SEED) -> tuple[list, int]:
    """``n`` seeded random loads that moorsolve finds an equilibrium for.

    Heading uniform on [0, 360) deg, force magnitude uniform on [0, max_force], moment
    uniform on [-max_moment, max_moment]. Loads moorsolve rejects (overload, no
    equilibrium) are dropped. Returns the loads and how many were dropped.
    """
    rng = np.random.default_rng(seed)
    loads, dropped = [], 0
    while len(loads) < n:
        if dropped > 10 * n:
            raise RuntimeError(f"{scene.name}: too many loads rejected; lower max_force")
        load = _polar(rng.uniform(0, scene.max_force), rng.uniform(0, 360),
                      rng.uniform(-scene.max_moment, scene.max_moment))
        try:
            moorsolve.solve(scene.with_load(load))
        except moorsolve.ConvergenceError:
            dropped += 1
            continue
        loads.append(load)
    return loads, dropped


# ---- columns ----------------------------------------------------------------------------


@dataclass
class Column:
    """Per-load timings of one solver in one start mode."""

    name: str
    tool: str
    warm: bool
    times_s: list = field(default_factory=list)
    converged: list = field(default_factory=list)
    residual_N: list = field(default_factory=list)      # force left unbalanced, if measured
    tension_error: list = field(default_factory=list)   # vs moorsolve reference, relative
    iterations: list = field(default_factory=list)

    def median_s(self) -> float:
        ok = [t for t, c in zip(self.times_s, self.converged) if c]
        return statistics.median(ok) if ok else float("nan")

    def summary(self) -> dict:
        def stats(xs):
            xs = [x for x in xs if x is not None and math.isfinite(x)]
            return None if not xs else {"median": statistics.median(xs), "max": max(xs)}
        return {"name": self.name, "tool": self.tool, "warm": self.warm,
                "median_s": self.median_s(),
                "converged": int(sum(self.converged)), "solves": len(self.converged),
                "iterations": stats(self.iterations),
                "residual_N": stats(self.residual_N),
                "tension_error_relative": stats(self.tension_error)}


def time_moorsolve(scene: BenchScene, loads: list, warm: bool, *,
                   solve_kwargs: dict | None = None, solver_time: bool = False) -> Column:
    """``moorsolve.solve`` per load (full Result, certificate included).

    From rest: a plain solve (moorsolve starts from the case position and its rest state).
    Warm: ``start=`` the previous load's ``Result.state``. The built problem is cached
    per scene structure; one untimed solve first builds it. With ``solver_time`` the
    time is the certificate's ``solve_time_s`` (the solve itself, without building the
    Result's profiles and tables), which is what MoorPy's time covers too.
    """
    kwargs = dict(solve_kwargs or {})
    col = Column("moorsolve " + " ".join(f"{k}={v}" for k, v in kwargs.items()),
                 "moorsolve", warm)
    cases = [scene.with_load(load) for load in loads]
    moorsolve.solve(cases[0], **kwargs)
    prev = None
    for case in cases:
        start = {"start": prev.state} if (warm and prev is not None) else {}
        t0 = time.perf_counter()
        try:
            result = moorsolve.solve(case, **kwargs, **start)
            ok = True
        except moorsolve.ConvergenceError:
            result, ok = None, False
        elapsed = time.perf_counter() - t0
        col.times_s.append(result.certificate.solve_time_s if (ok and solver_time) else elapsed)
        col.converged.append(ok)
        col.residual_N.append(result.certificate.force_N if ok else None)
        col.iterations.append(result.iterations if ok else None)
        prev = result if ok else prev
    return col


def time_moorpy(scene: BenchScene, loads: list, warm: bool, *, tol: float = MOORPY_TOL,
                references: list | None = None) -> Column:
    """MoorPy ``solveEquilibrium(tol)`` per load on one System built once.

    From rest: body back at the case position and the lines re-solved there (untimed)
    before each solve. Warm: from the previous load's equilibrium. After each solve
    (untimed) the force left unbalanced and, given moorsolve ``references``, the largest
    tension difference relative to the largest tension.
    """
    col = Column(f"MoorPy tol {tol:g} m", "moorpy", warm)
    peer = moorpy_system(scene.with_load(loads[0]), tol=tol)
    peer.solve()
    peer.reset()
    for i, load in enumerate(loads):
        peer.set_force(load)
        sol = peer.solve(from_rest=not warm)
        col.times_s.append(sol.solve_time_s)
        col.converged.append(sol.converged)
        col.iterations.append(sol.evaluations)
        if references is not None and sol.converged:
            col.tension_error.append(
                compare(scene.with_load(load), references[i], sol)["tension_relative"])
        col.residual_N.append(peer.unbalanced()[0] if sol.converged else None)
        if not sol.converged:
            peer.reset()
    return col


def time_kernel(scene: BenchScene, loads: list, warm: bool, *, tol: float = 1e-9) -> Column:
    """The compiled Newton kernel alone (``EquilibriumProblem.newton().raw``) per load.

    The parameter vectors and the closed-form start are prepared untimed (a sweep does
    that once per grid axis); the timed call is the kernel plus the certificate judgement
    on its outputs. A point the kernel cannot certify counts as not converged here
    (``solve`` and ``sweep`` would hand it to IPOPT).
    """
    from moorsolve.solve.assembly.cache import get_problem
    from moorsolve.solve.kernels.start import initial_point

    col = Column("moorsolve newton kernel", "moorsolve", warm)
    cases = [scene.with_load(load) for load in loads]
    problem = get_problem(cases[0])
    kernel = problem.newton()
    params = [problem.parameters(c) for c in cases]
    x_rest = initial_point(problem, cases[0])
    x_prev = x_rest.copy()
    for p in params:
        x0 = x_prev if warm else x_rest
        t0 = time.perf_counter()
        out = kernel.raw(x0, p, tol)
        ok, force, _, _ = problem.judge(*out[3], tol=tol)
        col.times_s.append(time.perf_counter() - t0)
        col.converged.append(ok)
        col.iterations.append(int(out[2][0]))
        col.residual_N.append(force if ok else None)
        if ok:
            x_prev = out[0].copy()
    return col


#: (column name, start mode, timing function). Add moorsolve variants here.
COLUMNS = [
    ("moorsolve ipopt", False, time_moorsolve),
    ("moorsolve ipopt", True, time_moorsolve),
    ("moorsolve ipopt, solve only", False,
     functools.partial(time_moorsolve, solver_time=True)),
    ("moorsolve newton kernel", False, time_kernel),
    ("moorsolve newton kernel", True, time_kernel),
    ("moorsolve newton", False,
     functools.partial(time_moorsolve, solve_kwargs={"solver": "newton"})),
    ("moorsolve newton", True,
     functools.partial(time_moorsolve, solve_kwargs={"solver": "newton"})),
    ("MoorPy tol 1e-4 m", False, functools.partial(time_moorpy, tol=MOORPY_TOL)),
    ("MoorPy tol 1e-4 m", True, functools.partial(time_moorpy, tol=MOORPY_TOL)),
    ("MoorPy default tol 0.05 m", False,
     functools.partial(time_moorpy, tol=peer_moorpy.MOORPY_DEFAULT_TOL)),
]
#: The column every ratio is taken against (per start mode).
BASELINE = "MoorPy tol 1e-4 m"


def run_columns(scene: BenchScene, loads: list) -> list[Column]:
    references = [moorsolve.solve(scene.with_load(load)) for load in loads]
    columns = []
    for name, warm, fn in COLUMNS:
        kwargs = {"references": references} if _takes(fn, "references") else {}
        col = fn(scene, loads, warm, **kwargs)
        col.name = name
        columns.append(col)
    return columns


def _takes(fn, arg: str) -> bool:
    import inspect
    return arg in inspect.signature(fn).parameters


# ---- agreement ---------------------------------------------------------------------------


def agreement(scene: BenchScene) -> dict:
    """moorsolve (``REFERENCE_TOL``) and MoorPy (``TIGHT_TOL``) on ``scene.check_load``."""
    case = scene.with_load(scene.check_load)
    result = moorsolve.solve(case, tol=REFERENCE_TOL)
    peer = moorpy_system(case)
    tight = peer.solve(tol=TIGHT_TOL)
    out = {"load": list(scene.check_load), "moorpy_tol_m": TIGHT_TOL,
           "moorpy_converged": tight.converged,
           "moorsolve_body": result.body,
           "moorpy_body": {"x_m": tight.x_m, "y_m": tight.y_m, "yaw_deg": tight.yaw_deg},
           "difference": compare(case, result, tight),
           "moorpy_unbalanced_N": peer.unbalanced()[0]}
    loose = peer.solve(tol=peer_moorpy.MOORPY_DEFAULT_TOL)
    force, moment = peer.unbalanced()
    out["default_tol"] = {"moorpy_tol_m": peer_moorpy.MOORPY_DEFAULT_TOL,
                          "unbalanced_force_N": force, "unbalanced_moment_Nm": moment,
                          "difference": compare(case, result, loose)}
    return out


# ---- scaling -----------------------------------------------------------------------------


def ring_case(n_legs: int, load_per_leg: float = 2e4) -> moorsolve.Case:
    """One body on ``n_legs`` identical chains evenly spread round a 20 m circle.

    Depth 50 m, 200 m of 0.13 t/m chain (EA 5.6e8 N) per leg, anchors 190 m out from the
    fairleads; a constant load of ``n_legs * load_per_leg`` toward 30 deg and a yaw moment,
    so every size carries about the same load per leg.
    """
    legs = []
    for i in range(n_legs):
        a = 2 * math.pi * i / n_legs
        c, s = math.cos(a), math.sin(a)
        legs.append({"name": f"L{i + 1}", "anchor": [210.0 * c, 210.0 * s],
                     "fairlead": [20.0 * c, 20.0 * s, 0.0],
                     "segments": [{"type": "chain", "length": 200.0}]})
    force = n_legs * load_per_leg
    data = {
        "name": f"ring of {n_legs} legs",
        "environment": {"depth": 50.0, "water_density": 1025},
        "line_types": {"chain": {"weight_in_water": "0.13 t/m", "ea": 5.6e8}},
        "body": {"free": ["surge", "sway", "yaw"],
                 "loads": {"force": [force * math.cos(math.radians(30)),
                                     force * math.sin(math.radians(30)), force * 5.0]}},
        "legs": legs,
    }
    return moorsolve.load_case(data)


#: moorsolve variants of the scaling study: name -> ``moorsolve.solve`` keyword arguments.
SCALING_VARIANTS = {"ipopt": {}, "newton": {"solver": "newton"}}


def scaling(sizes, repeats: int) -> list[dict]:
    """Median time per solve from rest, per leg count: each of ``SCALING_VARIANTS`` and
    MoorPy (1e-4 m). ``first_s`` is the first solve of a size, which builds the problem
    (and, for the Newton kernel, generates and compiles C code unless cached on disk)."""
    rows = []
    for n in sizes:
        case = ring_case(n)
        loads = [tuple(f * (0.5 + 0.5 * k / max(repeats - 1, 1)) for f in case.body.loads.force)
                 for k in range(repeats)]
        scene = BenchScene(case.name, case, 0, 0, loads[-1])
        row = {"legs": n, "solves": repeats}
        for name, kwargs in SCALING_VARIANTS.items():
            t0 = time.perf_counter()
            moorsolve.solve(case, **kwargs)
            row[f"{name}_first_s"] = time.perf_counter() - t0
            col = time_moorsolve(scene, loads, warm=False, solve_kwargs=kwargs)
            row[f"{name}_s"] = col.median_s()
            row[f"{name}_converged"] = int(sum(col.converged))
            row[f"{name}_iterations"] = statistics.median(col.iterations)
        mp = time_moorpy(scene, loads, warm=False)
        row.update(moorpy_s=mp.median_s(), moorpy_converged=int(sum(mp.converged)),
                   moorpy_evaluations=statistics.median(mp.iterations))
        rows.append(row)
    return rows


# ---- memory ------------------------------------------------------------------------------

#: Measured by default: a ``moorsolve.sweep`` of the typhoon dock (wind, current and
#: drift as in the case file) over a square grid of wind headings and speeds with ``n``
#: points, after a 4-point sweep in the setup has built and compiled the problem.
MEMORY_SETUP = textwrap.dedent("""
    import math, moorsolve
    case = moorsolve.load_case("cases/floating_dock.yaml")
    side = max(int(round(math.sqrt(n))), 1)
    grid = {"environment.wind.toward_deg": [360.0 * j / side for j in range(side)],
            "environment.wind.speed": [45.0 * (i + 1) / side for i in range(side)]}
    moorsolve.sweep(case, {"environment.wind.toward_deg": [0.0, 90.0],
                           "environment.wind.speed": [20.0, 40.0]})
""")
MEMORY_STATEMENT = textwrap.dedent("""
    table = moorsolve.sweep(case, grid)
    info = {"rows": len(table), "converged": int(table["converged"].sum())}
""")
#: The same measurement for a warm-started loop of ``moorsolve.solve`` (IPOPT) under
#: constant loads, keeping a summary row per point: ``peak_memory(n, MEMORY_SOLVE_LOOP,
#: MEMORY_SOLVE_LOOP_SETUP)``.
MEMORY_SOLVE_LOOP_SETUP = textwrap.dedent("""
    import math, moorsolve
    from peer_moorpy import with_constant_force
    base = moorsolve.load_case("cases/floating_dock.yaml")
    side = max(int(round(math.sqrt(n))), 1)
    loads = [(f * math.cos(math.radians(h)), f * math.sin(math.radians(h)), 0.0)
             for f in [4e6 * (i + 1) / side for i in range(side)]
             for h in [360.0 * j / side for j in range(side)]][:n]
    moorsolve.solve(with_constant_force(base, loads[0]))
""")
MEMORY_SOLVE_LOOP = textwrap.dedent("""
    rows, prev = [], None
    for load in loads:
        r = moorsolve.solve(with_constant_force(base, load),
                            start=None if prev is None else prev.state)
        prev = r
        rows.append((r.body["x_m"], r.body["y_m"], r.body["yaw_deg"],
                     *[leg.fairlead_tension_N for leg in r.legs]))
    info = {"rows": len(rows)}
""")

_MEMORY_DRIVER = textwrap.dedent("""
    import json, sys, time, tracemalloc
    sys.path[:0] = [{root!r}, {here!r}]

    def status_kB(key):
        with open("/proc/self/status") as f:
            return next(int(line.split()[1]) for line in f if line.startswith(key + ":"))

    n = {n}
    exec(compile({setup!r}, "setup", "exec"))
    setup_peak, setup_now = status_kB("VmHWM"), status_kB("VmRSS")
    if {trace!r}:
        tracemalloc.start()
    t0 = time.perf_counter()
    exec(compile({statement!r}, "statement", "exec"))
    elapsed = time.perf_counter() - t0
    out = dict(points=n, elapsed_s=elapsed, traced={trace!r},
               peak_rss_after_setup_kB=setup_peak, rss_after_setup_kB=setup_now,
               rss_end_kB=status_kB("VmRSS"), peak_rss_kB=status_kB("VmHWM"))
    if {trace!r}:
        out["peak_python_alloc_B"] = tracemalloc.get_traced_memory()[1]
    out["info"] = globals().get("info")
    print(json.dumps(out))
""")


def peak_memory(n: int, statement: str = MEMORY_STATEMENT, setup: str = MEMORY_SETUP, *,
                trace: bool = False) -> dict:
    """Run ``setup`` then ``statement`` (with ``n`` in scope) in a fresh interpreter.

    Returns, in kB, the process's peak resident set size (``VmHWM`` of /proc/self/status;
    ``ru_maxrss`` would include the parent's size at the fork) at the end and after
    ``setup`` (imports, building), and its current RSS after ``setup`` and at the end;
    ``elapsed_s`` of the statement; with ``trace`` also the peak of Python allocations
    during the statement (tracemalloc, which slows it about fivefold, so ``elapsed_s`` is
    then not a timing).
    """
    code = _MEMORY_DRIVER.format(root=str(ROOT), here=str(HERE), n=int(n), setup=setup,
                                 statement=statement, trace=bool(trace))
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                          check=False, text=True, env={**os.environ, "PYTHONBREAKPOINT": "0"})
    if proc.returncode != 0:
        raise RuntimeError(f"memory run failed:\n{proc.stderr[-2000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


# ---- report ------------------------------------------------------------------------------


def _ms(t):
    return f"{t * 1e3:9.3f}" if math.isfinite(t) else "      nan"


def print_agreement(name, a):
    d = a["difference"]
    load = ", ".join(f"{v:.4g}" for v in a["load"])
    print(f"{name}: load [{load}]; MoorPy at {a['moorpy_tol_m']:g} m "
          f"{'converged' if a['moorpy_converged'] else 'FAILED'}")
    print(f"  offset diff {d['offset_m']:.2e} m, yaw diff {d['yaw_deg']:.2e} deg, fairlead "
          f"tension diff {d['fairlead_tension_N']:.2e} N, anchor {d['anchor_tension_N']:.2e} N "
          f"({d['tension_relative']:.1e} of {d['max_tension_N']:.4g} N)")
    dt = a["default_tol"]
    print(f"  MoorPy at its default {dt['moorpy_tol_m']:g} m leaves "
          f"{dt['unbalanced_force_N']:.4g} N and {dt['unbalanced_moment_Nm']:.4g} N m "
          "unbalanced; tensions off by "
          f"{dt['difference']['tension_relative']:.1e} of the largest")


def print_table(name, columns, dropped):
    print(f"\n{name}: {len(columns[0].times_s)} loads ({dropped} drawn loads dropped as "
          "overload/no equilibrium)")
    print(f"  {'column':28s} {'start':5s} {'median ms':>9s} {'ok':>7s} {'MoorPy/col':>10s} "
          f"{'iter':>5s} {'resid N (med/max)':>21s} {'dT/Tmax max':>11s}")
    base = {c.warm: c.median_s() for c in columns if c.name == BASELINE}
    for c in columns:
        s = c.summary()
        r = s["residual_N"]
        e = s["tension_error_relative"]
        ratio = base.get(c.warm, float("nan")) / c.median_s()
        resid = "" if r is None else f"{r['median']:9.2e}/{r['max']:9.2e}"
        err = "" if e is None else f"{e['max']:.1e}"
        mode = "warm" if c.warm else "rest"
        it = "" if s["iterations"] is None else f"{s['iterations']['median']:g}"
        print(f"  {c.name:28s} {mode:5s} {_ms(c.median_s())} "
              f"{s['converged']:3d}/{s['solves']:<3d} {ratio:10.1f} {it:>5s} {resid:>21s} "
              f"{err:>11s}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help="20 loads per scene, scaling to 48 legs, a 1000-point sweep")
    ap.add_argument("--out", default=str(HERE / "results.json"))
    ap.add_argument("--skip", nargs="*", default=[], choices=["scaling", "memory"])
    args = ap.parse_args(argv)
    n_loads = 20 if args.quick else 100
    sizes = (3, 12, 48) if args.quick else (3, 12, 48, 192)
    repeats = 3 if args.quick else 10
    n_memory = 1000 if args.quick else 10_000

    import moorpy
    results = {"moorpy_version": moorpy.__version__ if hasattr(moorpy, "__version__")
               else peer_moorpy.MOORPY_VERSION,
               "moorsolve_version": moorsolve.__version__, "python": platform.python_version(),
               "machine": f"{platform.machine()}, {os.cpu_count()} cpus", "quick": args.quick,
               "load_average_at_start": os.getloadavg(),
               "moorpy_tol_m": MOORPY_TOL, "agreement": {}, "scenes": {}}
    print(f"== agreement (moorsolve tol {REFERENCE_TOL:g} vs MoorPy {TIGHT_TOL:g} m)")
    for scene in agreement_scenes():
        results["agreement"][scene.name] = a = agreement(scene)
        print_agreement(scene.name, a)

    print("\n== time per solve (median), ratios against MoorPy at 1e-4 m in the same start mode")
    for scene in scenes():
        loads, dropped = random_loads(scene, n_loads)
        columns = run_columns(scene, loads)
        print_table(scene.name, columns, dropped)
        results["scenes"][scene.name] = {
            "loads": [list(load) for load in loads], "dropped": dropped,
            "columns": [c.summary() for c in columns],
            "times_s": {f"{c.name} ({'warm' if c.warm else 'rest'})": c.times_s
                        for c in columns}}

    if "scaling" not in args.skip:
        print("\n== scaling: one body on N legs, median time per solve from rest "
              "(ratio = MoorPy / variant; first = first solve incl. build/compile)")
        head = "".join(f" {v + ' ms':>11s} {'ratio':>6s} {'first s':>8s}" for v in SCALING_VARIANTS)
        print(f"  {'legs':>5s} {'MoorPy ms':>10s}{head}")
        results["scaling"] = rows = scaling(sizes, repeats)
        for r in rows:
            cells = "".join(f" {_ms(r[v + '_s']):>11s} {r['moorpy_s'] / r[v + '_s']:6.1f} "
                            f"{r[v + '_first_s']:8.2f}" for v in SCALING_VARIANTS)
            print(f"  {r['legs']:5d} {_ms(r['moorpy_s']):>10s}{cells}")

    if "memory" not in args.skip:
        mem = peak_memory(n_memory)
        results["memory"] = mem
        print(f"\n== memory: moorsolve.sweep of the typhoon dock over {mem['points']} wind "
              f"headings x speeds in a fresh process ({mem['info']}), {mem['elapsed_s']:.2f} s: "
              f"peak RSS {mem['peak_rss_kB'] / 1024:.0f} MB (peak after setup "
              f"{mem['peak_rss_after_setup_kB'] / 1024:.0f} MB); RSS "
              f"{mem['rss_after_setup_kB'] / 1024:.0f} MB after setup, "
              f"{mem['rss_end_kB'] / 1024:.0f} MB at the end")

    Path(args.out).write_text(json.dumps(results, indent=1, default=_jsonable))
    print(f"\nwrote {args.out}")
    return 0


def _jsonable(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if dataclasses.is_dataclass(o):
        return dataclasses.asdict(o)
    raise TypeError(type(o))


if __name__ == "__main__":
    sys.exit(main())
