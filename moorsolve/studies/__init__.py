"""Studies built on the solver: sweeps (threads, Dask), offset envelopes, stiffness,
natural periods and sensitivities, design optimisation, the accuracy ladder and the
single-line inverse problems. Built on :mod:`moorsolve.solve`, never the reverse."""
