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


def test_units_load_pint_only_when_a_unit_string_is_read():
    loaded = _loaded_after("""
        from moorsolve.model.units import to_si
        assert to_si(5.0, "length", "x") == 5.0
    """)
    assert "pint" not in loaded
    loaded = _loaded_after("""
        from moorsolve.model.units import to_si
        assert abs(to_si("81 mm", "length", "x") - 0.081) < 1e-15
    """)
    assert "pint" in loaded


def test_solve_stays_the_function_after_its_package_is_imported():
    """``moorsolve.solve`` is a function and a package; importing the package's modules
    must not replace the function."""
    out = subprocess.run([sys.executable, "-c", textwrap.dedent("""
        import moorsolve
        import moorsolve.solve.cache, moorsolve.solve.equilibrium
        from moorsolve.solve import Result, get_problem
        print(callable(moorsolve.solve), moorsolve.solve.__module__)
        import moorsolve.solve.newton as newton        # the package's modules, as usual
        from moorsolve.solve import equilibrium
        print(newton.__name__, equilibrium.solve.__module__, moorsolve.solve.stability.__name__)
        print(moorsolve.solve(moorsolve.load_case("cases/buoy_vida.yaml")).converged)
    """)], cwd=ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True", "moorsolve", "moorsolve.solve.newton",
                                  "moorsolve.solve.equilibrium", "moorsolve.solve.stability",
                                  "True"]


def test_every_public_name_resolves():
    import moorsolve
    for name in moorsolve.__all__:
        assert getattr(moorsolve, name) is not None, name
    assert set(moorsolve.__all__) <= set(dir(moorsolve))
