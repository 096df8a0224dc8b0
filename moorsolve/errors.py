"""Exceptions raised by moorsolve.

Three kinds of failure reach a user: bad input (:class:`CaseError`), no equilibrium
(:class:`ConvergenceError`) and everything else the library chooses to report
(:class:`MoorsolveError`, the common base).
"""

from __future__ import annotations


class MoorsolveError(Exception):
    """Base class of every error moorsolve raises on purpose."""


class CaseError(MoorsolveError, ValueError):
    """A case file or case dictionary is invalid.

    Parameters
    ----------
    field : str
        Dotted path of the offending field, e.g. ``legs[3].segments[0].length``.
    message : str
        What is wrong and what is allowed, e.g. ``-5 m must be > 0``.
    """

    def __init__(self, field: str, message: str):
        self.field = field
        self.detail = message
        super().__init__(f"{field}: {message}" if field else message)


class ConvergenceError(MoorsolveError, RuntimeError):
    """No certified equilibrium was found.

    Attributes
    ----------
    reason : str
        The physical reason when one was diagnosed (a line that cannot reach, legs that
        would break, a load direction nothing restrains), else the solver's own status.
    residual_N : float
        The largest unbalanced force [N] at the best point reached.
    residual_Nm : float
        The largest unbalanced moment [N m] at the best point reached.
    status : str
        The solver's return status.
    iterations : int
        Solver iterations spent.
    result : moorsolve.Result or None
        The best point reached, for inspection (not an equilibrium).
    """

    def __init__(self, reason: str, *, residual_N: float = float("nan"),
                 residual_Nm: float = float("nan"), status: str = "",
                 iterations: int = 0, result=None, certified: bool | None = None):
        self.reason = reason
        self.residual_N = residual_N
        self.residual_Nm = residual_Nm
        self.status = status
        self.iterations = iterations
        self.result = result
        if certified is None:
            certified = result is not None and getattr(result, "converged", False)
        if certified:
            # An equilibrium was found and certified but is not acceptable (a line over
            # its breaking load): say so rather than "no equilibrium".
            text = (f"{reason} (a certified equilibrium: force residual {residual_N:.3g} N, "
                    f"moment residual {residual_Nm:.3g} N m)")
        else:
            text = (f"no equilibrium: {reason} (best force residual {residual_N:.3g} N, "
                    f"moment residual {residual_Nm:.3g} N m, solver status {status or 'n/a'}, "
                    f"{iterations} iterations)")
        super().__init__(text)


class MoorsolveWarning(UserWarning):
    """Base class of the warnings moorsolve issues."""


class UnusedInputWarning(MoorsolveWarning):
    """A case gives an input that no model uses (see :mod:`moorsolve.model.usage`).

    Attributes
    ----------
    field : str
        Dotted path of the unused input, e.g. ``environment.waves``.
    """

    def __init__(self, field: str, message: str):
        self.field = field
        super().__init__(f"{field}: {message}")
