"""Hydrodynamics from a case-file table and from WAMIT files: validation, units,
interpolation in frequency and heading."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import moorsolve
from moorsolve import CaseError
from moorsolve.dynamics.hydro import BodyHydro, table_mapping
from moorsolve.io.wamit import read_wamit, write_wamit

RHO, G = 1025.0, 9.80665


def table(n=5, headings=(0.0, 90.0), seed=1) -> dict:
    rng = np.random.default_rng(seed)
    om = np.linspace(0.2, 2.0, n)
    A = rng.normal(size=(n, 6, 6)) * 1e5
    B = rng.normal(size=(n, 6, 6)) * 1e4
    exc = [{"heading_deg": h, "re": (rng.normal(size=(n, 6)) * 1e5).tolist(),
            "im": (rng.normal(size=(n, 6)) * 1e5).tolist()} for h in headings]
    drift = [{"heading_deg": h, "values": (rng.normal(size=(n, 6)) * 1e3).tolist()}
             for h in headings]
    return {"source": "table", "omega": om.tolist(), "added_mass": A.tolist(),
            "damping": B.tolist(), "excitation": exc, "mean_drift": drift}


def case_with(hydro) -> dict:
    return {"environment": {"depth": 50, "waves": {"hs": 2, "tp": 8}},
            "line_types": {"h": {"weight_in_water": 0, "ea": 1e6}},
            "bodies": [{"name": "b", "free": ["surge"], "mass": 1e6, "hydrodynamics": hydro}],
            "lines": [{"name": n, "from": [x, 0, 0], "to": {"body": "b", "at": [0, 0, 0]},
                       "segments": [{"type": "h", "length": 99}]}
                      for n, x in (("w", -100), ("e", 100))]}


def test_table_read_in_si():
    t = table()
    body = moorsolve.load_case(case_with(t)).bodies[0]
    h = body.hydrodynamics
    assert h.source == "table" and h.omega == tuple(t["omega"])
    assert np.allclose(h.added_mass, t["added_mass"])
    assert np.allclose(h.excitation[1].im, t["excitation"][1]["im"])
    assert np.allclose(h.mean_drift[0].values, t["mean_drift"][0]["values"])


def test_table_mapping_round_trips_through_a_case():
    """Arrays written as a case-file table (6 significant digits) read back as the same
    arrays to that precision, headings, phases and signed zeros included."""
    rng = np.random.default_rng(7)
    om = np.linspace(0.3, 1.8, 4)
    A, B = rng.normal(size=(4, 6, 6)) * 1e5, rng.normal(size=(4, 6, 6)) * 1e4
    exc = {0.0: rng.normal(size=(4, 6)) * 1e5 + 1j * rng.normal(size=(4, 6)) * 1e5,
           90.0: -0.0 + 1j * rng.normal(size=(4, 6))}
    drift = {0.0: rng.normal(size=(4, 6)) * 1e3, 90.0: np.zeros((4, 6))}
    mapping = table_mapping(om, A, B, exc, drift)
    h = moorsolve.load_case(case_with(mapping)).bodies[0].hydrodynamics
    assert np.allclose(h.added_mass, A, rtol=1e-5, atol=0)
    assert np.allclose(h.damping, B, rtol=1e-5, atol=0)
    for k, (heading, x) in enumerate(exc.items()):
        assert h.excitation[k].heading_deg == heading
        assert np.allclose(np.array(h.excitation[k].re) + 1j * np.array(h.excitation[k].im),
                           x, rtol=1e-5, atol=0)
    assert np.allclose(h.mean_drift[0].values, drift[0.0], rtol=1e-5, atol=0)
    assert all(math.copysign(1.0, v) > 0 for row in mapping["excitation"][1]["re"] for v in row)
    assert "mean_drift" not in table_mapping(om, A, B, exc)


def test_interpolation_frequency_and_heading():
    t = table()
    h = BodyHydro(moorsolve.load_case(case_with(t)).bodies[0].hydrodynamics, "x")
    om = np.array(t["omega"])
    w = 0.25 * om[1] + 0.75 * om[2]
    A = np.array(t["added_mass"])
    assert np.allclose(h.added_mass([w])[0], 0.25 * A[1] + 0.75 * A[2])
    X0 = np.array(t["excitation"][0]["re"]) + 1j * np.array(t["excitation"][0]["im"])
    X1 = np.array(t["excitation"][1]["re"]) + 1j * np.array(t["excitation"][1]["im"])
    assert np.allclose(h.excitation(om, 30.0), 2 / 3 * X0 + 1 / 3 * X1)
    assert np.allclose(h.excitation(om, 90.0), X1)
    assert np.allclose(h.excitation(om, 360.0), X0)          # one turn is the same heading
    with pytest.raises(CaseError) as err:
        h.excitation(om, 135.0)
    assert err.value.field == "x.excitation" and "0, 90" in str(err.value)
    # Round the compass at its own spacing: 270 -> 360 interpolates across north.
    t4 = table(headings=(0.0, 90.0, 180.0, 270.0))
    h4 = BodyHydro(moorsolve.load_case(case_with(t4)).bodies[0].hydrodynamics, "x")
    D0, D3 = (np.array(t4["mean_drift"][k]["values"]) for k in (0, 3))
    assert np.allclose(h4.drift(om, 315.0), 0.5 * (D0 + D3))
    assert np.allclose(h4.drift(om, -45.0), 0.5 * (D0 + D3))


@pytest.mark.parametrize("edit, field, words", [
    (lambda t: t.update(omega=t["omega"][::-1]), "bodies[0].hydrodynamics.omega", "increasing"),
    (lambda t: t.update(omega=[6.0, 12.0, 18.0, 24.0, 300.0]), "bodies[0].hydrodynamics.omega",
     "period"),
    (lambda t: t.update(added_mass=t["added_mass"][:3]), "bodies[0].hydrodynamics.added_mass",
     "5 6x6 matrices"),
    (lambda t: t["excitation"][0].pop("im"), "bodies[0].hydrodynamics.excitation[0].im",
     "required"),
    (lambda t: t["excitation"][1].update(heading_deg=0), 
     "bodies[0].hydrodynamics.excitation[1].heading_deg", "strictly increasing"),
    (lambda t: t["mean_drift"][0].update(values=[[1] * 5] * 5),
     "bodies[0].hydrodynamics.mean_drift[0].values", "6 values"),
    (lambda t: t.update(source="bem"), "bodies[0].hydrodynamics.source",
     "table, wamit or capytaine"),
    (lambda t: t["damping"][0][0].__setitem__(0, "big"), "bodies[0].hydrodynamics.damping",
     "numbers only"),
])
def test_bad_tables(edit, field, words):
    t = table()
    edit(t)
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(case_with(t))
    assert err.value.field == field
    assert words in str(err.value)


def test_bad_damping():
    data = case_with(table())
    data["bodies"][0]["damping"] = {"critical_fraction": {"sideways": 0.1}}
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(data)
    assert err.value.field == "bodies[0].damping.critical_fraction.sideways"
    data["bodies"][0]["damping"] = {"linear": [1, 2, 3]}
    with pytest.raises(CaseError, match="give 6"):
        moorsolve.load_case(data)


# ---- WAMIT -----------------------------------------------------------------------------


def test_wamit_conventions_by_hand(tmp_path):
    # Rows written by hand in WAMIT's formats (User Manual v7, ch. 4), ULEN = 2 m:
    # A15 = Abar rho L^4, B15 = Bbar rho L^4 omega, X5 = Xbar rho g L^3, drift F1 = Fbar
    # rho g L, F6 = Fbar rho g L^2. A zero-frequency row (period 0) and the infinite
    # frequency row (-1) are skipped.
    per, p2 = 2 * math.pi / 0.5, 2 * math.pi / 1.0     # the shorter period's row is first
    (tmp_path / "h.1").write_text(f"-1.0 1 1 9.0\n0.0 1 1 8.0\n{p2} 1 1 7.0 7.0\n"
                                  f"{per} 1 5 1.5 0.25\n{per} 1 1 2.0 0.5\n")
    (tmp_path / "h.3").write_text(f"{per} 30.0 5 1.0 90.0 0.0 1.0\n"
                                  f"{per} 30.0 1 2.0 0.0 2.0 0.0\n"
                                  f"{p2} 30.0 1 2.0 0.0 2.0 0.0\n")
    (tmp_path / "h.8").write_text(f"{per} 30.0 30.0 1 0.5 0.0 0.5 0.0\n"
                                  f"{per} 30.0 60.0 1 9.9 0.0 9.9 0.0\n"
                                  f"{per} 30.0 30.0 6 0.25 180.0 -0.25 0.0\n"
                                  f"{p2} 30.0 30.0 1 0.5 0.0 0.5 0.0\n")
    data = case_with({"source": "wamit", "files": ["h.1", "h.3", "h.8"], "ulen": 2.0})
    import yaml
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(data))
    h = moorsolve.load_case(tmp_path / "case.yaml").bodies[0].hydrodynamics
    assert h.source == "wamit"
    assert h.omega == pytest.approx((0.5, 1.0))
    assert h.added_mass[1][0][0] == pytest.approx(7.0 * RHO * 2 ** 3)
    assert h.damping[1][0][0] == pytest.approx(7.0 * RHO * 2 ** 3 * 1.0)
    assert h.added_mass[0][0][4] == pytest.approx(1.5 * RHO * 2 ** 4)
    assert h.added_mass[0][0][0] == pytest.approx(2.0 * RHO * 2 ** 3)
    assert h.damping[0][0][4] == pytest.approx(0.25 * RHO * 2 ** 4 * 0.5)
    assert h.excitation[0].heading_deg == 30.0
    assert h.excitation[0].im[0][4] == pytest.approx(RHO * G * 2 ** 3)
    assert h.excitation[0].re[0][0] == pytest.approx(2.0 * RHO * G * 2 ** 2)
    assert h.mean_drift[0].values[0][0] == pytest.approx(0.5 * RHO * G * 2)
    assert h.mean_drift[0].values[0][5] == pytest.approx(-0.25 * RHO * G * 2 ** 2)


@pytest.mark.parametrize("drift", [".8", ".9", ".12d"])
def test_wamit_round_trip(tmp_path, drift):
    t = table(n=6, headings=(0.0, 45.0, 90.0))
    if drift == ".8":   # the momentum file has surge, sway and yaw only
        for d in t["mean_drift"]:
            d["values"] = [[v if i in (0, 1, 5) else 0.0 for i, v in enumerate(row)]
                           for row in d["values"]]
    write_wamit(tmp_path / "hull", t, ulen=3.0, rho=RHO, g=G, drift=drift)
    data = case_with({"source": "wamit", "ulen": 3.0,
                      "files": ["hull.1", "hull.3", "hull" + drift]})
    import yaml
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(data))
    case = moorsolve.load_case(tmp_path / "case.yaml")
    h = case.bodies[0].hydrodynamics
    assert np.allclose(h.omega, t["omega"], rtol=1e-8)
    assert np.allclose(h.added_mass, t["added_mass"], rtol=1e-7, atol=1e-6)
    assert np.allclose(h.damping, t["damping"], rtol=1e-7, atol=1e-6)
    for got, want in zip(h.excitation, t["excitation"]):
        assert np.allclose(got.re, want["re"], rtol=1e-7, atol=1e-6)
        assert np.allclose(got.im, want["im"], rtol=1e-7, atol=1e-6)
    for got, want in zip(h.mean_drift, t["mean_drift"]):
        assert np.allclose(got.values, want["values"], rtol=1e-7, atol=1e-6)
    # The source keeps the files' absolute names, not their values.
    kept = case.source["bodies"][0]["hydrodynamics"]
    assert "values" not in kept and all(str(tmp_path) in f for f in kept["files"])


def test_wamit_bad_files(tmp_path):
    import yaml
    (tmp_path / "h.1").write_text("6.0 1 1 one\n")
    data = case_with({"source": "wamit", "files": ["h.1", "h.3"]})
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(data))
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(tmp_path / "case.yaml")
    assert err.value.field == "bodies[0].hydrodynamics.files" and "not a row of numbers" \
        in str(err.value)
    (tmp_path / "h.1").write_text("6.0 1 1 1.0 1.0\n")
    with pytest.raises(CaseError, match="cannot read"):
        moorsolve.load_case(tmp_path / "case.yaml")
    data["bodies"][0]["hydrodynamics"]["files"] = ["h.1"]
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(data))
    with pytest.raises(CaseError, match=r"\.3 file is required"):
        moorsolve.load_case(tmp_path / "case.yaml")
    # Built from plain data (no file to read relative to), the names are refused.
    from moorsolve.model import build_case
    with pytest.raises(CaseError, match="read by moorsolve.load_case"):
        build_case(case_with({"source": "wamit", "files": ["h.1", "h.3"]}))
