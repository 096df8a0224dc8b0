"""Which bodies of a scene nothing holds horizontally: they drift off under any load.

A body free in surge or sway is held horizontally only through what joins it, line by line
and point by point, to something that cannot drift: a fixed point or end (an anchor, a
bollard), a body held in both surge and sway, or a body with its own horizontal restoring
(an extra spring in surge or sway, a fender or a pile guide). Buoyancy, weight and the flow
loads give no horizontal restoring; a body reached by no such path (a tanker whose one
hawser broke, or a buoy and the tanker on it once the buoy's last chain is gone) has no
equilibrium under a horizontal load and is indifferent without one. That is a topological
fact of the scene, found here before any solve, so that a damaged condition can say which
body is lost instead of reporting that a solver did not converge.
"""

from __future__ import annotations

from dataclasses import dataclass

from .scene import Case

__all__ = ["Drift", "drifting_bodies", "HORIZONTAL_DOFS"]

#: The degrees of freedom the mooring must restore for a body to stay on station.
HORIZONTAL_DOFS = ("surge", "sway")
_GROUND = ("ground", "")


@dataclass(frozen=True)
class Drift:
    """One body that nothing holds horizontally.

    Attributes
    ----------
    body : str
    dofs : tuple of str
        Its free horizontal degrees of freedom (surge, sway) nothing restores (a DOF with
        an extra spring of its own is held by it).
    group : tuple of str
        The bodies and free points that drift with it (joined to it by lines; itself
        included), as ``body NAME`` or ``point NAME``.
    lines : tuple of str
        The lines that go with it (between members of the group).
    """

    body: str
    dofs: tuple
    group: tuple
    lines: tuple

    def describe(self) -> str:
        """``body tanker is held by no line``, or ``body tanker is held only by line H1
        to body buoy, which drifts with it (no line path to an anchor)``."""
        others = [g for g in self.group if g != f"body {self.body}"]
        if not self.lines:
            return f"body {self.body} is held by no line"
        return (f"body {self.body} is held only by {_words(self.lines, 'line')} to "
                f"{', '.join(others)}, which drift{'s' if len(others) == 1 else ''} with it "
                "(no line path to an anchor)")

    @property
    def restores(self) -> str:
        """``nothing restores it in surge and sway``."""
        return f"nothing restores it in {' and '.join(self.dofs)}"


def _words(names, noun: str) -> str:
    return f"{noun} {names[0]}" if len(names) == 1 else f"{noun}s {', '.join(names)}"


def _unheld_dofs(body, case: Case) -> tuple:
    """The free horizontal DOFs nothing but lines could hold: none when the body has a
    fender or pile guide (contacts are judged by the contact model); else those without an
    extra spring of their own."""
    contacts = case.contacts
    if any(f.body == body.name for f in contacts.fenders) or \
            any(g.body == body.name for g in contacts.guides):
        return ()
    k = body.stiffness
    return tuple(d for i, d in enumerate(HORIZONTAL_DOFS)
                 if d in body.free and not (k is not None and k[i][i] > 0))


def drifting_bodies(case: Case) -> list[Drift]:
    """Every body free in surge or sway that no line path joins to anything that holds.

    Parameters
    ----------
    case : Case

    Returns
    -------
    list of Drift
        In the case's body order; empty when every body is held.
    """
    parent: dict = {}

    def find(node):
        parent.setdefault(node, node)
        while parent[node] != node:
            parent[node] = parent[parent[node]]
            node = parent[node]
        return node

    def union(a, b):
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb

    free_points = {p.name for p in case.points if p.free}
    unheld = {body.name: _unheld_dofs(body, case) for body in case.bodies}
    for body in case.bodies:
        node = ("body", body.name)
        find(node)
        if not unheld[body.name]:
            union(node, _GROUND)

    def node_of(end):
        if end.body is not None:
            return ("body", end.body)
        if end.point is not None and end.point in free_points:
            return ("point", end.point)
        return _GROUND

    for line in case.lines:
        union(node_of(line.a), node_of(line.b))
    ground = find(_GROUND)
    out = []
    for body in case.bodies:
        root = find(("body", body.name))
        if root == ground:
            continue
        members = [n for n in parent if find(n) == root]
        group = tuple(f"{kind} {name}" for kind, name in sorted(
            members, key=lambda n: (n[0] != "body" or n[1] != body.name, n)))
        lines = tuple(line.name for line in case.lines
                      if find(node_of(line.a)) == root)
        out.append(Drift(body=body.name, dofs=unheld[body.name], group=group, lines=lines))
    return out
