"""The verdict on a solved point and the Result built from it: the Result's classes
(:mod:`.classes`), the certificate (:mod:`.certify`), why a solve failed or is refused
(:mod:`.diagnosis`), the Result assembled from a point (:mod:`.outcome`), each line's part
(:mod:`.leg_results`, profiles drawn together in :mod:`.profile_batch`, fibre rope on the
seabed in :mod:`.fibre`).

``from moorsolve.solve.result import Result`` (and ``LegResult``, ``Certificate``,
``Stability``) keeps working: the classes are imported here.
"""

from .classes import Certificate, LegResult, Result, Stability

__all__ = ["Result", "LegResult", "Certificate", "Stability"]
