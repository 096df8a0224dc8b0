"""Environmental loads on the floating body: wind, current, mean wave drift, constant force.

Every function here is pure and works on Python floats and on CasADi ``SX``/``MX`` symbols
alike: the speeds, headings, wave height and body yaw may be symbolic (problem parameters
or unknowns), so only ``casadi`` arithmetic is used on them. Python ``if`` appears only on the
structure of the case (which load model is declared, whether lateral areas are given, the
rows of a coefficient table), so a built problem contains only the terms the scene asks for.

Frames and signs (see :mod:`moorsolve.model`): x, y horizontal, z up; a flow or wave train
travels *toward* the heading ``toward`` [rad], counter-clockwise from global +x. The body
frame is the global frame turned by the body yaw ``yaw`` [rad] about z, so the heading of the
flow relative to the body is ``theta = toward - yaw``. Loads are computed in the body frame,
their yaw moment about the body-frame origin is taken from the model's centre of pressure,
and the force is then rotated to the global frame.
"""

from __future__ import annotations

import math

import casadi

from ..constants import (HU_TANG_AIR_DENSITY_TECH, HU_TANG_GRAVITY,
                         HU_TANG_WATER_DENSITY_TECH)
from ..errors import CaseError

__all__ = [
    "hu_tang_wind_kN",
    "hu_tang_current_kN",
    "hu_tang_drift_kN",
    "table_coefficients",
    "drag_load_body",
    "hu_tang_wind_body",
    "hu_tang_current_body",
    "hu_tang_drift_body",
    "drift_coefficient_body",
    "body_to_global",
]

_N_PER_KN = 1.0e3               # Hu & Tang give their results in kN
_CURRENT_EXPONENT = 1.83        # Hu & Tang (2004): v^1.83
_FULL_TURN_DEG = 360.0
_DEG_PER_RAD = 180.0 / math.pi


# ---- Hu & Tang (2004) empirical magnitudes ------------------------------------------------

def hu_tang_wind_kN(speed, superstructure_area, hull_area):
    """Hu & Tang wind resistance ``R1 = 0.006 rho_a V^2 (F' + 0.31 F)`` [kN].

    Parameters
    ----------
    speed : float or casadi.SX or casadi.MX
        Wind speed V [m/s].
    superstructure_area : float
        F', projected area of the superstructure on the midship section [m^2].
    hull_area : float
        F, projected area of the hull above water on the midship section [m^2].

    Returns
    -------
    float or casadi.SX or casadi.MX
        R1 [kN], even in ``speed``.

    Notes
    -----
    Hu Lingbin and Tang Jun, "Solution and application of the catenary equation", Ship &
    Boat 2004 no. 1, section 3, with the paper's air
    density ``rho_a = 0.124 kgf s^2/m^4`` (``constants.HU_TANG_AIR_DENSITY_TECH``) kept inside
    the empirical formula. Example 1 (V = 30 m/s, F' = 107 m^2, F = 61.6 m^2) gives
    84.4339 kN from the printed formula and inputs; the paper prints 83.93 kN (0.6 % lower;
    no reading of its inputs reproduces that figure).
    """
    return (0.006 * HU_TANG_AIR_DENSITY_TECH * speed * speed
            * (superstructure_area + 0.31 * hull_area))


def hu_tang_current_kN(speed, wetted_area, coefficient=0.18):
    """Hu & Tang current resistance ``R2 = 0.01 f Omega v^1.83`` [kN].

    Parameters
    ----------
    speed : float or casadi.SX or casadi.MX
        Current speed v [m/s]. Taken as a magnitude: ``|v|^1.83`` is used.
    wetted_area : float
        Omega, wetted surface of the hull [m^2].
    coefficient : float, optional
        f, the resistance coefficient [-]; 0.18 in the paper.

    Returns
    -------
    float or casadi.SX or casadi.MX
        R2 [kN].

    Notes
    -----
    Hu & Tang (2004). The power is evaluated
    as ``casadi.power(casadi.fabs(v), 1.83)``: exact for every v (bit for bit the printed
    ``v^1.83`` for v > 0), equal to 0 at v = 0 with a derivative ``1.83 |v|^0.83 sgn(v)``
    that is 0 (finite) there, and even in v like the ``V^2`` of the other drag forms.
    Example 1 (f = 0.18, Omega = 1500 m^2, v = 1.5 m/s) gives 5.6704 kN from the printed
    formula and inputs; the paper prints 5.70 kN (0.5 % higher).
    """
    return 0.01 * coefficient * wetted_area * casadi.power(casadi.fabs(speed),
                                                           _CURRENT_EXPONENT)


def hu_tang_drift_kN(hs, beam, k=0.7, heading_rad=0.0):
    """Hu & Tang mean wave drift ``R3 = 0.75 k rho g B (Hs/4)^2 cos(alpha) 1e-2`` [kN].

    Parameters
    ----------
    hs : float or casadi.SX or casadi.MX
        Significant wave height H_1/3 [m].
    beam : float
        B, waterline breadth facing the waves [m].
    k : float, optional
        The paper's coefficient [-]; 0.7.
    heading_rad : float or casadi.SX or casadi.MX, optional
        alpha, wave heading relative to the bow [rad]; 0 for the paper's head-on case.

    Returns
    -------
    float or casadi.SX or casadi.MX
        R3 [kN] (signed by ``cos(alpha)``).

    Notes
    -----
    Hu & Tang (2004) (and its conclusion, section 5, the "Dali"
    formula), with the paper's water density ``rho = 104.61 kgf s^2/m^4`` and
    ``g = 9.8 m/s^2`` (``constants.HU_TANG_WATER_DENSITY_TECH``, ``HU_TANG_GRAVITY``).
    Example 1 (Hs = 1.5 m, B = 15.8 m, alpha = 0) gives 11.9585 kN; printed 11.96 kN.
    """
    amplitude = 0.25 * hs
    return (0.75 * k * HU_TANG_WATER_DENSITY_TECH * HU_TANG_GRAVITY * beam
            * amplitude * amplitude * casadi.cos(heading_rad) * 1.0e-2)


# ---- coefficient tables --------------------------------------------------------------------

def _table_nodes(table, field):
    """Validate a ``(heading_deg, cx, cy, cmz)`` table; return the periodic interpolation nodes.

    The returned headings run from the first row's heading to that plus 360 deg, closing
    the period with a copy of the first row unless the table already spans exactly 360 deg.
    """
    rows = []
    for i, row in enumerate(table):
        try:
            values = tuple(float(v) for v in row)
        except (TypeError, ValueError):
            raise CaseError(f"{field}[{i}]", f"{row!r} must be 4 numbers "
                            "(heading_deg, cx, cy, cmz)") from None
        if len(values) != 4 or not all(math.isfinite(v) for v in values):
            raise CaseError(f"{field}[{i}]", f"{row!r} must be 4 finite numbers "
                            "(heading_deg, cx, cy, cmz)")
        rows.append(values)
    if not rows:
        raise CaseError(field, "an empty table; give at least one row "
                        "(heading_deg, cx, cy, cmz)")
    for i in range(1, len(rows)):
        if rows[i][0] <= rows[i - 1][0]:
            raise CaseError(f"{field}[{i}]", f"heading {rows[i][0]} deg must be greater "
                            f"than the previous row's {rows[i - 1][0]} deg")
    span = rows[-1][0] - rows[0][0]
    if span > _FULL_TURN_DEG:
        raise CaseError(field, f"headings span {span} deg; they must lie within 360 deg")
    if span == _FULL_TURN_DEG:
        if rows[-1][1:] != rows[0][1:]:
            raise CaseError(f"{field}[{len(rows) - 1}]",
                            f"{rows[-1]!r} is 360 deg from the first row and must repeat "
                            f"its coefficients {rows[0][1:]!r}")
        return rows
    return rows + [(rows[0][0] + _FULL_TURN_DEG,) + rows[0][1:]]


def table_coefficients(table, heading_rad, field="table"):
    """Coefficients of a heading table, interpolated linearly and periodically.

    Parameters
    ----------
    table : sequence of (heading_deg, cx, cy, cmz)
        Rows with strictly increasing relative headings [deg] spanning at most 360 deg.
        The period is closed from the last row back to the first (plus 360 deg); a last row
        exactly 360 deg after the first must repeat its coefficients.
    heading_rad : float or casadi.SX or casadi.MX
        Relative heading theta [rad], any value (wrapped into the table's period).
    field : str, optional
        Dotted name of the table in the case, for error messages.

    Returns
    -------
    tuple of 3 (float or casadi.SX or casadi.MX)
        ``(cx, cy, cmz)`` [-].

    Raises
    ------
    CaseError
        If the table is empty, a row is not 4 finite numbers, the headings do not increase
        or span more than 360 deg.

    Notes
    -----
    The heading is wrapped as ``t = h0 + fmod(fmod(theta_deg - h0, 360) + 360, 360)`` and
    each column is written as a sum of ramps, ``y(t) = y0 + s0 (t - h0)
    + sum_i (s_i - s_(i-1)) max(t - h_i, 0)`` with ``s_i`` the slope of segment i: exact
    linear interpolation on ``[h0, h0 + 360]`` using only ``casadi.fmod``/``casadi.fmax``,
    so it holds for symbolic headings (no ``casadi.interpolant``). The table form follows
    the ``DragLoad`` docstring in :mod:`moorsolve.model`.
    """
    nodes = _table_nodes(table, field)
    h0 = nodes[0][0]
    shifted = heading_rad * _DEG_PER_RAD - h0
    t = h0 + casadi.fmod(casadi.fmod(shifted, _FULL_TURN_DEG) + _FULL_TURN_DEG,
                         _FULL_TURN_DEG)
    headings = [row[0] for row in nodes]
    ramps = [None] + [casadi.fmax(t - h, 0.0) for h in headings[1:-1]]
    out = []
    for column in (1, 2, 3):
        values = [row[column] for row in nodes]
        slopes = [(values[i + 1] - values[i]) / (headings[i + 1] - headings[i])
                  for i in range(len(nodes) - 1)]
        value = values[0] + slopes[0] * (t - h0)
        for i in range(1, len(slopes)):
            kink = slopes[i] - slopes[i - 1]
            if kink != 0.0:
                value = value + kink * ramps[i]
        out.append(value)
    return tuple(out)


# ---- body-frame loads of each model --------------------------------------------------------

def _centre_moment(centre, fx_body, fy_body):
    """Yaw moment [N m] of a body-frame force applied at ``centre`` (body frame [m])."""
    cx, cy = float(centre[0]), float(centre[1])
    moment = 0.0
    if cx != 0.0:
        moment = moment + cx * fy_body
    if cy != 0.0:
        moment = moment - cy * fx_body
    return moment


def _signed_square_cos(theta):
    c = casadi.cos(theta)
    return c * casadi.fabs(c)


def _signed_square_sin(theta):
    s = casadi.sin(theta)
    return s * casadi.fabs(s)


def drag_load_body(params, density, speed, heading_rad, field="drag"):
    """Quadratic drag ``0.5 rho C A V^2`` of a wind or current, in the body frame.

    Parameters
    ----------
    params : mapping
        The ``DragLoad`` fields (plain values): areas, coefficients (constant or a heading
        table), reference length and centre.
    density : float
        Fluid density [kg/m^3]: air for wind, water for current.
    speed : float or casadi.SX or casadi.MX
        Flow speed V [m/s].
    heading_rad : float or casadi.SX or casadi.MX
        Flow heading relative to the body, theta = toward - yaw [rad].
    field : str, optional
        Dotted name of the model in the case, for error messages.

    Returns
    -------
    tuple of 3
        ``(Fx, Fy, Mz)``: force along body x and y [N], yaw moment about the body-frame
        origin [N m].

    Notes
    -----
    With ``q = 0.5 rho V^2``: constant coefficients give ``Fx = q cx A_x cos(theta)|cos(theta)|``,
    ``Fy = q cy A_y sin(theta)|sin(theta)|``; a table gives ``Fx = q cx(theta) A_x``,
    ``Fy = q cy(theta) A_y`` and adds ``q cmz(theta) A_y length`` to the moment. The centre
    of pressure (cx_c, cy_c) adds ``cx_c Fy - cy_c Fx``. Definitions: ``DragLoad`` in
    :mod:`moorsolve.model`.
    """
    q = 0.5 * density * speed * speed
    if params["table"] is None:
        fx = q * (params["cx"] * params["area_x"]) * _signed_square_cos(heading_rad)
        fy = q * (params["cy"] * params["area_y"]) * _signed_square_sin(heading_rad)
        mz = _centre_moment(params["centre"], fx, fy)
    else:
        cx, cy, cmz = table_coefficients(params["table"], heading_rad, field=f"{field}.table")
        fx = q * params["area_x"] * cx
        fy = q * params["area_y"] * cy
        mz = _centre_moment(params["centre"], fx, fy)
        if params["length"] != 0.0:
            mz = mz + q * params["area_y"] * params["length"] * cmz
    return fx, fy, mz


def hu_tang_wind_body(params, speed, heading_rad, field="wind"):
    """Hu & Tang wind load in the body frame [N, N, N m].

    Parameters
    ----------
    params : mapping
        The ``HuTangWind`` fields (plain values).
    speed : float or casadi.SX or casadi.MX
        Wind speed [m/s].
    heading_rad : float or casadi.SX or casadi.MX
        Wind heading relative to the body, theta = toward - yaw [rad].
    field : str, optional
        Dotted name of the model in the case, for error messages.

    Returns
    -------
    tuple of 3
        ``(Fx, Fy, Mz)`` in the body frame [N, N, N m].

    Raises
    ------
    CaseError
        If only one of the two lateral areas is given.

    Notes
    -----
    Frontal areas only (the paper's use): magnitude ``R1(F', F)`` along the wind,
    ``(R1 cos(theta), R1 sin(theta))``. With both lateral areas:
    ``Fx = R1(F', F) cos|cos|``, ``Fy = R1(F'_lat, F_lat) sin|sin|``. R1 from
    :func:`hu_tang_wind_kN` (Hu & Tang 2004, section 3), converted to N.
    """
    frontal = _N_PER_KN * hu_tang_wind_kN(speed, params["superstructure_area"], params["hull_area"])
    lateral_given = (params["superstructure_area_lateral"] is not None,
                     params["hull_area_lateral"] is not None)
    if lateral_given == (False, False):
        fx = frontal * casadi.cos(heading_rad)
        fy = frontal * casadi.sin(heading_rad)
    elif lateral_given == (True, True):
        lateral = _N_PER_KN * hu_tang_wind_kN(speed, params["superstructure_area_lateral"],
                                              params["hull_area_lateral"])
        fx = frontal * _signed_square_cos(heading_rad)
        fy = lateral * _signed_square_sin(heading_rad)
    else:
        missing = ("superstructure_area_lateral" if lateral_given[1]
                   else "hull_area_lateral")
        raise CaseError(f"{field}.{missing}", "None; give both lateral areas or neither")
    return fx, fy, _centre_moment(params["centre"], fx, fy)


def hu_tang_current_body(params, speed, heading_rad):
    """Hu & Tang current load along the flow, in the body frame [N, N, N m].

    Parameters
    ----------
    params : mapping
        The ``HuTangCurrent`` fields (plain values).
    speed : float or casadi.SX or casadi.MX
        Current speed [m/s].
    heading_rad : float or casadi.SX or casadi.MX
        Current heading relative to the body, theta = toward - yaw [rad].

    Returns
    -------
    tuple of 3
        ``(R2 cos(theta), R2 sin(theta), Mz)`` with R2 from :func:`hu_tang_current_kN`
        in N.

    Notes
    -----
    Hu & Tang (2004), section 3; ``HuTangCurrent`` in :mod:`moorsolve.model`.
    """
    r2 = _N_PER_KN * hu_tang_current_kN(speed, params["wetted_area"], params["coefficient"])
    fx = r2 * casadi.cos(heading_rad)
    fy = r2 * casadi.sin(heading_rad)
    return fx, fy, _centre_moment(params["centre"], fx, fy)


def hu_tang_drift_body(params, hs, heading_rad):
    """Hu & Tang mean wave drift in the body frame [N, N, N m].

    Parameters
    ----------
    params : mapping
        The ``HuTangDrift`` fields (plain values).
    hs : float or casadi.SX or casadi.MX
        Significant wave height [m].
    heading_rad : float or casadi.SX or casadi.MX
        Wave heading relative to the body, alpha = toward - yaw [rad].

    Returns
    -------
    tuple of 3
        ``Fx = R3(B) cos(alpha)``; ``Fy = R3(length) sin(alpha)`` when the model gives a
        ``length``, else 0; the moment of that force about the body origin.

    Notes
    -----
    R3 from :func:`hu_tang_drift_kN` (Hu & Tang 2004, section 3), converted to N. The drift
    pushes the body in the direction the waves travel.
    """
    fx = _N_PER_KN * hu_tang_drift_kN(hs, params["beam"], params["k"], heading_rad)
    if params["length"] is None:
        fy = 0.0
    else:
        fy = (_N_PER_KN * hu_tang_drift_kN(hs, params["length"], params["k"], 0.0)
              * casadi.sin(heading_rad))
    return fx, fy, _centre_moment(params["centre"], fx, fy)


def drift_coefficient_body(params, water_density, gravity, hs, heading_rad):
    """Mean wave drift from drift coefficients, in the body frame [N, N, N m].

    Parameters
    ----------
    params : mapping
        The ``DriftCoefficient`` fields (plain values).
    water_density : float
        [kg/m^3].
    gravity : float
        [m/s^2].
    hs : float or casadi.SX or casadi.MX
        Significant wave height [m].
    heading_rad : float or casadi.SX or casadi.MX
        Wave heading relative to the body, theta = toward - yaw [rad].

    Returns
    -------
    tuple of 3
        ``Fx = rho g cx length_x (Hs/4)^2 cos(theta)``,
        ``Fy = rho g cy length_y (Hs/4)^2 sin(theta)`` and their moment.

    Notes
    -----
    The component formulas of ``DriftCoefficient`` in :mod:`moorsolve.model` (no factor
    0.5; the docstring's title line mentions one, its formulas do not); the Hs/4 scaling
    follows Hu & Tang (2004).
    """
    amplitude = 0.25 * hs
    scale = water_density * gravity * amplitude * amplitude
    fx = scale * (params["cx"] * params["length_x"]) * casadi.cos(heading_rad)
    fy = scale * (params["cy"] * params["length_y"]) * casadi.sin(heading_rad)
    return fx, fy, _centre_moment(params["centre"], fx, fy)


def body_to_global(fx_body, fy_body, yaw):
    """Rotate a body-frame horizontal force to the global frame.

    Parameters
    ----------
    fx_body, fy_body : float or casadi.SX or casadi.MX
        Force along body x and y [N].
    yaw : float or casadi.SX or casadi.MX
        Body yaw [rad], counter-clockwise from global x to body x.

    Returns
    -------
    tuple of 2
        ``(Fx, Fy)`` in the global frame [N].
    """
    c = casadi.cos(yaw)
    s = casadi.sin(yaw)
    return c * fx_body - s * fy_body, s * fx_body + c * fy_body


# ---- the body's load effects -----------------------------------------------------------------
