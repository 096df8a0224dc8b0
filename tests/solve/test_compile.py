"""Compiling the Newton kernel (issue 16): in the background, cached by structure, logged.

Each scenario runs in a fresh interpreter with its own cache folder, so it meets the
compiler as a first run does. The scene is small (one body on two chains) to keep the
compiles short; tests never assert times, only what is logged, which kernel ran and that
the answers agree.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

from conftest import ROOT

SCENE = {"environment": {"depth": 30.0},
         "line_types": {"chain": {"weight_in_water": 900.0, "ea": 4e8}},
         "body": {"free": ["surge", "sway"], "loads": {"force": [2e4, 5e3, 0.0]}},
         "legs": [{"name": "W", "anchor": [-150.0, 0.0], "fairlead": [-5.0, 0.0, 0.0],
                   "segments": [{"type": "chain", "length": 160.0}]},
                  {"name": "E", "anchor": [150.0, 0.0], "fairlead": [5.0, 0.0, 0.0],
                   "segments": [{"type": "chain", "length": 160.0}]}]}

PROBE = textwrap.dedent("""
    import json, logging, sys
    records = []
    class Keep(logging.Handler):
        def emit(self, record):
            records.append(record.getMessage())
    logging.getLogger("moorsolve").addHandler(Keep())
    logging.getLogger("moorsolve").setLevel(logging.INFO)
    import moorsolve
    from moorsolve.solve.assembly.cache import get_problem
    scene = json.loads(sys.argv[1])
    case = moorsolve.load_case(scene)
    first = moorsolve.solve(case, solver="newton")
    kernel = get_problem(case).newton()
    compiled_at_first = kernel.compiled
    ready = kernel.wait_compiled(600)
    second = moorsolve.solve(case, solver="newton")
    scene["body"]["loads"]["force"] = [-1e4, 2e4, 0.0]
    other = moorsolve.solve(moorsolve.load_case(scene), solver="newton")
    print(json.dumps({
        "records": records, "compiled_at_first": compiled_at_first, "ready": ready,
        "solvers": [first.solver, second.solver, other.solver],
        "first": first.body, "second": second.body,
        "library": str(kernel._library.path),
        "other_library": str(get_problem(moorsolve.load_case(scene)).newton()._library.path),
    }))
""")


def run_probe(tmp_path, mode: str) -> dict:
    env = {**os.environ, "MOORSOLVE_CACHE_DIR": str(tmp_path / "cache"),
           "MOORSOLVE_COMPILE": mode}
    env.pop("MOORSOLVE_NO_COMPILE", None)
    out = subprocess.run([sys.executable, "-c", PROBE, json.dumps(SCENE)], cwd=ROOT,
                         env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_background_compile_then_cached_by_structure(tmp_path):
    first_run = run_probe(tmp_path, "background")
    compiling = [r for r in first_run["records"] if r.startswith("compiling the Newton kernel")]
    assert len(compiling) == 1 and "solving interpreted meanwhile" in compiling[0]
    assert any(r.startswith("compiled the Newton kernel of 2 lines in ")
               for r in first_run["records"])
    # The first solve did not wait for the compiler; the later ones run compiled.
    assert not first_run["compiled_at_first"] and first_run["ready"]
    assert first_run["solvers"] == ["newton"] * 3
    for key in ("x_m", "y_m"):
        assert abs(first_run["first"][key] - first_run["second"][key]) < 1e-9
    # Another load on the same structure uses the same library...
    assert first_run["other_library"] == first_run["library"]
    # ... and a new process finds it by its key, without compiling.
    second_run = run_probe(tmp_path, "background")
    assert second_run["compiled_at_first"]
    assert not [r for r in second_run["records"] if r.startswith("compiling")]
    assert second_run["library"] == first_run["library"]


def test_compile_off_runs_interpreted_with_the_same_answer(tmp_path):
    run = run_probe(tmp_path, "off")
    assert not run["compiled_at_first"] and not run["ready"]
    assert run["solvers"] == ["newton"] * 3
    assert not [r for r in run["records"] if r.startswith("compil")]
    assert not (tmp_path / "cache").exists() or not list((tmp_path / "cache").iterdir())


def test_a_new_structure_gets_its_own_library(tmp_path):
    """The key is the structure (and scales): a third leg means a new library."""
    import moorsolve
    from moorsolve.solve.assembly.cache import get_problem
    from moorsolve.solve.kernels.newton import kernel_key

    two = moorsolve.load_case(SCENE)
    three = dict(SCENE, legs=SCENE["legs"] + [
        {"name": "N", "anchor": [0.0, 150.0], "fairlead": [0.0, 5.0, 0.0],
         "segments": [{"type": "chain", "length": 160.0}]}])
    heavier = dict(SCENE, body={"free": ["surge", "sway"],
                                "loads": {"force": [9e4, 0.0, 0.0]}})
    key = kernel_key(get_problem(two))
    assert kernel_key(get_problem(moorsolve.load_case(heavier))) == key
    assert kernel_key(get_problem(moorsolve.load_case(three))) != key


def test_the_cache_key_reads_every_source_that_builds_the_graphs(monkeypatch):
    """A compiled library is found by a key that hashes the sources of solve/, physics/ and
    audit/: every module of theirs, those of their sub-packages (solve/'s rooms) included,
    else an edit there would load a stale kernel from the disk cache without a word."""
    from pathlib import Path

    from moorsolve import compiled

    read = []
    original = Path.read_bytes

    def recording(path):
        read.append(Path(path).resolve())
        return original(path)

    monkeypatch.setattr(Path, "read_bytes", recording)
    first = compiled.code_version.__wrapped__()
    package = Path(compiled.__file__).resolve().parent
    expected = {p.resolve() for folder in ("solve", "physics", "audit")
                for p in (package / folder).rglob("*.py")} | {package / "compiled.py"}
    assert set(read) == expected
    assert package / "solve" / "kernels" / "newton.py" in expected    # a room's module

    # The key depends on each source's text and on where it lies.
    def edited(path, change):
        monkeypatch.setattr(Path, "read_bytes", lambda p: change(original(p))
                            if Path(p).resolve() == path else original(p))
        return compiled.code_version.__wrapped__()

    deep = package / "solve" / "kernels" / "newton.py"
    assert edited(deep, lambda text: text + b"\n# edited\n") != first
    assert edited(deep, lambda text: text) == first
