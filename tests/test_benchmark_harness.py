"""The MoorPy converter of benchmarks/ builds the same problem moorsolve solves.

Runs only where the ``bench`` extra (MoorPy 1.3.0) is installed. No timing is asserted.
"""

import dataclasses
import importlib.util
import math
import os
import sys

import numpy as np
import pytest

import moorsolve
from conftest import ROOT

os.environ.setdefault("PYTHONBREAKPOINT", "0")    # some MoorPy error branches call it
pytest.importorskip("moorpy")



def _load_peer():
    spec = importlib.util.spec_from_file_location(
        "peer_moorpy", ROOT / "benchmarks" / "peer_moorpy.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("peer_moorpy", module)   # dataclasses look their module up here
    spec.loader.exec_module(module)
    return module


peer_moorpy = _load_peer()


@pytest.fixture(scope="module")
def buoy():
    # Vida under a constant 3 kN toward 225 deg (the bora's heading) instead of its wind.
    a = math.radians(225.0)
    case = moorsolve.load_case(ROOT / "cases" / "buoy_vida.yaml")
    return peer_moorpy.with_constant_force(case, (3e3 * math.cos(a), 3e3 * math.sin(a), 0.0))


def test_line_type_keeps_the_submerged_weight(buoy):
    env = buoy.environment
    lt = buoy.line_types["chain"]
    mp_type = peer_moorpy.line_type(lt, env, ea=1e12)
    w = (mp_type["m"] - math.pi / 4 * mp_type["d_vol"] ** 2 * env.water_density) * env.gravity
    assert w == pytest.approx(lt.weight_in_water, rel=1e-13)
    assert lt.weight_in_water == pytest.approx(22.0 * 9.81, rel=1e-15)


def test_moorpy_equilibrium_matches_moorsolve_on_the_buoy(buoy):
    result = moorsolve.solve(buoy)
    scene = peer_moorpy.moorpy_system(buoy)
    sol = scene.solve(tol=1e-9)
    assert sol.converged, sol.error
    # MoorPy's own line weight after its solve is the case's weight in water.
    for line in scene.system.lineList:
        assert line.w == pytest.approx(buoy.line_types["chain"].weight_in_water, rel=1e-12)
    diff = peer_moorpy.compare(buoy, result, sol)
    # A 1e-9 m step tolerance and the near-rigid stand-in EA (stretch ~1e-12 of the length)
    # leave differences far below 1e-7 m and 1e-9 of the largest tension (measured 6e-11 m
    # and 1e-12).
    assert diff["offset_m"] < 1e-7
    assert diff["tension_relative"] < 1e-9
    force, moment = scene.unbalanced()
    assert force < 1e-6 * diff["max_tension_N"] and moment == 0.0
    # The offset is a real one (not two tools agreeing on zero): the load moves the buoy
    # several metres toward 225 deg.
    assert sol.x_m < -1.0 and sol.y_m < -1.0
    np.testing.assert_allclose(sol.fairlead_tension_N,
                               [leg.fairlead_tension_N for leg in result.legs], rtol=1e-9)


def test_default_tolerance_leaves_force_unbalanced(buoy):
    scene = peer_moorpy.moorpy_system(buoy)
    scene.solve(tol=peer_moorpy.MOORPY_DEFAULT_TOL)
    loose, _ = scene.unbalanced()
    scene.solve(tol=1e-9)
    tight, _ = scene.unbalanced()
    assert loose > 1e3 * tight


def test_what_cannot_be_compared_is_refused():
    dock = moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml")
    with pytest.raises(ValueError, match="only a constant"):
        peer_moorpy.moorpy_system(dock)
    rough = moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml")
    rough = peer_moorpy.with_constant_force(rough, (1e5, 0.0, 0.0))
    env = dataclasses.replace(rough.environment, seabed=moorsolve.model.Seabed(friction=0.5))
    with pytest.raises(ValueError, match="friction"):
        peer_moorpy.moorpy_system(dataclasses.replace(rough, environment=env))
    sloped = dataclasses.replace(rough.environment,
                                 seabed=moorsolve.model.Seabed(gradient=(0.01, 0.0)))
    with pytest.raises(ValueError, match="sloped"):
        peer_moorpy.moorpy_system(dataclasses.replace(rough, environment=sloped))
