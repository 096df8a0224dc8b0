"""The units case files use most, converted without building pint's registry.

Building pint's unit registry costs about half a second, more than reading a case and
solving it; a case whose quantities are all in these units (``"81 mm"``, ``"281 kN"``,
``"0.13 t/m"``, ``"20 kn"``) never builds it. Each factor is what pint converts one of the
unit to in SI (degrees for an angle), and the conversion is ``number * factor``, which is
how pint converts a multiplicative unit: the same float to the last bit (checked against
pint over thousands of numbers by the tests). Any other unit text goes to pint.
"""

from __future__ import annotations

#: Unit text as a case file writes it -> (kind, factor to the kind's SI unit).
COMMON_UNITS = {
    "m": ("length", 1.0),
    "mm": ("length", 0.001),
    "cm": ("length", 0.01),
    "km": ("length", 1000.0),
    "ft": ("length", 0.30479999999999996),
    "in": ("length", 0.0254),
    "N": ("force", 1.0),
    "kN": ("force", 1000.0),
    "MN": ("force", 1000000.0),
    "kgf": ("force", 9.80665),
    "tf": ("force", 9806.65),
    "lbf": ("force", 4.4482216152605005),
    "kip": ("force", 4448.221615260501),
    "kg": ("mass", 1.0),
    "t": ("mass", 1000.0),
    "N*m": ("moment", 1.0),
    "kN*m": ("moment", 1000.0),
    "MN*m": ("moment", 1000000.0),
    "N m": ("moment", 1.0),
    "kN m": ("moment", 1000.0),
    "MN m": ("moment", 1000000.0),
    "N/m": ("force_per_length", 1.0),
    "kN/m": ("force_per_length", 1000.0),
    "kgf/m": ("force_per_length", 9.80665),
    "tf/m": ("force_per_length", 9806.65),
    "kg/m": ("mass_per_length", 1.0),
    "t/m": ("mass_per_length", 1000.0),
    "m/s": ("speed", 1.0),
    "kn": ("speed", 0.5144444444444445),
    "kt": ("speed", 0.5144444444444445),
    "knot": ("speed", 0.5144444444444445),
    "knots": ("speed", 0.5144444444444445),
    "km/h": ("speed", 0.2777777777777778),
    "deg": ("angle", 1.0),
    "degree": ("angle", 1.0),
    "degrees": ("angle", 1.0),
    "rad": ("angle", 57.29577951308232),
    "radian": ("angle", 57.29577951308232),
    "s": ("time", 1.0),
    "min": ("time", 60.0),
    "h": ("time", 3600.0),
    "m^2": ("area", 1.0),
    "m**2": ("area", 1.0),
    "m^3": ("volume", 1.0),
    "m**3": ("volume", 1.0),
    "kg/m^3": ("density", 1.0),
    "kg/m**3": ("density", 1.0),
    "t/m^3": ("density", 1000.0),
    "m/s^2": ("acceleration", 1.0),
    "m/s**2": ("acceleration", 1.0),
    "kg*m^2": ("moment_of_inertia", 1.0),
    "t*m^2": ("moment_of_inertia", 1000.0),
    "kg m^2": ("moment_of_inertia", 1.0),
    "t m^2": ("moment_of_inertia", 1000.0),
    "N*m^2": ("bending_stiffness", 1.0),
    "kN*m^2": ("bending_stiffness", 1000.0),
    "N m^2": ("bending_stiffness", 1.0),
    "kN m^2": ("bending_stiffness", 1000.0),
}
