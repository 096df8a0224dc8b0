"""Names of a package imported on first use (PEP 562), so ``import moorsolve`` stays light.

``import moorsolve`` and ``moorsolve --help`` load no CasADi, numpy, pint, pandas,
matplotlib, Dask, scipy or MoorDyn code: a package lists where each public name lives and
:func:`lazy_exports` gives it the module-level ``__getattr__`` and ``__dir__`` that import
the defining module when the name is first asked for (tests/test_imports.py checks it).
"""

from __future__ import annotations

import importlib


def lazy_exports(package: str, names: dict, namespace: dict):
    """``(__getattr__, __dir__)`` for ``package``: ``names`` maps each public name to the
    module (relative to ``package``) that defines it; ``namespace`` is the package's
    ``globals()``, where a name is kept once imported."""

    def __getattr__(name):
        where = names.get(name)
        if where is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(where, package), name)
        namespace[name] = value
        return value

    def __dir__():
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__
