"""Dotted paths into case-file data: ``environment.wind.toward_deg``, ``legs[L3].anchor``.

A path is keys joined by dots; a list is indexed by position (``legs[0]``), by the
``name`` of its items (``legs[L3]``) or all at once (``legs[*].segments[0].length``).
Setting a path edits a copy of the case-file data, which :func:`load_case` then validates
like any case file, so a value may carry a unit (``"150 m"``) and a bad value is reported
against its field. A missing last key is created (validation decides if it is allowed);
a missing intermediate mapping is created too, so ``environment.current.speed`` can add a
current to a scene that had none. Setting a flow's ``toward_deg`` removes its ``from_deg``
and the other way round (a flow takes one of them).
"""

from __future__ import annotations

import copy
import re
from collections.abc import Mapping, MutableMapping

from ..errors import CaseError

#: Keys that say the same thing in other terms: setting one removes the others.
_ALTERNATIVES = {"toward_deg": ("from_deg",), "from_deg": ("toward_deg",)}

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
            # A flow's direction is one key or the other: setting one replaces the other.
            for other in _ALTERNATIVES.get(step, ()):
                node.pop(other, None)
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


def concrete_paths(data: Mapping, path: str) -> list[str]:
    """The field paths (``legs[2].anchor``, as validation names fields) that ``path``
    selects in ``data``: names and ``*`` resolved to positions. A missing key is kept."""
    out = [("", data)]
    for step in parse_path(path):
        nxt = []
        for prefix, node in out:
            if isinstance(step, str):
                child = node.get(step) if isinstance(node, Mapping) else None
                nxt.append((f"{prefix}.{step}" if prefix else step, child))
            elif isinstance(node, list):
                nxt += [(f"{prefix}[{i}]", node[i]) for i in _select(node, step[0], path)]
        out = nxt
    return [prefix for prefix, _ in out]


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


# ---- the values of `moorsolve sweep --set PATH=VALUES` -------------------------------------

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_RANGE = re.compile(rf"^({_NUMBER})\s*:\s*({_NUMBER})\s*:\s*({_NUMBER})(?:\s+(\S.*))?$")
_INT = re.compile(r"^[-+]?\d+$")
_MAX_RANGE = 1_000_000

SET_SYNTAX = ("PATH=VALUES; VALUES is a comma list (0,45,90), ranges start:stop:step with "
              "stop included when on the step (0:345:15, 10:30:5 kn), strings with units "
              "('10 kn,20 kn') and lists in brackets ([1e5,0,0],[2e5,0,0])")


def parse_assignment(text: str) -> tuple[str, list]:
    """``"PATH=VALUES"`` (one ``--set`` of ``moorsolve sweep``) as ``(path, values)``."""
    if not isinstance(text, str) or "=" not in text:
        raise CaseError("--set", f"{text!r} must be {SET_SYNTAX}")
    path, _, raw = text.partition("=")
    path = path.strip()
    parse_path(path)
    return path, parse_values(raw, f"--set {path}")


def parse_values(text: str, field: str) -> list:
    """The values of a ``--set``: a comma list whose items are numbers, ranges
    ``start:stop:step[ unit]`` (stop included when it falls on the step, to 1e-9 of a
    step), bracketed lists (``[1e5,0,0]``, items as here) or strings (``10 kn``; quotes
    optional). Commas inside brackets do not split."""
    items = _split_top(text, field)
    values: list = []
    for item in items:
        values.extend(_item(item, field))
    return values


def _split_top(text: str, field: str) -> list[str]:
    items, depth, start = [], 0, 0
    for k, ch in enumerate(text):
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
            if depth < 0:
                raise CaseError(field, f"{text!r}: a ']' without its '['")
        elif ch == "," and depth == 0:
            items.append(text[start:k])
            start = k + 1
    if depth:
        raise CaseError(field, f"{text!r}: a '[' without its ']'")
    items.append(text[start:])
    items = [i.strip() for i in items]
    if any(not i for i in items):
        raise CaseError(field, f"{text!r}: an empty value; write {SET_SYNTAX}")
    return items


def _item(item: str, field: str) -> list:
    if item.startswith("["):
        if not item.endswith("]"):
            raise CaseError(field, f"{item!r}: text after a ']'")
        inner = item[1:-1].strip()
        return [parse_values(inner, field) if inner else []]
    m = _RANGE.match(item)
    if m:
        return _range(item, *m.groups(), field)
    if ":" in item:
        raise CaseError(field, f"{item!r} is not a range start:stop:step of numbers "
                               f"(e.g. 0:345:15 or 10:30:5 kn)")
    if _INT.match(item):
        return [int(item)]
    try:
        return [float(item)] if re.fullmatch(_NUMBER, item) else [_unquote(item)]
    except ValueError:            # pragma: no cover - the pattern admits floats only
        return [_unquote(item)]


def _unquote(item: str) -> str:
    if len(item) >= 2 and item[0] == item[-1] and item[0] in "'\"":
        return item[1:-1]
    return item


def _range(item, a, b, c, unit, field) -> list:
    start, stop, step = float(a), float(b), float(c)
    if step == 0:
        raise CaseError(field, f"{item!r}: the step must not be 0")
    span = (stop - start) / step
    if span < -1e-9:
        raise CaseError(field, f"{item!r}: the step {c} leads away from {b}")
    count = int(span + 1e-9) + 1
    if count > _MAX_RANGE:
        raise CaseError(field, f"{item!r} gives {count} values; at most {_MAX_RANGE}")
    integral = all(_INT.match(x) for x in (a, b, c))
    values = [int(a) + k * int(c) if integral else round(start + k * step, 12)
              for k in range(count)]
    if unit:
        return [f"{v:g} {unit.strip()}" if not integral else f"{v} {unit.strip()}"
                for v in values]
    return values
