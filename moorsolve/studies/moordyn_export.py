"""A case written as a MoorDyn input file, at its equilibrium if asked: the solve composed
with io's writer (:func:`moorsolve.io.moordyn_write.export_moordyn`), so that io, a leaf,
imports no solver."""

from __future__ import annotations

import functools

__all__ = ["export_moordyn"]


def export_moordyn(case, out, *, version: int | None = None, equilibrium: bool = False,
                   tol: float | None = None, solver: str = "ipopt",
                   allow_overload: bool = False):
    """Write a case as a MoorDyn input file (atomically); returns the Result when solved.

    Parameters
    ----------
    case : str, pathlib.Path, mapping or moorsolve.Case
        The case (a case file is loaded and validated).
    out : str or pathlib.Path
        The MoorDyn file to write.
    version : 1 or 2, optional
        See :func:`moorsolve.io.moordyn_write.case_to_moordyn`.
    equilibrium : bool
        Solve the case first and write the equilibrium positions.
    tol, solver, allow_overload
        As for :func:`moorsolve.solve`, when ``equilibrium``.

    Raises
    ------
    CaseError
        Bad input (nothing written). ``ConvergenceError`` when ``equilibrium`` and the case
        has no equilibrium (nothing written).
    """
    from ..io.moordyn_write import export_moordyn as write
    solve = None
    if equilibrium:
        from ..solve.equilibrium import solve as run
        solve = functools.partial(run, tol=tol, solver=solver, allow_overload=allow_overload)
    return write(case, out, version=version, solve=solve)
