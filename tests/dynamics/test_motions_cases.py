"""The shipped buoy in a storm, the command line, and what the scene does not call for
(static answers) or gets wrong (one message naming the field)."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve import CaseError, MoorsolveWarning
from moorsolve.cli import main
from moorsolve.studies.stiffness import coupled_stiffness
from conftest import CASES

BUOY = CASES / "buoy_sea.yaml"
RHO, G = 1025.0, 9.80665


@pytest.fixture(scope="module")
def buoy():
    return moorsolve.motions(moorsolve.load_case(BUOY))


def test_buoy_heave_closed_form(buoy):
    # The buoy is axisymmetric with its chains at one level round its axis: heave nearly
    # stands apart from the other DOFs, so its RAO is one DOF's closed form with the
    # table's long-wave coefficients (radius 2 m, draft 6 m) and 3 % of critical damping,
    # to 2 % (the chains, off the axis at the keel, couple heave weakly to pitch).
    a, T = 2.0, 6.0
    K = coupled_stiffness(buoy.result)[0]
    k33 = K[2, 2]
    body = buoy.result.case.body_named("buoy")
    a33 = 4 / 3 * RHO * a ** 3
    w = buoy.omega
    k = w ** 2 / G
    f3 = (RHO * G * math.pi * a ** 2 - w ** 2 * a33) * np.exp(-k * T)
    h = moorsolve.dynamics.hydro.BodyHydro(body.hydrodynamics, "x")
    b33 = h.damping(w)[:, 2, 2] + 2 * 0.03 * math.sqrt(k33 * (body.mass + a33))
    x3 = f3 / (-w ** 2 * (body.mass + a33) + 1j * w * b33 + k33)
    heaving = np.abs(x3) > 0.5          # heave-dominated: up to and through its resonance
    assert heaving.sum() > 100
    assert np.allclose(buoy.body("buoy").rao[heaving, 2], x3[heaving], rtol=2e-2)
    # Long waves lift the buoy with the surface: |X3| -> rho g Awp / K33 (the chains add
    # a little vertical stiffness to the waterplane's).
    assert abs(buoy.body("buoy").rao[0, 2]) == pytest.approx(
        RHO * G * math.pi * a ** 2 / k33, rel=0.05)


def test_buoy_sea_and_statistics(buoy):
    assert buoy.sea["simulated"] == ["mean_drift", "wave_frequency", "slow_drift"]
    # DNV's gamma from Tp/sqrt(Hs) = 7/sqrt(2.5) = 4.43: exp(5.75 - 1.15 x 4.43) = 1.93.
    assert buoy.sea["gamma"] == pytest.approx(math.exp(5.75 - 1.15 * 7 / math.sqrt(2.5)))
    b = buoy.body("buoy")
    # The mean drift pushes the buoy the way the waves go (20 deg; 20.1 deg from the
    # table's linear interpolation between its 0 and 30 deg headings).
    assert math.degrees(math.atan2(b.mean_drift[1], b.mean_drift[0])) == pytest.approx(
        math.degrees(math.atan2(2 / 3 * 0.5, 1 / 3 + 2 / 3 * math.cos(math.radians(30)))))
    assert math.degrees(math.atan2(b.mean[1], b.mean[0])) == pytest.approx(20, abs=2)
    for part in (b.wf, b.lf):
        assert np.all(part["significant"] == 2 * part["sigma"])
        assert np.all(part["max"] > part["significant"])
    # Statistics of the WF response from its own spectrum: m0 and m2 by the trapezoid.
    S = np.abs(b.rao[:, 0]) ** 2 * buoy.spectrum
    m0 = np.trapezoid(S, buoy.omega)
    m2 = np.trapezoid(buoy.omega ** 2 * S, buoy.omega)
    assert b.wf["sigma"][0] == pytest.approx(math.sqrt(m0))
    assert b.wf["tz_s"][0] == pytest.approx(2 * math.pi * math.sqrt(m0 / m2))


def test_cli_motions(tmp_path, capsys):
    assert main(["motions", str(BUOY), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    body = data["motions"]["bodies"][0]
    assert body["name"] == "buoy" and body["dofs"][0] == "surge"
    assert len(body["wf"]["sigma"]) == 6 and body["design_offset_m"] > 0
    assert len(data["motions"]["rao"]["buoy"]["re"]) == len(data["motions"]["omega"])
    assert len(data["motions"]["rao"]["buoy"]["re"][0]) == 6
    png = tmp_path / "m.png"
    assert main(["motions", str(BUOY), "--plot", str(png)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "design offset (API RP 2SK)" in capsys.readouterr().out


def _data():
    return yaml.safe_load(BUOY.read_text())


def test_static_without_period(tmp_path, capsys):
    data = _data()
    data["environment"]["waves"] = {"hs": 2.5, "toward_deg": 20}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MoorsolveWarning)
        m = moorsolve.motions(moorsolve.load_case(data))
    assert m.static and m.sea["simulated"] == [] and "environment.waves.tp" in m.sea["reason"]
    path = tmp_path / "c.yaml"
    path.write_text(yaml.safe_dump(data))
    assert main(["motions", str(path)]) == 0
    assert "static answer only" in capsys.readouterr().out


def test_floating_body_without_hydrodynamics(tmp_path, capsys):
    data = _data()
    del data["bodies"][0]["hydrodynamics"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MoorsolveWarning)
        case = moorsolve.load_case(data)
    with pytest.raises(CaseError) as err:
        moorsolve.motions(case)
    assert err.value.field == "bodies[0].hydrodynamics"
    assert "floats free in a sea state" in str(err.value)
    path = tmp_path / "c.yaml"
    path.write_text(yaml.safe_dump(data))
    assert main(["motions", str(path)]) == 2
    assert "bodies[0].hydrodynamics" in capsys.readouterr().err


def test_narrow_tables_warn_with_the_fraction():
    data = _data()
    h = data["bodies"][0]["hydrodynamics"]
    keep = [i for i, w in enumerate(h["omega"]) if w <= 1.2]
    h["omega"] = [h["omega"][i] for i in keep]
    for key in ("added_mass", "damping"):
        h[key] = [h[key][i] for i in keep]
    for e in h["excitation"]:
        e["re"], e["im"] = [e["re"][i] for i in keep], [e["im"][i] for i in keep]
    for d in h["mean_drift"]:
        d["values"] = [d["values"][i] for i in keep]
    with pytest.warns(MoorsolveWarning, match=r"hold \d+\.\d% of the spectrum's m0") as rec:
        moorsolve.motions(moorsolve.load_case(data))
    text = str(rec[0].message)
    covered = float(text.split(" hold ")[1].split("%")[0]) / 100
    from moorsolve.dynamics.spectra import jonswap, gamma_dnv
    w = np.linspace(0.01, 40, 400001)
    S = jonswap(w, 2.5, 7.0, gamma_dnv(2.5, 7.0))
    inside = (w >= 0.2) & (w <= 1.2)
    assert covered == pytest.approx(np.trapezoid(S[inside], w[inside]) / np.trapezoid(S, w),
                                     abs=1.5e-3)


def test_heading_not_covered():
    data = _data()
    h = data["bodies"][0]["hydrodynamics"]
    h["excitation"] = h["excitation"][:3]         # 0, 30, 60 deg; the waves go at 20
    h["mean_drift"] = h["mean_drift"][:1]         # 0 deg only
    with pytest.raises(CaseError) as err:
        moorsolve.motions(moorsolve.load_case(data))
    assert err.value.field == "bodies[0].hydrodynamics.mean_drift"
    assert "20 deg" in str(err.value)


def test_undamped_slow_drift():
    data = _data()
    data["bodies"][0]["damping"] = {"critical_fraction": {"heave": 0.03}}
    with pytest.raises(CaseError) as err:
        moorsolve.motions(moorsolve.load_case(data))
    assert err.value.field == "bodies[0].damping"
    assert "no damping" in str(err.value)
    # Damped only through pitch's share of the surge mode: 0.025 % of critical, warned.
    data["bodies"][0]["damping"] = {"critical_fraction": {"heave": 0.03, "roll": 0.05,
                                                          "pitch": 0.05}}
    with pytest.warns(MoorsolveWarning, match=r"bodies\[0\]\.damping: the slow drift"):
        moorsolve.motions(moorsolve.load_case(data))


@pytest.mark.parametrize("key, field", [("mass", "bodies[0].mass"),
                                        ("inertia", "bodies[0].inertia")])
def test_missing_mass_or_inertia(key, field):
    data = _data()
    del data["bodies"][0][key]
    if key == "mass":
        data["bodies"][0]["free"] = ["surge", "sway", "yaw"]
        del data["bodies"][0]["hydrostatics"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MoorsolveWarning)
        case = moorsolve.load_case(data)
    with pytest.raises(CaseError) as err:
        moorsolve.motions(case)
    assert err.value.field == field


def test_unused_sea_state_is_warned():
    data = _data()
    del data["bodies"][0]["hydrodynamics"]
    with pytest.warns(moorsolve.UnusedInputWarning, match="no body has hydrodynamics"):
        moorsolve.load_case(data)
    data = _data()
    data["environment"]["waves"] = {"hs": 2.5}
    with pytest.warns(moorsolve.UnusedInputWarning, match="no sea state") as rec:
        moorsolve.load_case(data)
    assert any(getattr(r.message, "field", "") == "bodies[0].hydrodynamics" for r in rec) or \
        any("bodies[0].hydrodynamics" in str(r.message) for r in rec)
