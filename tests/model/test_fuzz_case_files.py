"""Fuzzed case files: hostile input gets a Case or a CaseError naming the field, nothing else.

Hypothesis mutates the shipped cases (as dictionaries and as YAML text) with wrong types,
missing and unknown keys, NaN, infinities, negative and zero quantities, bad unit strings,
absurd sizes and duplicate names, then feeds them to ``moorsolve.load_case`` and to the
command line. The promise (issue 7): a valid case or a CaseError / exit status 2 with one
line naming the field; never another exception, never a traceback, never a partial output
file.
"""

from __future__ import annotations

import copy
import math
import os
import re
import tempfile
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from hypothesis_budget import examples

from moorsolve import Case, CaseError, load_case
from moorsolve.cli import main
from conftest import ROOT

SHIPPED = {p.stem: yaml.safe_load(p.read_text(encoding="utf-8"))
           for p in sorted((ROOT / "cases").glob("*.yaml"))}
SMALL = ("buoy_vida", "ship_97m")      # quick to solve: the CLI runs solve on valid mutants

NAN, INF = float("nan"), float("inf")
BAD_NUMBERS = [NAN, INF, -INF, 0, 0.0, -1, -1e-300, 1e300, -1e300, 10**400, 1e-320, True,
               False]
BAD_STRINGS = ["", " ", "nan", "inf", "-inf", "NaN m", "inf kN", "1e999 m", "5 parsec",
               "5 kN/m/s", "kN", "12 12 m", "5 m**99", "5 degC", "5 dB", "9**9**9 m",
               "5 m; import os", "0x10 m", "1,5 m", "\x00", "é", "5 t/m", "-5 m", "0 m",
               "1e308 km", "5 lightyear", "5 s", "5 m/s", "30 deg", "5 kn", "-0 N"]
WRONG_TYPES = [None, [], {}, [1, 2], [1, 2, 3, 4], {"a": 1}, {"model": "drag"}, "text",
               [[1, 2, 3]], [None], {1: 2}, {None: 1}, ("t", "u")]


def _paths(node, path=()):
    """Every path to a value in a nested dict/list."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield path + (key,)
            yield from _paths(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield path + (i,)
            yield from _paths(value, path + (i,))


def _containers(node, path=()):
    if isinstance(node, dict):
        yield path
        for key, value in node.items():
            yield from _containers(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _containers(value, path + (i,))


def _get(node, path):
    for key in path:
        node = node[key]
    return node


junk = st.one_of(
    st.sampled_from(BAD_NUMBERS), st.sampled_from(BAD_STRINGS), st.sampled_from(WRONG_TYPES),
    st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**30, 10**30),
    st.text(max_size=12), st.booleans())


@st.composite
def mutation(draw, case):
    """One edit of ``case`` (in place); returns a label for statistics."""
    kind = draw(st.sampled_from(["set", "delete", "unknown_key", "negate", "zero", "scale",
                                 "duplicate_leg", "duplicate_name", "huge_list", "unit"]))
    paths = list(_paths(case))
    if kind in ("set", "delete", "negate", "zero", "scale", "unit"):
        path = draw(st.sampled_from(paths))
        parent, key = _get(case, path[:-1]), path[-1]
        if kind == "delete":
            del parent[key]
        elif kind == "set":
            parent[key] = copy.deepcopy(draw(junk))
        elif kind == "unit":
            value = parent[key]
            number = value if isinstance(value, (int, float)) and not isinstance(value, bool) \
                else draw(st.floats(-1e3, 1e3))
            unit = draw(st.sampled_from(["m", "mm", "km", "N", "kN", "t/m", "kg/m", "kgf", "kn",
                                         "m/s", "deg", "rad", "s", "m^2", "kg/m^3", "bogus",
                                         "m/s^2", "tf/m", "%"]))
            parent[key] = f"{number} {unit}"
        elif (isinstance(parent[key], (int, float)) and not isinstance(parent[key], bool)
              and abs(parent[key]) < 1e300):
            factor = {"negate": -1.0, "zero": 0.0}.get(kind)
            if factor is None:
                factor = draw(st.sampled_from([1e-30, 1e-9, 1e9, 1e30, 1e300]))
            parent[key] = parent[key] * factor
        else:
            return "noop"
        return kind
    if kind == "unknown_key":
        target = _get(case, draw(st.sampled_from(list(_containers(case)))))
        target[draw(st.sampled_from(["extra", "Depth", "ea ", "typo", "legs2", 7, None, 1.5]))] = 1
        return kind
    legs = case.get("legs")
    if not isinstance(legs, list) or not legs:
        return "noop"
    if kind == "duplicate_leg":
        legs.append(copy.deepcopy(draw(st.sampled_from(legs))))
    elif kind == "duplicate_name":
        if len(legs) < 2 or not all(isinstance(leg, dict) for leg in legs[:2]):
            return "noop"
        legs[1]["name"] = legs[0].get("name")
    elif kind == "huge_list":
        legs.extend(copy.deepcopy(legs[-1]) for _ in range(draw(st.sampled_from([50, 500]))))
    return kind


@st.composite
def mutated_case(draw, names=tuple(SHIPPED)):
    name = draw(st.sampled_from(names))
    case = copy.deepcopy(SHIPPED[name])
    labels = [draw(mutation(case)) for _ in range(draw(st.integers(1, 3)))]
    return name, case, labels


def assert_names_a_field(err: CaseError, case) -> None:
    assert isinstance(err.field, str)
    text = str(err)
    assert "Traceback" not in text and "\n" not in text.strip()
    assert err.detail, "a CaseError needs a message"


@settings(max_examples=examples(300), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(mutated_case())
def test_mutated_dict_gives_case_or_case_error(sample):
    name, case, labels = sample
    for label in labels:
        event(label)
    try:
        result = load_case(case)
    except CaseError as err:
        event("CaseError")
        assert_names_a_field(err, case)
    else:
        event("valid")
        assert isinstance(result, Case)
        for leg in result.legs:
            assert all(math.isfinite(v) for v in leg.anchor + leg.fairlead)
            assert leg.length > 0 and math.isfinite(leg.length)
        assert len({leg.name for leg in result.legs}) == len(result.legs)


# ---- YAML text mutations ----------------------------------------------------------------

TEXT_EDITS = [
    lambda t: t.replace("legs:", "legs:\nlegs:", 1),                       # duplicate key
    lambda t: t.replace("depth:", "depth: !!python/object:os.system\n  depth:", 1),
    lambda t: t.replace(":", "", 1),
    lambda t: t.replace("  ", "\t", 1),
    lambda t: t[: len(t) // 2],                                            # truncated
    lambda t: t + "\n---\nname: second document\n",
    lambda t: "a: &a [x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a]\n" + t,
    lambda t: t.replace("name:", "name: &n\n  - *n\n  -", 1),
    lambda t: t.replace("22.0", "2020-13-45", 1).replace("20.85", "2020-13-45", 1),
    lambda t: t.replace("depth: ", "depth: .nan #", 1),
    lambda t: t.replace("depth: ", "depth: -.inf #", 1),
    lambda t: t.replace("weight_in_water:", "weight_in_water: !!binary aGVsbG8= #", 1),
    lambda t: t.replace("legs:", "legs: !!set {a, b}\nunused:", 1),
    lambda t: "\ufeff" + t,
    lambda t: t.encode("utf-8").decode("latin-1") + "\u00ff",
    lambda t: "[" * 1200 + "]" * 1200,                               # deeper than Python
    lambda t: "",
    lambda t: "just a string",
    lambda t: t.replace("segments:", "segments: {<<: [*undefined]}\n  x:", 1),
]


# Edits that ignore the file's content run on one case only.
CONTENT_FREE = {15, 16, 17}
TEXT_CASES = [(name, edit) for edit in range(len(TEXT_EDITS)) for name in sorted(SHIPPED)
              if edit not in CONTENT_FREE or name == "ship_97m"]


@pytest.mark.parametrize("name, edit", TEXT_CASES)
def test_mutated_yaml_text_gives_case_or_case_error(tmp_path, name, edit):
    text = TEXT_EDITS[edit]((ROOT / "cases" / f"{name}.yaml").read_text(encoding="utf-8"))
    path = tmp_path / "case.yaml"
    path.write_text(text, encoding="utf-8")
    try:
        result = load_case(path)
    except CaseError as err:
        assert_names_a_field(err, None)
    else:
        assert isinstance(result, Case)


# ---- the command line -------------------------------------------------------------------

def run_cli(argv, capsys):
    try:
        status = main([str(a) for a in argv])
    except SystemExit as exc:            # argparse usage errors only
        status = exc.code
    captured = capsys.readouterr()
    return status, captured.out, captured.err


FIELD_LINE = re.compile(r"^moorsolve: bad input: \S")


@settings(max_examples=examples(25), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture,
                                 HealthCheck.data_too_large])
@given(sample=mutated_case(SMALL),
       command=st.sampled_from(["solve", "solve --json", "solve", "plot"]))
def test_mutated_case_through_the_cli(tmp_path, capfd, sample, command):
    name, case, labels = sample
    folder = Path(tempfile.mkdtemp(dir=tmp_path))
    path = folder / "case.yaml"
    try:
        path.write_text(yaml.safe_dump(case, allow_unicode=True), encoding="utf-8")
    except (yaml.YAMLError, ValueError):
        return                                   # not representable as YAML (e.g. a tuple)
    out_png = folder / "out.png"
    argv = command.split() + [path]
    if command == "plot":
        argv += ["-o", out_png]
    status, out, err = run_cli(argv, capfd)      # capfd: CasADi's C-level output too
    event(f"exit {status}")
    assert status in (0, 1, 2), (status, err)
    assert "Traceback" not in out + err
    if status == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and FIELD_LINE.match(lines[0]), err
        assert out == ""
    if status == 1:
        # Warnings about inputs no model uses may come first, one line each.
        lines = [line for line in err.strip().splitlines()
                 if not line.startswith("moorsolve: warning: ")]
        assert len(lines) == 1, err
        assert lines[0].startswith(("moorsolve: no equilibrium:", "moorsolve: overload:")), err
    leftovers = sorted(p.name for p in folder.iterdir() if p.name != "case.yaml")
    if command == "plot" and status == 0:
        assert leftovers == ["out.png"]
        assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    else:
        assert leftovers == [], leftovers           # nothing half-written


@pytest.mark.parametrize("edit", range(len(TEXT_EDITS)))
def test_mutated_yaml_text_through_the_cli(tmp_path, capfd, edit):
    text = TEXT_EDITS[edit]((ROOT / "cases" / "buoy_vida.yaml").read_text(encoding="utf-8"))
    path = tmp_path / "case.yaml"
    path.write_text(text, encoding="utf-8")
    status, out, err = run_cli(["plot", path, "-o", tmp_path / "out.png"], capfd)
    assert status in (0, 2), err
    assert "Traceback" not in err
    if status == 2:
        assert FIELD_LINE.match(err) and len(err.strip().splitlines()) == 1, err
        assert sorted(os.listdir(tmp_path)) == ["case.yaml"]


# ---- absurd sizes: found by fuzzing to reach the solver as overflow -----------------------

ABSURD = [
    (("line_types", "chain", "weight_in_water"), 1e300, "weight_in_water"),
    (("line_types", "chain", "weight_in_water"), 1e-300, "weight_in_water"),
    (("line_types", "chain", "ea"), 1e-300, "ea"),
    (("line_types", "chain", "ea"), 1e300, "ea"),
    (("environment", "depth"), 1e-300, "depth"),
    (("environment", "gravity"), 1e-300, "gravity"),
    (("environment", "air_density"), 1e300, "air_density"),
    (("environment", "wind", "speed"), 1e300, "speed"),
    (("body", "loads", "wind", "area_x"), 1e300, "area_x"),
    (("body", "loads", "force"), [1e300, 0, 0], "force[0]"),
    (("legs", 0, "segments", 0, "length"), 1e-300, "length"),
]


@pytest.mark.parametrize("path, value, field", ABSURD, ids=[a[2] + str(a[1]) for a in ABSURD])
def test_absurd_sizes_are_bad_input_not_overflow(tmp_path, capfd, path, value, field):
    """Before the plausibility limits these reached the solver as inf/NaN and came back as
    "no equilibrium" with CasADi and numpy warnings on stderr."""
    case = copy.deepcopy(SHIPPED["buoy_vida"])
    _get(case, path[:-1])[path[-1]] = value
    with pytest.raises(CaseError) as err:
        load_case(case)
    assert field in err.value.field
    file = tmp_path / "case.yaml"
    file.write_text(yaml.safe_dump(case), encoding="utf-8")
    status, out, errtext = run_cli(["solve", file], capfd)
    assert status == 2 and out == ""
    assert FIELD_LINE.match(errtext) and len(errtext.strip().splitlines()) == 1, errtext
