"""Case files in and results out; the only package of moorsolve that imports yaml.

:func:`load_case` reads a YAML case file (or a dictionary of the same shape), converts
every quantity to SI and validates it into a :class:`moorsolve.model.Case`.
:func:`read_moordyn`, :func:`moordyn_to_case_data` and :func:`import_moordyn` bring a MoorDyn
input file in; :func:`case_to_moordyn` and :func:`export_moordyn` write one.
:func:`import_moorpy` and :func:`export_moorpy` do the same for MoorPy's mooring YAML.
"""

from .case_file import load_case
from .moordyn import (MoorDynError, MoorDynImport, convert_moordyn, import_moordyn,
                      moordyn_to_case_data, read_import, read_moordyn)
from .moordyn_write import case_to_moordyn, export_moordyn
from .moorpy_yaml import case_to_moorpy, export_moorpy, import_moorpy, read_moorpy

__all__ = ["load_case", "read_moordyn", "moordyn_to_case_data", "import_moordyn",
           "convert_moordyn", "read_import", "MoorDynImport", "read_moorpy", "import_moorpy",
           "case_to_moorpy", "export_moorpy",
           "case_to_moordyn", "export_moordyn", "MoorDynError"]
