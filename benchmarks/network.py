"""Network scenes against NREL MoorPy: time per equilibrium, same scenes and loads, one run.

    PYTHONBREAKPOINT=0 python benchmarks/network.py [--quick] [--out FILE.json]

Needs the ``bench`` extra (MoorPy 1.3.0). Scenes:

* ``oc3_spar``: the OC3 Hywind spar on its three lines, free in six DOFs (the crow's-foot yaw
  spring dropped: MoorPy has no body spring), under random constant thrust, side force and
  yaw moment. Targets: IPOPT at least 10x, Newton at least 200x MoorPy's solveEquilibrium.
* ``three_platforms``: ``cases/three_platforms.yaml``, three six-DOF bodies on 15 lines
  with three bridles and two shared lines, under random constant forces on every body.
  Target: IPOPT at least 10x.

Each column solves every load from rest (bodies back at their case pose; for moorsolve no
warm start) and returns what a user gets: moorsolve's full ``Result`` (certificate,
stability, profiles), MoorPy's solved System. MoorPy runs at a step tolerance of 1e-4 m
(``MOORPY_TOL``). Before timing, every scene is checked against MoorPy at a tight tolerance
(positions and tensions). Timings on a shared 2-core machine are noisy: read the ratios.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import io
import json
import math
import os
import platform
import statistics
import sys
import time
import warnings
from pathlib import Path

os.environ.setdefault("PYTHONBREAKPOINT", "0")
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
from peer_moorpy_network import NetworkScene, without_extras
from speed import wait_steady

import moorsolve
from moorsolve.model import BodyLoads

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
MOORPY_TOL = 1e-4
SEED = 11


def scenes() -> dict:
    spar = without_extras(moorsolve.load_case(ROOT / "cases" / "oc3_spar.yaml"))
    three = moorsolve.load_case(ROOT / "cases" / "three_platforms.yaml")
    return {"oc3_spar": spar, "three_platforms": three}


def random_loads(case, n: int, rng) -> list:
    """``n`` lists of 6-forces, one per body."""
    loads = []
    for _ in range(n):
        per_body = []
        for _ in case.bodies:
            if len(case.bodies) == 1:       # a turbine: thrust, side force, yaw moment
                f = (rng.uniform(2e5, 1.5e6), rng.uniform(-3e5, 3e5), 0, 0, 0,
                     rng.uniform(-3e6, 3e6))
            else:
                f = (rng.uniform(-1e5, 1e5), rng.uniform(-1e5, 1e5), 0, 0, 0,
                     rng.uniform(-5e5, 5e5))
            per_body.append(tuple(float(v) for v in f))
        loads.append(per_body)
    return loads


def loaded(case, forces):
    bodies = tuple(dataclasses.replace(b, loads=BodyLoads(force=f))
                   for b, f in zip(case.bodies, forces))
    return dataclasses.replace(case, bodies=bodies, source=None)


def time_moorsolve(case, loads, solver: str) -> dict:
    times, ok = [], 0
    moorsolve.solve(loaded(case, loads[0]), solver=solver)      # build and compile
    wait_steady(loaded(case, loads[0]))
    for forces in loads:
        scene = loaded(case, forces)
        t0 = time.perf_counter()
        try:
            result = moorsolve.solve(scene, solver=solver)
            ok += bool(result.converged)
        except moorsolve.ConvergenceError:
            pass
        times.append(time.perf_counter() - t0)
    return {"median_s": statistics.median(times), "converged": ok, "n": len(loads)}


def time_moorpy(case, loads) -> dict:
    times, ok = [], 0
    for forces in loads:
        scene = NetworkScene(loaded(case, forces))
        t0 = time.perf_counter()
        ok += scene.solve(tol=MOORPY_TOL, maxIter=2000)
        times.append(time.perf_counter() - t0)
    return {"median_s": statistics.median(times), "converged": ok, "n": len(loads)}


def agreement(case, forces) -> dict:
    scene = loaded(case, forces)
    result = moorsolve.solve(scene, tol=1e-12)
    peer = NetworkScene(scene)
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        peer.solve(tol=1e-9, maxIter=2000)
    worst_pos = 0.0
    for b in result.bodies:
        ours = np.array([b["x_m"], b["y_m"], b["z_m"]] + [math.radians(b[k]) for k in
                                                         ("roll_deg", "pitch_deg", "yaw_deg")])
        worst_pos = max(worst_pos, float(np.max(np.abs(ours - peer.poses()[b["name"]]))))
    t_max = max(leg.fairlead_tension_N for leg in result.legs)
    worst_t = max(max(abs(lr.anchor_tension_N - ta), abs(lr.fairlead_tension_N - tb))
                  for lr, (ta, tb) in zip(result.legs, peer.tensions()))
    return {"pose": worst_pos, "tension_relative": worst_t / t_max}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="5 loads per scene")
    parser.add_argument("--out", default=str(HERE / "network_results.json"))
    args = parser.parse_args(argv)
    n = 5 if args.quick else 30
    rng = np.random.default_rng(SEED)
    out = {"machine": platform.platform(), "python": platform.python_version(),
           "moorpy_tol_m": MOORPY_TOL, "loads_per_scene": n, "scenes": {}}
    for name, case in scenes().items():
        loads = random_loads(case, n, rng)
        agree = agreement(case, loads[0])
        peer = time_moorpy(case, loads)
        row = {"agreement": agree, "moorpy": peer}
        for solver in ("ipopt", "newton"):
            col = time_moorsolve(case, loads, solver)
            col["ratio_vs_moorpy"] = peer["median_s"] / col["median_s"]
            row[solver] = col
        out["scenes"][name] = row
        print(f"{name}: agreement pose {agree['pose']:.1e} m/rad, tension "
              f"{agree['tension_relative']:.1e}; MoorPy {peer['median_s'] * 1e3:.2f} ms "
              f"({peer['converged']}/{n}); IPOPT {row['ipopt']['median_s'] * 1e3:.2f} ms "
              f"({row['ipopt']['ratio_vs_moorpy']:.1f}x); Newton "
              f"{row['newton']['median_s'] * 1e3:.2f} ms "
              f"({row['newton']['ratio_vs_moorpy']:.1f}x)")
    Path(args.out).write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
