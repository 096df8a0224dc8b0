"""The optional Capytaine path: against Capytaine called directly, the disk cache, and the
message naming the extra when Capytaine is missing."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

import moorsolve
from moorsolve import CaseError

RADIUS, DRAFT, PANEL = 1.0, 2.0, 0.5
OMEGA = [0.8, 1.6]


def case_data(cache) -> dict:
    return {"environment": {"depth": 40, "waves": {"hs": 1.0, "tp": 6.0}},
            "line_types": {"h": {"weight_in_water": 0, "ea": 1e6}},
            "bodies": [{"name": "can", "free": ["surge", "sway", "heave", "roll", "pitch",
                                                "yaw"],
                        "mass": 1025.0 * math.pi * RADIUS ** 2 * DRAFT,
                        "centre_of_gravity": [0, 0, -1.5], "inertia": [3000, 3000, 1500],
                        "hull": [{"shape": "cylinder", "radius": RADIUS, "bottom": -DRAFT,
                                  "top": 1.0}],
                        "hydrodynamics": {"source": "capytaine", "omega": OMEGA,
                                          "headings_deg": [0.0, 90.0], "panel_size": PANEL,
                                          "cache": str(cache)},
                        "damping": {"linear": [0, 0, 0, 0, 0, 500.0],
                                    "critical_fraction": {"surge": 0.05, "sway": 0.05,
                                                          "roll": 0.05, "pitch": 0.05}}}],
            "lines": [{"name": n, "from": [x, y, 0], "to": {"body": "can", "at": [0, 0, 0]},
                       "segments": [{"type": "h", "length": 49.5}]}
                      for n, x, y in (("w", -50, 0), ("e", 50, 0), ("n", 0, 50),
                                      ("s", 0, -50))]}


def test_missing_extra_is_named(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "capytaine", None)
    case = moorsolve.load_case(case_data(tmp_path))
    with pytest.raises(CaseError) as err:
        moorsolve.motions(case)
    assert err.value.field == "bodies[0].hydrodynamics.source"
    assert "moorsolve[hydro]" in str(err.value)


def test_capytaine_needs_a_hull(tmp_path):
    data = case_data(tmp_path)
    del data["bodies"][0]["hull"]
    data["bodies"][0]["hydrostatics"] = {"displaced_volume": 6.28, "waterplane_area": 3.14}
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(data)
    assert err.value.field == "bodies[0].hull"


def test_against_capytaine_directly(tmp_path, monkeypatch):
    cpt = pytest.importorskip("capytaine")
    import xarray as xr

    case = moorsolve.load_case(case_data(tmp_path))
    m = moorsolve.motions(case, n_omega=60)
    z = m.result.body_named("can")["z_m"]
    # Capytaine called directly on the same cylinder at the solved draft.
    mesh = cpt.mesh_vertical_cylinder(
        length=DRAFT + 1.0, radius=RADIUS, center=(0, 0, -DRAFT / 2 + 0.5 + z),
        resolution=(max(2, math.ceil(RADIUS / PANEL)),
                    max(12, math.ceil(2 * math.pi * RADIUS / PANEL)),
                    max(2, math.ceil((DRAFT + 1.0) / PANEL)))).immersed_part()
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, z)))
    names = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]
    ds = cpt.BEMSolver().fill_dataset(xr.Dataset(coords={
        "omega": OMEGA, "wave_direction": [0.0, math.pi / 2], "radiating_dof": names,
        "water_depth": [40.0 + 0.0], "rho": [1025.0], "g": [9.80665]}), body)
    h = m.hydrodynamics["can"]
    # Capytaine's own runs differ by about 3e-5 relative from one to the next (its
    # iterative linear solver): the comparison allows 2e-4.
    for k, w in enumerate(OMEGA):
        # A_ij: the force in DOF i (influenced) of an acceleration in DOF j (radiating).
        A = np.squeeze(ds["added_mass"].sel(omega=w, influenced_dof=names, radiating_dof=names)
                       .transpose(..., "influenced_dof", "radiating_dof").values)
        B = np.squeeze(ds["radiation_damping"].sel(omega=w, influenced_dof=names,
                                                   radiating_dof=names)
                       .transpose(..., "influenced_dof", "radiating_dof").values)
        assert A[0, 4] != pytest.approx(A[4, 0], rel=1e-6)    # the order matters here
        assert np.allclose(A, h.added_mass[k], rtol=2e-4, atol=2e-4 * abs(A).max())
        assert np.allclose(B, h.damping[k], rtol=2e-4, atol=2e-4 * abs(B).max())
        for j, beta in enumerate((0.0, math.pi / 2)):
            X = np.squeeze(ds["excitation_force"].sel(omega=w, wave_direction=beta,
                                                      influenced_dof=names).values)
            got = np.array(h.excitation[j].re[k]) + 1j * np.array(h.excitation[j].im[k])
            # e^{-i w t} (Capytaine) to e^{+i w t} (the tables): conjugated.
            assert np.allclose(got, np.conj(X), rtol=2e-4, atol=2e-4 * abs(X).max())
    # Physical: long-ish waves lift the can with the surface (|heave RAO| near 1 at 0.8).
    assert 0.5 < abs(m.body("can").rao[0, 2]) < 2.0
    # The second run reads the cache: the solver is never called.
    assert list(tmp_path.glob("capytaine-*.npz"))

    def fail(*a, **k):
        raise AssertionError("the BEM solver ran again")
    monkeypatch.setattr(cpt.BEMSolver, "fill_dataset", fail)
    m2 = moorsolve.motions(case, n_omega=60)
    assert np.allclose(m2.body("can").wf["sigma"], m.body("can").wf["sigma"])
