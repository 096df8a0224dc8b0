"""The case-file schema: every section, its keys, their units, defaults, ranges and meaning.

One declaration per section, read by the validators (:func:`~moorsolve.model.fields.
check_mapping` takes the allowed and required keys from here, the defaults of the plain
settings come from here) and by ``docs/make_case_reference.py``, which writes the manual's
case-file reference from it. A key cannot be accepted without being documented, nor
documented without being accepted: tests/model/test_schema.py walks both.

Adding a section is one call, in the module of its part of the case (:mod:`.case`,
:mod:`.bodies`, :mod:`.settings`, or a new module imported below)::

    section("fatigue", "checks.fatigue", "Fatigue damage of the lines over their life.", {
        "design_life": Key("service life the damage is summed over", "time",
                           default=20 * 365.25 * 86400.0, range="> 0"),
        "sn_curve": Key("S-N curve", "choice", REQUIRED, choices=("R3_chain", "wire")),
    })

Its parent names it (``"fatigue": Key("...", "mapping", section="fatigue")`` in the
``checks`` section), and its validator calls ``check_mapping(raw, path,
section="fatigue")`` and may take a quantity's unit and default from the declaration with
:func:`~moorsolve.model.fields.schema_quantity`. The package holds data only: it imports
the unit kinds and constants, so every validator may import it.
"""

from __future__ import annotations

from ._base import NONE, REQUIRED, SECTIONS, TYPES, Key, Section, default, get, section
# The declarations, in the order the reference page lists them.
from . import case, bodies, settings, life  # noqa: F401,E402

__all__ = ["Key", "Section", "REQUIRED", "NONE", "TYPES", "SECTIONS", "section", "get",
           "default"]
