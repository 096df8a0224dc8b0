"""Dotted paths into case-file data: ``environment.wind.toward_deg``, ``legs[L3].anchor``.

A path is keys joined by dots; a list is indexed by position (``legs[0]``), by the
``name`` of its items (``legs[L3]``) or all at once (``legs[*].segments[0].length``).
Setting a path edits a copy of the case-file data, which :func:`load_case` then validates
like any case file, so a value may carry a unit (``"150 m"``) and a bad value is reported
against its field. A missing last key is created (validation decides if it is allowed);
a missing intermediate mapping is created too, so ``environment.current.speed`` can add a
current to a scene that had none.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Mapping, MutableMapping

from ..errors import CaseError

_TOKEN = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[[^\[\]]+\])*)$")


def parse_path(path: str) -> list:
    """Split ``path`` into keys (str) and list selectors (int, name or ``"*"``)."""
    if not isinstance(path, str) or not path:
        raise CaseError("grid", f"{path!r} is not a dotted case path")
    steps: list = []
    for part in path.split("."):
        m = _TOKEN.match(part)
        if not m:
            raise CaseError(path, f"{part!r} is not a key or key[index]; paths look like "
                                  f"environment.wind.toward_deg or legs[L1].segments[0].length")
        steps.append(m.group(1))
        for sel in re.findall(r"\[([^\[\]]+)\]", m.group(2)):
            sel = sel.strip()
            steps.append(("*",) if sel == "*" else (int(sel),) if re.fullmatch(r"-?\d+", sel)
                         else (sel,))
    return steps


def with_values(data: Mapping, assignments: Mapping[str, object]) -> dict:
    """Case-file ``data`` with each ``path: value`` of ``assignments`` set.

    Only the mappings and lists along the edited paths are copied; the rest is shared
    with ``data``, which is never modified.
    """
    out = dict(data)
    for path, value in assignments.items():
        _set(out, parse_path(path), value, path)
    return out


def _set(node, steps: list, value, path: str) -> None:
    """Set ``value`` below ``node`` (already a private copy), copying what it descends into."""
    step, rest = steps[0], steps[1:]
    if isinstance(step, str):
        if not isinstance(node, MutableMapping):
            raise CaseError(path, f"cannot take key {step!r} of a {type(node).__name__}")
        if not rest:
            node[step] = copy.deepcopy(value)
            return
        child = node.get(step)
        if child is None:
            child = [] if isinstance(rest[0], tuple) else {}
        node[step] = child = _private(child)
        _set(child, rest, value, path)
        return
    if not isinstance(node, list):
        raise CaseError(path, f"{step[0]!r} selects from a list, but this is a "
                              f"{type(node).__name__}")
    for index in _select(node, step[0], path):
        if rest:
            node[index] = child = _private(node[index])
            _set(child, rest, value, path)
        else:
            node[index] = copy.deepcopy(value)


def _private(node):
    """A shallow copy of a mapping or list (other values are returned as they are)."""
    if isinstance(node, Mapping):
        return dict(node)
    if isinstance(node, list):
        return list(node)
    return node


def _select(items: list, sel, path: str) -> list[int]:
    if sel == "*":
        return list(range(len(items)))
    if isinstance(sel, int):
        if not -len(items) <= sel < len(items):
            raise CaseError(path, f"index {sel} is out of range for a list of {len(items)}")
        return [sel % len(items)]
    found = [i for i, item in enumerate(items)
             if isinstance(item, Mapping) and item.get("name") == sel]
    if not found:
        names = [item.get("name") for item in items if isinstance(item, Mapping)]
        raise CaseError(path, f"no item named {sel!r}; the names are {names}")
    return found
