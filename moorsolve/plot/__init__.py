"""Pictures of equilibria and studies; the only package that imports matplotlib (inside
its functions, so importing moorsolve does not).

Every plot function takes what it draws (a Result, a check report, an envelope, ...) and
an optional Axes, draws on it and returns it (a figure maker returns the Figure); none
calls ``plt.show()``.

- :mod:`.scene`: what a picture of an equilibrium shows, read from a Result;
  :mod:`.geometry`: the bodies' hulls and the berth's structures in it.
- :mod:`.plan`, :mod:`.views`: plan, elevation, 3-D view, line profiles, the equilibrium
  figure (colours and styles shared through :mod:`.style`).
- :mod:`.directions`: the direction conventions of a case file, drawn.
- :mod:`.berth`: quay walls, piles, fenders and pile guides in every view.
- :mod:`.labels`: the plan's labels, placed so that none overlaps another.
- :mod:`.interactive`: a 3-D view for notebooks (plotly, the ``interactive`` extra).
- :mod:`.studies`: check utilisation, accuracy ladder, envelopes, polar fields, design
  optimisation, restoring curves.
"""

from .berth import plot_berth
from .directions import plot_directions
from .interactive import plot_3d_interactive
from .scene import Scene, scene_of
from .studies import (figure_png, plot_accuracy, plot_envelope, plot_optimisation,
                      plot_polar_field, plot_restoring, plot_utilisation, utilisation_figure)
from .views import (plot_3d, plot_elevation, plot_equilibrium, plot_plan, plot_profiles,
                    view_direction)

__all__ = ["Scene", "scene_of", "plot_plan", "plot_elevation", "plot_3d", "plot_profiles",
           "plot_equilibrium", "view_direction", "plot_utilisation", "utilisation_figure",
           "figure_png", "plot_accuracy", "plot_envelope", "plot_polar_field",
           "plot_optimisation", "plot_restoring", "plot_directions", "plot_berth",
           "plot_3d_interactive"]
