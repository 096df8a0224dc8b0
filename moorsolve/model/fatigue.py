"""The fatigue check's input: a scatter diagram of sea states, a design life and a curve.

Only described and checked here; :mod:`moorsolve.life` computes the damage.
"""

from __future__ import annotations

from dataclasses import dataclass

from .sea import Spectrum

__all__ = ["FatigueSpec", "FATIGUE_METHODS", "DEFAULT_DFF"]

#: How damage follows from a tension spectrum.
FATIGUE_METHODS = ("narrow_band", "dirlik")
#: DNV-OS-E301's design fatigue factor for a line that can be inspected (the user's own
#: value replaces it; the standard's rise with the adjacent line's damage is not applied).
DEFAULT_DFF = 5.0


@dataclass(frozen=True)
class FatigueSpec:
    """``checks.fatigue`` of a case.

    Attributes
    ----------
    design_life : float
        [s].
    sea_states : tuple of (hs [m], tp [s], toward_deg, probability)
        The scatter diagram; probabilities sum to 1.
    spectrum : Spectrum
        The shape of every sea state's spectrum (JONSWAP by default).
    curve : Curve
        The default fatigue curve (:class:`moorsolve.catalog.fatigue.Curve`).
    curves : tuple of (line type name, Curve)
        Curves for particular line types.
    design_fatigue_factor : float
    method : str
        ``narrow_band`` or ``dirlik``.
    """

    design_life: float
    sea_states: tuple
    curve: object
    spectrum: Spectrum = Spectrum()
    curves: tuple = ()
    design_fatigue_factor: float = DEFAULT_DFF
    method: str = "narrow_band"

    def curve_for(self, line_type: str):
        """The curve of line type ``line_type``."""
        return dict(self.curves).get(line_type, self.curve)
