"""moorsolve: static equilibrium of moored floating bodies on elastic-catenary legs.

>>> import moorsolve
>>> case = moorsolve.load_case("cases/floating_dock.yaml")
>>> result = moorsolve.solve(case)
>>> result.to_dict()["body"]
"""

from .errors import (CaseError, ConvergenceError, MoorsolveError, MoorsolveWarning,
                     UnusedInputWarning)
from .io import (MoorDynError, case_to_moordyn, export_moordyn, export_moorpy, import_moordyn,
                 import_moorpy, load_case, moordyn_to_case_data, read_moordyn)
from .model import Case
from .solve import Certificate, LegResult, Result, solve
from .studies.sweep import sweep
from .studies.envelope import offset_envelope
from .studies.optimise import optimise
from .studies.sensitivity import sensitivity
from .studies.stiffness import (body_natural_periods, coupled_stiffness, natural_periods,
                                restoring_curve, stiffness)
from .studies.bounds import stiffness_bounds

__version__ = "0.1.0"

__all__ = ["load_case", "solve", "sweep", "Case", "Result", "LegResult", "Certificate",
           "offset_envelope", "stiffness", "coupled_stiffness", "body_natural_periods",
           "restoring_curve", "natural_periods", "sensitivity", "optimise", "stiffness_bounds",
           "read_moordyn", "moordyn_to_case_data", "import_moordyn", "case_to_moordyn",
           "export_moordyn", "MoorDynError", "import_moorpy", "export_moorpy",
           "MoorsolveError", "CaseError", "ConvergenceError", "MoorsolveWarning",
           "UnusedInputWarning", "__version__"]
