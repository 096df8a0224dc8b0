"""Speed of the frequency-domain motions (measured here, never asserted in tests).

    python benchmarks/motions_speed.py [--repeats 20]

Per scene, medians of wall time: the coupled response alone over 100 given frequencies
(``System.response``: assembling ``M(w)``, ``B(w)``, ``F(w)`` from the tables and the
batched solves), and ``moorsolve.motions(result)`` whole at its defaults (mean drift
re-solve, stiffness, wave-frequency grid with refinement, Newman slow drift, statistics).
Scenes: the shipped cylinder buoy (one body, 6 DOFs) and three platforms on shared lines
(18 DOFs) with table hydrodynamics.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests" / "dynamics"))


def _median(f, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def _scenes():
    import moorsolve
    import test_motions_coupled as coupled

    yield "buoy_sea (6 DOF)", moorsolve.load_case(ROOT / "cases" / "buoy_sea.yaml")
    data = yaml.safe_load((ROOT / "cases" / "three_platforms.yaml").read_text())
    data["environment"]["waves"] = {"hs": 4.0, "tp": 10.0, "toward_deg": 15.0}
    for k, body in enumerate(data["bodies"]):
        body["inertia"] = coupled.INERTIA
        body["hydrodynamics"] = coupled.hydro(k)
        body["damping"] = {"linear": coupled.LINEAR}
    yield "three_platforms (18 DOF)", moorsolve.load_case(data)


def main(argv=None):
    import moorsolve
    from moorsolve.dynamics.hydro import BodyHydro
    from moorsolve.dynamics.motions import _moving_bodies
    from moorsolve.dynamics.system import System
    from moorsolve.studies.stiffness import coupled_stiffness

    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=20)
    args = p.parse_args(argv)
    for name, case in _scenes():
        result = moorsolve.solve(case)
        moving = _moving_bodies(case)
        hydros = {b.name: BodyHydro(b.hydrodynamics, path) for path, b in moving}
        K, labels = coupled_stiffness(result)
        system = System(moving, hydros, result, K, labels, case.environment.waves.toward_deg)
        lo = max(h.omega[0] for h in hydros.values())
        hi = min(h.omega[-1] for h in hydros.values())
        omega = np.linspace(lo, hi, 100)
        t_resp = _median(lambda: system.response(omega), args.repeats)
        moorsolve.motions(result)                        # warm: the re-solve's problem built
        t_all = _median(lambda: moorsolve.motions(result), max(3, args.repeats // 4))
        print(f"{name:<26} response over 100 frequencies {t_resp * 1e3:7.2f} ms;  "
              f"motions() whole {t_all * 1e3:8.1f} ms")


if __name__ == "__main__":
    main()
