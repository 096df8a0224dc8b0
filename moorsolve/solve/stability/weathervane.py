"""The stable heading of weathervaning bodies: a walk round the yaw circle.

A body free in yaw whose mooring gives little or no yaw moment (a ship on a turret, a
tanker on a hawser to a CALM buoy) takes the heading at which the yaw moment of its loads
about the mooring vanishes. With wind and current crossed that moment ``M(psi)`` has
several zeros round the circle; those where it falls through zero (``dM/dpsi < 0``) are
stable, the others unstable. Raising the load from rest (the quasi-static branch,
:mod:`.equilibrium`) can end at a fold of the branch (no equilibrium near it: "no
equilibrium") or on an unstable zero.

This module finds the stable heading the body swings to from its case-file heading under
the full load: the yaw of every weathervaning body is *held* at a heading, everything else
(surge, sway, the other bodies, the lines, free points) solved at that heading by Newton
steps on the remaining rows, and the yaw moment read there. From the case heading the
heading is stepped the way the moment turns the body (counter-clockwise where the moment
is exactly zero), each held solve warm-started from the last, until the moment changes
sign: a zero where it falls, bracketed, refined by regula falsi, then released (the full
system polished and certified) and its stability checked. An unstable release (a coupled
surge-sway-yaw mode) continues the walk. This is the overdamped yaw motion of the body
with surge and sway following quasi-statically, so of several stable headings it picks
the one the body reaches from its case heading, deterministically, and it cannot stop at
an unstable one; a held solve at a fixed heading is well posed where the free problem
folds, so it also reaches equilibria the load stepping cannot. Several weathervaning
bodies are walked in turn (each with the others held), for a few rounds.

Why not several starts round the circle: a free start far from the answer lands on
whichever zero its Newton iteration falls into (stable or not, a choice no engineer can
predict), and it needs a start of the lines at a turned pose. Walking with the held solve
costs a few Newton solves per 10 degrees turned and is paid only when the first solve did
not end stable.
"""

from __future__ import annotations

import math
import time

import casadi as ca
import numpy as np

from ..kernels.newton import FLAT, STEP_LIMIT
from .static import _rows, assess

#: Heading step of the walk [rad], and the smallest step tried where a held solve fails.
_STEP = math.radians(10.0)
_SMALLEST_STEP = math.radians(10.0 / 16)
#: A held solve is settled when its largest scaled residual is below this.
_HELD_TOL = 1e-9
#: Regula falsi steps refining a bracketed zero, and the heading width that ends them [rad].
_REFINE_STEPS = 30
_REFINE_WIDTH = 1e-7
#: Rounds of walking body by body when several bodies weathervane.
_ROUNDS = 4
#: The solver status of a point reached by the walk (a success: the walk's Newton steps
#: settled it and the certificate holds).
WALKED = "yaw walk from the case heading, then Newton"


def yaw_unknowns(problem) -> list[int]:
    """The unknowns of the yaw of every body free in yaw."""
    return [j for j, (owner, _, dof) in enumerate(problem.nodes)
            if owner == "body" and dof == "yaw"]


class _Held:
    """Solves with the yaws ``held`` fixed: every other unknown settled by damped Newton
    steps on every other residual row."""

    def __init__(self, problem, p, held):
        self.problem, self.p = problem, p
        held_set = set(held)
        self.cols = np.array([j for j in range(problem.n_x) if j not in held_set], dtype=int)
        self.rows = _rows(problem, self.cols)
        self.moment_rows = _rows(problem, np.array(held, dtype=int))
        self.lb, self.ub = problem.bounds()
        self.solves = 0

    def settle(self, x, steps: int = 100):
        """``(x, moments)`` at the held yaws of ``x`` (the yaw moments as the residual
        rows give them, positive turning the body counter-clockwise), or ``(x, None)``
        where it does not settle."""
        problem, p, cols, rows = self.problem, self.p, self.cols, self.rows
        self.solves += 1
        x = np.array(x, dtype=float)
        g = np.asarray(problem.residual(x, p)).ravel()
        norm = float(np.max(np.abs(g[rows]), initial=0.0))
        for _ in range(steps):
            if not math.isfinite(norm):
                return x, None
            if norm < _HELD_TOL:
                return x, g[self.moment_rows].copy()
            J = np.asarray(problem.step_jacobian(x, p, g))[np.ix_(rows, cols)]
            if not np.all(np.isfinite(J)):
                return x, None
            try:
                step = np.linalg.solve(J, g[rows])
            except np.linalg.LinAlgError:
                step = np.linalg.lstsq(J, g[rows], rcond=None)[0]
            found = self._search(x, step, norm, flat=False)
            if found is None and problem.smoothed:
                # As the Newton kernel: where the smoothed step finds no descent (a body on
                # a slack hawser), the exact step with a pseudo-time spring as large as the
                # residual, kept where it does not grow the residual.
                spring = max(problem.REGULARISATION, norm)
                J = (np.asarray(problem.jacobian(x, p))
                     - np.asarray(ca.densify(problem.regularisation(spring))))[np.ix_(rows, cols)]
                try:
                    step = np.linalg.solve(J, g[rows])
                except np.linalg.LinAlgError:
                    step = np.linalg.lstsq(J, g[rows], rcond=None)[0]
                found = self._search(x, step, norm, flat=True)
            if found is None:
                break
            x, g, norm = found
        return (x, g[self.moment_rows].copy()) if norm < _HELD_TOL else (x, None)


    def _search(self, x, step, norm, *, flat: bool):
        """Backtracking along ``step`` (limited to :data:`STEP_LIMIT` a component):
        ``(x, g, |g|)`` where the held rows' residual fell (with ``flat``: did not grow
        and the point moved), else None."""
        problem, cols, rows = self.problem, self.cols, self.rows
        step = step * min(1.0, STEP_LIMIT / max(float(np.max(np.abs(step), initial=0.0)),
                                                1e-300))
        alpha = 1.0
        for _ in range(24 if flat else 16):
            trial = x.copy()
            trial[cols] = np.clip(x[cols] - alpha * step, self.lb[cols], self.ub[cols])
            g = np.asarray(problem.residual(trial, self.p)).ravel()
            n = float(np.max(np.abs(g[rows]), initial=0.0))
            if math.isfinite(n) and (n < norm or (flat and n <= (1 + FLAT) * norm
                                                  and np.any(trial != x))):
                return trial, g, n
            alpha *= 0.5
        return None


def _turned(problem, x, j, heading):
    y = np.array(x, dtype=float)
    y[j] = heading / problem.x_scale[j]
    return y


def _heading(problem, x, j) -> float:
    return float(x[j] * problem.x_scale[j])


def _walk_one(problem, held: _Held, x, k: int, j: int, release, deadline=None):
    """Walk the ``k``-th held yaw from the settled point ``x`` (its moments known) the way
    its moment turns it, once round at most. ``release(x)`` turns a bracketed zero into a
    result or None (keep walking); with ``release`` None the first zero is returned.
    ``j`` is the held yaw's unknown. Returns ``(x, result)`` or None, also when the
    ``deadline`` (a :func:`time.perf_counter` time) passes."""
    x, moments = held.settle(x)
    if moments is None:
        return None
    m = float(moments[k])
    direction = 1.0 if m >= 0.0 else -1.0
    psi, turned = _heading(problem, x, j), 0.0
    step = _STEP
    while turned < 2.0 * math.pi + _STEP:
        if deadline is not None and time.perf_counter() >= deadline:
            return None
        x_next, moments = held.settle(_turned(problem, x, j, psi + direction * step))
        if moments is None:
            if step <= _SMALLEST_STEP:
                return None
            step /= 2.0
            continue
        m_next = float(moments[k])
        psi_next = psi + direction * step
        if direction * m >= 0.0 > direction * m_next:
            # The moment changed sign: a zero where it falls through, between psi and psi_next.
            x_zero = _refine(problem, held, j, k, (psi, m, x), (psi_next, m_next, x_next))
            if x_zero is not None:
                if release is None:
                    return x_zero, None
                found = release(x_zero)
                if found is not None:
                    return x_zero, found
        x, m, psi = x_next, m_next, psi_next
        turned += step
        step = min(2.0 * step, _STEP)
        # Past a zero that did not release, keep walking the same way: the next bracket
        # is where the moment falls through zero again.
    return None


def _refine(problem, held: _Held, j, k, a, b):
    """Regula falsi (Illinois) between the bracketing ``a`` and ``b`` (heading, moment,
    point); the settled point at the zero, or None."""
    (psi_a, m_a, x_a), (psi_b, m_b, x_b) = a, b
    x_best = x_b
    for _ in range(_REFINE_STEPS):
        if abs(psi_b - psi_a) < _REFINE_WIDTH:
            break
        psi = (psi_a * m_b - psi_b * m_a) / (m_b - m_a)
        x_c, moments = held.settle(_turned(problem, x_b if abs(psi - psi_b) < abs(psi - psi_a)
                                                    else x_a, j, psi))
        if moments is None:
            return None
        m_c = float(moments[k])
        x_best = x_c
        if m_c == 0.0:
            break
        if (m_c > 0) == (m_b > 0):
            psi_b, m_b, x_b = psi, m_c, x_c
            m_a *= 0.5
        else:
            psi_a, m_a, x_a = psi, m_c, x_c
            m_b *= 0.5
    return x_best


def stable_heading(problem, x_start, p, tol, polish, deadline=None):
    """A stable certified equilibrium reached by walking the weathervaning bodies' yaw
    from ``x_start`` (the case-file heading under the full load), or None.

    ``polish(x)`` takes a point to the certificate (Newton on the full system). Returns
    ``(x, Stability, walked_deg)`` with ``walked_deg`` the turn of each weathervaning
    body from ``x_start`` [deg]. The walk gives up (None) at ``deadline``, a
    :func:`time.perf_counter` time.
    """
    yaws = yaw_unknowns(problem)
    if not yaws:
        return None
    held = _Held(problem, p, yaws)

    def release(x):
        end = polish(x)
        if not problem.certify(end, p, tol)[0]:
            return None
        stability = assess(problem, end, p)
        return (end, stability) if stability.stable else None

    if len(yaws) == 1:
        found = _walk_one(problem, held, x_start, 0, yaws[0], release, deadline)
        if found is None:
            return None
        x_end, stability = found[1]
    else:
        x, found = np.array(x_start, dtype=float), None
        for _ in range(_ROUNDS):
            for k in range(len(yaws)):
                walked = _walk_one(problem, held, x, k, yaws[k], None, deadline)
                if walked is None:
                    return None
                x = walked[0]
            found = release(x)
            if found is not None:
                break
        if found is None:
            return None
        x_end, stability = found
    walked = [math.degrees(_heading(problem, x_end, j) - _heading(problem, x_start, j))
              for j in yaws]
    return x_end, stability, walked
