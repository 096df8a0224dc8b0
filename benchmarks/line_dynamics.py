"""What line dynamics cost: every line of the 12-chain floating dock in one sea state.

    PYTHONPATH=. python benchmarks/line_dynamics.py [--frequencies 100] [--repeats 3]

``cases/floating_dock.yaml`` is solved once; each of its 12 chains is then modelled as lumped
masses about its static profile (default 60 elements) and driven at its fairlead by a
synthetic motion (0.5 m per metre of wave amplitude along the waves' heading, a quarter of
that heave) in a Pierson-Moskowitz sea (Hs 2 m, Tp 8 s) on ``--frequencies`` frequencies from
0.2 to 2.0 rad/s, with the drag linearised on the spectral response (iterated to
convergence). Timed (best of ``--repeats``): building the 12 line models, and solving them
(tension spectra, sigma, T_z and the characteristic tension at both ends).

The peer: MoorPy 1.3's ``Line.dynamicSolve`` for line L1 at the same frequencies, with the
same number of segments, against ours for that line: the ratio is MoorPy / moorsolve.
Results go to ``benchmarks/line_dynamics_results.json``; the ratios are what to read.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import platform
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import moorsolve  # noqa: E402
from moorsolve.dynamics.line_model import line_model  # noqa: E402
from moorsolve.dynamics.line_spectral import tension_statistics  # noqa: E402


def pierson_moskowitz(omega, hs=2.0, tp=8.0):
    wp = 2 * math.pi / tp
    return 5 / 16 * hs ** 2 * wp ** 4 / omega ** 5 * np.exp(-1.25 * (wp / omega) ** 4)


def best(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def moorpy_line(case, result, n_seg):
    import moorpy as mp
    env = case.environment
    leg = result.legs[0]
    lt = case.lines[0].line_type
    g, rho = env.gravity, env.water_density
    m = lt.weight_in_water / (g * (1 - rho / 7850.0))
    d_vol = math.sqrt(4 * m / 7850.0 / math.pi)
    system = mp.System(depth=env.depth, rho=rho, g=g)
    system.setLineType(name="c", lineType=dict(
        name="c", m=m, d_vol=d_vol, EA=lt.ea, w=lt.weight_in_water,
        Cd=2.4 * lt.diameter / d_vol, Ca=1.0, CdAx=0.0, CaAx=0.0, MBL=lt.mbl,
        material="chain", d_nom=lt.diameter))
    system.addPoint(1, list(leg.anchor))
    system.addPoint(1, list(leg.fairlead))
    system.addLine(case.lines[0].length, "c", nSegs=n_seg)
    system.pointList[0].attachLine(1, 0)
    system.pointList[1].attachLine(1, 1)
    system.initialize()
    system.solveEquilibrium()
    return system.lineList[0]


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--frequencies", type=int, default=100)
    p.add_argument("--elements", type=int, default=60)
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args(argv)
    case = moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml")
    result = moorsolve.solve(case)
    names = [leg.name for leg in result.legs]
    omega = np.linspace(0.2, 2.0, a.frequencies)
    S = pierson_moskowitz(omega)
    heading = math.radians(70.0)
    rao = np.outer([0.5 * math.cos(heading), 0.5 * math.sin(heading), 0.125],
                   np.ones_like(omega)) + 0j
    t_build, models = best(lambda: [line_model(case, result, n, n_elements=a.elements)
                                    for n in names], a.repeats)
    t_solve, stats = best(lambda: [tension_statistics(m, omega, rao, S) for m in models],
                          a.repeats)
    out = {"machine": platform.processor() or platform.machine(),
           "lines": len(names), "frequencies": a.frequencies, "elements": a.elements,
           "build_s": t_build, "solve_s": t_solve,
           "iterations": [s.response.iterations for s in stats],
           "sigma_fairlead_N": {s.name: s.fairlead.sigma_N for s in stats}}
    try:
        line = moorpy_line(case, result, a.elements)
        t_peer, peer = best(lambda: line.dynamicSolve(omega, S, np.zeros((len(omega), 3)),
                                                      rao.T.copy(), case.environment.depth,
                                                      kbot=3e6, cbot=3e5, tol=0.01),
                            a.repeats)
        t_ours, ours = best(lambda: tension_statistics(models[0], omega, rao, S,
                                                       tolerance=1e-2), a.repeats)
        out["peer"] = {"moorpy_s": t_peer, "moorsolve_s": t_ours, "ratio": t_peer / t_ours,
                       "sigma_moorpy_N": float(peer[2][-1]),
                       "sigma_moorsolve_N": ours.fairlead.sigma_N}
    except ImportError:
        out["peer"] = None
    (HERE / "line_dynamics_results.json").write_text(json.dumps(out, indent=2) + "\n")
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
