"""Case files in and results out; the only package of moorsolve that imports yaml.

:func:`load_case` reads a YAML case file (or a dictionary of the same shape), converts
every quantity to SI and validates it into a :class:`moorsolve.model.Case`.
:func:`read_moordyn`, :func:`moordyn_to_case_data` and :func:`import_moordyn` bring a MoorDyn
input file in; :func:`case_to_moordyn` and :func:`export_moordyn` write one. Each name is
imported on first use (:mod:`moorsolve._lazy`).
"""

from __future__ import annotations

from .._lazy import lazy_exports

_NAMES = {"load_case": ".case_file", "read_moordyn": ".moordyn",
          "moordyn_to_case_data": ".moordyn", "import_moordyn": ".moordyn",
          "MoorDynError": ".moordyn", "case_to_moordyn": ".moordyn_write",
          "export_moordyn": ".moordyn_write"}
__getattr__, __dir__ = lazy_exports(__name__, _NAMES, globals())

__all__ = ["load_case", "read_moordyn", "moordyn_to_case_data", "import_moordyn",
           "case_to_moordyn", "export_moordyn", "MoorDynError"]
