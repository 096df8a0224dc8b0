"""The sea state and the bodies' motions in it, about the certified static equilibrium.

- :mod:`.spectra`: wave spectra (JONSWAP in the DNV-RP-C205 form, Pierson-Moskowitz, a table)
  and their moments;
- :mod:`.hydro`: a body's hydrodynamic coefficients interpolated in frequency and heading;
- :mod:`.motions`: the coupled frequency-domain response of every free DOF of every body
  (wave-frequency, slow drift by Newman's approximation, mean drift), its statistics and
  API RP 2SK's design offset;
- :mod:`.line_model`, :mod:`.line_dynamics`, :mod:`.line_spectral`: a line's lumped-mass
  model about its static profile, its tension transfer functions driven by the motion of
  its ends (drag linearised by iteration), and the tension statistics in a sea state.

Built on :mod:`moorsolve.solve` (the equilibrium) and :mod:`moorsolve.studies.stiffness`
(the total tangent stiffness); neither imports this package.
"""

from .spectra import (gamma_dnv, jonswap, pierson_moskowitz, spectral_moment, spectrum_of,
                      tabulated)

__all__ = ["gamma_dnv", "jonswap", "pierson_moskowitz", "tabulated", "spectral_moment",
           "spectrum_of", "motions"]


def __getattr__(name):
    if name == "motions":
        from .motions import motions
        return motions
    raise AttributeError(name)
