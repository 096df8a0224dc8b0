"""The numerical solvers of a built problem and how a solve uses them: IPOPT's solver
objects (:mod:`.ipopt_solvers`, one BLAS thread: :mod:`.bundled_blas`), the compiled Newton
kernel (:mod:`.newton`), the problem's access to both (:mod:`.numerics`), starting points
(:mod:`.start`), the strategies that reach a loaded equilibrium (:mod:`.strategies`) and
the Newton polish (:mod:`.polish`).
"""
