"""The problem: a scene's equilibrium built once per structure as one CasADi problem.

The parameter layout (:mod:`.layout`) and vector (:mod:`.prepared`, what is derived once per
Case object), the assembly of bodies, points, lines and contacts (:mod:`.problem`), the
balance of the nodes (:mod:`.nodes`, :mod:`.body_loads`), the effects a scene calls for
(:mod:`.effects`), and the locked cache of built problems (:mod:`.cache`).
"""
