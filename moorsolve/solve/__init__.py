"""Build the CasADi problem from a Case, solve it (IPOPT or the compiled Newton kernel),
certify it, check its stability and return a Result.

The only package that calls ``casadi.nlpsol``. Its names are imported on first use
(:mod:`moorsolve._lazy`): importing the package loads no CasADi.
"""

from __future__ import annotations

from .._lazy import lazy_exports

_NAMES = {"solve": ".equilibrium", "get_problem": ".assembly.cache",
          "Result": ".result.classes", "LegResult": ".result.classes",
          "Certificate": ".result.classes", "Stability": ".result.classes"}
__getattr__, __dir__ = lazy_exports(__name__, _NAMES, globals())

__all__ = ["solve", "get_problem", "Result", "LegResult", "Certificate", "Stability"]
