"""One mooring line as lumped masses about its certified static profile.

The line is cut into straight elements between nodes taken on the profile a solve drew
(:attr:`moorsolve.solve.result.classes.LegResult.profile`, from end A, the anchor, to end B, the
fairlead; the touchdown and every segment joint are nodes). Each element carries its static
tension ``T``, and the linearised stiffness of a taut element of chord length ``l`` and
unit direction ``t`` is the axial spring plus the geometric (string) stiffness of its tension
(Cook, Malkus, Plesha & Witt 2002, *Concepts and Applications of Finite Element Analysis*,
4th ed., section 18.2; Hall & Goupee 2015, *Ocean Engineering* 104, eq. 2-5 for the lumped
mass line)::

    K_e = (EA_t / l_0) t t^T + (T / l) (I - t t^T)

``EA_t`` is the tangent axial stiffness at the static tension (``ea`` for Hooke, the
stretch law's ``dT/d(strain)`` otherwise, or the rope's dynamic stiffness where the line
type gives one; an inextensible line gets an axial stiffness a
million times its largest tension, a strain of 1e-6 there). Half of each element's mass and
hydrodynamic coefficients go to each of its nodes. Added mass acts normal to the line only
(``Ca rho A`` per unit length, ``A`` the displaced area); drag has a normal part
``0.5 rho Cd_n d |v_n| v_n`` and, where the line type gives one, a tangential part on the
same diameter; both are linearised on the response in :mod:`.line_dynamics`.

Seabed contact is that of the static solution: a node lying on the seabed (within a
millimetre-scale tolerance of it) is held vertically, rigidly (its vertical degree of
freedom removed) or by a spring of ``seabed_stiffness`` [Pa] times diameter times node
length (MoorDyn's contact law, Hall & Goupee 2015); it slides freely along the seabed
(no dynamic friction). Held bilaterally, a node at the touchdown may pull down in the
linear model: that is how the linearisation carries the line lifting off (or laying down)
near the touchdown to first order.

A clump weight or buoy at a joint adds its mass (its weight over g when no mass is given)
and the added mass of a sphere of its volume to the joint's node.

Mass per unit length: the weight in air over g when the line type gives it (the displaced
area is then the weight difference over rho g). Without it a line is taken as steel
(7850 kg/m^3: chain, wire) or, for a fibre rope, as filling its outer diameter; pass
``mass_per_length`` and ``displaced_area`` to say otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import CaseError

__all__ = ["LineModel", "line_model", "DEFAULT_DRAG", "STEEL_DENSITY"]

#: Density of steel [kg/m^3] for a chain or wire whose weight in air is not given.
STEEL_DENSITY = 7850.0
#: Normal drag coefficients on the nominal diameter when the line type gives none: studless
#: chain 2.4 (the figure DNV-OS-E301 tabulates for studless chain, and OrcaFlex's documented
#: chain default), fibre rope 1.2 (a rough circular cylinder at post-critical Reynolds
#: numbers, DNV-RP-C205 (2010) section 6.7). A line type that is neither chain nor fibre
#: (wire rope, a cable) is taken as chain unless it gives its own ``drag``.
DEFAULT_DRAG = {"chain": 2.4, "rope": 1.2}
#: Normal added-mass coefficient on the displaced area (a circular cylinder, DNV-RP-C205
#: (2010) Table D-2; 1.0 for chain as well, OrcaFlex's documented chain default).
DEFAULT_ADDED_MASS = 1.0
#: Elements of a line unless the caller asks for another number.
DEFAULT_ELEMENTS = 60
#: How much longer an element lying on the seabed is than a suspended one.
_GROUNDED_STRETCH = 4.0
#: Relative tolerance (of the water depth) within which a node lies on the seabed.
_SEABED_TOL = 1e-7
#: Axial stiffness of an inextensible line, as a multiple of its largest tension.
_RIGID_AXIAL = 1e6


@dataclass(frozen=True)
class LineModel:
    """A line as ``n`` elements between ``n + 1`` nodes, from end A (0) to end B (n).

    Attributes
    ----------
    name : str
    nodes : ndarray (n+1, 3)
        Static node positions [m], global.
    s : ndarray (n+1,)
        Unstretched arc length from end A [m].
    tension : ndarray (n,)
        Static effective tension of each element [N].
    axial : ndarray (n,)
        Axial spring of each element, ``EA_t / l_0`` [N/m].
    chord : ndarray (n,)
        Static chord length of each element [m].
    direction : ndarray (n, 3)
        Unit vector of each element, from end A toward end B.
    weight : ndarray (n,)
        Submerged weight of each element per unstretched length [N/m].
    mass : ndarray (n+1,)
        Structural mass lumped at each node [kg].
    added_mass : ndarray (n+1,)
        Normal added mass at each node [kg].
    drag_normal, drag_tangential : ndarray (n+1,)
        Quadratic drag coefficients per node, ``0.5 rho Cd d l`` [kg/m]: the drag force
        is this times ``|v| v`` [N].
    tangent : ndarray (n+1, 3)
        Unit tangent at each node (the mean of its elements' directions).
    grounded : ndarray (n+1,) of bool
        Nodes lying on the seabed in the static solution.
    seabed_spring : ndarray (n+1,) or None
        Vertical spring of each grounded node [N/m]; None: held rigidly.
    """

    name: str
    nodes: np.ndarray
    s: np.ndarray
    tension: np.ndarray
    axial: np.ndarray
    chord: np.ndarray
    direction: np.ndarray
    weight: np.ndarray
    mass: np.ndarray
    added_mass: np.ndarray
    drag_normal: np.ndarray
    drag_tangential: np.ndarray
    tangent: np.ndarray
    grounded: np.ndarray
    seabed_spring: Optional[np.ndarray] = None

    @property
    def n_elements(self) -> int:
        return len(self.chord)

    def stiffness(self) -> np.ndarray:
        """The assembled static stiffness ``(3(n+1), 3(n+1))`` [N/m] of all nodes (ends
        included), seabed springs included."""
        n = self.n_elements
        t = self.direction
        tt = t[:, :, None] * t[:, None, :]
        ke = (self.axial[:, None, None] * tt
              + (self.tension / self.chord)[:, None, None] * (np.eye(3) - tt))
        K = np.zeros((3 * (n + 1), 3 * (n + 1)))
        idx = np.arange(3)
        for e in range(n):
            a, b = 3 * e + idx, 3 * (e + 1) + idx
            K[np.ix_(a, a)] += ke[e]
            K[np.ix_(b, b)] += ke[e]
            K[np.ix_(a, b)] -= ke[e]
            K[np.ix_(b, a)] -= ke[e]
        if self.seabed_spring is not None:
            z = 3 * np.arange(n + 1) + 2
            K[z, z] += np.where(self.grounded, self.seabed_spring, 0.0)
        return K


def _segment_properties(lt, water_density: float, gravity: float, *, mass_per_length,
                        displaced_area, line_name: str, where: str) -> tuple:
    """``(m [kg/m], A [m^2], d [m], Cd_n, Cd_t)`` of one line type."""
    if lt.diameter is None:
        raise CaseError(f"line_types.{lt.name}.diameter",
                        f"line {line_name}: line dynamics need the line's diameter "
                        "(added mass and drag act on it)")
    d = float(lt.diameter)
    w = float(lt.weight_in_water)
    if mass_per_length is not None:
        m = float(mass_per_length)
        A = float(displaced_area) if displaced_area is not None else \
            (m * gravity - w) / (water_density * gravity)
    elif lt.weight_in_air is not None:
        m = lt.weight_in_air / gravity
        A = (lt.weight_in_air - w) / (water_density * gravity)
    elif lt.fibre:
        A = np.pi * d * d / 4
        m = w / gravity + water_density * A
    else:
        m = w / (gravity * (1.0 - water_density / STEEL_DENSITY))
        A = m / STEEL_DENSITY
    if displaced_area is not None:
        A = float(displaced_area)
    if not (m > 0 and A >= 0):
        raise CaseError(where, f"line {line_name}: mass per length {m:.4g} kg/m and "
                        f"displaced area {A:.4g} m^2 must be positive")
    if lt.drag is not None:
        cdn, cdt = lt.drag.normal, lt.drag.tangential
    else:
        cdn, cdt = DEFAULT_DRAG["rope" if lt.fibre else "chain"], 0.0
    return m, A, d, float(cdn), float(cdt)


def _resample(profile, line, env, n_elements: int) -> tuple:
    """Arc length, positions and tension ``(s, xyz, T)`` at about ``n_elements + 1`` nodes
    on the drawn profile: a cubic spline in arc length through each smooth piece of it
    (between touchdowns, lift-offs and segment joints), straight where it lies on the
    seabed."""
    from scipy.interpolate import CubicSpline

    if int(n_elements) < 2:
        raise CaseError("n_elements", f"{n_elements}: a line needs at least 2 elements")
    s = np.asarray(profile["s_m"], float)
    xyz = np.column_stack([profile["x_m"], profile["y_m"], profile["z_m"]]).astype(float)
    T = np.asarray(profile["tension_N"], float)
    tol = 1e-6 * max(line.length, 1.0)
    close = np.diff(s) <= tol                                # repeated breakpoints merge
    keep = np.concatenate([[True], ~close])
    if close[-1]:                                            # the end itself stays
        keep[-1], keep[-2] = True, False
    s, xyz, T = s[keep], xyz[keep], T[keep]
    on_bed = xyz[:, 2] <= env.seabed_z(xyz[:, 0], xyz[:, 1]) + _SEABED_TOL * env.depth
    interval_on_bed = on_bed[:-1] & on_bed[1:]
    joints = np.cumsum([seg.length for seg in line.segments])[:-1]
    cut = {0, len(s) - 1}
    cut |= {i + 1 for i in np.flatnonzero(interval_on_bed[1:] != interval_on_bed[:-1])}
    cut |= {int(np.argmin(np.abs(s - j))) for j in joints}
    cut = sorted(cut)
    pieces = [(a, b, bool(interval_on_bed[a])) for a, b in zip(cut[:-1], cut[1:])]
    weight = [(s[b] - s[a]) / (_GROUNDED_STRETCH if bed else 1.0) for a, b, bed in pieces]
    per = float(n_elements) / sum(weight)
    out_s, out_xyz, out_T = [s[:1]], [xyz[:1]], [T[:1]]
    for (a, b, bed), wt in zip(pieces, weight):
        k = max(1 if bed else 2, int(round(per * wt)))
        sk = np.linspace(s[a], s[b], k + 1)[1:]
        part = slice(a, b + 1)
        if bed or b - a < 3:
            pos = np.column_stack([np.interp(sk, s[part], xyz[part, j]) for j in range(3)])
        else:
            pos = CubicSpline(s[part], xyz[part], axis=0)(sk)
            pos[-1] = xyz[b]
        out_s.append(sk)
        out_xyz.append(pos)
        out_T.append(np.interp(sk, s[part], T[part]) if bed or b - a < 3
                     else CubicSpline(s[part], T[part])(sk))
    return np.concatenate(out_s), np.concatenate(out_xyz), np.concatenate(out_T)


def _tangent_ea(lt, T: float, dynamic: bool = False) -> Optional[float]:
    """``dT/d(strain)`` [N] at tension ``T`` (None when inextensible); with ``dynamic``,
    the line type's dynamic stiffness ``(alpha + beta L_m) MBL`` at mean load ``T`` where
    it gives one (the upper stiffness bound of a fibre rope)."""
    upper = lt.stiffness_bounds.upper if lt.stiffness_bounds is not None else None
    if dynamic and hasattr(upper, "alpha") and lt.mbl:
        return float(upper.ea(lt.mbl, T))
    if lt.stretch is not None:
        dT = max(1e-4 * abs(T), 1.0)
        lo = max(T - dT, 0.0)
        return (T + dT - lo) / (lt.stretch.strain_at(T + dT) - lt.stretch.strain_at(lo))
    return None if lt.ea is None else float(lt.ea)


def line_model(case, result, name: str, *, added_mass: float = DEFAULT_ADDED_MASS,
               drag_normal: Optional[float] = None, drag_tangential: Optional[float] = None,
               mass_per_length: Optional[float] = None,
               displaced_area: Optional[float] = None,
               seabed_stiffness: Optional[float] = None,
               n_elements: int = DEFAULT_ELEMENTS,
               dynamic_stiffness: bool = True) -> LineModel:
    """The lumped-mass model of line ``name`` about its solved static profile.

    Parameters
    ----------
    case : moorsolve.model.scene.Case
        The scene the result was solved from (line types, environment).
    result : moorsolve.Result
        A solved (certified) equilibrium.
    name : str
        The line's name.
    added_mass : float
        Normal added-mass coefficient on the displaced area (module notes).
    drag_normal, drag_tangential : float, optional
        Drag coefficients on the diameter, overriding the line type's (or the defaults).
    mass_per_length, displaced_area : float, optional
        Mass [kg/m] and displaced area [m^2] per unstretched length, overriding the rule
        of the module notes (every segment of the line).
    seabed_stiffness : float, optional
        Vertical seabed stiffness [Pa] (MoorDyn's ``kbot``); None holds grounded nodes
        rigidly.
    dynamic_stiffness : bool
        Where a line type gives a dynamic stiffness (``stiffness_bounds.upper`` of the
        form ``{model: dynamic, alpha, beta}``, a fibre rope's data sheet), its elements
        take ``(alpha + beta L_m) MBL`` at their static tension ``L_m`` (wave-frequency
        motion); False takes the quasi-static tangent stiffness of the stretch law
        everywhere (low-frequency motion, and the long-period limit of the statics).
    n_elements : int
        About how many elements: spread evenly over the suspended arc length, with
        elements four times longer on the seabed (straight there); every touchdown and
        segment joint is a node. The long-period tension stiffness converges as the square
        of the element length (about 1e-3 relative at 60 on a catenary with touchdown).

    Returns
    -------
    LineModel
    """
    lines = {ln.name: ln for ln in case.lines}
    legs = {lg.name: lg for lg in result.legs}
    if name not in lines or name not in legs:
        raise CaseError("line", f"{name!r} is not a line of this result "
                        f"(lines: {', '.join(sorted(legs))})")
    line, leg = lines[name], legs[name]
    env = case.environment
    rho, g = env.water_density, env.gravity
    s, xyz, T_node = _resample(leg.profile, line, env, n_elements)
    n = len(s) - 1
    l0 = np.diff(s)
    dxyz = np.diff(xyz, axis=0)
    chord = np.linalg.norm(dxyz, axis=1)
    if np.any(chord <= 0):
        raise CaseError(f"lines.{name}", "the static profile folds on itself (a slack "
                        "line): its dynamics cannot be linearised about it")
    direction = dxyz / chord[:, None]
    T_el = 0.5 * (T_node[:-1] + T_node[1:])
    # Which segment each element belongs to (by its mid arc length).
    bounds = np.cumsum([seg.length for seg in line.segments])
    seg_of = np.minimum(np.searchsorted(bounds, 0.5 * (s[:-1] + s[1:])),
                        len(line.segments) - 1)
    props = [_segment_properties(seg.line_type, rho, g, mass_per_length=mass_per_length,
                                 displaced_area=displaced_area, line_name=name,
                                 where=f"lines.{name}.segments[{i}]")
             for i, seg in enumerate(line.segments)]
    m_l, A_l, d_l, cdn_l, cdt_l = (np.array([p[k] for p in props])[seg_of] for k in range(5))
    w_l = np.array([seg.line_type.weight_in_water for seg in line.segments], float)[seg_of]
    if drag_normal is not None:
        cdn_l = np.full(n, float(drag_normal))
    if drag_tangential is not None:
        cdt_l = np.full(n, float(drag_tangential))
    ea = np.empty(n)
    T_big = max(float(np.max(np.abs(T_el))), 1.0)
    for e in range(n):
        ea_e = _tangent_ea(line.segments[seg_of[e]].line_type, max(T_el[e], 0.0),
                           dynamic_stiffness)
        ea[e] = _RIGID_AXIAL * T_big if ea_e is None else ea_e
    axial = ea / l0

    def to_nodes(per_element):
        out = np.zeros(n + 1)
        out[:-1] += 0.5 * per_element
        out[1:] += 0.5 * per_element
        return out

    mass = to_nodes(m_l * l0)
    # A clump weight or buoy at a joint: its mass (its weight over g when no mass is
    # given) and the added mass of a sphere of its volume, 0.5 rho V (DNV-RP-C205 (2010)
    # Table D-2), all directions.
    joints = np.cumsum([seg.length for seg in line.segments])[:-1]
    for s_joint, clump in zip(joints, line.joint_clumps):
        if clump is None:
            continue
        node = int(np.argmin(np.abs(s - s_joint)))
        body = clump.mass if clump.mass is not None else max(clump.weight / g, 0.0)
        mass[node] += body + 0.5 * rho * (clump.volume or 0.0)
    added = to_nodes(added_mass * rho * A_l * chord)
    qn = to_nodes(0.5 * rho * cdn_l * d_l * chord)
    qt = to_nodes(0.5 * rho * cdt_l * d_l * chord)
    tangent = np.zeros((n + 1, 3))
    tangent[:-1] += direction
    tangent[1:] += direction
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    seabed = env.seabed_z(xyz[:, 0], xyz[:, 1])
    grounded = xyz[:, 2] <= seabed + _SEABED_TOL * env.depth
    spring = None
    if seabed_stiffness is not None:
        spring = np.where(grounded, float(seabed_stiffness) * to_nodes(d_l * chord), 0.0)
    return LineModel(name=name, nodes=xyz, s=s, tension=T_el, axial=axial, chord=chord,
                     direction=direction, weight=w_l, mass=mass, added_mass=added, drag_normal=qn,
                     drag_tangential=qt, tangent=tangent, grounded=grounded,
                     seabed_spring=spring)
