"""What moorsolve tells its user beyond the answer (issue 18): inputs no model uses, a line
too short to reach, the one-off compile of a Newton kernel, ``--version`` and
``--allow-overload``."""

from __future__ import annotations

import copy
import logging
import math
import warnings

import pytest
import yaml

import moorsolve
from moorsolve import ConvergenceError, UnusedInputWarning

from conftest import CASES
from test_cli import run


def _data(name: str) -> dict:
    with open(CASES / name, encoding="utf-8") as f:
        return yaml.safe_load(f)


def _unused(data) -> dict:
    """``field -> message`` of the warnings ``load_case`` issues for ``data`` (or a path)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        moorsolve.load_case(data)
    found = {w.message.field: str(w.message) for w in caught
             if issubclass(w.category, UnusedInputWarning)}
    return found


# ---- inputs no model uses -------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(p.name for p in CASES.glob("*.yaml")))
def test_shipped_cases_use_every_input(name):
    # From the file: a case may name files beside it (a bathymetry grid).
    assert _unused(CASES / name) == {}


def test_waves_without_a_drift_model_are_named():
    data = _data("floating_dock.yaml")
    del data["body"]["loads"]["wave_drift"]
    found = _unused(data)
    assert list(found) == ["environment.waves"]
    assert "body.loads.wave_drift" in found["environment.waves"]
    # And the solve really is the same as without the waves.
    no_waves = copy.deepcopy(data)
    del no_waves["environment"]["waves"]
    with pytest.warns(UnusedInputWarning, match="environment.waves"):
        a = moorsolve.solve(moorsolve.load_case(data))
    b = moorsolve.solve(moorsolve.load_case(no_waves))
    assert a.body == b.body and "wave_drift" not in a.effects


def test_current_felt_by_nothing_is_named_and_line_drag_makes_it_count():
    data = _data("buoy_vida.yaml")
    data["environment"]["current"] = {"speed": 1.0, "toward_deg": 30.0}
    found = _unused(data)
    assert list(found) == ["environment.current"]
    assert "line type with drag" in found["environment.current"]
    chain = next(iter(data["line_types"].values()))
    chain["drag"] = {"normal": 1.1}
    chain.setdefault("diameter", 0.02)
    assert _unused(data) == {}


def test_load_models_without_their_flow_and_drag_without_current():
    data = _data("floating_dock.yaml")
    for flow in ("wind", "current", "waves"):
        del data["environment"][flow]
    data["line_types"]["spare"] = {"weight_in_water": 100.0, "diameter": 0.05,
                                   "drag": {"normal": 1.1}}
    data["legs"][0]["segments"] = [{"type": "spare", "length": data["legs"][0]["segments"][0]
                                    ["length"]}]
    found = _unused(data)
    assert {"body.loads.wind", "body.loads.current", "body.loads.wave_drift",
            "line_types.spare.drag"} <= set(found)
    assert "no wind" in found["body.loads.wind"]


def test_unused_line_type_friction_air_density_and_elements():
    data = _data("buoy_vida.yaml")
    data["line_types"]["unused"] = {"weight_in_water": 10.0}
    data["environment"]["air_density"] = 1.2          # used by Vida's wind model: no warning
    data["solver"] = {"line_elements": 10}
    found = _unused(data)
    assert set(found) == {"line_types.unused", "solver.line_elements"}
    del data["body"]["loads"]["wind"]
    assert "environment.air_density" in _unused(data)
    held = _data("buoy_vida.yaml")
    held["environment"]["seabed"] = {"friction": 0.5}
    assert "environment.seabed.friction" not in _unused(held)
    for leg in held["legs"]:                  # anchors lifted off the seabed
        leg["anchor"] = leg["anchor"][:2] + [-float(held["environment"]["depth"]) / 2]
    assert "environment.seabed.friction" in _unused(held)


def test_cli_prints_each_unused_input_as_one_warning_line(tmp_path, capsys):
    data = _data("floating_dock.yaml")
    del data["body"]["loads"]["wave_drift"]
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(data))
    status, out, err = run(["solve", path], capsys)
    assert status == 0
    assert err.splitlines() == [
        "moorsolve: warning: environment.waves: given but not used: the body declares no "
        "wave drift load model; add body.loads.wave_drift for it to act"]
    assert "warning" not in out


# ---- a line too short to reach ----------------------------------------------------------


SHORT = {
    "name": "too short",
    "environment": {"depth": 50.0},
    "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5.0e8, "mbl": 5.0e6}},
    "legs": [{"name": "L1", "anchor": [-130.0, 0.0], "fairlead": [0.0, 0.0, 0.0],
              "segments": [{"type": "chain", "length": 130.0}]}],
}


def test_elastic_line_too_short_says_it_cannot_reach_with_the_shortfall():
    with pytest.raises(ConvergenceError) as err:
        moorsolve.solve(moorsolve.load_case(SHORT))
    shortfall = math.hypot(130.0, 50.0) - 130.0
    assert f"leg L1 cannot reach its fairlead: it is {shortfall:.2f} m short" in err.value.reason
    assert "no equilibrium" not in str(err.value)          # the equilibrium exists
    accepted = moorsolve.solve(moorsolve.load_case(SHORT), allow_overload=True)
    leg = accepted.legs[0]
    # Stretched to the chord: the stretch of the line matches the tension it carries.
    assert leg.t_over_mbl > 1


def test_load_beyond_breaking_still_says_would_break():
    data = copy.deepcopy(SHORT)
    data["legs"][0]["segments"][0]["length"] = 150.0
    data["body"] = {"free": ["surge"], "loads": {"force": [2e7, 0, 0]}}
    with pytest.raises(ConvergenceError, match="leg L1 would break") as err:
        moorsolve.solve(moorsolve.load_case(data))
    assert "cannot reach" not in err.value.reason


def test_allow_overload_on_the_command_line(tmp_path, capsys):
    path = tmp_path / "short.yaml"
    path.write_text(yaml.safe_dump(SHORT))
    status, out, err = run(["solve", path], capsys)
    assert status == 1 and err.startswith("moorsolve: overload: leg L1 cannot reach")
    assert "--allow-overload" in err
    status, out, err = run(["solve", path, "--allow-overload"], capsys)
    assert status == 0 and "L1" in out
    png = tmp_path / "short.png"
    assert run(["plot", path, "-o", png], capsys)[0] == 1 and not png.exists()
    assert run(["plot", path, "-o", png, "--allow-overload"], capsys)[0] == 0 and png.exists()


@pytest.mark.parametrize("command", ["solve", "plot", "accuracy", "sweep", "envelope",
                                     "export-moordyn", "stiffness"])
def test_every_solving_command_takes_allow_overload(command, capsys):
    status, out, _ = run([command, "--help"], capsys)
    assert status == 0 and "--allow-overload" in out


def test_version(capsys):
    status, out, _ = run(["--version"], capsys)
    assert status == 0 and out.strip() == f"moorsolve {moorsolve.__version__}"


# ---- the compile a first Newton solve triggers -----------------------------------------------


def test_first_newton_compile_is_announced(tmp_path, monkeypatch, caplog):
    from moorsolve.solve.equilibrium import get_problem
    from moorsolve.solve.assembly.problem import EquilibriumProblem
    monkeypatch.setenv("MOORSOLVE_CACHE_DIR", str(tmp_path))
    monkeypatch.delenv("MOORSOLVE_NO_COMPILE", raising=False)
    case = moorsolve.load_case(CASES / "buoy_vida.yaml")
    cached = get_problem(case)
    fresh = EquilibriumProblem(case, cached.force_scale, cached.length_scale)
    with caplog.at_level(logging.INFO, logger="moorsolve"):
        kernel = fresh.newton()
    if kernel.compiled is None:
        pytest.skip("no C compiler: the kernel runs interpreted")
    messages = [r.getMessage() for r in caplog.records]
    assert any(m.startswith("compiling the Newton kernel of 3 lines with") and str(tmp_path)
               in m for m in messages), messages
    assert any(m.startswith("compiled the Newton kernel of 3 lines in") for m in messages), \
        messages
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="moorsolve"):
        EquilibriumProblem(case, cached.force_scale, cached.length_scale).newton()
    assert not [r for r in caplog.records if "compil" in r.getMessage()]   # from the cache


def test_unused_inputs_of_a_network_of_bodies():
    data = _data("three_platforms.yaml")
    data["environment"]["wind"] = {"speed": 20.0, "toward_deg": 0.0}
    found = _unused(data)
    assert list(found) == ["environment.wind"]
    assert "no body declares a wind load model" in found["environment.wind"]
    data["bodies"][1]["loads"] = {"wind": {"model": "drag", "area_x": 100, "area_y": 100}}
    assert _unused(data) == {}
    del data["environment"]["wind"]
    assert list(_unused(data)) == ["bodies[1].loads.wind"]
