"""What the check with line dynamics costs: the 12-chain dock in a sea state, intact and with
each chain removed in turn (13 conditions).

    PYTHONPATH=. python benchmarks/dynamic_check.py [--repeats 3]

``cases/dock_sea.yaml`` (table hydrodynamics, so nothing to compute before the first run but
the kernels) is checked once to warm up, then timed (best of ``--repeats``, wall clock and
process time): the whole ``run_checks`` (per condition: the static solve, the motions with
the mean drift re-solve, the design-offset solve, every line's lumped-mass dynamics with the
drag linearised by iteration, the low-frequency stiffness), and, for the intact condition,
its motions and its line dynamics alone. Results go to
``benchmarks/dynamic_check_results.json``.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import platform
import sys
import time
import warnings

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import moorsolve  # noqa: E402
from moorsolve.checks import run_checks  # noqa: E402
from moorsolve.dynamics.line_sea import line_tensions  # noqa: E402


def best(fn, repeats):
    wall, cpu, out = [], [], None
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return min(wall), min(cpu), out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args(argv)
    warnings.simplefilter("ignore")
    case = moorsolve.load_case(ROOT / "cases" / "dock_sea.yaml")
    run_checks(case)                                   # warm-up: kernels, caches
    wall, cpu, report = best(lambda: run_checks(case), a.repeats)
    m_wall, m_cpu, m = best(lambda: moorsolve.motions(case), a.repeats)
    l_wall, l_cpu, tensions = best(lambda: line_tensions(m), a.repeats)
    out = {"machine": platform.processor() or platform.machine(),
           "case": "cases/dock_sea.yaml", "conditions": len(report.conditions),
           "lines": len(case.lines), "check_wall_s": wall, "check_cpu_s": cpu,
           "intact_motions_wall_s": m_wall, "intact_motions_cpu_s": m_cpu,
           "intact_line_dynamics_wall_s": l_wall, "intact_line_dynamics_cpu_s": l_cpu,
           "line_frequencies": int(next(iter(tensions.values())).omega.size),
           "drag_iterations": max(t.iterations for t in tensions.values())}
    (HERE / "dynamic_check_results.json").write_text(json.dumps(out, indent=2) + "\n")
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
