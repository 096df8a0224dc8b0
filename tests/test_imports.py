"""What importing moorsolve loads: no heavy library before it is used (issue 16).

Start-up time is measured in benchmarks/ (benchmarks/startup.py); these tests check the
cause instead of a time: which modules a fresh interpreter holds after an import or a
command, read from ``sys.modules`` in a subprocess.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

from conftest import ROOT

#: Libraries that cost tens to hundreds of milliseconds to import.
HEAVY = ("casadi", "numpy", "pint", "pandas", "matplotlib", "dask", "distributed",
         "scipy", "moordyn", "yaml", "tqdm", "pyarrow")


def _loaded_after(code: str) -> set:
    """Top-level packages of ``HEAVY`` in ``sys.modules`` after running ``code``."""
    probe = textwrap.dedent(code) + textwrap.dedent(f"""
        import json, sys
        print(json.dumps(sorted({{m.split(".")[0] for m in sys.modules}} & set({HEAVY!r}))))
    """)
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True,
                         text=True, check=True)
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def test_import_moorsolve_loads_no_heavy_library():
    assert _loaded_after("import moorsolve") == set()


def test_help_loads_no_heavy_library():
    loaded = _loaded_after("""
        import contextlib, io
        from moorsolve.cli import main
        with contextlib.redirect_stdout(io.StringIO()):
            try:
                main(["--help"])
            except SystemExit:
                pass
    """)
    assert loaded == set()


def test_every_subcommand_help_loads_no_heavy_library():
    loaded = _loaded_after("""
        import contextlib, io
        from moorsolve.cli import _parser, main
        parser = _parser()
        commands = parser._subparsers._group_actions[0].choices
        with contextlib.redirect_stdout(io.StringIO()):
            for name in commands:
                try:
                    main([name, "--help"])
                except SystemExit:
                    pass
    """)
    assert loaded == set()


def test_plain_case_needs_no_units_solver_or_tables():
    """A case of plain SI numbers is validated without pint, CasADi or pandas."""
    loaded = _loaded_after("""
        import moorsolve
        moorsolve.load_case({"environment": {"depth": 50.0},
                             "line_types": {"chain": {"weight_in_water": 1000.0}},
                             "legs": [{"name": "L1", "anchor": [300.0, 0.0],
                                       "fairlead": [0.0, 0.0, 0.0],
                                       "segments": [{"type": "chain", "length": 320.0}]}]})
    """)
    assert not loaded & {"pint", "casadi", "pandas", "matplotlib", "dask", "scipy",
                         "moordyn"}


def test_units_load_pint_only_when_a_unit_outside_the_common_ones_is_read():
    loaded = _loaded_after("""
        from moorsolve.model.units import to_si
        assert to_si(5.0, "length", "x") == 5.0
        assert abs(to_si("81 mm", "length", "x") - 0.081) < 1e-15   # a common unit
    """)
    assert "pint" not in loaded
    loaded = _loaded_after("""
        from moorsolve.model.units import to_si
        assert abs(to_si("3 yd", "length", "x") - 2.7432) < 1e-12
    """)
    assert "pint" in loaded


def test_solve_stays_the_function_after_its_package_is_imported():
    """``moorsolve.solve`` is a function and a package; importing the package's modules
    must not replace the function."""
    out = subprocess.run([sys.executable, "-c", textwrap.dedent("""
        import moorsolve
        import moorsolve.solve.assembly.cache, moorsolve.solve.equilibrium
        from moorsolve.solve import Result, get_problem
        print(callable(moorsolve.solve), moorsolve.solve.__module__)
        import moorsolve.solve.kernels.newton as newton        # the package's modules, as usual
        from moorsolve.solve import equilibrium
        print(newton.__name__, equilibrium.solve.__module__, moorsolve.solve.stability.__name__)
        print(moorsolve.solve(moorsolve.load_case("cases/buoy_vida.yaml")).converged)
    """)], cwd=ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True", "moorsolve", "moorsolve.solve.kernels.newton",
                                  "moorsolve.solve.equilibrium", "moorsolve.solve.stability",
                                  "True"]


def test_every_public_name_resolves():
    import moorsolve
    for name in moorsolve.__all__:
        assert getattr(moorsolve, name) is not None, name
    assert set(moorsolve.__all__) <= set(dir(moorsolve))


# ---- the house's layering, read from the imports of the package's source ------------------

import ast  # noqa: E402
from pathlib import Path  # noqa: E402

PACKAGE = Path(ROOT) / "moorsolve"
#: What io (a leaf) may import of moorsolve: itself, the model and what lies below it.
BELOW_MODEL = {"io", "model", "catalog", "constants", "errors", "_lazy", "_version"}
#: Functions that read a file (or a case, study or table from one): no study calls them.
FILE_READERS = {"load_case", "load_study", "load_case_variant", "read_table", "read_moordyn",
                "read_moorpy", "read_import", "import_moordyn", "import_moorpy",
                "read_bathymetry", "_read_yaml", "open", "read_csv", "read_parquet",
                "read_text", "read_bytes", "safe_load"}


def _modules(package: str | None = None):
    """``(dotted name, path, tree)`` of every module of moorsolve (or of one package); a
    package's ``__init__.py`` goes by the package's name, as Python imports it."""
    root = PACKAGE if package is None else PACKAGE / package
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        yield ".".join(parts), path, ast.parse(path.read_text(encoding="utf-8"))


def _run_time_imports(name: str, path: Path, tree) -> list:
    """``(module imported, line)`` of every import of ``tree`` that runs (a function's too),
    relative imports resolved; what an ``if TYPE_CHECKING:`` block imports is left out."""
    checking = {id(node) for block in ast.walk(tree) if isinstance(block, ast.If)
                and "TYPE_CHECKING" in ast.unparse(block.test) for node in ast.walk(block)}
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if id(node) in checking:
            continue
        if isinstance(node, ast.Import):
            out += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                stem = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(stem + ([node.module] if node.module else []))
            if node.module is None:
                out += [(f"{base}.{alias.name}", node.lineno) for alias in node.names]
            else:
                out.append((base, node.lineno))
    return out


def _floor(module: str) -> str | None:
    """The package (or top-level module) of moorsolve that ``module`` is in."""
    parts = module.split(".")
    return parts[1] if parts[0] == "moorsolve" and len(parts) > 1 else None


def test_the_audit_imports_no_solver_code_at_run_time():
    """The audit is independent by structure: it recomputes from model/ and physics/ and
    imports nothing of solve/ (nor of what is built on it) except for annotations."""
    found = [f"{name}:{line} imports {target}"
             for name, path, tree in _modules("audit")
             for target, line in _run_time_imports(name, path, tree)
             if _floor(target) in {"solve", "studies", "checks", "report", "plot", "cli"}]
    assert found == []


def test_io_is_a_leaf():
    """io imports nothing above model/ (the solver, the studies, the reports)."""
    found = [f"{name}:{line} imports {target}"
             for name, path, tree in _modules("io")
             for target, line in _run_time_imports(name, path, tree)
             if _floor(target) is not None and _floor(target) not in BELOW_MODEL]
    assert found == []


def test_studies_read_no_file():
    """Studies edit scenes through the model (Case.with_values), never through files: no
    study calls a file reader, and from io a study imports only its writers."""
    calls, imports = [], []
    for name, path, tree in _modules("studies"):
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                f = node.func
                callee = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
                if callee in FILE_READERS:
                    calls.append(f"{name}:{node.lineno} calls {callee}")
        imports += [f"{name}:{line} imports {target}"
                    for target, line in _run_time_imports(name, path, tree)
                    if _floor(target) == "io"
                    and target not in ("moorsolve.io.sweep_output", "moorsolve.io.moordyn_write")]
    assert calls == [] and imports == []


def test_no_module_past_550_lines():
    lengths = {name: len(path.read_text(encoding="utf-8").splitlines())
               for name, path, _ in _modules()}
    assert {name: n for name, n in lengths.items() if n > 550} == {}


def test_the_layering_check_sees_what_it_forbids():
    """The checks above find a forbidden import where there is one (else they pass
    vacuously): a solver import in a function, and a relative import two levels up."""
    tree = ast.parse("def f():\n    from ..solve.result import Result\n"
                     "from typing import TYPE_CHECKING\n"
                     "if TYPE_CHECKING:\n    from ..solve import problem\n")
    found = _run_time_imports("moorsolve.audit.run", PACKAGE / "audit" / "run.py", tree)
    assert sorted((t, _floor(t)) for t, _ in found) == [("moorsolve.solve.result", "solve"),
                                                        ("typing", None)]
    # The same import in a package's __init__.py, resolved from the package's own name.
    name, path, _ = next(m for m in _modules("audit") if m[1].name == "__init__.py")
    found = _run_time_imports(name, path, ast.parse("from ..solve.result import Result\n"))
    assert [_floor(t) for t, _ in found] == ["solve"]


def test_no_import_cycles():
    """No cycle among the package's modules, function-level imports included (a lazy import
    back up the floors is a cycle all the same)."""
    modules = {name: (path, tree) for name, path, tree in _modules()}
    graph = {name: {target for target, _ in _run_time_imports(name, path, tree)
                    if target in modules and target != name}
             for name, (path, tree) in modules.items()}
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for name in graph:
        if name not in index:
            visit(name)
    assert not cycles, cycles
