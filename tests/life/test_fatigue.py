"""Line fatigue over a scatter diagram, end to end (moorsolve.fatigue, checks.fatigue)."""

import dataclasses
import json
import math

import numpy as np
import pytest
import yaml

import moorsolve
from moorsolve.cli import main
from moorsolve.dynamics.line_model import line_model
from moorsolve.dynamics.line_spectral import tension_statistics
from moorsolve.dynamics.spectra import jonswap
from moorsolve.errors import CaseError
from moorsolve.life.damage import narrow_band_damage, spectral_moments
from moorsolve.life.fatigue import YEAR_S, fatigue
from moorsolve.life.response import scatter_tensions


@pytest.fixture(scope="module")
def buoy(cases_dir):
    case = moorsolve.load_case(cases_dir / "buoy_fatigue.yaml")
    return case, moorsolve.solve(case)


@pytest.fixture(scope="module")
def buoy_fatigue(buoy):
    return fatigue(buoy[1])


def _raw(cases_dir):
    return yaml.safe_load((cases_dir / "buoy_fatigue.yaml").read_text())


def test_case_file_input(buoy):
    spec = buoy[0].checks.fatigue
    assert spec.design_life == pytest.approx(20 * YEAR_S)
    assert len(spec.sea_states) == 12 and spec.curve.name == "dnv_studless"
    assert spec.design_fatigue_factor == 5 and spec.method == "narrow_band"


@pytest.mark.parametrize("edit, field", [
    (lambda f: f["sea_states"]["table"][0].__setitem__(3, 0.5), "sea_states.table"),
    (lambda f: f.__setitem__("curve", {"catalog": "dnv_nylon"}), "curve.catalog"),
    (lambda f: f.__setitem__("curve", {"m": -3, "a_d": 6e10}), "curve.m"),
    (lambda f: f.__setitem__("method", "wirsching"), "method"),
    (lambda f: f.__setitem__("design_life", "20 parsecs"), "design_life"),
    (lambda f: f.__setitem__("curves", {"wire": {"catalog": "dnv_six_strand"}}), "curves"),
    (lambda f: f["sea_states"]["table"][1].__setitem__(0, -1.0), "sea_states.table[1]"),
])
def test_bad_input_names_the_field(cases_dir, edit, field):
    raw = _raw(cases_dir)
    edit(raw["checks"]["fatigue"])
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(raw)
    assert f"checks.fatigue.{field}" in str(err.value)


def test_user_curve_and_life_in_years(cases_dir):
    raw = _raw(cases_dir)
    raw["checks"]["fatigue"].update(curve={"m": 3, "a_d": 6.0e10}, design_life="10 year")
    spec = moorsolve.load_case(raw).checks.fatigue
    assert (spec.curve.m, spec.curve.a_d, spec.curve.basis) == (3.0, 6.0e10, "stress_chain")
    assert spec.design_life == pytest.approx(10 * 365.25 * 86400)


def test_tension_against_an_independent_chain(buoy):
    """One sea state's fairlead tension sigma: the scatter machinery (RAOs once per heading,
    ends moved by the rotation's derivative, the batched line solve) against
    moorsolve.motions for a case given that sea state, the fairlead moved by the small
    rotation x + theta x r, and the single-line tension_statistics. The buoy's mean drift
    tables are dropped so that both stand at the same equilibrium."""
    case, _ = buoy
    body = case.bodies[0]
    hydro = dataclasses.replace(body.hydrodynamics, mean_drift=())
    hs, tp, toward = 2.0, 7.0, 250.0
    waves = dataclasses.replace(case.environment.waves, hs=hs, tp=tp, toward_deg=toward)
    still = dataclasses.replace(case, bodies=(dataclasses.replace(body, hydrodynamics=hydro),),
                                environment=dataclasses.replace(case.environment, waves=waves))
    result = moorsolve.solve(still)
    spec = case.checks.fatigue
    ours = scatter_tensions(result, ((hs, tp, toward, 1.0),), spec.spectrum, n_omega=200,
                            n_elements=40)
    m = moorsolve.motions(result)
    rao = m.bodies[0].rao.copy()
    rao[:, 3:] *= math.pi / 180
    b = result.body_named("buoy")
    for j, leg in enumerate(result.legs):
        arm = np.array(leg.fairlead) - np.array([b["x_m"], b["y_m"], b["z_m"]])
        u = (rao[:, :3] + np.cross(rao[:, 3:], arm)).T
        S = jonswap(m.omega, hs, tp)
        ref = tension_statistics(line_model(still, result, leg.name, n_elements=40),
                                 m.omega, u, S)
        sigma = math.sqrt(np.trapezoid(ours.spectra[0, j, 1], ours.omega))
        assert sigma == pytest.approx(ref.fairlead.sigma_N, rel=2e-3)   # 3e-4 seen
        assert sigma > 0


def test_damage_is_the_sum_of_the_sea_states(buoy, buoy_fatigue):
    """Each end: damage = sum of the per-state damages, each the narrow-band formula of
    its tension spectrum over probability x life; life = design life / damage; pass iff
    DFF x D <= 1."""
    case, result = buoy
    spec = case.checks.fatigue
    tensions = scatter_tensions(result, spec.sea_states, spec.spectrum)
    area = 2 * math.pi * 0.050 ** 2 / 4 * 1e6            # two bars, mm^2 -> m^2 x 1e6
    for e in buoy_fatigue.ends:
        j = tensions.lines.index(e.line)
        k = 0 if e.end == "anchor" else 1
        expected = []
        for i, s in enumerate(spec.sea_states):
            m0, m2 = spectral_moments(tensions.omega, tensions.spectra[i, j, k] / area ** 2,
                                      (0, 2))
            expected.append(narrow_band_damage(m0, m2, s[3] * spec.design_life, 3.0, 6.0e10))
        assert e.per_state == pytest.approx(expected, rel=1e-9)
        assert e.damage == pytest.approx(sum(expected), rel=1e-12)
        assert e.life_y == pytest.approx(20.0 / e.damage, rel=1e-12)
        assert e.passed == (5 * e.damage <= 1)


def test_dirlik_and_longer_life(buoy, buoy_fatigue):
    """Dirlik on these wave-frequency tension spectra is within 10 % of the narrow band and
    below it; damage is linear in the design life and cubic in the curve's range scale."""
    case, result = buoy
    spec = case.checks.fatigue
    dirlik = fatigue(result, method="dirlik")
    for nb, dk in zip(buoy_fatigue.ends, dirlik.ends):
        assert 0.9 * nb.damage < dk.damage <= nb.damage * 1.0001
    longer = fatigue(result, dataclasses.replace(spec, design_life=2 * spec.design_life))
    for a, b in zip(buoy_fatigue.ends, longer.ends):
        assert b.damage == pytest.approx(2 * a.damage, rel=1e-9)
        assert b.life_y == pytest.approx(a.life_y, rel=1e-9)


def test_result_dict_and_text(buoy_fatigue):
    d = json.loads(json.dumps(buoy_fatigue.to_dict()))
    assert len(d["ends"]) == 6 and d["design_fatigue_factor"] == 5
    assert d["not_simulated"] == ["low_frequency_tension", "mean_drift_per_sea_state"]
    assert d["adjacent_line_rule"].startswith("not applied")
    text = repr(buoy_fatigue)
    assert "DFF x D" in text and "L3" in text


def test_plot(buoy_fatigue, tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    from moorsolve.plot.fatigue import plot_damage_per_sea_state
    ax = plot_damage_per_sea_state(buoy_fatigue)
    assert len(ax.patches) == 3 * 12
    ax.figure.savefig(tmp_path / "f.png")


def test_cli_fatigue_and_check(cases_dir, tmp_path, capsys):
    status = main(["fatigue", str(cases_dir / "buoy_fatigue.yaml"), "--json",
                   "--plot", str(tmp_path / "d.png")])
    out = json.loads(capsys.readouterr().out)
    assert status == 0 and out["passed"] and (tmp_path / "d.png").stat().st_size > 0
    status = main(["check", str(cases_dir / "buoy_fatigue.yaml"), "--json", "--no-damaged"])
    out = json.loads(capsys.readouterr().out)
    assert "fatigue" in out and len(out["fatigue"]["ends"]) == 6


def test_cli_bad_scatter_diagram_exits_2(cases_dir, tmp_path, capsys):
    raw = _raw(cases_dir)
    raw["checks"]["fatigue"]["sea_states"]["table"][0][3] = 0.9
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(raw))
    assert main(["fatigue", str(path)]) == 2
    err = capsys.readouterr().err
    assert "checks.fatigue.sea_states.table" in err and "Traceback" not in err


def test_a_case_without_fatigue_or_hydrodynamics_is_refused(cases_dir):
    with pytest.raises(CaseError, match="checks.fatigue"):
        fatigue(moorsolve.load_case(cases_dir / "buoy_sea.yaml"))


def test_tension_records_by_rainflow(buoy, tmp_path, capsys, cases_dir):
    """A record of constant-amplitude cycles: n cycles of range 2A in T_record, scaled to
    the life: D = (T_life / T_record) n (2 A / area)^3 / a_D, counted by rainflow."""
    from moorsolve.life.series import series_fatigue
    case, _ = buoy
    spec = case.checks.fatigue
    t = np.arange(0.0, 3600.0 + 1e-9, 0.25)
    amplitude = 30e3
    x = 40e3 + amplitude * np.sin(2 * np.pi * t / 8.0)          # 450 cycles in an hour
    fr = series_fatigue(case, {"time_s": t, "L1.fairlead": x})
    area = 2 * math.pi * 0.050 ** 2 / 4 * 1e6
    cycles = 3600.0 / 8.0
    expected = spec.design_life / 3600.0 * cycles * (2 * amplitude / area) ** 3 / 6.0e10
    assert fr.ends[0].damage == pytest.approx(expected, rel=2e-3)
    assert fr.method == "rainflow" and "rainflow" in repr(fr)
    path = tmp_path / "record.csv"
    np.savetxt(path, np.column_stack([t, x]), delimiter=",", header="time_s,L1.fairlead",
               comments="")
    status = main(["fatigue", str(cases_dir / "buoy_fatigue.yaml"), "--series", str(path),
                   "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["ends"][0]["damage"] == pytest.approx(expected, rel=2e-3)
    assert status == (0 if out["passed"] else 1)
    with pytest.raises(CaseError, match="LINE.anchor or LINE.fairlead"):
        series_fatigue(case, {"time_s": t, "L9.fairlead": x})


def test_a_sea_state_outside_the_hydrodynamics_is_warned_of(buoy):
    """The buoy's tables start at 0.2 rad/s: a 25 s swell holds most of its energy below."""
    case, result = buoy
    spec = dataclasses.replace(case.checks.fatigue,
                               sea_states=((1.0, 6.0, 20.0, 0.5), (1.0, 25.0, 20.0, 0.5)))
    with pytest.warns(moorsolve.MoorsolveWarning, match=r"sea_states.table\[1\]"):
        fatigue(result, spec)


def test_design_life_given_once_for_wear_and_fatigue(cases_dir):
    """The fatigue block takes checks.design_life where it gives none of its own; two
    different lives are refused by name; a plain number is years in both places."""
    raw = _raw(cases_dir)
    life = raw["checks"]["fatigue"].pop("design_life")
    raw["checks"]["design_life"] = life
    assert moorsolve.load_case(raw).checks.fatigue.design_life == pytest.approx(20 * YEAR_S)
    raw["checks"]["fatigue"]["design_life"] = 25
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(raw)
    assert err.value.field == "checks.fatigue.design_life"
    del raw["checks"]["design_life"]
    assert moorsolve.load_case(raw).checks.fatigue.design_life == pytest.approx(25 * YEAR_S)
    del raw["checks"]["fatigue"]["design_life"]
    with pytest.raises(CaseError, match="design life"):
        moorsolve.load_case(raw)
