"""Build the CasADi problem from a Case, run IPOPT, return a certified Result.

The only package that calls ``casadi.nlpsol``.
"""

from .equilibrium import get_problem, solve
from .result import Certificate, LegResult, Result

__all__ = ["solve", "get_problem", "Result", "LegResult", "Certificate"]
