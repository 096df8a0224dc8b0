"""The independent audit of a Result: is what it reports a consistent equilibrium?

It reads the Result (profiles, end forces, joints, body poses, loads; or the report's line
table, :mod:`moorsolve.model.line_table`) and the case, and recomputes from
:mod:`moorsolve.model` and :mod:`moorsolve.physics` with its own formulas. It imports
nothing from :mod:`moorsolve.solve` at run time (tests/test_imports.py holds it to that):
the solver calls it, never the reverse.

- :mod:`.run`: :func:`audit`, :func:`audit_findings`, :func:`result_warnings`,
  :class:`AuditFailure`;
- :mod:`.lines` (with :mod:`.line_data`): the per-line checks on drawn profiles;
- :mod:`.closed_form`: the same questions in closed form for one-segment catenaries,
  compiled with the body screen;
- :mod:`.bodies`: the balance of every free body and free point.
"""

from .run import (AuditFailure, air_hint, audit, audit_findings, closed_form_audit,
                  result_warnings)

__all__ = ["audit", "audit_findings", "closed_form_audit", "result_warnings", "AuditFailure",
           "air_hint"]
