"""The loads a body's declared models put on it, dispatched from the model to the physics.

:mod:`moorsolve.physics.loads` holds the formulas on plain arguments; this module knows the
model classes and picks the formula for each declared load model.
"""

from __future__ import annotations

import dataclasses

from ...errors import CaseError
from ...model import (BodyLoads, DragLoad, DriftCoefficient, Environment, HuTangCurrent,
                     HuTangDrift, HuTangWind)
from ...physics.loads import (body_to_global, drag_load_body, drift_coefficient_body,
                             hu_tang_current_body, hu_tang_drift_body, hu_tang_wind_body)

#: The body load effects, in the order they are reported.
EFFECT_ORDER = ("wind", "current", "wave_drift", "force")


def effect_names(loads: BodyLoads, environment: Environment) -> list:
    """The body load effects a case simulates, in the fixed order of :data:`EFFECT_ORDER`.

    Parameters
    ----------
    loads : BodyLoads
    environment : Environment

    Returns
    -------
    list of str
        Among ``"wind"``, ``"current"``, ``"wave_drift"``, ``"force"``: a load model counts
        when it is declared and its environment (wind, current, waves) is present; a
        constant force counts whenever it is given.
    """
    present = {
        "wind": loads.wind is not None and environment.wind is not None,
        "current": loads.current is not None and environment.current is not None,
        "wave_drift": loads.wave_drift is not None and environment.waves is not None,
        "force": loads.force is not None,
    }
    return [name for name in EFFECT_ORDER if present[name]]


def _to_global(body_load, yaw):
    fx, fy, mz = body_load
    gx, gy = body_to_global(fx, fy, yaw)
    return gx, gy, mz


def body_loads(loads: BodyLoads, environment: Environment, yaw, wind_speed, wind_toward,
               current_speed, current_toward, wave_hs, wave_toward) -> dict:
    """Forces and yaw moments of every simulated body load effect.

    Parameters
    ----------
    loads : BodyLoads
        The load models the body declares.
    environment : Environment
        Says which of wind, current and waves are present, and gives the densities
        (``air_density`` for wind drag, ``water_density`` for current drag and drift
        coefficients) and ``gravity``. Its speeds and headings are not read: they are the
        arguments below, so a built problem can change them.
    yaw : float or casadi.SX or casadi.MX
        Body yaw [rad].
    wind_speed, current_speed : float or casadi.SX or casadi.MX
        [m/s]; ignored when that flow is absent.
    wind_toward, current_toward, wave_toward : float or casadi.SX or casadi.MX
        Direction of travel [rad], counter-clockwise from global +x; ignored when absent.
    wave_hs : float or casadi.SX or casadi.MX
        Significant wave height [m]; ignored when there are no waves.

    Returns
    -------
    dict of str to tuple of 3
        Effect name (order of :func:`effect_names`) to ``(Fx, Fy, Mz)``: force in the global
        frame [N] and yaw moment about the body-frame origin [N m]. ``"force"`` is the
        declared constant ``[Fx, Fy, Mz]``, already global.

    Raises
    ------
    CaseError
        If a load slot holds a model it does not accept (wind: ``DragLoad`` or
        ``HuTangWind``; current: ``DragLoad`` or ``HuTangCurrent``; wave drift:
        ``HuTangDrift`` or ``DriftCoefficient``), the constant force is not 3 numbers, or
        a table or lateral-area pair is invalid.

    Notes
    -----
    The heading relative to the body is ``theta = toward - yaw``; each model gives its
    body-frame force and moment (see the ``*_body`` functions), then the force is rotated
    by ``yaw`` (:func:`body_to_global`); the moment is the same in both frames. Load model
    definitions: :mod:`moorsolve.model`; Hu & Tang forms: Hu & Tang (2004), section 3. The Hu & Tang forms keep the paper's own constants (densities
    in kgf s^2/m^4, g = 9.8) and do not use ``environment``'s densities.
    """
    names = effect_names(loads, environment)
    effects = {}
    if "wind" in names:
        theta = wind_toward - yaw
        model = loads.wind
        if isinstance(model, DragLoad):
            body = drag_load_body(dataclasses.asdict(model), environment.air_density, wind_speed,
                                  theta,
                                  field="body.loads.wind")
        elif isinstance(model, HuTangWind):
            body = hu_tang_wind_body(dataclasses.asdict(model), wind_speed, theta,
                                     field="body.loads.wind")
        else:
            raise CaseError("body.loads.wind", f"{type(model).__name__} is not a wind load "
                            "model; expected DragLoad or HuTangWind")
        effects["wind"] = _to_global(body, yaw)
    if "current" in names:
        theta = current_toward - yaw
        model = loads.current
        if isinstance(model, DragLoad):
            body = drag_load_body(dataclasses.asdict(model), environment.water_density,
                                  current_speed, theta,
                                  field="body.loads.current")
        elif isinstance(model, HuTangCurrent):
            body = hu_tang_current_body(dataclasses.asdict(model), current_speed, theta)
        else:
            raise CaseError("body.loads.current", f"{type(model).__name__} is not a current "
                            "load model; expected DragLoad or HuTangCurrent")
        effects["current"] = _to_global(body, yaw)
    if "wave_drift" in names:
        theta = wave_toward - yaw
        model = loads.wave_drift
        if isinstance(model, HuTangDrift):
            body = hu_tang_drift_body(dataclasses.asdict(model), wave_hs, theta)
        elif isinstance(model, DriftCoefficient):
            body = drift_coefficient_body(dataclasses.asdict(model), environment.water_density,
                                          environment.gravity, wave_hs, theta)
        else:
            raise CaseError("body.loads.wave_drift", f"{type(model).__name__} is not a wave "
                            "drift model; expected HuTangDrift or DriftCoefficient")
        effects["wave_drift"] = _to_global(body, yaw)
    if "force" in names:
        force = loads.force
        try:
            values = tuple(float(v) for v in force)
        except (TypeError, ValueError):
            raise CaseError("body.loads.force", f"{force!r} must be 3 numbers "
                            "[Fx N, Fy N, Mz N m]") from None
        if len(values) != 3:
            raise CaseError("body.loads.force", f"{force!r} must be 3 numbers "
                            "[Fx N, Fy N, Mz N m]")
        effects["force"] = values
    return effects


def body_loads_3d(loads: BodyLoads, environment: Environment, R, yaw, wind_speed, wind_toward,
                  current_speed, current_toward, wave_hs, wave_toward) -> dict:
    """Force and moment (about the body-frame origin, global axes) of every flow load model.

    The same models as :func:`body_loads`, applied in three dimensions: each model's
    body-frame horizontal force (turned to the global frame by the yaw) acts at its
    ``centre`` (body frame ``[x, y]`` at z = 0, or ``[x, y, z]``) on the body at its actual
    orientation ``R``, so heel and trim move the point of action and a centre above the
    waterline heels the body. A table's pure yaw-moment coefficient adds a moment about the
    vertical. The relative heading is ``toward - yaw``. The constant force is not included
    (the problem places it). Returns ``name -> (force 3-vector, moment 3-vector)``.
    """
    import casadi as ca

    from ...physics.kinematics import cross
    from ...physics.loads import _centre_moment

    planar = body_loads(dataclasses.replace(loads, force=None), environment, yaw,
                        wind_speed, wind_toward, current_speed, current_toward, wave_hs,
                        wave_toward)
    models = {"wind": loads.wind, "current": loads.current, "wave_drift": loads.wave_drift}
    out = {}
    for name, (gx, gy, mz) in planar.items():
        centre = tuple(models[name].centre)
        c3 = ca.vertcat(centre[0], centre[1], centre[2] if len(centre) > 2 else 0.0)
        # The body-frame force again, to separate the model's own (table) moment from the
        # lever arm of its centre.
        cy_, sy_ = ca.cos(yaw), ca.sin(yaw)
        fx_b, fy_b = cy_ * gx + sy_ * gy, -sy_ * gx + cy_ * gy
        pure = mz - _centre_moment(centre, fx_b, fy_b)
        force = ca.vertcat(gx, gy, 0)
        out[name] = (force, cross(R @ c3, force) + ca.vertcat(0, 0, pure))
    return out
