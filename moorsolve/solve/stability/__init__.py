"""Static stability of an equilibrium and the search for a stable one (:mod:`.static`), and
the stable heading of weathervaning bodies (:mod:`.weathervane`).
"""
