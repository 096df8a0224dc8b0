"""Life of the mooring: fatigue damage of the line ends over a scatter diagram.

- :mod:`.damage`: Miner's damage of a Gaussian tension (narrow band, Dirlik) and of a
  series counted by rainflow;
- :mod:`.response`: the line-end tension spectra in every sea state, the RAOs solved once
  per heading;
- :mod:`.fatigue`: :func:`fatigue`, damage, life and the design fatigue factor per line end.

The curves are data: :mod:`moorsolve.catalog.fatigue`. The entry point is
``moorsolve.fatigue`` (:func:`moorsolve.life.fatigue.fatigue`).
"""
