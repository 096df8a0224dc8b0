"""Build the CasADi problem from a Case, solve it (IPOPT or the compiled Newton kernel),
certify it, check its stability and return a Result.

The only package that calls ``casadi.nlpsol``.
"""

from .cache import get_problem
from .equilibrium import solve
from .result import Certificate, LegResult, Result, Stability

__all__ = ["solve", "get_problem", "Result", "LegResult", "Certificate", "Stability"]
