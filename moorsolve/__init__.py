"""moorsolve: static equilibrium of moored floating bodies on elastic-catenary legs.

>>> import moorsolve
>>> case = moorsolve.load_case("cases/floating_dock.yaml")
>>> result = moorsolve.solve(case)
>>> result.to_dict()["body"]

Importing the package is light: each public name below is imported when first used
(:mod:`moorsolve._lazy`).
"""

from __future__ import annotations

from . import solve as _solve_package  # noqa: F401  (light; binds before solve() below)
from ._lazy import lazy_exports
from .errors import (CaseError, ConvergenceError, MoorsolveError, MoorsolveWarning,
                     UnusedInputWarning)

__version__ = "0.1.0"

_NAMES = {
    "load_case": ".io.case_file",
    "read_moordyn": ".io.moordyn", "moordyn_to_case_data": ".io.moordyn",
    "import_moordyn": ".io.moordyn", "MoorDynError": ".io.moordyn",
    "case_to_moordyn": ".io.moordyn_write", "export_moordyn": ".io.moordyn_write",
    "import_moorpy": ".io.moorpy_yaml", "export_moorpy": ".io.moorpy_yaml",
    "Case": ".model.scene",
    "Certificate": ".solve.result", "LegResult": ".solve.result", "Result": ".solve.result",
    "sweep": ".studies.sweep",
    "offset_envelope": ".studies.envelope",
    "optimise": ".studies.optimise",
    "sensitivity": ".studies.sensitivity",
    "stiffness": ".studies.stiffness", "coupled_stiffness": ".studies.stiffness",
    "body_natural_periods": ".studies.stiffness", "restoring_curve": ".studies.stiffness",
    "natural_periods": ".studies.stiffness",
    "stiffness_bounds": ".studies.bounds",
}
__getattr__, __dir__ = lazy_exports(__name__, _NAMES, globals())


def solve(case, **options):
    """Static equilibrium of ``case``, certified: :func:`moorsolve.solve.equilibrium.solve`
    (keyword options ``tol``, ``solver``, ``allow_overload``, ``start``, ``stability``).

    The name ``moorsolve.solve`` is both this function and the :mod:`moorsolve.solve`
    package; the function is bound here, after the (light) package, so importing any of
    the package's modules later leaves it in place.
    """
    run = _SOLVE or _import_solve()
    return run(case, **options)


_SOLVE = None


def _import_solve():
    global _SOLVE
    from .solve.equilibrium import solve as run
    _SOLVE = run
    return run


__all__ = ["load_case", "solve", "sweep", "Case", "Result", "LegResult", "Certificate",
           "offset_envelope", "stiffness", "coupled_stiffness", "body_natural_periods",
           "restoring_curve", "natural_periods", "sensitivity", "optimise", "stiffness_bounds",
           "read_moordyn", "moordyn_to_case_data", "import_moordyn", "case_to_moordyn",
           "export_moordyn", "MoorDynError", "import_moorpy", "export_moorpy",
           "MoorsolveError", "CaseError", "ConvergenceError", "MoorsolveWarning",
           "UnusedInputWarning", "__version__"]
