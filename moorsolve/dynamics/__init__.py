"""Dynamics about the static equilibrium: sea states, body motions and line dynamics in the
frequency domain, built on the certified equilibrium of :mod:`moorsolve.solve`."""
