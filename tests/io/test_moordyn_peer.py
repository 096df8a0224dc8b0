"""MoorDyn itself as the peer of the export: the file we write at equilibrium is loaded and
initialised by MoorDyn (NREL's lumped-mass code, the ``moordyn`` 2.7.2 wheel of the bench
extra), and the mooring force it puts on the coupled body is compared with ours.

MoorDyn's initial-condition solve is a dynamic relaxation of a lumped-mass model (25
segments per line as exported, the seabed a penalty spring), so it agrees with the exact
elastic catenary only to its discretisation: on the dock a few parts in 10^4 (Fx -95.27 kN
against our -95.23 kN, Fy -3731.6 kN against -3733.3 kN, Mz -28678 kN m against -28648 kN m
when this test was written). The bound of 3e-3 of the force's magnitude fails for any
mapping error (a wrong weight in water, length, anchor or pose changes the force by percent).
"""

import math

import numpy as np
import pytest

import moorsolve
from moorsolve.studies.stiffness import mooring_force
from conftest import ROOT

moordyn = pytest.importorskip("moordyn")



def _moordyn_body_force(path, pose):
    """Initialise MoorDyn with its coupled body at ``pose`` = (x, y, yaw_deg) and return the
    mooring force on the body [Fx, Fy, Mz]."""
    system = moordyn.Create(str(path))
    try:
        x, y, yaw = pose
        moordyn.Init(system, np.array([x, y, 0.0, 0.0, 0.0, math.radians(yaw)]), np.zeros(6))
        force = moordyn.GetBodyForce(moordyn.GetBody(system, 1))
    finally:
        moordyn.Close(system)
    return np.array([force[0], force[1], force[5]])


def test_moordyn_holds_the_exported_dock_equilibrium_with_our_mooring_force(tmp_path):
    case = moorsolve.load_case(str(ROOT / "cases" / "floating_dock.yaml"))
    path = tmp_path / "dock.dat"
    result = moorsolve.export_moordyn(case, path, equilibrium=True)
    pose = (result.body["x_m"], result.body["y_m"], result.body["yaw_deg"])
    ours = np.array(mooring_force(case, pose)[0])
    theirs = _moordyn_body_force(path, pose)
    scale = np.hypot(ours[0], ours[1])
    assert abs(theirs[0] - ours[0]) < 3e-3 * scale
    assert abs(theirs[1] - ours[1]) < 3e-3 * scale
    assert abs(theirs[2] - ours[2]) < 3e-3 * abs(ours[2])   # yaw moment about the body origin
