"""End-to-end tests of the ``moorsolve`` command line (CONTRACT.md "Command line" and "Result").

Most tests call :func:`moorsolve.cli.main` in-process and read its output with ``capsys``; a few
run the real process (``python -m moorsolve.cli``) to check that nothing escapes as a traceback.
Exit status: 0 solved, 1 no equilibrium, 2 bad input (one line naming the field).
"""

from __future__ import annotations

import json
import numbers
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from moorsolve.cli import main
from conftest import ROOT

CASES_DIR = ROOT / "cases"
CASES = sorted(CASES_DIR.glob("*.yaml"))
BUOY = CASES_DIR / "buoy_vida.yaml"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

LEG_KEYS = {
    "fairlead_tension_N": float, "horizontal_tension_N": float, "fairlead_vertical_N": float,
    "anchor_tension_N": float, "anchor_horizontal_N": float, "anchor_vertical_N": float,
    "grounded_length_m": float, "touchdown_from_anchor_m": float,
    "uplift": bool, "slack": bool,
}

# ---- helpers ----------------------------------------------------------------------------


def run(argv, capsys):
    """Run the CLI in-process; return (exit status, stdout, stderr).

    argparse errors leave through SystemExit; anything else must come back as a status.
    """
    try:
        status = main([str(a) for a in argv])
    except SystemExit as exc:
        status = exc.code
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def run_process(*args, cwd=ROOT):
    """Run the CLI as a real process."""
    return subprocess.run([sys.executable, "-m", "moorsolve.cli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=120)


def buoy() -> dict:
    with open(BUOY, encoding="utf-8") as f:
        return yaml.safe_load(f)


def write_case(tmp_path: Path, data, name="case.yaml") -> Path:
    path = tmp_path / name
    with open(path, "w", encoding="utf-8") as f:
        yaml.safe_dump(data, f)
    return path


def assert_one_line(err: str) -> str:
    text = err.strip()
    assert text, "expected a message on stderr"
    assert "\n" not in text, f"stderr is not one line:\n{err}"
    assert "Traceback" not in err
    return text


def is_number(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def check_result_json(data: dict, leg_names: list) -> None:
    """Every CONTRACT.md key, with the right type, and a certified equilibrium."""
    assert data["converged"] is True
    assert isinstance(data["solver"], str) and data["solver"]
    assert isinstance(data["iterations"], int) and not isinstance(data["iterations"], bool)
    assert data["iterations"] >= 0
    assert is_number(data["solve_time_s"]) and data["solve_time_s"] >= 0
    residual = data["residual"]
    assert is_number(residual["force_N"]) and residual["force_N"] >= 0
    assert is_number(residual["moment_Nm"]) and residual["moment_Nm"] >= 0
    assert isinstance(data["effects"], list)
    assert all(isinstance(e, str) for e in data["effects"])
    body = data["body"]
    if body is None:
        # A network case with several bodies: each in "bodies" (CONTRACT.md).
        assert len(data["bodies"]) > 1
        for b in data["bodies"]:
            for key in ("x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg"):
                assert is_number(b[key]), key
        assert isinstance(data["stability"]["stable"], bool)
    else:
        for key in ("x_m", "y_m", "yaw_deg"):
            assert is_number(body[key]), key
    assert isinstance(data["legs"], list)
    assert [leg["name"] for leg in data["legs"]] == leg_names
    for leg in data["legs"]:
        assert isinstance(leg["name"], str)
        for key, kind in LEG_KEYS.items():
            assert key in leg, f"leg {leg['name']} lacks {key}"
            if kind is bool:
                assert isinstance(leg[key], bool), (leg["name"], key, leg[key])
            else:
                assert is_number(leg[key]), (leg["name"], key, leg[key])
                # A network line's end A need not be an anchor: a shared line pulls the
                # body at its end A down (a negative upward pull).
                if not (key.endswith("_vertical_N") and "bodies" in data):
                    assert leg[key] >= 0, (leg["name"], key, leg[key])
    # The largest force the scene carries: a line's tension, or a fender's or pile
    # guide's reaction (a pontoon held by guides alone may have only slack lines).
    largest = max([leg["fairlead_tension_N"] for leg in data["legs"]]
                  + [c["reaction_N"] for c in data.get("fenders", []) + data.get("guides", [])])
    assert largest > 0
    assert residual["force_N"] <= 1e-9 * largest


def leg_names(case_path: Path) -> list:
    with open(case_path, encoding="utf-8") as f:
        data = yaml.safe_load(f)
        return [leg["name"] for leg in data.get("legs") or data.get("lines") or []]


# ---- 1. solve on the shipped cases ------------------------------------------------------


def test_shipped_cases_found():
    assert {p.name for p in CASES} >= {"buoy_vida.yaml", "floating_dock.yaml", "ship_97m.yaml"}


@pytest.mark.parametrize("case", CASES, ids=lambda p: p.stem)
def test_solve_prints_table(case, capsys):
    status, out, err = run(["solve", case], capsys)
    assert status == 0, err
    assert "Traceback" not in err
    lines = out.splitlines()
    for name in leg_names(case):
        assert any(line.split() and line.split()[0] == name for line in lines), \
            f"leg {name} missing from the table:\n{out}"


@pytest.mark.parametrize("case", CASES, ids=lambda p: p.stem)
def test_solve_json(case, capsys):
    status, out, err = run(["solve", case, "--json"], capsys)
    assert status == 0, err
    check_result_json(json.loads(out), leg_names(case))


def test_solve_json_process():
    """The real process: JSON on stdout, no traceback."""
    case = CASES_DIR / "floating_dock.yaml"
    proc = run_process("solve", case, "--json")
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    check_result_json(json.loads(proc.stdout), leg_names(case))


# ---- 2. --tol ----------------------------------------------------------------------------


def test_tol_accepted(capsys):
    status, out, err = run(["solve", BUOY, "--json", "--tol", "1e-6"], capsys)
    assert status == 0, err
    data = json.loads(out)
    assert data["converged"] is True
    largest = max(leg["fairlead_tension_N"] for leg in data["legs"])
    assert data["residual"]["force_N"] <= 1e-6 * largest


@pytest.mark.parametrize("command", ["solve", "plot"])
@pytest.mark.parametrize("tol", ["0", "abc", "2"])
def test_tol_rejected(tol, command, capsys, tmp_path):
    out_png = tmp_path / "out.png"
    argv = [command, BUOY, "--tol", tol] + (["-o", out_png] if command == "plot" else [])
    status, out, err = run(argv, capsys)
    assert status == 2
    message = assert_one_line(err)
    assert "--tol" in message
    assert tol in message
    assert not out_png.exists()


# ---- 3. plot -----------------------------------------------------------------------------


def test_plot_writes_png(tmp_path, capsys):
    target = tmp_path / "out.png"
    status, out, err = run(["plot", BUOY, "-o", target], capsys)
    assert status == 0, err
    assert "Traceback" not in err
    data = target.read_bytes()
    assert len(data) > len(PNG_MAGIC)
    assert data.startswith(PNG_MAGIC)
    # Written beside the target and renamed: no temporary file is left behind.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.png"]


def test_plot_bad_extension(tmp_path, capsys):
    target = tmp_path / "out.txt"
    status, out, err = run(["plot", BUOY, "-o", target], capsys)
    assert status == 2
    message = assert_one_line(err)
    assert "--output" in message
    assert "out.txt" in message
    assert not target.exists()
    assert list(tmp_path.iterdir()) == []


def test_plot_missing_folder(tmp_path, capsys):
    target = tmp_path / "no_such_folder" / "out.png"
    status, out, err = run(["plot", BUOY, "-o", target], capsys)
    assert status == 2
    message = assert_one_line(err)
    assert "--output" in message
    assert "no_such_folder" in message
    assert not target.parent.exists()
    assert list(tmp_path.iterdir()) == []


# ---- 4. bad input -------------------------------------------------------------------------


def _set(*path_and_value):
    """A mutation setting data[path...] = value."""
    *path, key, value = path_and_value

    def mutate(data):
        node = data
        for p in path:
            node = node[p]
        node[key] = value
    return mutate


# id -> (mutation of the buoy case, substrings the message must contain: field, value)
MUTATIONS = {
    "unknown_top_level_key": (_set("colour", "red"), ["colour", "unknown key"]),
    "unknown_leg_key": (_set("legs", 0, "colour", "red"), ["legs[0].colour", "unknown key"]),
    "missing_line_type": (_set("legs", 0, "segments", 0, "type", "rope"),
                          ["legs[0].segments[0].type", "rope"]),
    "negative_length": (_set("legs", 0, "segments", 0, "length", -5.0),
                        ["legs[0].segments[0].length", "-5"]),
    "unknown_unit": (_set("legs", 0, "segments", 0, "length", "5 blargs"),
                     ["legs[0].segments[0].length", "blargs"]),
    "nan_depth": (_set("environment", "depth", float("nan")), ["environment.depth", "nan"]),
    "fairlead_below_seabed": (_set("legs", 0, "fairlead", [0.0, 0.0, -30.0]),
                              ["legs[0].fairlead", "-30"]),
    "inextensible_too_short": (_set("legs", 0, "segments", 0, "length", 10.0),
                               ["legs[0].segments", "10 m"]),
}

def _bad_yaml(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path, [name]


# id -> builder(tmp_path) returning (case path, substrings the message must contain)
FILES = {
    "invalid_yaml": lambda tmp: _bad_yaml(tmp, "broken.yaml",
                                          "environment: {depth: 22\nlegs: [\n"),
    "missing_file": lambda tmp: (tmp / "nowhere.yaml", ["nowhere.yaml", "not found"]),
    "empty_file": lambda tmp: _bad_yaml(tmp, "empty.yaml", ""),
    "yaml_list": lambda tmp: (write_case(tmp, [buoy()], "list.yaml"), ["list.yaml", "list"]),
}


def _bad_input(tmp_path, kind):
    if kind in FILES:
        return FILES[kind](tmp_path)
    mutate, expected = MUTATIONS[kind]
    data = buoy()
    mutate(data)
    return write_case(tmp_path, data), expected


def _check_bad_input(command, path, expected, tmp_path, capsys):
    out_png = tmp_path / "out.png"
    argv = ["solve", path] if command == "solve" else ["plot", path, "-o", out_png]
    before = sorted(tmp_path.iterdir())
    status, out, err = run(argv, capsys)
    assert status == 2, (status, err)
    message = assert_one_line(err)
    for text in expected:
        assert text in message, f"{text!r} not in {message!r}"
    assert out.strip() == ""
    if command == "plot":
        assert not out_png.exists()
        assert sorted(tmp_path.iterdir()) == before


@pytest.mark.parametrize("command", ["solve", "plot"])
@pytest.mark.parametrize("kind", list(MUTATIONS) + list(FILES))
def test_bad_input(kind, command, tmp_path, capsys):
    path, expected = _bad_input(tmp_path, kind)
    _check_bad_input(command, path, expected, tmp_path, capsys)


@pytest.mark.parametrize("command", ["solve", "plot"])
@pytest.mark.parametrize("where", ["depth", "length"])
def test_absurd_sizes_are_bad_input(where, command, tmp_path, capsys):
    # pint knows the parsec: the value converts, and the size check must catch it.
    data = buoy()
    if where == "depth":
        data["environment"]["depth"] = "5 parsecs"
        expected = ["environment.depth", "parsecs"]
    else:
        data["legs"][0]["segments"][0]["length"] = "5 parsecs"
        expected = ["legs[0].segments[0].length", "parsecs"]
    path = write_case(tmp_path, data)
    _check_bad_input(command, path, expected, tmp_path, capsys)


def test_bad_input_process(tmp_path):
    """The real process: one line, status 2, no traceback, no plot written."""
    data = buoy()
    data["legs"][0]["colour"] = "red"
    path = write_case(tmp_path, data)
    target = tmp_path / "out.png"
    proc = run_process("plot", path, "-o", target)
    assert proc.returncode == 2
    message = assert_one_line(proc.stderr)
    assert "legs[0].colour" in message
    assert proc.stdout.strip() == ""
    assert not target.exists()


# ---- 5. no equilibrium ----------------------------------------------------------------------


def overloaded_case(tmp_path) -> Path:
    data = buoy()
    data["body"]["loads"]["force"] = [5e7, 0, 0]
    data["line_types"]["chain"]["mbl"] = "100 kN"
    return write_case(tmp_path, data, "overload.yaml")


def _check_no_equilibrium(status, out, err):
    assert status == 1, (status, err)
    assert "Traceback" not in err
    text = err.strip().lower()
    assert "break" in text or "overload" in text, err
    assert "residual" in text, err


def test_no_equilibrium(tmp_path, capsys):
    status, out, err = run(["solve", overloaded_case(tmp_path)], capsys)
    _check_no_equilibrium(status, out, err)
    assert out.strip() == ""


def test_no_equilibrium_process(tmp_path):
    proc = run_process("solve", overloaded_case(tmp_path), "--json")
    _check_no_equilibrium(proc.returncode, proc.stdout, proc.stderr)
    assert proc.stdout.strip() == ""


def test_no_equilibrium_plot_writes_nothing(tmp_path, capsys):
    path = overloaded_case(tmp_path)
    target = tmp_path / "out.png"
    status, out, err = run(["plot", path, "-o", target], capsys)
    _check_no_equilibrium(status, out, err)
    assert not target.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["overload.yaml"]


# ---- 6. usage errors ------------------------------------------------------------------------


@pytest.mark.parametrize("argv", [["frobnicate"], ["solve"], ["plot", "x.yaml"]],
                         ids=["unknown_command", "solve_no_case", "plot_no_output"])
def test_usage_errors(argv, capsys):
    status, out, err = run(argv, capsys)
    assert status == 2
    assert_one_line(err)


def test_no_arguments_process():
    """Bare ``moorsolve``: the usage and every command on stderr, status 2, nothing on stdout."""
    proc = run_process()
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stdout == ""
    assert proc.stderr.startswith("usage: moorsolve")
    for command in ("solve", "plot", "check", "sweep", "envelope"):
        assert f"\n    {command} " in proc.stderr
    assert proc.stderr.rstrip().splitlines()[-1].startswith("moorsolve: error: name a command")
