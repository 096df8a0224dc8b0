"""moorsolve: static equilibrium of moored floating bodies on elastic-catenary legs.

>>> import moorsolve
>>> case = moorsolve.load_case("cases/floating_dock.yaml")
>>> result = moorsolve.solve(case)
>>> result.to_dict()["body"]

Importing the package is light: each public name below is imported when first used
(:mod:`moorsolve._lazy`).
"""

from __future__ import annotations

from collections.abc import Mapping

from . import solve as _solve_package  # noqa: F401  (light; binds before solve() below)
from ._lazy import lazy_exports
from .errors import (CaseError, ConvergenceError, MoorsolveError, MoorsolveWarning,
                     UnusedInputWarning)

from ._version import __version__

_NAMES = {
    "load_case": ".io.case_file",
    "read_moordyn": ".io.moordyn", "moordyn_to_case_data": ".io.moordyn",
    "import_moordyn": ".io.moordyn", "MoorDynError": ".io.moordyn",
    "case_to_moordyn": ".io.moordyn_write", "export_moordyn": ".studies.moordyn_export",
    "import_moorpy": ".io.moorpy_yaml", "export_moorpy": ".io.moorpy_yaml",
    "Case": ".model.scene",
    "Certificate": ".solve.result.classes", "LegResult": ".solve.result.classes",
    "Result": ".solve.result.classes",
    "sweep": ".studies.sweep",
    "offset_envelope": ".studies.envelope",
    "sensitivity": ".studies.sensitivity",
    "stiffness": ".studies.stiffness", "coupled_stiffness": ".studies.stiffness",
    "body_natural_periods": ".studies.stiffness", "restoring_curve": ".studies.stiffness",
    "natural_periods": ".studies.stiffness", "one_sided_stiffness": ".studies.one_sided",
    "stiffness_bounds": ".studies.bounds",
    "motions": ".dynamics.motions",
    "cost": ".checks.cost",
    "fatigue": ".life.fatigue",
}
__getattr__, __dir__ = lazy_exports(__name__, _NAMES, globals())


class _Solve:
    """Static equilibrium of ``case`` (a Case, or a dict of a case file's shape, loaded as
    :func:`moorsolve.load_case` would), certified: :func:`moorsolve.solve.equilibrium.solve`
    (keyword options ``tol``, ``solver``, ``allow_overload``, ``start``, ``stability``,
    ``audit``).

    ``moorsolve.solve`` is both this callable and the :mod:`moorsolve.solve` package: it is
    bound here, after the (light) package, so importing the package's modules later leaves
    it in place, and its attributes are the package's, so ``import moorsolve.solve.kernels.newton
    as newton`` works as for any package.
    """

    __name__ = __qualname__ = "solve"
    __module__ = "moorsolve"

    _run = None             # the solver entry, imported on the first call

    def __call__(self, case, **options):
        if isinstance(case, Mapping):          # a dict of a case file's shape
            from .io.case_file import load_case
            case = load_case(case)
        run = self._run
        if run is None:
            from .solve.equilibrium import solve as run
            self._run = run
        return run(case, **options)

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        import importlib

        try:
            return importlib.import_module(f"{__name__}.solve.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.solve.{name}":
                raise
        return getattr(_solve_package, name)

    def __repr__(self) -> str:
        return "<function moorsolve.solve(case, **options)>"


solve = _Solve()


def optimise(case, study, **options):
    """Design optimisation of ``case`` over ``study``:
    :func:`moorsolve.studies.optimise.optimise` (keyword option ``verify``).

    ``study`` is a validated :class:`~moorsolve.model.study.Study`, or a study file (str or
    path) or mapping, read and validated against ``case`` first, in one pass
    (:func:`moorsolve.io.study_file.load_study`): the study itself reads no file.
    """
    from .model.study import Study
    from .studies.optimise import optimise as run
    if not isinstance(study, Study):
        from .io.study_file import load_study
        study = load_study(study, case)
    return run(case, study, **options)


__all__ = ["load_case", "solve", "sweep", "Case", "Result", "LegResult", "Certificate",
           "offset_envelope", "stiffness", "one_sided_stiffness", "coupled_stiffness",
           "body_natural_periods", "restoring_curve", "natural_periods", "motions",
           "fatigue", "sensitivity", "optimise", "stiffness_bounds",
           "read_moordyn", "moordyn_to_case_data", "import_moordyn", "case_to_moordyn",
           "export_moordyn", "MoorDynError", "import_moorpy", "export_moorpy",
           "MoorsolveError", "CaseError", "ConvergenceError", "MoorsolveWarning",
           "UnusedInputWarning", "__version__"]
