"""The accuracy ladder (`moorsolve accuracy`): it measures, it does not assert times."""

import json

import pytest

import moorsolve
from moorsolve.cli import main
from moorsolve.studies.accuracy import accuracy_ladder
from conftest import ROOT

CASES = ROOT / "cases"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def test_ladder_errors_shrink_with_tolerance_and_simpler_models_show_their_error():
    case = moorsolve.load_case(CASES / "floating_dock.yaml")
    rungs = accuracy_ladder(case, tolerances=(1e-4, 1e-8, 1e-12), repeats=1)
    by = {(r.ladder, r.setting, r.solver): r for r in rungs}
    for solver in ("ipopt", "newton"):
        loose = by[("tolerance", "tol 1e-04", solver)]
        tight = by[("tolerance", "tol 1e-12", solver)]
        # Each rung is certified at its own tolerance, so its error is within it
        # (up to the reference's own 1e-12).
        assert loose.tension_error_relative <= 1e-4
        assert tight.tension_error_relative <= 2e-12
        assert tight.tension_error_relative <= loose.tension_error_relative
        assert tight.time_s > 0 and tight.iterations >= loose.iterations
    # The dock's chains stretch by about 0.1 %: dropping EA is a visible model error.
    inext = by[("fidelity", "inextensible lines", "ipopt")]
    assert inext.tension_error_relative > 1e-3
    assert by[("fidelity", "as declared", "ipopt")].tension_error_relative <= 1e-9


def test_accuracy_command_writes_table_json_and_plot(tmp_path, capsys):
    out = tmp_path / "ladder.png"
    assert main(["accuracy", str(CASES / "ship_97m.yaml"), "--repeats", "1", "--json",
                 "--plot", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    settings = {(r["ladder"], r["setting"], r["solver"]) for r in data["rungs"]}
    assert ("tolerance", "tol 1e-04", "ipopt") in settings
    assert ("tolerance", "tol 1e-12", "newton") in settings
    assert out.read_bytes()[:8] == PNG_MAGIC
    assert main(["accuracy", str(CASES / "ship_97m.yaml"), "--repeats", "1"]) == 0
    assert "What accuracy costs" in capsys.readouterr().out


@pytest.mark.parametrize("argv, field", [
    (["--repeats", "0"], "--repeats"), (["--plot", "x.jpg"], "--plot")])
def test_accuracy_bad_options_exit_2(tmp_path, capsys, argv, field):
    argv = [a if a != "x.jpg" else str(tmp_path / a) for a in argv]
    with pytest.raises(SystemExit) if field == "--repeats" else _no_raise() as exc:
        status = main(["accuracy", str(CASES / "ship_97m.yaml"), *argv])
    status = exc.value.code if field == "--repeats" else status
    assert status == 2
    assert field in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


class _no_raise:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


@pytest.mark.parametrize("solver", ["ipopt", "newton"])
def test_solve_command_takes_solver(capsys, solver):
    assert main(["solve", str(CASES / "buoy_vida.yaml"), "--json", "--solver", solver,
                 "--no-profiles"]) == 0
    assert json.loads(capsys.readouterr().out)["solver"] == solver
