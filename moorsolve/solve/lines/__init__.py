"""Each line's part of the problem: what the line is (:mod:`.line_kinds`), its block behind
one protocol (:mod:`.blocks`; lumped-node lines in :mod:`.discrete`), its stretch-law
parameters (:mod:`.stretch_params`) and its seabed plane on a bathymetry grid
(:mod:`.bathymetry`).
"""
