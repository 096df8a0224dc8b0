"""Hu & Tang's inverse questions on one leg, solved as small NLPs on the same leg block.

Hu & Tang (2004) search the catenary by hand-written loops for three design
questions; here each is one IPOPT problem whose constraints are the leg block of
:func:`moorsolve.physics.catenary.leg_function` (the span residuals ``rX = rZ = 0``), so an
elastic line, seabed contact and anchor uplift are handled exactly as in the equilibrium
solve. Unknowns: anchor distance ``X``, horizontal tension ``H`` (the leg's ``u``), fairlead
vertical tension ``V`` and unstretched length ``L``; the fairlead is ``height`` above the
anchor, which lies on the seabed.

* :func:`minimum_anchor_distance`: the least ``X`` at which a given fairlead (or horizontal)
  tension lifts no anchor: minimise ``X`` subject to the leg, the load and ``V_A <= 0``
  (their Tables 1, 2 and 4; the optimum has the touchdown exactly at the anchor).
* :func:`required_chain_length`: the least chain for a given load that keeps a required
  length on the seabed: minimise ``L`` subject to the leg, the load and
  ``L - V/w >= grounded_length`` (their example 1: 184.78 m + 45 m kept on the seabed).
* :func:`uplift_at_distance`: the anchor uplift force and angle when the anchor lies at a
  given distance and the line carries a given load (their Table 3).

Every answer is checked after the solve (span residuals, load and inequality) and raises
:class:`~moorsolve.errors.ConvergenceError` if it does not hold.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from functools import cache

import casadi as ca
import numpy as np

from ..errors import ConvergenceError
from ..physics.catenary import (LegKind, leg_function)
from ..solve.kernels.bundled_blas import limit_bundled_blas

__all__ = ["InverseResult", "minimum_anchor_distance", "required_chain_length",
           "uplift_at_distance"]

#: Relative accuracy demanded of every answer (spans against the height, load against
#: itself); the published tables print 6-7 digits.
_ACCURACY = 1e-9


@dataclass(frozen=True)
class InverseResult:
    """One leg's state answering an inverse question. Forces [N], lengths [m], angles [deg].

    ``length_m`` is the unstretched line from anchor to fairlead; ``order_length_m`` adds
    the inboard length asked for (chain locker to hawse pipe in Hu & Tang).
    """

    question: str
    anchor_distance_m: float
    height_m: float
    horizontal_tension_N: float
    fairlead_vertical_N: float
    fairlead_tension_N: float
    fairlead_angle_deg: float
    length_m: float
    suspended_length_m: float
    grounded_length_m: float
    anchor_vertical_N: float
    uplift_angle_deg: float
    order_length_m: float
    iterations: int

    def to_dict(self) -> dict:
        return asdict(self)


def _check_inputs(height, weight, ea, fairlead_tension, horizontal_tension):
    if not height > 0:
        raise ValueError(f"height {height} m must be > 0")
    if not weight > 0:
        raise ValueError(f"weight {weight} N/m must be > 0 (a sinking line)")
    if ea is not None and not ea > 0:
        raise ValueError(f"ea {ea} N must be > 0 (or None for an inextensible line)")
    if (fairlead_tension is None) == (horizontal_tension is None):
        raise ValueError("give exactly one of fairlead_tension and horizontal_tension")
    load = fairlead_tension if fairlead_tension is not None else horizontal_tension
    if not load > 0:
        raise ValueError(f"tension {load} N must be > 0")
    if fairlead_tension is not None and not fairlead_tension > weight * height:
        raise ValueError(f"fairlead tension {fairlead_tension} N must exceed the weight of a "
                         f"vertical line to the seabed, w*height = {weight * height:.6g} N")


@cache
def _nlp(question: str, elastic: bool, given: str):
    """The NLP of one question, built once: ``x = [X, H, V, L]`` scaled, parameters
    ``p = [height, w, ea_inv, load, fixed, l_scale, f_scale]`` (``fixed``: anchor distance
    for ``uplift``, grounded length for ``chain``)."""
    xs = ca.SX.sym("x", 4)
    p = ca.SX.sym("p", 7)
    Z, w, ea_inv, load, fixed, ls, fs = ca.vertsplit(p)
    X, H, V, L = xs[0] * ls, xs[1] * fs, xs[2] * fs, xs[3] * ls
    leg = leg_function(LegKind(elastic=elastic, contact=True))
    out = leg.call({"X": X, "Z": Z, "u": H, "V": V, "L": L, "w": w, "ea_inv": ea_inv,
                    "mu": 0})
    T = ca.sqrt(H**2 + V**2)
    load_res = (T - load) if given == "fairlead" else (H - load)
    g = [out["rX"] / ls, out["rZ"] / ls, load_res / fs]
    if question == "distance":
        f = xs[0]
        g.append((V - w * L) / fs)                     # V_A <= 0: no uplift
    elif question == "chain":
        f = xs[3]
        g.append((L - V / w - fixed) / ls)             # grounded length >= required
    else:
        f = 0
        g.append((X - fixed) / ls)                     # the anchor distance is given
    nlp = {"x": xs, "p": p, "f": f, "g": ca.vertcat(*g)}
    opts = {"print_time": False, "error_on_fail": False,
            "ipopt": {"print_level": 0, "sb": "yes", "tol": 1e-14, "constr_viol_tol": 1e-13,
                      "acceptable_tol": 1e-12, "max_iter": 500, "mu_strategy": "adaptive"}}
    solver = ca.nlpsol(f"inverse_{question}_{given}_{int(elastic)}", "ipopt", nlp, opts)
    limit_bundled_blas()
    check = ca.Function("check", [xs, p], [ca.vertcat(*g), out["grounded"], out["VA"]])
    return solver, check


def _touchdown_start(height, w, H):
    """Inextensible touchdown-at-anchor state for horizontal tension H: (X, V, L)."""
    V = math.sqrt((H + w * height) ** 2 - H**2)
    return (H / w) * math.asinh(V / H), V, V / w


def _solve(question, height, weight, ea, fairlead_tension, horizontal_tension, fixed,
           order_extra=0.0) -> InverseResult:
    _check_inputs(height, weight, ea, fairlead_tension, horizontal_tension)
    given = "fairlead" if fairlead_tension is not None else "horizontal"
    load = fairlead_tension if given == "fairlead" else horizontal_tension
    H0 = load - weight * height if given == "fairlead" else load
    X0, V0, L0 = _touchdown_start(height, weight, H0)
    if question == "chain":
        X0, L0 = X0 + fixed, L0 + fixed
    elif question == "uplift":
        # The anchor inside the touchdown span: start from a suspended line of the
        # same height through the given distance.
        X0, L0 = fixed, max(math.hypot(fixed, height) * 1.01, L0 * fixed / X0)
    ls = max(height, X0)
    fs = max(load, weight * height)
    solver, check = _nlp(question, ea is not None, given)
    p = [height, weight, 1.0 / ea if ea else 0.0, load, fixed, ls, fs]
    x0 = [X0 / ls, H0 / fs, V0 / fs, L0 / ls]
    # Each optimum has its inequality active (the least anchor distance has the touchdown
    # exactly at the anchor, the least chain exactly the grounded length asked for), so it
    # is solved as the square system with the inequality as an equality, and without
    # bounds on the distance and the tension (the load equation fixes it): with them a tiny
    # horizontal tension (a nearly vertical line) left IPOPT stuck at a bound ("no
    # solution" where the answer exists).
    lbg = [0, 0, 0, 0]
    ubg = [0, 0, 0, 0]
    lbx = [-np.inf, -np.inf, -np.inf, 1e-9]
    ubx = [np.inf] * 4
    sol = solver(x0=x0, p=p, lbx=lbx, ubx=ubx, lbg=lbg, ubg=ubg)
    stats = solver.stats()
    x = np.asarray(sol["x"]).ravel()
    g, grounded, VA = (np.asarray(v).ravel() for v in check(x, p))
    violation = max(abs(g[0]), abs(g[1]), abs(g[2]),
                    max(g[3] - ubg[3], lbg[3] - g[3], 0.0))
    # The system is square: a point that satisfies it is the answer, whatever IPOPT's
    # optimality measure says about a near-degenerate (nearly vertical) line.
    if not violation <= _ACCURACY:
        raise ConvergenceError(
            f"the {question} question has no solution for these inputs "
            f"(IPOPT: {stats.get('return_status')})",
            residual_N=float(violation * fs), status=str(stats.get("return_status")),
            iterations=int(stats.get("iter_count", 0)))
    X, H, V, L = x[0] * ls, x[1] * fs, x[2] * fs, x[3] * ls
    VA = max(V - weight * L, 0.0)
    grounded = float(grounded[0])
    return InverseResult(
        question=question, anchor_distance_m=X, height_m=height, horizontal_tension_N=H,
        fairlead_vertical_N=V, fairlead_tension_N=math.hypot(H, V),
        fairlead_angle_deg=math.degrees(math.atan2(V, H)), length_m=L,
        suspended_length_m=L - grounded, grounded_length_m=grounded,
        anchor_vertical_N=VA, uplift_angle_deg=math.degrees(math.atan2(VA, H)),
        order_length_m=L + order_extra, iterations=int(stats.get("iter_count", 0)))


def minimum_anchor_distance(height: float, weight: float, *,
                            fairlead_tension: float | None = None,
                            horizontal_tension: float | None = None,
                            ea: float | None = None) -> InverseResult:
    """Least anchor distance at which the load lifts no anchor (Hu & Tang Tables 1, 2, 4).

    Parameters
    ----------
    height : float
        Fairlead above the anchor (the water depth for a fairlead at the surface) [m].
    weight : float
        Submerged weight per length [N/m].
    fairlead_tension, horizontal_tension : float
        The load [N]; give exactly one.
    ea : float, optional
        Axial stiffness [N]; None for an inextensible line.

    Notes
    -----
    Minimise ``X`` subject to the leg block's span residuals, the load and ``V - w L <= 0``.
    The optimum has the touchdown exactly at the anchor (Hu & Tang's alpha = 0 condition);
    ``length_m`` is then the suspended length, the least chain that reaches.
    """
    return _solve("distance", height, weight, ea, fairlead_tension, horizontal_tension, 0.0)


def required_chain_length(height: float, weight: float, grounded_length: float, *,
                          fairlead_tension: float | None = None,
                          horizontal_tension: float | None = None,
                          ea: float | None = None,
                          inboard_length: float = 0.0) -> InverseResult:
    """Least chain for a load that keeps ``grounded_length`` [m] on the seabed.

    ``inboard_length`` [m] (chain locker to hawse pipe) is added to ``order_length_m``. Hu &
    Tang's example 1: 184.78 m suspended + 45 m on the seabed + 15 m inboard = 244.78 m.

    Notes
    -----
    Minimise ``L`` subject to the leg block, the load and ``L - V/w >= grounded_length``;
    ``anchor_distance_m`` is where the anchor must then lie.
    """
    if not grounded_length >= 0:
        raise ValueError(f"grounded_length {grounded_length} m must be >= 0")
    if not inboard_length >= 0:
        raise ValueError(f"inboard_length {inboard_length} m must be >= 0")
    return _solve("chain", height, weight, ea, fairlead_tension, horizontal_tension,
                  grounded_length, inboard_length)


def uplift_at_distance(height: float, weight: float, anchor_distance: float, *,
                       fairlead_tension: float | None = None,
                       horizontal_tension: float | None = None,
                       ea: float | None = None) -> InverseResult:
    """Anchor uplift force and angle for a load with the anchor at a given distance
    (Hu & Tang Table 3: uplift allowed, e.g. on a sinker block).

    The line length is the unknown that makes the leg reach: ``length_m`` is the chain
    between anchor and fairlead. An anchor farther out than the minimum distance has no
    uplift (``anchor_vertical_N = 0`` and a grounded length).
    """
    if not anchor_distance > 0:
        raise ValueError(f"anchor_distance {anchor_distance} m must be > 0")
    return _solve("uplift", height, weight, ea, fairlead_tension, horizontal_tension,
                  anchor_distance)
