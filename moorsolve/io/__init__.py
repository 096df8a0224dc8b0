"""Case files in and results out; the only package of moorsolve that imports yaml.

:func:`load_case` reads a YAML case file (or a dictionary of the same shape), converts
every quantity to SI and validates it into a :class:`moorsolve.model.Case`.
"""

from .case_file import load_case

__all__ = ["load_case"]
